!> Driver: the scalable benchmark, a planar chain of N unit links with unit
!! masses in Cartesian coordinates (drivers/problems/chain_problem.f90), started
!! straight and horizontal at rest, falling under gravity; optionally with every
!! other joint and the free end on the horizontal line through the pivot
!! (slider=yes: N/2 slider cranks in series, each passing a rank-deficient
!! configuration when its crank swings through the bottom).
!!
!! Usage: chain [key=value ...]
!!   n_links=16 (N >= 1; even with slider=yes)   slider=no|yes   tf=1   nout=100   gravity=9.81
!!   mass=1 (of each joint)   stiffness=0 damping=0 (vertical springs -k y and dashpots -c y' under
!!   every joint: with a light mass, the stiff variant, e.g. mass=1e-2 stiffness=1e4 damping=10)
!!   peer=no|yes (yes: plain IDA with its band solver on the unregularized stabilized index-2
!!   form, drivers/common/chain_peer.f90, instead of regdae), and the solver options (formulation
!!   and linear_solver choose the engine; the defaults take the augmented formulation and the
!!   sparse (KLU) solver from 8 links on)
!! Output: '#' lines, the table 't x_end y_end energy max_abs_g sigma_min' at nout+1 equally spaced
!! times (sigma_min: sigma_min(GB) there, NaN for the peer),
!! and the last line
!!   summary n_links=... slider=... engine=... engine_end=... status=ok|warning|failed t_end=... max_drift=... energy_change=...
!!           singular_passes=... sigma_min=... [max_err_th=... (N = 2 with slider, no springs: against the slider
!!           crank's reduced ODE by CVODE at 1e-13)] steps=... res_evals=... jac_evals=...
!!           err_test_fails=... conv_fails=... seconds=... output_seconds=... seconds_per_step=... peak_rss_kb=...
!! (engine: formulation/linear solver at the start, or peer/band; engine_end: the same at the end of
!! the run, after any switch of formulation; seconds: init and advances, not the output;
!! peak_rss_kb: the process's peak resident memory (getrusage), set-up and output included;
!! max_drift: max |g| at the outputs; energy_change: max |E - E(0)| at the outputs; status=warning:
!! an advance returned a warning (x valid, the tolerance maybe not met; a '# warning:' line says
!! which), the run goes on.)
!! Exit status: 0 ok or warning, 1 solver failure, 2 bad arguments.
program chain_driver
    use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
    use, intrinsic :: iso_c_binding, only: c_long
    use regdae
    use chain_problem, only: chain, new_chain, chain_start, chain_energy_of, chain_violation
    use chain_peer, only: run_chain_peer
    use slider_crank_problem, only: slider_crank_reduced
    use reference_ode, only: integrate_reference
    use driver_support, only: resolved_line, event_lines, &
                              format_int, common_argument, stats_fields, run_status, argument, split_key_value, num, &
                              stopwatch, warning_log, die_usage, read_number, read_count
    implicit none

    interface
        !> The process's peak resident memory in kB (drivers/common/process_memory.c).
        integer(c_long) function peak_rss_kb() bind(C, name='regdae_peak_rss_kb')
            import :: c_long
        end function peak_rss_kb
    end interface

    character(len=*), parameter :: prog = 'chain'
    real(wp), parameter :: t0 = 0.0_wp, pi = acos(-1.0_wp)
    call run_chain()

contains

    subroutine run_chain()
        type(solver_options) :: opts
        type(regdae_solver) :: solver
        type(solver_stats) :: st
        type(chain) :: problem
        type(stopwatch) :: solve_clock, output_clock
        type(warning_log) :: warnings   ! the advances' warnings
        type(slider_crank_reduced) :: reduced
        character(len=:), allocatable :: events
        character(len=:), allocatable :: key, value, status_text, engine, engine_end, extra
        integer :: i, k, nout, stat, n_links
        logical :: ok, slider, peer
        real(wp) :: tf, gravity, seconds, e, e0, energy_change, max_drift, drift, max_err, joint_mass, stiffness, damping
        real(wp), allocatable :: times(:), q0(:), v0(:), q(:), v(:), y(:), table(:, :), qpeer(:, :), ref(:, :), angle1(:)
        integer :: steps, res_evals, jac_evals
        character(len=:), allocatable :: peer_message

        events = ''
        n_links = 16
        slider = .false.
        peer = .false.
        tf = 1.0_wp
        nout = 100
        gravity = 9.81_wp
        joint_mass = 1.0_wp
        stiffness = 0.0_wp
        damping = 0.0_wp
        do i = 1, command_argument_count()
            call split_key_value(argument(i), key, value, ok)
            if (.not. ok) call die_usage(prog, 'argument "'//argument(i)//'" is not of the form key=value')
            select case (key)
            case ('n_links'); call read_count(prog, key, value, n_links, 1, 1000000)
            case ('slider'); slider = yes_no(key, value)
            case ('peer'); peer = yes_no(key, value)
            case ('tf'); call read_number(prog, key, value, tf)
            case ('gravity'); call read_number(prog, key, value, gravity)
            case ('mass'); call read_number(prog, key, value, joint_mass)
                if (.not. (joint_mass > 0.0_wp)) call die_usage(prog, 'mass must be > 0')
            case ('stiffness'); call read_number(prog, key, value, stiffness)
                if (.not. (stiffness >= 0.0_wp)) call die_usage(prog, 'stiffness must be >= 0')
            case ('damping'); call read_number(prog, key, value, damping)
                if (.not. (damping >= 0.0_wp)) call die_usage(prog, 'damping must be >= 0')
            case default
                call common_argument(prog, key, value, opts, nout)
            end select
        end do
        if (.not. (tf > t0)) call die_usage(prog, 'tf must be > 0')
        if (slider .and. mod(n_links, 2) /= 0) call die_usage(prog, 'slider=yes needs an even n_links')

        problem = new_chain(n_links, slider, gravity)
        problem%joint_mass = joint_mass
        problem%stiffness = stiffness
        problem%damping = damping
        allocate (q0(problem%n), v0(problem%n), q(problem%n), v(problem%n), y(problem%m))
        allocate (table(6, 0:nout), angle1(0:nout))
        call chain_start(problem, q0, v0)
        times = [(t0 + (tf - t0)*real(k, wp)/real(nout, wp), k=0, nout)]
        write (*, '(a)') '# regdae chain: '//format_int(n_links)//' unit links, unit masses, Cartesian coordinates'
        if (slider) write (*, '(a)') '# slider: every other joint and the free end on the line y = 0'
        write (*, '(a)') '# n = '//format_int(problem%n)//' coordinates, m = '//format_int(problem%m)// &
            ' constraints; rtol='//num(opts%rtol)//' atol='//num(opts%atol)//' tf='//num(tf)//' nout='//format_int(nout)

        max_drift = 0.0_wp
        energy_change = 0.0_wp
        max_err = -1.0_wp
        e0 = chain_energy_of(problem, q0, v0)
        if (peer) then
            ! plain IDA (band) on the unregularized stabilized index-2 form
            allocate (qpeer(problem%n, nout + 1))
            call run_chain_peer(n_links, slider, opts%rtol, opts%atol, times, qpeer, steps, res_evals, jac_evals, &
                                seconds, stat, peer_message, max_drift, joint_mass, stiffness, damping)
            st%steps = steps
            st%res_evals = res_evals
            st%jac_evals = jac_evals
            st%t = t0
            energy_change = ieee_value(1.0_wp, ieee_quiet_nan)   ! the peer returns positions only
            do k = 0, nout
                if (stat /= 0 .and. .not. all(qpeer(:, k + 1) == qpeer(:, k + 1))) exit
                st%t = times(k + 1)
                table(:, k) = [times(k + 1), qpeer(problem%n - 1, k + 1), qpeer(problem%n, k + 1), &
                               ieee_value(1.0_wp, ieee_quiet_nan), chain_violation(problem, qpeer(:, k + 1)), &
                               ieee_value(1.0_wp, ieee_quiet_nan)]
            end do
            engine = 'peer/band'
            engine_end = engine
            status_text = 'ok'
            if (stat /= 0) then
                write (*, '(a)') '# error: '//peer_message
                status_text = 'failed'
            end if
            call output_clock%start()
            call write_table(table, min(nout, nint((st%t - t0)/(tf - t0)*nout)))
            call output_clock%stop()
            extra = ''
        else
            call solve_clock%start()
            call solver%init(problem, t0, q0, v0, opts, stat)
            call solve_clock%stop()
            engine = formulation_name(solver%formulation())//'/'//linear_solver_name(solver%linear_solver())
            k = -1
            if (stat == regdae_success) then
                write (*, '(a)') resolved_line(solver)
                do k = 0, nout
                    call solve_clock%start()
                    call solver%advance(times(k + 1), q, y, stat, v)
                    call solve_clock%stop()
                    if (stat < 0) exit
                    call warnings%note(solver, stat, times(k + 1))
                    e = chain_energy_of(problem, q, v)
                    drift = chain_violation(problem, q)
                    energy_change = max(energy_change, abs(e - e0))
                    max_drift = max(max_drift, drift)
                    table(:, k) = [times(k + 1), q(problem%n - 1), q(problem%n), e, drift, solver%sigma_min()]
                    angle1(k) = atan2(q(1), -q(2))   ! joint 1 from the downward vertical
                end do
                if (stat > 0) stat = regdae_success
            end if
            seconds = solve_clock%seconds()
            st = solver%statistics()
            status_text = run_status(solver, stat, warnings)
            call output_clock%start()
            call write_table(table, k - 1)
            call output_clock%stop()
            extra = ' singular_passes='//format_int(st%singular_passes)//' sigma_min='//num(st%sigma_min)
            if (slider .and. n_links == 2 .and. k > nout .and. stiffness == 0.0_wp .and. damping == 0.0_wp) then
                ! the slider crank of Example 5.2: joint 1 at (sin th1, -cos th1)
                allocate (ref(2, 0:nout))
                reduced%gravity = gravity
                call integrate_reference(reduced, t0, [pi/2, 0.0_wp], times, ref, 1.0e-13_wp, 1.0e-13_wp, k)
                max_err = ieee_value(1.0_wp, ieee_quiet_nan)
                if (k == 0) max_err = maxval(abs(angle1 - ref(1, :)))
                extra = extra//' max_err_th='//num(max_err)
            end if
            engine_end = formulation_name(solver%formulation())//'/'//linear_solver_name(solver%linear_solver())
            events = event_lines(solver)
            call solver%destroy()
        end if
        write (*, '(a)', advance='no') events
        write (*, '(a)') 'summary n_links='//format_int(n_links)//' slider='//trim(merge('yes', 'no ', slider))// &
            ' engine='//engine//' engine_end='//engine_end//' status='//status_text//' t_end='//num(st%t)// &
            ' max_drift='//num(max_drift)// &
            ' energy_change='//num(energy_change)//extra//stats_fields(st, seconds, output_clock%seconds())// &
            ' seconds_per_step='//num(seconds/max(1.0_wp, real(st%steps, wp)))// &
            ' peak_rss_kb='//format_int(int(peak_rss_kb()))
        if (status_text == 'failed') stop 1
    end subroutine run_chain

    logical function yes_no(name, text)
        character(len=*), intent(in) :: name, text
        if (text /= 'yes' .and. text /= 'no') call die_usage(prog, 'bad value "'//text//'" for '//name//' (yes, no)')
        yes_no = (text == 'yes')
    end function yes_no

    subroutine write_table(table, last)
        real(wp), intent(in) :: table(:, 0:)
        integer, intent(in) :: last
        integer :: j
        write (*, '(a1,a23,5a24)') '#', 't', 'x_end', 'y_end', 'energy', 'max_abs_g', 'sigma_min'
        do j = 0, last
            write (*, '(6es24.15e3)') table(:, j)
        end do
    end subroutine write_table

end program chain_driver
