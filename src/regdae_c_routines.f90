!> The routines of a problem given through the C interface: C function pointers
!! of the two kinds declared in `include/regdae.h` and the user's `void *`.
!!
!! ```c
!! typedef int (*regdae_point_fn)(double t, const double *x, double *out, void *user_data);
!! typedef int (*regdae_motion_fn)(double t, const double *x, const double *v, double *out,
!!                                 void *user_data);
!! ```
!! A callback returns 0 on success, > 0 for a recoverable failure and < 0 to stop,
!! exactly like the `stat` of a Fortran problem's routine. And the event functions
!! of `regdae_set_events` (`c_events`, an extension of `event_functions`):
!!
!! ```c
!! typedef int (*regdae_event_fn)(double t, const double *x, const double *v, double *e,
!!                                void *user_data);
!! ```
module regdae_c_routines
    use, intrinsic :: iso_c_binding, only: c_int, c_double, c_ptr, c_funptr, c_null_ptr, c_null_funptr, &
                                           c_associated, c_f_procpointer, c_loc
    use regdae_kinds, only: wp
    use regdae_format, only: format_int, format_real
    use regdae_foreign_problems, only: foreign_routines, n_routines, routine_name
    use regdae_events, only: event_functions
    implicit none
    private

    abstract interface
        !> A routine of (t, x): f, B, g, G, g_t (first order), g, G, g_t, M, and the
        !! values of M and G in pattern order.
        integer(c_int) function point_callback(t, x, val, user_data) bind(C)
            import :: c_int, c_double, c_ptr
            real(c_double), value :: t              !! time
            real(c_double), intent(in) :: x(*)      !! position (state), length n
            real(c_double), intent(out) :: val(*)   !! the value; matrices column by column
            type(c_ptr), value :: user_data         !! the user's pointer, passed through
        end function point_callback

        !> A routine of (t, x, v): f and B (second order), the forces, the curvature, the invariant.
        integer(c_int) function motion_callback(t, x, v, val, user_data) bind(C)
            import :: c_int, c_double, c_ptr
            real(c_double), value :: t
            real(c_double), intent(in) :: x(*)      !! position, length n
            real(c_double), intent(in) :: v(*)      !! velocity, length n
            real(c_double), intent(out) :: val(*)
            type(c_ptr), value :: user_data
        end function motion_callback

        !> The event functions e(1:n) at (t, x, v); v NULL for a first-order problem.
        integer(c_int) function event_callback(t, x, v, e, user_data) bind(C)
            import :: c_int, c_double, c_ptr
            real(c_double), value :: t
            real(c_double), intent(in) :: x(*)      !! position, length n
            type(c_ptr), value :: v                 !! velocity, length n, or NULL
            real(c_double), intent(out) :: e(*)     !! the event functions' values
            type(c_ptr), value :: user_data
        end function event_callback
    end interface

    !> The event functions of `regdae_set_events`: a C callback and its user_data.
    type, extends(event_functions), public :: c_events
        type(c_funptr) :: callback = c_null_funptr
        type(c_ptr) :: user_data = c_null_ptr
        integer :: returned = 0   !! the callback's last nonzero return
    contains
        procedure :: values => c_event_values
    end type c_events

    !> C callbacks by routine code (a null pointer: not given) and the user's data.
    type, extends(foreign_routines), public :: c_routines
        type(c_funptr) :: callbacks(n_routines) = c_null_funptr   !! by routine code
        type(c_ptr) :: user_data = c_null_ptr                      !! passed to every callback
    contains
        procedure :: has => c_has
        procedure :: evaluate => c_evaluate
    end type c_routines

contains

    logical function c_has(self, which)
        class(c_routines), intent(in) :: self
        integer, intent(in) :: which
        c_has = c_associated(self%callbacks(which))
    end function c_has

    subroutine c_evaluate(self, which, t, x, val, stat, v)
        class(c_routines), intent(inout) :: self
        integer, intent(in) :: which
        real(wp), intent(in) :: t
        real(wp), intent(in) :: x(*)
        real(wp), intent(out) :: val(*)
        integer, intent(inout) :: stat
        real(wp), intent(in), optional :: v(*)
        procedure(point_callback), pointer :: point
        procedure(motion_callback), pointer :: motion
        if (present(v)) then
            call c_f_procpointer(self%callbacks(which), motion)
            stat = int(motion(t, x, v, val, self%user_data))
        else
            call c_f_procpointer(self%callbacks(which), point)
            stat = int(point(t, x, val, self%user_data))
        end if
        if (stat /= 0) self%failure = 'the callback '//trim(routine_name(which))//' returned '//format_int(stat)// &
                                      ' at t = '//format_real(t)
    end subroutine c_evaluate

    subroutine c_event_values(self, t, x, v, e, stat)
        class(c_events), intent(inout) :: self
        real(wp), intent(in) :: t, x(:), v(:)
        real(wp), intent(out) :: e(:)
        integer, intent(inout) :: stat
        procedure(event_callback), pointer :: events
        real(c_double), target :: vt(size(v))
        type(c_ptr) :: vp
        vp = c_null_ptr
        if (size(v) > 0) then
            vt = v
            vp = c_loc(vt)
        end if
        call c_f_procpointer(self%callback, events)
        stat = int(events(t, x, vp, e, self%user_data))
        if (stat /= 0) self%returned = stat
    end subroutine c_event_values

end module regdae_c_routines
