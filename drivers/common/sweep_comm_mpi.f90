!> The messages of drivers/sweep over MPI (module mpi_f08): rank 0 sends rows to
!! the other ranks and receives their result lines. Each message is a text with an
!! integer id: a header (id, length) with tag 2 tag, then the characters with tag
!! 2 tag + 1, both from the same sender (MPI keeps their order). The serial build
!! compiles sweep_comm_serial.f90 instead: the same module with one rank.
module sweep_comm
    use mpi_f08
    implicit none
    private

    public :: comm_start, comm_stop, send_text, receive_text, text_waiting

    !> `receive_text` from whichever rank sent first.
    integer, parameter, public :: any_rank = -1
    !> How the program was built (its progress lines say it).
    character(len=*), parameter, public :: comm_kind = 'MPI'

contains

    !> MPI_Init; this process's rank and the number of ranks.
    subroutine comm_start(rank, ranks)
        integer, intent(out) :: rank, ranks
        call MPI_Init()
        call MPI_Comm_rank(MPI_COMM_WORLD, rank)
        call MPI_Comm_size(MPI_COMM_WORLD, ranks)
    end subroutine comm_start

    subroutine comm_stop()
        call MPI_Finalize()
    end subroutine comm_stop

    !> Send `id` and `text` to rank `dest` (blocking; short texts go eagerly).
    subroutine send_text(dest, tag, id, text)
        integer, intent(in) :: dest, tag, id
        character(len=*), intent(in) :: text
        call MPI_Send([id, len(text)], 2, MPI_INTEGER, dest, 2*tag, MPI_COMM_WORLD)
        call MPI_Send(text, len(text), MPI_CHARACTER, dest, 2*tag + 1, MPI_COMM_WORLD)
    end subroutine send_text

    !> Receive an id and a text with `tag` from `source` (or `any_rank`); `from` is the sender.
    subroutine receive_text(source, tag, id, text, from)
        integer, intent(in) :: source, tag
        integer, intent(out) :: id, from
        character(len=:), allocatable, intent(out) :: text
        integer :: header(2)
        type(MPI_Status) :: status
        if (source == any_rank) then
            call MPI_Recv(header, 2, MPI_INTEGER, MPI_ANY_SOURCE, 2*tag, MPI_COMM_WORLD, status)
        else
            call MPI_Recv(header, 2, MPI_INTEGER, source, 2*tag, MPI_COMM_WORLD, status)
        end if
        from = status%MPI_SOURCE
        id = header(1)
        allocate (character(len=header(2)) :: text)
        call MPI_Recv(text, header(2), MPI_CHARACTER, from, 2*tag + 1, MPI_COMM_WORLD, MPI_STATUS_IGNORE)
    end subroutine receive_text

    !> Has some rank sent a text with `tag` that is not received yet?
    logical function text_waiting(tag)
        integer, intent(in) :: tag
        call MPI_Iprobe(MPI_ANY_SOURCE, 2*tag, MPI_COMM_WORLD, text_waiting, MPI_STATUS_IGNORE)
    end function text_waiting

end module sweep_comm
