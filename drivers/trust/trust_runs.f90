!> The regdae runs of drivers/trust's cells: a mechanical or first-order problem from its start
!! to the outputs with the cell's options, stopped at the first failure or at the driver's wall
!! budget, recorded with the positions, energy and violation at each output reached.
module trust_runs
    use, intrinsic :: iso_fortran_env, only: int64
    use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
    use regdae, only: wp, regdae_solver, solver_options, solver_stats, second_order_problem, dae_problem, &
                      regdae_err_bad_input, regdae_err_not_psd
    use trust_support, only: status_budget
    use driver_support, only: num, stopwatch, clock_start, elapsed_seconds
    implicit none
    private
    public :: run_mechanical, run_first_order

    !> One run: its status (the failure, else the first warning, else 0), the outputs reached
    !! with status >= 0, the positions there, energy and constraint violation there (mechanical),
    !! the statistics, the solve's seconds and the message of the failure or first warning.
    type, public :: run_record
        integer :: stat = 0
        integer :: good = 0
        logical :: refused = .false.
        real(wp), allocatable :: x(:, :), energy(:), violation(:)
        real(wp) :: energy0 = 0.0_wp   !! the energy at the start
        real(wp) :: err = 0.0_wp       !! the error the family measured for this run
        integer, allocatable :: out_stat(:)   !! the status of each output's advance
        logical :: silent_later = .false.     !! a later pass went wrong with status 0 (split_at_last_warning)
        type(solver_stats) :: st
        real(wp) :: seconds = 0.0_wp
        character(len=:), allocatable :: message
    end type run_record

contains

    !> A regdae run of a mechanical (or second-order) problem from (q0, v0) at t = 0 to the
    !! outputs `times`: the positions, the energy (the problem's invariant) and max |g| there.
    subroutine run_mechanical(problem, q0, v0, times, opts, seconds_budget, rec)
        class(second_order_problem), intent(in) :: problem
        real(wp), intent(in) :: q0(:), v0(:), times(:)
        type(solver_options), intent(in) :: opts
        real(wp), intent(in) :: seconds_budget
        type(run_record), intent(out) :: rec
        type(regdae_solver) :: solver
        type(stopwatch) :: clock
        class(second_order_problem), allocatable :: probe
        real(wp) :: q(size(q0)), v(size(q0)), gval(problem%m), e
        integer(int64) :: start
        integer :: k, stat, warning, ustat

        allocate (probe, source=problem)
        call new_record(rec, size(q0), size(times))
        ustat = 0
        call probe%invariant(0.0_wp, q0, v0, rec%energy0, ustat)
        warning = 0
        start = clock_start()
        call clock%start()
        call solver%init(problem, 0.0_wp, q0, v0, opts, stat)
        call clock%stop()
        if (stat < 0) then
            call init_failed(rec, solver, stat)
        else
            do k = 1, size(times)
                call clock%start()
                call solver%advance(times(k), q, stat=stat, v=v)
                call clock%stop()
                if (advance_failed(rec, solver, stat, warning)) exit
                rec%out_stat(k) = stat
                rec%x(:, k) = q
                rec%good = k
                ustat = 0
                call probe%invariant(times(k), q, v, e, ustat)
                rec%energy(k) = e
                call probe%constraint(times(k), q, gval, ustat)
                rec%violation(k) = maxval(abs(gval))
                if (over_budget(rec, k, times, start, seconds_budget)) exit
            end do
            if (rec%stat == 0) rec%stat = warning
        end if
        rec%st = solver%statistics()
        rec%seconds = clock%seconds()
        call solver%destroy()
    end subroutine run_mechanical

    !> A regdae run of a first-order DAE from (t0, x0) to the outputs `times`.
    subroutine run_first_order(problem, t0, x0, times, opts, seconds_budget, rec)
        class(dae_problem), intent(in) :: problem
        real(wp), intent(in) :: t0, x0(:), times(:)
        type(solver_options), intent(in) :: opts
        real(wp), intent(in) :: seconds_budget
        type(run_record), intent(out) :: rec
        type(regdae_solver) :: solver
        type(stopwatch) :: clock
        real(wp) :: x(size(x0))
        integer(int64) :: start
        integer :: k, stat, warning

        call new_record(rec, size(x0), size(times))
        warning = 0
        start = clock_start()
        call clock%start()
        call solver%init(problem, t0, x0, opts, stat)
        call clock%stop()
        if (stat < 0) then
            call init_failed(rec, solver, stat)
        else
            do k = 1, size(times)
                if (times(k) == t0) then   ! the initial point itself is an output
                    rec%x(:, k) = x0
                    rec%good = k
                    cycle
                end if
                call clock%start()
                call solver%advance(times(k), x, stat=stat)
                call clock%stop()
                if (advance_failed(rec, solver, stat, warning)) exit
                rec%out_stat(k) = stat
                rec%x(:, k) = x
                rec%good = k
                if (over_budget(rec, k, times, start, seconds_budget)) exit
            end do
            if (rec%stat == 0) rec%stat = warning
        end if
        rec%st = solver%statistics()
        rec%seconds = clock%seconds()
        call solver%destroy()
    end subroutine run_first_order

    ! An empty record of n components at nout outputs (NaN until reached).
    subroutine new_record(rec, n, nout)
        type(run_record), intent(out) :: rec
        integer, intent(in) :: n, nout
        real(wp) :: nan
        nan = ieee_value(1.0_wp, ieee_quiet_nan)
        allocate (rec%x(n, nout), rec%energy(nout), rec%violation(nout), rec%out_stat(nout))
        rec%out_stat = 0
        rec%x = nan
        rec%energy = nan
        rec%violation = nan
        rec%message = ''
    end subroutine new_record

    ! init failed: a refusal (bad input, or `direct` on a GB that is not PSD) or a failure.
    ! After an advance: a failure (stat < 0) recorded with the solver's message (true: the run
    ! ends); the first warning kept in `warning` with its message.
    logical function advance_failed(rec, solver, stat, warning) result(failed)
        type(run_record), intent(inout) :: rec
        type(regdae_solver), intent(in) :: solver
        integer, intent(in) :: stat
        integer, intent(inout) :: warning
        failed = (stat < 0)
        if (failed) then
            rec%stat = stat
            rec%message = solver%message()
        else if (stat > 0 .and. warning == 0) then
            warning = stat
            rec%message = solver%message()
        end if
    end function advance_failed

    ! After output k: the driver's wall budget exhausted before the last output (recorded; true:
    ! the run ends).
    logical function over_budget(rec, k, times, start, seconds_budget) result(over)
        type(run_record), intent(inout) :: rec
        integer, intent(in) :: k
        real(wp), intent(in) :: times(:), seconds_budget
        integer(int64), intent(in) :: start
        over = (k < size(times) .and. elapsed_seconds(start) > seconds_budget)
        if (over) then
            rec%stat = status_budget
            rec%message = 'the driver''s wall budget of '//num(seconds_budget)//' s is exhausted at t = '// &
                          num(times(k))
        end if
    end function over_budget

    ! A refusal or failure of init.
    subroutine init_failed(rec, solver, stat)
        type(run_record), intent(inout) :: rec
        type(regdae_solver), intent(in) :: solver
        integer, intent(in) :: stat
        rec%stat = stat
        rec%message = solver%message()
        rec%refused = (stat == regdae_err_bad_input .or. stat == regdae_err_not_psd)
    end subroutine init_failed

end module trust_runs
