!> Helpers shared by the regdae drivers: `key=value` arguments, number
!! formatting for the summary line, wall-clock time.
module driver_support
    use, intrinsic :: iso_fortran_env, only: int64, error_unit
    use regdae, only: wp, format_real, format_int, solver_options, solver_stats, set_option, regdae_success, &
                      regdae_solver, parse_real, parse_integer, option_auto, integrator_name, formulation_name
    use regdae_parse, only: has_outer_blank
    implicit none
    private

    public :: format_int
    public :: read_number, read_count, common_argument, parse_number, parse_count, common_option
    public :: stats_fields, run_status, resolved_line, event_lines, timing_option

    !> The largest `nout` the drivers accept: their tables hold nout + 1 rows.
    integer, parameter, public :: max_nout = 1000000
    public :: argument, split_key_value, num, elapsed_seconds, clock_start, die_usage, sort_ascending

    !> Accumulates the wall-clock time between start and stop calls: the solve
    !! (init and advances) apart from writing the output.
    type, public :: stopwatch
        integer(int64) :: total = 0      !! accumulated clock counts
        integer(int64) :: since = 0      !! count at the last start
    contains
        procedure :: start => stopwatch_start
        procedure :: stop => stopwatch_stop
        !> The accumulated seconds.
        procedure :: seconds => stopwatch_seconds
    end type stopwatch

    !> The warnings (status > 0) of a run's advances: how many, the first one's
    !! time and message (the summary's status word is then 'warning').
    type, public :: warning_log
        integer :: count = 0
        real(wp) :: t_first = 0.0_wp
        character(len=:), allocatable :: first
    contains
        procedure :: note => warning_note
    end type warning_log

contains

    !> The i-th command-line argument.
    function argument(i) result(arg)
        integer, intent(in) :: i
        character(len=:), allocatable :: arg
        integer :: length
        call get_command_argument(i, length=length)
        allocate (character(len=length) :: arg)
        if (length > 0) call get_command_argument(i, arg)
    end function argument

    !> Split `key=value`; `ok` is false when there is no '=' or the key is empty.
    subroutine split_key_value(arg, key, value, ok)
        character(len=*), intent(in) :: arg
        character(len=:), allocatable, intent(out) :: key, value
        logical, intent(out) :: ok
        integer :: eq
        eq = index(arg, '=')
        ok = eq > 1
        if (ok) then
            key = arg(1:eq - 1)
            value = arg(eq + 1:)
        else
            key = arg
            value = ''
        end if
    end subroutine split_key_value

    !> A real for the summary line, 5 significant digits (NaN and Inf as such).
    function num(x) result(s)
        real(wp), intent(in) :: x
        character(len=:), allocatable :: s
        if (x == option_auto) then
            s = 'auto'
        else
            s = format_real(x, 4)
        end if
    end function num

    !> The '# resolved:' line of a solver after init: the values its automatic
    !! options took (the weights, eps, the drift bound at t0, work_tol) and the
    !! formulation and integrator in force.
    function resolved_line(solver) result(text)
        type(regdae_solver), intent(in) :: solver
        character(len=:), allocatable :: text
        type(solver_options) :: o
        o = solver%options()
        text = '# resolved: formulation='//formulation_name(solver%formulation())//' integrator='// &
               integrator_name(o%integrator)//' gamma='//num(o%gamma)//' gamma0='//num(o%gamma0)//' gamma1='// &
               num(o%gamma1)//' eps='//num(o%eps)//' drift_tol='//num(o%drift_tol)//' (at t0)'
    end function resolved_line

    !> The solver's events (integrator switches), one '# event: ' line each; empty if none.
    function event_lines(solver) result(text)
        type(regdae_solver), intent(in) :: solver
        character(len=:), allocatable :: text, log
        integer :: a, b
        log = solver%events()
        text = ''
        a = 1
        do while (a <= len(log))
            b = index(log(a:), new_line('a'))
            if (b == 0) b = len(log) - a + 2
            text = text//'# event: '//log(a:a + b - 2)//new_line('a')
            a = a + b
        end do
    end function event_lines

    !> Start a wall-clock measurement.
    function clock_start() result(count)
        integer(int64) :: count
        call system_clock(count)
    end function clock_start

    !> Seconds since `start` (from `clock_start`).
    function elapsed_seconds(start) result(sec)
        integer(int64), intent(in) :: start
        real(wp) :: sec
        integer(int64) :: now, rate
        call system_clock(now, rate)
        sec = real(now - start, wp)/real(rate, wp)
    end function elapsed_seconds

    subroutine stopwatch_start(self)
        class(stopwatch), intent(inout) :: self
        call system_clock(self%since)
    end subroutine stopwatch_start

    subroutine stopwatch_stop(self)
        class(stopwatch), intent(inout) :: self
        integer(int64) :: now
        call system_clock(now)
        self%total = self%total + (now - self%since)
    end subroutine stopwatch_stop

    real(wp) function stopwatch_seconds(self)
        class(stopwatch), intent(in) :: self
        integer(int64) :: rate
        call system_clock(count_rate=rate)
        stopwatch_seconds = real(self%total, wp)/real(rate, wp)
    end function stopwatch_seconds

    !> Read a finite real option value (the forms of `parse_real`: 1e-3, 1E-3,
    !! 1d-3, .5, 5., +5), or stop with a usage error naming the key.
    subroutine read_number(program_name, key, value, x)
        character(len=*), intent(in) :: program_name, key, value
        real(wp), intent(inout) :: x
        character(len=:), allocatable :: msg
        call parse_number(key, value, x, msg)
        if (len(msg) > 0) call die_usage(program_name, msg)
    end subroutine read_number

    !> `read_number` without stopping: `msg` is empty on success, else the usage
    !! message naming the key (x unchanged).
    subroutine parse_number(key, value, x, msg)
        character(len=*), intent(in) :: key, value
        real(wp), intent(inout) :: x
        character(len=:), allocatable, intent(out) :: msg
        logical :: ok
        msg = blank_message(key, value)
        if (len(msg) > 0) return
        call parse_real(value, x, ok)
        if (.not. ok) msg = 'bad value "'//value//'" for '//key//' (a finite number, e.g. 1e-3, 2.5 or .5)'
    end subroutine parse_number

    ! Values are taken as given: a blank (or tab, newline) before or after one
    ! ("rtol=1e-3 " in quotes) is refused, as by the C door, not read as 1e-3.
    function blank_message(key, value) result(msg)
        character(len=*), intent(in) :: key, value
        character(len=:), allocatable :: msg
        msg = ''
        if (has_outer_blank(value)) msg = 'bad value "'//value//'" for '//key// &
                                         ': a blank before or after it (values are taken as given)'
    end function blank_message

    !> Read an integer option value in [lo, hi], or stop with a usage error
    !! naming the key and the range.
    subroutine read_count(program_name, key, value, k, lo, hi)
        character(len=*), intent(in) :: program_name, key, value
        integer, intent(inout) :: k
        integer, intent(in) :: lo, hi
        character(len=:), allocatable :: msg
        call parse_count(key, value, k, lo, hi, msg)
        if (len(msg) > 0) call die_usage(program_name, msg)
    end subroutine read_count

    !> `read_count` without stopping: `msg` is empty on success, else the usage
    !! message naming the key and the range (k unchanged).
    subroutine parse_count(key, value, k, lo, hi, msg)
        character(len=*), intent(in) :: key, value
        integer, intent(inout) :: k
        integer, intent(in) :: lo, hi
        character(len=:), allocatable, intent(out) :: msg
        integer :: tmp
        logical :: ok
        msg = blank_message(key, value)
        if (len(msg) > 0) return
        tmp = lo
        call parse_integer(value, tmp, ok)
        if (.not. ok .or. tmp < lo .or. tmp > hi) then
            msg = 'bad value "'//value//'" for '//key//' (an integer in ['//format_int(lo)//', '//format_int(hi)//'])'
        else
            k = tmp
        end if
    end subroutine parse_count

    !> The timing drivers' options (drivers/bench, drivers/car_axis): `reps` (runs per
    !! row, in [1, max_reps]), `min_time` (seconds per row, in [0, 60]), `tol_from`
    !! and `tol_to` (the rows' rtol = 10^-k, k in [1, 14]); .true. when key is one
    !! of them (read, or a usage error), .false. otherwise.
    logical function timing_option(program_name, key, value, max_reps, reps, min_time, tol_from, tol_to) result(known)
        character(len=*), intent(in) :: program_name, key, value
        integer, intent(in) :: max_reps
        integer, intent(inout) :: reps, tol_from, tol_to
        real(wp), intent(inout) :: min_time
        known = .true.
        select case (key)
        case ('reps'); call read_count(program_name, key, value, reps, 1, max_reps)
        case ('min_time'); call read_number(program_name, key, value, min_time)
            if (.not. (min_time >= 0 .and. min_time <= 60)) call die_usage(program_name, 'min_time must be in [0, 60] seconds')
        case ('tol_from'); call read_count(program_name, key, value, tol_from, 1, 14)
        case ('tol_to'); call read_count(program_name, key, value, tol_to, 1, 14)
        case default; known = .false.
        end select
    end function timing_option

    !> The arguments all drivers share: `nout` (an integer in [1, max_nout]) and
    !! every solver option; anything else stops with a usage error naming it.
    subroutine common_argument(program_name, key, value, opts, nout)
        character(len=*), intent(in) :: program_name, key, value
        type(solver_options), intent(inout) :: opts
        integer, intent(inout) :: nout
        character(len=:), allocatable :: msg
        call common_option(key, value, opts, nout, msg)
        if (len(msg) > 0) call die_usage(program_name, msg)
    end subroutine common_argument

    !> `common_argument` without stopping: `msg` is empty on success, else the
    !! message naming the key (drivers/sweep: a bad row is reported, not fatal).
    subroutine common_option(key, value, opts, nout, msg)
        character(len=*), intent(in) :: key, value
        type(solver_options), intent(inout) :: opts
        integer, intent(inout) :: nout
        character(len=:), allocatable, intent(out) :: msg
        integer :: stat
        msg = blank_message(key, value)
        if (len(msg) > 0) then
            return
        else if (key == 'nout') then
            call parse_count(key, value, nout, 1, max_nout, msg)
        else
            call set_option(opts, key, value, stat, msg)
            if (stat == regdae_success) then
                msg = ''
            else if (len(msg) == 0) then
                msg = 'bad option '//key//'='//value
            end if
        end if
    end subroutine common_option

    !> The statistics fields that end every summary line: `seconds` is the solve
    !! (init and advances), `output_seconds` (if given) the writing of the table.
    function stats_fields(st, seconds, output_seconds) result(text)
        type(solver_stats), intent(in) :: st
        real(wp), intent(in) :: seconds
        real(wp), intent(in), optional :: output_seconds
        character(len=:), allocatable :: text
        text = ' steps='//format_int(st%steps)//' res_evals='//format_int(st%res_evals)// &
               ' jac_evals='//format_int(st%jac_evals)//' err_test_fails='//format_int(st%err_test_fails)// &
               ' conv_fails='//format_int(st%conv_fails)//' switches='//format_int(st%switches)// &
               ' work_defect='//num(st%work_defect)//' pass_checks='//format_int(st%pass_checks)// &
               ' passes_resolved='//format_int(st%passes_resolved)//' passes_unresolved='// &
               format_int(st%passes_unresolved)//' pass_error='//num(st%pass_error)// &
               ' companion_steps='//format_int(st%companion_steps)//' seconds='//num(seconds)
        if (present(output_seconds)) text = text//' output_seconds='//num(output_seconds)
    end function stats_fields

    !> The summary's status word of a finished run: 'ok', or 'failed' after the
    !! line '# error: <the solver's message>'.
    function run_status(solver, stat, warnings) result(text)
        type(regdae_solver), intent(in) :: solver
        integer, intent(in) :: stat
        type(warning_log), intent(in), optional :: warnings   !! the warnings of the run's advances
        character(len=:), allocatable :: text
        text = 'ok'
        if (stat < 0) then
            write (*, '(a)') '# error: '//solver%message()
            text = 'failed'
        else if (stat > 0) then
            write (*, '(a)') '# warning: '//solver%message()
            text = 'warning'
        end if
        if (present(warnings)) then
            if (warnings%count > 0) then
                write (*, '(a)') '# warning: '//format_int(warnings%count)//' advance(s) returned a warning; '// &
                    'the first, at t = '//num(warnings%t_first)//': '//warnings%first
                if (text == 'ok') text = 'warning'
            end if
        end if
    end function run_status

    !> Keep a run's warnings: `note` after each advance (stat > 0 counts; the first
    !! message and time are kept).
    subroutine warning_note(self, solver, stat, t)
        class(warning_log), intent(inout) :: self
        type(regdae_solver), intent(in) :: solver
        integer, intent(in) :: stat
        real(wp), intent(in) :: t
        if (stat <= 0) return
        self%count = self%count + 1
        if (self%count == 1) then
            self%first = solver%message()
            self%t_first = t
        end if
    end subroutine warning_note

    !> Print a usage error naming the problem and stop with status 2.
    subroutine die_usage(program_name, text)
        character(len=*), intent(in) :: program_name, text
        write (error_unit, '(a)') program_name//': '//text
        stop 2
    end subroutine die_usage

    !> Insertion sort, ascending (the drivers' short lists: a few hundred values).
    pure subroutine sort_ascending(a)
        real(wp), intent(inout) :: a(:)
        real(wp) :: x
        integer :: i, j
        do i = 2, size(a)
            x = a(i)
            j = i - 1
            do while (j >= 1)
                if (a(j) <= x) exit
                a(j + 1) = a(j)
                j = j - 1
            end do
            a(j + 1) = x
        end do
    end subroutine sort_ascending

end module driver_support
