!> SUNDIALS IDA (`regdae_ida_backend`) behind the integrator interface
!! (`regdae_integrator`): integrator=ida, and the stiff slot of integrator=auto,
!! on each formulation: the eliminated one (the unknowns z), the multiplier one
!! ((z, y)) and the augmented one (`regdae_augmented_system`'s vector u, created
!! by the front's init or the switching policy on that system), with the dense,
!! band or sparse (KLU) linear solver. Its `advance` is `regdae_implicit_steps`'s
!! loop over IDA's single steps (the same steps as IDA_NORMAL), the monitor
!! sampling every accepted step's end and the output time, in time order; IDA's
!! interpolant gives the state at tout. With integrator=auto the loop asks the
!! switching policy every 20 steps whether the explicit method would do.
module regdae_ida_integrator
    use, intrinsic :: iso_c_binding, only: c_double, c_associated, c_long
    use, intrinsic :: iso_fortran_env, only: int64
    use fida_mod, only: FIDAGetNumSteps
    use regdae_kinds, only: wp
    use regdae_status
    use regdae_format, only: format_real, format_int
    use regdae_options, only: linear_solver_dense
    use regdae_solver_stats, only: solver_stats
    use regdae_ida_backend, only: ida_backend
    use regdae_regularized_system, only: new_regularized_system
    use regdae_augmented_system, only: augmented_system
    use regdae_solver_core, only: solver_core
    use regdae_switching_policy, only: spectral_radius
    use regdae_implicit_steps, only: implicit_stepper, name_len
    implicit none
    private

    public :: ida_in_slot

    !> IDA on one formulation of the core's model (see the module documentation).
    type, extends(implicit_stepper), public :: ida_integrator
        type(ida_backend) :: ida                       !! IDA and its callbacks (a fixed address: user_data)
    contains   ! the interface's procedures (regdae_integrator documents them)
        procedure :: start => ida_start
        procedure :: step_towards => ida_step_towards
        procedure :: to_step_end => ida_to_step_end
        procedure :: name => ida_name
        procedure :: state => ida_state
        procedure :: slope => ida_slope
        procedure :: interpolate => ida_interpolate
        procedure :: time => ida_time
        procedure :: last_step => ida_last_step
        procedure :: statistics => ida_statistics
        procedure :: stiffness => ida_stiffness
        procedure :: ready => ida_ready
        procedure :: free => ida_free
        procedure :: augmented => ida_augmented
        procedure :: state_written => ida_state_written
        procedure :: steps_taken => ida_steps_taken
    end type ida_integrator

contains

    !> The IDA integrator in the core's stiff slot (allocated there if the slot is
    !! empty); null if the slot holds another integrator.
    function ida_in_slot(core) result(p)
        type(solver_core), pointer, intent(in) :: core
        type(ida_integrator), pointer :: p
        p => null()
        if (.not. allocated(core%stiff)) allocate (ida_integrator :: core%stiff)
        select type (s => core%stiff)
        type is (ida_integrator)
            p => s
            p%core => core
        end select
    end function ida_in_slot

    !> From the consistent state z at t: on the augmented system, IDA restarted at
    !! its initial guess from z = (q, v) and IDACalcIC; otherwise, with the slope and
    !! multiplier given (or from the eliminated formulation), IDA restarted on
    !! (z, y) of the multiplier formulation or z, or created on the dense system.
    subroutine ida_start(self, t, z, stat, msg, h0, zp, y)
        class(ida_integrator), intent(inout), target :: self
        real(wp), intent(in) :: t, z(:)
        integer, intent(out) :: stat
        character(len=:), allocatable, intent(out) :: msg
        real(wp), intent(in), optional :: h0, zp(:), y(:)
        type(augmented_system), pointer :: sys
        real(wp), allocatable :: zp_(:), y_(:), u0(:), up0(:), id(:)
        logical :: recoverable
        integer :: nx
        msg = ''
        associate (core => self%core)
            nx = core%nx
            sys => self%augmented()
            if (associated(sys)) then
                allocate (u0(sys%neq), up0(sys%neq), id(sys%neq))
                call sys%initial_guess(z(1:nx), z(nx + 1:2*nx), u0, up0, id)
                call self%ida%restart(t, u0, up0, stat)
                if (stat == regdae_success) call self%ida%calc_ic(id, t + 1.0e-3_wp*max(1.0_wp, abs(t)), stat, msg)
                return
            end if
            if (present(zp) .and. present(y)) then
                zp_ = zp
                y_ = y
            else
                allocate (zp_(core%n), y_(core%m))
                call core%model%slope_eliminated(t, z, zp_, y_, stat, recoverable)
                if (stat /= regdae_success) then
                    msg = core%model%message
                    return
                end if
            end if
            if (self%ready()) then
                if (core%neq > core%n) then   ! the multiplier formulation
                    call self%ida%restart(t, [z, y_], [zp_, spread(0.0_wp, 1, core%m)], stat)
                else
                    call self%ida%restart(t, z, zp_, stat)
                end if
            else
                call self%ida%create(new_regularized_system(core%model, core%n, core%neq), core%opts, &
                                     linear_solver_dense, core%excluded, t, [z, y_], [zp_, spread(0.0_wp, 1, core%m)], &
                                     stat, msg, [core%atol_z, spread(core%opts%atol, 1, core%neq - core%n)])
            end if
        end associate
    end subroutine ida_start

    !> One IDA step towards tout (IDA_ONE_STEP, tstop at tout with stop_at_output).
    subroutine ida_step_towards(self, tout, t_now, stat, msg)
        class(ida_integrator), intent(inout), target :: self
        real(wp), intent(in) :: tout
        real(wp), intent(out) :: t_now
        integer, intent(out) :: stat
        character(len=:), allocatable, intent(inout) :: msg
        integer :: ierr
        stat = regdae_success
        call self%ida%step(tout, self%core%opts%stop_at_output, t_now, ierr)
        if (ierr >= 0) return
        stat = self%ida%failure_status()
        msg = 'IDA failed at t = '//format_real(t_now)//' (flag '//format_int(ierr)//'): '// &
              self%ida%ida_message//merge_text(' | last residual failure: ', self%ida%pending_message)
    end subroutine ida_step_towards

    !> IDA's interpolant at the end of its last step.
    subroutine ida_to_step_end(self)
        class(ida_integrator), intent(inout), target :: self
        integer :: ierr
        call self%ida%interpolate(self%ida%current_time(), ierr)
    end subroutine ida_to_step_end

    function ida_name(self) result(who)
        class(ida_integrator), intent(in) :: self
        character(len=name_len) :: who
        who = 'IDA'
    end function ida_name

    function ida_state(self) result(u)
        class(ida_integrator), intent(in), target :: self
        real(c_double), pointer :: u(:)
        u => self%ida%state()
    end function ida_state

    function ida_slope(self) result(up)
        class(ida_integrator), intent(in), target :: self
        real(c_double), pointer :: up(:)
        up => self%ida%slope()
    end function ida_slope

    !> IDA's interpolant at t (state and slope); stat: IDAGetDky's flag. Where state
    !! and slope hold it at t already (the last interpolation, no step since), nothing to do.
    subroutine ida_interpolate(self, t, stat)
        class(ida_integrator), intent(inout), target :: self
        real(wp), intent(in) :: t
        integer, intent(out) :: stat
        call self%ida%interpolate(t, stat)
    end subroutine ida_interpolate

    real(wp) function ida_time(self)
        class(ida_integrator), intent(in) :: self
        ida_time = self%ida%current_time()
    end function ida_time

    real(wp) function ida_last_step(self)
        class(ida_integrator), intent(in) :: self
        ida_last_step = self%ida%last_step()
    end function ida_last_step

    !> IDA's counters (over its restarts) added to st; its last step when active.
    subroutine ida_statistics(self, st, active)
        class(ida_integrator), intent(in) :: self
        type(solver_stats), intent(inout) :: st
        logical, intent(in) :: active
        type(solver_stats) :: own
        if (.not. c_associated(self%ida%ida_mem)) return   ! never created
        call self%ida%get_statistics(own)
        st%steps = st%steps + own%steps
        st%res_evals = st%res_evals + own%res_evals
        st%jac_res_evals = st%jac_res_evals + own%jac_res_evals
        st%jac_evals = st%jac_evals + own%jac_evals
        st%lin_setups = st%lin_setups + own%lin_setups
        st%nonlin_iters = st%nonlin_iters + own%nonlin_iters
        st%err_test_fails = st%err_test_fails + own%err_test_fails
        st%conv_fails = st%conv_fails + own%conv_fails
        if (active) st%h_last = own%h_last
    end subroutine ida_statistics

    !> IDA's steps over its restarts: ida_statistics' count from IDA's step counter alone
    !! (asked at every output).
    integer(int64) function ida_steps_taken(self) result(n)
        class(ida_integrator), intent(in) :: self
        integer(c_long) :: k(1)
        n = 0
        if (.not. c_associated(self%ida%ida_mem)) return   ! never created
        if (FIDAGetNumSteps(self%ida%ida_mem, k) /= 0) k = 0
        n = k(1) + self%ida%carried%steps
    end function ida_steps_taken

    !> The spectral radius of the eliminated formulation's Jacobian at IDA's state.
    real(wp) function ida_stiffness(self, t) result(rho)
        class(ida_integrator), intent(inout), target :: self
        real(wp), intent(in) :: t
        real(c_double), pointer :: u(:)
        u => self%ida%state()
        rho = spectral_radius(self%core, t, u(1:self%core%n))
    end function ida_stiffness

    logical function ida_ready(self)
        class(ida_integrator), intent(in) :: self
        ida_ready = allocated(self%ida%system)
    end function ida_ready

    subroutine ida_free(self)
        class(ida_integrator), intent(inout) :: self
        call self%ida%free()
    end subroutine ida_free

    function ida_augmented(self) result(sys)
        class(ida_integrator), intent(in), target :: self
        type(augmented_system), pointer :: sys
        sys => null()
        if (.not. allocated(self%ida%system)) return
        select type (s => self%ida%system)
        type is (augmented_system)
            sys => s
        end select
    end function ida_augmented

    !> The caller wrote into state(): the next interpolation computes again.
    subroutine ida_state_written(self)
        class(ida_integrator), intent(inout) :: self
        call self%ida%forget_interpolation()
    end subroutine ida_state_written

    ! prefix//text, or '' for an empty text.
    pure function merge_text(prefix, text) result(s)
        character(len=*), intent(in) :: prefix, text
        character(len=merge(len(prefix) + len(text), 0, len(text) > 0)) :: s
        if (len(text) > 0) s = prefix//text
    end function merge_text

end module regdae_ida_integrator
