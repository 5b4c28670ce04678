!> C strings as Fortran strings (SUNDIALS' messages; the C interface).
module regdae_c_strings
    use, intrinsic :: iso_c_binding, only: c_ptr, c_char, c_null_char, c_associated, c_f_pointer
    implicit none
    private

    public :: c_string

contains

    !> The NUL-terminated C string at p (at most 4096 characters; '' for a null pointer).
    function c_string(p) result(s)
        type(c_ptr), intent(in) :: p
        character(len=:), allocatable :: s
        character(kind=c_char), pointer :: chars(:)
        integer :: k, length
        length = 0
        if (c_associated(p)) then
            call c_f_pointer(p, chars, [4096])
            do while (length < size(chars))
                if (chars(length + 1) == c_null_char) exit
                length = length + 1
            end do
        end if
        allocate (character(len=length) :: s)
        do k = 1, length
            s(k:k) = chars(k)
        end do
    end function c_string

end module regdae_c_strings
