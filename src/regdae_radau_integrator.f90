!> The Radau IIA integrator of order 5 (`regdae_radau_iia`) behind the integrator
!! interface (`regdae_integrator`): integrator=radau, and the stiff slot of
!! integrator=auto for small systems (`regdae_switching_policy`'s rule). It
!! integrates the eliminated formulation as an ODE z' = F(t, z) (the model's
!! slope_eliminated, as dopri5 does), with dense LU and difference-quotient
!! Jacobians; the error test leaves out what the IDA path leaves out (core%excluded).
!! With formulation=augmented it integrates the augmented system as the index-1
!! DAE of `regdae_radau_augmented` (the accelerations a = v' as algebraic unknowns,
!! mass diag(1 on q and v, 0 elsewhere)), dense LU and grouped difference
!! quotients; the error test leaves out what IDA's does on that system (u, y, s,
!! and v with excluded=vy) and a, which IDA's vector does not hold (a stays in
!! with exclusion=off). Its state() and slope() are then the augmented vector and
!! its derivative in IDA's order (v' = a), and `augmented()` the system.
!! Before each step it compares the system's parameters (eps and the weights, which
!! the monitor sets between steps) with those of the last step and, when they
!! changed, has Radau evaluate F at the step's start again and take a new Jacobian
!! (`refresh`), on either formulation.
!! Its `advance` is `regdae_implicit_steps`'s loop over Radau's single steps, the
!! monitor sampling every accepted step's end and the output time, in time order,
!! like the IDA integrator; with integrator=auto the loop asks the switching
!! policy every 20 steps whether the explicit method would do.
module regdae_radau_integrator
    use, intrinsic :: iso_c_binding, only: c_double
    use regdae_kinds, only: wp
    use regdae_status
    use regdae_format, only: format_real
    use regdae_solver_stats, only: solver_stats
    use regdae_radau_system, only: radau_system, radau_options, radau_stats
    use regdae_radau_iia, only: radau_integrator
    use regdae_radau_augmented, only: augmented_dae
    use regdae_eliminated_ode, only: eliminated_ode
    use regdae_augmented_system, only: augmented_system
    use regdae_solver_core, only: solver_core
    use regdae_switching_policy, only: spectral_radius
    use regdae_implicit_steps, only: implicit_stepper, name_len
    implicit none
    private

    public :: radau_in_slot

    !> Radau IIA on the core's model (see the module documentation).
    type, extends(implicit_stepper), public :: radau_adapter
        type(radau_integrator) :: radau                !! the method's state
        type(eliminated_ode) :: ode                    !! the system it integrates (eliminated formulation)
        type(augmented_dae) :: dae                     !! the system it integrates (augmented formulation)
        logical :: on_augmented = .false.              !! dae, not ode (set by take_augmented)
        real(wp), allocatable :: uu(:), uup(:)         !! dae: the unknowns U = (x, a) and U'
        type(radau_stats) :: before                    !! the counters of the earlier starts
        real(wp), allocatable :: z(:), zp(:)           !! the state and slope at the time reached (or interpolated)
        logical :: started = .false.                   !! radau holds a started state
    contains   ! the interface's procedures (regdae_integrator documents them)
        procedure :: start => radau_start
        procedure :: step_towards => radau_step_towards
        procedure :: to_step_end => radau_to_step_end
        procedure :: name => radau_name
        procedure :: state => radau_state
        procedure :: slope => radau_slope
        procedure :: interpolate => radau_interpolate
        procedure :: time => radau_time
        procedure :: last_step => radau_last_step
        procedure :: statistics => radau_statistics
        procedure :: stiffness => radau_stiffness
        procedure :: ready => radau_ready
        procedure :: free => radau_free
        procedure :: augmented => radau_augmented
        !> Integrate the augmented system sys (set up, parameters resolved) from now on.
        procedure :: take_augmented => radau_take_augmented
        !> Just started on the eliminated formulation: its first Jacobian given (radau_take_jacobian).
        procedure :: take_jacobian => radau_take_jacobian
    end type radau_adapter

