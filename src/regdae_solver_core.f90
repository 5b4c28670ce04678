!> The state of one problem of the solver front (`regdae_solver_front`): the
!! model, the integrators, the options in force, the counters of integrator=auto
!! and the diagnostics, in one record that the front, the monitor's sampling
!! (`regdae_solver_sampling`), the integrators (extensions of `regdae_integrator`)
!! and the switching policy (`regdae_integrator_switching`) share; with its
!! allocation (`new_core`), the integrator in charge (`active_integrator`) and
!! the events log (`log_event`). Split from regdae_solver_front so that those
!! modules can work on the state without depending on the front.
module regdae_solver_core
    use regdae_kinds, only: wp
    use regdae_options, only: solver_options, formulation_eliminated, integrator_ida, integrator_dopri5, &
                              linear_solver_dense
    use regdae_regularization, only: regularized_dae
    use regdae_integrator, only: integrator
    use regdae_monitor, only: solution_monitor
    use regdae_taylor_layer, only: taylor_layer_watch
    implicit none
    private

    public :: new_core, log_event, active_integrator

    !> The state of one problem: the model, the backend, the options and the
    !! diagnostics; allocated once per init, so that the backend (IDA's user_data)
    !! and the model it evaluates stay at fixed addresses.
    type, public :: solver_core
        type(regularized_dae), pointer :: model => null()   !! the model the backends evaluate (new_core)
        class(integrator), allocatable :: nonstiff   !! the explicit integrator (integrator=dopri5, auto)
        class(integrator), allocatable :: stiff      !! the implicit integrator (integrator=ida or radau, auto after a switch)
        type(solver_options) :: opts      !! the options in force, auto values resolved
        integer :: n = 0, m = 0, neq = 0   !! n: size of the state z; neq: IDA unknowns
        integer :: nx = 0                  !! size of x reported to the user
        logical :: second_order = .false.  !! the user's problem is of order 2: z = (x, v)
        real(wp) :: multiplier_sign = 1.0_wp   !! -1: report lambda = -y (mechanical problems)
        real(wp) :: t = 0.0_wp            !! the time reached
        logical :: started = .false.       !! the integration has gone beyond t0
        real(wp) :: sampled_t = -huge(1.0_wp)   !! IDA: the last time the monitor sampled
        type(taylor_layer_watch) :: layer  !! order >= 3: the growth in the Taylor weights' layer (implicit steps)
        logical :: augmented = .false.     !! formulation=augmented: the state lives in IDA's vector, y too
        integer :: formulation = formulation_eliminated   !! resolved
        integer :: active = integrator_ida     !! the integrator now in charge: dopri5 (the nonstiff
                                               !! slot) or ida or radau (the stiff slot)
        logical :: switching = .false.         !! integrator=auto: switch between dopri5 and IDA
        integer :: switches = 0                !! switches so far
        integer :: explicit_votes = 0          !! consecutive checks that found the explicit method would do
        real(wp), allocatable :: rho_w(:)      !! power iteration's vector (the stiffness estimate)
        character(len=:), allocatable :: events   !! the log of switches
        integer :: n_events = 0                !! entries in the log
        integer :: back_switches = 0           !! ida -> dopri5 switches so far
        real(wp) :: eps_factor = 0.0_wp       !! > 0: eps automatic (regdae_scales)
        real(wp) :: drift_factor = 0.0_wp     !! > 0: drift bound automatic
        real(wp) :: work_floor = 0.0_wp       !! the work-energy check's smallest energy scale
        real(wp) :: rate0 = 0.0_wp            !! the rate of the motion at t0 (regdae_auto_rules)
        real(wp) :: ell0 = 0.0_wp             !! the constraint length at t0
        real(wp) :: sigma_pred0 = -1.0_wp     !! a singular start: the predicted regular sigma_min(GB)
        real(wp) :: eps_auto0 = 0.0_wp        !! the automatic eps at t0 (also when the user set eps)
        logical :: follow_weights = .false.   !! the automatic weights follow the motion along the run
        logical :: rest_start = .false.       !! the start is at rest in an equilibrium (rest_in_equilibrium):
                                              !! dopri5 keeps every step within the constraint modes' stable step
        logical :: stop_at_pass_end = .false. !! advance returns early at the end of a singular pass
        logical :: auto_gamma = .false., auto_gamma0 = .false., auto_gamma1 = .false.   !! which were auto
        real(wp) :: t0 = 0.0_wp               !! integrator=auto: the start, kept until the first output
        real(wp), allocatable :: z0(:)        !! the state at t0 (integrator=auto: kept until the first output)
        integer :: linear_solver = linear_solver_dense    !! resolved
        logical, allocatable :: excluded(:)   !! unknowns left out of the error test
        real(wp), allocatable :: y_work(:)    !! the multiplier at an output time
        real(wp), allocatable :: zp_work(:)   !! the slope z' at an output time (the acceleration on request)
        real(wp), allocatable :: atol_z(:)    !! the absolute tolerance of each component of the state z
        type(solution_monitor) :: monitor     !! diagnostics, sampled at the output times (IDA) or the accepted steps (dopri5)
    end type solver_core

contains

    !> The integrator in charge: the nonstiff slot while dopri5 is active, else the stiff one.
    function active_integrator(core) result(p)
        type(solver_core), intent(in), target :: core
        class(integrator), pointer :: p
        if (core%active == integrator_dopri5) then
            p => core%nonstiff
        else
            p => core%stiff
        end if
    end function active_integrator

    !> A new core with its model (both at fixed addresses until destroy).
    subroutine new_core(core)
        type(solver_core), pointer, intent(out) :: core
        allocate (core)
        allocate (core%model)
    end subroutine new_core

    !> Append a line to the events log; after max_events lines only the count grows.
    subroutine log_event(core, text)
        type(solver_core), intent(inout) :: core
        character(len=*), intent(in) :: text
        integer, parameter :: max_events = 50
        core%n_events = core%n_events + 1
        if (core%n_events <= max_events) then
            core%events = core%events//text//new_line('a')
        else if (core%n_events == max_events + 1) then
            core%events = core%events//'(later switches are counted in the statistics only)'//new_line('a')
        end if
    end subroutine log_event

end module regdae_solver_core
