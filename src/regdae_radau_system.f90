!> The problem, the options and the statistics of the Radau IIA integrator
!! (regdae_radau_iia): a system \(M u' = F(t, u)\) with a constant diagonal M
!! (1 on differential rows, 0 on algebraic ones: ODEs and semi-explicit DAEs as
!! Hairer & Wanner's RADAU5 runs them, Solving ODEs II, sections IV.8 and VI.1).
module regdae_radau_system
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
    use regdae_kinds, only: wp
    use regdae_status, only: regdae_success, regdae_err_bad_input
    use regdae_format, only: format_real, format_int
    implicit none
    private

    public :: radau_system, radau_rhs, radau_options, radau_stats, validate_options, difference_jacobian

    !> A problem \(M u' = F(t, u)\). Extend it with the problem's parameters and
    !! supply `rhs`; supply `jacobian` and let `has_jacobian` return .true. for an
    !! analytic \(\partial F/\partial u\) (else: forward difference quotients).
    type, abstract :: radau_system
    contains
        !> F(t, u).
        procedure(radau_rhs), deferred :: rhs
        !> Whether `jacobian` is supplied (default .false.).
        procedure :: has_jacobian => system_has_no_jacobian
        !> dF/du at (t, u), f = F(t, u) given (default: none, sets stat < 0).
        procedure :: jacobian => system_no_jacobian
        !> Whether the parameters of F that its owner may set between steps changed since
        !! the last call, which records them (default: F has none, .false.).
        procedure :: note_parameters => system_no_parameters
    end type radau_system

    abstract interface
        !> The right-hand side F(t, u). On failure set stat to a nonzero regdae
        !! status and recoverable = .true. if a smaller step may avoid it (the
        !! integrator halves the step), .false. to stop the integration at once.
        subroutine radau_rhs(self, t, u, f, stat, recoverable)
            import :: radau_system, wp
            class(radau_system), intent(inout) :: self
            real(wp), intent(in) :: t          !! time
            real(wp), intent(in) :: u(:)       !! state, size n
            real(wp), intent(out) :: f(:)      !! F(t, u), size n
            integer, intent(out) :: stat       !! regdae_success or a failure code
            logical, intent(out) :: recoverable
        end subroutine radau_rhs
    end interface

    !> Options of the Radau IIA integrator, with their defaults.
    type :: radau_options
        real(wp) :: rtol = 1.0e-6_wp          !! relative tolerance (> 0)
        real(wp) :: atol = 1.0e-6_wp          !! absolute tolerance (>= 0), unless atol_vector is given
        real(wp), allocatable :: atol_vector(:)   !! per-component absolute tolerances (size n)
        real(wp), allocatable :: rtol_vector(:)   !! per-component relative tolerances (size n)
        real(wp) :: h0 = 0                    !! first step; 0: chosen from ||u0|| and ||F(t0, u0)||
        real(wp) :: h_max = 0                 !! largest step; 0: unbounded
        integer :: max_steps = 100000         !! steps (accepted or not) per start
        integer :: max_newton = 7             !! Newton iterations per step
        logical :: fixed_step = .false.       !! steps of h0 without error control (order measurements)
        !> Tolerances as Hairer & Wanner's RADAU5 takes them (its user documentation):
        !! the local error is kept below rtol' = 0.1 rtol^(2/3) (atol' = atol rtol'/rtol),
        !! which brings the global error near rtol; .false.: rtol and atol bound the local error.
        logical :: radau5_tolerances = .false.
        real(wp), allocatable :: mass(:)      !! diagonal of M (size n); default: identity (an ODE)
        integer, allocatable :: dae_index(:)  !! index 1, 2 or 3 per component: error scaled by h^(index-1)
        logical, allocatable :: error_test(:) !! .false. takes a component out of the error test
    end type radau_options

    !> Counters of one integration.
    type :: radau_stats
        integer :: steps = 0              !! steps attempted
        integer :: accepted = 0           !! steps accepted
        integer :: rejected = 0           !! steps rejected by the error test
        integer :: rhs_evals = 0          !! evaluations of F (those of the difference quotients included)
        integer :: jacobians = 0          !! Jacobians computed
        integer :: lu_decompositions = 0  !! factorizations of the pair (E_1, E_2)
        integer :: newton_iterations = 0  !! Newton iterations
        integer :: newton_failures = 0    !! steps whose Newton iteration failed
    end type radau_stats

contains

    !> The options and the initial values u0 (at t0) checked; msg = '' when they are
    !! valid, else what is wrong (the integrator's start refuses them).
    subroutine validate_options(opts, t0, u0, msg)
        type(radau_options), intent(in) :: opts
        real(wp), intent(in) :: t0, u0(:)
        character(len=:), allocatable, intent(out) :: msg
        integer :: n
        n = size(u0)
        msg = ''
        if (n < 1) then
            msg = 'radau: the state is empty'
        else if (.not. ieee_is_finite(t0) .or. .not. all(ieee_is_finite(u0))) then
            msg = 'radau: t0 or u0 is not finite'
        else if (.not. (opts%rtol > 0) .or. .not. ieee_is_finite(opts%rtol)) then
            msg = 'radau: rtol must be positive and finite (got '//format_real(opts%rtol)//')'
        else if (.not. (opts%atol >= 0) .or. .not. ieee_is_finite(opts%atol)) then
            msg = 'radau: atol must be >= 0 and finite (got '//format_real(opts%atol)//')'
        else if (.not. vector_ok(opts%rtol_vector, n, .true.)) then
            msg = 'radau: rtol_vector needs size(u0) positive finite entries'
        else if (.not. vector_ok(opts%atol_vector, n, .false.)) then
            msg = 'radau: atol_vector needs size(u0) finite entries >= 0'
        else if (.not. (opts%h0 >= 0) .or. .not. ieee_is_finite(opts%h0)) then
            msg = 'radau: h0 must be >= 0 and finite'
        else if (.not. (opts%h_max >= 0) .or. .not. ieee_is_finite(opts%h_max)) then
            msg = 'radau: h_max must be >= 0 and finite'
        else if (opts%max_steps < 1 .or. opts%max_newton < 1) then
            msg = 'radau: max_steps and max_newton must be >= 1'
        else if (opts%fixed_step .and. .not. (opts%h0 > 0)) then
            msg = 'radau: fixed_step needs h0 > 0'
        else if (allocated(opts%mass)) then
            if (size(opts%mass) /= n) then
                msg = 'radau: mass has size '//format_int(size(opts%mass))//', the state '//format_int(n)
            else if (.not. all(ieee_is_finite(opts%mass))) then
                msg = 'radau: mass is not finite'
            end if
        end if
        if (len(msg) > 0) return
        if (allocated(opts%dae_index)) then
            if (size(opts%dae_index) /= n) then
                msg = 'radau: dae_index needs size(u0) entries'
            else if (any(opts%dae_index < 1 .or. opts%dae_index > 3)) then
                msg = 'radau: dae_index entries must be 1, 2 or 3'
            end if
        end if
        if (allocated(opts%error_test)) then
            if (size(opts%error_test) /= n) then
                msg = 'radau: error_test needs size(u0) entries'
            else if (.not. any(opts%error_test)) then
                msg = 'radau: error_test excludes every component'
            end if
        end if
    end subroutine validate_options

    ! Is v absent, or of size n, finite and positive (positive) or >= 0?
    logical function vector_ok(v, n, positive)
        real(wp), allocatable, intent(in) :: v(:)
        integer, intent(in) :: n
        logical, intent(in) :: positive
        vector_ok = .true.
        if (.not. allocated(v)) return
        vector_ok = size(v) == n
        if (.not. vector_ok) return
        vector_ok = all(ieee_is_finite(v))
        if (positive) then
            vector_ok = vector_ok .and. all(v > 0)
        else
            vector_ok = vector_ok .and. all(v >= 0)
        end if
    end function vector_ok

    !> dF/du at (t, u) by forward difference quotients, f = F(t, u) given: column j
    !! from F(t, u + delta_j e_j), delta_j = sqrt(eps max(1e-5, |u_j|)) (RADAU5's
    !! increment) rounded to what u_j + delta_j represents. The Radau integrator's
    !! Jacobian where the system supplies none, and the one integrator=auto's start
    !! test takes (regdae_switching_policy), which it then hands to Radau. stat:
    !! regdae_success, or the status of the evaluation that failed (the loop stops
    !! there); a NaN or Inf in F is left in dfdu for the caller to check. evals: the
    !! evaluations of F made.
    subroutine difference_jacobian(sys, t, u, f, dfdu, stat, recoverable, evals)
        class(radau_system), intent(inout) :: sys
        real(wp), intent(in) :: t          !! time
        real(wp), intent(in) :: u(:)       !! state, size n
        real(wp), intent(in) :: f(:)       !! F(t, u)
        real(wp), intent(out) :: dfdu(:, :) !! dF/du, n x n
        integer, intent(out) :: stat
        logical, intent(out) :: recoverable
        integer, intent(out) :: evals
        real(wp) :: work(size(u)), uj, delta
        integer :: j
        stat = regdae_success
        recoverable = .false.
        evals = 0
        work = u
        do j = 1, size(u)
            uj = u(j)
            delta = sqrt(epsilon(1.0_wp)*max(1.0e-5_wp, abs(uj)))
            work(j) = uj + delta
            delta = work(j) - uj
            evals = evals + 1
            recoverable = .false.
            call sys%rhs(t, work, dfdu(:, j), stat, recoverable)
            if (stat /= regdae_success) exit
            dfdu(:, j) = (dfdu(:, j) - f)/delta
            work(j) = uj
        end do
    end subroutine difference_jacobian

    logical function system_has_no_jacobian(self)
        class(radau_system), intent(in) :: self
        system_has_no_jacobian = .false.
    end function system_has_no_jacobian

    !> The default `note_parameters`: F has no parameters set between steps. A system
    !! whose F has some (regdae's eps and weights, which the monitor sets) says whether
    !! they changed; its owner asks before each step and calls the integrator's
    !! `refresh` when they did, since the integrator keeps F(t, u) of the current point.
    subroutine system_no_parameters(self, changed)
        class(radau_system), intent(inout) :: self
        logical, intent(out) :: changed
        changed = .false.
    end subroutine system_no_parameters

    !> The default `jacobian`: none (the integrator uses difference quotients
    !! unless `has_jacobian` says otherwise).
    subroutine system_no_jacobian(self, t, u, f, dfdu, stat, recoverable)
        class(radau_system), intent(inout) :: self
        real(wp), intent(in) :: t          !! time
        real(wp), intent(in) :: u(:)       !! state
        real(wp), intent(in) :: f(:)       !! F(t, u)
        real(wp), intent(out) :: dfdu(:, :) !! dF/du, n x n
        integer, intent(out) :: stat       !! regdae_success or a failure code
        logical, intent(out) :: recoverable
        dfdu = 0
        stat = regdae_err_bad_input
        recoverable = .false.
    end subroutine system_no_jacobian

end module regdae_radau_system
