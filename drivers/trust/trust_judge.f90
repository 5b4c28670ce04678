!> The judge of drivers/trust's cells: a run's class against its bound (trust_support's rules,
!! with the rerun without the checks where a check stopped it, and a later silent departure
!! after the last warning), its row and notes, and the count.
module trust_judge
    use, intrinsic :: iso_fortran_env, only: int64
    use regdae, only: wp
    use trust_support, only: tally, weighted_error, verdict, cell_class, stopped_by_check, write_row, write_note, &
                             class_no_reference, verdict_undecided, class_warned, class_silent
    use trust_grid, only: pi
    use trust_runs, only: run_record
    implicit none
    private
    public :: judge_and_print, split_at_last_warning, fold_crossings, notes, no_reference

contains

    !> Classify a cell of the error families, rerunning it with the checks off when a check
    !! stopped it, print its row and notes, and count it.
    !! ref_chk: the reference's uncertainty in the same norm (trust_support's verdict).
    subroutine judge_and_print(counts, family, index, label, p1, p2, rtol, rec, err, err_ref, bound, ref_chk, rerun, extra)
        type(tally), intent(inout) :: counts
        character(len=*), intent(in) :: family   !! the family's name, the rows' second column
        integer, intent(in) :: index
        character(len=*), intent(in) :: label
        real(wp), intent(in) :: p1, p2, rtol
        type(run_record), intent(in) :: rec
        real(wp), intent(in) :: err, err_ref, bound, ref_chk
        type(run_record), intent(in) :: rerun     !! the checks-off run (used when a check stopped rec)
        character(len=*), intent(in) :: extra
        real(wp) :: rerun_err
        integer :: code, rerun_stat, rerun_judged
        rerun_err = 0.0_wp
        rerun_stat = 0
        rerun_judged = verdict_undecided
        if (stopped_by_check(rec%stat)) then
            rerun_err = rerun%err
            rerun_stat = rerun%stat
            rerun_judged = verdict(rerun_err, bound, ref_chk)
        end if
        code = cell_class(rec%stat, verdict(err, bound, ref_chk), rerun_stat, rerun_judged, rec%refused)
        ! a warning does not cover a later pass that goes wrong with status 0 (a branch left
        ! silently after a harmless warning: fourbar seed=77 cell 107, about 10 error weights when
        ! warned at t = 0.65 and 1.85, 1e8 at status 0 after the fold at t = 3)
        if (code == class_warned .and. rec%silent_later) code = class_silent
        call counts%add(code)
        call write_row(index, family, label, p1, p2, rtol, rec%stat, code, err, err_ref, bound, rec%st%t, &
                       rec%st%steps, rec%seconds, extra)
        call notes(rec, rerun, rerun_err)
    end subroutine judge_and_print

    !> rec%silent_later: after the last output returned with a warning, the reference passes a
    !! singular configuration other than the warned pass's (crossing(k): between outputs k-1 and k;
    !! the warned pass's is the crossing nearest to that output), and at an output with status 0
    !! from there on the error is beyond `bound` and 100 times the largest error at all the outputs
    !! before that crossing: a new departure at a later pass, not what the warned pass left behind
    !! (whose error grows over the passes after it: the crank's slow starts at the singular
    !! configuration, warned at t = 0, 8e4 error weights at R = 1e-8 by t = 10 without a jump).
    subroutine split_at_last_warning(rec, xref, rtol, crossing, bound)
        type(run_record), intent(inout) :: rec
        real(wp), intent(in) :: xref(:, :), rtol
        logical, intent(in) :: crossing(:)
        real(wp), intent(in) :: bound
        real(wp) :: before, e
        integer :: k, last, own
        rec%silent_later = .false.
        last = 0
        do k = 1, rec%good
            if (rec%out_stat(k) > 0) last = k
        end do
        if (last == 0) return
        own = 0
        do k = 1, size(crossing)
            if (.not. crossing(k)) cycle
            if (own == 0) then
                own = k
            else if (abs(k - last) < abs(own - last)) then
                own = k
            end if
        end do
        before = -1.0_wp   ! < 0: no later crossing yet
        do k = last + 1, rec%good
            if (crossing(k) .and. k /= own) before = weighted_error(rec%x, xref, rtol, k - 1)
            if (before < 0.0_wp .or. rec%out_stat(k) /= 0) cycle
            e = weighted_error(rec%x(:, k:k), xref(:, k:k), rtol, 1)
            if (e > max(bound, 100.0_wp*before)) rec%silent_later = .true.
        end do
    end subroutine split_at_last_warning

    !> crossing(k): th1 passes a multiple of pi (a fold of the four-bar, the crank's dead point
    !! (0, pi)) between outputs k-1 and k of the reference th1(:).
    pure function fold_crossings(th1) result(crossing)
        real(wp), intent(in) :: th1(:)
        logical :: crossing(size(th1))
        integer :: k
        crossing = .false.
        do k = 2, size(th1)
            crossing(k) = floor(th1(k - 1)/pi) /= floor(th1(k)/pi)
        end do
    end function fold_crossings

    !> The '#' lines after a row: the message of a failure or warning, the checks-off run.
    subroutine notes(rec, rerun, rerun_err)
        type(run_record), intent(in) :: rec, rerun
        real(wp), intent(in) :: rerun_err
        if (rec%stat < 0) call write_note('message: ', rec%message)
        if (rec%stat > 0) call write_note('warning: ', rec%message)
        if (stopped_by_check(rec%stat)) then
            write (*, '(a,i0,a,es11.4e3,a,es12.5e2)') '#   checks off: status=', rerun%stat, ' err=', rerun_err, &
                ' t_end=', rerun%st%t
            if (rerun%stat < 0) call write_note('checks off, message: ', rerun%message)
        end if
    end subroutine notes

    !> A cell whose reference could not be computed: a row of class no_reference and the cause.
    subroutine no_reference(counts, family, cell, label, p1, p2, rtol, why)
        type(tally), intent(inout) :: counts
        character(len=*), intent(in) :: family   !! the family's name, the rows' second column
        integer, intent(in) :: cell
        character(len=*), intent(in) :: label, why
        real(wp), intent(in) :: p1, p2, rtol
        integer(int64), parameter :: no_steps = 0
        call counts%add(class_no_reference)
        call write_row(cell, family, label, p1, p2, rtol, 0, class_no_reference, 0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, &
                       no_steps, 0.0_wp, '')
        call write_note('no reference: ', why)
    end subroutine no_reference

end module trust_judge
