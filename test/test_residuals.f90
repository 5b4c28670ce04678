!> Unit tests of the regularized residuals against values computed by hand
!! for Example 5.1 (orientation psd) at t = 0.5, x = 1.7, y = 0.3, x' = 0.9,
!! gamma = 10, eps = 0.01:
!!   f = 2, B = G = 0.5, g = 0.5*1.7 - 0.5*1.5 = 0.1, g_t = 1.7 - 1 - 1 = -0.3,
!!   GB = 0.25, r = G f + g_t + gamma g = 1 - 0.3 + 1 = 1.7.
module test_residuals
    use regdae, only: wp, constraint_dt_difference, solver_options, method_trust_region, method_direct, method_baumgarte, &
                      lsq_normal, lsq_stacked, regdae_success
    use regdae_regularization, only: regularized_dae
    use ex51_problem, only: ex51, new_ex51, orientation_psd
    use regdae_testing, only: checker, test_case, new_test
    implicit none
    private
    public :: residual_tests

    real(wp), parameter :: t = 0.5_wp, x(1) = 1.7_wp, y(1) = 0.3_wp, xp(1) = 0.9_wp
    real(wp), parameter :: tol = 4*epsilon(1.0_wp)

    !> Example 5.1 without its g_t: exercises the default difference quotient.
    type, extends(ex51) :: ex51_without_gt
    contains
        procedure :: constraint_dt => dq_constraint_dt
    end type ex51_without_gt

