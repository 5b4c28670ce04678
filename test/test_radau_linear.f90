!> Tests of the Radau IIA integrator's Newton matrices (regdae_radau_linear): the real
!! and complex LU and their solves, the rounding floor of the increments, a singular
!! matrix; part of the `radau` suite (test_radau).
module test_radau_linear
    use regdae_kinds, only: wp
    use regdae_status, only: regdae_success, regdae_err_singular
    use regdae_radau_linear, only: radau_newton_matrices
    use regdae_testing, only: checker, test_case, new_test
    implicit none
    private
    public :: radau_linear_tests

contains

    !> The tests of this module.
    function radau_linear_tests() result(tests)
        type(test_case), allocatable :: tests(:)
        tests = [new_test('newton_matrices', newton_matrices)]
    end function radau_linear_tests

    ! The Newton matrices' LU and solves, the module's own (n <= 16) and LAPACK's (n = 20):
    ! E_1 x = b and E_2 (x + i y) = b + i c for matrices that need row exchanges (J with
    ! scattered large entries) and a singular M, checked by their residuals: a backward-stable
    ! LU leaves a few u ||E|| ||x||, and 1e-12 relative to ||E|| ||x|| is ample at n <= 20.
    ! The rounding floor (on the algebraic row of M) the same way, and 0 for an ODE (n = 1).
    subroutine newton_matrices(chk)
        type(checker), intent(inout) :: chk
        integer, parameter :: sizes(3) = [1, 5, 20]
        real(wp), parameter :: fr = 0.3_wp, fa = 0.2_wp, fb = 0.7_wp
        type(radau_newton_matrices) :: lin
        real(wp), allocatable :: jac(:, :), mass(:), b(:), c(:), x(:), y(:), e1(:, :), rho(:), fl(:)
        complex(wp), allocatable :: e2(:, :), r(:)
        integer :: i, j, k, n, stat
        character(len=8) :: tag
        do k = 1, size(sizes)
            n = sizes(k)
            write (tag, '(i0)') n
            allocate (jac(n, n), mass(n), b(n), c(n), fl(n))
            do j = 1, n
                do i = 1, n
                    jac(i, j) = sin(real(3*i*i + 7*j, wp))   ! scattered large entries: rows are exchanged
                end do
                b(j) = cos(real(j, wp))
                c(j) = sin(real(2*j, wp))
            end do
            mass = 1.0_wp
            if (n > 1) mass(2) = 0.0_wp             ! a singular M, as in a DAE
            call lin%init(n)
            call lin%factor(jac, mass, fr, fa, fb, stat)
            call chk%equal(stat, regdae_success, 'newton matrices factored, n = '//trim(tag))
            e1 = -jac
            e2 = cmplx(-jac, 0.0_wp, wp)
            do i = 1, n
                e1(i, i) = e1(i, i) + fr*mass(i)
                e2(i, i) = e2(i, i) + cmplx(fa, fb, wp)*mass(i)
            end do
            x = b
            call lin%solve_real(x)
            call chk%true(maxval(abs(matmul(e1, x) - b)) <= 1.0e-12_wp*maxval(abs(e1))*max(1.0_wp, maxval(abs(x))), &
                          'real Newton system solved, n = '//trim(tag))
            x = b
            y = c
            call lin%solve_complex(x, y)
            r = matmul(e2, cmplx(x, y, wp)) - cmplx(b, c, wp)
            call chk%true(maxval(abs(r)) <= 1.0e-12_wp*maxval(abs(e2))*max(1.0_wp, maxval(abs(cmplx(x, y, wp)))), &
                          'complex Newton system solved, n = '//trim(tag))
            ! the rounding floor at u = b, F = c: |E_1^-1 rho|, rho = eps_m (|F| + |J| |u|) on the algebraic rows
            rho = merge(epsilon(1.0_wp)*(abs(c) + matmul(abs(jac), abs(b))), 0.0_wp, mass == 0)
            call lin%rounding_floor(jac, mass, b, c, fl)
            x = rho
            call lin%solve_real(x)
            call chk%true(all(fl == abs(x)) .and. maxval(abs(matmul(e1, x) - rho)) <= &
                          1.0e-12_wp*maxval(abs(e1))*max(maxval(rho), maxval(abs(x))), &
                          'rounding floor |E_1^-1 rho| on the algebraic rows, n = '//trim(tag))
            call chk%true(n > 1 .eqv. any(fl > 0), 'rounding floor nonzero where M has an algebraic row, n = '//trim(tag))
            deallocate (jac, mass, b, c, fl)
        end do
        ! an exactly singular E_1 (J = fr M in column 1): the status the step control expects
        call lin%init(2)
        call lin%factor(reshape([fr, 0.0_wp, 0.0_wp, 1.0_wp], [2, 2]), [1.0_wp, 1.0_wp], fr, fa, fb, stat)
        call chk%equal(stat, regdae_err_singular, 'an exactly singular Newton matrix reported')
    end subroutine newton_matrices

end module test_radau_linear
