!> Rows that kill their process (drivers/sweep, issue 20): the crash log beside the
!! result file, FILE.crashes, one line `crash id=<row> signal=<n>` or `crash id=<row> exit`
!! appended by the process whose row died of a fatal signal or exited from inside the row
!! (drivers/common/sweep_crash.c). A resume counts a row's crashes; a row not in the result
!! file that crashed `crash_attempts` times gets the result line `<id> <problem> crashed
!! message=...` instead of a third attempt, so one bad row never blocks the table. A kill
!! from outside (SIGKILL, SIGTERM) writes nothing: the row only runs again.
module sweep_crashes
    use, intrinsic :: iso_c_binding, only: c_int, c_char, c_null_char
    use driver_support, only: format_int
    use sweep_table, only: text_line, read_lines, word
    implicit none
    private

    public :: open_crash_log, running_row, crash_counts, crashed_line, remove_crash_log, crash_if_asked

    !> Crashes after which a row is not run again but recorded as crashed.
    integer, parameter, public :: crash_attempts = 2

    interface
        integer(c_int) function c_crash_log(path) bind(C, name='regdae_sweep_crash_log')
            import :: c_int, c_char
            character(kind=c_char), intent(in) :: path(*)
        end function c_crash_log
        subroutine c_crash_row(id) bind(C, name='regdae_sweep_crash_row')
            import :: c_int
            integer(c_int), value :: id
        end subroutine c_crash_row
        subroutine c_crash_now(sig) bind(C, name='regdae_sweep_crash_now')
            import :: c_int
            integer(c_int), value :: sig
        end subroutine c_crash_now
    end interface

contains

    !> The crash log of result file `out`: opened (created) by every process of the sweep
    !! before its first row. False when it cannot be opened (crashes are then not recorded).
    logical function open_crash_log(out) result(ok)
        character(len=*), intent(in) :: out
        ok = (c_crash_log(out//'.crashes'//c_null_char) == 0)
    end function open_crash_log

    !> The row now running in this process, 0 for none (between rows, and while rank 0
    !! serves the other ranks from a row's hook: a failure there is not the row's).
    subroutine running_row(id)
        integer, intent(in) :: id
        call c_crash_row(int(id, c_int))
    end subroutine running_row

    !> Testing (check_sweep.sh): REGDAE_SWEEP_CRASH=ID[:SIGNAL] kills the process at the
    !! start of row ID by SIGNAL (11, SIGSEGV, by default; 0: exit(1) as the Fortran runtime
    !! does when an allocation is refused).
    subroutine crash_if_asked(id)
        integer, intent(in) :: id
        character(len=64) :: spec
        integer :: length, status, colon, row, sig, ios
        call get_environment_variable('REGDAE_SWEEP_CRASH', spec, length, status)
        if (status /= 0 .or. length == 0) return
        colon = index(spec, ':')
        sig = 11
        if (colon > 0) then
            read (spec(1:colon - 1), *, iostat=ios) row
            if (ios == 0) read (spec(colon + 1:length), *, iostat=ios) sig
        else
            read (spec(1:length), *, iostat=ios) row
        end if
        if (ios /= 0 .or. row /= id) return
        call c_crash_now(int(sig, c_int))
    end subroutine crash_if_asked

    !> Crashes per row id (1..nrows) in the crash log of `out`, and the last one's cause
    !! ('signal 11', 'exit'); nothing when there is no log. Lines that do not parse (a
    !! write cut short) are skipped.
    subroutine crash_counts(out, nrows, counts, cause)
        character(len=*), intent(in) :: out
        integer, intent(in) :: nrows
        integer, intent(out) :: counts(nrows)
        type(text_line), intent(out) :: cause(nrows)
        type(text_line), allocatable :: lines(:)
        character(len=:), allocatable :: tail, msg, w
        integer :: i, id, stat, ios
        logical :: exists
        counts = 0
        inquire (file=out//'.crashes', exist=exists)
        if (.not. exists) return
        call read_lines(out//'.crashes', lines, tail, stat, msg)
        if (stat /= 0) return
        do i = 1, size(lines)
            if (word(lines(i)%s, 1) /= 'crash') cycle
            w = word(lines(i)%s, 2)
            if (len(w) < 4) cycle
            if (w(1:3) /= 'id=') cycle
            read (w(4:), *, iostat=ios) id
            if (ios /= 0 .or. id < 1 .or. id > nrows) cycle
            counts(id) = counts(id) + 1
            w = word(lines(i)%s, 3)
            if (len(w) > 7) then
                cause(id)%s = 'signal '//w(8:)
            else
                cause(id)%s = 'exit'
            end if
        end do
    end subroutine crash_counts

    !> The result line of a row that crashed `count` times (no newline, no crc).
    function crashed_line(id, problem, count, cause) result(line)
        integer, intent(in) :: id, count
        character(len=*), intent(in) :: problem, cause
        character(len=:), allocatable :: line
        line = format_int(id)//' '//problem//' crashed message=the row killed its process '//format_int(count)// &
               ' times (the last: '//describe(cause)//'); not run again'
    end function crashed_line

    !> The crash log of `out` removed: the sweep is complete, or its result file is new.
    subroutine remove_crash_log(out)
        character(len=*), intent(in) :: out
        integer :: u, ios
        logical :: exists
        inquire (file=out//'.crashes', exist=exists)
        if (.not. exists) return
        open (newunit=u, file=out//'.crashes', status='old', iostat=ios)
        if (ios == 0) close (u, status='delete', iostat=ios)
    end subroutine remove_crash_log

    function describe(cause) result(text)
        character(len=*), intent(in) :: cause
        character(len=:), allocatable :: text
        text = cause
        select case (cause)
        case ('signal 11'); text = 'signal 11, SIGSEGV'
        case ('signal 7'); text = 'signal 7, SIGBUS'
        case ('signal 8'); text = 'signal 8, SIGFPE'
        case ('signal 4'); text = 'signal 4, SIGILL'
        case ('signal 6'); text = 'signal 6, SIGABRT'
        case ('exit'); text = 'an exit from inside the row, e.g. an allocation the system refused'
        end select
    end function describe

end module sweep_crashes
