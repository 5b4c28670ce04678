!> The C interface (`include/regdae.h`): a thin layer over the Fortran API in the
!! manner of minpack's `minpack_capi`. This module: the handles and messages, the
!! problem and its patterns, the integration and its results; the options are in
!! regdae_c_options, the events in regdae_c_events, the session behind a handle in
!! regdae_c_session.
!!
!! A `regdae_solver *` is the address of a `c_session`: the Fortran solver, the
!! options, the C callbacks with their `void *user_data`, the declared patterns
!! and the last message, NUL-terminated for `regdae_message`. Nothing lives
!! outside the session, so any number of handles can be used side by side.
!! Every function checks its pointers and sizes first and answers bad input with
!! `REGDAE_ERR_BAD_INPUT` and a message naming the argument (a NULL handle: the
!! status alone, there is nowhere to keep a message).
module regdae_c_api
    use, intrinsic :: iso_c_binding, only: c_int, c_double, c_char, c_ptr, c_funptr, c_null_ptr, c_null_char, &
                                           c_null_funptr, c_associated, c_f_pointer, c_loc
    use regdae_status, only: regdae_success, regdae_err_bad_input, regdae_err_not_initialized, &
                             status_codes, status_texts, status_text_len, unknown_status_text
    use regdae_format, only: format_int
    use regdae_sparsity, only: sparsity_pattern, pattern_from_entries, dense_pattern
    use regdae_mechanical_problem, only: mechanical_structure
    use regdae_foreign_problems, only: foreign_first_order, foreign_second_order, foreign_mechanical, routine_f, &
                                       routine_b, routine_g, routine_gx, routine_gt, routine_curvature, &
                                       routine_invariant, routine_mass, routine_forces, routine_mass_values, &
                                       routine_gx_values
    use regdae_c_records, only: c_stats, to_c_stats
    use regdae_c_session, only: c_session, kind_none, kind_first_order, kind_second_order, kind_mechanical, &
                                open_session, record, refuse, set_message, solver_result
    implicit none
    private

    !> The patterns a mechanical problem may declare (REGDAE_PATTERN_* in include/regdae.h).
    integer, parameter, public :: pattern_mass = 1        !! M, n x n
    integer, parameter, public :: pattern_constraint = 2  !! G, m x n
    integer, parameter, public :: pattern_force_q = 3     !! d(f - M a)/dq, n x n
    integer, parameter, public :: pattern_force_v = 4     !! df/dq', n x n

    !> The version of regdae: CMakeLists.txt's project(VERSION), REGDAE_VERSION_* in
    !! include/regdae.h (ctest capi.version checks all three against each other).
    integer, parameter, public :: regdae_version_major = 0, regdae_version_minor = 1, regdae_version_patch = 0

    ! The texts C receives as `const char *` that outlive every call: the status
    ! descriptions, the version and the message of a NULL handle. Initialized here and
    ! never written (protected: no procedure assigns them), so any number of threads
    ! may read them at once; the only module variables of the library, because C needs
    ! an address that stays valid and a parameter has none.
    character(len=status_text_len, kind=c_char), target, protected :: c_status_texts(size(status_codes)) = status_texts
    character(len=len(unknown_status_text), kind=c_char), target, protected :: c_unknown_status = unknown_status_text
    character(len=6, kind=c_char), target, protected :: c_version = '0.1.0'//c_null_char
    character(len=*, kind=c_char), parameter :: null_handle_text = &
        'regdae: no solver (a NULL handle: regdae_create returned NULL, or regdae_destroy has freed it)'//c_null_char
    character(len=len(null_handle_text), kind=c_char), target, protected :: c_null_handle = null_handle_text

    public :: regdae_create, regdae_destroy, regdae_message, regdae_status_string, regdae_version
    public :: regdae_set_first_order, regdae_set_second_order, regdae_set_mechanical, regdae_set_curvature, &
              regdae_set_invariant, regdae_set_pattern, regdae_set_pattern_values, &
              regdae_pattern_position
    public :: regdae_init, regdae_advance, regdae_get_statistics, regdae_error_estimate

