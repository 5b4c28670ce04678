!> Tests of the Radau IIA integrator (regdae_radau_iia): its coefficients, its
!! order at fixed steps, stiff accuracy (Prothero-Robinson), a stiff linear
!! system and an index-1 DAE against exact solutions, tolerance proportionality,
!! the step counts on Van der Pol, failures of F, a change of F between steps
!! (`refresh`), and bad input; the Newton matrices' LU in test_radau_linear.
module test_radau
    use regdae_kinds, only: wp
    use regdae_status, only: regdae_success, regdae_err_bad_input, regdae_err_user_callback, &
                             regdae_err_not_initialized, regdae_err_integration
    use regdae_radau_tableau, only: radau_coefficients, radau_iia_coefficients
    use regdae_radau_system, only: radau_system, radau_options, radau_stats
    use regdae_radau_iia, only: radau_integrator
    use test_radau_linear, only: radau_linear_tests
    use regdae_testing, only: checker, test_case, new_test
    implicit none
    private
    public :: radau_tests

    !> x' = -y + x (1 - r^2), y' = x + y (1 - r^2): r' = r (1 - r^2), angle' = 1, so
    !! r(t) = (1 + (1/r0^2 - 1) e^{-2t})^{-1/2}, angle(t) = angle0 + t.
    type, extends(radau_system) :: limit_cycle
    contains
        procedure :: rhs => limit_cycle_rhs
    end type limit_cycle

    !> Prothero-Robinson: y' = lambda (y - sin t) + cos t, y(0) = 0: y = sin t.
    type, extends(radau_system) :: prothero_robinson
        real(wp) :: lambda = -1.0e6_wp
    contains
        procedure :: rhs => pr_rhs
        procedure :: has_jacobian => pr_has_jacobian
        procedure :: jacobian => pr_jacobian
    end type prothero_robinson

    !> The limit cycle as 2 u' = 2 F(u) (mass = (2, 2)).
    type, extends(limit_cycle) :: doubled_limit_cycle
    contains
        procedure :: rhs => doubled_rhs
    end type doubled_limit_cycle

    !> Prothero-Robinson without its analytic Jacobian (difference quotients).
    type, extends(prothero_robinson) :: pr_quotients
    contains
        procedure :: has_jacobian => pr_no_jacobian
    end type pr_quotients

    !> y' = Q D Q^T y, Q a Householder reflector, D = diag(-1, -1e4, -1e6).
    type, extends(radau_system) :: stiff_linear
        real(wp) :: a(3, 3) = 0
    contains
        procedure :: rhs => stiff_linear_rhs
    end type stiff_linear

    !> u1' = -u1 + u2^2, 0 = sin t - u2, 0 = u1 u2 - u3 (M = diag(1, 0, 0)):
    !! u2 = sin t, u1 = 1/2 - cos(2t)/10 - sin(2t)/5, u3 = u1 u2.
    type, extends(radau_system) :: index1_dae
    contains
        procedure :: rhs => dae_rhs
    end type index1_dae

    !> An index-2 DAE: y' = z, 0 = sin t - y (M = diag(1, 0)): y = sin t, z = cos t.
    type, extends(radau_system) :: index2_dae
    contains
        procedure :: rhs => index2_rhs
    end type index2_dae

    !> u1' = -u1 + u2, 0 = p - u2 (M = diag(1, 0)): u2 = p; p is changed between steps.
    type, extends(radau_system) :: shifted_dae
        real(wp) :: p = 1
    contains
        procedure :: rhs => shifted_rhs
    end type shifted_dae

    !> Van der Pol: y1' = y2, y2' = mu ((1 - y1^2) y2 - y1).
    type, extends(radau_system) :: van_der_pol
        real(wp) :: mu = 1.0e6_wp
    contains
        procedure :: rhs => vdp_rhs
    end type van_der_pol

    !> y' = -y, failing beyond t_fail: recoverably on its first n_recoverable such calls,
    !! then (fatal = .true.) unrecoverably.
    type, extends(radau_system) :: failing_decay
        real(wp) :: t_fail = 0.5_wp
        integer :: n_recoverable = 0
        logical :: fatal = .false.
        integer :: failures = 0
    contains
        procedure :: rhs => failing_rhs
    end type failing_decay

