!> Random inputs for `set_option` and the number parser, with a fixed seed
!! (reproducible; `REGDAE_FUZZ_SEED` and `REGDAE_FUZZ_COUNT` in the environment
!! change the seed and the number of cases for long runs).
!!
!! Properties checked on every case: `set_option` returns success or
!! `regdae_err_bad_input`; after success the record passes `validate_options`;
!! after a failure the message names the key and the record is unchanged. A real
!! written with 17 significant digits in any of Fortran's forms (E, ES, F, and
!! the exponent letter D or d) reads back exactly; a mutated number is either refused or
!! read as the same value Fortran's own reader gives it.
module test_fuzz
    use, intrinsic :: iso_fortran_env, only: int64
    use regdae
    use regdae_testing, only: checker, test_case, new_test
    implicit none
    private
    public :: fuzz_tests

    !> xorshift64 generator (shifts and exclusive ors only: no integer overflow):
    !! the same sequence on every compiler.
    type :: rng
        integer(int64) :: state = 88172645463325252_int64
    end type rng

    character(len=18), parameter :: keys(30) = [character(len=18) :: 'method', 'formulation', 'lsq', 'exclusion', &
        'stop_at_output', 'gamma', 'eps', 'rtol', 'atol', 'max_steps', 'h_init', 'h_max', 'ic_tol', 'index', &
        'gamma0', 'gamma1', 'curvature', 'excluded', 'singular_threshold', 'jump_tol', 'drift_tol', 'invariant_tol', &
        'taylor_h', 'mass_damping', 'integrator', 'nout', 'Method', 'eps ', 'epsilon', '']
    character(len=24), parameter :: values(44) = [character(len=24) :: 'trust_region', 'direct', 'baumgarte', &
        'multiplier', 'eliminated', 'auto', 'normal', 'stacked', 'suppress', 'weights', 'off', 'yes', 'no', 'y', &
        'vy', 'ida', 'dopri5', '2', '3', '1e-6', '0', '-1', '1e300', '1e400', 'nan', 'inf', '1-3', '1.5-2', '.5', &
        '5.', '+5', '1d-3', '2147483647', '2147483648', '1e5', '1e-300', '0.5', '1', '', ' ', 'x', '1e', '--1', '1 2']

