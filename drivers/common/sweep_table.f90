!> The files of drivers/sweep: the table of runs (one row a line) and the result
!! file (one line a row, appended by `sweep_schedule` as rows finish), read whole and
!! split into lines; the rows a result file already holds (a rerun skips them); a
!! partial last line (a write cut short by a kill) dropped; the file rewritten in row
!! order at the end; a row's numeric `key=value` (for the order of dispatch); the
!! check word `crc=` that makes a result line prove itself; the POSIX calls a writer
!! needs (fsync, flock). No MPI and no module state here.
module sweep_table
    use, intrinsic :: iso_c_binding, only: c_int, c_long, c_char, c_null_char
    use, intrinsic :: iso_fortran_env, only: int64
    use driver_support, only: format_int
    use regdae, only: wp, parse_integer, parse_real
    implicit none
    private

    !> One line of text.
    type, public :: text_line
        character(len=:), allocatable :: s
    end type text_line

    !> The longest table row (characters): rows and results travel between MPI ranks as
    !! messages short enough to be sent eagerly, so a send never waits for its receiver.
    integer, parameter, public :: max_row_length = 1000

    public :: read_lines, table_rows, word, results_present, sort_result_file, row_real
    public :: with_check, line_checked, lock_file, write_line, sync_file, close_file


    interface
        !> POSIX truncate(2): cut the file at `length` bytes.
        integer(c_int) function c_truncate(path, length) bind(C, name='truncate')
            import :: c_int, c_long, c_char
            character(kind=c_char), intent(in) :: path(*)
            integer(c_long), value :: length
        end function c_truncate

        !> C rename(3): replace `new` by `old` (atomic within one file system).
        integer(c_int) function c_rename(old, new) bind(C, name='rename')
            import :: c_int, c_char
            character(kind=c_char), intent(in) :: old(*), new(*)
        end function c_rename

        !> C remove(3).
        integer(c_int) function c_remove(path) bind(C, name='remove')
            import :: c_int, c_char
            character(kind=c_char), intent(in) :: path(*)
        end function c_remove

        !> drivers/common/sweep_posix.c: open for appending and lock a file (descriptor >= 0;
        !! -1 cannot open, -2 locked by another process), write with errors seen, create,
        !! fsync, close.
        integer(c_int) function c_sweep_lock(path, tries) bind(C, name='regdae_sweep_lock')
            import :: c_int, c_char
            character(kind=c_char), intent(in) :: path(*)
            integer(c_int), value :: tries
        end function c_sweep_lock
        integer(c_int) function c_sweep_write(fd, text, n) bind(C, name='regdae_sweep_write')
            import :: c_int, c_char
            integer(c_int), value :: fd, n
            character(kind=c_char), intent(in) :: text(*)
        end function c_sweep_write
        integer(c_int) function c_sweep_create(path) bind(C, name='regdae_sweep_create')
            import :: c_int, c_char
            character(kind=c_char), intent(in) :: path(*)
        end function c_sweep_create
        integer(c_int) function c_sweep_sync(fd) bind(C, name='regdae_sweep_sync')
            import :: c_int
            integer(c_int), value :: fd
        end function c_sweep_sync
        integer(c_int) function c_sweep_close(fd) bind(C, name='regdae_sweep_close')
            import :: c_int
            integer(c_int), value :: fd
        end function c_sweep_close
    end interface

