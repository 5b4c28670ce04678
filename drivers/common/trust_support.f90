!> The pieces of drivers/trust that do not depend on a problem: the weighted error
!! norm, the classes of a cell and their tallies, the grid's cell selection
!! (`part=k/K`, `cell=I`, `rtol=R`), the options with regdae's checks off, and the
!! row format.
!!
!! Classes of a cell (a regdae run with the default options but rtol = atol = R):
!!
!! | class       | when |
!! |-------------|------|
!! | ok          | status 0 and err <= bound |
!! | warned      | status > 0 (a warning, e.g. regdae_warn_unresolved), whatever err |
!! | silent      | status 0 and err > bound |
!! | false_alarm | status < 0 by one of regdae's checks (branch, drift, work, invariant), and the same run |
!! |             | with the checks off ends with status >= 0 and err <= bound |
!! | failed      | any other status < 0 (also the driver's wall budget, `status_budget`) |
!! | refused     | init refused the case: bad input, or `direct` on a GB that is not positive semidefinite |
!! | undecided   | the reference's own uncertainty decides: abs(err - bound) <= ref_chk (below) |
!! | no_reference | the reference could not be computed: the cell is not judged |
!!
!! The reference's uncertainty ref_chk is the same norm of the difference between the reference
!! and its convergence check (the same reference method at a 10 times looser tolerance), taken
!! as the reference's error: where the errors fall with the tolerance the tight run errs by about
!! ref_chk/9, so the true error of the cell lies in [err - ref_chk, err + ref_chk]. A cell is then
!! within its bound when err + ref_chk <= bound, beyond it when err - ref_chk > bound, and
!! undecided otherwise (with a converged reference, ref_chk << bound, only cells at the bound).
!! Where the reference's errors do not fall with its tolerance, ref_chk can understate them: the
!! drivers print the checks so that this can be seen.
module trust_support
    use, intrinsic :: iso_fortran_env, only: int64
    use regdae, only: wp, solver_options, regdae_err_branch, regdae_err_drift, regdae_err_invariant, regdae_err_work
    implicit none
    private

    !> The status the driver gives a run it stopped because it exceeded its wall budget.
    integer, parameter, public :: status_budget = -1000

    integer, parameter, public :: class_ok = 1, class_warned = 2, class_silent = 3, class_false_alarm = 4, &
                                  class_failed = 5, class_refused = 6, class_undecided = 7, class_no_reference = 8
    integer, parameter :: class_count = 8
    character(len=12), parameter :: class_names(class_count) = [character(len=12) :: 'ok', 'warned', 'silent', &
                                                                 'false_alarm', 'failed', 'refused', 'undecided', &
                                                                 'no_reference']

    !> Verdicts of an error against its bound, given the reference's uncertainty.
    integer, parameter, public :: verdict_within = 1, verdict_beyond = -1, verdict_undecided = 0

    !> The counts of the classes of one family's cells.
    type, public :: tally
        integer :: counts(class_count) = 0   !! by class code
    contains
        !> Count one cell of class `code`.
        procedure :: add => tally_add
        !> The line `summary family=NAME cells=.. ok=.. warned=.. silent=.. false_alarm=.. failed=..
        !! refused=.. undecided=.. no_reference=..`.
        procedure :: summary => tally_summary
    end type tally

    !> Which cells of a grid this process runs.
    type, public :: cell_filter
        integer :: part = 1          !! k of part=k/K
        integer :: parts = 1         !! K
        integer :: cell = 0          !! cell=I: only cell I (0: all)
        real(wp) :: rtol = -1.0_wp   !! rtol=R: only the cells of that R (< 0: all)
    contains
        !> Whether cell `index` (numbered from 1 within its family) with tolerance `rtol` runs here:
        !! mod(index, K) = k - 1, cell=I and rtol=R.
        procedure :: selected => filter_selected
    end type cell_filter

    public :: class_name, weighted_error, verdict, cell_class, stopped_by_check, checks_off, write_row, write_note

contains

    !> The name of a class code.
    function class_name(code) result(name)
        integer, intent(in) :: code   !! class_ok ... class_no_reference
        character(len=:), allocatable :: name
        name = trim(class_names(code))
    end function class_name

    subroutine tally_add(self, code)
        class(tally), intent(inout) :: self
        integer, intent(in) :: code
        self%counts(code) = self%counts(code) + 1
    end subroutine tally_add

    function tally_summary(self, family) result(line)
        class(tally), intent(in) :: self
        character(len=*), intent(in) :: family
        character(len=:), allocatable :: line
        integer :: i
        line = 'summary family='//family//' cells='//int_text(sum(self%counts))
        do i = 1, class_count
            line = line//' '//trim(class_names(i))//'='//int_text(self%counts(i))
        end do
    end function tally_summary

    logical function filter_selected(self, index, rtol)
        class(cell_filter), intent(in) :: self
        integer, intent(in) :: index
        real(wp), intent(in) :: rtol
        filter_selected = modulo(index, self%parts) == self%part - 1
        if (self%cell > 0) filter_selected = filter_selected .and. index == self%cell
        if (self%rtol > 0.0_wp) filter_selected = filter_selected .and. rtol == self%rtol
    end function filter_selected

    !> The weighted error max over the outputs 1..good and the components of
    !! |x_i - xref_i| / (rtol |xref_i| + rtol); 0 when good = 0, huge() for a NaN.
    pure real(wp) function weighted_error(x, xref, rtol, good) result(err)
        real(wp), intent(in) :: x(:, :)      !! (components, outputs)
        real(wp), intent(in) :: xref(:, :)   !! the same shape
        real(wp), intent(in) :: rtol         !! R: rtol = atol
        integer, intent(in) :: good          !! the outputs that count, 1..good
        real(wp) :: e
        integer :: i, k
        err = 0.0_wp
        do k = 1, min(good, size(x, 2))
            do i = 1, size(x, 1)
                e = abs(x(i, k) - xref(i, k))/(rtol*abs(xref(i, k)) + rtol)
                if (.not. (e <= huge(1.0_wp))) e = huge(1.0_wp)
                err = max(err, e)
            end do
        end do
    end function weighted_error

    !> A run stopped by one of regdae's checks (velocity jump, drift, invariant, work-energy).
    logical function stopped_by_check(stat)
        integer, intent(in) :: stat   !! the run's status
        stopped_by_check = any(stat == [regdae_err_branch, regdae_err_drift, regdae_err_invariant, regdae_err_work])
    end function stopped_by_check

    !> `opts` with the checks off: jump_tol = drift_tol = work_tol = invariant_tol = 0.
    function checks_off(opts) result(o)
        type(solver_options), intent(in) :: opts
        type(solver_options) :: o
        o = opts
        o%jump_tol = 0.0_wp
        o%drift_tol = 0.0_wp
        o%work_tol = 0.0_wp
        o%invariant_tol = 0.0_wp
    end function checks_off

    !> err against bound when the reference itself is uncertain by ref_chk: verdict_within
    !! (err + ref_chk <= bound), verdict_beyond (err - ref_chk > bound) or verdict_undecided.
    pure integer function verdict(err, bound, ref_chk)
        real(wp), intent(in) :: err, bound, ref_chk
        if (err + ref_chk <= bound) then
            verdict = verdict_within
        else if (err - ref_chk > bound) then
            verdict = verdict_beyond
        else
            verdict = verdict_undecided
        end if
    end function verdict

    !> The class of a cell from its status and its verdict; for a run stopped by a check, the
    !! status and verdict of the same run with the checks off.
    integer function cell_class(stat, judged, rerun_stat, rerun_judged, refused) result(code)
        integer, intent(in) :: stat            !! the run's status (the failure, else the first warning, else 0)
        integer, intent(in) :: judged          !! its verdict (verdict_within, _beyond, _undecided)
        integer, intent(in) :: rerun_stat      !! used only when stopped_by_check(stat)
        integer, intent(in) :: rerun_judged    !! used only when stopped_by_check(stat)
        logical, intent(in) :: refused         !! init refused the case
        if (refused) then
            code = class_refused
        else if (stat > 0) then
            code = class_warned
        else if (stat == 0) then
            select case (judged)
            case (verdict_within); code = class_ok
            case (verdict_beyond); code = class_silent
            case default; code = class_undecided
            end select
        else if (stopped_by_check(stat) .and. rerun_stat >= 0 .and. rerun_judged == verdict_within) then
            code = class_false_alarm
        else if (stopped_by_check(stat) .and. rerun_stat >= 0 .and. rerun_judged == verdict_undecided) then
            code = class_undecided
        else
            code = class_failed
        end if
    end function cell_class

    !> One row: cell family case p1 p2 R status class err err_ref bound t_end steps seconds, then `extra`.
    subroutine write_row(index, family, label, p1, p2, rtol, stat, code, err, err_ref, bound, t_end, steps, seconds, extra)
        integer, intent(in) :: index                !! the cell's number within its family
        character(len=*), intent(in) :: family, label
        real(wp), intent(in) :: p1, p2              !! the start parameters (see the family's header)
        real(wp), intent(in) :: rtol                !! R
        integer, intent(in) :: stat, code           !! regdae's status, the class
        real(wp), intent(in) :: err, err_ref, bound, t_end
        integer(int64), intent(in) :: steps
        real(wp), intent(in) :: seconds
        character(len=*), intent(in) :: extra       !! the family's extra columns (may be empty)
        character(len=12) :: fam, cls
        character(len=20) :: lab
        fam = family
        cls = class_name(code)
        lab = label
        write (*, '(i6,1x,a,1x,a,2(1x,es13.6e2),1x,es8.1e2,1x,i6,1x,a,3(1x,es11.4e3),1x,es12.5e2,1x,i8,1x,es10.3e2,a)') &
            index, fam, lab, p1, p2, rtol, stat, cls, err, err_ref, bound, t_end, steps, seconds, extra
    end subroutine write_row

    !> A `# ` line after a row: `what` and the first 80 characters of `text`.
    subroutine write_note(what, text)
        character(len=*), intent(in) :: what, text
        write (*, '(a)') '#   '//what//text(1:min(80, len(text)))
    end subroutine write_note

    function int_text(k) result(s)
        integer, intent(in) :: k
        character(len=:), allocatable :: s
        character(len=24) :: buf
        write (buf, '(i0)') k
        s = trim(buf)
    end function int_text

end module trust_support
