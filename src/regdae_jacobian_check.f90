!> The check of the user's constraint Jacobian at the initial point
!! (`check_jacobians=yes`): G from constraint_jacobian, and for a mechanical
!! problem that declares its structure the sparse G of
!! constraint_jacobian_values, against central difference quotients of g
!! (`regdae_differences`); regdae_err_jacobian names the worst entry. Split from
!! regdae_solver_front, whose init paths call it.
module regdae_jacobian_check
    use regdae_kinds, only: wp
    use regdae_status
    use regdae_second_order_problem, only: second_order_problem
    use regdae_mechanical_problem, only: mechanical_problem
    use regdae_augmented_system, only: augmented_system
    use regdae_differences, only: central_difference_step
    use regdae_format, only: format_real, format_int
    implicit none
    private

    public :: check_second_order_jacobian, check_structured_jacobian

contains

    !> check_jacobians: the user's G (constraint_jacobian) against central
    !! difference quotients of g at (t0, x0); regdae_err_jacobian names the worst entry.
    subroutine check_second_order_jacobian(problem, t0, x0, stat, msg)
        class(second_order_problem), intent(inout) :: problem
        real(wp), intent(in) :: t0, x0(:)
        integer, intent(out) :: stat
        character(len=:), allocatable, intent(out) :: msg
        real(wp), allocatable :: gx(:, :), dq(:, :)
        if (.not. check_arrays(problem%m, problem%n, gx, dq, stat, msg)) return
        call problem%constraint_jacobian(t0, x0, gx, stat)
        if (stat == 0) call constraint_difference_quotient(problem, t0, x0, dq, stat)
        if (stat /= 0) then
            msg = 'check_jacobians: a user routine of the constraint failed (stat = '//format_int(stat)//')'
            stat = regdae_err_user_callback
            return
        end if
        call compare_jacobian('constraint_jacobian', gx, dq, stat, msg)
    end subroutine check_second_order_jacobian

    !> check_jacobians, structured problems: the sparse G of constraint_jacobian_values too.
    subroutine check_structured_jacobian(problem, sys, t0, q0, stat, msg)
        class(mechanical_problem), intent(in) :: problem
        type(augmented_system), intent(in) :: sys
        real(wp), intent(in) :: t0, q0(:)
        integer, intent(out) :: stat
        character(len=:), allocatable, intent(out) :: msg
        class(mechanical_problem), allocatable :: copy
        real(wp), allocatable :: gx(:, :), dq(:, :)
        real(wp) :: vals(sys%st%constraint%nnz())
        integer :: i, k
        if (.not. check_arrays(problem%m, problem%n, gx, dq, stat, msg)) return
        allocate (copy, source=problem)
        stat = 0
        msg = ''
        call copy%constraint_jacobian_values(t0, q0, sys%st%constraint, vals, stat)
        if (stat == 0) call constraint_difference_quotient(copy, t0, q0, dq, stat)
        if (stat /= 0) then
            if (stat /= regdae_err_structure) msg = 'check_jacobians: a user routine of the constraint failed '// &
                                                    '(stat = '//format_int(stat)//')'
            if (stat == regdae_err_structure) msg = 'constraint_jacobian has a nonzero outside the declared '// &
                                                    'constraint pattern'
            if (stat /= regdae_err_structure) stat = regdae_err_user_callback
            return
        end if
        gx = 0.0_wp
        do i = 1, problem%m
            do k = sys%st%constraint%row_start(i), sys%st%constraint%row_start(i + 1) - 1
                gx(i, sys%st%constraint%cols(k)) = vals(k)
            end do
        end do
        call compare_jacobian('constraint_jacobian_values', gx, dq, stat, msg)
    end subroutine check_structured_jacobian

    ! The two dense m x n arrays of check_jacobians; false with regdae_err_memory and a
    ! message when the system refuses them.
    logical function check_arrays(m, n, gx, dq, stat, msg) result(ok)
        integer, intent(in) :: m, n
        real(wp), allocatable, intent(out) :: gx(:, :), dq(:, :)
        integer, intent(out) :: stat
        character(len=:), allocatable, intent(out) :: msg
        allocate (gx(m, n), dq(m, n), stat=stat)
        ok = (stat == 0)
        msg = ''
        if (ok) return
        stat = regdae_err_memory
        msg = 'check_jacobians: out of memory (two dense '//format_int(m)//' x '//format_int(n)// &
              ' matrices: the check is for small instances)'
    end function check_arrays

    ! Central difference quotients of g(x, t0), column j with the step of
    ! regdae_differences for x_j.
    subroutine constraint_difference_quotient(problem, t0, x0, dq, stat)
        class(second_order_problem), intent(inout) :: problem
        real(wp), intent(in) :: t0, x0(:)
        real(wp), intent(out) :: dq(:, :)
        integer, intent(inout) :: stat
        real(wp) :: x(size(x0)), gp(problem%m), gm(problem%m), d
        integer :: j
        x = x0
        do j = 1, problem%n
            d = central_difference_step(x0(j))
            x(j) = x0(j) + d
            call problem%constraint(t0, x, gp, stat)
            if (stat /= 0) return
            x(j) = x0(j) - d
            call problem%constraint(t0, x, gm, stat)
            if (stat /= 0) return
            x(j) = x0(j)
            dq(:, j) = (gp - gm)/(2.0_wp*d)
        end do
    end subroutine constraint_difference_quotient

    ! |analytic - dq| <= 1e-6 max(1, max |dq|) entry by entry (central differences
    ! are accurate to about u^(2/3) ~ 4e-11 relative); else regdae_err_jacobian.
    subroutine compare_jacobian(name, analytic, dq, stat, msg)
        character(len=*), intent(in) :: name
        real(wp), intent(in) :: analytic(:, :), dq(:, :)
        integer, intent(out) :: stat
        character(len=:), allocatable, intent(out) :: msg
        integer :: worst(2)
        real(wp) :: scale
        stat = regdae_success
        msg = ''
        if (size(dq) == 0) return
        scale = max(1.0_wp, maxval(abs(dq)))
        worst = maxloc(abs(analytic - dq))
        if (abs(analytic(worst(1), worst(2)) - dq(worst(1), worst(2))) <= 1.0e-6_wp*scale) return
        stat = regdae_err_jacobian
        msg = 'check_jacobians: '//name//' disagrees with the difference quotient of the constraint at entry ('// &
              format_int(worst(1))//', '//format_int(worst(2))//'): '//format_real(analytic(worst(1), worst(2)))// &
              ' against '//format_real(dq(worst(1), worst(2)))
    end subroutine compare_jacobian

end module regdae_jacobian_check
