!> The routines of a problem given through the C interface: C function pointers
!! of the two kinds declared in `include/regdae.h` and the user's `void *`.
!!
!! ```c
!! typedef int (*regdae_point_fn)(double t, const double *x, double *out, void *user_data);
!! typedef int (*regdae_motion_fn)(double t, const double *x, const double *v, double *out,
!!                                 void *user_data);
!! ```
!! A callback returns 0 on success, > 0 for a recoverable failure and < 0 to stop,
!! exactly like the `stat` of a Fortran problem's routine.
module regdae_c_routines
    use, intrinsic :: iso_c_binding, only: c_int, c_double, c_ptr, c_funptr, c_null_ptr, c_null_funptr, &
                                           c_associated, c_f_procpointer
    use regdae_kinds, only: wp
    use regdae_format, only: format_int, format_real
    use regdae_foreign_problems, only: foreign_routines, n_routines, routine_name
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
    end interface

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
        if (stat /= 0) self%failure = 'the callback '//routine_name(which)//' returned '//format_int(stat)// &
                                      ' at t = '//format_real(t)
    end subroutine c_evaluate

end module regdae_c_routines
