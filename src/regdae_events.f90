!> Root finding (events): user event functions e_i(t, x, v), i = 1 ... n,
!! located on the continuous extension of the integrator in charge, through the
!! integrator interface only (`regdae_integrator`: `interpolate`, `state`,
!! `time`, `last_step`), in the manner of IDA's and DDASKR's root finding.
!!
!! The front (`regdae_solver_front`) drives the integrator one step at a time
!! while events are set (the implicit ones by the one-step mode of `advance`,
!! the others by asking for `step_target`) and, after each step, calls `scan` on
!! the part (t_lo, t_hi] of the step not yet searched. A function *crosses* in
!! (t_lo, t_hi] when its value at t_hi is zero or of the sign opposite to its
!! last nonzero value; a crossing is *reported* when it goes the way the
!! function's direction asks (+1: increasing, from negative; -1: decreasing; 0:
!! both). The earliest reported crossing is bracketed by the Illinois variant
!! of regula falsi on the interpolated values until the bracket is shorter than
!!
!!     t_tol = 4 epsilon max(|t|, |h|)     (h the integrator's last step),
!!
!! and the root is the bracket's right end (where the function has changed
!! sign or is zero). The location is exact for the integrator's continuous
!! extension; its error against the true solution is the interpolant's error
!! over |de/dt| (about the tolerance times the time scale of e). Every function
!! reported at that root (within t_tol) is marked +1 (increasing) or -1
!! (decreasing) in `found`. A function zero at t0 is not reported there: its
!! sign is taken from its first nonzero value (IDA's rule); likewise, after a
!! root where a function is exactly zero, its next nonzero value sets its sign
!! without a report, so a zero is reported once.
!!
!! Where the integrator took more than one step since the last scan (its first
!! steps from a start, or a step a thousand times smaller than the one before),
!! no continuous extension covers (t_lo, t_b], t_b = t - |h|: a crossing there
!! is located by the secant between the values at t_lo and t_b, and a stop there
!! returns the state interpolated linearly between the two (an error up to the
!! length of that stretch).
!!
!! The front tells the search where the integrator left its state after each
!! advance (`state_after`: a one-step advance's step end, or the output time it
!! interpolated at): the values there are taken without interpolating again.
module regdae_events
    use, intrinsic :: iso_c_binding, only: c_double
    use regdae_kinds, only: wp
    use regdae_status, only: regdae_success, regdae_err_user_callback, regdae_err_bad_input, regdae_err_integration
    use regdae_format, only: format_real, format_int
    use regdae_integrator, only: integrator
    use regdae_augmented_system, only: augmented_system
    implicit none
    private

    !> The user's event functions: extend this type (its components carry the
    !! parameters) and give `values`.
    type, abstract, public :: event_functions
    contains
        !> e(i) = e_i(t, x, v), i = 1 ... n (n set with `set_events`).
        procedure(event_values), deferred :: values
    end type event_functions

    abstract interface
        !> The event functions at (t, x, v): v is x' for problems of order >= 2 and
        !! empty (size 0) for first-order ones (e_i(t, x)). Leave stat at 0; set it
        !! nonzero if e cannot be evaluated (the advance fails with
        !! regdae_err_user_callback).
        subroutine event_values(self, t, x, v, e, stat)
            import :: event_functions, wp
            class(event_functions), intent(inout) :: self
            real(wp), intent(in) :: t, x(:), v(:)
            real(wp), intent(out) :: e(:)
            integer, intent(inout) :: stat
        end subroutine event_values
    end interface

    !> The events of one solver: the functions, their filters, the search's state.
    type, public :: event_locator
        class(event_functions), allocatable :: fn   !! the user's functions (a copy)
        integer :: n = 0                        !! number of functions (0: no events)
        integer, allocatable :: direction(:)    !! +1, -1 or 0 per function
        logical, allocatable :: stops(:)        !! stop at the root (true) or log and continue
        integer, allocatable :: found(:)        !! at the last root: +1 / -1 reported there, 0 not
        integer, allocatable :: counts(:)       !! roots reported so far per function
        integer :: total = 0                    !! roots reported so far
        real(wp) :: t_root = 0.0_wp             !! the last root
        logical :: primed = .false.             !! the search has its start (t_lo, e_lo)
        real(wp) :: t_lo = 0.0_wp               !! searched up to here
        real(wp), allocatable :: e_lo(:), e_hi(:), e_mid(:), e_b(:)
        integer, allocatable :: sgn(:)          !! sign of the last nonzero value (0: none yet)
        real(wp), allocatable :: x(:), v(:)     !! x and v at an evaluation (the augmented formulation's)
        real(wp), allocatable :: u_lo(:)        !! the integrator's state at t_u_lo: t_lo where that is the end
        real(wp) :: t_u_lo = -huge(1.0_wp)      !! of a step (the secant needs it only after more than one step)
        real(wp) :: t_state = -huge(1.0_wp)     !! the time of the integrator's state and slope (the last
                                                !! interpolation; -huge: not known)
        real(wp) :: t_step_end = -huge(1.0_wp)  !! the integrator's state (not necessarily its slope) is the
                                                !! end of the step it just took, here (-huge: not so)
        integer, allocatable :: sgn_lo(:)       !! the signs at the search's start (locate's scratch)
        character(len=:), allocatable :: log    !! lines for the solver's event log
    contains
        !> Set (n > 0) or clear (n = 0) the functions.
        procedure :: set => locator_set
        !> The search starts at t (the integrator's state there).
        procedure :: prime => locator_prime
        !> The next time to ask of the integrator: about one step on.
        procedure :: step_target => locator_step_target
        !> Search (t_lo, t_hi] of the integrator's last step; stop = a stopping root found.
        procedure :: scan => locator_scan
        !> Where the integrator's state is after an advance (the search evaluates there
        !! without interpolating).
        procedure :: state_after => locator_state_after
    end type event_locator

    integer, parameter :: max_iterations = 200

