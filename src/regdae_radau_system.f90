!> The problem, the options and the statistics of the Radau IIA integrator
!! (regdae_radau_iia): a system \(M u' = F(t, u)\) with a constant diagonal M
!! (1 on differential rows, 0 on algebraic ones: ODEs and semi-explicit DAEs as
!! Hairer & Wanner's RADAU5 runs them, Solving ODEs II, sections IV.8 and VI.1).
module regdae_radau_system
    use regdae_kinds, only: wp
    use regdae_status, only: regdae_err_bad_input
    implicit none
    private

    public :: radau_system, radau_rhs, radau_options, radau_stats

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

    logical function system_has_no_jacobian(self)
        class(radau_system), intent(in) :: self
        system_has_no_jacobian = .false.
    end function system_has_no_jacobian

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
