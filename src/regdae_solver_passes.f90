!> What regdae_solver_trust needs of a solver to verify singular passes with
!! companions (`regdae_solver_front`'s engine procedures): the checkpoint before a
!! pass, the state and a restart from it, a companion started on the same
!! problem at tighter tolerances, the distance of two states in error weights,
!! and the events log. They reach the integrator in charge through the
!! integrator interface (`regdae_integrator`).
submodule (regdae_solver_front) regdae_solver_passes
    use regdae_velocity_index2, only: velocity_index2_problem
    use regdae_projection, only: project_first_order, project_second_order
    use regdae_sparse_projection, only: project_structured
    use regdae_auto_rules, only: automatic_eps_factor
    use regdae_work_energy, only: kinetic_energy_and_power
    implicit none

contains

    module procedure engine_stop_at_pass_ends
        if (.not. associated(self%core)) return
        self%core%stop_at_pass_end = on
        self%core%monitor%defer_in_pass = on
    end procedure engine_stop_at_pass_ends

    module procedure engine_take_pass_end
        ended = .false.
        if (.not. associated(self%core)) return
        ended = self%core%monitor%pass_ended
        self%core%monitor%pass_ended = .false.
    end procedure engine_take_pass_end

    module procedure engine_checkpoint
        t = 0.0_wp
        frozen = .false.
        valid = .false.
        if (.not. associated(self%core)) return
        associate (mon => self%core%monitor)
            valid = mon%checkpoint_valid
            frozen = mon%checkpoint_frozen
            if (.not. valid) return
            t = mon%checkpoint_t
            if (present(z)) z = mon%checkpoint_z
        end associate
    end procedure engine_checkpoint

    module procedure engine_release_checkpoint
        if (associated(self%core)) call self%core%monitor%release_checkpoint(t, z)
    end procedure engine_release_checkpoint

    module procedure engine_integrator_time
        class(integrator), pointer :: stepper
        t = self%t
        if (.not. associated(self%core)) return
        t = self%core%t
        stepper => active_integrator(self%core)
        if (.not. associated(stepper)) return
        if (stepper%ready()) t = stepper%time()
    end procedure engine_integrator_time

    module procedure engine_same
        same = .false.
        if (associated(self%core) .and. associated(other%core)) same = associated(self%core, other%core)
    end procedure engine_same

    module procedure engine_x_size
        n = 0
        if (associated(self%core)) n = self%core%nx
    end procedure engine_x_size

    module procedure engine_time
        t = self%t
    end procedure engine_time

    module procedure engine_steps_taken
        n = 0
        if (.not. associated(self%core)) return
        if (allocated(self%core%stiff)) n = n + self%core%stiff%steps_taken()
        if (allocated(self%core%nonstiff)) n = n + self%core%nonstiff%steps_taken()
    end procedure engine_steps_taken

    module procedure engine_state_size
        n = 0
        if (associated(self%core)) n = self%core%n
    end procedure engine_state_size

    module procedure engine_state
        class(integrator), pointer :: stepper
        type(augmented_system), pointer :: sys
        real(c_double), pointer :: u(:)
        integer :: nx
        if (.not. associated(self%core)) return
        nx = self%core%nx
        stepper => active_integrator(self%core)
        u => stepper%state()
        sys => stepper%augmented()
        if (associated(sys)) then
            call sys%unpack(u, u, q=z(1:nx), v=z(nx + 1:2*nx))
        else
            z = u(1:size(z))
        end if
    end procedure engine_state

    module procedure engine_restart_at
        class(integrator), pointer :: stepper
        character(len=:), allocatable :: msg
        stat = regdae_err_not_initialized
        if (.not. associated(self%core)) return
        associate (core => self%core)
            core%t = t
            self%t = t
            core%sampled_t = t
            stepper => active_integrator(core)
            call stepper%start(t, z, stat, msg, h0=stepper%last_step())
            if (stat == regdae_success .and. core%monitor%work_tol > 0.0_wp) call rebase_work(core, stepper, t, z)
        end associate
    end procedure engine_restart_at

    ! The work-energy balance goes on from the state z at t (engine_restart_at).
    subroutine rebase_work(core, stepper, t, z)
        type(solver_core), intent(inout) :: core
        class(integrator), intent(in), target :: stepper
        real(wp), intent(in) :: t, z(:)
        type(augmented_system), pointer :: sys
        real(c_double), pointer :: u(:), up(:)
        real(wp) :: kinetic, power, y(core%m), q(core%nx), v(core%nx)
        integer :: wstat
        logical :: recoverable
        wstat = -1
        sys => stepper%augmented()
        if (associated(sys)) then
            u => stepper%state()
            up => stepper%slope()
            call sys%unpack(u, up, q=q, v=v, y=y)
            call kinetic_energy_and_power(sys%problem, t, q, v, y, kinetic, power, wstat, sys%st%mass)
        else
            call core%model%evaluate(t, z, wstat, recoverable)
            if (wstat == regdae_success) call core%model%work_sample(t, z, kinetic, power, wstat)
        end if
        if (wstat == 0) call core%monitor%rebase_work(t, kinetic, power)
    end subroutine rebase_work

    module procedure engine_start_companion
        type(solver_options) :: opts
        type(augmented_system), pointer :: sys
        real(wp) :: eps, zs(size(z)), ratio
        integer :: nx
        logical :: do_project
        stat = regdae_err_not_initialized
        if (.not. associated(self%core)) return
        associate (core => self%core)
            nx = core%nx
            if (core%augmented) sys => core%stiff%augmented()
            opts = core%opts
            opts%rtol = core%opts%rtol/kappa
            opts%atol = core%opts%atol/kappa
            if (opts%atol_v /= option_auto) opts%atol_v = core%opts%atol_v/kappa
            opts%jump_tol = 0.0_wp
            opts%drift_tol = 0.0_wp
            opts%work_tol = 0.0_wp
            opts%invariant_tol = 0.0_wp
            opts%resolution_tol = 0.0_wp
            opts%ic_tol = huge(1.0_wp)
            opts%check_jacobians = .false.
            opts%h_init = 0.0_wp
            opts%integrator = core%active   ! the integrator in charge (dopri5, ida or radau)
            opts%formulation = core%formulation
            opts%linear_solver = merge(core%linear_solver, linear_solver_auto, core%augmented)
            if (core%augmented) then
                eps = sys%eps
                opts%gamma = sys%gamma1
                opts%gamma1 = sys%gamma1
                opts%gamma0 = sys%gamma0
                if (opts%index == 2) opts%gamma0 = 0.5_wp*sys%gamma1**2
            else
                eps = core%model%eps
                if (core%model%order == 1) opts%gamma = core%model%w(1)
                if (core%model%order == 2) then
                    opts%gamma0 = core%model%w(1)
                    opts%gamma1 = core%model%w(2)
                end if
            end if
            ! an automatic eps shrinks with the tolerance as its rule says (rtol^2 within its
            ! bounds; direct: the square root of that): below the rule's floor thinner layers
            ! are not resolved in double precision, and the companion has the same eps
            opts%eps = eps
            if (core%eps_factor > 0.0_wp) then
                ratio = automatic_eps_factor(opts%rtol)/automatic_eps_factor(core%opts%rtol)
                if (opts%method == method_direct) ratio = sqrt(ratio)
                opts%eps = eps*ratio
            end if
            if (present(eps_scale)) opts%eps = opts%eps*eps_scale
            ! the start projected onto the constraints (engine_project_start), once per pass
            zs = z
            do_project = .true.
            if (present(projected)) do_project = .not. projected
            if (do_project) call self%project_start(t, zs)
            if (core%augmented) then
                call other%init(sys%problem, t, zs(1:nx), zs(nx + 1:2*nx), opts, stat, &
                                atol_vector=core%atol_z/kappa)
            else if (allocated(core%model%second)) then
                call other%init(core%model%second, t, zs(1:nx), zs(nx + 1:2*nx), opts, stat, &
                                atol_vector=core%atol_z/kappa)
            else if (allocated(core%model%higher)) then
                stat = regdae_err_bad_input   ! order >= 3: not verified
            else
                select type (p => core%model%first)
                type is (velocity_index2_problem)
                    call other%init(p%second, t, zs(1:nx), zs(nx + 1:2*nx), opts, stat, atol_vector=core%atol_z/kappa)
                class default
                    call other%init(p, t, zs(1:nx), opts, stat, atol_vector=core%atol_z/kappa)
                end select
            end if
        end associate
    end procedure engine_start_companion

    ! The start projected onto the constraints: the solution's drift is within its tolerance,
    ! not within the companion's (with a thinner layer it can bounce off the branch).
    module procedure engine_project_start
        type(augmented_system), pointer :: sys
        integer :: nx, pstat
        if (.not. associated(self%core)) return
        associate (core => self%core)
            nx = core%nx
            if (core%augmented) then
                sys => core%stiff%augmented()
                if (sys%st%declared) then
                    call project_structured(sys%problem, sys%st%constraint, t, z(1:nx), z(nx + 1:2*nx), pstat)
                else
                    call project_second_order(sys%problem, t, z(1:nx), z(nx + 1:2*nx), pstat)
                end if
            else if (allocated(core%model%second)) then
                call project_second_order(core%model%second, t, z(1:nx), z(nx + 1:2*nx), pstat)
            else if (allocated(core%model%higher)) then
                return
            else
                select type (p => core%model%first)
                type is (velocity_index2_problem)
                    call project_second_order(p%second, t, z(1:nx), z(nx + 1:2*nx), pstat)
                class default
                    call project_first_order(p, t, z(1:nx), pstat)
                end select
            end if
        end associate
    end procedure engine_project_start

    module procedure engine_limit_steps
        if (associated(self%core)) self%core%opts%max_steps = max(1, steps)
    end procedure engine_limit_steps

    module procedure engine_regularized
        yes = .false.
        if (associated(self%core)) yes = self%core%opts%method /= method_baumgarte .and. self%core%monitor%regularized()
    end procedure engine_regularized

    module procedure engine_eps_floored
        floored = .false.
        if (.not. associated(self%core)) return
        if (.not. (self%core%eps_factor > 0.0_wp)) return
        floored = abs(automatic_eps_factor(self%core%opts%rtol/kappa_a) - automatic_eps_factor(self%core%opts%rtol/ &
                      kappa_b)) <= 1.0e-6_wp*automatic_eps_factor(self%core%opts%rtol/kappa_a)
    end procedure engine_eps_floored

    module procedure engine_state_distance
        integer :: i
        logical :: skip_v
        d = 0.0_wp
        if (.not. associated(self%core)) return
        associate (core => self%core)
            ! the positions (x) only: the error the user reads; right after a pass the
            ! velocities carry its layer's sensitivity, which the positions integrate away
            skip_v = core%second_order
            do i = 1, min(size(za), size(zb), core%n)
                if (skip_v .and. i > core%nx) cycle
                d = max(d, abs(za(i) - zb(i))/(core%opts%rtol*abs(zb(i)) + core%atol_z(i)))
            end do
        end associate
        if (.not. (d == d)) d = huge(1.0_wp)
    end procedure engine_state_distance

    module procedure engine_note_event
        if (associated(self%core)) call log_event(self%core, text)
    end procedure engine_note_event

end submodule regdae_solver_passes