contains

    !> The Radau integrator in the core's stiff slot (allocated there if the slot
    !! is empty); null if the slot holds another integrator.
    function radau_in_slot(core) result(p)
        type(solver_core), pointer, intent(in) :: core
        type(radau_adapter), pointer :: p
        p => null()
        if (.not. allocated(core%stiff)) allocate (radau_adapter :: core%stiff)
        select type (s => core%stiff)
        type is (radau_adapter)
            p => s
            p%core => core
        end select
    end function radau_in_slot

    !> Start (again) at (t, z): the core's tolerances (rtol, the state's atol), the
    !! error test without the excluded components, the first step h0 when given (> 0).
    !! On the augmented system z is (q, v) and the algebraic unknowns are computed.
    subroutine radau_start(self, t, z, stat, msg, h0, zp, y)
        class(radau_adapter), intent(inout), target :: self
        real(wp), intent(in) :: t, z(:)
        integer, intent(out) :: stat
        character(len=:), allocatable, intent(out) :: msg
        real(wp), intent(in), optional :: h0, zp(:), y(:)
        type(radau_options) :: ro
        logical :: changed
        associate (core => self%core)
            if (self%started) self%before = add_stats(self%before, self%radau%statistics())
            ro%rtol = core%opts%rtol
            ro%max_steps = huge(1)   ! the budget is counted per advance (max_steps), here
            ro%h_max = core%opts%h_max
            if (present(h0)) ro%h0 = max(0.0_wp, h0)
            if (self%on_augmented) then
                ro%atol_vector = self%dae%tolerances(self%dae%sys%tolerance_vector(core%atol_z(1:core%nx), &
                                                     core%atol_z(core%nx + 1:core%n), core%opts%atol), core%opts%atol)
                ro%error_test = [.not. core%excluded(1:core%neq), spread(.not. any(core%excluded), 1, core%nx)]
                ro%mass = self%dae%mass
                self%dae%failure = ''
                if (.not. allocated(self%uu)) allocate (self%uu(core%neq + core%nx), self%uup(core%neq + core%nx))
                call self%dae%consistent(t, z(1:core%nx), z(core%nx + 1:core%n), self%uu, stat, msg)
                if (stat /= regdae_success) return
                call self%radau%start(self%dae, t, self%uu, ro, stat)
                call self%dae%note_parameters(changed)   ! the parameters F(t0, u0) was taken with
            else
                self%ode%model => core%model
                self%ode%failure = ''
                if (.not. allocated(self%ode%y)) allocate (self%ode%y(core%m))
                self%z = z
                if (.not. allocated(self%zp)) allocate (self%zp(core%n))
                ro%atol_vector = core%atol_z(1:core%n)
                ro%error_test = .not. core%excluded(1:core%n)
                if (.not. any(ro%error_test)) deallocate (ro%error_test)
                call self%radau%start(self%ode, t, z, ro, stat)
                call self%ode%note_parameters(changed)
            end if
            self%started = .true.
            msg = ''
            if (stat /= regdae_success) then
                msg = self%radau%message()
                return
            end if
            call self%to_step_end()
        end associate
    end subroutine radau_start

    !> One Radau step towards tout (landing on it with stop_at_output), the state
    !! and slope at its end.
    subroutine radau_step_towards(self, tout, t_now, stat, msg)
        class(radau_adapter), intent(inout), target :: self
        real(wp), intent(in) :: tout
        real(wp), intent(out) :: t_now
        integer, intent(out) :: stat
        character(len=:), allocatable, intent(inout) :: msg
        character(len=:), allocatable :: failure
        if (self%on_augmented) then
            call step_on(self%dae)
            failure = self%dae%failure
        else
            call step_on(self%ode)
            failure = self%ode%failure
        end if
        t_now = self%radau%time()
        call self%to_step_end()
        if (stat == regdae_success) return
        msg = 'Radau failed at t = '//format_real(t_now)//': '//self%radau%message()
        if (len(failure) > 0) msg = msg//' | last failure of F: '//failure
    contains
        subroutine step_on(sys)
            class(radau_system), intent(inout) :: sys
            logical :: changed
            ! the monitor may have set new eps or weights since the last step: F(t0, u0) anew
            call sys%note_parameters(changed)
            if (changed) then
                call self%radau%refresh(sys, stat)
                if (stat /= regdae_success) return
            end if
            if (self%core%opts%stop_at_output) then
                call self%radau%step(sys, stat, tout)
            else
                call self%radau%step(sys, stat)
            end if
        end subroutine step_on
    end subroutine radau_step_towards

    !> The state and slope at the end of the last step.
    subroutine radau_to_step_end(self)
        class(radau_adapter), intent(inout), target :: self
        if (self%on_augmented) then
            call self%radau%state(self%uu)
            call self%radau%slope(self%uup)
            call self%dae%augmented_pair(self%uu, self%uup, self%z, self%zp)
        else
            call self%radau%state(self%z)
            call self%radau%slope(self%zp)
        end if
    end subroutine radau_to_step_end

    function radau_name(self) result(who)
        class(radau_adapter), intent(in) :: self
        character(len=name_len) :: who
        who = 'Radau'
    end function radau_name

    function radau_state(self) result(u)
        class(radau_adapter), intent(in), target :: self
        real(c_double), pointer :: u(:)
        u => self%z
    end function radau_state

    function radau_slope(self) result(up)
        class(radau_adapter), intent(in), target :: self
        real(c_double), pointer :: up(:)
        up => self%zp
    end function radau_slope

    !> The last step's collocation polynomial at t (state and slope).
    subroutine radau_interpolate(self, t, stat)
        class(radau_adapter), intent(inout), target :: self
        real(wp), intent(in) :: t
        integer, intent(out) :: stat
        if (self%on_augmented) then
            call self%radau%solution_at(t, self%uu, stat)
            if (stat == regdae_success) call self%radau%slope_at(t, self%uup, stat)
            if (stat == regdae_success) call self%dae%augmented_pair(self%uu, self%uup, self%z, self%zp)
            return
        end if
        call self%radau%solution_at(t, self%z, stat)
        if (stat == regdae_success) call self%radau%slope_at(t, self%zp, stat)
    end subroutine radau_interpolate

    real(wp) function radau_time(self)
        class(radau_adapter), intent(in) :: self
        radau_time = self%radau%time()
    end function radau_time

    real(wp) function radau_last_step(self)
        class(radau_adapter), intent(in) :: self
        radau_last_step = self%radau%last_step()
    end function radau_last_step

    !> Radau's counters (over its starts) added to st in IDA's terms: steps
    !! (accepted), res_evals (F, the difference quotients' included), jac_evals,
    !! lin_setups (the pairs of real and complex LU), nonlin_iters, err_test_fails
    !! (rejected steps), conv_fails (Newton failures); its last step when active.
    subroutine radau_statistics(self, st, active)
        class(radau_adapter), intent(in) :: self
        type(solver_stats), intent(inout) :: st
        logical, intent(in) :: active
        type(radau_stats) :: own
        own = self%before
        if (self%started) own = add_stats(own, self%radau%statistics())
        st%steps = st%steps + own%accepted
        st%res_evals = st%res_evals + own%rhs_evals
        if (self%on_augmented) then   ! the grouped Jacobians' evaluations are not Radau's own
            st%res_evals = st%res_evals + self%dae%jacobian_evals
            st%jac_res_evals = st%jac_res_evals + self%dae%jacobian_evals
        else
            st%jac_res_evals = st%jac_res_evals + own%jacobians*self%core%n
        end if
        st%jac_evals = st%jac_evals + own%jacobians
        st%lin_setups = st%lin_setups + own%lu_decompositions
        st%nonlin_iters = st%nonlin_iters + own%newton_iterations
        st%err_test_fails = st%err_test_fails + own%rejected
        st%conv_fails = st%conv_fails + own%newton_failures
        if (active) st%h_last = self%radau%last_step()
    end subroutine radau_statistics

    pure type(radau_stats) function add_stats(a, b) result(c)
        type(radau_stats), intent(in) :: a, b
        c%steps = a%steps + b%steps
        c%accepted = a%accepted + b%accepted
        c%rejected = a%rejected + b%rejected
        c%rhs_evals = a%rhs_evals + b%rhs_evals
        c%jacobians = a%jacobians + b%jacobians
        c%lu_decompositions = a%lu_decompositions + b%lu_decompositions
        c%newton_iterations = a%newton_iterations + b%newton_iterations
        c%newton_failures = a%newton_failures + b%newton_failures
    end function add_stats

    !> The spectral radius of the eliminated formulation's Jacobian at the state
    !! (0 on the augmented system: integrator=auto does not switch there).
    real(wp) function radau_stiffness(self, t) result(rho)
        class(radau_adapter), intent(inout), target :: self
        real(wp), intent(in) :: t
        rho = 0.0_wp
        if (.not. self%on_augmented) rho = spectral_radius(self%core, t, self%z)
    end function radau_stiffness

    logical function radau_ready(self)
        class(radau_adapter), intent(in) :: self
        radau_ready = self%started
    end function radau_ready

    subroutine radau_free(self)
        class(radau_adapter), intent(inout) :: self
        if (self%started) self%before = add_stats(self%before, self%radau%statistics())
        self%started = .false.
    end subroutine radau_free

    function radau_augmented(self) result(sys)
        class(radau_adapter), intent(in), target :: self
        type(augmented_system), pointer :: sys
        sys => null()
        if (self%on_augmented) sys => self%dae%sys
    end function radau_augmented

    !> Just started on the eliminated formulation at (t, z): jac is dF/dz there as
    !! Radau would compute it (`difference_jacobian` on the same eliminated_ode, F at the
    !! same point and parameters), made by integrator=auto's start test; the first step
    !! takes it instead of computing it again.
    subroutine radau_take_jacobian(self, jac)
        class(radau_adapter), intent(inout) :: self
        real(wp), intent(in) :: jac(:, :)   !! n x n
        if (.not. self%on_augmented) call self%radau%take_jacobian(jac)
    end subroutine radau_take_jacobian

    subroutine radau_take_augmented(self, sys)
        class(radau_adapter), intent(inout), target :: self
        type(augmented_system), intent(in) :: sys   !! set up, its eps and weights resolved
        call self%dae%setup(sys)
        self%on_augmented = .true.
        if (.not. allocated(self%z)) allocate (self%z(sys%neq), self%zp(sys%neq))
    end subroutine radau_take_augmented

end module regdae_radau_integrator
