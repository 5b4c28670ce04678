!> What `regdae_ida_backend` reports about its IDA run: the residual's failures (recorded
!! for failure_status, a stall at a point the solution cannot pass made fatal), the check of
!! the grouped difference-quotient Newton matrix against the column-by-column one
!! (check_jacobians on a declared structure) and IDA's counters as a solver_stats record.
submodule (regdae_ida_backend) regdae_ida_checks
    implicit none

contains

    ! The system's residual; returns 0, or +1 (recoverable) / -1 (fatal) after
    ! recording the failure in the backend.
    integer(c_int) module function evaluate_residual(self, t, u, up, res) result(ierr)
        type(ida_backend), intent(inout) :: self
        real(wp), intent(in) :: t, u(:), up(:)
        real(wp), intent(out) :: res(:)
        integer :: stat
        logical :: recoverable

        call self%system%residual(t, u, up, res, stat, recoverable)
        ierr = 0
        if (stat == regdae_success) then
            if (all(ieee_is_finite(res))) return
            stat = regdae_err_nonfinite
            recoverable = .true.
            self%system%message = 'NaN or Inf in the residual at t = '//format_real(t)
        end if
        ierr = callback_failure(self, t, stat, recoverable)
    end function evaluate_residual

    ! A callback of the system failed at t (stat, recoverable, the system's message):
    ! kept for failure_status, and IDA's flag (1: recoverable, -1: not).
    integer(c_int) module function callback_failure(self, t, stat, recoverable) result(ierr)
        type(ida_backend), intent(inout) :: self
        real(wp), intent(in) :: t
        integer, intent(in) :: stat
        logical, intent(in) :: recoverable
        self%pending_stat = stat
        self%pending_recoverable = recoverable
        self%pending_message = self%system%message
        if (recoverable) call note_recoverable_failure(self, t)
        ierr = merge(1_c_int, -1_c_int, self%pending_recoverable)
    end function callback_failure

    ! A recoverable failure at the trial time t. IDA retries with a smaller step;
    ! when the failure sits at a point the solution cannot pass (f NaN for all
    ! t >= t1, say), every retry that crosses it fails and every step that
    ! stops short succeeds, so IDA creeps towards it until max_steps. The
    ! failures are counted from the earliest failing time t_s on, as long as
    ! IDA's time stays below t_s; at stall_limit of them the failure becomes
    ! unrecoverable, with a message that says where the integration is stuck.
    subroutine note_recoverable_failure(self, t)
        type(ida_backend), intent(inout) :: self
        real(wp), intent(in) :: t
        integer, parameter :: stall_limit = 25
        real(c_double) :: tn(1)
        integer(c_int) :: ierr
        if (.not. c_associated(self%ida_mem)) return
        ierr = FIDAGetCurrentTime(self%ida_mem, tn)
        if (ierr /= 0) return
        if (self%stall_count > 0 .and. tn(1) > self%stall_t) self%stall_count = 0   ! got past it
        if (self%stall_count == 0) then
            self%stall_t = t
        else
            self%stall_t = min(self%stall_t, t)
        end if
        self%stall_count = self%stall_count + 1
        if (self%stall_count < stall_limit) return
        self%pending_recoverable = .false.
        self%pending_stat = regdae_err_integration
        self%pending_message = 'IDA cannot get past t = '//format_real(self%stall_t)//': '// &
                               format_int(stall_limit)//' recoverable failures of the residual at or beyond it '// &
                               'while the integration stayed at t = '//format_real(tn(1))//' (last: '// &
                               self%system%message//')'
    end subroutine note_recoverable_failure

    module subroutine backend_check_grouped(self, t, cj, stat, msg)
        class(ida_backend), intent(inout) :: self
        real(wp), intent(in) :: t, cj
        integer, intent(out) :: stat
        character(len=:), allocatable, intent(out) :: msg
        real(wp), allocatable :: full(:, :), grouped(:, :), res(:)
        real(c_double), pointer :: u(:), up(:)
        real(wp) :: d, scale, worst, diff
        integer :: j, k, a, c, neq, ierr, wi, wj
        stat = regdae_success
        msg = ''
        if (.not. self%system%structured) return
        neq = self%neq
        allocate (full(neq, neq), grouped(neq, neq), source=0.0_wp)
        allocate (res(neq))
        u => FN_VGetArrayPointer(self%uu)
        up => FN_VGetArrayPointer(self%up)
        ierr = evaluate_residual(self, t, u, up, res)
        self%u_pert = u(1:neq)
        self%up_pert = up(1:neq)
        do j = 1, neq   ! one column at a time
            d = sqrt(epsilon(1.0_wp))*max(abs(u(j)), 1.0_wp)
            self%u_pert(j) = u(j) + d
            d = self%u_pert(j) - u(j)
            self%up_pert(j) = up(j) + cj*d
            ierr = evaluate_residual(self, t, self%u_pert, self%up_pert, self%r_pert)
            full(:, j) = (self%r_pert - res)/d
            self%u_pert(j) = u(j)
            self%up_pert(j) = up(j)
        end do
        do c = 1, self%ngroups   ! the groups, as ida_jacobian_grouped does
            do a = self%group_start(c), self%group_start(c + 1) - 1
                j = self%group_cols(a)
                d = sqrt(epsilon(1.0_wp))*max(abs(u(j)), 1.0_wp)
                self%u_pert(j) = u(j) + d
                self%delta(j) = self%u_pert(j) - u(j)
                self%up_pert(j) = up(j) + cj*self%delta(j)
            end do
            ierr = evaluate_residual(self, t, self%u_pert, self%up_pert, self%r_pert)
            do a = self%group_start(c), self%group_start(c + 1) - 1
                j = self%group_cols(a)
                self%u_pert(j) = u(j)
                self%up_pert(j) = up(j)
                do k = self%csc_start(j), self%csc_start(j + 1) - 1
                    grouped(self%csc_rows(k), j) = (self%r_pert(self%csc_rows(k)) - res(self%csc_rows(k)))/self%delta(j)
                end do
            end do
        end do
        worst = 0.0_wp
        wi = 0
        wj = 0
        do j = 1, neq
            scale = max(1.0_wp, maxval(abs(full(:, j))))
            do k = 1, neq
                diff = abs(full(k, j) - grouped(k, j))/scale
                if (diff > worst) then
                    worst = diff
                    wi = k
                    wj = j
                end if
            end do
        end do
        if (worst > 1.0e-6_wp) then
            stat = regdae_err_jacobian
            msg = 'the Newton matrix from the declared sparsity patterns differs from the full difference quotient: '// &
                  'entry ('//format_int(wi)//', '//format_int(wj)//') is '//format_real(grouped(wi, wj))// &
                  ' grouped, '//format_real(full(wi, wj))//' full (unknowns in IDA''s order): a pattern (mass, '// &
                  'constraint, force_q, force_v) misses a dependence'
        end if
    end subroutine backend_check_grouped

    module subroutine backend_statistics(self, st)
        class(ida_backend), intent(in) :: self
        type(solver_stats), intent(inout) :: st
        integer(c_long) :: k(1)
        real(c_double) :: h(1)
        integer(c_int) :: ierr
        if (.not. c_associated(self%ida_mem)) return
        associate (mem => self%ida_mem, c => self%carried)
            ierr = FIDAGetNumSteps(mem, k); st%steps = k(1) + c%steps
            ierr = FIDAGetNumResEvals(mem, k); st%res_evals = k(1) + self%jac_res_evals + c%res_evals
            ierr = FIDAGetNumJacEvals(mem, k); st%jac_evals = k(1) + c%jac_evals
            ierr = FIDAGetNumLinSolvSetups(mem, k); st%lin_setups = k(1) + c%lin_setups
            ierr = FIDAGetNumNonlinSolvIters(mem, k); st%nonlin_iters = k(1) + c%nonlin_iters
            ierr = FIDAGetNumErrTestFails(mem, k); st%err_test_fails = k(1) + c%err_test_fails
            ierr = FIDAGetNumNonlinSolvConvFails(mem, k); st%conv_fails = k(1) + c%conv_fails
            ierr = FIDAGetLastStep(mem, h); st%h_last = h(1)
        end associate
        st%jac_res_evals = self%jac_res_evals
    end subroutine backend_statistics

end submodule regdae_ida_checks
