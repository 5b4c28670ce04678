!> Unit tests of the damped least-squares, shifted and square solves against
!! closed-form solutions.
!!
!! The matrices are A = U diag(s) V^T with U = H and V = H P, H the 4 x 4
!! Hadamard matrix over 2 (entries +-1/2, orthogonal) and P a permutation, and
!! s powers of two: A and r = U c are then exact in binary, and the reference
!! y = V diag(s / (s^2 + eps)) c is correct to a few units of roundoff, so the
!! tolerances below measure the solvers alone.
module test_lsq
    use regdae, only: wp, damped_lsq_workspace, damped_lsq_solve, shifted_spd_solve, square_solve, &
                      lsq_normal, lsq_stacked, lsq_checked, regdae_success, regdae_err_singular, regdae_err_not_psd, &
                      regdae_err_bad_input
    use regdae_testing, only: checker, test_case, new_test
    use regdae_lapack, only: dgesvd
    implicit none
    private
    public :: lsq_tests

    real(wp), parameter :: h(4, 4) = 0.5_wp*reshape([1, 1, 1, 1, 1, -1, 1, -1, 1, 1, -1, -1, 1, -1, -1, 1], [4, 4])
    integer, parameter :: perm(4) = [2, 4, 1, 3]
    real(wp), parameter :: c(4) = [1.0_wp, -2.0_wp, 3.0_wp, 0.5_wp]
    real(wp), parameter :: u = epsilon(1.0_wp)

