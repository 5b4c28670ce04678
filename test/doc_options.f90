!> The documentation of the options against the code (issue 19, item 6).
!!
!!     doc_options_tester table  doc/api.md         (ctest doc.options)
!!     doc_options_tester header include/regdae.h   (ctest capi.option_keys)
!!
!! The code's options are the components of a default-constructed `solver_options`,
!! read from its namelist output: an option added to the type is seen here without
!! a change to this program, and fails both tests until it is documented.
!!
!! `table`: every row of doc/api.md's options table (section 2, the table headed
!! `| key / component | values | default | meaning |`) names components of
!! `solver_options`, and its default, given to the code's own parser (`set_option`)
!! on a default record, changes nothing: the documented default is the code's. An
!! option without a row, a row without an option, a key in two rows and a default
!! that `set_option` refuses fail too, each with a message naming the key.
!!
!! `header`: include/regdae.h's `regdae_options` has the fields of the C record
!! `c_options` in its order, `c_options` has those of `solver_options` (field for
!! field, as the header says), and the comments of `regdae_set_option`,
!! `regdae_set_real_option` and `regdae_set_int_option` list every key they take
!! (all; the real ones; the integer and switch ones) and no other.
!!
!! Prints one line per failed check and 'N passed, N failed'; exit status 1 if a
!! check failed, 2 for bad arguments.
program doc_options_tester
    use regdae, only: wp, solver_options, set_option, regdae_success, option_text, format_int
    use regdae_c_records, only: c_options, to_c_options
    implicit none

    !> A line of text (of a file, or a value).
    type :: text_line
        character(len=:), allocatable :: s
    end type text_line

    !> The components of a record as its namelist output gives them, in order.
    type :: record_dump
        type(text_line), allocatable :: names(:)    !! lower case
        type(text_line), allocatable :: values(:)   !! as written
    end type record_dump

    character(len=*), parameter :: table_header = '| key / component | values | default | meaning |'
    character(len=4096) :: mode, path
    integer :: passed, failed

    passed = 0
    failed = 0
    if (command_argument_count() /= 2) then
        write (*, '(a)') 'usage: doc_options_tester table DOC_API_MD | header REGDAE_H'
        stop 2
    end if
    call get_command_argument(1, mode)
    call get_command_argument(2, path)
    select case (mode)
    case ('table')
        call check_table(trim(path))
    case ('header')
        call check_header(trim(path))
    case default
        write (*, '(a)') 'doc_options_tester: unknown mode "'//trim(mode)//'" (table, header)'
        stop 2
    end select
    write (*, '(i0,a,i0,a)') passed, ' passed, ', failed, ' failed'
    if (failed > 0) stop 1