contains

    !> Set n event functions fn with their directions and stop flags (defaults:
    !! 0 and true); n = 0 clears the events.
    subroutine locator_set(self, fn, n, stat, msg, direction, stop)
        class(event_locator), intent(inout) :: self
        class(event_functions), intent(in) :: fn
        integer, intent(in) :: n
        integer, intent(out) :: stat
        character(len=:), allocatable, intent(out) :: msg
        integer, intent(in), optional :: direction(:)
        logical, intent(in), optional :: stop(:)
        stat = regdae_err_bad_input
        msg = ''
        if (n < 0) then
            msg = 'set_events: n = '//format_int(n)//' must be >= 0'
            return
        end if
        if (present(direction)) then
            if (size(direction) /= n) then
                msg = 'set_events: direction must have length n = '//format_int(n)
                return
            end if
            if (any(abs(direction) > 1)) then
                msg = 'set_events: each direction must be -1 (decreasing), 0 (both) or +1 (increasing)'
                return
            end if
        end if
        if (present(stop)) then
            if (size(stop) /= n) then
                msg = 'set_events: stop must have length n = '//format_int(n)
                return
            end if
        end if
        if (allocated(self%fn)) deallocate (self%fn)
        self%n = n
        self%total = 0
        self%primed = .false.
        self%log = ''
        stat = regdae_success
        if (n == 0) return
        allocate (self%fn, source=fn)
        self%direction = spread(0, 1, n)
        if (present(direction)) self%direction = direction
        self%stops = spread(.true., 1, n)
        if (present(stop)) self%stops = stop
        self%found = spread(0, 1, n)
        self%counts = spread(0, 1, n)
        self%e_lo = spread(0.0_wp, 1, n)
        self%e_hi = self%e_lo
        self%e_mid = self%e_lo
        self%e_b = self%e_lo
        self%sgn = spread(0, 1, n)
        self%sgn_lo = self%sgn
        if (allocated(self%x)) deallocate (self%x, self%v)
    end subroutine locator_set

    !> Start the search at t from the integrator's state (which is at t; nx
    !! positions; v taken when `with_v`): each function's sign is its value's
    !! (none if zero).
    subroutine locator_prime(self, stepper, t, nx, with_v, stat, msg)
        class(event_locator), intent(inout) :: self
        class(integrator), intent(inout), target :: stepper
        real(wp), intent(in) :: t
        integer, intent(in) :: nx
        logical, intent(in) :: with_v
        integer, intent(out) :: stat
        character(len=:), allocatable, intent(out) :: msg
        real(c_double), pointer :: u(:)
        if (allocated(self%x)) then
            if (size(self%x) /= nx .or. size(self%v) /= merge(nx, 0, with_v)) deallocate (self%x, self%v)
        end if
        if (.not. allocated(self%x)) allocate (self%x(nx), self%v(merge(nx, 0, with_v)))
        msg = ''
        call evaluate(self, stepper, t, self%e_lo, stat, msg, at_state=.true.)
        if (stat /= regdae_success) return
        self%sgn = int(sign(1.0_wp, self%e_lo))
        where (self%e_lo == 0.0_wp) self%sgn = 0
        self%t_lo = t
        u => stepper%state()
        self%u_lo = u
        self%t_u_lo = t
        self%found = 0
        self%primed = .true.
    end subroutine locator_prime

    !> The output time to ask of an integrator without a one-step mode (`steps_singly`)
    !! at time t (its last step h) so that it takes about one step: t + |h|/1000, or, before its first step, a
    !! millionth of the way to tout (at least 1000 time resolutions); never
    !! beyond tout. With `land` (stop_at_output), tout itself once t + |h|
    !! reaches it (the integrator's step ends there).
    real(wp) function locator_step_target(self, t, h, tout, resolution, land) result(t_ask)
        class(event_locator), intent(in) :: self
        real(wp), intent(in) :: t, h, tout, resolution
        logical, intent(in) :: land
        real(wp) :: delta
        t_ask = tout
        if (land .and. t + abs(h) >= tout .and. abs(h) > 0.0_wp) return
        if (abs(h) > 0.0_wp) then
            delta = 1.0e-3_wp*abs(h)
        else
            delta = 1.0e-6_wp*(tout - t)
        end if
        t_ask = min(tout, t + max(delta, 1.0e3_wp*resolution))
    end function locator_step_target

    !> After an advance of the integrator that stopped at t_stop, its last step ending
    !! at t_end: where its state is. `reached` (outcome_reached): the integrators
    !! interpolate at a t_stop inside their last step (state and slope there); in
    !! one-step mode (`single`) with a step taken (t_end beyond t_before, the time before
    !! the advance), at t_stop = t_end the state is the step's own (its slope need not be
    !! the continuous extension's). Otherwise unknown.
    subroutine locator_state_after(self, reached, single, t_before, t_stop, t_end)
        class(event_locator), intent(inout) :: self
        logical, intent(in) :: reached, single
        real(wp), intent(in) :: t_before   !! read with `single` only
        real(wp), intent(in) :: t_stop, t_end
        self%t_state = -huge(1.0_wp)
        self%t_step_end = -huge(1.0_wp)
        if (.not. reached) return
        if (t_stop < t_end) then
            self%t_state = t_stop
        else if (single) then
            if (t_end > t_before) self%t_step_end = t_stop
        end if
    end subroutine locator_state_after

    !> Search (t_lo, t_hi] of the integrator's last step for roots. Roots that only
    !! continue are logged and counted; at the first root with a function that
    !! stops, `stop` is true, t_root and found() are set and the integrator's state
    !! is at t_root. Without a stopping root the search has
    !! reached t_hi (the integrator's state is left where the last evaluation was).
    !! msg is allocated only on a failure.
    subroutine locator_scan(self, stepper, t_hi, stop, stat, msg)
        class(event_locator), intent(inout) :: self
        class(integrator), intent(inout), target :: stepper
        real(wp), intent(in) :: t_hi
        logical, intent(out) :: stop
        integer, intent(out) :: stat
        character(len=:), allocatable, intent(out) :: msg
        real(wp) :: t_b, h, t_end, t_step
        stop = .false.
        stat = regdae_success
        if (.not. (t_hi > self%t_lo)) return
        h = abs(stepper%last_step())
        t_step = stepper%time()
        t_b = t_step - h
        if (t_b > self%t_lo .and. t_b < t_hi) then
            ! no continuous extension covers (t_lo, t_b]: the secant there
            call evaluate(self, stepper, t_b, self%e_b, stat, msg)
            if (stat /= regdae_success) return
            call search(t_b, .false.)
            if (stop .or. stat /= regdae_success) return
        end if
        call evaluate(self, stepper, t_hi, self%e_hi, stat, msg)
        if (stat /= regdae_success) return
        if (.not. any_reported(self%sgn, self%e_hi)) then   ! no crossing (most steps): on to t_hi
            call accept(self, stepper, t_hi, self%e_hi, t_step, stat, msg)
            return
        end if
        self%e_b(:) = self%e_hi
        call search(t_hi, .true.)
    contains
        ! (t_lo, t_end], the values at t_end in e_b: locate, log, repeat past
        ! continuing roots; dense: the integrator interpolates inside.
        subroutine search(t_end_, dense)
            real(wp), intent(in) :: t_end_
            logical, intent(in) :: dense
            logical :: any_root
            real(wp) :: t_before
            t_end = t_end_
            do
                t_before = self%t_lo
                call locate(self, stepper, t_end, h, dense, any_root, stat, msg)
                if (stat /= regdae_success) return
                if (.not. any_root) exit
                if (.not. (self%t_lo > t_before)) exit   ! no progress (a secant's root at t_lo)
                call note_root(self)
                if (any(self%found /= 0 .and. self%stops)) then
                    stop = .true.
                    return
                end if
                if (.not. (t_end > self%t_lo)) exit
            end do
            call accept(self, stepper, t_end, self%e_b, t_step, stat, msg)
        end subroutine search
    end subroutine locator_scan

    ! Locate the first reported crossing in (t_lo, t_end] (values at t_end in
    ! e_b); on a root, t_lo moves to it (its values and state there).
    subroutine locate(self, stepper, t_end, h, dense, any_root, stat, msg)
        type(event_locator), intent(inout) :: self
        class(integrator), intent(inout), target :: stepper
        real(wp), intent(in) :: t_end, h
        logical, intent(in) :: dense
        logical, intent(out) :: any_root
        integer, intent(out) :: stat
        character(len=:), allocatable, intent(inout) :: msg
        real(wp) :: ta, tb, tm, ttol, fa, fb, frac, best
        integer :: i, k, side, last_side
        logical :: moved
        real(c_double), pointer :: u(:)
        stat = regdae_success
        any_root = .false.
        self%e_hi(:) = self%e_b
        if (.not. any_reported(self%sgn, self%e_hi)) return
        associate (s_lo => self%sgn_lo)
            s_lo = self%sgn
            any_root = .true.
            ta = self%t_lo
            tb = t_end
            ttol = 4*epsilon(1.0_wp)*max(abs(tb), h)
            self%e_mid = self%e_lo   ! the values at ta (where a function was zero: its sign)
            where (self%e_mid == 0.0_wp) self%e_mid = s_lo*tiny(1.0_wp)
            if (.not. dense) then
                ! the secant of the earliest crossing
                tm = tb
                do i = 1, self%n
                    if (.not. reported_one(i, s_lo(i), self%e_hi(i))) cycle
                    tm = min(tm, tb - (tb - ta)*self%e_hi(i)/(self%e_hi(i) - self%e_mid(i)))
                end do
                tm = max(ta, min(tb, tm))
                self%found = 0
                do i = 1, self%n
                    if (.not. reported_one(i, s_lo(i), self%e_hi(i))) cycle
                    if (abs(tb - (tb - ta)*self%e_hi(i)/(self%e_hi(i) - self%e_mid(i)) - tm) <= ttol) &
                        self%found(i) = -s_lo(i)
                end do
                ! the state and the values there, linear between ta and tb
                self%e_hi = self%e_mid + (tm - ta)/(tb - ta)*(self%e_hi - self%e_mid)
                call stepper%interpolate(tb, stat)
                u => stepper%state()
                ! (the state at ta is kept where ta ended a step, as it does here: else the state at tb)
                if (self%t_u_lo == ta) u = self%u_lo + (tm - ta)/(tb - ta)*(u - self%u_lo)
                call stepper%state_written()
                self%t_state = tm
                self%t_step_end = -huge(1.0_wp)
                stat = regdae_success
                call move_lo(self, stepper, tm, self%e_hi)
                return
            end if
            side = 0
            last_side = 0
            fa = 1.0_wp   ! the Illinois weights of the retained ends
            fb = 1.0_wp
            do k = 1, max_iterations
                if (tb - ta <= ttol) exit
                ! the crossing whose secant root comes first
                best = 0.0_wp
                do i = 1, self%n
                    if (.not. reported_one(i, s_lo(i), self%e_hi(i))) cycle
                    frac = abs(fb*self%e_hi(i))/abs(fb*self%e_hi(i) - fa*self%e_mid(i))
                    best = max(best, frac)
                end do
                tm = tb - (tb - ta)*min(max(best, 0.0_wp), 1.0_wp)
                tm = max(ta + 0.5_wp*ttol, min(tb - 0.5_wp*ttol, tm))
                call evaluate(self, stepper, tm, self%e_lo, stat, msg)   ! e_lo: scratch here
                if (stat /= regdae_success) return
                moved = any_reported(s_lo, self%e_lo)
                if (moved) then   ! a crossing in (ta, tm]: tm is the new right end
                    tb = tm
                    self%e_hi = self%e_lo
                    side = 1
                else              ! none: tm is the new left end
                    ta = tm
                    self%e_mid = self%e_lo
                    where (self%e_mid == 0.0_wp) self%e_mid = s_lo*tiny(1.0_wp)
                    side = 2
                end if
                ! Illinois: an end retained again counts half as much again
                if (side /= last_side) then
                    fa = 1.0_wp
                    fb = 1.0_wp
                else if (side == 1) then
                    fa = 0.5_wp*fa
                else
                    fb = 0.5_wp*fb
                end if
                last_side = side
            end do
            self%found = 0
            do i = 1, self%n
                if (reported_one(i, s_lo(i), self%e_hi(i))) self%found(i) = -s_lo(i)
            end do
            ! the state at the root (the last evaluation may have been at the left end)
            call evaluate(self, stepper, tb, self%e_hi, stat, msg)
            if (stat /= regdae_success) return
            call move_lo(self, stepper, tb, self%e_hi)
        end associate
    contains
        logical function reported_one(i, s, e)
            integer, intent(in) :: i, s
            real(wp), intent(in) :: e
            reported_one = reported(s, e)
            if (reported_one .and. self%direction(i) /= 0) reported_one = (self%direction(i) == -s)
        end function reported_one
    end subroutine locate

    ! Does any function cross (signs s before, values e now)?
    pure logical function any_reported(s, e)
        integer, intent(in) :: s(:)
        real(wp), intent(in) :: e(:)
        integer :: j
        any_reported = .true.
        do j = 1, size(s)
            if (reported(s(j), e(j))) return
        end do
        any_reported = .false.
    end function any_reported

    ! Does a function of sign s (0: none yet) cross to the value e?
    elemental logical function reported(s, e)
        integer, intent(in) :: s
        real(wp), intent(in) :: e
        reported = .false.
        if (s == 0) return
        reported = (e == 0.0_wp .or. int(sign(1.0_wp, e)) /= s)
    end function reported

    ! The search has reached t with the values e there: the signs follow (a
    ! function zero at a reported root has none until its next nonzero value).
    subroutine move_lo(self, stepper, t, e)
        type(event_locator), intent(inout) :: self
        class(integrator), intent(inout), target :: stepper
        real(wp), intent(in) :: t, e(:)
        integer :: i
        do i = 1, self%n
            if (self%found(i) /= 0) then
                ! a reported function: its new side, or none until its next nonzero value
                ! (zero here, or the secant's root still on the old side)
                self%sgn(i) = 0
                if (e(i) /= 0.0_wp .and. int(sign(1.0_wp, e(i))) == self%found(i)) self%sgn(i) = self%found(i)
            else if (e(i) /= 0.0_wp) then
                self%sgn(i) = int(sign(1.0_wp, e(i)))
            end if
        end do
        self%e_lo = e
        self%t_lo = t
        call keep_state(self, stepper, t, stepper%time())   ! the state is at t
    end subroutine move_lo

    ! u_lo: the integrator's state at t (t_lo), where t ends its step: the search covers the
    ! rest of a step before the integrator steps on, so only a step's end can start a
    ! stretch of more than one step (the secant's); in place where the size is the same.
    subroutine keep_state(self, stepper, t, t_step)
        type(event_locator), intent(inout) :: self
        class(integrator), intent(inout), target :: stepper
        real(wp), intent(in) :: t, t_step   !! t_step: the end of the integrator's last step
        real(c_double), pointer :: u(:)
        if (t < t_step) return
        u => stepper%state()
        if (size(self%u_lo) == size(u)) then
            self%u_lo(:) = u
        else
            self%u_lo = u
        end if
        self%t_u_lo = t
    end subroutine keep_state

    ! No reported root in (t_lo, t], the values e at t: the search moves there.
    subroutine accept(self, stepper, t, e, t_step, stat, msg)
        type(event_locator), intent(inout) :: self
        class(integrator), intent(inout), target :: stepper
        real(wp), intent(in) :: t, e(:)
        real(wp), intent(in) :: t_step   ! the end of the integrator's last step
        integer, intent(out) :: stat
        character(len=:), allocatable, intent(inout) :: msg
        integer :: i
        stat = regdae_success
        do i = 1, self%n
            if (e(i) /= 0.0_wp) self%sgn(i) = int(sign(1.0_wp, e(i)))
        end do
        self%e_lo(:) = e
        self%t_lo = t
        if (self%t_state /= t .and. self%t_step_end /= t) then
            call stepper%interpolate(t, stat)
            self%t_state = t
            self%t_step_end = -huge(1.0_wp)
            if (stat /= regdae_success) then
                stat = regdae_err_integration
                msg = 'events: the integrator could not interpolate at t = '//format_real(t, 16)
                return
            end if
        end if
        call keep_state(self, stepper, t, t_step)
    end subroutine accept

    ! A root at t_lo with found(): counted and logged.
    subroutine note_root(self)
        type(event_locator), intent(inout) :: self
        integer :: i
        self%t_root = self%t_lo
        do i = 1, self%n
            if (self%found(i) == 0) cycle
            self%counts(i) = self%counts(i) + 1
            self%total = self%total + 1
            self%log = self%log//'t = '//format_real(self%t_root, 16)//': event '//format_int(i)// &
                       trim(merge(' (increasing)', ' (decreasing)', self%found(i) > 0))// &
                       trim(merge(', stop    ', ', continue', self%stops(i)))//new_line('a')
        end do
    end subroutine note_root

    ! The event functions at t of the integrator's continuous extension (into x, v).
    subroutine evaluate(self, stepper, t, e, stat, msg, at_state)
        type(event_locator), intent(inout) :: self
        class(integrator), intent(inout), target :: stepper
        real(wp), intent(in) :: t
        real(wp), intent(out) :: e(:)
        integer, intent(out) :: stat
        character(len=:), allocatable, intent(inout) :: msg
        logical, intent(in), optional :: at_state   !! the integrator's state is at t already
        stat = regdae_success
        ! the state is at t already: given, the last interpolation's, or the step's end
        if (present(at_state)) then
            self%t_state = t
        else if (t /= self%t_state .and. t /= self%t_step_end) then
            call stepper%interpolate(t, stat)
            self%t_state = t
            self%t_step_end = -huge(1.0_wp)
        end if
        if (stat /= regdae_success) then
            stat = regdae_err_integration
            msg = 'events: the integrator could not interpolate at t = '//format_real(t, 16)
            return
        end if
        stat = 0
        call unpack_values(self, stepper, t, e, stat)
        if (stat /= 0) then
            stat = regdae_err_user_callback
            msg = 'the event functions reported failure at t = '//format_real(t, 16)
        end if
    end subroutine evaluate

    ! The event functions at t of the integrator's state: x and v its own parts (the
    ! augmented formulation's unpacked into x, v).
    subroutine unpack_values(self, stepper, t, e, stat)
        type(event_locator), intent(inout) :: self
        class(integrator), intent(inout), target :: stepper
        real(wp), intent(in) :: t
        real(wp), intent(out) :: e(:)
        integer, intent(inout) :: stat
        real(c_double), pointer :: u(:)
        type(augmented_system), pointer :: sys
        integer :: nx
        u => stepper%state()
        nx = size(self%x)
        sys => stepper%augmented()
        if (associated(sys)) then
            call sys%unpack(u, u, q=self%x)
            if (size(self%v) > 0) call sys%unpack(u, u, v=self%v)
            call self%fn%values(t, self%x, self%v, e, stat)
        else
            call self%fn%values(t, u(1:nx), u(nx + 1:nx + size(self%v)), e, stat)
        end if
    end subroutine unpack_values

end module regdae_events
