!> The check of the user's constraint Jacobian at the initial point
!! (`check_jacobians=yes`): G from constraint_jacobian, and for a mechanical
!! problem that declares its structure the sparse G of
!! constraint_jacobian_values, against central difference quotients of g
!! (`regdae_differences`); regdae_err_jacobian names the worst entry. Split from
!! regdae_solver_front, whose init paths call it.
!!
!! A declared structure is checked in the user's terms: M of `mass_values` against
!! `mass_matrix` and its nonzeros against the `mass` pattern, and the difference
!! quotients of f(q, v, t) - M(q) a in q and of f in v against the `force_q` and
!! `force_v` patterns; every entry is named by its (row, column) in M, G or the
!! force Jacobian, the coordinates as the problem numbers them.
module regdae_jacobian_check
    use regdae_kinds, only: wp
    use regdae_status
    use regdae_second_order_problem, only: second_order_problem
    use regdae_mechanical_problem, only: mechanical_problem, mechanical_structure
    use regdae_sparsity, only: sparsity_pattern
    use regdae_augmented_system, only: augmented_system
    use regdae_differences, only: central_difference_step
    use regdae_format, only: format_real, format_int
    implicit none
    private

    public :: check_second_order_jacobian, check_structured_jacobian, compare_jacobian

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

    !> check_jacobians, structured problems: the sparse G of constraint_jacobian_values,
    !! then M and the force patterns (`check_declared_patterns`), at (t0, q0, v0).
    subroutine check_structured_jacobian(problem, sys, t0, q0, v0, stat, msg)
        class(mechanical_problem), intent(in) :: problem
        type(augmented_system), intent(in) :: sys
        real(wp), intent(in) :: t0, q0(:), v0(:)
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
        call check_declared_patterns(copy, sys%st, t0, q0, v0, stat, msg)
        if (stat /= regdae_success) return
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

    !> The declared patterns of M, force_q and force_v at (t0, q0, v0): `mass_values`
    !! equal to `mass_matrix` on the pattern and no nonzero of M outside it; the central
    !! difference quotients of f(q, v0, t0) - M(q) a in q (a a fixed vector of entries
    !! in [0.5, 1.5]) and of f(q0, v, t0) in v nonzero only inside `force_q` and
    !! `force_v`. regdae_err_jacobian names the pattern and the entry (row, column)
    !! found outside it; the checked problem is a copy (its state is not the solver's).
    subroutine check_declared_patterns(problem, st, t0, q0, v0, stat, msg)
        class(mechanical_problem), intent(inout) :: problem
        type(mechanical_structure), intent(in) :: st
        real(wp), intent(in) :: t0, q0(:), v0(:)
        integer, intent(out) :: stat
        character(len=:), allocatable, intent(out) :: msg
        real(wp), allocatable :: mass(:, :), dq(:, :)
        real(wp) :: mvals(st%mass%nnz()), a(size(q0))
        integer :: i, j, k
        if (.not. check_arrays(problem%n, problem%n, mass, dq, stat, msg)) return
        a = [(1.0_wp + 0.5_wp*sin(real(i, wp)), i=1, size(q0))]
        call problem%mass_matrix(t0, q0, mass, stat)
        if (stat == 0) call problem%mass_values(t0, q0, st%mass, mvals, stat)
        if (stat /= 0) then
            call user_failure('mass_matrix or mass_values', stat, msg)
            return
        end if
        ! M: mass_values on the pattern, nothing outside it
        do i = 1, problem%n
            do j = 1, problem%n
                k = st%mass%position(i, j)
                if (k == 0 .and. mass(i, j) /= 0.0_wp) then
                    msg = 'check_jacobians: M (mass_matrix) has the nonzero entry ('//format_int(i)//', '// &
                          format_int(j)//') = '//format_real(mass(i, j))//' outside the declared mass pattern'
                else if (k > 0) then
                    if (abs(mvals(k) - mass(i, j)) > 1.0e-12_wp*max(1.0_wp, maxval(abs(mass)))) &
                        msg = 'check_jacobians: mass_values gives M('//format_int(i)//', '//format_int(j)//') = '// &
                              format_real(mvals(k))//', mass_matrix '//format_real(mass(i, j))
                end if
                if (len(msg) > 0) then
                    stat = regdae_err_jacobian
                    return
                end if
            end do
        end do
        call force_quotients(problem, t0, q0, v0, a, .true., dq, stat)
        if (stat == 0) call outside_pattern('force_q', 'd(f - M(q) a)/dq', st%force_q, dq, stat, msg)
        if (stat == 0) call force_quotients(problem, t0, q0, v0, a, .false., dq, stat)
        if (stat == 0) call outside_pattern('force_v', 'df/dv', st%force_v, dq, stat, msg)
        if (stat /= 0 .and. stat /= regdae_err_jacobian) call user_failure('forces or mass_matrix', stat, msg)
    end subroutine check_declared_patterns

    ! Central difference quotients, column j, of f(q, v0, t0) - M(q) a in q_j (in_q) or
    ! of f(q0, v, t0) in v_j.
    subroutine force_quotients(problem, t0, q0, v0, a, in_q, dq, stat)
        class(mechanical_problem), intent(inout) :: problem
        real(wp), intent(in) :: t0, q0(:), v0(:), a(:)
        logical, intent(in) :: in_q
        real(wp), intent(out) :: dq(:, :)
        integer, intent(inout) :: stat
        real(wp) :: q(size(q0)), v(size(v0)), hp(size(q0)), hm(size(q0)), d
        real(wp), allocatable :: mass(:, :)
        integer :: j
        allocate (mass(size(q0), size(q0)))
        q = q0
        v = v0
        do j = 1, size(q0)
            if (in_q) then
                d = central_difference_step(q0(j))
                q(j) = q0(j) + d
                call force_minus_inertia(hp)
                q(j) = q0(j) - d
                call force_minus_inertia(hm)
                q(j) = q0(j)
            else
                d = central_difference_step(v0(j))
                v(j) = v0(j) + d
                call force_minus_inertia(hp)
                v(j) = v0(j) - d
                call force_minus_inertia(hm)
                v(j) = v0(j)
            end if
            if (stat /= 0) return
            dq(:, j) = (hp - hm)/(2.0_wp*d)
        end do
    contains
        ! f(q, v, t0) - M(q) a (in_q) or f(q, v, t0)
        subroutine force_minus_inertia(h)
            real(wp), intent(out) :: h(:)
            h = 0.0_wp
            if (stat /= 0) return
            call problem%forces(t0, q, v, h, stat)
            if (stat /= 0 .or. .not. in_q) return
            call problem%mass_matrix(t0, q, mass, stat)
            h = h - matmul(mass, a)
        end subroutine force_minus_inertia
    end subroutine force_quotients

    ! regdae_err_jacobian when a difference quotient of `what` exceeds its noise (1e-6
    ! times the largest, at least 1e-6) outside the pattern `name`; the largest such
    ! entry is named.
    subroutine outside_pattern(name, what, pattern, dq, stat, msg)
        character(len=*), intent(in) :: name, what
        type(sparsity_pattern), intent(in) :: pattern
        real(wp), intent(in) :: dq(:, :)
        integer, intent(inout) :: stat
        character(len=:), allocatable, intent(inout) :: msg
        real(wp) :: noise, worst
        integer :: i, j, wi, wj
        noise = 1.0e-6_wp*max(1.0_wp, maxval(abs(dq)))
        worst = noise
        wi = 0
        wj = 0
        do j = 1, size(dq, 2)
            do i = 1, size(dq, 1)
                if (abs(dq(i, j)) > worst .and. pattern%position(i, j) == 0) then
                    worst = abs(dq(i, j))
                    wi = i
                    wj = j
                end if
            end do
        end do
        if (wi == 0) return
        stat = regdae_err_jacobian
        msg = 'check_jacobians: the declared '//name//' pattern misses entry ('//format_int(wi)//', '// &
              format_int(wj)//') of '//what//': its difference quotient at t0 is '//format_real(dq(wi, wj))
    end subroutine outside_pattern

    ! The message of a user routine that failed during the check (stat > 0 or < 0).
    subroutine user_failure(names, stat, msg)
        character(len=*), intent(in) :: names
        integer, intent(inout) :: stat
        character(len=:), allocatable, intent(inout) :: msg
        if (stat == regdae_err_structure) then
            msg = 'check_jacobians: '//names//': a nonzero outside the declared pattern'
        else
            msg = 'check_jacobians: a user routine ('//names//') failed (stat = '//format_int(stat)//')'
            stat = regdae_err_user_callback
        end if
    end subroutine user_failure

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

    !> |analytic - dq| <= 1e-6 max(1, max |dq|) entry by entry (central differences
    !! are accurate to about u^(2/3) ~ 4e-11 relative); else regdae_err_jacobian with
    !! the worst entry (row, column) named.
    subroutine compare_jacobian(name, analytic, dq, stat, msg, of)
        character(len=*), intent(in) :: name               !! the user's routine that gave `analytic`
        real(wp), intent(in) :: analytic(:, :), dq(:, :)    !! the user's matrix, the difference quotients
        integer, intent(out) :: stat
        character(len=:), allocatable, intent(out) :: msg
        character(len=*), intent(in), optional :: of        !! what dq differentiates (default: the constraint)
        integer :: worst(2)
        real(wp) :: scale
        character(len=:), allocatable :: quotient_of
        quotient_of = 'the constraint'
        if (present(of)) quotient_of = of
        stat = regdae_success
        msg = ''
        if (size(dq) == 0) return
        scale = max(1.0_wp, maxval(abs(dq)))
        worst = maxloc(abs(analytic - dq))
        if (abs(analytic(worst(1), worst(2)) - dq(worst(1), worst(2))) <= 1.0e-6_wp*scale) return
        stat = regdae_err_jacobian
        msg = 'check_jacobians: '//name//' disagrees with the difference quotient of '//quotient_of//' at entry ('// &
              format_int(worst(1))//', '//format_int(worst(2))//'): '//format_real(analytic(worst(1), worst(2)))// &
              ' against '//format_real(dq(worst(1), worst(2)))
    end subroutine compare_jacobian

end module regdae_jacobian_check
