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
        write (fmt, '(a,i0,a,i0,a)') '(es', d + 9, '.', d, 'e3)'
        write (buf, fmt) x
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

    pure function format_int_64(k) result(s)
        integer(int64), intent(in) :: k
        character(len=:), allocatable :: s
        character(len=24) :: buf
        write (buf, '(i0)') k
        s = trim(buf)
    end function format_int_64

end module regdae_format
