!> The stability grid (not a test): trust-region runs of Example 5.1 and the
!! slider crank (index 2 and 3) over gamma, eps and rtol, each classified
!!   ok      status ok and error within the bound below,
!!   failed  status failed (with the time reached),
!!   silent  status ok but off the physical branch or error above the bound.
!! Bounds: Example 5.1, max|x - (t+1)| <= 3 eps^(1/4) + 100 rtol (the layer estimate
!! 1.311 eps^(1/4) of doc/ex51.md with margin, plus the integration error); slider crank,
!! on the branch (max |th1 + th2 - pi| <= 0.1) and max theta error <=
!! max(0.1, 6 * 1.311 eps^(1/4) + 300 rtol) (six passes, each a layer; the explicit
!! oracle on the reduced ODE, which knows the branch, has errors up to 250 rtol here).
!! The crank runs check the energy as regdae's invariant (invariant_tol = 1 J) and
!! keep regdae's default branch checks (jump_tol, drift_tol).
!! Index 3 uses gamma1 = gamma, gamma0 = gamma^2/2 (the paper's 2/h and 2/h^2). At most 20000
!! steps per output interval: a cell that needs more counts as failed.
!!
!! Usage: stability [problem=all|ex51|crank2|crank3] [rtol=R] [gamma=G] [checks=on|off]
!! (R, G: one value of the grid; checks=off: without regdae's jump, drift and invariant checks)
!! Output: rows 'problem gamma eps rtol status class max_err t_end code velocity_jump
!!   max_drift invariant_change' (code: regdae's status; the last three from the solver's
!!   statistics) and a last line summary cells=... ok=... failed=... silent=...
program stability_driver
    use regdae
    use ex51_problem, only: new_ex51, orientation_psd
    use slider_crank_problem, only: slider_crank_reduced, new_slider_crank
    use reference_ode, only: integrate_reference
    use driver_support, only: format_int, argument, split_key_value, num, die_usage, read_number
    implicit none
    real(wp), parameter :: pi = acos(-1.0_wp)
    real(wp), parameter :: gammas(8) = [1.0e1_wp, 1.0e2_wp, 1.0e3_wp, 1.0e4_wp, 1.0e5_wp, 1.0e6_wp, 1.0e7_wp, 1.0e8_wp]
    real(wp), parameter :: epss(8) = [1.0e-2_wp, 1.0e-4_wp, 1.0e-6_wp, 1.0e-8_wp, 1.0e-10_wp, 1.0e-12_wp, 1.0e-14_wp, 0.0_wp]
    real(wp), parameter :: rtols(4) = [1.0e-3_wp, 1.0e-5_wp, 1.0e-7_wp, 1.0e-10_wp]
    integer, parameter :: max_steps = 20000   ! per output interval: a cell that needs more is 'failed'
    real(wp) :: crank_times(501), ref(2, 501)
    character(len=*), parameter :: usage = 'usage: stability [problem=all|ex51|crank2|crank3] [rtol=R] [gamma=G] '// &
                                           '[checks=on|off]'
    character(len=:), allocatable :: key, value, which
    real(wp) :: only_rtol, only_gamma
    logical :: checks = .true.
    integer :: i, k, ig, ie, ir, stat, counts(3)
    logical :: ok
    type(slider_crank_reduced) :: reduced

    which = 'all'
    only_rtol = -1.0_wp
    only_gamma = -1.0_wp
    do i = 1, command_argument_count()
        call split_key_value(argument(i), key, value, ok)
        if (.not. ok) call die_usage('stability', usage)
        select case (key)
        case ('problem'); which = value
            if (all(value /= [character(len=6) :: 'all', 'ex51', 'crank2', 'crank3'])) &
                call die_usage('stability', 'bad value "'//value//'" for problem (all, ex51, crank2, crank3)')
        case ('rtol'); call read_number('stability', key, value, only_rtol)
            if (.not. any(rtols == only_rtol)) &
                call die_usage('stability', 'rtol must be one of the grid''s values: 1e-3, 1e-5, 1e-7, 1e-10')
        case ('gamma'); call read_number('stability', key, value, only_gamma)
            if (.not. any(gammas == only_gamma)) &
                call die_usage('stability', 'gamma must be one of the grid''s values: 1e1, 1e2, ..., 1e8')
        case ('checks')
            if (value /= 'on' .and. value /= 'off') call die_usage('stability', usage)
            checks = (value == 'on')
        case default; call die_usage('stability', usage)
        end select
    end do
    crank_times = [(0.02_wp*k, k=0, 500)]
    call integrate_reference(reduced, 0.0_wp, [pi/2, 0.0_wp], crank_times, ref, 1.0e-13_wp, 1.0e-13_wp, stat)
    counts = 0
    write (*, '(a)') '# problem gamma eps rtol status class max_err t_end code velocity_jump max_drift invariant_change'
    do ir = 1, size(rtols)
        do ie = 1, size(epss)
            do ig = 1, size(gammas)
                if (only_rtol > 0.0_wp .and. rtols(ir) /= only_rtol) cycle
                if (only_gamma > 0.0_wp .and. gammas(ig) /= only_gamma) cycle
                if (which == 'all' .or. which == 'ex51') call ex51_cell(gammas(ig), epss(ie), rtols(ir))
                if (which == 'all' .or. which == 'crank2') call crank_cell(2, gammas(ig), epss(ie), rtols(ir))
                if (which == 'all' .or. which == 'crank3') call crank_cell(3, gammas(ig), epss(ie), rtols(ir))
            end do
        end do
    end do
    write (*, '(a)') 'summary cells='//format_int(sum(counts))//' ok='//format_int(counts(1))//' failed='// &
        format_int(counts(2))//' silent='//format_int(counts(3))
    ! Free what the program allocated: valgrind and LeakSanitizer report the rest as lost.
    if (allocated(key)) deallocate (key, value)
    deallocate (which)

contains

    subroutine ex51_cell(gamma, eps, rtol)
        real(wp), intent(in) :: gamma, eps, rtol
        type(solver_options) :: opts
        type(regdae_solver) :: solver
        real(wp) :: x(1), y(1), t, err
        integer :: k, stat
        opts%gamma = gamma
        opts%eps = eps
        opts%rtol = rtol
        opts%atol = rtol
        opts%stop_at_output = .true.
        opts%max_steps = max_steps
        err = 0.0_wp
        call solver%init(new_ex51(orientation_psd), -1.0_wp, [0.0_wp], opts, stat)
        do k = 0, 200
            if (stat < 0) exit
            t = -1.0_wp + 0.01_wp*k
            call solver%advance(t, x, y, stat)
            if (stat >= 0) err = max(err, abs(x(1) - (t + 1.0_wp)))
        end do
        call classify('ex51', gamma, eps, rtol, stat, err, err <= 3.0_wp*eps**0.25_wp + 100.0_wp*rtol, solver)
        call solver%destroy()
    end subroutine ex51_cell

    subroutine crank_cell(index, gamma, eps, rtol)
        integer, intent(in) :: index
        real(wp), intent(in) :: gamma, eps, rtol
        type(solver_options) :: opts
        type(regdae_solver) :: solver
        real(wp) :: th(2), err, dev, bound
        integer :: k, stat
        opts%index = index
        opts%gamma = gamma
        opts%gamma1 = gamma
        opts%gamma0 = gamma**2/2
        opts%eps = eps
        opts%rtol = rtol
        opts%atol = rtol
        opts%max_steps = max_steps
        opts%invariant_tol = 1.0_wp   ! energy (J): 1.7% of the potential-energy range 6 g
        if (.not. checks) then        ! what the grid looks like without regdae's checks
            opts%invariant_tol = 0.0_wp
            opts%jump_tol = 0.0_wp
            opts%drift_tol = 0.0_wp
        end if
        err = 0.0_wp
        dev = 0.0_wp
        call solver%init(new_slider_crank(9.8_wp), 0.0_wp, [pi/2, pi/2], [0.0_wp, 0.0_wp], opts, stat)
        do k = 1, size(crank_times)
            if (stat < 0) exit
            call solver%advance(crank_times(k), th, stat=stat)
            if (stat >= 0) then
                err = max(err, abs(th(1) - ref(1, k)), abs(th(2) - (pi - ref(1, k))))
                dev = max(dev, abs(modulo(th(1) + th(2), 2*pi) - pi))
            end if
        end do
        ! Six singular passes, each a regularization layer of 1.311 eps^(1/4) (doc/ex51.md),
        ! and the tolerance's share: the branch-knowing oracle's error is <= 250 rtol here.
        bound = max(0.1_wp, 6*1.311_wp*eps**0.25_wp + 300*rtol)
        call classify('crank'//format_int(index), gamma, eps, rtol, stat, err, dev <= 0.1_wp .and. err <= bound, &
                      solver)
        call solver%destroy()
    end subroutine crank_cell

    subroutine classify(name, gamma, eps, rtol, stat, err, within, solver)
        character(len=*), intent(in) :: name
        real(wp), intent(in) :: gamma, eps, rtol, err
        integer, intent(in) :: stat
        logical, intent(in) :: within
        type(regdae_solver), intent(in) :: solver
        character(len=:), allocatable :: status, class
        type(solver_stats) :: st
        st = solver%statistics()
        if (stat < 0) then
            status = 'failed'
            class = 'failed'
            counts(2) = counts(2) + 1
        else if (within) then
            status = 'ok'
            class = 'ok'
            counts(1) = counts(1) + 1
        else
            status = 'ok'
            class = 'silent'
            counts(3) = counts(3) + 1
        end if
        write (*, '(a)') name//' '//num(gamma)//' '//num(eps)//' '//num(rtol)//' '//status//' '//class//' '// &
            num(err)//' '//num(st%t)//' '//format_int(stat)//' '//num(st%velocity_jump)//' '//num(st%max_drift)// &
            ' '//num(st%invariant_change)
    end subroutine classify

end program stability_driver
