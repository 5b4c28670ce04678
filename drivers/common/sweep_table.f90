!> The files of drivers/sweep: the table of runs (one row a line) and the result
!! file (one line a row, appended by `sweep_schedule` as rows finish), read whole and
!! split into lines; the rows a result file already holds (a rerun skips them); a
!! partial last line (a write cut short by a kill) dropped; the file rewritten in row
!! order at the end; a row's numeric `key=value` (for the order of dispatch). No MPI
!! and no module state here.
module sweep_table
    use, intrinsic :: iso_c_binding, only: c_int, c_long, c_char, c_null_char
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
    !! the row with id k is rows(k).
    function table_rows(lines, tail) result(rows)
        type(text_line), intent(in) :: lines(:)
        character(len=*), intent(in) :: tail
        type(text_line), allocatable :: rows(:)
        integer :: i
        allocate (rows(0))
        do i = 1, size(lines)
            if (is_row(lines(i)%s)) rows = [rows, lines(i)]
        end do
        if (is_row(tail)) rows = [rows, text_line(tail)]
    end function table_rows

    logical function is_row(line)
        character(len=*), intent(in) :: line
        character(len=:), allocatable :: first
        first = word(line, 1)
        is_row = len(first) > 0
        if (is_row) is_row = first(1:1) /= '#'
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
    !! 'id problem ...' ('#' lines skipped). Each line's problem must be the first
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
        integer :: i, id, complete_bytes
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
        do i = 1, size(lines)
            first = word(lines(i)%s, 1)
            if (len(first) == 0) cycle
            if (first(1:1) == '#') cycle
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
    !! by id (the first line of an id if it occurs twice). The sorted text goes to
    !! `path.sorting`, which is then renamed over `path`, so that a kill at any moment
    !! leaves the complete file, sorted or not (a rerun sorts it). Nothing is written
    !! when the file is in row order already. stat = 0, or 1 with msg.
    subroutine sort_result_file(path, nrows, stat, msg)
        character(len=*), intent(in) :: path
        integer, intent(in) :: nrows
        integer, intent(out) :: stat
        character(len=:), allocatable, intent(out) :: msg
        type(text_line), allocatable :: lines(:)
        character(len=:), allocatable :: tail, first, temporary
        integer, allocatable :: at(:)
        integer :: i, id, u, last
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
        open (newunit=u, file=temporary, status='replace', action='write', iostat=stat)
        if (stat == 0) then
            do i = 1, size(lines)
                first = word(lines(i)%s, 1)
                if (len(first) > 0) then
                    if (first(1:1) == '#') write (u, '(a)', iostat=stat) lines(i)%s
                end if
                if (stat /= 0) exit
            end do
        end if
        if (stat == 0) then
            do id = 1, nrows
                if (at(id) > 0) write (u, '(a)', iostat=stat) lines(at(id))%s
                if (stat /= 0) exit
            end do
        end if
        if (stat == 0) close (u, iostat=stat)
        if (stat == 0) stat = c_rename(temporary//c_null_char, path//c_null_char)
        if (stat /= 0) then
            stat = 1
            msg = 'cannot rewrite "'//path//'" in row order (through "'//temporary//'"): its lines stay '// &
                  'in the order they were written'
        end if
    end subroutine sort_result_file

end module sweep_table
