!> Numbers as text for messages and output lines.
!!
!! No function here has a deferred-length (`character(len=:), allocatable`)
!! result: gfortran keeps the length of such a result in a static variable per
!! call site, which two threads would share (doc/methods.md, "No global state").
!! The results have automatic lengths, given by pure functions of the arguments.
module regdae_format
    use regdae_kinds, only: wp
    use, intrinsic :: iso_fortran_env, only: int64
    implicit none
    private

    public :: format_real, format_int, text_length

    !> A real in scientific notation without blanks, e.g. `1.234568E-05`, with
    !! `digits` digits after the point (default 6); NaN and Inf as such.
    interface format_real
        module procedure format_real_default, format_real_digits
    end interface format_real

    !> An integer without blanks: default kind or 64-bit (the solver's counters,
    !! `solver_stats`, print without conversion).
    interface format_int
        module procedure format_int_default, format_int_64
    end interface format_int

    !> Length of real_text's buffer (es25.16e3 and shorter fit).
    integer, parameter :: real_buffer_len = 40

contains

    pure function format_real_default(x) result(s)
        real(wp), intent(in) :: x
        character(len=len_trim(real_text(x, 6))) :: s
        s = real_text(x, 6)
    end function format_real_default

    pure function format_real_digits(x, digits) result(s)
        real(wp), intent(in) :: x
        integer, intent(in) :: digits
        character(len=len_trim(real_text(x, digits))) :: s
        s = real_text(x, digits)
    end function format_real_digits

    ! format_real's text, left-adjusted and padded with blanks.
    pure function real_text(x, digits) result(s)
        real(wp), intent(in) :: x
        integer, intent(in) :: digits
        character(len=real_buffer_len) :: s
        character(len=real_buffer_len) :: buf
        character(len=20) :: fmt
        integer :: d, e, n
        d = max(1, min(digits, 17))
        select case (d)   ! the common ones as constant formats (parsed once by the run-time library)
        case (6)
            write (buf, '(es15.6e3)') x
        case (16)
            write (buf, '(es25.16e3)') x
        case default
            fmt = '(es'//format_int_64(int(d + 9, int64))//'.'//format_int_64(int(d, int64))//'e3)'
            write (buf, fmt) x
        end select
        s = adjustl(buf)
        n = len_trim(s)
        ! Two exponent digits unless three are needed: 1.5E-008 -> 1.5E-08.
        e = scan(s(:n), 'E')
        if (e > 0 .and. n - e == 4) then
            if (s(e + 2:e + 2) == '0') s = s(1:e + 1)//s(e + 3:n)
        end if
    end function real_text

    pure function format_int_default(k) result(s)
        integer, intent(in) :: k
        character(len=int_width(int(k, int64))) :: s
        s = format_int_64(int(k, int64))
    end function format_int_default

    ! The decimal digits of k, built by hand (an internal write costs a thousand times more:
    ! the event log formats a line per root).
    pure function format_int_64(k) result(s)
        integer(int64), intent(in) :: k
        character(len=int_width(k)) :: s
        integer(int64) :: rest
        integer :: i
        if (k == -huge(k) - 1) then   ! no positive counterpart
            write (s, '(i0)') k
            return
        end if
        rest = abs(k)
        i = len(s) + 1
        do
            i = i - 1
            s(i:i) = achar(iachar('0') + int(mod(rest, 10_int64)))
            rest = rest/10
            if (rest == 0) exit
        end do
        if (k < 0) s(1:1) = '-'
    end function format_int_64

    ! The number of characters of k in decimal, its sign included.
    pure integer function int_width(k) result(width)
        integer(int64), intent(in) :: k
        integer(int64) :: rest
        if (k == -huge(k) - 1) then
            width = 20
            return
        end if
        rest = abs(k)
        width = merge(2, 1, k < 0)
        do while (rest >= 10)
            rest = rest/10
            width = width + 1
        end do
    end function int_width

    !> The length of an allocatable text, 0 where it is not allocated: the result length of
    !! a function that returns such a text or ''.
    pure integer function text_length(text)
        character(len=:), allocatable, intent(in) :: text
        text_length = 0
        if (allocated(text)) text_length = len(text)
    end function text_length

end module regdae_format
