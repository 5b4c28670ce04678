!> Where the FORTRAN 77 doors (DREGDAE, DREGDASKR) keep a heap object's address
!! between calls: in words of the caller's IWORK, beside a mark and a check word, so
!! that a call finds the object of its own problem, and an IWORK that never held
!! one (or was changed) is recognized. No SAVE, COMMON or module variable.
module regdae_iwork_address
    use, intrinsic :: iso_c_binding, only: c_ptr, c_null_ptr
    implicit none
    private

    !> Default integers that hold an address (2 for 64-bit addresses and 32-bit integers).
    integer, parameter, public :: address_words = ceiling(real(storage_size(c_null_ptr))/real(storage_size(0)))

    public :: put_address, get_address

contains

    !> Keep `address` in `words` (address_words of them), with `mark` and its check word.
    subroutine put_address(address, mark, mark_word, check_word_out, words)
        type(c_ptr), intent(in) :: address
        integer, intent(in) :: mark             !! the door's own mark
        integer, intent(out) :: mark_word       !! IWORK's word for the mark
        integer, intent(out) :: check_word_out  !! IWORK's word for the check word
        integer, intent(out) :: words(:)        !! IWORK's words for the address
        words = transfer(address, words)
        mark_word = mark
        check_word_out = check_word(mark, words)
    end subroutine put_address

    !> The address `words` hold; false (and null) unless the mark and the check word fit.
    logical function get_address(mark, mark_word, check_word_in, words, address) result(found)
        integer, intent(in) :: mark, mark_word, check_word_in
        integer, intent(in) :: words(:)
        type(c_ptr), intent(out) :: address
        address = c_null_ptr
        found = (mark_word == mark)
        if (found) found = (check_word_in == check_word(mark, words))
        if (found) address = transfer(words, address)
    end function get_address

    ! A check word of the address words (with the mark).
    pure integer function check_word(mark, words)
        integer, intent(in) :: mark, words(:)
        integer :: k
        check_word = mark
        do k = 1, size(words)
            check_word = ieor(ishftc(check_word, 7), words(k))
        end do
    end function check_word

end module regdae_iwork_address
