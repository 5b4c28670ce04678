!> Status codes of regdae and their messages.
!!
!! The sign convention is IDA's: 0 is success, a positive code a warning (the
!! result is usable, see the code), a negative code an unrecoverable failure. User callbacks follow it too: leave `stat` at 0 on
!! success, set it > 0 for a recoverable failure (the integrator retries with a
!! smaller step) and < 0 for an unrecoverable one.
module regdae_status
    implicit none
    private

    integer, parameter, public :: regdae_success = 0                 !! success
    integer, parameter, public :: regdae_warn_multiplier_undefined = 1  !! x(tout) is valid, y(tout) is not (NaN)
    integer, parameter, public :: regdae_warn_unresolved = 2         !! x(tout) is the integrator's, but near a singular
                                                                     !! configuration its error exceeds resolution_tol rtol
    integer, parameter, public :: regdae_root_found = 3              !! advance returned at a root of an event function
                                                                     !! that stops (x there; which ones: the roots array)
    integer, parameter, public :: regdae_err_bad_input = -101        !! invalid argument or option
    integer, parameter, public :: regdae_err_inconsistent_ic = -102  !! x(t0) violates g(x, t0) = 0
    integer, parameter, public :: regdae_err_user_callback = -103    !! a user routine reported failure
    integer, parameter, public :: regdae_err_not_psd = -104          !! direct method: GB not symmetric PSD
    integer, parameter, public :: regdae_err_singular = -105         !! a matrix that must be invertible is singular
    integer, parameter, public :: regdae_err_lapack = -106           !! LAPACK reported an argument error
    integer, parameter, public :: regdae_err_sundials = -107         !! SUNDIALS object creation or setup failed
    integer, parameter, public :: regdae_err_integration = -108      !! IDA failed during the integration
    integer, parameter, public :: regdae_err_not_initialized = -109  !! solver used before a successful init
    integer, parameter, public :: regdae_err_nonfinite = -110        !! NaN or Inf in a computed quantity
    integer, parameter, public :: regdae_err_mass_matrix = -111      !! M(q) not symmetric positive definite
    integer, parameter, public :: regdae_err_branch = -112           !! the velocity jumped across a singular interval
    integer, parameter, public :: regdae_err_drift = -113            !! the position constraint drifted beyond drift_tol
    integer, parameter, public :: regdae_err_invariant = -114        !! the problem's invariant changed beyond invariant_tol
    integer, parameter, public :: regdae_err_structure = -115        !! a matrix has an entry outside its declared pattern, or a
                                                                     !! mass matrix declared constant varies
    integer, parameter, public :: regdae_err_jacobian = -116         !! a Jacobian disagrees with difference quotients
    integer, parameter, public :: regdae_err_work = -117             !! the work-energy balance of a mechanical problem failed
    integer, parameter, public :: regdae_err_memory = -118           !! the system refused an allocation

    public :: status_message, reported_length

    !> The length of an entry of `status_texts` (the longest text, its NUL and a spare).
    integer, parameter, public :: status_text_len = 106
    !> Every status code; `status_texts` has its description at the same position.
    integer, parameter, public :: status_codes(22) = [regdae_success, regdae_warn_multiplier_undefined, regdae_warn_unresolved, &
        regdae_err_bad_input, regdae_err_inconsistent_ic, regdae_err_user_callback, regdae_err_not_psd, regdae_err_singular, &
        regdae_err_lapack, regdae_err_sundials, regdae_err_integration, regdae_err_not_initialized, regdae_err_nonfinite, &
        regdae_err_mass_matrix, regdae_err_branch, regdae_err_drift, regdae_err_invariant, regdae_err_structure, &
        regdae_err_work, regdae_err_memory, regdae_err_jacobian, regdae_root_found]
    !> The fixed description of each code of `status_codes`, NUL-terminated (the C interface
    !! returns them as static texts: `regdae_status_string`) and blank-padded after the NUL.
    character(len=status_text_len), parameter, public :: status_texts(22) = [character(len=status_text_len) :: &
        'success'//achar(0), &
        'x is valid, but the multiplier is undefined at this time (singular multiplier equation)'//achar(0), &
        'the integration error near a singular configuration exceeds resolution_tol times the tolerance'//achar(0), &
        'invalid input'//achar(0), &
        'inconsistent initial values: the constraint g(x0, t0) = 0 is violated'//achar(0), &
        'a user-supplied routine reported failure'//achar(0), &
        'direct regularization needs GB symmetric positive semidefinite'//achar(0), &
        'singular matrix'//achar(0), &
        'LAPACK error'//achar(0), &
        'SUNDIALS setup error'//achar(0), &
        'the integrator (IDA) failed'//achar(0), &
        'solver not initialized'//achar(0), &
        'NaN or Inf encountered'//achar(0), &
        'the mass matrix M(q) is not symmetric positive definite'//achar(0), &
        'the velocity jumped across a singular configuration: the solution probably changed branch'//achar(0), &
        'the position constraint g(x, t) = 0 drifted beyond drift_tol'//achar(0), &
        'the invariant of the problem changed beyond invariant_tol'//achar(0), &
        'a nonzero entry outside the sparsity pattern the problem declared, or an M declared constant varies'//achar(0), &
        'the work-energy balance failed: the constraint forces did work (energy gained or lost)'//achar(0), &
        'out of memory: the system refused an allocation'//achar(0), &
        'a Jacobian (user G, or the Newton matrix from the declared patterns) disagrees with difference quotients'// &
        achar(0), &
        'an event function that stops has a root: the state is returned there'//achar(0)]
    !> The description of a code that is none of `status_codes`, NUL-terminated.
    character(len=*), parameter, public :: unknown_status_text = 'unknown status code (not a regdae status)'//achar(0)

contains

    !> Short, fixed description of a status code (the solver adds the details:
    !! which quantity, at what time); `unknown status code (not a regdae status)`
    !! for a code that is none of `status_codes`.
    pure function status_message(code) result(msg)
        integer, intent(in) :: code                                     !! a regdae status code
        character(len=index(status_text(code), achar(0)) - 1) :: msg   !! its description
        msg = status_text(code)   ! up to the NUL
    end function status_message

    !> The length of `message` where it is allocated, else of `status_message(code)`: the
    !! length of a solver's `message()`, which says one or the other.
    pure integer function reported_length(message, code)
        character(len=:), allocatable, intent(in) :: message
        integer, intent(in) :: code
        if (allocated(message)) then
            reported_length = len(message)
        else
            reported_length = len(status_message(code))
        end if
    end function reported_length

    ! The NUL-terminated description of a code, padded with blanks (status_message's
    ! result has this automatic length, not a deferred one: doc/methods.md, "No global state").
    pure function status_text(code) result(text)
        integer, intent(in) :: code
        character(len=max(status_text_len, len(unknown_status_text))) :: text
        integer :: k
        text = unknown_status_text
        do k = 1, size(status_codes)
            if (status_codes(k) == code) text = status_texts(k)
        end do
    end function status_text

end module regdae_status
