!> Numbers as text for messages and output lines.
module regdae_format
    use regdae_kinds, only: wp
    use, intrinsic :: iso_fortran_env, only: int64
    implicit none
    private

    public :: format_real, format_int

    !> An integer without blanks: default kind or 64-bit (the solver's counters,
    !! `solver_stats`, print without conversion).
    interface format_int
        module procedure format_int_default, format_int_64
    end interface format_int

contains

    !> A real in scientific notation without blanks, e.g. `1.234568E-05`,
    !! with `digits` digits after the point (default 6); NaN and Inf as such.
    pure function format_real(x, digits) result(s)
        real(wp), intent(in) :: x
        integer, intent(in), optional :: digits
        character(len=:), allocatable :: s
        character(len=40) :: buf
        character(len=20) :: fmt
        integer :: d, e
        d = 6
        if (present(digits)) d = max(1, min(digits, 17))
        select case (d)   ! the common ones as constant formats (parsed once by the run-time library)
        case (6)
            write (buf, '(es15.6e3)') x
        case (16)
            write (buf, '(es25.16e3)') x
        case default
            fmt = '(es'//format_int_64(int(d + 9, int64))//'.'//format_int_64(int(d, int64))//'e3)'
            write (buf, fmt) x
        end select
        s = trim(adjustl(buf))
        ! Two exponent digits unless three are needed: 1.5E-008 -> 1.5E-08.
        e = scan(s, 'E')
        if (e > 0 .and. len(s) - e == 4) then
            if (s(e + 2:e + 2) == '0') s = s(1:e + 1)//s(e + 3:)
        end if
    end function format_real

    pure function format_int_default(k) result(s)
        integer, intent(in) :: k
        character(len=:), allocatable :: s
        s = format_int_64(int(k, int64))
    end function format_int_default

    ! The decimal digits of k, built by hand (an internal write costs a thousand times more:
    ! the event log formats a line per root).
    pure function format_int_64(k) result(s)
        integer(int64), intent(in) :: k
        character(len=:), allocatable :: s
        character(len=24) :: buf
        integer(int64) :: rest
        integer :: i
        if (k == -huge(k) - 1) then   ! no positive counterpart
            write (buf, '(i0)') k
            s = trim(buf)
            return
        end if
        rest = abs(k)
        i = len(buf) + 1
        do
            i = i - 1
            buf(i:i) = achar(iachar('0') + int(mod(rest, 10_int64)))
            rest = rest/10
            if (rest == 0) exit
        end do
        if (k < 0) then
            i = i - 1
            buf(i:i) = '-'
        end if
        s = buf(i:)
    end function format_int_64

end module regdae_format
