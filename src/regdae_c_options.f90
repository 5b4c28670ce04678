!> The C interface's option entries (include/regdae.h: regdae_set_option,
!! regdae_set_real_option, regdae_set_int_option, regdae_set_atol_vector,
!! regdae_get_options): every option reaches the drivers' key=value parser.
module regdae_c_options
    use, intrinsic :: iso_c_binding, only: c_int, c_double, c_ptr, c_associated, c_f_pointer
    use regdae_status, only: regdae_success, regdae_err_bad_input
    use regdae_format, only: format_int, format_real
    use regdae_options, only: solver_options, set_option, option_auto, method_name, integrator_name, formulation_name, &
                              lsq_name, exclusion_name, excluded_name, linear_solver_name
    use regdae_c_records, only: c_options, to_c_options
    use regdae_c_strings, only: c_string
    use regdae_parse, only: has_outer_blank
    use regdae_c_session, only: c_session, open_session, record, refuse, set_message
    implicit none
    private

    public :: regdae_set_option, regdae_set_real_option, regdae_set_int_option, regdae_get_options, &
              regdae_set_atol_vector

contains

    !> `int regdae_set_option(solver, key, value)`: the drivers' key=value parser.
    integer(c_int) function regdae_set_option(handle, key, value) bind(C, name='regdae_set_option')
        type(c_ptr), value :: handle, key, value
        type(c_session), pointer :: s
        regdae_set_option = regdae_err_bad_input
        if (.not. open_session(handle, s)) return
        if (.not. (c_associated(key) .and. c_associated(value))) then
            regdae_set_option = refuse(s, 'regdae_set_option: key or value is NULL')
        else
            regdae_set_option = set_text_option(s, c_string(key), c_string(value), 'regdae_set_option')
        end if
    end function regdae_set_option

    !> `int regdae_set_atol_vector(solver, atol, n)`: the absolute tolerance per
    !! component of the state for the next regdae_init (n: the state's length, 2n for
    !! second-order and mechanical problems, positions then velocities; checked by
    !! regdae_init); atol NULL and n 0: back to the atol option.
    integer(c_int) function regdae_set_atol_vector(handle, atol, n) bind(C, name='regdae_set_atol_vector')
        type(c_ptr), value :: handle, atol
        integer(c_int), value :: n
        type(c_session), pointer :: s
        real(c_double), pointer :: values(:)
        regdae_set_atol_vector = regdae_err_bad_input
        if (.not. open_session(handle, s)) return
        if (.not. c_associated(atol) .and. n == 0) then
            if (allocated(s%atol_vector)) deallocate (s%atol_vector)
        else if (.not. c_associated(atol) .or. n < 1) then
            regdae_set_atol_vector = refuse(s, 'regdae_set_atol_vector: atol is NULL or n = '//format_int(n)// &
                                            ' < 1 (NULL and 0 clear the vector)')
            return
        else
            call c_f_pointer(atol, values, [n])
            s%atol_vector = values
        end if
        regdae_set_atol_vector = regdae_success
        call set_message(s, '')
    end function regdae_set_atol_vector

    !> `int regdae_set_real_option(solver, key, value)`: a real option by its key
    !! (REGDAE_AUTO: `auto`); the value reaches the parser with 17 significant
    !! digits, read back exactly.
    integer(c_int) function regdae_set_real_option(handle, key, value) bind(C, name='regdae_set_real_option')
        type(c_ptr), value :: handle, key
        real(c_double), value :: value
        type(c_session), pointer :: s
        regdae_set_real_option = regdae_err_bad_input
        if (.not. open_session(handle, s)) return
        if (.not. c_associated(key)) then
            regdae_set_real_option = refuse(s, 'regdae_set_real_option: key is NULL')
        else if (value == option_auto) then
            regdae_set_real_option = set_text_option(s, c_string(key), 'auto', 'regdae_set_real_option')
        else
            regdae_set_real_option = set_text_option(s, c_string(key), format_real(value, 16), 'regdae_set_real_option')
        end if
    end function regdae_set_real_option

    !> `int regdae_set_int_option(solver, key, value)`: an integer option (index,
    !! max_steps, max_order), a code (method, formulation, lsq, exclusion, excluded, integrator,
    !! linear_solver: REGDAE_*) or a switch (stop_at_output, curvature,
    !! check_jacobians, pass_check, error_estimate: 0 or 1) by its key.
    integer(c_int) function regdae_set_int_option(handle, key, value) bind(C, name='regdae_set_int_option')
        type(c_ptr), value :: handle, key
        integer(c_int), value :: value
        character(len=*), parameter :: who = 'regdae_set_int_option'
        type(c_session), pointer :: s
        character(len=:), allocatable :: name, text
        regdae_set_int_option = regdae_err_bad_input
        if (.not. open_session(handle, s)) return
        if (.not. c_associated(key)) then
            regdae_set_int_option = refuse(s, who//': key is NULL')
            return
        end if
        name = c_string(key)
        select case (name)
        case ('method'); text = method_name(value)
        case ('formulation'); text = formulation_name(value)
        case ('lsq'); text = lsq_name(value)
        case ('exclusion'); text = exclusion_name(value)
        case ('excluded'); text = excluded_name(value)
        case ('integrator'); text = integrator_name(value)
        case ('linear_solver'); text = linear_solver_name(value)
        case ('stop_at_output', 'curvature', 'check_jacobians', 'pass_check', 'error_estimate')
            text = 'unknown'
            if (value == 0 .or. value == 1) text = trim(merge('yes', 'no ', value == 1))
        case default; text = format_int(value)
        end select
        if (text == 'unknown') then
            regdae_set_int_option = refuse(s, who//': '//format_int(value)//' is not a value of option "'//name//'"')
        else
            regdae_set_int_option = set_text_option(s, name, text, who)
        end if
    end function regdae_set_int_option

    !> `int regdae_get_options(const regdae_solver *solver, regdae_options *options)`:
    !! the options in force after a successful regdae_init (`auto` resolved), else those set.
    integer(c_int) function regdae_get_options(handle, out) bind(C, name='regdae_get_options')
        type(c_ptr), value :: handle, out
        type(c_session), pointer :: s
        type(c_options), pointer :: c
        type(solver_options) :: opts
        regdae_get_options = regdae_err_bad_input
        if (.not. open_session(handle, s)) return
        if (.not. c_associated(out)) then
            regdae_get_options = refuse(s, 'regdae_get_options: options is NULL')
            return
        end if
        opts = s%opts
        if (s%initialized) then
            opts = s%solver%options()
            opts%formulation = s%solver%formulation()
            opts%linear_solver = s%solver%linear_solver()
            if (s%solver%lsq_method() /= 0) opts%lsq = s%solver%lsq_method()
            ! integrator: options() gives the one in charge (never auto)
        end if
        call c_f_pointer(out, c)
        c = to_c_options(opts)
        regdae_get_options = record(s, regdae_success, '')
    end function regdae_get_options

    ! An option from its text (the drivers' parser); the message names the caller. A
    ! C string has its own length: a blank around the key or the value is refused (the
    ! parser, written for blank-padded Fortran texts, would ignore it).
    integer(c_int) function set_text_option(s, key, value, who) result(status)
        type(c_session), intent(inout) :: s
        character(len=*), intent(in) :: key, value, who
        character(len=:), allocatable :: msg
        integer :: stat
        if (has_outer_blank(key) .or. has_outer_blank(value)) then
            status = refuse(s, who//': key "'//key//'" or value "'//value//'" begins or ends with a blank: '// &
                            'keys and values are read exactly as given')
            return
        end if
        call set_option(s%opts, key, value, stat, msg)
        if (stat /= regdae_success) msg = who//': '//msg
        status = record(s, stat, msg)
    end function set_text_option

end module regdae_c_options