contains

    ! --- handles and messages ---------------------------------------------------------

    !> `regdae_solver *regdae_create(void)`: a new handle (NULL if memory is exhausted).
    type(c_ptr) function regdae_create() bind(C, name='regdae_create')
        type(c_session), pointer :: s
        integer :: ierr
        regdae_create = c_null_ptr
        allocate (s, stat=ierr)
        if (ierr /= 0) return
        call set_message(s, '')
        regdae_create = c_loc(s)
    end function regdae_create

    !> `void regdae_destroy(regdae_solver **solver)`: free the handle and set *solver to NULL.
    subroutine regdae_destroy(handle_ref) bind(C, name='regdae_destroy')
        type(c_ptr), value :: handle_ref   !! address of the handle (NULL, or *handle_ref NULL: nothing to do)
        type(c_ptr), pointer :: handle
        type(c_session), pointer :: s
        if (.not. c_associated(handle_ref)) return
        call c_f_pointer(handle_ref, handle)
        if (.not. c_associated(handle)) return
        call c_f_pointer(handle, s)
        call s%solver%destroy()
        ! gfortran 12 leaves the patterns inside `structure` (allocatable components
        ! two levels down, next to the finalizable solver) allocated when the session is
        ! deallocated (valgrind: definitely lost): free them first.
        s%structure = mechanical_structure()
        deallocate (s)
        handle = c_null_ptr
    end subroutine regdae_destroy

    !> `const char *regdae_message(const regdae_solver *solver)`: the message of the
    !! last call on the handle ("" after success); for a NULL handle a static text
    !! saying so (never NULL).
    type(c_ptr) function regdae_message(handle) bind(C, name='regdae_message')
        type(c_ptr), value :: handle
        type(c_session), pointer :: s
        regdae_message = c_loc(c_null_handle)
        if (.not. c_associated(handle)) return
        call c_f_pointer(handle, s)
        regdae_message = c_loc(s%message(1))
    end function regdae_message

    !> `const char *regdae_status_string(int status)`: the fixed description of a
    !! status code (`status_message` of the Fortran API), a static text; for a code
    !! that is no regdae status, a static text saying so (never NULL).
    type(c_ptr) function regdae_status_string(code) bind(C, name='regdae_status_string')
        integer(c_int), value :: code
        integer :: k
        regdae_status_string = c_loc(c_unknown_status)
        do k = 1, size(status_codes)
            if (status_codes(k) == code) regdae_status_string = c_loc(c_status_texts(k))
        end do
    end function regdae_status_string

    !> `const char *regdae_version(int *major, int *minor, int *patch)`: the library's
    !! version as a static text ("0.1.0"), and its three numbers in the ints that are
    !! not NULL.
    type(c_ptr) function regdae_version(major, minor, patch) bind(C, name='regdae_version')
        type(c_ptr), value :: major, minor, patch
        call put(major, regdae_version_major)
        call put(minor, regdae_version_minor)
        call put(patch, regdae_version_patch)
        regdae_version = c_loc(c_version)
    contains
        subroutine put(p, value)
            type(c_ptr), intent(in) :: p
            integer, intent(in) :: value
            integer(c_int), pointer :: target_int
            if (.not. c_associated(p)) return
            call c_f_pointer(p, target_int)
            target_int = int(value, c_int)
        end subroutine put
    end function regdae_version

    ! --- the problem ------------------------------------------------------------------

    !> `int regdae_set_first_order(solver, n, m, f, b, g, gx, gt, user_data)`.
    integer(c_int) function regdae_set_first_order(handle, n, m, f, b, g, gx, gt, user_data) &
        bind(C, name='regdae_set_first_order')
        type(c_ptr), value :: handle, user_data
        integer(c_int), value :: n, m
        type(c_funptr), value :: f, b, g, gx, gt
        regdae_set_first_order = set_problem(handle, kind_first_order, n, m, [f, b, g, gx, gt], &
                                             [routine_f, routine_b, routine_g, routine_gx, routine_gt], &
                                             user_data, 'regdae_set_first_order')
    end function regdae_set_first_order

    !> `int regdae_set_second_order(solver, n, m, f, b, g, gx, gt, user_data)`.
    integer(c_int) function regdae_set_second_order(handle, n, m, f, b, g, gx, gt, user_data) &
        bind(C, name='regdae_set_second_order')
        type(c_ptr), value :: handle, user_data
        integer(c_int), value :: n, m
        type(c_funptr), value :: f, b, g, gx, gt
        regdae_set_second_order = set_problem(handle, kind_second_order, n, m, [f, b, g, gx, gt], &
                                              [routine_f, routine_b, routine_g, routine_gx, routine_gt], &
                                              user_data, 'regdae_set_second_order')
    end function regdae_set_second_order

    !> `int regdae_set_mechanical(solver, n, m, mass, forces, g, gx, gt, user_data)`.
    integer(c_int) function regdae_set_mechanical(handle, n, m, mass, forces, g, gx, gt, user_data) &
        bind(C, name='regdae_set_mechanical')
        type(c_ptr), value :: handle, user_data
        integer(c_int), value :: n, m
        type(c_funptr), value :: mass, forces, g, gx, gt
        regdae_set_mechanical = set_problem(handle, kind_mechanical, n, m, [mass, forces, g, gx, gt], &
                                            [routine_mass, routine_forces, routine_g, routine_gx, routine_gt], &
                                            user_data, 'regdae_set_mechanical')
    end function regdae_set_mechanical

    !> `int regdae_set_curvature(solver, curvature)`: second-order and mechanical problems.
    integer(c_int) function regdae_set_curvature(handle, fn) bind(C, name='regdae_set_curvature')
        type(c_ptr), value :: handle
        type(c_funptr), value :: fn
        regdae_set_curvature = set_optional_routine(handle, routine_curvature, fn, kind_second_order, &
                                                    'regdae_set_curvature')
    end function regdae_set_curvature

    !> `int regdae_set_invariant(solver, invariant)`: second-order and mechanical problems.
    integer(c_int) function regdae_set_invariant(handle, fn) bind(C, name='regdae_set_invariant')
        type(c_ptr), value :: handle
        type(c_funptr), value :: fn
        regdae_set_invariant = set_optional_routine(handle, routine_invariant, fn, kind_second_order, &
                                                    'regdae_set_invariant')
    end function regdae_set_invariant

    !> `int regdae_set_pattern_values(solver, which, values)`: the routine that gives
    !! the entries of M (REGDAE_PATTERN_MASS) or G (REGDAE_PATTERN_CONSTRAINT) in
    !! pattern order; NULL: taken from the dense callback.
    integer(c_int) function regdae_set_pattern_values(handle, which, fn) bind(C, name='regdae_set_pattern_values')
        type(c_ptr), value :: handle
        integer(c_int), value :: which
        type(c_funptr), value :: fn
        type(c_session), pointer :: s
        regdae_set_pattern_values = regdae_err_bad_input
        if (which == pattern_mass .or. which == pattern_constraint) then
            regdae_set_pattern_values = set_optional_routine(handle, merge(routine_mass_values, routine_gx_values, &
                                                                           which == pattern_mass), &
                                                             fn, kind_mechanical, 'regdae_set_pattern_values')
        else if (open_session(handle, s)) then
            regdae_set_pattern_values = refuse(s, 'regdae_set_pattern_values: which = '//format_int(which)// &
                                               ' is neither REGDAE_PATTERN_MASS nor REGDAE_PATTERN_CONSTRAINT')
        end if
    end function regdae_set_pattern_values

    !> `int regdae_set_pattern(solver, which, nnz, rows, cols)`: declare the pattern
    !! `which` of a mechanical problem from nnz (row, column) pairs, 0-based.
    integer(c_int) function regdae_set_pattern(handle, which, nnz, rows, cols) bind(C, name='regdae_set_pattern')
        type(c_ptr), value :: handle, rows, cols
        integer(c_int), value :: which, nnz
        character(len=*), parameter :: who = 'regdae_set_pattern: '
        type(c_session), pointer :: s
        integer(c_int), pointer :: r(:), c(:)
        integer, allocatable :: row(:), col(:)   ! 1-based
        integer :: nrows
        regdae_set_pattern = regdae_err_bad_input
        if (.not. open_session(handle, s)) return
        if (s%kind /= kind_mechanical) then
            regdae_set_pattern = refuse(s, who//'patterns are for mechanical problems: call regdae_set_mechanical first')
            return
        else if (which < pattern_mass .or. which > pattern_force_v) then
            regdae_set_pattern = refuse(s, who//'which = '//format_int(which)//' is not a REGDAE_PATTERN_* code')
            return
        else if (nnz < 0) then
            regdae_set_pattern = refuse(s, who//'nnz = '//format_int(nnz)//' is negative')
            return
        end if
        allocate (row(0), col(0))
        if (nnz > 0) then
            if (.not. (c_associated(rows) .and. c_associated(cols))) then
                regdae_set_pattern = refuse(s, who//'rows or cols is NULL')
                return
            end if
            call c_f_pointer(rows, r, [nnz])
            call c_f_pointer(cols, c, [nnz])
            row = r + 1
            col = c + 1
        end if
        nrows = merge(s%m, s%n, which == pattern_constraint)
        if (any(row < 1 .or. row > nrows) .or. any(col < 1 .or. col > s%n)) then
            regdae_set_pattern = refuse(s, who//'an entry lies outside the '//format_int(nrows)//' x '// &
                                        format_int(s%n)//' matrix (indices are 0-based)')
            return
        end if
        s%patterns(which) = pattern_from_entries(nrows, s%n, row, col)
        s%declared(which) = .true.
        regdae_set_pattern = record(s, regdae_success, '')
    end function regdae_set_pattern

    !> `int regdae_pattern_position(solver, which, i, j)`: the 0-based index of entry
    !! (i, j) in the values of pattern `which` (pattern order), -1 if absent.
    integer(c_int) function regdae_pattern_position(handle, which, i, j) bind(C, name='regdae_pattern_position')
        type(c_ptr), value :: handle
        integer(c_int), value :: which, i, j
        type(c_session), pointer :: s
        regdae_pattern_position = -1
        if (.not. open_session(handle, s)) return
        if (which < pattern_mass .or. which > pattern_force_v) then
            call set_message(s, 'regdae_pattern_position: which = '//format_int(which)//' is not a REGDAE_PATTERN_* code')
            return
        end if
        if (s%declared(which)) regdae_pattern_position = s%patterns(which)%position(i + 1, j + 1) - 1
        call set_message(s, '')
    end function regdae_pattern_position

    ! --- integration ------------------------------------------------------------------

    !> `int regdae_init(solver, t0, x0, nx0, v0, nv0)`: start the problem at t0 (v0:
    !! second-order and mechanical problems; NULL for first-order ones).
    integer(c_int) function regdae_init(handle, t0, x0, nx0, v0, nv0) bind(C, name='regdae_init')
        type(c_ptr), value :: handle, x0, v0
        real(c_double), value :: t0
        integer(c_int), value :: nx0, nv0
        character(len=*), parameter :: who = 'regdae_init: '
        type(c_session), pointer :: s
        real(c_double), pointer :: x(:), v(:)
        type(foreign_first_order) :: first
        type(foreign_second_order) :: second
        type(foreign_mechanical) :: mechanical
        integer :: stat
        character(len=:), allocatable :: problem_msg

        regdae_init = regdae_err_bad_input
        if (.not. open_session(handle, s)) return
        s%initialized = .false.
        if (s%kind == kind_none) then
            problem_msg = 'no problem: call regdae_set_first_order, regdae_set_second_order or regdae_set_mechanical first'
        else
            call array_problem(x0, nx0, s%n, 'x0', problem_msg)
        end if
        if (len(problem_msg) == 0) then
            if (s%kind /= kind_first_order) then
                call array_problem(v0, nv0, s%n, 'v0', problem_msg)
            else if (c_associated(v0) .or. nv0 /= 0) then
                problem_msg = 'v0 is for second-order and mechanical problems: pass NULL and 0 for a first-order one'
            end if
        end if
        if (len(problem_msg) > 0) then
            regdae_init = refuse(s, who//problem_msg)
            return
        end if
        call c_f_pointer(x0, x, [nx0])
        if (allocated(s%routines%failure)) deallocate (s%routines%failure)
        select case (s%kind)
        case (kind_first_order)
            first%n = s%n
            first%m = s%m
            first%routines => s%routines
            call s%solver%init(first, t0, x, s%opts, stat, atol_vector=s%atol_vector)   ! unallocated: absent
        case (kind_second_order)
            call c_f_pointer(v0, v, [nv0])
            second%n = s%n
            second%m = s%m
            second%routines => s%routines
            call s%solver%init(second, t0, x, v, s%opts, stat, atol_vector=s%atol_vector)   ! unallocated: absent
        case default
            call c_f_pointer(v0, v, [nv0])
            mechanical%n = s%n
            mechanical%m = s%m
            mechanical%routines => s%routines
            call declare_structure(s, mechanical)
            call s%solver%init(mechanical, t0, x, v, s%opts, stat, atol_vector=s%atol_vector)   ! unallocated: absent
        end select
        s%initialized = (stat == regdae_success)
        regdae_init = solver_result(s, stat)
    end function regdae_init

    !> `int regdae_advance(solver, tout, x, nx, y, ny, v, nv)`: integrate to tout;
    !! x(tout) always, y (lambda) and v when not NULL.
    integer(c_int) function regdae_advance(handle, tout, x, nx, y, ny, v, nv) bind(C, name='regdae_advance')
        type(c_ptr), value :: handle, x, y, v
        real(c_double), value :: tout
        integer(c_int), value :: nx, ny, nv
        character(len=*), parameter :: who = 'regdae_advance: '
        type(c_session), pointer :: s
        real(c_double), pointer :: xs(:), ys(:), vs(:)
        character(len=:), allocatable :: problem_msg
        integer :: stat
        logical :: want_y, want_v

        regdae_advance = regdae_err_bad_input
        if (.not. open_session(handle, s)) return
        if (.not. s%initialized) then
            regdae_advance = record(s, regdae_err_not_initialized, who//'no successful regdae_init on this handle')
            return
        end if
        want_y = c_associated(y) .or. ny /= 0
        want_v = c_associated(v) .or. nv /= 0
        call array_problem(x, nx, s%n, 'x', problem_msg)
        if (len(problem_msg) == 0 .and. want_y) call array_problem(y, ny, s%m, 'y', problem_msg)
        if (len(problem_msg) == 0 .and. want_v) then
            if (s%kind == kind_first_order) then
                problem_msg = 'v is for second-order and mechanical problems: pass NULL and 0 for a first-order one'
            else
                call array_problem(v, nv, s%n, 'v', problem_msg)
            end if
        end if
        if (len(problem_msg) > 0) then
            regdae_advance = refuse(s, who//problem_msg)
            return
        end if
        call c_f_pointer(x, xs, [nx])
        if (allocated(s%routines%failure)) deallocate (s%routines%failure)
        if (want_y .and. want_v) then
            call c_f_pointer(y, ys, [ny])
            call c_f_pointer(v, vs, [nv])
            call s%solver%advance(tout, xs, ys, stat, v=vs)
        else if (want_y) then
            call c_f_pointer(y, ys, [ny])
            call s%solver%advance(tout, xs, ys, stat)
        else if (want_v) then
            call c_f_pointer(v, vs, [nv])
            call s%solver%advance(tout, xs, stat=stat, v=vs)
        else
            call s%solver%advance(tout, xs, stat=stat)
        end if
        regdae_advance = solver_result(s, stat)
    end function regdae_advance

    !> `int regdae_get_statistics(const regdae_solver *solver, regdae_stats *stats)`.
    integer(c_int) function regdae_get_statistics(handle, out) bind(C, name='regdae_get_statistics')
        type(c_ptr), value :: handle, out
        type(c_session), pointer :: s
        type(c_stats), pointer :: c
        regdae_get_statistics = regdae_err_bad_input
        if (.not. open_session(handle, s)) return
        if (.not. c_associated(out)) then
            regdae_get_statistics = refuse(s, 'regdae_get_statistics: stats is NULL')
            return
        end if
        call c_f_pointer(out, c)
        c = to_c_stats(s%solver%statistics())
        regdae_get_statistics = record(s, regdae_success, '')
    end function regdae_get_statistics

    !> `int regdae_error_estimate(const regdae_solver *solver, double *e, int n)`: with the
    !! option error_estimate, e = x_companion - x at the last output (n entries, the size of
    !! x); REGDAE_ERR_BAD_INPUT (e filled with NaN) when there is no estimate.
    integer(c_int) function regdae_error_estimate(handle, e, n) bind(C, name='regdae_error_estimate')
        type(c_ptr), value :: handle, e
        integer(c_int), value :: n
        type(c_session), pointer :: s
        real(c_double), pointer :: values(:)
        regdae_error_estimate = regdae_err_bad_input
        if (.not. open_session(handle, s)) return
        if (.not. c_associated(e) .or. n < 1) then
            regdae_error_estimate = refuse(s, 'regdae_error_estimate: e is NULL or n = '//format_int(n)//' < 1')
            return
        end if
        call c_f_pointer(e, values, [n])
        if (.not. s%solver%error_estimate(values)) then
            regdae_error_estimate = refuse(s, 'regdae_error_estimate: no estimate (the option error_estimate is off, '// &
                                           'no output yet, n is not the size of x, or the companion failed)')
            return
        end if
        regdae_error_estimate = record(s, regdae_success, '')
    end function regdae_error_estimate

    ! What is wrong with the array argument `name` (address p, length given) that
    ! must have length `expected`; '' if nothing.
    subroutine array_problem(p, given, expected, name, text)
        type(c_ptr), intent(in) :: p
        integer(c_int), intent(in) :: given
        integer, intent(in) :: expected
        character(len=*), intent(in) :: name
        character(len=:), allocatable, intent(out) :: text
        text = ''
        if (.not. c_associated(p)) then
            text = name//' is NULL'
        else if (given /= expected) then
            text = name//' has length '//format_int(given)//'; the problem needs '//format_int(expected)
        end if
    end subroutine array_problem

    ! Set the problem of a handle: its kind, sizes, required callbacks (`fns`: the
    ! four required ones and g_t, which may be NULL) and user data.
    integer(c_int) function set_problem(handle, kind, n, m, fns, codes, user_data, who) result(status)
        type(c_ptr), intent(in) :: handle, user_data
        integer, intent(in) :: kind
        integer(c_int), intent(in) :: n, m
        type(c_funptr), intent(in) :: fns(5)
        integer, intent(in) :: codes(5)
        character(len=*), intent(in) :: who
        type(c_session), pointer :: s
        integer :: k
        status = regdae_err_bad_input
        if (.not. open_session(handle, s)) return
        if (n < 1 .or. m < 0 .or. m > n) then
            status = refuse(s, who//': sizes must satisfy 1 <= n and 0 <= m <= n (n = '//format_int(n)//', m = '// &
                            format_int(m)//')')
            return
        end if
        do k = 1, 4
            if (.not. c_associated(fns(k))) then
                status = refuse(s, who//': the callback '//trim(callback_argument(kind, k))//' is NULL (only gt may be)')
                return
            end if
        end do
        call s%solver%destroy()
        s%initialized = .false.
        s%kind = kind
        s%n = n
        s%m = m
        s%declared = .false.
        s%routines%callbacks = c_null_funptr
        s%routines%callbacks(codes) = fns
        s%routines%user_data = user_data
        status = record(s, regdae_success, '')
    end function set_problem

    ! The name of the k-th callback argument of regdae_set_<kind>, padded with blanks.
    pure function callback_argument(kind, k) result(name)
        integer, intent(in) :: kind, k
        character(len=6) :: name
        character(len=6), parameter :: first(4) = [character(len=6) :: 'f', 'b', 'g', 'gx']
        character(len=6), parameter :: mechanical(4) = [character(len=6) :: 'mass', 'forces', 'g', 'gx']
        if (kind == kind_mechanical) then
            name = mechanical(k)
        else
            name = first(k)
        end if
    end function callback_argument

    ! Set (fn) or remove (NULL) an optional callback of a problem of kind `needs`
    ! (second order: also mechanical).
    integer(c_int) function set_optional_routine(handle, which, fn, needs, who) result(status)
        type(c_ptr), intent(in) :: handle
        integer, intent(in) :: which, needs
        type(c_funptr), intent(in) :: fn
        character(len=*), intent(in) :: who
        type(c_session), pointer :: s
        status = regdae_err_bad_input
        if (.not. open_session(handle, s)) return
        if (s%kind < needs .and. needs == kind_second_order) then
            status = refuse(s, who//': needs a second-order or mechanical problem: call regdae_set_second_order '// &
                            'or regdae_set_mechanical first')
            return
        else if (s%kind < needs) then
            status = refuse(s, who//': needs a mechanical problem: call regdae_set_mechanical first')
            return
        end if
        s%routines%callbacks(which) = fn
        status = record(s, regdae_success, '')
    end function set_optional_routine

    ! The declared structure of a mechanical problem (patterns not declared: dense),
    ! kept in the session for the solver's copies of the problem to point at.
    subroutine declare_structure(s, problem)
        type(c_session), target, intent(inout) :: s
        type(foreign_mechanical), intent(inout) :: problem
        s%structure = mechanical_structure()
        problem%declared => s%structure
        s%structure%declared = any(s%declared)
        if (.not. s%structure%declared) return
        call pattern_or_dense(s%declared(pattern_mass), s%patterns(pattern_mass), s%n, s%structure%mass)
        call pattern_or_dense(s%declared(pattern_constraint), s%patterns(pattern_constraint), s%m, &
                              s%structure%constraint)
        call pattern_or_dense(s%declared(pattern_force_q), s%patterns(pattern_force_q), s%n, s%structure%force_q)
        call pattern_or_dense(s%declared(pattern_force_v), s%patterns(pattern_force_v), s%n, s%structure%force_v)
        s%structure%curvature_supplied = s%routines%has(routine_curvature)
    contains
        ! A subroutine, not a function: gfortran 12 leaks the allocatable components
        ! of a derived-type function result assigned to a component.
        subroutine pattern_or_dense(declared, pattern, nrows, p)
            logical, intent(in) :: declared
            type(sparsity_pattern), intent(in) :: pattern
            integer, intent(in) :: nrows
            type(sparsity_pattern), intent(out) :: p
            if (declared) then
                p = pattern
            else
                p = dense_pattern(nrows, s%n)
            end if
        end subroutine pattern_or_dense
    end subroutine declare_structure

end module regdae_c_api
