!> C strings as Fortran strings (SUNDIALS' messages; the C interface).
module regdae_c_strings
    use, intrinsic :: iso_c_binding, only: c_ptr, c_char, c_size_t, c_associated, c_f_pointer
    implicit none
    private

    public :: c_string

    !> Longest C string read (characters before the NUL).
    integer, parameter :: c_string_max = 4096

    interface
        ! The C library's strnlen: the characters before the NUL, at most maxlen.
        pure function c_strnlen(s, maxlen) bind(C, name='strnlen') result(length)
            import :: c_ptr, c_size_t
            type(c_ptr), value :: s
            integer(c_size_t), value :: maxlen
            integer(c_size_t) :: length
        end function c_strnlen
    end interface

contains

    !> The NUL-terminated C string at p (at most 4096 characters; '' for a null pointer).
    !! The result has an automatic length, not a deferred one (doc/methods.md, "No global state").
    function c_string(p) result(s)
        type(c_ptr), intent(in) :: p
        character(len=c_length(p)) :: s
        character(kind=c_char), pointer :: chars(:)
        integer :: k
        if (len(s) == 0) return
        call c_f_pointer(p, chars, [len(s)])
        do k = 1, len(s)
            s(k:k) = chars(k)
        end do
    end function c_string

    ! The length of the C string at p, at most c_string_max; 0 for a null pointer.
    pure integer function c_length(p)
        type(c_ptr), intent(in) :: p
        c_length = 0
        if (c_associated(p)) c_length = int(c_strnlen(p, int(c_string_max, c_size_t)))
    end function c_length

end module regdae_c_strings
