!> The integrator interface: what the solver front (`regdae_solver_front`) and
!! the switching policy (`regdae_integrator_switching`) ask of an integrator of
!! the regularized system, in the manner of SUNDIALS ARKODE's core and its
!! steppers. The front's `advance` is written once over this interface: it asks
!! the integrator in charge to advance to the output time and acts on the
!! outcome (at tout, the end of a singular pass, a hand-over to the other
!! integrator, a monitor alarm, a failure); it never names an integrator.
!!
!! An integrator extends `integrator` in a file of its own and keeps what it
!! needs of the problem's state (the model, the options, the monitor) through a
!! pointer to the solver's core record (`regdae_solver_core`), which holds two
!! slots: `nonstiff` (the explicit Dormand-Prince, `regdae_dopri5_integrator`)
!! and `stiff` (SUNDIALS IDA on the eliminated, multiplier or augmented
!! formulation, `regdae_ida_integrator`, or Radau IIA on the eliminated or the
!! augmented one, `regdae_radau_integrator`). A new integrator is one new module: its type,
!! extending this one, allocated in a slot by the front's init (and by the
!! switching policy for `auto`).
!!
!! The procedures (doc/methods.md, "The integrator interface"):
!!  - `start(t, z, stat, msg [, h0, zp, y])`: start, or start again, from a
!!    consistent state z at t (the state of the eliminated formulation; the
!!    slope zp and multiplier y where the caller has them, else computed);
!!  - `advance(tout, t_stop, outcome, stat, msg [, one_step])`: step towards tout,
!!    sampling the monitor at every accepted step, until one of the `outcome_*`
!!    codes; with one_step (where `steps_singly()`), return after one accepted
!!    step with outcome_reached at t_stop = min(the step's end, tout);
!!  - `steps_singly()`: does advance honour one_step (default: no);
!!  - `state()`, `slope()`: the integrator's unknowns and their derivatives at the
!!    time reached (or interpolated), as a pointer into its own storage;
!!  - `interpolate(t, stat)`: the continuous extension at a t inside the last
!!    step, into `state()` (and `slope()` where the method has one);
!!  - `time()`, `last_step()`: the end of the last step and its size;
!!  - `statistics(st, active)`: the integrator's counters added to st;
!!  - `stiffness(t)`: an estimate of the spectral radius of the Jacobian of the
!!    regularized system at the state at t (0: none);
!!  - `ready()`: does the integrator hold a started state; `free()`: release it;
!!  - `augmented()`: the augmented system it integrates, if it does (null otherwise);
!!  - `state_written()`: the caller wrote into `state()` (IDA then interpolates again
!!    at a time it last interpolated at; by default nothing to do).
module regdae_integrator
    use, intrinsic :: iso_c_binding, only: c_double
    use, intrinsic :: iso_fortran_env, only: int64
    use regdae_kinds, only: wp
    use regdae_solver_stats, only: solver_stats
    use regdae_augmented_system, only: augmented_system
    implicit none
    private

    !> The outcome of `advance`.
    integer, parameter, public :: outcome_reached = 0   !! at tout (its state, interpolated where needed)
    integer, parameter, public :: outcome_pass_end = 1  !! stopped at the end of a singular pass, at t_stop < tout
    integer, parameter, public :: outcome_stiff = 2     !! the system is stiff at t_stop: hand over to the stiff integrator
    integer, parameter, public :: outcome_nonstiff = 3  !! the explicit method would do at t_stop: hand back to it
    integer, parameter, public :: outcome_alarm = 4     !! the monitor's alarm at t_stop (the state there)
    integer, parameter, public :: outcome_failed = 5    !! failed at t_stop (stat, msg); the state there; no multiplier
    integer, parameter, public :: outcome_exhausted = 6 !! the step budget (max_steps) spent at t_stop (stat, msg)
    integer, parameter, public :: outcome_broken = 7    !! failed without a state to return (stat, msg)

    !> An integrator of the regularized system (see the module documentation).
    type, abstract, public :: integrator
    contains
        !> Start (again) from the consistent state z at t.
        procedure(integrator_start), deferred :: start
        !> Step towards tout until an outcome (`outcome_*`).
        procedure(integrator_advance), deferred :: advance
        !> The unknowns at the time reached (a pointer into the integrator's storage).
        procedure(integrator_vector), deferred :: state
        !> Their derivatives there.
        procedure(integrator_vector), deferred :: slope
        !> The continuous extension at t inside the last step, into state() (and slope()).
        procedure(integrator_interpolate), deferred :: interpolate
        !> The end of the last step.
        procedure(integrator_real), deferred :: time
        !> The size of the last step.
        procedure(integrator_real), deferred :: last_step
        !> The counters added to st (h_last set when `active`).
        procedure(integrator_statistics), deferred :: statistics
        !> An estimate of the spectral radius of the Jacobian at the state at t (0: none).
        procedure(integrator_stiffness), deferred :: stiffness
        !> Does the integrator hold a started state?
        procedure(integrator_ready), deferred :: ready
        !> Release what the integrator holds (it can be started again).
        procedure(integrator_free), deferred :: free
        !> The augmented system integrated, if it is (null otherwise).
        procedure :: augmented => no_augmented_system
        !> Does advance honour its one_step argument (return after each step)?
        procedure :: steps_singly => no_single_steps
        !> The caller wrote into state(): an integrator that keeps its last interpolation
        !! (to skip interpolating at the same time again) forgets it (default: nothing to do).
        procedure :: state_written => nothing_kept
        !> The steps taken (statistics' count; an integrator that keeps it at hand returns it cheaper).
        procedure :: steps_taken => counted_steps
    end type integrator

    abstract interface
        subroutine integrator_start(self, t, z, stat, msg, h0, zp, y)
            import :: integrator, wp
            class(integrator), intent(inout), target :: self
            real(wp), intent(in) :: t, z(:)
            integer, intent(out) :: stat
            character(len=:), allocatable, intent(out) :: msg
            real(wp), intent(in), optional :: h0      !! a first step (explicit methods; 0: chosen)
            real(wp), intent(in), optional :: zp(:)   !! z'(t), consistent with z
            real(wp), intent(in), optional :: y(:)    !! the multiplier at t
        end subroutine integrator_start

        subroutine integrator_advance(self, tout, t_stop, outcome, stat, msg, one_step)
            import :: integrator, wp
            class(integrator), intent(inout), target :: self
            real(wp), intent(in) :: tout
            real(wp), intent(out) :: t_stop
            integer, intent(out) :: outcome, stat
            character(len=:), allocatable, intent(out) :: msg
            logical, intent(in), optional :: one_step   !! return after one accepted step (where steps_singly())
        end subroutine integrator_advance

        function integrator_vector(self) result(u)
            import :: integrator, c_double
            class(integrator), intent(in), target :: self
            real(c_double), pointer :: u(:)
        end function integrator_vector

        subroutine integrator_interpolate(self, t, stat)
            import :: integrator, wp
            class(integrator), intent(inout), target :: self
            real(wp), intent(in) :: t
            integer, intent(out) :: stat
        end subroutine integrator_interpolate

        real(wp) function integrator_real(self)
            import :: integrator, wp
            class(integrator), intent(in) :: self
        end function integrator_real

        subroutine integrator_statistics(self, st, active)
            import :: integrator, solver_stats
            class(integrator), intent(in) :: self
            type(solver_stats), intent(inout) :: st
            logical, intent(in) :: active
        end subroutine integrator_statistics

        real(wp) function integrator_stiffness(self, t)
            import :: integrator, wp
            class(integrator), intent(inout), target :: self
            real(wp), intent(in) :: t
        end function integrator_stiffness

        logical function integrator_ready(self)
            import :: integrator
            class(integrator), intent(in) :: self
        end function integrator_ready

        subroutine integrator_free(self)
            import :: integrator
            class(integrator), intent(inout) :: self
        end subroutine integrator_free
    end interface

contains

    function no_augmented_system(self) result(sys)
        class(integrator), intent(in), target :: self
        type(augmented_system), pointer :: sys
        sys => null()
    end function no_augmented_system

    logical function no_single_steps(self)
        class(integrator), intent(in) :: self
        no_single_steps = .false.
    end function no_single_steps

    subroutine nothing_kept(self)
        class(integrator), intent(inout) :: self
    end subroutine nothing_kept

    integer(int64) function counted_steps(self) result(n)
        class(integrator), intent(in) :: self
        type(solver_stats) :: st
        call self%statistics(st, .false.)
        n = st%steps
    end function counted_steps

end module regdae_integrator