contains

    function residual_tests() result(tests)
        type(test_case), allocatable :: tests(:)
        tests = [new_test('pieces', pieces), &
                 new_test('multiplier_trust_region', multiplier_trust_region), &
                 new_test('multiplier_direct', multiplier_direct), &
                 new_test('multiplier_baumgarte', multiplier_baumgarte), &
                 new_test('eliminated_all_methods', eliminated_all_methods), &
                 new_test('default_constraint_dt', default_constraint_dt)]
    end function residual_tests

    subroutine dq_constraint_dt(self, t, x, v, stat)
        class(ex51_without_gt), intent(inout) :: self
        real(wp), intent(in) :: t, x(:)
        real(wp), intent(out) :: v(:)
        integer, intent(inout) :: stat
        call constraint_dt_difference(self, t, x, v, stat)
    end subroutine dq_constraint_dt

    function model_for(method, lsq) result(model)
        integer, intent(in) :: method, lsq
        type(regularized_dae) :: model
        type(solver_options) :: opts
        opts%method = method
        opts%gamma = 10.0_wp
        opts%eps = 0.01_wp
        call model%init_first_order(new_ex51(orientation_psd), opts, lsq)
    end function model_for

    subroutine pieces(chk)
        type(checker), intent(inout) :: chk
        type(regularized_dae) :: model
        integer :: stat
        logical :: recoverable
        model = model_for(method_trust_region, lsq_normal)
        call model%evaluate(t, x, stat, recoverable)
        call chk%equal(stat, regdae_success, 'status')
        call chk%close(model%f(1), 2.0_wp, tol, 'f')
        call chk%close(model%b(1, 1), 0.5_wp, tol, 'B')
        call chk%close(model%g(1), 0.1_wp, tol, 'g')
        call chk%close(model%gx(1, 1), 0.5_wp, tol, 'G')
        call chk%close(model%gt(1), -0.3_wp, tol, 'g_t')
        call chk%close(model%gb(1, 1), 0.25_wp, tol, 'GB')
        call chk%close(model%r(1), 1.7_wp, tol, 'r = G f + g_t + gamma g')
    end subroutine pieces

    ! x row: x' - f + B y = 0.9 - 2 + 0.15 = -0.95;
    ! y row: GB (GB y - r) + eps y = 0.25 (0.075 - 1.7) + 0.003 = -0.40325.
    subroutine multiplier_trust_region(chk)
        type(checker), intent(inout) :: chk
        call check_multiplier(chk, method_trust_region, -0.95_wp, -0.40325_wp)
    end subroutine multiplier_trust_region

    ! y row: (GB + eps) y - r = 0.26*0.3 - 1.7 = -1.622.
    subroutine multiplier_direct(chk)
        type(checker), intent(inout) :: chk
        call check_multiplier(chk, method_direct, -0.95_wp, -1.622_wp)
    end subroutine multiplier_direct

    ! y row (2.5): gamma g + G x' + g_t = 1 + 0.45 - 0.3 = 1.15.
    subroutine multiplier_baumgarte(chk)
        type(checker), intent(inout) :: chk
        call check_multiplier(chk, method_baumgarte, -0.95_wp, 1.15_wp)
    end subroutine multiplier_baumgarte

    subroutine check_multiplier(chk, method, expected_x, expected_y)
        type(checker), intent(inout) :: chk
        integer, intent(in) :: method
        real(wp), intent(in) :: expected_x, expected_y
        type(regularized_dae) :: model
        real(wp) :: res_x(1), res_y(1)
        integer :: stat
        logical :: recoverable
        model = model_for(method, lsq_normal)
        call model%residual_multiplier(t, x, y, xp, res_x, res_y, stat, recoverable)
        call chk%equal(stat, regdae_success, 'status')
        call chk%close(res_x(1), expected_x, tol, 'x row')
        call chk%close(res_y(1), expected_y, tol, 'y row')
    end subroutine check_multiplier

    ! y(x): trust region GB r/(GB^2 + eps) = 0.425/0.0725; direct r/(GB + eps) = 1.7/0.26;
    ! Baumgarte r/GB = 6.8. Residual x' - f + B y.
    subroutine eliminated_all_methods(chk)
        type(checker), intent(inout) :: chk
        call check_eliminated(chk, method_trust_region, lsq_normal, 0.425_wp/0.0725_wp)
        call check_eliminated(chk, method_trust_region, lsq_stacked, 0.425_wp/0.0725_wp)
        call check_eliminated(chk, method_direct, lsq_normal, 1.7_wp/0.26_wp)
        call check_eliminated(chk, method_baumgarte, lsq_normal, 6.8_wp)
    end subroutine eliminated_all_methods

    subroutine check_eliminated(chk, method, lsq, expected_y)
        type(checker), intent(inout) :: chk
        integer, intent(in) :: method, lsq
        real(wp), intent(in) :: expected_y
        type(regularized_dae) :: model
        real(wp) :: res(1), y_used(1)
        integer :: stat
        logical :: recoverable
        model = model_for(method, lsq)
        call model%residual_eliminated(t, x, xp, res, y_used, stat, recoverable)
        call chk%equal(stat, regdae_success, 'status')
        call chk%close(y_used(1), expected_y, 8*tol, 'y(x)')
        call chk%close(res(1), xp(1) - 2.0_wp + 0.5_wp*expected_y, 8*tol, 'residual')
        ! The explicit integrator's slope F is the same model: residual = x' - F.
        call model%slope_eliminated(t, x, res, y_used, stat, recoverable)
        call chk%equal(stat, regdae_success, 'slope status')
        call chk%close(res(1), 2.0_wp - 0.5_wp*expected_y, 8*tol, 'slope F = f - B y')
    end subroutine check_eliminated

    ! Central difference with d = u^(1/3): error ~ u^(2/3) ~ 4e-11 on g_t = -0.3
    ! (g is quadratic in t, so the truncation error is zero here; the bound is rounding).
    subroutine default_constraint_dt(chk)
        type(checker), intent(inout) :: chk
        type(ex51_without_gt) :: p
        real(wp) :: gt(1)
        integer :: stat
        p%ex51 = new_ex51(orientation_psd)
        stat = 0
        call p%constraint_dt(t, x, gt, stat)
        call chk%equal(stat, 0, 'status')
        call chk%close(gt(1), -0.3_wp, 1.0e-10_wp, 'g_t by difference quotient')
    end subroutine default_constraint_dt

end module test_residuals
