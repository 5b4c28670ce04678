!> The text forms of drivers/trust's rows, notes and headers: an integer, a real in the rows'
!! es11.4e3 or with 17 significant digits, a list of reals.
module trust_text
    use regdae, only: wp
    implicit none
    private
    public :: itext, etext, num_exact, list_text

contains

    !> An integer in i0.
    function itext(k) result(s)
        integer, intent(in) :: k
        character(len=:), allocatable :: s
        character(len=24) :: buf
        write (buf, '(i0)') k
        s = trim(buf)
    end function itext

    !> A real in es11.4e3 (the rows' format for errors).
    function etext(x) result(s)
        real(wp), intent(in) :: x
        character(len=:), allocatable :: s
        character(len=16) :: buf
        write (buf, '(es11.4e3)') x
        s = trim(adjustl(buf))
    end function etext

    !> A real with 17 significant digits (read back exactly).
    function num_exact(x) result(s)
        real(wp), intent(in) :: x
        character(len=:), allocatable :: s
        character(len=32) :: buf
        write (buf, '(es24.16e3)') x
        s = trim(adjustl(buf))
    end function num_exact

    !> The values of `a` in es11.4e3, or (exact = .true., the seeded grids' draws, which may be
    !! negative) with 17 significant digits.
    function list_text(a, exact) result(s)
        real(wp), intent(in) :: a(:)
        logical, intent(in), optional :: exact
        character(len=:), allocatable :: s
        integer :: i
        logical :: digits17
        digits17 = .false.
        if (present(exact)) digits17 = exact
        s = ''
        do i = 1, size(a)
            if (digits17) then
                s = s//' '//num_exact(a(i))
            else
                s = s//' '//etext(a(i))
            end if
        end do
    end function list_text

end module trust_text