contains

    function lsq_tests() result(tests)
        type(test_case), allocatable :: tests(:)
        tests = [new_test('well_conditioned', well_conditioned), &
                 new_test('ill_conditioned', ill_conditioned), &
                 new_test('rank_deficient', rank_deficient), &
                 new_test('eps_to_zero_recovers_inverse', eps_to_zero), &
                 new_test('eps_zero_rank_deficient', eps_zero_rank_deficient), &
                 new_test('shifted_spd', shifted_spd), &
                 new_test('square', square), &
                 new_test('bad_input', bad_input), &
                 new_test('checked_switches_by_conditioning', checked_switches), &
                 new_test('smallest_singular_value_2x2', singular_2x2)]
    end function lsq_tests

    ! lsq=auto (lsq_checked): the normal equations where A^T A + eps I is well
    ! conditioned (s = 2, 1, 1/2, 1/4: cond 64), the stacked system where it is
    ! not (s down to 2^-20 with eps = 2^-60: cond ~ 2^40); the result then as
    ! accurate as lsq_stacked's (both within 1e-10 of the exact reference).
    subroutine checked_switches(chk)
        type(checker), intent(inout) :: chk
        type(damped_lsq_workspace) :: ws
        real(wp) :: s_good(4), s_bad(4), y(4), y_ref(4), eps
        integer :: stat
        call ws%init(4, 4)
        s_good = [2.0_wp, 1.0_wp, 0.5_wp, 0.25_wp]
        eps = 1.0e-6_wp
        call damped_lsq_solve(ws, a_matrix(s_good), matmul(h, c), eps, lsq_checked, y, stat)
        call chk%equal(stat, regdae_success, 'well conditioned: success')
        call chk%true(ws%stacked_solves == 0, 'well conditioned: the normal equations')
        call chk%true(maxval(abs(y - damped_reference(s_good, eps))) <= 1.0e-12_wp, 'well conditioned: accurate')
        s_bad = [1.0_wp, 2.0_wp**(-8), 2.0_wp**(-14), 2.0_wp**(-20)]
        eps = 2.0_wp**(-60)
        y_ref = damped_reference(s_bad, eps)
        call damped_lsq_solve(ws, a_matrix(s_bad), matmul(h, c), eps, lsq_checked, y, stat)
        call chk%equal(stat, regdae_success, 'ill conditioned: success')
        call chk%true(ws%stacked_solves == 1, 'ill conditioned: the stacked system')
        call chk%true(maxval(abs(y - y_ref))/maxval(abs(y_ref)) <= 1.0e-10_wp, 'ill conditioned: accurate')
        write (*, '(a,es10.2)') '    ill conditioned, relative error of lsq_checked: ', &
            maxval(abs(y - y_ref))/maxval(abs(y_ref))
    end subroutine checked_switches

    pure function v_matrix() result(v)
        real(wp) :: v(4, 4)
        v = h(:, perm)
    end function v_matrix

    pure function a_matrix(s) result(a)
        real(wp), intent(in) :: s(4)
        real(wp) :: a(4, 4)
        integer :: i
        a = 0.0_wp
        do i = 1, 4
            a = a + s(i)*spread(h(:, i), 2, 4)*spread(v_matrix_col(i), 1, 4)
        end do
    end function a_matrix

    pure function v_matrix_col(i) result(col)
        integer, intent(in) :: i
        real(wp) :: col(4)
        col = h(:, perm(i))
    end function v_matrix_col

    ! Reference damped solution V diag(s/(s^2+eps)) c (0 where s = 0).
    pure function damped_reference(s, eps) result(y)
        real(wp), intent(in) :: s(4), eps
        real(wp) :: y(4), d(4)
        where (s /= 0.0_wp)
            d = s/(s**2 + eps)
        elsewhere
            d = 0.0_wp
        end where
        y = matmul(v_matrix(), d*c)
    end function damped_reference

    subroutine solve_both(s, eps, y_normal, y_stacked, stat_normal, stat_stacked)
        real(wp), intent(in) :: s(4), eps
        real(wp), intent(out) :: y_normal(4), y_stacked(4)
        integer, intent(out) :: stat_normal, stat_stacked
        type(damped_lsq_workspace) :: ws
        real(wp) :: a(4, 4), r(4)
        call ws%init(4, 4)
        a = a_matrix(s)
        r = matmul(h, c)
        call damped_lsq_solve(ws, a, r, eps, lsq_normal, y_normal, stat_normal)
        call damped_lsq_solve(ws, a, r, eps, lsq_stacked, y_stacked, stat_stacked)
    end subroutine solve_both

    ! cond(A^T A + eps I) = (4 + eps)/(1/16 + eps) < 40: both within 1e-14.
    subroutine well_conditioned(chk)
        type(checker), intent(inout) :: chk
        real(wp), parameter :: s(4) = [2.0_wp, 1.0_wp, 0.5_wp, 0.25_wp], eps = 0.0625_wp
        real(wp) :: yn(4), ys(4)
        integer :: sn, ss
        call solve_both(s, eps, yn, ys, sn, ss)
        call chk%equal(sn, regdae_success, 'normal status')
        call chk%equal(ss, regdae_success, 'stacked status')
        call chk%close_rel(yn, damped_reference(s, eps), 1.0e-14_wp, 'normal equations')
        call chk%close_rel(ys, damped_reference(s, eps), 1.0e-14_wp, 'stacked')
    end subroutine well_conditioned

    ! sigma_min = 2^-17 (7.6e-6), eps = 2^-40 (9.1e-13): the normal matrix has
    ! condition number ~1.7e10, so its solution may lose u * 1.7e10 ~ 4e-6;
    ! the stacked matrix has condition number ~1.3e5 and keeps ~1e-11.
    subroutine ill_conditioned(chk)
        type(checker), intent(inout) :: chk
        real(wp), parameter :: s(4) = [1.0_wp, 0.5_wp, 2.0_wp**(-10), 2.0_wp**(-17)], eps = 2.0_wp**(-40)
        real(wp) :: yn(4), ys(4), ref(4), cond_normal, cond_stacked
        integer :: sn, ss
        call solve_both(s, eps, yn, ys, sn, ss)
        ref = damped_reference(s, eps)
        cond_normal = (1.0_wp + eps)/(s(4)**2 + eps)
        cond_stacked = sqrt(cond_normal)
        call chk%equal(sn, regdae_success, 'normal status')
        call chk%equal(ss, regdae_success, 'stacked status')
        call chk%close_rel(yn, ref, 10*u*cond_normal, 'normal equations within 10 u cond(N)')
        call chk%close_rel(ys, ref, 10*u*cond_stacked, 'stacked within 10 u cond(S)')
        write (*, '(a,2es10.2)') '    relative errors normal, stacked: ', &
            maxval(abs(yn - ref))/maxval(abs(ref)), maxval(abs(ys - ref))/maxval(abs(ref))
    end subroutine ill_conditioned

    ! s4 = 0: the component along V e4 must vanish. c4 /= 0 makes the system
    ! inconsistent, so least-squares perturbation theory allows u cond^2 for the
    ! stacked solve as well as for the normal equations, cond^2 = (1 + eps)/eps = 1e8
    ! (measured: 2e-10 stacked).
    subroutine rank_deficient(chk)
        type(checker), intent(inout) :: chk
        real(wp), parameter :: s(4) = [1.0_wp, 0.5_wp, 0.25_wp, 0.0_wp], eps = 1.0e-8_wp
        real(wp) :: yn(4), ys(4), ref(4), bound
        integer :: sn, ss
        call solve_both(s, eps, yn, ys, sn, ss)
        ref = damped_reference(s, eps)
        bound = 10*u*(1.0_wp + eps)/eps
        call chk%equal(sn, regdae_success, 'normal status')
        call chk%equal(ss, regdae_success, 'stacked status')
        call chk%close_rel(yn, ref, bound, 'normal equations')
        call chk%close_rel(ys, ref, bound, 'stacked')
        call chk%close(dot_product(v_matrix_col(4), ys), 0.0_wp, bound*maxval(abs(ref)), &
                       'no component in the null space')
    end subroutine rank_deficient

    ! Invertible A: y(eps) -> A^-1 r with error ~ eps ||D^-3 c||, and eps = 0 gives A^-1 r.
    subroutine eps_to_zero(chk)
        type(checker), intent(inout) :: chk
        real(wp), parameter :: s(4) = [2.0_wp, 1.0_wp, 0.5_wp, 0.25_wp]
        real(wp) :: yn(4), ys(4), inverse(4), eps, bound
        integer :: sn, ss, k
        inverse = matmul(v_matrix(), c/s)
        do k = 2, 12, 2
            eps = 10.0_wp**(-k)
            call solve_both(s, eps, yn, ys, sn, ss)
            bound = 1.1_wp*eps*maxval(abs(c/s**3)) + 1.0e-13_wp
            call chk%true(maxval(abs(yn - inverse)) <= bound, 'normal: |y(eps) - A^-1 r| <= eps |D^-3 c|')
            call chk%true(maxval(abs(ys - inverse)) <= bound, 'stacked: |y(eps) - A^-1 r| <= eps |D^-3 c|')
        end do
        call solve_both(s, 0.0_wp, yn, ys, sn, ss)
        call chk%close_rel(yn, inverse, 1.0e-14_wp, 'normal, eps = 0')
        call chk%close_rel(ys, inverse, 1.0e-14_wp, 'stacked, eps = 0')
    end subroutine eps_to_zero

    ! eps = 0 and singular A: the stacked solve gives the minimum-norm solution,
    ! the normal equations report a singular matrix.
    subroutine eps_zero_rank_deficient(chk)
        type(checker), intent(inout) :: chk
        real(wp), parameter :: s(4) = [1.0_wp, 0.5_wp, 0.25_wp, 0.0_wp]
        real(wp) :: yn(4), ys(4)
        integer :: sn, ss
        call solve_both(s, 0.0_wp, yn, ys, sn, ss)
        call chk%equal(ss, regdae_success, 'stacked status')
        call chk%close_rel(ys, damped_reference(s, 0.0_wp), 1.0e-13_wp, 'stacked minimum-norm solution')
        call chk%equal(sn, regdae_err_singular, 'normal equations report the singular matrix')
    end subroutine eps_zero_rank_deficient

    ! sigma_min of 2 x 2 matrices (regdae_damped_lsq writes dgesvd's arithmetic out for
    ! them): against dgesvd itself on rotated diagonals, triangular and rank-one matrices,
    ! signed zeros and a tiny scale (where dgesvd scales and the written-out path defers to
    ! it); a fresh workspace per matrix (no structural rank deficiency carried over), and
    ! one that has seen only rank-one matrices (sigma on the structural rank: sigma_1).
    subroutine singular_2x2(chk)
        type(checker), intent(inout) :: chk
        type(damped_lsq_workspace) :: ws
        real(wp) :: a(2, 2), sv(2), work(64), dummy(1, 1), ca, sa, cb, sb, sigma, expected
        integer :: k, info
        character(len=2) :: tag
        do k = 1, 12
            ca = cos(0.7_wp*k)
            sa = sin(0.7_wp*k)
            cb = cos(1.9_wp*k + 0.3_wp)
            sb = sin(1.9_wp*k + 0.3_wp)
            a = matmul(reshape([ca, sa, -sa, ca], [2, 2]), &
                       matmul(diag2(3.0_wp, 10.0_wp**(-k)), reshape([cb, -sb, sb, cb], [2, 2])))
            select case (k)
            case (9); a(2, 1) = 0.0_wp
            case (10); a(1, 2) = 0.0_wp
            case (11); a(:, 2) = 2*a(:, 1)
            case (12); a = reshape([-0.0_wp, 1.0e-300_wp, 0.0_wp, 2.0e-300_wp], [2, 2])
            end select
            call ws%init(2, 2)
            sigma = ws%smallest_singular_value(a)
            call dgesvd('N', 'N', 2, 2, a, 2, sv, dummy, 1, dummy, 1, work, size(work), info)
            write (tag, '(i2)') k
            call chk%equal(info, 0, 'dgesvd '//tag)
            ! a first rank-deficient sample sets the structural deficiency: sigma_1 then
            expected = sv(2)
            if (sv(2) <= 2*u*sv(1)) expected = sv(1)
            call chk%true(abs(sigma - expected) <= 8*u*sv(1), 'sigma_min as dgesvd''s '//tag)
        end do
        call ws%init(2, 2)
        do k = 1, 3
            a = reshape([1.0_wp*k, 2.0_wp, -2.0_wp*k, -4.0_wp], [2, 2])   ! rank one
            sigma = ws%smallest_singular_value(a)
        end do
        call chk%true(abs(sigma - norm2(a)) <= 8*u*norm2(a), 'rank one throughout: sigma on the structural rank')
    contains
        pure function diag2(d1, d2) result(d)
            real(wp), intent(in) :: d1, d2
            real(wp) :: d(2, 2)
            d = reshape([d1, 0.0_wp, 0.0_wp, d2], [2, 2])
        end function diag2
    end subroutine singular_2x2

    subroutine shifted_spd(chk)
        type(checker), intent(inout) :: chk
        type(damped_lsq_workspace) :: ws
        real(wp) :: a(4, 4), y(4), s(4), eps
        integer :: stat
        call ws%init(4, 4)
        ! Symmetric PSD, singular: A = H diag(s) H^T.
        s = [1.0_wp, 0.5_wp, 0.25_wp, 0.0_wp]
        eps = 1.0e-6_wp
        a = matmul(h, matmul(diag(s), transpose(h)))
        call shifted_spd_solve(ws, a, matmul(h, c), eps, y, stat)
        call chk%equal(stat, regdae_success, 'PSD status')
        call chk%close_rel(y, matmul(h, c/(s + eps)), 10*u*(1.0_wp + eps)/eps, '(A + eps I)^-1 r')
        ! Indefinite: refused.
        s(4) = -0.5_wp
        a = matmul(h, matmul(diag(s), transpose(h)))
        call shifted_spd_solve(ws, a, matmul(h, c), 0.01_wp, y, stat)
        call chk%equal(stat, regdae_err_not_psd, 'indefinite matrix refused')
        ! Not symmetric: refused.
        a = a_matrix([1.0_wp, 0.5_wp, 0.25_wp, 0.125_wp])
        call shifted_spd_solve(ws, a, c, 0.01_wp, y, stat)
        call chk%equal(stat, regdae_err_not_psd, 'non-symmetric matrix refused')
    end subroutine shifted_spd

    subroutine square(chk)
        type(checker), intent(inout) :: chk
        type(damped_lsq_workspace) :: ws
        real(wp) :: y(4), s(4)
        integer :: stat
        call ws%init(4, 4)
        s = [2.0_wp, 1.0_wp, 0.5_wp, 0.25_wp]
        call square_solve(ws, a_matrix(s), matmul(h, c), y, stat)
        call chk%equal(stat, regdae_success, 'invertible status')
        call chk%close_rel(y, matmul(v_matrix(), c/s), 1.0e-14_wp, 'A^-1 r')
        call square_solve(ws, diag([1.0_wp, 2.0_wp, 0.0_wp, 3.0_wp]), c, y, stat)
        call chk%equal(stat, regdae_err_singular, 'singular matrix reported')
    end subroutine square

    subroutine bad_input(chk)
        type(checker), intent(inout) :: chk
        type(damped_lsq_workspace) :: ws
        real(wp) :: y(4), y3(3)
        integer :: stat
        call ws%init(4, 4)
        call damped_lsq_solve(ws, diag(c), c, -1.0e-6_wp, lsq_normal, y, stat)
        call chk%equal(stat, regdae_err_bad_input, 'eps < 0')
        call damped_lsq_solve(ws, diag(c), c, 1.0e-6_wp, lsq_stacked, y3, stat)
        call chk%equal(stat, regdae_err_bad_input, 'wrong solution length')
        call damped_lsq_solve(ws, diag(c(1:3)), c(1:3), 1.0e-6_wp, lsq_stacked, y3, stat)
        call chk%equal(stat, regdae_err_bad_input, 'matrix of another size than the workspace')
        call damped_lsq_solve(ws, diag(c), c, 1.0e-6_wp, 99, y, stat)
        call chk%equal(stat, regdae_err_bad_input, 'unknown method')
    end subroutine bad_input

    pure function diag(d) result(a)
        real(wp), intent(in) :: d(:)
        real(wp) :: a(size(d), size(d))
        integer :: i
        a = 0.0_wp
        do i = 1, size(d)
            a(i, i) = d(i)
        end do
    end function diag

end module test_lsq
