!> The three-stage Radau IIA method of order 5 with step-size control, for
!! \(M u' = F(t, u)\) with a constant diagonal M (ODEs and semi-explicit DAEs).
!!
!! Written for regdae from the method's published description: E. Hairer and
!! G. Wanner, Solving Ordinary Differential Equations II, 2nd ed., Springer 1996,
!! section IV.8 ("Implementation of implicit Runge-Kutta methods"), and VI.1 for
!! the DAE form. Not derived from anyone's code. In short (doc/methods.md, "Radau IIA"):
!!
!! - Stages \(Y_i = u_0 + z_i\), \(M Z = h (A \otimes I) F(Z)\); the result is the last
!!   stage, \(u_1 = u_0 + z_3\).
!! - Simplified Newton on \(W = (T^{-1} \otimes I) Z\): one real (\(\gamma/h\, M - J\)) and one
!!   complex (\((\alpha + i\beta)/h\, M - J\)) n x n LU per new Jacobian or step size
!!   (regdae_radau_linear); starting values from the last step's collocation polynomial;
!!   convergence rate \(\theta_k = \|\Delta W_k\|/\|\Delta W_{k-1}\|\), stop when
!!   \(\eta_k \|\Delta W_k\| \le \kappa\), \(\eta_k = \theta_k/(1 - \theta_k)\), \(\eta_0 = \max(\eta_{old}, u)^{0.8}\);
!!   give up when \(\theta_k \ge 0.99\) or \(\theta_k^{k_{max}-k}/(1-\theta_k)\|\Delta W_k\| > \kappa\).
!!   With algebraic rows the weights are at least the rounding floor of the increments over
!!   \(\kappa\) (regdae_radau_linear's rounding_floor, after each LU).
!! - Error: \(err = (\gamma/h\, M - J)^{-1}(F(t_0, u_0) + M \sum_j e_j z_j / h)\); at the first
!!   step and after a rejection, when err >= 1, once more with \(F(t_0, u_0 + err)\).
!! - Step: \(h_{new} = h / q\), \(q = err^{1/4}/fac\) clamped to [1/8, 5], fac = 0.9 (2 kmax + 1)/(2 kmax + newt),
!!   and Gustafsson's predictive \(q_G = (h_{old}/h)(err^2/err_{old})^{1/4}/fac\): \(q = \max(q, q_G)\).
!!   The Jacobian is kept while \(\theta \le 0.001\) (0.03 with algebraic rows, whose rate is O(h) even
!!   with a fresh J); so is h (and the LU) while \(1 \le h_{new}/h \le 1.2\).
!!
!! The integrator integrates forward in time (t increasing).
module regdae_radau_iia
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
    use regdae_kinds, only: wp
    use regdae_status, only: regdae_success, regdae_err_bad_input, regdae_err_integration, &
                             regdae_err_not_initialized, regdae_err_nonfinite, regdae_err_singular
    use regdae_format, only: format_real, format_int, text_length
    use regdae_radau_tableau, only: radau_coefficients, radau_iia_coefficients
    use regdae_radau_linear, only: radau_newton_matrices
    use regdae_radau_system, only: radau_system, radau_options, radau_stats, validate_options, difference_jacobian
    implicit none
    private

    public :: radau_integrator

    real(wp), parameter :: safety = 0.9_wp          ! safety factor of the step-size formula
    real(wp), parameter :: quot_min = 1.0_wp/8      ! h_new <= 8 h
    real(wp), parameter :: quot_max = 5.0_wp        ! h_new >= h/5
    real(wp), parameter :: theta_jacobian = 1.0e-3_wp  ! keep J while the Newton rate stays below
    ! the same with algebraic rows (M_ii = 0): there the rate with a fresh J is O(h), not
    ! O(h^2) (J_aa's change over the step is not damped by h/gamma; measured 4.5 h on the
    ! 4-link chain), and 1e-3 would take a new J at every step (doc/methods.md, "Radau IIA")
    real(wp), parameter :: theta_jacobian_dae = 0.03_wp
    real(wp), parameter :: keep_low = 1.0_wp, keep_high = 1.2_wp  ! keep h (and the LU) for h_new/h in here
    real(wp), parameter :: theta_diverge = 0.99_wp  ! Newton diverges
    real(wp), parameter :: first_reject_factor = 0.1_wp   ! the first step rejected: h/10
    real(wp), parameter :: newton_fail_factor = 0.5_wp    ! Newton failed: h/2
    real(wp), parameter :: err_old_min = 1.0e-2_wp  ! lower bound of the error kept for Gustafsson's formula

    !> The integrator. All state is private; see the module description.
    type :: radau_integrator
        private
        type(radau_coefficients) :: rc
        type(radau_newton_matrices) :: lin
        type(radau_stats) :: counts
        integer :: n = 0
        integer :: stat = regdae_err_not_initialized
        character(len=:), allocatable :: msg
        real(wp), allocatable :: rtol(:), atol(:), mass(:)
        integer, allocatable :: dae_index(:)
        logical, allocatable :: in_test(:)
        real(wp) :: h_max = 0, kappa = 0.03_wp, h_fixed = 0
        integer :: max_steps = 0, max_newton = 0, n_test = 0
        logical :: fixed = .false.
        ! the current point
        real(wp) :: t = 0, h = 0
        real(wp), allocatable :: u(:), f0(:), jac(:, :), sc(:)
        ! with algebraic rows: the rounding floor of the Newton increments (rounding_floor)
        logical :: algebraic = .false.
        real(wp), allocatable :: floor(:)
        ! the last accepted step: u(t_prev + s h_last) = u_prev + sum_k q(:, k) s^k
        logical :: have_step = .false.
        real(wp) :: t_prev = 0, h_last = 0
        real(wp), allocatable :: u_prev(:), q(:, :)
        ! Newton and error work
        real(wp), allocatable :: z(:, :), w(:, :), fz(:, :), dw(:, :), err_v(:), work(:)
        ! controller state
        logical :: jac_current = .false., need_jac = .true., lu_valid = .false.
        logical :: first = .true., after_reject = .false.
        real(wp) :: h_lu = 0, theta = 1, eta = 1, err_old = 1, h_acc_old = 0
        real(wp) :: theta_keep = theta_jacobian   ! theta_jacobian, or theta_jacobian_dae with algebraic rows
    contains
        !> Start at (t0, u0) with the given options.
        procedure :: start => radau_start
        !> One accepted step (never past t_stop when given).
        procedure :: step => radau_step
        !> F changed at the current point (its parameters were changed between steps):
        !! F(t, u) evaluated again and a new Jacobian at the next step.
        procedure :: refresh => radau_refresh
        !> Steps until tout is reached or passed; u(tout) from the continuous extension.
        procedure :: advance => radau_advance
        !> u(t) for t in the last step, from its collocation polynomial.
        procedure :: solution_at => radau_solution_at
        !> u'(t) for t in the last step: the collocation polynomial's derivative.
        procedure :: slope_at => radau_slope_at
        !> The size of the last accepted step (0 before the first).
        procedure :: last_step => radau_last_step
        !> The current time.
        procedure :: time => radau_time
        !> The step size the next step will try.
        procedure :: step_size => radau_step_size
        !> The current state u(t).
        procedure :: state => radau_state
        !> The slope u'(t) (the collocation polynomial's derivative at the end of the last step).
        procedure :: slope => radau_slope
        !> The counters.
        procedure :: statistics => radau_statistics
        !> The status of the last call (regdae_status).
        procedure :: status => radau_status
        !> What went wrong ('' after success).
        procedure :: message => radau_message
        !> Take a Jacobian at the current point made by difference_jacobian (see radau_take_jacobian).
        procedure :: take_jacobian => radau_take_jacobian
        procedure, private :: fail, eval, compute_jacobian, jacobian_taken, newton, error_estimate, weights, accept, &
                              step_fraction
    end type radau_integrator

contains

    !> Start at (t0, u0). stat: regdae_success, regdae_err_bad_input (with a
    !! message), or the status of a failing F(t0, u0).
    subroutine radau_start(self, sys, t0, u0, opts, stat)
        class(radau_integrator), intent(inout) :: self
        class(radau_system), intent(inout) :: sys
        real(wp), intent(in) :: t0              !! initial time
        real(wp), intent(in) :: u0(:)           !! initial state (consistent for a DAE)
        type(radau_options), intent(in) :: opts
        integer, intent(out) :: stat
        integer :: n
        logical :: recoverable
        real(wp) :: d0, d1

        n = size(u0)
        self%n = n
        self%counts = radau_stats()
        self%have_step = .false.
        call validate_options(opts, t0, u0, self%msg)
        if (len(self%msg) > 0) then
            self%stat = regdae_err_bad_input
            stat = self%stat
            return
        end if
        self%rc = radau_iia_coefficients()
        call self%lin%init(n)
        self%rtol = spread(opts%rtol, 1, n)
        if (allocated(opts%rtol_vector)) self%rtol = opts%rtol_vector
        self%atol = spread(opts%atol, 1, n)
        if (allocated(opts%atol_vector)) self%atol = opts%atol_vector
        if (opts%radau5_tolerances) then
            self%atol = self%atol*(0.1_wp*self%rtol**(2.0_wp/3))/self%rtol
            self%rtol = 0.1_wp*self%rtol**(2.0_wp/3)
        end if
        self%mass = spread(1.0_wp, 1, n)
        if (allocated(opts%mass)) self%mass = opts%mass
        self%algebraic = any(self%mass == 0)
        self%theta_keep = merge(theta_jacobian_dae, theta_jacobian, self%algebraic)
        self%dae_index = spread(1, 1, n)
        if (allocated(opts%dae_index)) self%dae_index = opts%dae_index
        self%in_test = spread(.true., 1, n)
        if (allocated(opts%error_test)) self%in_test = opts%error_test
        self%n_test = count(self%in_test)
        self%h_max = opts%h_max
        self%max_steps = opts%max_steps
        self%max_newton = opts%max_newton
        self%fixed = opts%fixed_step
        ! Newton's tolerance: kappa = 0.03, at most sqrt(rtol), at least 10 u / rtol (reachable in rounding)
        self%kappa = max(10*epsilon(1.0_wp)/minval(self%rtol), min(0.03_wp, sqrt(minval(self%rtol))))
        self%t = t0
        self%u = u0
        if (allocated(self%f0)) deallocate (self%f0, self%jac, self%sc, self%u_prev, self%q, self%z, self%w, &
                                            self%fz, self%dw, self%err_v, self%work, self%floor)
        allocate (self%f0(n), self%jac(n, n), self%sc(n), self%u_prev(n), self%q(n, 3), self%z(n, 3), &
                  self%w(n, 3), self%fz(n, 3), self%dw(n, 3), self%err_v(n), self%work(n), self%floor(n))
        self%floor = 0
        self%q = 0
        self%z = 0
        self%jac_current = .false.
        self%need_jac = .true.
        self%lu_valid = .false.
        self%first = .true.
        self%after_reject = .false.
        self%theta = 1
        self%eta = 1
        self%err_old = 1
        self%h_acc_old = 0
        self%stat = regdae_success
        self%msg = ''
        call self%eval(sys, t0, self%u, self%f0, stat, recoverable)
        if (stat /= regdae_success) then
            call self%fail(stat, 'F(t0, u0) failed')
            return
        end if
        if (opts%h0 > 0) then
            self%h = opts%h0
        else   ! 1 % of the state's scale over the slope's, in the weighted norm
            call self%weights(1.0_wp)
            d0 = sqrt(sum((self%u/self%sc)**2)/n)
            d1 = sqrt(sum((merge(self%f0/self%mass, 0.0_wp, self%mass /= 0)/self%sc)**2)/n)
            self%h = 1.0e-6_wp
            if (d0 > 1.0e-5_wp .and. d1 > 1.0e-5_wp) self%h = 0.01_wp*d0/d1
        end if
        if (self%h_max > 0) self%h = min(self%h, self%h_max)
        self%h_fixed = self%h
        self%t_prev = t0
        self%h_last = 0
        self%u_prev = u0
    end subroutine radau_start

    !> One accepted step from t, ending at t_stop at the latest (it lands there
    !! exactly when the step would pass it). stat: regdae_success, or a failure
    !! whose message says what failed (the integrator must then be started again).
    subroutine radau_step(self, sys, stat, t_stop)
        class(radau_integrator), intent(inout) :: self
        class(radau_system), intent(inout) :: sys
        integer, intent(out) :: stat
        real(wp), intent(in), optional :: t_stop   !! do not step past this time
        real(wp) :: h, err, fac, quot, h_new
        integer :: newt
        logical :: converged, recoverable, landed

        stat = self%stat
        if (stat /= regdae_success) return
        if (present(t_stop)) then
            if (.not. (t_stop > self%t)) then
                call self%fail(regdae_err_bad_input, 'radau: t_stop '//format_real(t_stop)//' is not ahead of t')
                stat = self%stat
                return
            end if
        end if
        do
            if (self%counts%steps >= self%max_steps) then
                call self%fail(regdae_err_integration, 'radau: too many steps (max_steps = '// &
                               format_int(self%max_steps)//')')
                exit
            end if
            h = self%h
            if (self%fixed) h = self%h_fixed
            if (self%h_max > 0) h = min(h, self%h_max)
            landed = .false.
            if (present(t_stop)) then
                if (self%t + 1.0001_wp*h >= t_stop) then
                    h = t_stop - self%t
                    landed = .true.
                end if
            end if
            if (.not. (h > 10*epsilon(1.0_wp)*abs(self%t)) .or. h <= tiny(1.0_wp)) then
                call self%fail(regdae_err_integration, 'radau: step size too small (h = '//format_real(h)//')')
                exit
            end if
            if (h /= self%h_lu) self%lu_valid = .false.
            if (self%need_jac) then
                call self%compute_jacobian(sys, stat)
                if (stat /= regdae_success) exit
            end if
            if (.not. self%lu_valid) then
                call self%lin%factor(self%jac, self%mass, self%rc%gamma/h, self%rc%alpha/h, self%rc%beta/h, stat)
                self%counts%lu_decompositions = self%counts%lu_decompositions + 1
                if (stat == regdae_err_singular .and. .not. self%fixed) then
                    self%h = newton_fail_factor*h   ! a singular Newton matrix: try a smaller step
                    self%counts%steps = self%counts%steps + 1
                    cycle
                else if (stat /= regdae_success) then
                    call self%fail(stat, 'radau: the Newton matrix is singular')
                    exit
                end if
                self%lu_valid = .true.
                self%h_lu = h
                if (self%algebraic) call self%lin%rounding_floor(self%jac, self%mass, self%u, self%f0, self%floor)
            end if
            self%counts%steps = self%counts%steps + 1
            call self%newton(sys, h, converged, newt, stat, recoverable)
            if (stat /= regdae_success .and. .not. recoverable) then
                call self%fail(stat, 'radau: F failed in the Newton iteration')
                exit
            end if
            if (.not. converged) then
                self%counts%newton_failures = self%counts%newton_failures + 1
                if (.not. self%jac_current .and. stat == regdae_success) then
                    self%need_jac = .true.      ! first a fresh Jacobian at the same step
                    self%h = h
                else if (self%fixed) then
                    call self%fail(regdae_err_integration, 'radau: the Newton iteration failed at a fixed step')
                    exit
                else
                    self%h = newton_fail_factor*h
                    self%after_reject = .true.
                end if
                cycle
            end if
            err = 0
            if (.not. self%fixed) then
                call self%error_estimate(sys, h, err, stat, recoverable)
                if (stat /= regdae_success) then
                    if (.not. recoverable) then
                        call self%fail(stat, 'radau: F failed in the error estimate')
                        exit
                    end if
                    err = 1/quot_min**4   ! treated as a large error: h / 5 below
                end if
            end if
            fac = min(safety, safety*(2*self%max_newton + 1)/real(2*self%max_newton + newt, wp))
            quot = max(quot_min, min(quot_max, err**0.25_wp/fac))
            if (err < 1) then
                if (.not. self%first) then   ! Gustafsson's predictive controller
                    quot = max(quot, max(quot_min, min(quot_max, &
                               (self%h_acc_old/h)*(err**2/self%err_old)**0.25_wp/fac)))
                end if
                h_new = h/quot
                self%h_acc_old = h
                self%err_old = max(err_old_min, err)
                call self%accept(sys, h, h_new, landed, t_stop, stat)
                exit
            end if
            self%counts%rejected = self%counts%rejected + 1
            if (self%first) then
                self%h = first_reject_factor*h
            else
                self%h = h/quot
            end if
            self%after_reject = .true.
            self%need_jac = .not. self%jac_current
        end do
        stat = self%stat
    end subroutine radau_step

    !> The system's F changed between steps (its parameters were set anew, as the
    !! monitor sets regdae's eps and weights): F(t, u) evaluated again, and the next
    !! step takes a new Jacobian. Without it the step's start keeps the old F(t0, u0):
    !! the error estimate uses it, and the Jacobian's difference quotients take it as
    !! their base, (F_new(u + d e_j) - F_old(u))/d, off by (F_new - F_old)/d (on an
    !! algebraic row measured: entries -1 computed as -324 ... 1777, and Newton
    !! diverging at every h, issue 21).
    !! stat: regdae_success, or F's failure (the integrator then fails).
    subroutine radau_refresh(self, sys, stat)
        class(radau_integrator), intent(inout) :: self
        class(radau_system), intent(inout) :: sys
        integer, intent(out) :: stat
        logical :: recoverable
        stat = self%stat
        if (stat /= regdae_success) return
        call self%eval(sys, self%t, self%u, self%f0, stat, recoverable)
        if (stat /= regdae_success) then
            call self%fail(stat, 'radau: F failed after the system changed')
            return
        end if
        self%need_jac = .true.
    end subroutine radau_refresh

    !> Take the step of size h (Z converged, error accepted) and choose the next.
    subroutine accept(self, sys, h, h_new, landed, t_stop, stat)
        class(radau_integrator), intent(inout) :: self
        class(radau_system), intent(inout) :: sys
        real(wp), intent(in) :: h, h_new
        logical, intent(in) :: landed
        real(wp), intent(in), optional :: t_stop
        integer, intent(out) :: stat
        real(wp) :: hn, ratio
        logical :: recoverable

        self%t_prev = self%t
        self%h_last = h
        self%u_prev(:) = self%u
        call transform(self%rc%p, self%z, self%q)
        self%u(:) = self%u + self%z(:, 3)
        self%t = self%t + h
        if (landed) self%t = t_stop
        self%have_step = .true.
        self%counts%accepted = self%counts%accepted + 1
        self%jac_current = .false.
        call self%eval(sys, self%t, self%u, self%f0, stat, recoverable)
        if (stat /= regdae_success) then
            call self%fail(stat, 'radau: F failed at the end of an accepted step')
            return
        end if
        hn = h_new
        if (self%after_reject) hn = min(hn, h)   ! no increase right after a rejection
        ratio = hn/h
        if (self%fixed) then
            self%need_jac = self%theta > self%theta_keep
        else if (self%theta <= self%theta_keep .and. ratio >= keep_low .and. ratio <= keep_high) then
            self%h = h                          ! same h, same Jacobian, same LU
            self%need_jac = .false.
        else
            self%h = hn
            self%need_jac = self%theta > self%theta_keep
        end if
        self%first = .false.
        self%after_reject = .false.
    end subroutine accept

    !> The simplified Newton iteration for the stages of a step of size h.
    !! converged = .false. with stat = regdae_success when it diverges or is too
    !! slow; with stat /= 0 when F failed (recoverable tells whether h/2 may help).
    subroutine newton(self, sys, h, converged, newt, stat, recoverable)
        class(radau_integrator), intent(inout) :: self
        class(radau_system), intent(inout) :: sys
        real(wp), intent(in) :: h
        logical, intent(out) :: converged
        integer, intent(out) :: newt
        integer, intent(out) :: stat
        logical, intent(out) :: recoverable
        real(wp) :: s, eta, dn, dn_old, theta, theta_max, fg, fa, fb
        integer :: i, k, n

        n = self%n
        converged = .false.
        recoverable = .true.
        stat = regdae_success
        call self%weights(h)
        if (self%have_step) then   ! the last step's collocation polynomial, extrapolated
            do i = 1, 3
                s = 1 + self%rc%c(i)*h/self%h_last
                self%z(:, i) = self%u_prev - self%u + s*(self%q(:, 1) + s*(self%q(:, 2) + s*self%q(:, 3)))
            end do
        else
            self%z(:, :) = 0
        end if
        call transform(self%rc%t_inv, self%z, self%w)
        fg = self%rc%gamma/h
        fa = self%rc%alpha/h
        fb = self%rc%beta/h
        eta = max(self%eta, epsilon(1.0_wp))**0.8_wp
        theta = 0
        theta_max = 0
        dn_old = 1
        newt = 0
        do while (newt < self%max_newton)
            do i = 1, 3
                self%work(:) = self%u + self%z(:, i)
                call self%eval(sys, self%t + self%rc%c(i)*h, self%work, self%fz(:, i), stat, recoverable)
                if (stat /= regdae_success) return
            end do
            newt = newt + 1
            self%counts%newton_iterations = self%counts%newton_iterations + 1
            call transform(self%rc%t_inv, self%fz, self%dw)
            self%dw(:, 1) = self%dw(:, 1) - fg*self%mass*self%w(:, 1)
            self%dw(:, 2) = self%dw(:, 2) - self%mass*(fa*self%w(:, 2) - fb*self%w(:, 3))
            self%dw(:, 3) = self%dw(:, 3) - self%mass*(fb*self%w(:, 2) + fa*self%w(:, 3))
            call self%lin%solve_real(self%dw(:, 1))
            call self%lin%solve_complex(self%dw(:, 2), self%dw(:, 3))
            dn = 0
            do k = 1, 3
                dn = dn + sum((self%dw(:, k)/self%sc)**2)
            end do
            dn = sqrt(dn/(3*n))
            if (.not. ieee_is_finite(dn)) return
            if (newt > 1) then
                theta = dn/dn_old
                theta_max = max(theta_max, theta)
                if (theta >= theta_diverge) return
                eta = theta/(1 - theta)
                if (theta**(self%max_newton - newt)/(1 - theta)*dn > self%kappa) return
            end if
            dn_old = dn
            self%w(:, :) = self%w + self%dw
            call transform(self%rc%t, self%w, self%z)
            if (eta*dn <= self%kappa) then
                converged = .true.
                exit
            end if
        end do
        if (converged) then
            self%eta = eta
            self%theta = theta
            ! With algebraic rows the last ratio is no rate when the last increment fell to
            ! the rounding level (1e-8 after 0.1, 0.016 on radau/dae_index1_exact): carried
            ! into the next step's eta_0 it ends an iteration after one increment of 25
            ! weights, and as theta it keeps J. The slowest ratio of the iteration instead.
            if (self%algebraic .and. newt > 1) then
                self%theta = theta_max
                self%eta = theta_max/(1 - theta_max)
            end if
        end if
    end subroutine newton

    !> y(:, k) = sum_j m(k, j) x(:, j): the 3 x 3 matrix m applied to the stage index.
    pure subroutine transform(m, x, y)
        real(wp), intent(in) :: m(3, 3), x(:, :)
        real(wp), intent(out) :: y(:, :)
        integer :: k
        do k = 1, 3
            y(:, k) = m(k, 1)*x(:, 1) + m(k, 2)*x(:, 2) + m(k, 3)*x(:, 3)
        end do
    end subroutine transform

    !> The scaled norm of the embedded error estimate, refined once at the first
    !! step and after a rejection when it is >= 1.
    subroutine error_estimate(self, sys, h, err, stat, recoverable)
        class(radau_integrator), intent(inout) :: self
        class(radau_system), intent(inout) :: sys
        real(wp), intent(in) :: h
        real(wp), intent(out) :: err
        integer, intent(out) :: stat
        logical, intent(out) :: recoverable
        real(wp) :: e(3)
        e = self%rc%e/h
        ! fz(:, 2) holds M sum_j e_j z_j / h while the estimate is refined
        self%fz(:, 2) = self%mass*(e(1)*self%z(:, 1) + e(2)*self%z(:, 2) + e(3)*self%z(:, 3))
        self%err_v(:) = self%f0 + self%fz(:, 2)
        call self%lin%solve_real(self%err_v)
        self%sc(:) = (self%atol + self%rtol*max(abs(self%u), abs(self%u + self%z(:, 3))))/h**(self%dae_index - 1)
        err = error_norm(self%err_v, self%sc, self%in_test, self%n_test)
        stat = regdae_success
        recoverable = .true.
        if (err >= 1 .and. (self%first .or. self%after_reject)) then
            self%work(:) = self%u + self%err_v
            call self%eval(sys, self%t, self%work, self%fz(:, 1), stat, recoverable)
            if (stat /= regdae_success) return
            self%err_v(:) = self%fz(:, 1) + self%fz(:, 2)
            call self%lin%solve_real(self%err_v)
            err = error_norm(self%err_v, self%sc, self%in_test, self%n_test)
        end if
        if (.not. ieee_is_finite(err)) err = 1/quot_min**4
        err = max(err, 1.0e-10_wp)
    end subroutine error_estimate

    pure real(wp) function error_norm(v, sc, in_test, n_test)
        real(wp), intent(in) :: v(:), sc(:)
        logical, intent(in) :: in_test(:)
        integer, intent(in) :: n_test
        error_norm = sqrt(sum((v/sc)**2, mask=in_test)/n_test)
    end function error_norm

    !> The weights of the Newton norm at the current point: (atol + rtol |u|) / h^(index-1),
    !! and with algebraic rows at least floor / kappa, so that the iteration's target
    !! (kappa times the weight) is not below the rounding floor of its increments.
    subroutine weights(self, h)
        class(radau_integrator), intent(inout) :: self
        real(wp), intent(in) :: h
        self%sc(:) = (self%atol + self%rtol*abs(self%u))/h**(self%dae_index - 1)
        if (self%algebraic) self%sc(:) = max(self%sc, self%floor/self%kappa)
    end subroutine weights

    !> dF/du at the current point: the system's, or forward difference quotients.
    subroutine compute_jacobian(self, sys, stat)
        class(radau_integrator), intent(inout) :: self
        class(radau_system), intent(inout) :: sys
        integer, intent(out) :: stat
        logical :: recoverable
        integer :: evals
        self%counts%jacobians = self%counts%jacobians + 1
        if (sys%has_jacobian()) then
            call sys%jacobian(self%t, self%u, self%f0, self%jac, stat, recoverable)
        else
            call difference_jacobian(sys, self%t, self%u, self%f0, self%jac, stat, recoverable, evals)
            self%counts%rhs_evals = self%counts%rhs_evals + evals
        end if
        if (stat == regdae_success .and. .not. all(ieee_is_finite(self%jac))) stat = regdae_err_nonfinite
        if (stat /= regdae_success) then
            call self%fail(stat, 'radau: the Jacobian failed')
            return
        end if
        call self%jacobian_taken()
    end subroutine compute_jacobian

    !> Take jac as dF/du at the current point (t, u), made by difference_jacobian with
    !! F(t, u) as this integrator evaluated it (at the start, or at the last accepted step's
    !! end) for a system without `jacobian`: the next step factors it rather than computing
    !! it again. Counted as a Jacobian and its n evaluations of F.
    subroutine radau_take_jacobian(self, jac)
        class(radau_integrator), intent(inout) :: self
        real(wp), intent(in) :: jac(:, :)   !! n x n
        self%counts%jacobians = self%counts%jacobians + 1
        self%counts%rhs_evals = self%counts%rhs_evals + self%n
        self%jac(:, :) = jac
        call self%jacobian_taken()
    end subroutine radau_take_jacobian

    ! A Jacobian at the current point in jac: kept while Newton converges fast, factored anew.
    subroutine jacobian_taken(self)
        class(radau_integrator), intent(inout) :: self
        self%jac_current = .true.
        self%need_jac = .false.
        self%lu_valid = .false.
    end subroutine jacobian_taken

    !> F(t, u), counted; a NaN or Inf in it is a recoverable failure.
    subroutine eval(self, sys, t, u, f, stat, recoverable)
        class(radau_integrator), intent(inout) :: self
        class(radau_system), intent(inout) :: sys
        real(wp), intent(in) :: t, u(:)
        real(wp), intent(out) :: f(:)
        integer, intent(out) :: stat
        logical, intent(out) :: recoverable
        self%counts%rhs_evals = self%counts%rhs_evals + 1
        recoverable = .false.
        call sys%rhs(t, u, f, stat, recoverable)
        if (stat == regdae_success .and. .not. all_finite(f)) then
            stat = regdae_err_nonfinite
            recoverable = .true.
        end if
    end subroutine eval

    ! No entry of f is NaN or Inf: one loop with a sum that stays 0 exactly while they
    ! are finite (0 * NaN and 0 * Inf are NaN), cheaper per evaluation than
    ! all(ieee_is_finite(f)).
    pure logical function all_finite(f)
        real(wp), intent(in) :: f(:)
        real(wp) :: probe
        integer :: i
        probe = 0
        do i = 1, size(f)
            probe = probe + 0*f(i)
        end do
        all_finite = (probe == 0)
    end function all_finite

    !> Record a failure (code and message with the time).
    subroutine fail(self, code, text)
        class(radau_integrator), intent(inout) :: self
        integer, intent(in) :: code
        character(len=*), intent(in) :: text
        self%stat = code
        self%msg = text//' at t = '//format_real(self%t)
    end subroutine fail

    !> Steps until tout is reached or passed, then u(tout) from the continuous
    !! extension (or exactly, landing on tout, with land = .true.).
    subroutine radau_advance(self, sys, tout, u_out, stat, land, t_stop)
        class(radau_integrator), intent(inout) :: self
        class(radau_system), intent(inout) :: sys
        real(wp), intent(in) :: tout             !! output time (not behind the last step)
        real(wp), intent(out) :: u_out(:)         !! u(tout)
        integer, intent(out) :: stat
        logical, intent(in), optional :: land     !! end the last step at tout exactly
        real(wp), intent(in), optional :: t_stop  !! never step past this time (>= tout)
        real(wp) :: stop_at
        logical :: have_stop

        stat = self%stat
        if (stat /= regdae_success) return
        have_stop = present(t_stop)
        if (have_stop) stop_at = t_stop
        if (present(land)) then
            if (land) then
                have_stop = .true.
                stop_at = tout
            end if
        end if
        if (.not. ieee_is_finite(tout) .or. tout < self%t_prev .or. size(u_out) /= self%n) then
            call self%fail(regdae_err_bad_input, 'radau: tout '//format_real(tout)// &
                           ' is behind the last step, or u_out has the wrong size')
            stat = self%stat
            return
        end if
        if (have_stop) then
            if (stop_at < tout) then
                call self%fail(regdae_err_bad_input, 'radau: t_stop is before tout')
                stat = self%stat
                return
            end if
        end if
        do while (self%t < tout)
            if (have_stop) then
                call self%step(sys, stat, stop_at)
            else
                call self%step(sys, stat)
            end if
            if (stat /= regdae_success) return
        end do
        call self%solution_at(tout, u_out, stat)
    end subroutine radau_advance

    !> u(t) for t in [t_prev, t] of the last step (u0 itself before the first).
    subroutine radau_solution_at(self, t, u_out, stat)
        class(radau_integrator), intent(in) :: self
        real(wp), intent(in) :: t          !! a time in the last step
        real(wp), intent(out) :: u_out(:)  !! u(t)
        integer, intent(out) :: stat       !! regdae_success or regdae_err_bad_input
        real(wp) :: s
        if (.not. self%step_fraction(t, size(u_out), s, stat)) return
        if (t == self%t) then
            u_out = self%u
        else
            u_out = self%u_prev + s*(self%q(:, 1) + s*(self%q(:, 2) + s*self%q(:, 3)))
        end if
    end subroutine radau_solution_at

    !> u'(t) for t in [t_prev, t] of the last step (F/m at the start before the first step).
    subroutine radau_slope_at(self, t, up, stat)
        class(radau_integrator), intent(in) :: self
        real(wp), intent(in) :: t          !! a time in the last step
        real(wp), intent(out) :: up(:)     !! u'(t)
        integer, intent(out) :: stat       !! regdae_success or regdae_err_bad_input
        real(wp) :: s
        if (.not. self%step_fraction(t, size(up), s, stat)) return
        if (self%have_step) then
            up = (self%q(:, 1) + s*(2*self%q(:, 2) + 3*s*self%q(:, 3)))/self%h_last
        else
            call self%slope(up)
        end if
    end subroutine radau_slope_at

    !> Is t in the last step (or t itself before the first) and m the state's size?
    !! s: (t - t_prev)/h_last; stat: regdae_success, regdae_err_not_initialized or
    !! regdae_err_bad_input.
    logical function step_fraction(self, t, m, s, stat) result(ok)
        class(radau_integrator), intent(in) :: self
        real(wp), intent(in) :: t
        integer, intent(in) :: m
        real(wp), intent(out) :: s
        integer, intent(out) :: stat
        real(wp) :: slack
        ok = .false.
        s = 1
        stat = regdae_err_not_initialized
        if (self%n == 0) return
        stat = regdae_err_bad_input
        if (m /= self%n) return
        if (self%have_step) then
            slack = 100*epsilon(1.0_wp)*max(abs(self%t), abs(self%h_last))
            if (.not. (t >= self%t_prev - slack .and. t <= self%t + slack)) return
            s = (t - self%t_prev)/self%h_last
        else if (t /= self%t) then
            return
        end if
        stat = regdae_success
        ok = .true.
    end function step_fraction

    real(wp) function radau_last_step(self)
        class(radau_integrator), intent(in) :: self
        radau_last_step = self%h_last
    end function radau_last_step

    real(wp) function radau_time(self)
        class(radau_integrator), intent(in) :: self
        radau_time = self%t
    end function radau_time

    real(wp) function radau_step_size(self)
        class(radau_integrator), intent(in) :: self
        radau_step_size = self%h
    end function radau_step_size

    subroutine radau_state(self, u)
        class(radau_integrator), intent(in) :: self
        real(wp), intent(out) :: u(:)   !! u(t), size n
        u = self%u
    end subroutine radau_state

    !> u'(t): before the first step F/m on the differential rows (0 on the
    !! algebraic ones), after it the derivative of the last step's collocation polynomial.
    subroutine radau_slope(self, up)
        class(radau_integrator), intent(in) :: self
        real(wp), intent(out) :: up(:)   !! u'(t), size n
        if (self%have_step) then
            up = (self%q(:, 1) + 2*self%q(:, 2) + 3*self%q(:, 3))/self%h_last
        else
            up = merge(self%f0/self%mass, 0.0_wp, self%mass /= 0)
        end if
    end subroutine radau_slope

    type(radau_stats) function radau_statistics(self)
        class(radau_integrator), intent(in) :: self
        radau_statistics = self%counts
    end function radau_statistics

    integer function radau_status(self)
        class(radau_integrator), intent(in) :: self
        radau_status = self%stat
    end function radau_status

    function radau_message(self) result(msg)
        class(radau_integrator), intent(in) :: self
        character(len=text_length(self%msg)) :: msg
        if (allocated(self%msg)) msg = self%msg
    end function radau_message

end module regdae_radau_iia
