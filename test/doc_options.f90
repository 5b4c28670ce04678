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
!! (all; the real ones; the integer and switch ones) and no other; the parser's table
!! (`set_option`) takes every component and every key regdae_set_option's list names.
!!
!! Prints one line per failed check and 'N passed, N failed'; exit status 1 if a
!! check failed, 2 for bad arguments.
program doc_options_tester
    use regdae, only: wp, solver_options, set_option, regdae_success, option_text, format_int
    use regdae_c_records, only: c_options, to_c_options
    implicit none

    ! Plain character arrays throughout: gfortran 12 leaks the allocatable components of
    ! derived types grown by array constructors (LeakSanitizer in the sanitized build).
    integer, parameter :: word_len = 64      ! a key, a component's name, a default, a field
    integer, parameter :: value_len = 256    ! a component's value as its namelist output writes it
    integer, parameter :: line_len = 4096    ! a line of doc/api.md or include/regdae.h (longer: the test fails)
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
        character(len=line_len), allocatable :: lines(:)
        character(len=word_len), allocatable :: names(:), keys(:), defaults(:), documented(:)
        character(len=value_len), allocatable :: values(:)
        integer :: i, k, first

        call read_lines(file, lines)
        call record_components(names, values, opts=solver_options())
        first = 0
        do i = 1, size(lines)
            if (trim(adjustl(lines(i))) == table_header) then
                first = i + 2   ! after the header and the |---| line
                exit
            end if
        end do
        call check(first > 0, file//': no options table (no line "'//table_header//'")')
        if (first == 0) return
        allocate (documented(0))
        do i = first, size(lines)
            if (index(adjustl(lines(i)), '|') /= 1) exit
            call table_row(lines(i), keys, defaults)
            call check(size(keys) > 0 .and. size(keys) == size(defaults), file//': the row "'// &
                       shortened(lines(i))//'" must name its keys in backquotes and give one default per key')
            if (size(keys) == 0 .or. size(keys) /= size(defaults)) cycle
            do k = 1, size(keys)
                call check(.not. any(documented == keys(k)), file//': the options table has two rows for `'// &
                           trim(keys(k))//'`')
                documented = [character(len=word_len) :: documented, keys(k)]
                call check_default(trim(keys(k)), trim(defaults(k)), names, values, file)
            end do
        end do
        do i = 1, size(names)
            call check(any(documented == names(i)), 'the option `'//trim(names(i))//'` (solver_options%'// &
                       trim(names(i))//') has no row in the options table of '//file// &
                       ' (section 2): document its values, default and meaning')
        end do
    end subroutine check_table

    ! The documented default of one key, given to set_option on a default record
    ! (whose components are names and values), must leave the record as it is.
    subroutine check_default(key, default, names, values, file)
        character(len=*), intent(in) :: key, default, file
        character(len=*), intent(in) :: names(:), values(:)
        type(solver_options) :: opts
        character(len=word_len), allocatable :: changed_names(:)
        character(len=value_len), allocatable :: changed(:)
        character(len=:), allocatable :: msg
        integer :: stat, j
        logical :: same

        if (.not. any(names == key)) then
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
        call record_components(changed_names, changed, opts=opts)
        same = .true.
        do j = 1, size(names)
            if (changed(j) == values(j)) cycle
            same = .false.
            call check(.false., file//': `'//key//'`: the documented default is "'//default//'", the code''s is '// &
                       readable(trim(values(j)))//' (solver_options%'//trim(names(j))//')')
        end do
        if (same) call check(.true., '')
    end subroutine check_default

    ! The keys (in backquotes, first cell) and defaults (third cell, comma-separated,
    ! without backquotes and remarks in parentheses) of a table row.
    subroutine table_row(row, keys, defaults)
        character(len=*), intent(in) :: row
        character(len=word_len), allocatable, intent(out) :: keys(:), defaults(:)
        character(len=:), allocatable :: cell
        integer :: i, open_quote

        allocate (keys(0), defaults(0))
        cell = table_cell(row, 1)
        open_quote = 0
        do i = 1, len(cell)
            if (cell(i:i) /= '`') cycle
            if (open_quote == 0) then
                open_quote = i
            else
                keys = [character(len=word_len) :: keys, cell(open_quote + 1:i - 1)]
                open_quote = 0
            end if
        end do
        cell = without_remarks(table_cell(row, 3))
        do
            i = index(cell, ',')
            if (i == 0) exit
            defaults = [character(len=word_len) :: defaults, adjustl(cell(1:i - 1))]
            cell = cell(i + 1:)
        end do
        defaults = [character(len=word_len) :: defaults, adjustl(cell)]
    end subroutine table_row

    ! Cell k (1-based) of a Markdown table row (`\|` is a | inside a cell); '' if none.
    function table_cell(row, k) result(cell)
        character(len=*), intent(in) :: row
        integer, intent(in) :: k
        character(len=:), allocatable :: cell
        character(len=:), allocatable :: r
        integer :: i, start, found
        cell = ''
        r = trim(adjustl(row))
        start = 0
        found = 0
        do i = 1, len(r)
            if (r(i:i) /= '|') cycle
            if (i > 1) then
                if (r(i - 1:i - 1) == '\') cycle
            end if
            if (start > 0) found = found + 1
            if (found == k) then
                cell = trim(adjustl(r(start + 1:i - 1)))
                return
            end if
            start = i
        end do
    end function table_cell

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
        character(len=line_len), allocatable :: lines(:)
        character(len=:), allocatable :: kind, any_key, real_key, int_key
        character(len=word_len), allocatable :: names(:), record(:), fields(:)
        character(len=value_len), allocatable :: values(:), record_values(:)
        integer :: i

        call read_lines(file, lines)
        call record_components(names, values, opts=solver_options())
        call record_components(record, record_values, c=to_c_options(solver_options()))
        ! the C record: the header's struct is c_options, which is solver_options
        call struct_fields(lines, 'regdae_options', fields)
        call check(size(fields) > 0, file//': no "typedef struct regdae_options {"')
        do i = 1, max(size(fields), size(record))
            if (i > size(fields)) then
                call check(.false., file//': regdae_options lacks the field `'//trim(record(i))// &
                           '` of c_options (src/regdae_c_records.f90), field '//format_int(i))
            else if (i > size(record)) then
                call check(.false., file//': regdae_options has the field `'//trim(fields(i))// &
                           '`, which c_options (src/regdae_c_records.f90) does not have')
            else
                call check(fields(i) == record(i), file//': field '//format_int(i)//' of regdae_options is `'// &
                           trim(fields(i))//'`, of c_options (src/regdae_c_records.f90) `'//trim(record(i))//'`')
            end if
        end do
        do i = 1, size(names)
            call check(any(record == names(i)), 'src/regdae_c_records.f90: c_options (and '//file// &
                       ': regdae_options) has no field `'//trim(names(i))//'` of solver_options: '// &
                       'regdae_get_options cannot return it')
        end do
        do i = 1, size(record)
            call check(any(names == record(i)), 'src/regdae_c_records.f90: c_options has the field `'// &
                       trim(record(i))//'`, which solver_options does not have')
        end do
        ! the keys each setter's comment lists (the comments: any, real, integer keys)
        any_key = comment_of(lines, 'regdae_set_option')
        real_key = comment_of(lines, 'regdae_set_real_option')
        int_key = comment_of(lines, 'regdae_set_int_option')
        ! the parser's table (set_option's keys) has every component, and every key the
        ! list of regdae_set_option's comment names
        do i = 1, size(names)
            call check(parser_takes(trim(names(i))), 'src/regdae_options.f90: set_option does not take the key `'// &
                       trim(names(i))//'` of solver_options')
        end do
        call check_listed_keys(any_key, file)
        do i = 1, size(names)
            kind = value_kind(trim(values(i)))
            call check_key_listed(any_key, 'regdae_set_option', trim(names(i)), .true., file)
            call check_key_listed(real_key, 'regdae_set_real_option', trim(names(i)), kind == 'real', file)
            call check_key_listed(int_key, 'regdae_set_int_option', trim(names(i)), &
                                  kind == 'integer' .or. kind == 'logical', file)
        end do
    end subroutine check_header

    ! Does set_option's table have `key` (a bad value, not an unknown key)?
    logical function parser_takes(key)
        character(len=*), intent(in) :: key
        type(solver_options) :: opts
        character(len=:), allocatable :: msg
        integer :: stat
        call set_option(opts, key, '?', stat, msg)
        parser_takes = index(msg, 'unknown option') == 0
    end function parser_takes

    ! The key list of regdae_set_option's comment (after "section 2:", up to the ";")
    ! names only keys that set_option takes.
    subroutine check_listed_keys(comment, file)
        character(len=*), intent(in) :: comment, file
        character(len=:), allocatable :: list, key
        integer :: start, finish, comma
        start = index(comment, 'section 2:')
        call check(start > 0, file//': the comment of regdae_set_option has no key list ("section 2: key, ...;")')
        if (start == 0) return
        list = comment(start + len('section 2:'):)
        finish = index(list, ';')
        if (finish > 0) list = list(:finish - 1)
        do while (len_trim(list) > 0)
            comma = index(list, ',')
            if (comma == 0) comma = len(list) + 1
            key = trim(adjustl(list(:comma - 1)))
            if (index(key, '*') > 0) key = trim(adjustl(key(index(key, '*') + 1:)))   ! a line's " * "
            call check(parser_takes(key), file//': the comment of regdae_set_option lists `'//key// &
                       '`, which set_option (src/regdae_options.f90) does not take')
            if (comma > len(list)) exit
            list = list(comma + 1:)
        end do
    end subroutine check_listed_keys

    ! The comment of `function` names `key` if and only if `expected`.
    subroutine check_key_listed(comment, function, key, expected, file)
        character(len=*), intent(in) :: comment    !! the comment of `function`
        character(len=*), intent(in) :: function, key, file
        logical, intent(in) :: expected
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
    subroutine struct_fields(lines, name, fields)
        character(len=*), intent(in) :: lines(:)
        character(len=*), intent(in) :: name
        character(len=word_len), allocatable, intent(out) :: fields(:)
        character(len=:), allocatable :: declaration
        integer :: i, semicolon, blank
        logical :: inside
        allocate (fields(0))
        inside = .false.
        do i = 1, size(lines)
            if (index(lines(i), 'typedef struct '//name//' {') == 1) then
                inside = .true.
            else if (inside .and. index(lines(i), '}') == 1) then
                return
            else if (inside) then
                semicolon = index(lines(i), ';')
                if (semicolon == 0) cycle
                declaration = trim(lines(i)(1:semicolon - 1))
                blank = index(declaration, ' ', back=.true.)
                fields = [character(len=word_len) :: fields, declaration(blank + 1:)]
            end if
        end do
    end subroutine struct_fields

    ! The /** ... */ comment right before the line that declares `int function(`.
    function comment_of(lines, function) result(comment)
        character(len=*), intent(in) :: lines(:)
        character(len=*), intent(in) :: function
        character(len=:), allocatable :: comment
        integer :: i, j
        comment = ''
        do i = 1, size(lines)
            if (index(lines(i), 'int '//function//'(') /= 1) cycle
            do j = i - 1, 1, -1
                comment = trim(lines(j))//' '//comment
                if (index(adjustl(lines(j)), '/**') == 1) return
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

    ! The components of a solver_options (opts) or a c_options (c) record, names (lower
    ! case) and values: the lines `NAME%COMPONENT=value,` of its namelist output.
    subroutine record_components(names, values, opts, c)
        character(len=word_len), allocatable, intent(out) :: names(:)
        character(len=value_len), allocatable, intent(out) :: values(:)
        type(solver_options), intent(in), optional :: opts
        type(c_options), intent(in), optional :: c
        type(solver_options) :: options
        type(c_options) :: record
        namelist /options_record/ options
        namelist /c_record/ record
        character(len=value_len) :: line
        character(len=:), allocatable :: value
        integer :: percent, equals, unit, ios
        allocate (names(0), values(0))
        open (newunit=unit, status='scratch', action='readwrite')
        if (present(opts)) then
            options = opts
            write (unit, nml=options_record)
        else if (present(c)) then
            record = c
            write (unit, nml=c_record)
        end if
        rewind (unit)
        do
            read (unit, '(a)', iostat=ios) line
            if (ios /= 0) exit
            percent = index(line, '%')
            equals = index(line, '=')
            if (percent == 0 .or. equals < percent) cycle
            value = trim(adjustl(line(equals + 1:)))
            if (len(value) > 0) then
                if (value(len(value):) == ',') value = trim(value(1:len(value) - 1))
            end if
            names = [character(len=word_len) :: names, lower(trim(adjustl(line(percent + 1:equals - 1))))]
            values = [character(len=value_len) :: values, value]
        end do
        close (unit)
    end subroutine record_components

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

    ! Every line of a file; a line longer than line_len fails the test.
    subroutine read_lines(file, lines)
        character(len=*), intent(in) :: file
        character(len=line_len), allocatable, intent(out) :: lines(:)
        integer :: unit, ios, k
        open (newunit=unit, file=file, status='old', action='read', iostat=ios)
        if (ios /= 0) then
            write (*, '(a)') 'doc_options_tester: cannot open '//file
            stop 2
        end if
        k = 0
        do
            read (unit, '(a)', iostat=ios)
            if (ios /= 0) exit
            k = k + 1
        end do
        allocate (lines(k))
        rewind (unit)
        do k = 1, size(lines)
            read (unit, '(a)', advance='no', iostat=ios) lines(k)
            if (ios /= 0) cycle   ! the end of the line (iostat_eor): it fitted
            call check(.false., file//': line '//format_int(k)//' has more than '//format_int(line_len)// &
                       ' characters (raise line_len in test/doc_options.f90)')
            read (unit, '(a)')    ! the rest of that line
        end do
        close (unit)
    end subroutine read_lines

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