contains

    ! --- the options table of doc/api.md ------------------------------------------

    subroutine check_table(file)
        character(len=*), intent(in) :: file
        type(text_line), allocatable :: lines(:), keys(:), defaults(:), documented(:)
        type(record_dump) :: code
        integer :: i, k, first

        allocate (lines(0))   ! (gfortran 12 -Wall warns of an unallocated intent(out) array otherwise)
        call read_lines(file, lines)
        code = options_dump(solver_options())
        first = 0
        do i = 1, size(lines)
            if (trim(adjustl(lines(i)%s)) == table_header) then
                first = i + 2   ! after the header and the |---| line
                exit
            end if
        end do
        call check(first > 0, file//': no options table (no line "'//table_header//'")')
        if (first == 0) return
        allocate (documented(0))
        do i = first, size(lines)
            if (index(adjustl(lines(i)%s), '|') /= 1) exit
            call table_row(lines(i)%s, keys, defaults)
            call check(size(keys) > 0 .and. size(keys) == size(defaults), file//': the row "'// &
                       shortened(lines(i)%s)//'" must name its keys in backquotes and give one default per key')
            if (size(keys) == 0 .or. size(keys) /= size(defaults)) cycle
            do k = 1, size(keys)
                call check(.not. listed(keys(k)%s, documented), file//': the options table has two rows for `'// &
                           keys(k)%s//'`')
                documented = [documented, keys(k)]
                call check_default(keys(k)%s, defaults(k)%s, code, file)
            end do
        end do
        do i = 1, size(code%names)
            call check(listed(code%names(i)%s, documented), 'the option `'//code%names(i)%s//'` (solver_options%'// &
                       code%names(i)%s//') has no row in the options table of '//file// &
                       ' (section 2): document its values, default and meaning')
        end do
    end subroutine check_table

    ! The documented default of one key, given to set_option on a default record,
    ! must leave the record as it is.
    subroutine check_default(key, default, code, file)
        character(len=*), intent(in) :: key, default, file
        type(record_dump), intent(in) :: code
        type(solver_options) :: opts
        type(record_dump) :: changed
        character(len=:), allocatable :: msg
        integer :: stat, j
        logical :: same

        if (.not. listed(key, code%names)) then
            call check(.false., file//': the options table has a row for `'//key// &
                       '`, which is not an option (no component of solver_options)')
            return
        end if
        opts = solver_options()
        call set_option(opts, key, default, stat, msg)
        if (stat /= regdae_success) then
            call check(.false., file//': `'//key//'`: the default documented, "'//default// &
                       '", is refused by set_option: '//msg)
            return
        end if
        changed = options_dump(opts)
        same = .true.
        do j = 1, size(code%names)
            if (changed%values(j)%s == code%values(j)%s) cycle
            same = .false.
            call check(.false., file//': `'//key//'`: the documented default is "'//default//'", the code''s is '// &
                       readable(code%values(j)%s)//' (solver_options%'//code%names(j)%s//')')
        end do
        if (same) call check(.true., '')
    end subroutine check_default

    ! The keys (in backquotes, first cell) and defaults (third cell, comma-separated,
    ! without backquotes and remarks in parentheses) of a table row.
    subroutine table_row(row, keys, defaults)
        character(len=*), intent(in) :: row
        type(text_line), allocatable, intent(out) :: keys(:), defaults(:)
        type(text_line), allocatable :: cells(:)
        character(len=:), allocatable :: cell
        integer :: i, open_quote

        allocate (keys(0), defaults(0))
        call table_cells(row, cells)
        if (size(cells) < 4) return
        cell = cells(1)%s
        open_quote = 0
        do i = 1, len(cell)
            if (cell(i:i) /= '`') cycle
            if (open_quote == 0) then
                open_quote = i
            else
                keys = [keys, text_line(cell(open_quote + 1:i - 1))]
                open_quote = 0
            end if
        end do
        cell = without_remarks(cells(3)%s)
        do
            i = index(cell, ',')
            if (i == 0) exit
            defaults = [defaults, text_line(trim(adjustl(cell(1:i - 1))))]
            cell = cell(i + 1:)
        end do
        defaults = [defaults, text_line(trim(adjustl(cell)))]
    end subroutine table_row

    ! The cells of a Markdown table row (`\|` is a | inside a cell).
    subroutine table_cells(row, cells)
        character(len=*), intent(in) :: row
        type(text_line), allocatable, intent(out) :: cells(:)
        character(len=:), allocatable :: r
        integer :: i, start
        allocate (cells(0))
        r = trim(adjustl(row))
        start = 0
        do i = 1, len(r)
            if (r(i:i) /= '|') cycle
            if (i > 1) then
                if (r(i - 1:i - 1) == '\') cycle
            end if
            if (start > 0) cells = [cells, text_line(trim(adjustl(r(start + 1:i - 1))))]
            start = i
        end do
    end subroutine table_cells

    ! The text without what is in parentheses and without backquotes.
    pure function without_remarks(text) result(plain)
        character(len=*), intent(in) :: text
        character(len=:), allocatable :: plain
        integer :: i, depth
        plain = ''
        depth = 0
        do i = 1, len(text)
            select case (text(i:i))
            case ('(')
                depth = depth + 1
            case (')')
                depth = max(0, depth - 1)
            case ('`')
            case default
                if (depth == 0) plain = plain//text(i:i)
            end select
        end do
    end function without_remarks

    ! --- the C header ------------------------------------------------------------------

    subroutine check_header(file)
        character(len=*), intent(in) :: file
        type(text_line), allocatable :: lines(:), fields(:)
        type(record_dump) :: code, record
        character(len=:), allocatable :: kind
        logical :: real_key, int_key
        integer :: i

        allocate (lines(0), fields(0))   ! (as in check_table)
        call read_lines(file, lines)
        code = options_dump(solver_options())
        record = c_record_dump(to_c_options(solver_options()))
        ! the C record: the header's struct is c_options, which is solver_options
        fields = struct_fields(lines, 'regdae_options')
        call check(size(fields) > 0, file//': no "typedef struct regdae_options {"')
        do i = 1, max(size(fields), size(record%names))
            if (i > size(fields)) then
                call check(.false., file//': regdae_options lacks the field `'//record%names(i)%s// &
                           '` of c_options (src/regdae_c_records.f90), field '//format_int(i))
            else if (i > size(record%names)) then
                call check(.false., file//': regdae_options has the field `'//fields(i)%s// &
                           '`, which c_options (src/regdae_c_records.f90) does not have')
            else
                call check(fields(i)%s == record%names(i)%s, file//': field '//format_int(i)//' of regdae_options is `'// &
                           fields(i)%s//'`, of c_options (src/regdae_c_records.f90) `'//record%names(i)%s//'`')
            end if
        end do
        do i = 1, size(code%names)
            call check(listed(code%names(i)%s, record%names), 'src/regdae_c_records.f90: c_options (and '//file// &
                       ': regdae_options) has no field `'//code%names(i)%s//'` of solver_options: '// &
                       'regdae_get_options cannot return it')
        end do
        do i = 1, size(record%names)
            call check(listed(record%names(i)%s, code%names), 'src/regdae_c_records.f90: c_options has the field `'// &
                       record%names(i)%s//'`, which solver_options does not have')
        end do
        ! the keys each setter's comment lists
        do i = 1, size(code%names)
            kind = value_kind(code%values(i)%s)
            real_key = (kind == 'real')
            int_key = (kind == 'integer' .or. kind == 'logical')
            call check_key_listed(lines, 'regdae_set_option', code%names(i)%s, .true., file)
            call check_key_listed(lines, 'regdae_set_real_option', code%names(i)%s, real_key, file)
            call check_key_listed(lines, 'regdae_set_int_option', code%names(i)%s, int_key, file)
        end do
    end subroutine check_header

    ! The comment of `function` names `key` if and only if `expected`.
    subroutine check_key_listed(lines, function, key, expected, file)
        type(text_line), intent(in) :: lines(:)
        character(len=*), intent(in) :: function, key, file
        logical, intent(in) :: expected
        character(len=:), allocatable :: comment
        comment = comment_of(lines, function)
        if (len(comment) == 0) then
            call check(.false., file//': no comment before "int '//function//'("')
        else if (expected) then
            call check(has_word(comment, key), file//': the comment of '//function//' does not list the key `'// &
                       key//'`')
        else
            call check(.not. has_word(comment, key), file//': the comment of '//function//' lists the key `'//key// &
                       '`, which it does not take')
        end if
    end subroutine check_key_listed

    ! The field names of `typedef struct name { ... } name;`, in order.
    function struct_fields(lines, name) result(fields)
        type(text_line), intent(in) :: lines(:)
        character(len=*), intent(in) :: name
        type(text_line), allocatable :: fields(:)
        character(len=:), allocatable :: declaration
        integer :: i, semicolon, blank
        logical :: inside
        allocate (fields(0))
        inside = .false.
        do i = 1, size(lines)
            if (index(lines(i)%s, 'typedef struct '//name//' {') == 1) then
                inside = .true.
            else if (inside .and. index(lines(i)%s, '}') == 1) then
                return
            else if (inside) then
                semicolon = index(lines(i)%s, ';')
                if (semicolon == 0) cycle
                declaration = trim(lines(i)%s(1:semicolon - 1))
                blank = index(declaration, ' ', back=.true.)
                fields = [fields, text_line(declaration(blank + 1:))]
            end if
        end do
    end function struct_fields

    ! The /** ... */ comment right before the line that declares `int function(`.
    function comment_of(lines, function) result(comment)
        type(text_line), intent(in) :: lines(:)
        character(len=*), intent(in) :: function
        character(len=:), allocatable :: comment
        integer :: i, j
        comment = ''
        do i = 1, size(lines)
            if (index(lines(i)%s, 'int '//function//'(') /= 1) cycle
            do j = i - 1, 1, -1
                comment = lines(j)%s//' '//comment
                if (index(adjustl(lines(j)%s), '/**') == 1) return
            end do
            comment = ''
            return
        end do
    end function comment_of

    ! `word` occurs in `text` with no letter, digit or _ on either side.
    pure logical function has_word(text, word)
        character(len=*), intent(in) :: text, word
        integer :: start, at
        has_word = .false.
        start = 1
        do
            at = index(text(start:), word)
            if (at == 0) return
            at = start + at - 1
            has_word = .true.
            if (at > 1) has_word = .not. word_char(text(at - 1:at - 1))
            if (has_word .and. at + len(word) <= len(text)) has_word = .not. word_char(text(at + len(word):at + len(word)))
            if (has_word) return
            start = at + 1
        end do
    end function has_word

    pure logical function word_char(c)
        character, intent(in) :: c
        word_char = (c >= 'a' .and. c <= 'z') .or. (c >= 'A' .and. c <= 'Z') .or. (c >= '0' .and. c <= '9') .or. c == '_'
    end function word_char

    ! --- records through their namelist output ---------------------------------------

    function options_dump(opts) result(dump)
        type(solver_options), intent(in) :: opts
        type(record_dump) :: dump
        type(solver_options) :: options
        namelist /options_record/ options
        integer :: unit
        options = opts
        open (newunit=unit, status='scratch', action='readwrite')
        write (unit, nml=options_record)
        dump = dump_from(unit)
    end function options_dump

    function c_record_dump(c) result(dump)
        type(c_options), intent(in) :: c
        type(record_dump) :: dump
        type(c_options) :: record
        namelist /c_record/ record
        integer :: unit
        record = c
        open (newunit=unit, status='scratch', action='readwrite')
        write (unit, nml=c_record)
        dump = dump_from(unit)
    end function c_record_dump

    ! The lines `NAME%COMPONENT=value,` of a namelist output on `unit` (closed after).
    function dump_from(unit) result(dump)
        integer, intent(in) :: unit
        type(record_dump) :: dump
        type(text_line), allocatable :: lines(:)
        character(len=:), allocatable :: name, value
        integer :: i, percent, equals
        rewind (unit)
        call read_unit(unit, lines)
        close (unit)
        allocate (dump%names(0), dump%values(0))
        do i = 1, size(lines)
            percent = index(lines(i)%s, '%')
            equals = index(lines(i)%s, '=')
            if (percent == 0 .or. equals < percent) cycle
            value = trim(adjustl(lines(i)%s(equals + 1:)))
            if (len(value) > 0) then
                if (value(len(value):) == ',') value = trim(value(1:len(value) - 1))
            end if
            name = lower(trim(adjustl(lines(i)%s(percent + 1:equals - 1))))
            dump%names = [dump%names, text_line(name)]
            dump%values = [dump%values, text_line(value)]
        end do
    end function dump_from

    ! logical (T, F), integer, real or text: what a namelist value is.
    function value_kind(value) result(kind)
        character(len=*), intent(in) :: value
        character(len=:), allocatable :: kind
        real(wp) :: x
        integer :: ios
        if (value == 'T' .or. value == 'F') then
            kind = 'logical'
        else if (verify(value, '+-0123456789') == 0) then
            kind = 'integer'
        else
            read (value, *, iostat=ios) x
            kind = merge('real', 'text', ios == 0)
        end if
    end function value_kind

    ! A namelist value as the options are written: yes/no, auto, or the number.
    function readable(value) result(text)
        character(len=*), intent(in) :: value
        character(len=:), allocatable :: text
        real(wp) :: x
        select case (value_kind(value))
        case ('logical')
            text = trim(merge('yes', 'no ', value == 'T'))
        case ('real')
            read (value, *) x
            text = option_text(x)
        case default
            text = value
        end select
    end function readable

    ! --- small helpers -------------------------------------------------------------

    subroutine check(condition, what)
        logical, intent(in) :: condition
        character(len=*), intent(in) :: what
        if (condition) then
            passed = passed + 1
        else
            failed = failed + 1
            write (*, '(a)') '  FAIL '//what
        end if
    end subroutine check

    logical function listed(word, list)
        character(len=*), intent(in) :: word
        type(text_line), intent(in) :: list(:)
        integer :: i
        listed = .false.
        do i = 1, size(list)
            if (list(i)%s == word) listed = .true.
        end do
    end function listed

    subroutine read_lines(file, lines)
        character(len=*), intent(in) :: file
        type(text_line), allocatable, intent(out) :: lines(:)
        integer :: unit, ios
        open (newunit=unit, file=file, status='old', action='read', iostat=ios)
        if (ios /= 0) then
            write (*, '(a)') 'doc_options_tester: cannot open '//file
            stop 2
        end if
        call read_unit(unit, lines)
        close (unit)
    end subroutine read_lines

    ! Every line of `unit`, of any length.
    subroutine read_unit(unit, lines)
        integer, intent(in) :: unit
        type(text_line), allocatable, intent(out) :: lines(:)
        character(len=256) :: chunk
        character(len=:), allocatable :: line
        integer :: ios, got
        allocate (lines(0))
        line = ''
        do
            read (unit, '(a)', advance='no', iostat=ios, size=got) chunk
            if (is_iostat_end(ios)) exit
            line = line//chunk(1:got)
            if (ios == 0) cycle      ! more of the same line
            lines = [lines, text_line(line)]   ! end of record
            line = ''
        end do
    end subroutine read_unit

    pure function lower(text) result(low)
        character(len=*), intent(in) :: text
        character(len=:), allocatable :: low
        integer :: i
        low = text
        do i = 1, len(text)
            if (text(i:i) >= 'A' .and. text(i:i) <= 'Z') low(i:i) = achar(iachar(text(i:i)) + 32)
        end do
    end function lower

    pure function shortened(text) result(short)
        character(len=*), intent(in) :: text
        character(len=:), allocatable :: short
        short = trim(text(1:min(len(text), 60)))
        if (len_trim(text) > 60) short = short//' ...'
    end function shortened

end program doc_options_tester
