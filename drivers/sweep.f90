!> Driver: a sweep, many runs from a table, on MPI ranks or serially (issue 13).
!!
!! Usage: sweep table=FILE [out=FILE|-] [progress=SECONDS] [ahead=N] [order=cost|table] [lock_wait=SECONDS]
!!        mpirun -np K sweep table=FILE out=FILE ...
!!   table=FILE    the runs, one a line: a problem (ex51, crank2, crank3, pendulum, chain) and
!!                 key=value words with the drivers' keys (drivers/common/sweep_rows.f90 lists
!!                 them); blank lines and lines starting with '#' are skipped. A row's id is its
!!                 number among the other lines (1, 2, ...): editing the table renumbers the rows
!!   out=-         the result file; '-' (the default) is stdout, without resuming. With a file
!!                 that exists, the rows it holds are not run again (a killed sweep resumes)
!!   progress=5    seconds between the progress lines on stderr (rows done of the total,
!!                 failures so far, time spent and left); 0: only the first and last line
!!   ahead=2       rows queued at first on each other rank (1..100); doubled (up to 100) for a
!!                 rank that ran dry while rank 0 was busy with its own row
!!   order=cost    the order in which rows are handed out: cost, the estimated most expensive
!!                 first (the tightest rtol, then the largest gamma or gamma1; table order among
!!                 equals), so that long rows do not start last; table: in table order
!!   lock_wait=30  seconds to wait for the result file's lock (one writer per file: another
!!                 sweep on it, or the ranks of a killed mpirun); then exit 1, nothing run
!! Output: a '#' line (on a new file), then one line per row, in row order at the end whatever
!! the number of ranks,
!!   <id> <problem> <status> t_end=... <errors> steps=... res_evals=... jac_evals=...
!!       err_test_fails=... conv_fails=... switches=... work_defect=... seconds=... crc=... [message=...]
!! status ok, warning, failed, off_branch, bad_input or crashed (with message=, the rest of the line;
!! crashed: the row killed its process twice, as FILE.crashes records, and is not run again);
!! crc= the line's check (FNV-1a of the rest: a rerun keeps only lines that pass it). Each line
!! is written by one write(2), its errors checked, as soon as its row is done (in the order the
!! rows finish; fsync at most every 10 s and at the end); when every row is done the file is rewritten in row order (FILE.sorting,
!! renamed over FILE). A rerun drops a partial last line (a kill in the middle of a write) and
!! runs the rows not in the file: the file ends equal to an uninterrupted run's. With out=-
!! the lines are printed in row order at the end.
!! Exit status: 0 the sweep is complete (whatever its rows' status), 1 the result file cannot
!! be read or written (a full disk: the sweep stops at the failed write) or stays locked, 2 bad arguments, an unreadable table or a result file of another table.
!! Built with MPI (CMake option REGDAE_MPI) rank 0 runs rows too and serves the other ranks
!! between its output times; without MPI the same program runs every row itself.
program sweep_driver
    use sweep_comm, only: comm_start, comm_stop
    use sweep_schedule, only: sweep_main, serve_rows, release_ranks
    implicit none
    integer :: rank, ranks, code

    code = 0
    call comm_start(rank, ranks)
    if (rank == 0) then
        call sweep_main(ranks, code)
        call release_ranks(ranks)
    else
        call serve_rows()
    end if
    call comm_stop()
    if (code == 1) stop 1
    if (code == 2) stop 2
end program sweep_driver