contains

    function fuzz_tests() result(tests)
        type(test_case), allocatable :: tests(:)
        tests = [new_test('set_option_random', set_option_random), &
                 new_test('numbers_round_trip', numbers_round_trip), &
                 new_test('mutated_numbers', mutated_numbers)]
    end function fuzz_tests

    ! Seed and count from the environment, or the defaults.
    subroutine fuzz_setup(gen, count, default_count)
        type(rng), intent(out) :: gen
        integer, intent(out) :: count
        integer, intent(in) :: default_count
        character(len=32) :: text
        integer :: length, status, seed
        logical :: ok
        count = default_count
        seed = 1
        call get_environment_variable('REGDAE_FUZZ_SEED', text, length, status)
        if (status == 0) call parse_integer(text(1:length), seed, ok)
        call get_environment_variable('REGDAE_FUZZ_COUNT', text, length, status)
        if (status == 0) call parse_integer(text(1:length), count, ok)
        gen%state = ieor(gen%state, 2654435761_int64*int(seed, int64))
        if (gen%state == 0) gen%state = 1
    end subroutine fuzz_setup

    integer(int64) function next(gen)
        type(rng), intent(inout) :: gen
        gen%state = ieor(gen%state, shiftr(gen%state, 12))
        gen%state = ieor(gen%state, shiftl(gen%state, 25))
        gen%state = ieor(gen%state, shiftr(gen%state, 27))
        next = shiftr(gen%state, 1)   ! nonnegative
    end function next

    !> An integer in [1, n].
    integer function below(gen, n)
        type(rng), intent(inout) :: gen
        integer, intent(in) :: n
        below = 1 + int(mod(next(gen), int(n, int64)))
    end function below

    !> A real in [0, 1).
    real(wp) function uniform(gen)
        type(rng), intent(inout) :: gen
        uniform = real(shiftr(next(gen), 10), wp)*2.0_wp**(-53)
    end function uniform

    subroutine set_option_random(chk)
        type(checker), intent(inout) :: chk
        type(rng) :: gen
        type(solver_options) :: opts, before
        character(len=:), allocatable :: msg, key, value
        integer :: c, count, stat, vstat, failures
        failures = 0
        call fuzz_setup(gen, count, 20000)
        do c = 1, count
            key = trim(keys(below(gen, size(keys))))
            value = trim(values(below(gen, size(values))))
            if (below(gen, 4) == 1) value = random_number_text(gen)
            before = opts
            call set_option(opts, key, value, stat, msg)
            if (stat == regdae_success) then
                call validate_options(opts, vstat, msg)
                if (vstat /= regdae_success) call record('accepted an invalid record: '//msg)
            else if (stat == regdae_err_bad_input) then
                if (index(msg, key) == 0) call record('message does not name the key')
                if (.not. same_options(opts, before)) call record('a refused value changed the record')
            else
                call record('status '//format_int(stat))
            end if
            if (mod(c, 50) == 0) opts = solver_options()   ! start again from the defaults now and then
        end do
        call chk%equal(failures, 0, 'set_option properties over random keys and values')
    contains
        subroutine record(what)
            character(len=*), intent(in) :: what
            failures = failures + 1
            if (failures <= 5) write (*, '(a)') '    key "'//key//'" value "'//value//'": '//what
        end subroutine record
    end subroutine set_option_random

    ! Every component equal: the records written out (list-directed output
    ! prints every component of a type without allocatable parts).
    logical function same_options(a, b)
        type(solver_options), intent(in) :: a, b
        character(len=4000) :: text_a, text_b
        write (text_a, *) a
        write (text_b, *) b
        same_options = (text_a == text_b)
    end function same_options

    ! A finite real with a random sign, mantissa and exponent in [-300, 300],
    ! written in a random Fortran form with 17 significant digits.
    function random_number_text(gen, x) result(text)
        type(rng), intent(inout) :: gen
        real(wp), intent(out), optional :: x
        character(len=:), allocatable :: text
        character(len=64) :: buf
        real(wp) :: value
        integer :: e
        e = below(gen, 601) - 301
        value = (1.0_wp + 9.0_wp*uniform(gen))*10.0_wp**e
        if (below(gen, 2) == 1) value = -value
        select case (below(gen, 5))
        case (1); write (buf, '(es26.16e3)') value
        case (2); write (buf, '(e27.17e3)') value
        case (3); write (buf, '(es26.16e3)') value
            buf(index(buf, 'E'):index(buf, 'E')) = merge('D', 'd', below(gen, 2) == 1)
        case (4); write (buf, '(es26.16)') value
            if (abs(e) >= 99) write (buf, '(es26.16e3)') value
        case default
            if (abs(e) <= 15) then
                write (buf, '(f40.' // format_int(max(0, 16 - e)) // ')') value
            else
                write (buf, '(es26.16e3)') value
            end if
        end select
        text = trim(adjustl(buf))
        if (present(x)) x = value
    end function random_number_text

    subroutine numbers_round_trip(chk)
        type(checker), intent(inout) :: chk
        type(rng) :: gen
        character(len=:), allocatable :: text
        real(wp) :: x, y, reference
        integer :: c, count, failures, ios
        logical :: ok
        failures = 0
        call fuzz_setup(gen, count, 20000)
        do c = 1, count
            text = random_number_text(gen, x)
            y = 0.0_wp
            call parse_real(text, y, ok)
            read (text, *, iostat=ios) reference
            if (.not. ok .or. y /= reference .or. abs(y - x) > 1.0e-15_wp*abs(x)) then
                failures = failures + 1
                if (failures <= 5) write (*, '(a)') '    "'//text//'" not read back'
            end if
        end do
        call chk%equal(failures, 0, 'written reals read back')
    end subroutine numbers_round_trip

    ! A number with one character inserted, deleted or replaced: refused, or
    ! read as the same value as Fortran's list-directed reader (which accepts more).
    subroutine mutated_numbers(chk)
        type(checker), intent(inout) :: chk
        character(len=*), parameter :: alphabet = '0123456789+-.eEdDxn, '
        type(rng) :: gen
        character(len=:), allocatable :: text
        real(wp) :: y, reference
        integer :: c, count, failures, accepted, ios, pos, kind
        logical :: ok
        character :: ch
        failures = 0
        accepted = 0
        call fuzz_setup(gen, count, 20000)
        do c = 1, count
            text = random_number_text(gen)
            pos = below(gen, len(text))
            ch = alphabet(below(gen, len(alphabet)):)
            kind = below(gen, 3)
            if (kind == 1) text = text(1:pos - 1)//ch//text(pos:)
            if (kind == 2) text = text(1:pos - 1)//text(pos + 1:)
            if (kind == 3) text(pos:pos) = ch
            y = -7.0_wp
            call parse_real(text, y, ok)
            if (.not. ok) then
                if (y /= -7.0_wp) failures = failures + 1
                cycle
            end if
            accepted = accepted + 1
            read (text, *, iostat=ios) reference
            if (ios /= 0 .or. y /= reference) then
                failures = failures + 1
                if (failures <= 5) write (*, '(a)') '    "'//text//'" accepted but not as Fortran reads it'
            end if
        end do
        call chk%equal(failures, 0, 'mutated numbers: refused, or read as Fortran reads them')
        call chk%true(accepted > 0 .and. accepted < count, 'some mutations accepted, some refused')
    end subroutine mutated_numbers

end module test_fuzz
