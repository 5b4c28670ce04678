!> The C interface's event entries (include/regdae.h: regdae_set_events,
!! regdae_get_roots; doc/api.md, Events): the C event callback with its user_data
!! handed to the solver's root finding, and the roots of the last stop.
module regdae_c_events
    use, intrinsic :: iso_c_binding, only: c_int, c_ptr, c_funptr, c_associated, c_f_pointer
    use regdae_status, only: regdae_success, regdae_err_bad_input
    use regdae_format, only: format_int
    use regdae_c_routines, only: c_events
    use regdae_c_session, only: c_session, open_session, record, refuse, solver_result
    implicit none
    private

    public :: regdae_set_events, regdae_get_roots

contains

    !> `int regdae_set_events(solver, n_events, events, direction, stop, user_data)`: event
    !! functions (doc/api.md, Events); direction and stop may be NULL (0: both; 1: stop).
    integer(c_int) function regdae_set_events(handle, n, events, direction, stop, user_data) &
        bind(C, name='regdae_set_events')
        type(c_ptr), value :: handle, direction, stop, user_data
        integer(c_int), value :: n
        type(c_funptr), value :: events
        type(c_session), pointer :: s
        type(c_events) :: ev
        integer(c_int), pointer :: ds(:), ss(:)
        integer :: stat
        regdae_set_events = regdae_err_bad_input
        if (.not. open_session(handle, s)) return
        if (n > 0 .and. .not. c_associated(events)) then
            regdae_set_events = refuse(s, 'regdae_set_events: events is NULL with n_events = '//format_int(n))
            return
        end if
        ev%callback = events
        ev%user_data = user_data
        if (n < 0) then
            call s%solver%set_events(ev, int(n), stat)
        else if (c_associated(direction) .and. c_associated(stop)) then
            call c_f_pointer(direction, ds, [n])
            call c_f_pointer(stop, ss, [n])
            call s%solver%set_events(ev, int(n), stat, direction=int(ds), stop=(ss /= 0))
        else if (c_associated(direction)) then
            call c_f_pointer(direction, ds, [n])
            call s%solver%set_events(ev, int(n), stat, direction=int(ds))
        else if (c_associated(stop)) then
            call c_f_pointer(stop, ss, [n])
            call s%solver%set_events(ev, int(n), stat, stop=(ss /= 0))
        else
            call s%solver%set_events(ev, int(n), stat)
        end if
        regdae_set_events = solver_result(s, stat)
    end function regdae_set_events

    !> `int regdae_get_roots(const regdae_solver *solver, int *roots, int n_events)`: after
    !! REGDAE_ROOT_FOUND, +1 / -1 / 0 per event function.
    integer(c_int) function regdae_get_roots(handle, roots, n) bind(C, name='regdae_get_roots')
        type(c_ptr), value :: handle, roots
        integer(c_int), value :: n
        type(c_session), pointer :: s
        integer(c_int), pointer :: rs(:)
        integer, allocatable :: found(:)
        regdae_get_roots = regdae_err_bad_input
        if (.not. open_session(handle, s)) return
        found = s%solver%roots()
        if (.not. c_associated(roots) .or. n /= size(found)) then
            regdae_get_roots = refuse(s, 'regdae_get_roots: roots must be an array of n_events = '// &
                                      format_int(size(found))//' ints')
            return
        end if
        call c_f_pointer(roots, rs, [n])
        rs = int(found, c_int)
        regdae_get_roots = record(s, regdae_success, '')
    end function regdae_get_roots

end module regdae_c_events
