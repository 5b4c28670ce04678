!> Numbers from text, strictly: the forms people write on a command line or
!! in an options file, and nothing else.
!!
!! Fortran's list-directed input reads `1-3` as 1e-3, `1+3` as 1e3 and
!! `1.5-2` as 0.015, so a typo becomes a valid value. These routines accept
!!
!! - reals: an optional sign, digits with an optional decimal point (at least
!!   one digit: `5`, `5.`, `.5`, `+5`, `-0.25`), and an optional exponent
!!   `e`, `E`, `d` or `D` with an optional sign and at least one digit
!!   (`1e-3`, `1E-3`, `1d-3`, `2.5D+02`); the value must be finite;
!! - integers: an optional sign and digits, within the default integer's range;
!!
!! with leading and trailing blanks ignored, and refuse everything else
!! (`1-3`, `1e`, `.`, `nan`, `inf`, `0x10`, `1 2`, an empty string, an overflow).
!!
!! Blanks around the number are ignored because a Fortran text has no length of its
!! own: a `character(len=32)` variable holding `1e-3` ends in 28 blanks, which are
!! padding, not input. Where a text does have its own length (a C string, a
!! command-line argument), a blank before or after it is part of what was typed:
!! the C door refuses such a text (`1e-3 `) before reading it, with `has_outer_blank`
!! (the drivers' command line does not, yet).
module regdae_parse
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
    use regdae_kinds, only: wp
    implicit none
    private

    public :: parse_real, parse_integer, has_outer_blank

contains

    !> Read a finite real from `text`; `ok` is false (and `x` unchanged) unless
    !! the whole text is one number of the accepted form.
    subroutine parse_real(text, x, ok)
        character(len=*), intent(in) :: text
        real(wp), intent(inout) :: x
        logical, intent(out) :: ok
        character(len=:), allocatable :: s
        real(wp) :: tmp
        integer :: i, ios, n, digits_before, digits_after, digits_exp

        ok = .false.
        s = trim(adjustl(text))
        n = len(s)
        if (n == 0 .or. n > 256) return
        i = 1
        if (s(i:i) == '+' .or. s(i:i) == '-') i = i + 1
        digits_before = count_digits(s, i)
        digits_after = 0
        if (i <= n) then
            if (s(i:i) == '.') then
                i = i + 1
                digits_after = count_digits(s, i)
            end if
        end if
        if (digits_before + digits_after == 0) return
        if (i <= n) then
            if (index('eEdD', s(i:i)) == 0) return
            s(i:i) = 'e'
            i = i + 1
            if (i <= n) then
                if (s(i:i) == '+' .or. s(i:i) == '-') i = i + 1
            end if
            digits_exp = count_digits(s, i)
            if (digits_exp == 0) return
        end if
        if (i <= n) return
        read (s, *, iostat=ios) tmp
        if (ios /= 0) return
        if (.not. ieee_is_finite(tmp)) return
        x = tmp
        ok = .true.
    end subroutine parse_real

    !> Read a default integer from `text`; `ok` is false (and `k` unchanged)
    !! unless the whole text is an optionally signed string of digits whose
    !! value fits.
    subroutine parse_integer(text, k, ok)
        character(len=*), intent(in) :: text
        integer, intent(inout) :: k
        logical, intent(out) :: ok
        character(len=:), allocatable :: s
        integer :: i, ios, tmp

        ok = .false.
        s = trim(adjustl(text))
        if (len(s) == 0 .or. len(s) > 64) return
        i = 1
        if (s(1:1) == '+' .or. s(1:1) == '-') i = 2
        if (count_digits(s, i) == 0 .or. i <= len(s)) return
        read (s, *, iostat=ios) tmp
        if (ios /= 0) return
        k = tmp
        ok = .true.
    end subroutine parse_integer

    !> Does `text` begin or end with a blank or a control character (tab, newline)? A
    !! door whose texts have their own length (C strings) refuses such a value, so that
    !! `"1e-3 "` is not taken for `1e-3`.
    pure logical function has_outer_blank(text)
        character(len=*), intent(in) :: text   !! the text, at its own length
        has_outer_blank = .false.
        if (len(text) == 0) return
        has_outer_blank = iachar(text(1:1)) <= 32 .or. iachar(text(len(text):len(text))) <= 32
    end function has_outer_blank

    ! The number of decimal digits in s starting at i; i moves past them.
    integer function count_digits(s, i) result(nd)
        character(len=*), intent(in) :: s
        integer, intent(inout) :: i
        nd = 0
        do while (i <= len(s))
            if (index('0123456789', s(i:i)) == 0) exit
            nd = nd + 1
            i = i + 1
        end do
    end function count_digits

end module regdae_parse