contains

    function radau_tests() result(tests)
        type(test_case), allocatable :: tests(:)
        tests = [new_test('coefficients', coefficients), new_test('order_fixed_steps', order_fixed_steps), &
                 new_test('prothero_robinson_adaptive', pr_adaptive), new_test('prothero_robinson_fixed', pr_fixed), &
                 new_test('stiff_linear_exact', stiff_linear_exact), new_test('dae_index1_exact', dae_index1_exact), &
                 new_test('dae_index2', dae_index2), &
                 new_test('tolerance_proportionality', tolerance_proportionality), &
                 new_test('mass_and_jacobian', mass_and_jacobian), new_test('dense_output', dense_output), &
                 new_test('van_der_pol_counts', van_der_pol_counts), &
                 new_test('rhs_failures', rhs_failures), new_test('refresh_after_change', refresh_after_change), &
                 new_test('bad_input', bad_input), radau_linear_tests()]
    end function radau_tests

    ! ---------------------------------------------------------------- problems

    subroutine limit_cycle_rhs(self, t, u, f, stat, recoverable)
        class(limit_cycle), intent(inout) :: self
        real(wp), intent(in) :: t, u(:)
        real(wp), intent(out) :: f(:)
        integer, intent(out) :: stat
        logical, intent(out) :: recoverable
        real(wp) :: g
        g = 1 - u(1)**2 - u(2)**2
        f(1) = -u(2) + u(1)*g
        f(2) = u(1) + u(2)*g
        stat = regdae_success
        recoverable = .true.
    end subroutine limit_cycle_rhs

    function limit_cycle_exact(t, r0) result(u)
        real(wp), intent(in) :: t, r0
        real(wp) :: u(2), r
        r = 1/sqrt(1 + (1/r0**2 - 1)*exp(-2*t))
        u = r*[cos(t), sin(t)]
    end function limit_cycle_exact

    subroutine pr_rhs(self, t, u, f, stat, recoverable)
        class(prothero_robinson), intent(inout) :: self
        real(wp), intent(in) :: t, u(:)
        real(wp), intent(out) :: f(:)
        integer, intent(out) :: stat
        logical, intent(out) :: recoverable
        f(1) = self%lambda*(u(1) - sin(t)) + cos(t)
        stat = regdae_success
        recoverable = .true.
    end subroutine pr_rhs

    logical function pr_has_jacobian(self)
        class(prothero_robinson), intent(in) :: self
        pr_has_jacobian = .true.
    end function pr_has_jacobian

    subroutine pr_jacobian(self, t, u, f, dfdu, stat, recoverable)
        class(prothero_robinson), intent(inout) :: self
        real(wp), intent(in) :: t, u(:), f(:)
        real(wp), intent(out) :: dfdu(:, :)
        integer, intent(out) :: stat
        logical, intent(out) :: recoverable
        dfdu = self%lambda
        stat = regdae_success
        recoverable = .true.
    end subroutine pr_jacobian

    subroutine doubled_rhs(self, t, u, f, stat, recoverable)
        class(doubled_limit_cycle), intent(inout) :: self
        real(wp), intent(in) :: t, u(:)
        real(wp), intent(out) :: f(:)
        integer, intent(out) :: stat
        logical, intent(out) :: recoverable
        call limit_cycle_rhs(self, t, u, f, stat, recoverable)
        f = 2*f
    end subroutine doubled_rhs

    logical function pr_no_jacobian(self)
        class(pr_quotients), intent(in) :: self
        pr_no_jacobian = .false.
    end function pr_no_jacobian

    subroutine stiff_linear_rhs(self, t, u, f, stat, recoverable)
        class(stiff_linear), intent(inout) :: self
        real(wp), intent(in) :: t, u(:)
        real(wp), intent(out) :: f(:)
        integer, intent(out) :: stat
        logical, intent(out) :: recoverable
        f = matmul(self%a, u)
        stat = regdae_success
        recoverable = .true.
    end subroutine stiff_linear_rhs

    ! Q = I - 2 v v^T / v^T v, v = (1, 2, 3); the system and its exact flow.
    subroutine stiff_linear_setup(lambda, q, a)
        real(wp), intent(in) :: lambda(3)
        real(wp), intent(out) :: q(3, 3), a(3, 3)
        real(wp) :: v(3)
        integer :: i
        v = [1.0_wp, 2.0_wp, 3.0_wp]
        q = -2*spread(v, 2, 3)*spread(v, 1, 3)/dot_product(v, v)
        do i = 1, 3
            q(i, i) = q(i, i) + 1
        end do
        a = matmul(q, matmul(diag(lambda), transpose(q)))
    end subroutine stiff_linear_setup

    pure function diag(d) result(m)
        real(wp), intent(in) :: d(:)
        real(wp) :: m(size(d), size(d))
        integer :: i
        m = 0
        do i = 1, size(d)
            m(i, i) = d(i)
        end do
    end function diag

    subroutine shifted_rhs(self, t, u, f, stat, recoverable)
        class(shifted_dae), intent(inout) :: self
        real(wp), intent(in) :: t, u(:)
        real(wp), intent(out) :: f(:)
        integer, intent(out) :: stat
        logical, intent(out) :: recoverable
        f(1) = -u(1) + u(2)
        f(2) = self%p - u(2) + 0*t
        stat = regdae_success
        recoverable = .true.
    end subroutine shifted_rhs

    subroutine dae_rhs(self, t, u, f, stat, recoverable)
        class(index1_dae), intent(inout) :: self
        real(wp), intent(in) :: t, u(:)
        real(wp), intent(out) :: f(:)
        integer, intent(out) :: stat
        logical, intent(out) :: recoverable
        f(1) = -u(1) + u(2)**2
        f(2) = sin(t) - u(2)
        f(3) = u(1)*u(2) - u(3)
        stat = regdae_success
        recoverable = .true.
    end subroutine dae_rhs

    function dae_exact(t) result(u)
        real(wp), intent(in) :: t
        real(wp) :: u(3)
        u(1) = 0.5_wp - cos(2*t)/10 - sin(2*t)/5
        u(2) = sin(t)
        u(3) = u(1)*u(2)
    end function dae_exact

    subroutine index2_rhs(self, t, u, f, stat, recoverable)
        class(index2_dae), intent(inout) :: self
        real(wp), intent(in) :: t, u(:)
        real(wp), intent(out) :: f(:)
        integer, intent(out) :: stat
        logical, intent(out) :: recoverable
        f(1) = u(2)
        f(2) = sin(t) - u(1)
        stat = regdae_success
        recoverable = .true.
    end subroutine index2_rhs

    subroutine vdp_rhs(self, t, u, f, stat, recoverable)
        class(van_der_pol), intent(inout) :: self
        real(wp), intent(in) :: t, u(:)
        real(wp), intent(out) :: f(:)
        integer, intent(out) :: stat
        logical, intent(out) :: recoverable
        f(1) = u(2)
        f(2) = self%mu*((1 - u(1)**2)*u(2) - u(1))
        stat = regdae_success
        recoverable = .true.
    end subroutine vdp_rhs

    subroutine failing_rhs(self, t, u, f, stat, recoverable)
        class(failing_decay), intent(inout) :: self
        real(wp), intent(in) :: t, u(:)
        real(wp), intent(out) :: f(:)
        integer, intent(out) :: stat
        logical, intent(out) :: recoverable
        f = -u
        stat = regdae_success
        recoverable = .true.
        if (t > self%t_fail) then
            if (self%failures < self%n_recoverable) then
                self%failures = self%failures + 1
                stat = regdae_err_user_callback
            else if (self%fatal) then
                stat = regdae_err_user_callback
                recoverable = .false.
            end if
        end if
    end subroutine failing_rhs

    ! ---------------------------------------------------------------- helpers

    !> Least-squares slope of log(y) against log(x).
    pure real(wp) function loglog_slope(x, y)
        real(wp), intent(in) :: x(:), y(:)
        real(wp) :: lx(size(x)), ly(size(y))
        lx = log(x)
        ly = log(y)
        loglog_slope = sum((lx - sum(lx)/size(lx))*(ly - sum(ly)/size(ly)))/sum((lx - sum(lx)/size(lx))**2)
    end function loglog_slope

    !> Integrate sys from t0 with u0 to t_end (landing on it); u = u(t_end).
    subroutine run(sys, t0, u0, t_end, opts, u, stat, stats)
        class(radau_system), intent(inout) :: sys
        real(wp), intent(in) :: t0, u0(:), t_end
        type(radau_options), intent(in) :: opts
        real(wp), intent(out) :: u(:)
        integer, intent(out) :: stat
        type(radau_stats), intent(out), optional :: stats
        type(radau_integrator) :: integ
        call integ%start(sys, t0, u0, opts, stat)
        if (stat == regdae_success) call integ%advance(sys, t_end, u, stat, land=.true.)
        if (stat /= regdae_success) write (*, '(a)') '    '//integ%message()
        if (present(stats)) stats = integ%statistics()
    end subroutine run

    ! ---------------------------------------------------------------- tests

    !> The coefficients against their defining properties. Tolerances: the
    !! entries are O(1) to O(10) and computed in a few operations, so 1e-13
    !! (about 500 u) is rounding.
    subroutine coefficients(chk)
        type(checker), intent(inout) :: chk
        type(radau_coefficients) :: rc
        real(wp) :: lam(3, 3), r(3, 3), s6, z
        integer :: i, k
        character(len=1) :: kk
        rc = radau_iia_coefficients()
        s6 = sqrt(6.0_wp)
        do i = 1, 3   ! row sums are the nodes
            call chk%close(sum(rc%a(i, :)), rc%c(i), 1.0e-14_wp, 'sum of row of A = c_i')
        end do
        do k = 1, 5   ! the quadrature (b, c) is exact for degree <= 4: order 5
            write (kk, '(i1)') k
            call chk%close(sum(rc%b*rc%c**(k - 1)), 1.0_wp/k, 1.0e-14_wp, 'sum b c^(k-1) = 1/k, k = '//kk)
        end do
        do k = 1, 3   ! stage order 3: C(3), sum_j a_ij c_j^(k-1) = c_i^k / k
            write (kk, '(i1)') k
            r(:, k) = matmul(rc%a, rc%c**(k - 1)) - rc%c**k/k
            call chk%true(maxval(abs(r(:, k))) < 1.0e-14_wp, 'C(3) holds, k = '//kk)
        end do
        r = matmul(rc%a, rc%a_inv)
        call chk%true(maxval(abs(r - diag([1.0_wp, 1.0_wp, 1.0_wp]))) < 1.0e-13_wp, 'A A^-1 = I')
        lam = matmul(rc%t_inv, matmul(rc%a_inv, rc%t))
        r = diag([rc%gamma, rc%alpha, rc%alpha])
        r(2, 3) = -rc%beta
        r(3, 2) = rc%beta
        call chk%true(maxval(abs(lam - r)) < 1.0e-13_wp, 'T^-1 A^-1 T = diag(gamma, [alpha -beta; beta alpha])')
        ! gamma and alpha + i beta are the roots of z^3 - 9 z^2 + 36 z - 60 (the poles of R(z))
        z = rc%gamma
        call chk%close(z**3 - 9*z**2 + 36*z - 60, 0.0_wp, 1.0e-12_wp, 'gamma is a pole of R')
        call chk%close(abs(cubic(cmplx(rc%alpha, rc%beta, wp))), 0.0_wp, 1.0e-12_wp, 'alpha + i beta is a pole of R')
        call chk%close(rc%gamma, 3.6378342527444957_wp, 1.0e-14_wp, 'gamma (published 3.63783425...)')
        ! the published error estimator weights, e = gamma0/3 (-13 - 7 s6, -13 + 7 s6, -1) / gamma0
        call chk%close(rc%e(1), (-13 - 7*s6)/3, 1.0e-13_wp, 'e_1')
        call chk%close(rc%e(2), (-13 + 7*s6)/3, 1.0e-13_wp, 'e_2')
        call chk%close(rc%e(3), -1.0_wp/3, 1.0e-13_wp, 'e_3')
        ! the collocation polynomial reproduces the stages: sum_k p(k, j) c_i^k = delta_ij
        do i = 1, 3
            do k = 1, 3
                r(i, k) = sum(rc%p(:, k)*rc%c(i)**[1, 2, 3])
            end do
        end do
        call chk%true(maxval(abs(r - diag([1.0_wp, 1.0_wp, 1.0_wp]))) < 1.0e-13_wp, 'collocation polynomial')
    contains
        complex(wp) function cubic(x)
            complex(wp), intent(in) :: x
            cubic = x**3 - 9*x**2 + 36*x - 60
        end function cubic
    end subroutine coefficients

    !> Order 5 at fixed steps h = 0.4 ... 0.4/32 on the limit cycle (t in [0, 4],
    !! r0 = 0.2), against the exact solution. Newton is converged far below the
    !! error (rtol = atol = 1e-13: kappa tol ~ 3e-16; 20 iterations allowed for
    !! the largest step), so the slope is the method's. The slope is fitted on
    !! h = 0.4 ... 0.025, where the error (1e-5 ... 1e-11) is far above rounding.
    subroutine order_fixed_steps(chk)
        type(checker), intent(inout) :: chk
        type(limit_cycle) :: sys
        type(radau_options) :: opts
        real(wp) :: u(2), hs(6), errs(6), slope
        integer :: k, stat
        opts%rtol = 1.0e-13_wp
        opts%atol = 1.0e-13_wp
        opts%fixed_step = .true.
        opts%max_newton = 20
        do k = 1, size(hs)
            hs(k) = 0.4_wp/2**(k - 1)
            opts%h0 = hs(k)
            call run(sys, 0.0_wp, [0.2_wp, 0.0_wp], 4.0_wp, opts, u, stat)
            call chk%equal(stat, regdae_success, 'fixed-step run')
            errs(k) = maxval(abs(u - limit_cycle_exact(4.0_wp, 0.2_wp)))
            write (*, '(a,es10.3,a,es10.3)') '    fixed h = ', hs(k), ': error ', errs(k)
        end do
        slope = loglog_slope(hs(1:5), errs(1:5))
        write (*, '(a,f6.3)') '    order (slope of log error against log h, h = 0.4 ... 0.025): ', slope
        call chk%true(slope >= 4.8_wp .and. slope <= 5.2_wp, 'order 5 at fixed steps')
    end subroutine order_fixed_steps

    !> Prothero-Robinson with lambda = -1e6, -1e7, -1e8 at rtol = atol = 1e-6, adaptive:
    !! the error at t = 0.1, 1, 2 (steps landing there) within 10 rtol. (Between the
    !! steps the continuous extension is a cubic: on this stiff problem the steps grow
    !! to O(1) and it is good to about h^4/4! only, 1e-2; the estimate controls the
    !! step's end, not the extension, as in Hairer & Wanner's code.)
    subroutine pr_adaptive(chk)
        type(checker), intent(inout) :: chk
        type(prothero_robinson) :: sys
        type(radau_options) :: opts
        type(radau_integrator) :: integ
        real(wp) :: u(1), lambdas(3) = [-1.0e6_wp, -1.0e7_wp, -1.0e8_wp], touts(3) = [0.1_wp, 1.0_wp, 2.0_wp], err
        integer :: k, i, stat
        type(radau_stats) :: st
        opts%rtol = 1.0e-6_wp
        opts%atol = 1.0e-6_wp
        do k = 1, size(lambdas)
            sys%lambda = lambdas(k)
            call integ%start(sys, 0.0_wp, [0.0_wp], opts, stat)
            err = 0
            do i = 1, size(touts)
                call integ%advance(sys, touts(i), u, stat, land=.true.)
                call chk%equal(stat, regdae_success, 'adaptive Prothero-Robinson')
                err = max(err, abs(u(1) - sin(touts(i))))
            end do
            st = integ%statistics()
            write (*, '(a,es8.1,a,es10.3,a,i0,a,i0)') '    lambda = ', lambdas(k), ': error ', err, ', steps ', &
                st%accepted, ', rejected ', st%rejected
            call chk%true(err <= 10*opts%rtol, 'Prothero-Robinson error within 10 rtol')
        end do
    end subroutine pr_adaptive

    !> Prothero-Robinson at fixed steps h = 0.4 ... 0.4/16 on [0, 2]. For |h lambda| >> 1
    !! the theory of stiffly accurate methods (Hairer & Wanner II, IV.15) gives the
    !! error O(h^(q+1)/(h lambda)) = O(h^3/|lambda|), q = 3 the stage order: the
    !! classical order 5 is not seen, the error is damped by 1/|lambda| instead.
    !! Asserted: the slope 3 +- 0.3 at lambda = -1e6 (errors 1e-9 ... 1e-13, above
    !! rounding), and 100x smaller errors at lambda = -1e8 (within 20 %) on the three
    !! largest steps (the smaller ones reach rounding, 1e-16, there).
    subroutine pr_fixed(chk)
        type(checker), intent(inout) :: chk
        type(prothero_robinson) :: sys
        type(radau_options) :: opts
        real(wp) :: u(1), hs(5), errs(5, 2), lambdas(2) = [-1.0e6_wp, -1.0e8_wp], slope
        integer :: k, j, stat
        opts%rtol = 1.0e-13_wp
        opts%atol = 1.0e-13_wp
        opts%fixed_step = .true.
        do j = 1, 2
            sys%lambda = lambdas(j)
            do k = 1, size(hs)
                hs(k) = 0.4_wp/2**(k - 1)
                opts%h0 = hs(k)
                call run(sys, 0.0_wp, [0.0_wp], 2.0_wp, opts, u, stat)
                call chk%equal(stat, regdae_success, 'fixed-step Prothero-Robinson')
                errs(k, j) = abs(u(1) - sin(2.0_wp))
            end do
            write (*, '(a,es8.1,a,5es10.2)') '    lambda = ', lambdas(j), ': errors', errs(:, j)
        end do
        slope = loglog_slope(hs, errs(:, 1))
        write (*, '(a,f6.3)') '    slope at lambda = -1e6: ', slope
        call chk%true(slope >= 2.7_wp .and. slope <= 3.3_wp, 'slope 3 (h^3 / lambda) in the stiff regime')
        call chk%true(all(abs(errs(1:3, 1)/errs(1:3, 2)/100 - 1) < 0.2_wp), 'error proportional to 1/|lambda|')
    end subroutine pr_fixed

    !> y' = Q D Q^T y, eigenvalues -1, -1e4, -1e6, exact y(t) = Q exp(D t) Q^T y0,
    !! at rtol = 1e-6 (atol 1e-10) checked inside the transients (dense output) and after.
    subroutine stiff_linear_exact(chk)
        type(checker), intent(inout) :: chk
        type(stiff_linear) :: sys
        type(radau_options) :: opts
        type(radau_integrator) :: integ
        real(wp) :: q(3, 3), lambda(3) = [-1.0_wp, -1.0e4_wp, -1.0e6_wp], y0(3) = [1.0_wp, 1.0_wp, 1.0_wp]
        real(wp) :: touts(6) = [1.0e-6_wp, 1.0e-5_wp, 1.0e-4_wp, 1.0e-2_wp, 1.0_wp, 10.0_wp], u(3), exact(3), err
        integer :: i, stat
        type(radau_stats) :: st
        call stiff_linear_setup(lambda, q, sys%a)
        opts%rtol = 1.0e-6_wp
        opts%atol = 1.0e-10_wp
        call integ%start(sys, 0.0_wp, y0, opts, stat)
        err = 0
        do i = 1, size(touts)
            call integ%advance(sys, touts(i), u, stat)
            call chk%equal(stat, regdae_success, 'stiff linear run')
            exact = matmul(q, exp(lambda*touts(i))*matmul(transpose(q), y0))
            err = max(err, maxval(abs(u - exact))/maxval(abs(exact)))
            write (*, '(a,es8.1,a,es10.3)') '    t = ', touts(i), ': relative error ', &
                maxval(abs(u - exact))/maxval(abs(exact))
        end do
        st = integ%statistics()
        write (*, '(a,i0,a,i0,a,i0,a,i0)') '    steps ', st%accepted, ', rejected ', st%rejected, ', Jacobians ', &
            st%jacobians, ', LU ', st%lu_decompositions
        call chk%true(err <= 10*opts%rtol, 'stiff linear system within 10 rtol of the exact solution')
    end subroutine stiff_linear_exact

    !> The semi-explicit index-1 DAE (M = diag(1, 0, 0)) against its exact solution, with
    !! the algebraic components in the error test and without them.
    subroutine dae_index1_exact(chk)
        type(checker), intent(inout) :: chk
        type(index1_dae) :: sys
        type(radau_options) :: opts
        real(wp) :: u(3), err
        integer :: stat, k
        type(radau_stats) :: st
        opts%rtol = 1.0e-7_wp
        opts%atol = 1.0e-7_wp
        opts%mass = [1.0_wp, 0.0_wp, 0.0_wp]
        do k = 1, 2
            if (k == 2) opts%error_test = [.true., .false., .false.]
            call run(sys, 0.0_wp, dae_exact(0.0_wp), 5.0_wp, opts, u, stat, st)
            call chk%equal(stat, regdae_success, 'index-1 DAE run')
            err = maxval(abs(u - dae_exact(5.0_wp)))
            write (*, '(a,l1,a,es10.3,a,i0)') '    algebraic components in the error test: ', k == 1, ': error ', &
                err, ', steps ', st%accepted
            call chk%true(err <= 10*opts%rtol, 'index-1 DAE within 10 rtol')
        end do
    end subroutine dae_index1_exact

    !> F changed between steps (p: 1 -> 2 at t = 0.5, as the monitor changes the augmented
    !! formulation's eps and weights): after `refresh` the next step takes a new Jacobian
    !! (its difference quotients from the new F(t, u)) and the solution follows the new F:
    !! u2 = 2, u1(1) = 2 + (u1(0.5) - 2) e^{-1/2}, u1(0.5) = 1 - e^{-1/2}.
    subroutine refresh_after_change(chk)
        type(checker), intent(inout) :: chk
        type(shifted_dae) :: sys
        type(radau_integrator) :: ri
        type(radau_options) :: opts
        real(wp) :: u(2), u1_half
        integer :: stat, jacobians
        type(radau_stats) :: st
        opts%rtol = 1.0e-8_wp
        opts%atol = 1.0e-8_wp
        opts%mass = [1.0_wp, 0.0_wp]
        call ri%start(sys, 0.0_wp, [0.0_wp, 1.0_wp], opts, stat)
        call ri%advance(sys, 0.5_wp, u, stat, land=.true.)
        call chk%equal(stat, regdae_success, 'steps to t = 0.5')
        sys%p = 2
        call ri%refresh(sys, stat)
        call chk%equal(stat, regdae_success, 'refresh')
        st = ri%statistics()
        jacobians = st%jacobians
        call ri%step(sys, stat)
        st = ri%statistics()
        call chk%equal(st%jacobians, jacobians + 1, 'a new Jacobian at the step after refresh')
        call ri%advance(sys, 1.0_wp, u, stat, land=.true.)
        call chk%equal(stat, regdae_success, 'steps to t = 1 with the new F')
        u1_half = 1 - exp(-0.5_wp)
        call chk%close(u(2), 2.0_wp, 1.0e-12_wp, 'u2 follows p')
        call chk%close(u(1), 2 + (u1_half - 2)*exp(-0.5_wp), 1.0e-7_wp, 'u1 after the change')
    end subroutine refresh_after_change

    !> The index-2 DAE with dae_index = (1, 2): the error of the index-2 component
    !! enters the test multiplied by h. Radau IIA's orders on index 2 (Hairer & Wanner
    !! II, VII.4): 5 for y, 3 for z at the step points.
    subroutine dae_index2(chk)
        type(checker), intent(inout) :: chk
        type(index2_dae) :: sys
        type(radau_options) :: opts
        real(wp) :: u(2), tols(3), erry(3), errz(3)
        integer :: stat, k
        type(radau_stats) :: st
        opts%mass = [1.0_wp, 0.0_wp]
        opts%dae_index = [1, 2]
        do k = 1, size(tols)
            tols(k) = 10.0_wp**(-3 - 2*k)
            opts%rtol = tols(k)
            opts%atol = tols(k)
            call run(sys, 0.0_wp, [0.0_wp, 1.0_wp], 3.0_wp, opts, u, stat, st)
            call chk%equal(stat, regdae_success, 'index-2 DAE run')
            erry(k) = abs(u(1) - sin(3.0_wp))
            errz(k) = abs(u(2) - cos(3.0_wp))
            write (*, '(a,es8.1,a,es10.3,a,es10.3,a,i0,a,i0)') '    rtol = ', tols(k), ': error y ', erry(k), &
                ', z ', errz(k), ', steps ', st%accepted, ', rejected ', st%rejected
        end do
        call chk%true(all(erry <= 10*tols), 'index-2 DAE: y within 10 rtol')
        call chk%true(all(errz <= 100*tols), 'index-2 DAE: z within 100 rtol')
    end subroutine dae_index2

    !> The error at t = 10 on the limit cycle for rtol = atol = 1e-4 ... 1e-10 falls with the tolerance.
    subroutine tolerance_proportionality(chk)
        type(checker), intent(inout) :: chk
        type(limit_cycle) :: sys
        type(radau_options) :: opts
        real(wp) :: u(2), tols(7), errs(7), slope
        integer :: k, stat
        type(radau_stats) :: st
        do k = 1, size(tols)
            tols(k) = 10.0_wp**(-3 - k)
            opts%rtol = tols(k)
            opts%atol = tols(k)
            call run(sys, 0.0_wp, [0.5_wp, 0.0_wp], 10.0_wp, opts, u, stat, st)
            call chk%equal(stat, regdae_success, 'limit cycle run')
            errs(k) = maxval(abs(u - limit_cycle_exact(10.0_wp, 0.5_wp)))
            write (*, '(a,es8.1,a,es10.3,a,i0)') '    rtol = ', tols(k), ': error ', errs(k), ', steps ', st%accepted
        end do
        slope = loglog_slope(tols, errs)
        write (*, '(a,f6.3)') '    slope of log error against log rtol: ', slope
        call chk%true(slope >= 0.8_wp, 'tolerance proportionality (slope >= 0.8)')
    end subroutine tolerance_proportionality

    !> A general constant diagonal M: 2 u' = 2 F(u) gives u' = F(u)'s solution (to
    !! rounding: the same steps, E_1 and E_2 scaled by 2); difference quotients
    !! instead of Prothero-Robinson's analytic Jacobian: the same accuracy (the
    !! quotient of a linear F is exact to about sqrt(u) relative, Newton's rate ~1e-8).
    subroutine mass_and_jacobian(chk)
        type(checker), intent(inout) :: chk
        type(limit_cycle) :: plain
        type(doubled_limit_cycle) :: doubled
        type(prothero_robinson) :: pr
        type(pr_quotients) :: prq
        type(radau_options) :: opts
        real(wp) :: u1(2), u2(2), v1(1), v2(1)
        integer :: stat
        type(radau_stats) :: s1, s2
        opts%rtol = 1.0e-8_wp
        opts%atol = 1.0e-8_wp
        call run(plain, 0.0_wp, [0.5_wp, 0.0_wp], 3.0_wp, opts, u1, stat, s1)
        call chk%equal(stat, regdae_success, 'M = I run')
        opts%mass = [2.0_wp, 2.0_wp]
        call run(doubled, 0.0_wp, [0.5_wp, 0.0_wp], 3.0_wp, opts, u2, stat, s2)
        call chk%equal(stat, regdae_success, 'M = 2 I run')
        call chk%true(maxval(abs(u1 - u2)) <= 1.0e-12_wp, 'M = 2 I: the solution of M = I')
        call chk%equal(s2%accepted, s1%accepted, 'M = 2 I: the steps of M = I')
        deallocate (opts%mass)
        opts%rtol = 1.0e-6_wp
        opts%atol = 1.0e-6_wp
        call run(pr, 0.0_wp, [0.0_wp], 2.0_wp, opts, v1, stat, s1)
        call chk%equal(stat, regdae_success, 'analytic Jacobian run')
        call run(prq, 0.0_wp, [0.0_wp], 2.0_wp, opts, v2, stat, s2)
        call chk%equal(stat, regdae_success, 'difference quotients run')
        write (*, '(a,2es10.3,a,i0,a,i0,a,i0)') '    errors analytic / quotients ', abs(v1 - sin(2.0_wp)), &
            abs(v2 - sin(2.0_wp)), ', steps ', s1%accepted, ' / ', s2%accepted, ', F with quotients ', s2%rhs_evals
        call chk%true(abs(v2(1) - sin(2.0_wp)) <= 10*opts%rtol, 'difference quotients: accuracy')
        call chk%true(s2%rhs_evals > s1%rhs_evals, 'difference quotients: their evaluations counted')
    end subroutine mass_and_jacobian

    !> The continuous extension inside each step against the exact solution: its
    !! error O(h^4) (the collocation polynomial, stage order 3) stays within 10 rtol
    !! at rtol = 1e-8; advance(land) ends exactly at tout.
    subroutine dense_output(chk)
        type(checker), intent(inout) :: chk
        type(limit_cycle) :: sys
        type(radau_options) :: opts
        type(radau_integrator) :: integ
        real(wp) :: u(2), t, err
        integer :: stat, i
        opts%rtol = 1.0e-8_wp
        opts%atol = 1.0e-8_wp
        call integ%start(sys, 0.0_wp, [0.5_wp, 0.0_wp], opts, stat)
        err = 0
        do i = 1, 100
            t = 0.037_wp*i
            call integ%advance(sys, t, u, stat)
            call chk%equal(stat, regdae_success, 'dense output run')
            err = max(err, maxval(abs(u - limit_cycle_exact(t, 0.5_wp))))
        end do
        write (*, '(a,es10.3)') '    continuous extension: largest error ', err
        call chk%true(err <= 10*opts%rtol, 'continuous extension within 10 rtol')
        call integ%advance(sys, 4.0_wp, u, stat, land=.true.)
        call chk%true(integ%time() == 4.0_wp, 'advance(land) ends at tout')
        call chk%true(maxval(abs(u - limit_cycle_exact(4.0_wp, 0.5_wp))) <= 10*opts%rtol, 'u(tout) after landing')
        call integ%solution_at(100.0_wp, u, stat)
        call chk%equal(stat, regdae_err_bad_input, 'solution_at outside the last step')
    end subroutine dense_output

    !> Van der Pol with mu = 1e6 from (2, -0.6) on [0, 2] at rtol = atol = 1e-4: the
    !! counts printed (a published run of a RADAU5 implementation, Assimulo's example
    !! radau5ode_vanderpol: 241 steps, 2233 F, 160 Jacobians, 251 LU, 7 rejected);
    !! asserted only: success, y1 on the slow branch (1 < y1 < 2), and at most 4x those steps.
    subroutine van_der_pol_counts(chk)
        type(checker), intent(inout) :: chk
        type(van_der_pol) :: sys
        type(radau_options) :: opts
        real(wp) :: u(2)
        integer :: stat, k
        type(radau_stats) :: st
        opts%rtol = 1.0e-4_wp
        opts%atol = 1.0e-4_wp
        do k = 1, 2
            opts%radau5_tolerances = k == 2
            call run(sys, 0.0_wp, [2.0_wp, -0.6_wp], 2.0_wp, opts, u, stat, st)
            call chk%equal(stat, regdae_success, 'Van der Pol run')
            write (*, '(a,l1,a,i0,a,i0,a,i0,a,i0,a,i0,a,i0,a,i0)') '    Van der Pol mu = 1e6, radau5_tolerances ', &
                k == 2, ': steps ', st%steps, ', accepted ', st%accepted, ', rejected ', st%rejected, &
                ', F ', st%rhs_evals, ', Jacobians ', st%jacobians, ', LU ', st%lu_decompositions, &
                ', Newton failures ', st%newton_failures
            write (*, '(a,2es16.8)') '    y(2) = ', u
            call chk%true(u(1) > 1 .and. u(1) < 2, 'y1(2) on the slow branch')
            call chk%true(st%accepted <= 4*241, 'at most 4x the published step count')
        end do
    end subroutine van_der_pol_counts

    !> A recoverable failure of F halves the step and the run succeeds; an
    !! unrecoverable one stops the integration with F's status.
    subroutine rhs_failures(chk)
        type(checker), intent(inout) :: chk
        type(failing_decay) :: sys
        type(radau_options) :: opts
        type(radau_integrator) :: integ
        real(wp) :: u(1)
        integer :: stat
        type(radau_stats) :: st
        opts%rtol = 1.0e-8_wp
        opts%atol = 1.0e-8_wp
        sys%n_recoverable = 3
        call run(sys, 0.0_wp, [1.0_wp], 1.0_wp, opts, u, stat, st)
        call chk%equal(stat, regdae_success, 'recoverable failures: success')
        call chk%true(st%newton_failures >= 1, 'recoverable failures counted as Newton failures')
        call chk%close(u(1), exp(-1.0_wp), 1.0e-7_wp, 'recoverable failures: accuracy')
        sys = failing_decay(fatal=.true.)
        call integ%start(sys, 0.0_wp, [1.0_wp], opts, stat)
        call integ%advance(sys, 1.0_wp, u, stat)
        call chk%equal(stat, regdae_err_user_callback, 'unrecoverable failure: its status')
        call chk%true(integ%time() <= 0.5_wp, 'unrecoverable failure: stopped before t_fail')
        call chk%true(len(integ%message()) > 0, 'unrecoverable failure: a message')
        write (*, '(a)') '    message: '//integ%message()
        call integ%step(sys, stat)
        call chk%equal(stat, regdae_err_user_callback, 'the failure persists until a new start')
    end subroutine rhs_failures

    !> Bad input: a status and a message, never a crash.
    subroutine bad_input(chk)
        type(checker), intent(inout) :: chk
        type(limit_cycle) :: sys
        type(radau_options) :: opts
        type(radau_integrator) :: integ
        real(wp) :: u(2), nan
        integer :: stat
        call integ%step(sys, stat)
        call chk%equal(stat, regdae_err_not_initialized, 'step before start')
        nan = 0
        nan = nan/nan
        call expect_bad(opts, [nan, 0.0_wp], 'NaN in u0')
        opts%rtol = -1.0e-6_wp
        call expect_bad(opts, [0.5_wp, 0.0_wp], 'rtol < 0')
        opts = radau_options()
        opts%atol_vector = [1.0e-6_wp, 1.0e-6_wp, 1.0e-6_wp]
        call expect_bad(opts, [0.5_wp, 0.0_wp], 'atol_vector of the wrong size')
        opts = radau_options()
        opts%mass = [1.0_wp]
        call expect_bad(opts, [0.5_wp, 0.0_wp], 'mass of the wrong size')
        opts = radau_options()
        opts%dae_index = [1, 4]
        call expect_bad(opts, [0.5_wp, 0.0_wp], 'index 4')
        opts = radau_options()
        opts%error_test = [.false., .false.]
        call expect_bad(opts, [0.5_wp, 0.0_wp], 'no component in the error test')
        opts = radau_options()
        opts%fixed_step = .true.
        call expect_bad(opts, [0.5_wp, 0.0_wp], 'fixed step without h0')
        opts = radau_options()
        opts%max_newton = 0
        call expect_bad(opts, [0.5_wp, 0.0_wp], 'max_newton = 0')
        opts = radau_options()
        call integ%start(sys, 0.0_wp, [0.5_wp, 0.0_wp], opts, stat)
        call integ%advance(sys, -1.0_wp, u, stat)
        call chk%equal(stat, regdae_err_bad_input, 'tout behind t0')
        opts%max_steps = 3
        call integ%start(sys, 0.0_wp, [0.5_wp, 0.0_wp], opts, stat)
        call integ%advance(sys, 100.0_wp, u, stat)
        call chk%equal(stat, regdae_err_integration, 'max_steps reached')
        write (*, '(a)') '    message: '//integ%message()
    contains
        subroutine expect_bad(o, u0, what)
            type(radau_options), intent(in) :: o
            real(wp), intent(in) :: u0(:)
            character(len=*), intent(in) :: what
            type(radau_integrator) :: fresh
            integer :: st
            call fresh%start(sys, 0.0_wp, u0, o, st)
            call chk%equal(st, regdae_err_bad_input, what)
            call chk%true(len(fresh%message()) > 0, what//': a message')
        end subroutine expect_bad
    end subroutine bad_input


end module test_radau