contains

    !> The complete lines of a file (without their newlines) and the text after the
    !! last newline (`tail`, empty when the file ends with one). stat = 0, or the
    !! iostat of the failed open or read (msg then says which file).
    subroutine read_lines(path, lines, tail, stat, msg)
        character(len=*), intent(in) :: path
        type(text_line), allocatable, intent(out) :: lines(:)
        character(len=:), allocatable, intent(out) :: tail, msg
        integer, intent(out) :: stat
        character(len=:), allocatable :: buffer
        integer :: u, nbytes, a, b, count
        msg = ''
        tail = ''
        allocate (lines(0))
        open (newunit=u, file=path, access='stream', form='unformatted', status='old', action='read', iostat=stat)
        if (stat /= 0) then
            msg = 'cannot open "'//path//'"'
            return
        end if
        inquire (unit=u, size=nbytes)
        allocate (character(len=max(nbytes, 0)) :: buffer)
        if (nbytes > 0) read (u, iostat=stat) buffer
        close (u)
        if (stat /= 0) then
            msg = 'cannot read "'//path//'"'
            return
        end if
        count = 0
        do a = 1, len(buffer)
            if (buffer(a:a) == new_line('a')) count = count + 1
        end do
        deallocate (lines)
        allocate (lines(count))
        a = 1
        do count = 1, size(lines)
            b = a + index(buffer(a:), new_line('a')) - 1
            lines(count)%s = buffer(a:b - 1)
            a = b + 1
        end do
        tail = buffer(a:)
    end subroutine read_lines

    !> The rows of a table: its lines (and a last line without a newline) that are
    !! neither blank nor comments ('#' as the first non-blank character), in order;
    !! the row with id k is rows(k), from the table's line line_numbers(k) (linear in
    !! the table's size: 10^5 rows in well under a second).
    subroutine table_rows(lines, tail, rows, line_numbers)
        type(text_line), intent(in) :: lines(:)
        character(len=*), intent(in) :: tail
        type(text_line), allocatable, intent(out) :: rows(:)
        integer, allocatable, intent(out) :: line_numbers(:)
        logical :: keep(size(lines))
        integer :: i, k
        do i = 1, size(lines)
            keep(i) = is_row(lines(i)%s)
        end do
        k = count(keep)
        if (is_row(tail)) k = k + 1
        allocate (rows(k), line_numbers(k))
        k = 0
        do i = 1, size(lines)
            if (.not. keep(i)) cycle
            k = k + 1
            rows(k)%s = lines(i)%s
            line_numbers(k) = i
        end do
        if (k < size(rows)) then
            rows(k + 1)%s = tail
            line_numbers(k + 1) = size(lines) + 1
        end if
    end subroutine table_rows

    logical function is_row(line)
        character(len=*), intent(in) :: line
        integer :: i
        is_row = .false.
        do i = 1, len(line)
            if (blank(line(i:i))) cycle
            is_row = line(i:i) /= '#'
            return
        end do
    end function is_row

    !> The k-th blank-separated word of a line (blanks: space, tab, carriage return);
    !! empty if there are fewer.
    function word(line, k) result(w)
        character(len=*), intent(in) :: line
        integer, intent(in) :: k
        character(len=:), allocatable :: w
        integer :: i, start, count
        w = ''
        count = 0
        i = 1
        do while (i <= len(line))
            if (blank(line(i:i))) then
                i = i + 1
                cycle
            end if
            start = i
            do while (i <= len(line))
                if (blank(line(i:i))) exit
                i = i + 1
            end do
            count = count + 1
            if (count == k) then
                w = line(start:i - 1)
                return
            end if
        end do
    end function word

    pure logical function blank(c)
        character, intent(in) :: c
        blank = (c == ' ' .or. c == achar(9) .or. c == achar(13))
    end function blank

    !> Which rows a result file already holds: done(id) for each complete line
    !! 'id problem ...' whose check word crc= matches it ('#' lines skipped; a line
    !! that fails its check is not a result, its row runs again, `note` counts them). Each line's problem must be the first
    !! word of the table's row `id`, given in `problems`: otherwise the file is another
    !! table's results and stat = 2 with the line in msg. A partial last line (no
    !! newline: a write cut short) is cut off the file, and `note` says so.
    !! stat = 0 (also when the file does not exist: nothing done), 1 if it cannot be
    !! read or cut.
    subroutine results_present(path, problems, done, note, stat, msg)
        character(len=*), intent(in) :: path
        type(text_line), intent(in) :: problems(:)
        logical, intent(out) :: done(:)
        character(len=:), allocatable, intent(out) :: note, msg
        integer, intent(out) :: stat
        type(text_line), allocatable :: lines(:)
        character(len=:), allocatable :: tail, first
        integer :: i, id, complete_bytes, bad, first_bad
        logical :: exists, ok
        done = .false.
        note = ''
        msg = ''
        stat = 0
        inquire (file=path, exist=exists)
        if (.not. exists) return
        call read_lines(path, lines, tail, stat, msg)
        if (stat /= 0) then
            stat = 1
            return
        end if
        bad = 0
        do i = 1, size(lines)
            first = word(lines(i)%s, 1)
            if (len(first) == 0) cycle
            if (first(1:1) == '#') cycle
            if (.not. line_checked(lines(i)%s)) then   ! cut or garbled (or of a version without crc=): rerun
                bad = bad + 1
                if (bad == 1) first_bad = i
                cycle
            end if
            id = 0
            call parse_integer(first, id, ok)
            if (ok) ok = (id >= 1 .and. id <= size(problems))
            if (ok) ok = (word(lines(i)%s, 2) == problems(max(id, 1))%s)
            if (.not. ok) then
                stat = 2
                msg = '"'//path//'" line '//format_int(i)//' ("'//first//' '//word(lines(i)%s, 2)// &
                      ' ...") is not a result of this table''s rows: another table''s results?'
                return
            end if
            done(id) = .true.
        end do
        if (len(tail) > 0) then
            complete_bytes = sum([(len(lines(i)%s) + 1, i=1, size(lines))])
            if (c_truncate(path//c_null_char, int(complete_bytes, c_long)) /= 0) then
                stat = 1
                msg = 'cannot cut the partial last line off "'//path//'"'
                return
            end if
            note = 'dropped the partial last line of "'//path//'" (a write cut short): '// &
                   format_int(len(tail))//' characters'
        end if
        if (bad > 0) then
            if (len(note) > 0) note = note//'; '
            note = note//format_int(bad)//' line(s) of "'//path//'" fail their check (crc=), the first at line '// &
                   format_int(first_bad)//': their rows run again, and the final sort drops the lines'
        end if
    end subroutine results_present

    !> The value of `key=value` in a row as a real number: the last word `key=...` that
    !! parses, `fallback` if none does (no such word, or e.g. `gamma=auto`).
    function row_real(line, key, fallback) result(x)
        character(len=*), intent(in) :: line, key
        real(wp), intent(in) :: fallback
        real(wp) :: x, y
        character(len=:), allocatable :: w
        integer :: k
        logical :: ok
        x = fallback
        k = 2
        do
            w = word(line, k)
            if (len(w) == 0) exit
            if (len(w) > len(key) + 1) then
                if (w(:len(key) + 1) == key//'=') then
                    call parse_real(w(len(key) + 2:), y, ok)
                    if (ok) x = y
                end if
            end if
            k = k + 1
        end do
    end function row_real

    !> Rewrite a result file in row order: its '#' lines first, then the result lines
    !! by id (the first line of an id if it occurs twice; lines that fail their check
    !! dropped). The sorted text goes to
    !! `path.sorting`, which is then renamed over `path`, so that a kill at any moment
    !! leaves the complete file, sorted or not (a rerun sorts it); it is on the device
    !! (fsync) before the rename. Nothing is written
    !! when the file is in row order already. stat = 0, or 1 with msg.
    subroutine sort_result_file(path, nrows, stat, msg)
        character(len=*), intent(in) :: path
        integer, intent(in) :: nrows
        integer, intent(out) :: stat
        character(len=:), allocatable, intent(out) :: msg
        type(text_line), allocatable :: lines(:)
        character(len=:), allocatable :: tail, first, temporary
        integer, allocatable :: at(:)
        character(len=:), allocatable :: why
        integer :: i, id, u, last, ios
        logical :: ok, sorted
        call read_lines(path, lines, tail, stat, msg)
        if (stat /= 0) then
            stat = 1
            return
        end if
        allocate (at(nrows))
        at = 0
        sorted = (len(tail) == 0)
        last = -1
        do i = 1, size(lines)
            first = word(lines(i)%s, 1)
            if (len(first) == 0) then   ! a blank line: dropped
                sorted = .false.
                cycle
            end if
            if (first(1:1) == '#') then
                sorted = sorted .and. last < 0
                cycle
            end if
            if (.not. line_checked(lines(i)%s)) then   ! a line that fails its check: dropped
                sorted = .false.
                cycle
            end if
            id = 0
            call parse_integer(first, id, ok)
            if (.not. ok .or. id < 1 .or. id > nrows) then
                stat = 1
                msg = '"'//path//'" line '//format_int(i)//' is not a result line: not sorted'
                return
            end if
            sorted = sorted .and. id > last
            last = max(last, id)
            if (at(id) == 0) at(id) = i
        end do
        if (sorted) return
        temporary = path//'.sorting'
        u = c_sweep_create(temporary//c_null_char)
        stat = merge(0, 1, u >= 0)
        if (stat == 0) then
            do i = 1, size(lines)
                first = word(lines(i)%s, 1)
                if (len(first) > 0) then
                    if (first(1:1) == '#') call write_line(u, lines(i)%s, stat, why)
                end if
                if (stat /= 0) exit
            end do
        end if
        if (stat == 0) then
            do id = 1, nrows
                if (at(id) > 0) call write_line(u, lines(at(id))%s, stat, why)
                if (stat /= 0) exit
            end do
        end if
        if (stat == 0) call sync_file(u, stat)   ! on the device before the rename
        if (u >= 0) then
            call close_file(u, ios)
            if (stat == 0) stat = ios
        end if
        if (stat == 0) stat = c_rename(temporary//c_null_char, path//c_null_char)
        if (stat /= 0) then
            ios = c_remove(temporary//c_null_char)
            stat = 1
            msg = 'cannot rewrite "'//path//'" in row order (through "'//temporary//'"): its lines stay '// &
                  'in the order they were written'
        end if
    end subroutine sort_result_file

    !> A result line with its check word: ` crc=HHHHHHHH` (FNV-1a, 32 bits, of the line
    !! without it, in hex) before ` message=` (the message stays the rest of the line),
    !! else at the end.
    function with_check(line) result(checked)
        character(len=*), intent(in) :: line
        character(len=:), allocatable :: checked
        character(len=8) :: hex
        integer :: at
        hex = fnv1a(line)
        at = index(line, ' message=')
        if (at > 0) then
            checked = line(1:at - 1)//' crc='//hex//line(at:)
        else
            checked = line//' crc='//hex
        end if
    end function with_check

    !> Does a result line carry a check word that matches the rest of it? (A line cut
    !! short, garbled, or of a regdae without crc= does not.)
    logical function line_checked(line) result(ok)
        character(len=*), intent(in) :: line
        integer :: at
        ok = .false.
        at = index(line, ' crc=')   ! the first: a message after it may hold anything
        if (at == 0 .or. len(line) < at + 12) return
        if (len(line) > at + 12) then
            if (line(at + 13:at + 13) /= ' ') return
        end if
        ok = (line(at + 5:at + 12) == fnv1a(line(1:at - 1)//line(at + 13:)))
    end function line_checked

    ! FNV-1a (32 bits) of a text, in 8 upper-case hex digits.
    function fnv1a(text) result(hex)
        character(len=*), intent(in) :: text
        character(len=8) :: hex
        integer(int64), parameter :: prime = 16777619_int64, basis = 2166136261_int64, mask = 4294967295_int64
        integer(int64) :: h
        integer :: i
        h = basis
        do i = 1, len(text)
            h = iand(ieor(h, int(ichar(text(i:i)), int64))*prime, mask)
        end do
        write (hex, '(z8.8)') h
    end function fnv1a

    !> One writer per result file: open `path` for appending (created if missing) and take
    !! an exclusive lock on it (flock), waiting up to `seconds` (polled every 0.1 s). fd:
    !! the descriptor to write through (write_line), which holds the lock until close_file
    !! or the end of the process (also a kill). stat = 0 held, 1 the file cannot be opened
    !! for writing, 2 another process holds the lock.
    subroutine lock_file(path, seconds, fd, stat)
        character(len=*), intent(in) :: path
        real, intent(in) :: seconds
        integer, intent(out) :: fd, stat
        fd = c_sweep_lock(path//c_null_char, int(max(1, nint(10.0*min(seconds, 86400.0))), c_int))
        stat = 0
        if (fd == -1) stat = 1
        if (fd == -2) stat = 2
    end subroutine lock_file

    !> Write a line and its newline to descriptor fd in one write(2) (1: stdout). stat =
    !! 0, or the errno of the failure (28: the disk is full), which msg names.
    subroutine write_line(fd, line, stat, msg)
        integer, intent(in) :: fd
        character(len=*), intent(in) :: line
        integer, intent(out) :: stat
        character(len=:), allocatable, intent(out) :: msg
        stat = c_sweep_write(int(fd, c_int), line//new_line('a'), int(len(line) + 1, c_int))
        msg = ''
        if (stat /= 0) msg = errno_text(stat)
    end subroutine write_line

    !> fsync the file open on fd (nothing to do for a device or a pipe): stat = 0, or
    !! the errno.
    subroutine sync_file(fd, stat)
        integer, intent(in) :: fd
        integer, intent(out) :: stat
        stat = c_sweep_sync(int(fd, c_int))
    end subroutine sync_file

    !> Close fd (releasing its lock): stat = 0, or the errno.
    subroutine close_file(fd, stat)
        integer, intent(in) :: fd
        integer, intent(out) :: stat
        stat = c_sweep_close(int(fd, c_int))
    end subroutine close_file

    ! errno in words, for the few a writer meets.
    function errno_text(code) result(text)
        integer, intent(in) :: code
        character(len=:), allocatable :: text
        select case (code)
        case (28); text = 'no space left on the device (ENOSPC)'
        case (5); text = 'input/output error (EIO)'
        case (27); text = 'file too large (EFBIG)'
        case (122); text = 'disk quota exceeded (EDQUOT)'
        case (30); text = 'read-only file system (EROFS)'
        case (32); text = 'broken pipe (EPIPE)'
        case default; text = 'errno '//format_int(code)
        end select
    end function errno_text

end module sweep_table
