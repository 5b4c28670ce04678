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
    integer, parameter, public :: regdae_err_structure = -115        !! a matrix has an entry outside its declared pattern
    integer, parameter, public :: regdae_err_jacobian = -116         !! a Jacobian disagrees with difference quotients
    integer, parameter, public :: regdae_err_work = -117             !! the work-energy balance of a mechanical problem failed
    integer, parameter, public :: regdae_err_memory = -118           !! the system refused an allocation

    public :: status_message

contains

    !> Short, fixed description of a status code (the solver adds the details:
    !! which quantity, at what time).
    pure function status_message(code) result(msg)
        integer, intent(in) :: code          !! a regdae status code
        character(len=:), allocatable :: msg !! its description
        select case (code)
        case (regdae_success)
            msg = 'success'
        case (regdae_warn_multiplier_undefined)
            msg = 'x is valid, but the multiplier is undefined at this time (singular multiplier equation)'
        case (regdae_warn_unresolved)
            msg = 'the integration error near a singular configuration exceeds resolution_tol times the tolerance'
        case (regdae_err_bad_input)
            msg = 'invalid input'
        case (regdae_err_inconsistent_ic)
            msg = 'inconsistent initial values: the constraint g(x0, t0) = 0 is violated'
        case (regdae_err_user_callback)
            msg = 'a user-supplied routine reported failure'
        case (regdae_err_not_psd)
            msg = 'direct regularization needs GB symmetric positive semidefinite'
        case (regdae_err_singular)
            msg = 'singular matrix'
        case (regdae_err_lapack)
            msg = 'LAPACK error'
        case (regdae_err_sundials)
            msg = 'SUNDIALS setup error'
        case (regdae_err_integration)
            msg = 'the integrator (IDA) failed'
        case (regdae_err_not_initialized)
            msg = 'solver not initialized'
        case (regdae_err_nonfinite)
            msg = 'NaN or Inf encountered'
        case (regdae_err_mass_matrix)
            msg = 'the mass matrix M(q) is not symmetric positive definite'
        case (regdae_err_branch)
            msg = 'the velocity jumped across a singular configuration: the solution probably changed branch'
        case (regdae_err_drift)
            msg = 'the position constraint g(x, t) = 0 drifted beyond drift_tol'
        case (regdae_err_invariant)
            msg = 'the invariant of the problem changed beyond invariant_tol'
        case (regdae_err_structure)
            msg = 'a matrix has a nonzero entry outside the sparsity pattern the problem declared'
        case (regdae_err_work)
            msg = 'the work-energy balance failed: the constraint forces did work (energy gained or lost)'
        case (regdae_err_memory)
            msg = 'out of memory: the system refused an allocation'
        case (regdae_err_jacobian)
            msg = 'a Jacobian (user G, or the Newton matrix from the declared patterns) disagrees with difference quotients'
        case default
            msg = 'unknown status code'
        end select
    end function status_message

end module regdae_status
