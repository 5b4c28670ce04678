!> The scheduling of drivers/sweep: rank 0 reads the table, skips the rows the
!! result file already holds, orders the others by their estimated cost (the tightest
!! rtol first, then the largest gamma), hands them out one at a time (`ahead` rows
!! queued per rank) to the other ranks as they return results, runs rows itself in
!! between (serving the others from `run_row`'s hook after every output time), takes
!! back a row queued behind a running one when it has nothing else to run, and
!! appends each result line as soon as it arrives; at the end the result file is
!! rewritten in row order (a new file renamed over the old one). The ranks exchange
!! only through module sweep_comm (MPI, or one rank without it).
module sweep_schedule
    use, intrinsic :: iso_fortran_env, only: int64, error_unit
    use regdae, only: wp, parse_real, solver_options
    use driver_support, only: format_int, argument, split_key_value, parse_count, clock_start, elapsed_seconds
    use sweep_rows, only: run_row, row_problem, row_hook
    use sweep_table, only: text_line, read_lines, table_rows, word, results_present, sort_result_file, &
                           row_real, max_row_length, with_check, lock_file, write_line, sync_file, close_file
    use sweep_comm, only: send_text, receive_text, text_waiting, any_rank, comm_kind
    use sweep_crashes, only: open_crash_log, running_row, crash_counts, crashed_line, remove_crash_log, &
                             crash_if_asked, crash_attempts
    implicit none
    private

    public :: sweep_main, serve_rows, release_ranks

    integer, parameter :: tag_row = 1, tag_result = 2, tag_cancel = 3
    integer, parameter :: stop_id = 0   !! a row id that tells a rank to stop
    integer, parameter :: max_ahead = 100  !! the deepest queue per rank (the largest ahead= too)
    !> Seconds between two fsyncs of the result file (and one at the end).
    real(wp), parameter :: sync_every = 10.0_wp
    !> Seconds a sweep waits by default for the lock of its result file (another sweep on
    !! it, or the orphaned ranks of a killed mpirun, which live on for 2-3 s): lock_wait=.
    real(wp), parameter :: lock_wait_default = 30.0_wp

    !> Rank 0's state: the rows to run, the results held for stdout, the counts.
    type, extends(row_hook) :: sweep_master
        type(text_line), allocatable :: rows(:)      !! the table's rows; id k is rows(k)
        integer, allocatable :: order(:)             !! the ids to run, in the order they are handed out
        type(text_line), allocatable :: held(:)      !! by id: the results for stdout, written at the end
        integer, allocatable :: queued(:)            !! rows handed to each rank and not answered
        integer, allocatable :: pending(:, :)        !! (max_ahead, rank): their ids, in the order sent
        integer, allocatable :: answered(:)          !! answers received from each rank (master_poll's count)
        integer, allocatable :: depth(:)             !! rows to keep queued on each rank: `ahead` at first, doubled
                                                     !! (up to max_ahead) each time the rank ran dry
        logical, allocatable :: arrived(:)           !! by id: its result is in (a second one is dropped)
        logical, allocatable :: taken(:)             !! by id: taken back from the rank it was queued on
        integer :: ranks = 1, ahead = 2
        logical :: by_cost = .true.    !! order=cost (the default) or order=table
        logical :: to_file = .false.   !! out= a file: each result appended when it arrives
        integer :: next = 1            !! the next position in `order` to hand out or run
        integer :: finished = 0        !! results received in this run
        integer :: taken_back = 0      !! rows taken back from the rank they were queued on
        integer :: earlier = 0         !! rows found in the result file
        integer :: crashed = 0         !! rows written as crashed by this run (crash_attempts crashes before)
        integer :: current = 0         !! the row rank 0 is running (0: none)
        integer :: counts(3) = 0       !! failed, off_branch, bad_input
        integer :: fd = 1                             !! where result lines go: the result file's descriptor,
                                                      !! which holds its lock (lock_file), or 1 (stdout)
        character(len=:), allocatable :: out          !! the result file's name ('-': stdout)
        logical :: write_failed = .false.             !! a write, flush or fsync failed: the sweep stops
        character(len=:), allocatable :: write_message
        real(wp) :: every = 5.0_wp     !! seconds between progress lines (0: none)
        integer(int64) :: started = 0, reported = 0, synced = 0
    contains
        procedure :: poll => master_poll
        procedure :: feed => master_feed
        procedure :: take => master_take
        procedure :: report => master_report
        procedure :: take_back => master_take_back
        procedure :: put => master_put
    end type sweep_master

contains

    !> Rank 0: parse the command line, run the sweep. code: 0 done (whatever the rows'
    !! status), 1 the result file cannot be read or written, 2 bad arguments, an unreadable
    !! table or a result file of another table. Every message goes to stderr.
    subroutine sweep_main(ranks, code)
        integer, intent(in) :: ranks
        integer, intent(out) :: code
        type(sweep_master) :: m
        type(text_line), allocatable :: lines(:), problems(:)
        character(len=:), allocatable :: key, value, table, out, tail, msg, note
        logical, allocatable :: done(:), crashed(:)
        integer, allocatable :: line_numbers(:), crashes(:)
        type(text_line), allocatable :: causes(:)
        logical :: ok
        integer :: i, w, pos, ios, nbytes
        real(wp) :: lock_wait
        lock_wait = lock_wait_default
        table = ''
        out = '-'
        code = 2
        do i = 1, command_argument_count()
            call split_key_value(argument(i), key, value, ok)
            msg = ''
            if (.not. ok) then
                msg = 'argument "'//argument(i)//'" is not of the form key=value'
            else
                select case (key)
                case ('table'); table = value
                case ('out'); out = value
                case ('ahead'); call parse_count(key, value, m%ahead, 1, 100, msg)
                case ('order')
                    if (value /= 'cost' .and. value /= 'table') msg = 'bad value "'//value//'" for order (cost|table)'
                    m%by_cost = (value == 'cost')
                case ('progress')
                    call parse_real(value, m%every, ok)
                    if (.not. ok .or. m%every < 0.0_wp) msg = 'bad value "'//value//'" for progress (seconds >= 0)'
                case ('lock_wait')
                    call parse_real(value, lock_wait, ok)
                    if (.not. ok .or. .not. (lock_wait >= 0.0_wp .and. lock_wait <= 86400.0_wp)) &
                        msg = 'bad value "'//value//'" for lock_wait (seconds, 0 to 86400)'
                case default; msg = 'unknown key "'//key//'" (table, out, progress, ahead, order, lock_wait)'
                end select
            end if
            if (len(msg) > 0) then
                call say(msg)
                return
            end if
        end do
        if (len(table) == 0) then
            call say('usage: sweep table=FILE [out=FILE|-] [progress=SECONDS] [ahead=N] [order=cost|table] '// &
                     '[lock_wait=SECONDS]')
            return
        end if
        call read_lines(table, lines, tail, ios, msg)
        if (ios /= 0) then
            call say(msg)
            return
        end if
        call table_rows(lines, tail, m%rows, line_numbers)
        deallocate (lines)
        do i = 1, size(m%rows)   ! a row too long is refused (bad_input) without reading all of it
            if (len(m%rows(i)%s) > max_row_length) then
                call say('table line '//format_int(line_numbers(i))//' (row '//format_int(i)//') has '// &
                         format_int(len(m%rows(i)%s))//' characters, more than '//format_int(max_row_length)// &
                         ': its result is bad_input')
                m%rows(i)%s = m%rows(i)%s(1:max_row_length + 1)
            end if
        end do
        allocate (problems(size(m%rows)))
        do i = 1, size(m%rows)   ! (an array constructor of text_line(f(...)) leaks with gfortran 12)
            problems(i)%s = row_problem(m%rows(i)%s)
        end do
        allocate (done(size(m%rows)), crashed(size(m%rows)), crashes(size(m%rows)), causes(size(m%rows)))
        done = .false.
        crashed = .false.
        m%out = out
        if (out /= '-') then
            ! one writer per result file: an exclusive lock (flock) held until the end
            code = 1
            call lock_file(out, real(lock_wait), m%fd, ios)
            if (ios == 1) then
                call say('cannot open "'//out//'" for writing')
                return
            else if (ios == 2) then
                call say('"'//out//'" is locked by another process (another sweep on it, or the ranks of a '// &
                         'killed mpirun that live on for a few seconds): waited '//format_int(nint(lock_wait))// &
                         ' s (lock_wait=); not started')
                return
            end if
            call results_present(out, problems, done, note, code, msg)
            if (len(note) > 0) call say(note)
            if (code /= 0) then
                call say(msg)
                ! code: results_present's stat, 1 cannot read or cut, 2 another table's results
                return
            end if
            ! the rows that killed their process crash_attempts times are not run again
            nbytes = 0
            inquire (file=out, size=nbytes)
            if (nbytes <= 0) call remove_crash_log(out)   ! a crash log of an earlier result file
            call crash_counts(out, size(m%rows), crashes, causes)
            crashed = (.not. done .and. crashes >= crash_attempts)
            done = done .or. crashed
            if (.not. open_crash_log(out)) call say('cannot open "'//out//'.crashes": a row that kills its '// &
                                                    'process is not recorded (it runs again on a resume)')
        end if
        code = 0
        m%to_file = (out /= '-')
        m%earlier = count(done .and. .not. crashed)
        m%order = pack([(i, i=1, size(m%rows))], .not. done)
        if (m%by_cost) call order_by_cost(m%rows, m%order)
        allocate (m%queued(ranks - 1), m%pending(max_ahead, ranks - 1), m%depth(ranks - 1), m%answered(ranks - 1), &
                  m%arrived(size(m%rows)), m%taken(size(m%rows)))
        m%depth = m%ahead
        m%answered = 0
        if (.not. m%to_file) allocate (m%held(size(m%rows)))
        m%queued = 0
        m%arrived = .false.
        m%taken = .false.
        m%ranks = ranks
        nbytes = 0
        if (m%to_file) inquire (file=out, size=nbytes)   ! the header on a new (or empty) file only
        if (nbytes <= 0) call m%put('# regdae sweep: id problem status t_end=... <errors> steps=... '// &
            'res_evals=... jac_evals=... err_test_fails=... conv_fails=... switches=... work_defect=... seconds=... '// &
            'crc=... [message=...]')
        do i = 1, size(m%rows)
            if (.not. crashed(i)) cycle
            call m%put(with_check(crashed_line(i, problems(i)%s, crashes(i), causes(i)%s)))
            m%crashed = m%crashed + 1
        end do
        if (m%crashed > 0) call say(format_int(m%crashed)//' row(s) crashed '//format_int(crash_attempts)// &
                                    ' times before: written as crashed, not run again')
        if (m%write_failed) then
            call say(m%write_message//'; not started')
            code = 1
            return
        end if
        call say(format_int(size(m%rows))//' rows in "'//table//'", '//format_int(m%earlier)//' already in "'//out// &
                 '", '//format_int(size(m%order))//' to run on '//format_int(ranks)//' rank(s) ('//comm_kind//')')
        m%started = clock_start()
        m%reported = m%started
        do w = 1, ranks - 1
            call m%feed(w)
        end do
        do
            if (m%write_failed) exit
            if (m%next <= size(m%order)) then
                pos = m%next
                m%next = m%next + 1
                call m%take(0, m%order(pos), guarded_row(m%order(pos), m%rows(m%order(pos))%s, m))
                call m%poll()
            else if (m%take_back(pos)) then   ! a row queued behind a running one: run it here
                call m%take(0, pos, guarded_row(pos, m%rows(pos)%s, m))
                call m%poll()
            else if (any(m%queued > 0)) then
                call m%take(-1, 0, '')
                call m%report(.false.)
            else
                exit
            end if
        end do
        if (m%write_failed) then
            call say(m%write_message//'; the sweep stops (the lines written before are kept: a rerun goes on)')
            code = 1
            if (m%to_file) call close_file(m%fd, ios)
            return
        end if
        call m%report(.true.)
        if (m%to_file) then
            call sync_file(m%fd, ios)
            if (ios == 0) call close_file(m%fd, ios)
            if (ios /= 0) then
                call say('cannot write "'//out//'" (fsync or close failed, errno '//format_int(ios)//'): the '// &
                         'rows of this run may not be on the device; a rerun checks every line')
                code = 1
                return
            end if
            call sort_result_file(out, size(m%rows), ios, msg)
            if (ios /= 0) then
                call say(msg)
                code = 1
            else
                call remove_crash_log(out)   ! complete: the crashes are in the result lines
            end if
        else
            do i = 1, size(m%rows)
                if (allocated(m%held(i)%s)) call m%put(m%held(i)%s)
            end do
            if (m%write_failed) then
                call say(m%write_message)
                code = 1
            end if
        end if
    end subroutine sweep_main

    !> Every other rank: run the rows rank 0 sends until it sends `stop_id`, and answer
    !! each: its result line, or an empty text for a row that rank 0 took back (a cancel
    !! received before the row started; one that came later finds the row run, and rank
    !! 0 drops the second result).
    subroutine serve_rows()
        character(len=:), allocatable :: line, ignored, key, value
        integer, allocatable :: cancelled(:)
        integer :: id, from, back, i
        logical :: ok
        allocate (cancelled(0))
        do i = 1, command_argument_count()   ! the crash log of the result file (rank 0 says if it fails)
            call split_key_value(argument(i), key, value, ok)
            if (ok .and. key == 'out' .and. value /= '-') ok = open_crash_log(value)
        end do
        do
            call receive_text(0, tag_row, id, line, from)
            if (id == stop_id) exit
            do while (text_waiting(tag_cancel))
                call receive_text(0, tag_cancel, back, ignored, from)
                cancelled = [cancelled, back]
            end do
            if (any(cancelled == id)) then
                cancelled = pack(cancelled, cancelled /= id)
                call send_text(0, tag_result, id, '')
            else
                call send_text(0, tag_result, id, guarded_row(id, line))
            end if
        end do
    end subroutine serve_rows

    !> run_row with the crash log told which row runs (and the testing hook of
    !! REGDAE_SWEEP_CRASH); on rank 0 the master remembers it for its hook.
    function guarded_row(id, line, m) result(text)
        integer, intent(in) :: id
        character(len=*), intent(in) :: line
        class(sweep_master), intent(inout), optional :: m
        character(len=:), allocatable :: text
        if (present(m)) m%current = id
        call running_row(id)
        call crash_if_asked(id)
        if (present(m)) then
            text = run_row(id, line, m)
            m%current = 0
        else
            text = run_row(id, line)
        end if
        call running_row(0)
    end function guarded_row

    !> Rank 0, at the end: tell every other rank to stop.
    subroutine release_ranks(ranks)
        integer, intent(in) :: ranks
        integer :: w
        do w = 1, ranks - 1
            call send_text(w, tag_row, stop_id, '')
        end do
    end subroutine release_ranks

    !> Between rank 0's output times: receive what has arrived, hand out more rows,
    !! write a progress line when one is due.
    !! A rank whose whole queue was answered by then ran dry while rank 0 was busy with
    !! its own row (rank 0 serves only between its output times): its queue doubles (up
    !! to max_ahead; the rows taken back at the end keep a deep queue from costing).
    subroutine master_poll(self)
        class(sweep_master), intent(inout) :: self
        integer :: before(size(self%queued)), w
        call running_row(0)   ! a failure while serving is not the row's
        before = self%queued
        self%answered = 0
        do while (text_waiting(tag_result))
            call self%take(-1, 0, '')
        end do
        do w = 1, size(self%queued)
            if (before(w) > 0 .and. self%answered(w) >= before(w) .and. self%next <= size(self%order)) then
                self%depth(w) = min(2*self%depth(w), max_ahead)
                call self%feed(w)
            end if
        end do
        call self%report(.false.)
        call running_row(self%current)
    end subroutine master_poll

    !> Queue rows on rank w up to its depth.
    subroutine master_feed(self, w)
        class(sweep_master), intent(inout) :: self
        integer, intent(in) :: w
        integer :: id
        do while (self%queued(w) < self%depth(w) .and. self%next <= size(self%order))
            id = self%order(self%next)
            call send_text(w, tag_row, id, self%rows(id)%s)
            self%next = self%next + 1
            self%queued(w) = self%queued(w) + 1
            self%pending(self%queued(w), w) = id
        end do
    end subroutine master_feed

    !> A result: rank 0's own (from = 0, id, text), or (from = -1) the next one another
    !! rank sends (blocking), after which that rank gets more rows. Then append it to the
    !! result file, one write and a flush (for stdout: hold it until the end).
    subroutine master_take(self, from, id, text)
        class(sweep_master), intent(inout) :: self
        integer, intent(in) :: from, id
        character(len=*), intent(in) :: text
        character(len=:), allocatable :: line, status
        integer :: rid, sender, k
        if (from < 0) then
            call receive_text(any_rank, tag_result, rid, line, sender)
            k = findloc(self%pending(1:self%queued(sender), sender), rid, dim=1)
            self%pending(k:self%queued(sender) - 1, sender) = self%pending(k + 1:self%queued(sender), sender)
            self%queued(sender) = self%queued(sender) - 1
            self%answered(sender) = self%answered(sender) + 1
            call self%feed(sender)
        else
            rid = id
            line = text
        end if
        if (len(line) == 0 .or. self%arrived(rid)) return   ! a row taken back: skipped there, or run twice
        self%arrived(rid) = .true.
        line = with_check(line)
        if (self%to_file) then
            call self%put(line)
            if (self%write_failed) return
        else
            self%held(rid)%s = line
        end if
        self%finished = self%finished + 1
        status = word(line, 3)
        if (status == 'failed') self%counts(1) = self%counts(1) + 1
        if (status == 'off_branch') self%counts(2) = self%counts(2) + 1
        if (status == 'bad_input') self%counts(3) = self%counts(3) + 1
    end subroutine master_take

    !> Write one line to the result file (or stdout) and flush it; every `sync_every`
    !! seconds fsync the file. A failure sets write_failed with a message naming the
    !! file (the sweep then stops: no row is counted that is not written).
    subroutine master_put(self, line)
        class(sweep_master), intent(inout) :: self
        character(len=*), intent(in) :: line
        character(len=:), allocatable :: why
        integer :: ios
        if (self%write_failed) return
        call write_line(self%fd, line, ios, why)
        if (ios == 0 .and. self%to_file .and. elapsed_seconds(self%synced) >= sync_every) then
            call sync_file(self%fd, ios)
            if (ios /= 0) why = 'fsync failed (errno '//format_int(ios)//')'
            self%synced = clock_start()
        end if
        if (ios /= 0) then
            self%write_failed = .true.
            if (self%to_file) then
                self%write_message = 'cannot write "'//self%out//'": '//why
            else
                self%write_message = 'cannot write to stdout: '//why
            end if
        end if
    end subroutine master_put

    !> Nothing is left to hand out: take back a row queued on another rank behind the
    !! one it is running (the last of its queue, not taken back yet), tell that rank to
    !! skip it, and return its id to run here; false when there is none. Without it a
    !! long row queued behind another long one waits while rank 0 has nothing to do.
    logical function master_take_back(self, id) result(found)
        class(sweep_master), intent(inout) :: self
        integer, intent(out) :: id
        integer :: w, k
        found = .false.
        id = 0
        do w = 1, self%ranks - 1
            do k = self%queued(w), 2, -1
                if (self%taken(self%pending(k, w)) .or. self%arrived(self%pending(k, w))) cycle
                id = self%pending(k, w)
                self%taken(id) = .true.
                self%taken_back = self%taken_back + 1
                call send_text(w, tag_cancel, id, '')
                found = .true.
                return
            end do
        end do
    end function master_take_back

    !> A progress line on stderr when `every` seconds have passed since the last (or
    !! `final`): rows done of the total, failures so far, time spent and left.
    subroutine master_report(self, final)
        class(sweep_master), intent(inout) :: self
        logical, intent(in) :: final
        real(wp) :: spent, left
        character(len=:), allocatable :: estimate, prefix
        if (.not. final .and. (self%every <= 0.0_wp .or. elapsed_seconds(self%reported) < self%every)) return
        self%reported = clock_start()
        spent = elapsed_seconds(self%started)
        estimate = ''
        if (.not. final .and. self%finished > 0) then
            left = spent/self%finished*(size(self%order) - self%finished)
            estimate = ', about '//duration(left)//' left'
        end if
        prefix = ''
        if (final) prefix = 'done, '
        if (final .and. self%taken_back > 0) estimate = ', '//format_int(self%taken_back)//' row(s) taken back '// &
                                                        'from the rank they were queued on'
        call say(prefix//format_int(self%earlier + self%finished + self%crashed)//'/'// &
                 format_int(size(self%rows))//' rows ('//format_int(self%earlier)//' from before); this run: '// &
                 format_int(self%counts(1))//' failed, '// &
                 format_int(self%counts(2))//' off_branch, '//format_int(self%counts(3))//' bad_input, '// &
                 format_int(self%crashed)//' crashed; '// &
                 duration(spent)//estimate)
    end subroutine master_report

    !> Sort the ids to run by their estimated cost, the most expensive first, so that
    !! the long rows start early and do not leave one rank working alone at the end: the
    !! tightest rtol first (a run's steps grow as rtol falls), then the largest gamma
    !! (gamma or gamma1: the stiffer stabilization), table order among equals. A row
    !! without rtol has the solver's default; one without a numeric gamma counts as 0.
    subroutine order_by_cost(rows, ids)
        type(text_line), intent(in) :: rows(:)
        integer, intent(inout) :: ids(:)
        type(solver_options) :: defaults
        real(wp), allocatable :: rtol(:), gamma(:)
        integer, allocatable :: work(:)
        integer :: i, id
        allocate (rtol(size(rows)), gamma(size(rows)), work(size(ids)))
        do i = 1, size(ids)
            id = ids(i)
            rtol(id) = row_real(rows(id)%s, 'rtol', defaults%rtol)
            gamma(id) = max(row_real(rows(id)%s, 'gamma', 0.0_wp), row_real(rows(id)%s, 'gamma1', 0.0_wp))
        end do
        call merge_sort(ids, work)
    contains
        logical function before(a, b)
            integer, intent(in) :: a, b
            if (rtol(a) /= rtol(b)) then
                before = rtol(a) < rtol(b)
            else if (gamma(a) /= gamma(b)) then
                before = gamma(a) > gamma(b)
            else
                before = a < b
            end if
        end function before

        recursive subroutine merge_sort(x, w)
            integer, intent(inout) :: x(:), w(:)
            integer :: half, i, j, k
            logical :: take_right
            if (size(x) < 2) return
            half = size(x)/2
            call merge_sort(x(:half), w(:half))
            call merge_sort(x(half + 1:), w(half + 1:))
            w = x
            i = 1
            j = half + 1
            do k = 1, size(x)
                if (j <= size(x)) then
                    if (i > half) then
                        take_right = .true.
                    else
                        take_right = before(w(j), w(i))
                    end if
                else
                    take_right = .false.
                end if
                if (take_right) then
                    x(k) = w(j)
                    j = j + 1
                else
                    x(k) = w(i)
                    i = i + 1
                end if
            end do
        end subroutine merge_sort
    end subroutine order_by_cost

    !> Seconds as '12 s', '3.4 min' or '2.5 h'.
    function duration(seconds) result(text)
        real(wp), intent(in) :: seconds
        character(len=:), allocatable :: text
        character(len=16) :: buffer
        if (seconds < 100.0_wp) then
            write (buffer, '(f8.1, a)') seconds, ' s'
        else if (seconds < 6000.0_wp) then
            write (buffer, '(f8.1, a)') seconds/60.0_wp, ' min'
        else
            write (buffer, '(f12.1, a)') seconds/3600.0_wp, ' h'
        end if
        text = trim(adjustl(buffer))
    end function duration

    subroutine say(text)
        character(len=*), intent(in) :: text
        write (error_unit, '(a)') 'sweep: '//text
        flush (error_unit)
    end subroutine say

end module sweep_schedule
