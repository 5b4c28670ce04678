!> The run logic of drivers/sweep: one row of a sweep table in, one result line
!! out. A row is a problem name and `key=value` words, the keys of the drivers:
!!
!!   ex51      orientation=psd|paper x0=0 nout=200             (t in [-1, 1]; error against x = t + 1)
!!   crank2    th1=pi/2 w1=0 tf=10 nout=1000 gravity=9.8 branch_tol=0.1   (the slider crank at index 2;
!!   crank3    the same at index 3; errors against the reduced ODE by CVODE at 1e-13, as drivers/ex52;
!!             curvature_source=difference|analytic: regdae's difference quotient for g_xx(v, v), as
!!             drivers/ex52, or the analytic one, as drivers/bench)
!!   pendulum  phi0=pi/2 w0=0 tf=10 nout=1000 gravity=9.81     (against the angle ODE by CVODE, as
!!             drivers/pendulum; index=2|3 as a solver option)
!!   chain     n_links=16 slider=no tf=1 nout=100 gravity=9.81 mass=1 stiffness=0 damping=0
!!             (no reference: the drift and the energy change, as drivers/chain)
!!
!! and every solver option of `set_option` (method, gamma, eps, rtol, atol, ...), with the
!! drivers' defaults (stop_at_output=yes except for the chain). The result line:
!!
!!   <id> <problem> <status> t_end=... <errors> steps=... res_evals=... jac_evals=...
!!       err_test_fails=... conv_fails=... switches=... work_defect=... seconds=... [message=...]
!!
!! status: ok; warning (the run ended, but an advance returned a warning, e.g. a singular pass
!! the pass check did not resolve: message= the first one); failed (the solver stopped:
!! message= its message); off_branch (crank2, crank3:
!! the solver ended but |th1 + th2 - pi| exceeded branch_tol, as ex52's status=failed with its
!! warning); bad_input (a row that cannot run: an unknown problem or key, a bad value, or
!! init's regdae_err_bad_input; message= why). seconds: init and advances only (not the
!! reference). <errors>: ex51 max_err_x; crank max_err_th max_abs_g3 max_energy_err
!! max_branch_dev singular_passes; pendulum max_err_pos max_abs_g; chain engine max_drift
!! energy_change singular_passes sigma_min. A row that is not even a problem has its
!! problem printed as '-' when its first word is a key=value. No MPI here: a `row_hook`
!! given to `run_row` is called after every output time (drivers/sweep's rank 0 serves
!! the other ranks from it while it runs a row itself).
module sweep_rows
    use regdae
    use ex51_problem, only: ex51, new_ex51, orientation_psd, orientation_paper
    use slider_crank_problem, only: slider_crank, slider_crank_reduced, new_slider_crank
    use pendulum_problem, only: pendulum, pendulum_angle, new_pendulum
    use chain_problem, only: chain, new_chain, chain_start, chain_energy_of, chain_violation
    use reference_ode, only: integrate_reference, ode_system
    use driver_support, only: num, stats_fields, stopwatch, split_key_value, parse_number, parse_count, &
                              common_option
    use sweep_table, only: word, max_row_length
    implicit none
    private

    public :: run_row, row_problem, one_line

    !> The problems a row may name.
    character(len=*), parameter, public :: problem_list = 'ex51, crank2, crank3, pendulum, chain'

    !> Called by `run_row` after each output time of a run (and never inside the solver).
    type, abstract, public :: row_hook
    contains
        procedure(hook_poll), deferred :: poll
    end type row_hook

    abstract interface
        subroutine hook_poll(self)
            import :: row_hook
            class(row_hook), intent(inout) :: self
        end subroutine hook_poll
    end interface

    real(wp), parameter :: pi = acos(-1.0_wp)
    !> The keys that belong to one problem or another (each problem's own: `own_keys`).
    character(len=*), parameter :: problem_keys = &
        ' orientation x0 th1 w1 tf gravity branch_tol curvature_source phi0 w0 n_links slider mass stiffness damping peer '

    !> A parsed row: the problem, its parameters and the solver options.
    type :: row_setup
        character(len=:), allocatable :: problem
        type(solver_options) :: opts
        integer :: nout = 1
        real(wp) :: tf = 1.0_wp, gravity = 9.81_wp
        real(wp) :: angle = 0.0_wp, speed = 0.0_wp   !! crank: th1, w1; pendulum: phi0, w0
        real(wp) :: branch_tol = 0.1_wp
        logical :: analytic_curvature = .false.      !! crank: curvature_source=analytic (drivers/bench's g_xx(v, v))
        real(wp) :: x0 = 0.0_wp
        integer :: orientation = orientation_psd
        integer :: n_links = 16
        logical :: slider = .false.
        real(wp) :: joint_mass = 1.0_wp, stiffness = 0.0_wp, damping = 0.0_wp
    end type row_setup

    !> What a run gives its result line.
    type :: row_result
        character(len=:), allocatable :: status    !! ok, failed, off_branch, bad_input
        character(len=:), allocatable :: fields    !! ' t_end=... <errors>'
        character(len=:), allocatable :: message   !! why, unless ok
        type(solver_stats) :: st
        real(wp) :: seconds = 0.0_wp
        logical :: ran = .false.                   !! the solver was set up: st and seconds mean something
    end type row_result

    !> One run of a row, the problem's part: `drive` calls prepare (the problem, the output
    !! times, a reference: untimed), start (the solver's init) and, for each output time k,
    !! advance (timed) and measure (the errors there), then fields (the error columns).
    type, abstract :: row_run
        type(regdae_solver) :: solver
        real(wp), allocatable :: times(:)   !! the output times
    contains
        procedure(run_prepare), deferred :: prepare
        procedure(run_start), deferred :: start
        procedure(run_advance), deferred :: advance
        procedure(run_measure), deferred :: measure
        procedure(run_prepare), deferred :: fields
    end type row_run

    abstract interface
        subroutine run_prepare(self, s, r)
            import :: row_run, row_setup, row_result
            class(row_run), intent(inout) :: self
            type(row_setup), intent(in) :: s
            type(row_result), intent(inout) :: r
        end subroutine run_prepare
        subroutine run_start(self, s, stat)
            import :: row_run, row_setup
            class(row_run), intent(inout) :: self
            type(row_setup), intent(in) :: s
            integer, intent(out) :: stat
        end subroutine run_start
        subroutine run_advance(self, k, stat)
            import :: row_run
            class(row_run), intent(inout) :: self
            integer, intent(in) :: k
            integer, intent(out) :: stat
        end subroutine run_advance
        subroutine run_measure(self, k)
            import :: row_run
            class(row_run), intent(inout) :: self
            integer, intent(in) :: k
        end subroutine run_measure
    end interface

    type, extends(row_run) :: ex51_run
        type(ex51) :: problem
        real(wp) :: x(1) = 0.0_wp, y(1) = 0.0_wp, max_err = 0.0_wp
    contains
        procedure :: prepare => ex51_prepare
        procedure :: start => ex51_start
        procedure :: advance => ex51_advance
        procedure :: measure => ex51_measure
        procedure :: fields => ex51_fields
    end type ex51_run

    type, extends(row_run) :: crank_run
        type(slider_crank) :: crank
        real(wp), allocatable :: ref(:, :)
        real(wp) :: th(2) = 0.0_wp, w(2) = 0.0_wp, lam(1) = 0.0_wp, e0 = 0.0_wp, branch_tol = 0.0_wp
        real(wp) :: max_err = 0.0_wp, max_g3 = 0.0_wp, max_de = 0.0_wp, max_dev = 0.0_wp
        real(wp) :: t_off = -1.0_wp   !! the first output time off the branch (< 0: none)
    contains
        procedure :: prepare => crank_prepare
        procedure :: start => crank_start
        procedure :: advance => crank_advance
        procedure :: measure => crank_measure
        procedure :: fields => crank_fields
    end type crank_run

    type, extends(row_run) :: pendulum_run
        type(pendulum) :: problem
        real(wp), allocatable :: ref(:, :)
        real(wp) :: x(2) = 0.0_wp, v(2) = 0.0_wp, y(1) = 0.0_wp, max_err = 0.0_wp, max_g = 0.0_wp
    contains
        procedure :: prepare => pendulum_prepare
        procedure :: start => pendulum_start
        procedure :: advance => pendulum_advance
        procedure :: measure => pendulum_measure
        procedure :: fields => pendulum_fields
    end type pendulum_run

    type, extends(row_run) :: chain_run
        type(chain) :: problem
        real(wp), allocatable :: q0(:), v0(:), q(:), v(:), y(:)
        real(wp) :: e0 = 0.0_wp, energy_change = 0.0_wp, max_drift = 0.0_wp
        character(len=:), allocatable :: engine   !! formulation/linear solver
    contains
        procedure :: prepare => chain_prepare
        procedure :: start => chain_run_start
        procedure :: advance => chain_advance
        procedure :: measure => chain_measure
        procedure :: fields => chain_fields
    end type chain_run

contains

    !> Run the table row `line` as row `id` and return its result line (no newline).
    function run_row(id, line, hook) result(text)
        integer, intent(in) :: id
        character(len=*), intent(in) :: line
        class(row_hook), intent(inout), optional :: hook
        character(len=:), allocatable :: text
        type(row_setup) :: s
        type(row_result) :: r
        class(row_run), allocatable :: run
        character(len=:), allocatable :: msg
        r%fields = ''
        r%status = ''
        call parse_row(line, s, msg)
        if (len(msg) > 0) then
            r%status = 'bad_input'
            r%message = msg
        else
            select case (s%problem)
            case ('ex51'); allocate (ex51_run :: run)
            case ('crank2', 'crank3'); allocate (crank_run :: run)
            case ('pendulum'); allocate (pendulum_run :: run)
            case default; allocate (chain_run :: run)
            end select
            call drive(run, s, r, hook)
        end if
        text = format_int(id)//' '//row_problem(line)//' '//r%status//r%fields
        if (r%ran) text = text//stats_fields(r%st, r%seconds)
        if (r%status /= 'ok') text = text//' message='//one_line(r%message)
    end function run_row

    !> The problem word of a row as its result line shows it: the first word, or '-'
    !! if that is a key=value (a row without a problem).
    function row_problem(line) result(name)
        character(len=*), intent(in) :: line
        character(len=:), allocatable :: name
        name = word(line, 1)
        if (index(name, '=') > 0 .or. len(name) == 0) name = '-'
    end function row_problem

    !> A text on one line: newlines, tabs and carriage returns become blanks, at most
    !! `max_row_length` characters.
    function one_line(text) result(line)
        character(len=*), intent(in) :: text
        character(len=:), allocatable :: line
        integer :: i
        line = text(1:min(len(text), max_row_length))
        do i = 1, len(line)
            if (any(line(i:i) == [new_line('a'), achar(9), achar(13)])) line(i:i) = ' '
        end do
    end function one_line

    subroutine parse_row(line, s, msg)
        character(len=*), intent(in) :: line
        type(row_setup), intent(out) :: s
        character(len=:), allocatable, intent(out) :: msg
        type(solver_options) :: solver_options_default
        character(len=:), allocatable :: token, key, value
        integer :: k
        logical :: ok
        msg = ''
        if (len_trim(line) > max_row_length) then
            msg = 'the row is longer than '//format_int(max_row_length)//' characters'
            return
        end if
        s%problem = word(line, 1)
        s%opts%stop_at_output = .true.
        select case (s%problem)
        case ('ex51')
            s%nout = 200
        case ('crank2', 'crank3')
            s%nout = 1000
            s%tf = 10.0_wp
            s%gravity = 9.8_wp
            s%angle = pi/2
            s%opts%index = merge(2, 3, s%problem == 'crank2')
        case ('pendulum')
            s%nout = 1000
            s%tf = 10.0_wp
            s%angle = pi/2
        case ('chain')
            s%nout = 100
            s%opts%stop_at_output = solver_options_default%stop_at_output   ! as drivers/chain
        case default
            msg = 'unknown problem "'//s%problem//'" (the first word of a row: '//problem_list//')'
            return
        end select
        k = 2
        do
            token = word(line, k)
            if (len(token) == 0) exit
            k = k + 1
            call split_key_value(token, key, value, ok)
            if (.not. ok) then
                msg = '"'//token//'" is not of the form key=value'
            else
                call set_key(s, key, value, msg)
            end if
            if (len(msg) > 0) return
        end do
        if (s%problem /= 'ex51' .and. .not. (s%tf > 0.0_wp)) msg = 'tf must be > 0'
        if (s%slider .and. mod(s%n_links, 2) /= 0) msg = 'slider=yes needs an even n_links'
    end subroutine parse_row

    !> The problem's own keys (besides nout and the solver options).
    function own_keys(problem) result(keys)
        character(len=*), intent(in) :: problem
        character(len=:), allocatable :: keys
        select case (problem)
        case ('ex51'); keys = 'orientation x0'
        case ('crank2', 'crank3'); keys = 'th1 w1 tf gravity branch_tol curvature_source'
        case ('pendulum'); keys = 'phi0 w0 tf gravity'
        case default; keys = 'n_links slider tf gravity mass stiffness damping'
        end select
    end function own_keys

    subroutine set_key(s, key, value, msg)
        type(row_setup), intent(inout) :: s
        character(len=*), intent(in) :: key, value
        character(len=:), allocatable, intent(out) :: msg
        msg = ''
        if (index(problem_keys, ' '//key//' ') > 0 .and. index(' '//own_keys(s%problem)//' ', ' '//key//' ') == 0) then
            msg = 'key "'//key//'" does not apply to '//s%problem//' (its keys: '//own_keys(s%problem)// &
                  ', nout and the solver options)'
            return
        end if
        select case (key)
        case ('tf'); call parse_number(key, value, s%tf, msg)
        case ('gravity'); call parse_number(key, value, s%gravity, msg)
        case ('th1', 'phi0'); call parse_number(key, value, s%angle, msg)
        case ('w1', 'w0'); call parse_number(key, value, s%speed, msg)
        case ('branch_tol'); call parse_number(key, value, s%branch_tol, msg)
        case ('x0'); call parse_number(key, value, s%x0, msg)
        case ('mass'); call parse_positive(key, value, s%joint_mass, .false., msg)
        case ('stiffness'); call parse_positive(key, value, s%stiffness, .true., msg)
        case ('damping'); call parse_positive(key, value, s%damping, .true., msg)
        case ('n_links'); call parse_count(key, value, s%n_links, 1, 1000000, msg)
        case ('slider')
            if (value /= 'yes' .and. value /= 'no') msg = 'bad value "'//value//'" for slider (yes, no)'
            s%slider = (value == 'yes')
        case ('curvature_source')
            if (value /= 'analytic' .and. value /= 'difference') &
                msg = 'bad value "'//value//'" for curvature_source (difference, analytic)'
            s%analytic_curvature = (value == 'analytic')
        case ('orientation')
            select case (value)
            case ('psd'); s%orientation = orientation_psd
            case ('paper'); s%orientation = orientation_paper
            case default; msg = 'bad value "'//value//'" for orientation (psd|paper)'
            end select
        case ('index')
            if (s%problem == 'crank2' .or. s%problem == 'crank3') then
                msg = 'index is the problem name''s here: crank2 or crank3'
            else
                call common_option(key, value, s%opts, s%nout, msg)
            end if
        case ('peer'); msg = 'peer=yes (the plain IDA peer) is the chain driver''s, not the sweep''s'
        case default
            call common_option(key, value, s%opts, s%nout, msg)
        end select
    end subroutine set_key

    !> A number > 0 (>= 0 if `zero_ok`), or msg.
    subroutine parse_positive(key, value, x, zero_ok, msg)
        character(len=*), intent(in) :: key, value
        real(wp), intent(inout) :: x
        logical, intent(in) :: zero_ok
        character(len=:), allocatable, intent(out) :: msg
        call parse_number(key, value, x, msg)
        if (len(msg) > 0) return
        if (zero_ok .and. .not. (x >= 0.0_wp)) msg = key//' must be >= 0'
        if (.not. zero_ok .and. .not. (x > 0.0_wp)) msg = key//' must be > 0'
    end subroutine parse_positive

    !> nout + 1 equally spaced times from t0 to tf.
    function output_times(t0, tf, nout) result(times)
        real(wp), intent(in) :: t0, tf
        integer, intent(in) :: nout
        real(wp), allocatable :: times(:)
        integer :: k
        times = [(t0 + (tf - t0)*real(k, wp)/real(nout, wp), k=0, nout)]
    end function output_times

    !> Run a parsed row: the problem's part (`row_run`) and the part every problem shares:
    !! the solver's init and advances timed, the hook after each output time, the status.
    subroutine drive(run, s, r, hook)
        class(row_run), intent(inout) :: run
        type(row_setup), intent(in) :: s
        type(row_result), intent(inout) :: r
        class(row_hook), intent(inout), optional :: hook
        type(stopwatch) :: clock
        integer :: k, stat
        character(len=:), allocatable :: warning
        call run%prepare(s, r)
        if (r%status == 'failed') return
        call clock%start()
        call run%start(s, stat)
        call clock%stop()
        do k = 1, size(run%times)
            if (stat < 0) exit
            call clock%start()
            call run%advance(k, stat)
            call clock%stop()
            if (stat < 0) exit   ! a warning (stat > 0) at an output time: x is valid, go on
            if (stat > 0 .and. .not. allocated(warning)) warning = run%solver%message()
            call run%measure(k)
            if (present(hook)) call hook%poll()
        end do
        r%ran = .true.
        r%st = run%solver%statistics()
        r%seconds = clock%seconds()
        r%fields = ' t_end='//num(r%st%t)
        r%status = 'ok'
        r%message = ''
        if (stat < 0) then
            r%status = trim(merge('bad_input', 'failed   ', stat == regdae_err_bad_input))
            r%message = run%solver%message()
            if (len(r%message) == 0) r%message = status_message(stat)
        else if (allocated(warning)) then   ! x was returned, but the tolerance may not be met
            r%status = 'warning'
            r%message = warning
        end if
        call run%solver%destroy()
        call run%fields(s, r)
    end subroutine drive

    !> The output times of a row from t = 0 and the reference states (angle, speed) there
    !! from (s%angle, s%speed), by CVODE at rtol = atol = 1e-13 as the drivers; if CVODE
    !! fails, the row has failed (r%status).
    subroutine reference_states(system, s, times, ref, r)
        class(ode_system), intent(inout) :: system
        type(row_setup), intent(in) :: s
        real(wp), allocatable, intent(out) :: times(:), ref(:, :)
        type(row_result), intent(inout) :: r
        integer :: rstat
        times = output_times(0.0_wp, s%tf, s%nout)
        allocate (ref(2, size(times)))
        call integrate_reference(system, 0.0_wp, [s%angle, s%speed], times, ref, 1.0e-13_wp, 1.0e-13_wp, rstat)
        if (rstat /= 0) then
            r%status = 'failed'
            r%message = 'the reference integration (CVODE) failed, flag '//format_int(rstat)
        end if
    end subroutine reference_states

    ! Example 5.1 as drivers/ex51: t in [-1, 1], against x = t + 1.

    subroutine ex51_prepare(self, s, r)
        class(ex51_run), intent(inout) :: self
        type(row_setup), intent(in) :: s
        type(row_result), intent(inout) :: r
        self%problem = new_ex51(s%orientation)
        self%times = output_times(-1.0_wp, 1.0_wp, s%nout)
    end subroutine ex51_prepare

    subroutine ex51_start(self, s, stat)
        class(ex51_run), intent(inout) :: self
        type(row_setup), intent(in) :: s
        integer, intent(out) :: stat
        call self%solver%init(self%problem, self%times(1), [s%x0], s%opts, stat)
    end subroutine ex51_start

    subroutine ex51_advance(self, k, stat)
        class(ex51_run), intent(inout) :: self
        integer, intent(in) :: k
        integer, intent(out) :: stat
        call self%solver%advance(self%times(k), self%x, self%y, stat)
    end subroutine ex51_advance

    subroutine ex51_measure(self, k)
        class(ex51_run), intent(inout) :: self
        integer, intent(in) :: k
        self%max_err = max(self%max_err, abs(self%x(1) - self%problem%x_exact(self%times(k))))
    end subroutine ex51_measure

    subroutine ex51_fields(self, s, r)
        class(ex51_run), intent(inout) :: self
        type(row_setup), intent(in) :: s
        type(row_result), intent(inout) :: r
        r%fields = r%fields//' max_err_x='//num(self%max_err)
    end subroutine ex51_fields

    ! The slider crank at index 2 or 3 as drivers/ex52: against the reduced ODE on the
    ! physical branch th2 = pi - th1; off_branch when |th1 + th2 - pi| > branch_tol.

    subroutine crank_prepare(self, s, r)
        class(crank_run), intent(inout) :: self
        type(row_setup), intent(in) :: s
        type(row_result), intent(inout) :: r
        type(slider_crank_reduced) :: reduced
        self%crank = new_slider_crank(s%gravity)
        self%crank%analytic_curvature = s%analytic_curvature
        reduced%gravity = s%gravity
        call reference_states(reduced, s, self%times, self%ref, r)
        self%e0 = self%crank%energy([s%angle, pi - s%angle], [s%speed, -s%speed])
    end subroutine crank_prepare

    subroutine crank_start(self, s, stat)
        class(crank_run), intent(inout) :: self
        type(row_setup), intent(in) :: s
        integer, intent(out) :: stat
        self%branch_tol = s%branch_tol
        call self%solver%init(self%crank, 0.0_wp, [s%angle, pi - s%angle], [s%speed, -s%speed], s%opts, stat)
    end subroutine crank_start

    subroutine crank_advance(self, k, stat)
        class(crank_run), intent(inout) :: self
        integer, intent(in) :: k
        integer, intent(out) :: stat
        call self%solver%advance(self%times(k), self%th, self%lam, stat, self%w)
    end subroutine crank_advance

    subroutine crank_measure(self, k)
        class(crank_run), intent(inout) :: self
        integer, intent(in) :: k
        real(wp) :: dev
        associate (th => self%th, ref => self%ref)
            self%max_err = max(self%max_err, abs(th(1) - ref(1, k)), abs(th(2) - (pi - ref(1, k))))
            self%max_g3 = max(self%max_g3, abs(cos(th(1)) + cos(th(2))))
            self%max_de = max(self%max_de, abs(self%crank%energy(th, self%w) - self%e0))
            dev = abs(modulo(th(1) + th(2) - pi + pi, 2*pi) - pi)
        end associate
        if (dev > self%branch_tol .and. self%t_off < 0.0_wp) self%t_off = self%times(k)
        self%max_dev = max(self%max_dev, dev)
    end subroutine crank_measure

    subroutine crank_fields(self, s, r)
        class(crank_run), intent(inout) :: self
        type(row_setup), intent(in) :: s
        type(row_result), intent(inout) :: r
        r%fields = r%fields//' max_err_th='//num(self%max_err)//' max_abs_g3='//num(self%max_g3)// &
                   ' max_energy_err='//num(self%max_de)//' max_branch_dev='//num(self%max_dev)// &
                   ' singular_passes='//format_int(r%st%singular_passes)
        if ((r%status == 'ok' .or. r%status == 'warning') .and. self%t_off >= 0.0_wp) then
            r%status = 'off_branch'
            r%message = 'left the physical branch th2 = pi - th1 at t = '//num(self%t_off)// &
                        ' (max |th1 + th2 - pi| = '//num(self%max_dev)//' > branch_tol = '//num(s%branch_tol)//')'
        end if
    end subroutine crank_fields

    ! The Cartesian pendulum as drivers/pendulum: against the angle ODE.

    subroutine pendulum_prepare(self, s, r)
        class(pendulum_run), intent(inout) :: self
        type(row_setup), intent(in) :: s
        type(row_result), intent(inout) :: r
        type(pendulum_angle) :: angle
        self%problem = new_pendulum(s%gravity)
        angle%gravity = s%gravity
        call reference_states(angle, s, self%times, self%ref, r)
    end subroutine pendulum_prepare

    subroutine pendulum_start(self, s, stat)
        class(pendulum_run), intent(inout) :: self
        type(row_setup), intent(in) :: s
        integer, intent(out) :: stat
        call self%solver%init(self%problem, 0.0_wp, [sin(s%angle), -cos(s%angle)], &
                              s%speed*[cos(s%angle), sin(s%angle)], s%opts, stat)
    end subroutine pendulum_start

    subroutine pendulum_advance(self, k, stat)
        class(pendulum_run), intent(inout) :: self
        integer, intent(in) :: k
        integer, intent(out) :: stat
        call self%solver%advance(self%times(k), self%x, self%y, stat, self%v)
    end subroutine pendulum_advance

    subroutine pendulum_measure(self, k)
        class(pendulum_run), intent(inout) :: self
        integer, intent(in) :: k
        self%max_err = max(self%max_err, maxval(abs(self%x - [sin(self%ref(1, k)), -cos(self%ref(1, k))])))
        self%max_g = max(self%max_g, abs(self%x(1)**2 + self%x(2)**2 - 1.0_wp))
    end subroutine pendulum_measure

    subroutine pendulum_fields(self, s, r)
        class(pendulum_run), intent(inout) :: self
        type(row_setup), intent(in) :: s
        type(row_result), intent(inout) :: r
        r%fields = r%fields//' max_err_pos='//num(self%max_err)//' max_abs_g='//num(self%max_g)
    end subroutine pendulum_fields

    ! The chain as drivers/chain (regdae, not the peer): no reference; the drift and the
    ! energy change.

    subroutine chain_prepare(self, s, r)
        class(chain_run), intent(inout) :: self
        type(row_setup), intent(in) :: s
        type(row_result), intent(inout) :: r
        self%problem = new_chain(s%n_links, s%slider, s%gravity)
        self%problem%joint_mass = s%joint_mass
        self%problem%stiffness = s%stiffness
        self%problem%damping = s%damping
        allocate (self%q0(self%problem%n), self%v0(self%problem%n), self%q(self%problem%n), self%v(self%problem%n), &
                  self%y(self%problem%m))
        call chain_start(self%problem, self%q0, self%v0)
        self%times = output_times(0.0_wp, s%tf, s%nout)
        self%e0 = chain_energy_of(self%problem, self%q0, self%v0)
    end subroutine chain_prepare

    subroutine chain_run_start(self, s, stat)
        class(chain_run), intent(inout) :: self
        type(row_setup), intent(in) :: s
        integer, intent(out) :: stat
        call self%solver%init(self%problem, 0.0_wp, self%q0, self%v0, s%opts, stat)
        self%engine = formulation_name(self%solver%formulation())//'/'//linear_solver_name(self%solver%linear_solver())
    end subroutine chain_run_start

    subroutine chain_advance(self, k, stat)
        class(chain_run), intent(inout) :: self
        integer, intent(in) :: k
        integer, intent(out) :: stat
        call self%solver%advance(self%times(k), self%q, self%y, stat, self%v)
    end subroutine chain_advance

    subroutine chain_measure(self, k)
        class(chain_run), intent(inout) :: self
        integer, intent(in) :: k
        self%energy_change = max(self%energy_change, abs(chain_energy_of(self%problem, self%q, self%v) - self%e0))
        self%max_drift = max(self%max_drift, chain_violation(self%problem, self%q))
    end subroutine chain_measure

    subroutine chain_fields(self, s, r)
        class(chain_run), intent(inout) :: self
        type(row_setup), intent(in) :: s
        type(row_result), intent(inout) :: r
        r%fields = r%fields//' engine='//self%engine//' max_drift='//num(self%max_drift)//' energy_change='// &
                   num(self%energy_change)//' singular_passes='//format_int(r%st%singular_passes)//' sigma_min='// &
                   num(r%st%sigma_min)
    end subroutine chain_fields

end module sweep_rows
