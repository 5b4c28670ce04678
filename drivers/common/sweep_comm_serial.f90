!> The messages of drivers/sweep without MPI (REGDAE_MPI=OFF): one rank, which runs
!! every row itself, so nothing is ever sent. The same interface as sweep_comm_mpi.f90.
module sweep_comm
    implicit none
    private

    public :: comm_start, comm_stop, send_text, receive_text, text_waiting

    !> `receive_text` from whichever rank sent first.
    integer, parameter, public :: any_rank = -1
    !> How the program was built (its progress lines say it).
    character(len=*), parameter, public :: comm_kind = 'serial'

contains

    !> One rank: rank 0 of 1.
    subroutine comm_start(rank, ranks)
        integer, intent(out) :: rank, ranks
        rank = 0
        ranks = 1
    end subroutine comm_start

    subroutine comm_stop()
    end subroutine comm_stop

    !> Never called with one rank (there is no other rank to send to).
    subroutine send_text(dest, tag, id, text)
        integer, intent(in) :: dest, tag, id
        character(len=*), intent(in) :: text
        error stop 'sweep_comm (serial): send_text with one rank'
    end subroutine send_text

    !> Never called with one rank (there is no other rank to receive from).
    subroutine receive_text(source, tag, id, text, from)
        integer, intent(in) :: source, tag
        integer, intent(out) :: id, from
        character(len=:), allocatable, intent(out) :: text
        error stop 'sweep_comm (serial): receive_text with one rank'
    end subroutine receive_text

    !> Nothing is ever waiting.
    logical function text_waiting(tag)
        integer, intent(in) :: tag
        text_waiting = .false.
    end function text_waiting

end module sweep_comm
