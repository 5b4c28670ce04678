!> The session behind a C handle (`regdae_solver *` in include/regdae.h) and the
!! helpers every C entry shares: open a handle, keep its message, turn a solver status
!! into a C status. The entries themselves are in regdae_c_api (handles, problems,
!! integration), regdae_c_options and regdae_c_events.
module regdae_c_session
    use, intrinsic :: iso_c_binding, only: c_int, c_char, c_ptr, c_null_char, c_associated, c_f_pointer
    use regdae_kinds, only: wp
    use regdae_status, only: regdae_success, regdae_err_bad_input, regdae_err_user_callback
    use regdae_options, only: solver_options
    use regdae_sparsity, only: sparsity_pattern
    use regdae_mechanical_problem, only: mechanical_structure
    use regdae_solver_trust, only: regdae_solver
    use regdae_c_routines, only: c_routines
    implicit none
    private

    !> The kinds of problem a session holds (none set yet, regdae_set_first_order,
    !! regdae_set_second_order, regdae_set_mechanical).
    integer, parameter, public :: kind_none = 0, kind_first_order = 1, kind_second_order = 2, kind_mechanical = 3

    !> What a handle points at: the solver, the options, the C callbacks, the declared
    !! patterns and the last message.
    type, public :: c_session
        type(regdae_solver) :: solver
        type(solver_options) :: opts
        type(c_routines) :: routines
        integer :: kind = kind_none
        integer :: n = 0, m = 0
        logical :: initialized = .false.             ! the last regdae_init succeeded
        type(sparsity_pattern) :: patterns(4)        ! by pattern code
        logical :: declared(4) = .false.
        type(mechanical_structure) :: structure      ! what the last regdae_init declared (the problem points here)
        character(kind=c_char), allocatable :: message(:)   ! NUL-terminated
        real(wp), allocatable :: atol_vector(:)      ! regdae_set_atol_vector (unallocated: the atol option)
    end type c_session

    public :: open_session, record, refuse, set_message, solver_result

contains

    !> The session behind a handle; false for NULL.
    logical function open_session(handle, s)
        type(c_ptr), intent(in) :: handle
        type(c_session), pointer, intent(out) :: s
        s => null()
        open_session = c_associated(handle)
        if (open_session) call c_f_pointer(handle, s)
    end function open_session

    !> Keep `text` as the handle's message; return `code`.
    integer(c_int) function record(s, code, text)
        type(c_session), intent(inout) :: s
        integer, intent(in) :: code
        character(len=*), intent(in) :: text
        call set_message(s, text)
        record = int(code, c_int)
    end function record

    !> Bad input: REGDAE_ERR_BAD_INPUT with the message.
    integer(c_int) function refuse(s, text)
        type(c_session), intent(inout) :: s
        character(len=*), intent(in) :: text
        refuse = record(s, regdae_err_bad_input, text)
    end function refuse

    !> Keep `text`, NUL-terminated, as the handle's message (for regdae_message).
    subroutine set_message(s, text)
        type(c_session), intent(inout) :: s
        character(len=*), intent(in) :: text
        integer :: k
        if (allocated(s%message)) deallocate (s%message)
        allocate (s%message(len(text) + 1))
        do k = 1, len(text)
            s%message(k) = text(k:k)
        end do
        s%message(len(text) + 1) = c_null_char
    end subroutine set_message

    !> The status of a solver call and its message; a failing callback is named.
    integer(c_int) function solver_result(s, stat)
        type(c_session), intent(inout) :: s
        integer, intent(in) :: stat
        character(len=:), allocatable :: text
        text = ''
        if (stat /= regdae_success) text = s%solver%message()
        if (stat == regdae_err_user_callback .and. allocated(s%routines%failure)) &
            text = text//' ('//s%routines%failure//')'
        solver_result = record(s, stat, text)
    end function solver_result

end module regdae_c_session
