!> Tests of integrator=radau through the solver (regdae_radau_integrator): its
!! results against independent references and against integrator=ida and
!! integrator=dopri5 on the slider crank, the pendulum and the chain; the augmented
!! formulation under Radau against the eliminated one and the references; the
!! option's parsing and refusals; its statistics. And the integrator alone on the car axis's
!! index-3 form with RADAU5's conventions against RADAU5's step counts.
module test_radau_solver
    use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
    use regdae
    use slider_crank_problem, only: slider_crank_reduced, new_slider_crank
    use pendulum_problem, only: pendulum_angle, new_pendulum
    use chain_problem, only: chain, new_chain, chain_start
    use car_axis_problem, only: car_axis, new_car_axis, car_axis_reference, car_axis_t_end, car_axis_x0, car_axis_v0
    use car_axis_index3_problem, only: car_axis_index3, car_axis_index3_setup
    use regdae_radau_iia, only: radau_integrator
    use regdae_radau_system, only: radau_options, radau_stats
    use regdae_format, only: format_int
    use reference_ode, only: integrate_reference
    use regdae_testing, only: checker, test_case, new_test
    implicit none
    private
    public :: radau_solver_tests

    real(wp), parameter :: pi = acos(-1.0_wp)
    integer, parameter :: integrators(3) = [integrator_radau, integrator_ida, integrator_dopri5]
    integer, parameter :: formulations(2) = [formulation_augmented, formulation_eliminated]

contains

    function radau_solver_tests() result(tests)
        type(test_case), allocatable :: tests(:)
        tests = [new_test('radau_option', radau_option), &
                 new_test('radau_slider_crank', radau_slider_crank), &
                 new_test('radau_pendulum', radau_pendulum), &
                 new_test('radau_chain', radau_chain), &
                 new_test('radau_refresh_eliminated', radau_refresh_eliminated), &
                 new_test('radau_car_axis', radau_car_axis), &
                 new_test('radau_car_axis_index3', radau_car_axis_index3), &
                 new_test('radau_augmented_option', radau_augmented_option), &
                 new_test('radau_augmented_slider_crank', radau_augmented_slider_crank), &
                 new_test('radau_augmented_pendulum', radau_augmented_pendulum), &
                 new_test('radau_augmented_chain', radau_augmented_chain), &
                 new_test('auto_picks_radau_when_small', auto_picks_radau_when_small)]
    end function radau_solver_tests

    ! integrator=radau is parsed and named; it needs the eliminated formulation.
    subroutine radau_option(chk)
        type(checker), intent(inout) :: chk
        type(solver_options) :: opts
        character(len=:), allocatable :: msg
        integer :: stat
        call set_option(opts, 'integrator', 'radau', stat, msg)
        call chk%equal(stat, regdae_success, 'integrator=radau parsed')
        call chk%equal(opts%integrator, integrator_radau, 'integrator=radau sets integrator_radau')
        call chk%true(integrator_name(integrator_radau) == 'radau', 'its name')
        call validate_options(opts, stat, msg)
        call chk%equal(stat, regdae_success, 'integrator=radau valid')
        opts%formulation = formulation_multiplier
        call validate_options(opts, stat, msg)
        call chk%equal(stat, regdae_err_bad_input, 'integrator=radau with formulation=multiplier refused')
        call chk%true(index(msg, 'integrator=radau needs formulation=eliminated or augmented') > 0, &
                      'with a message that says why')
        opts%formulation = formulation_auto
        call set_option(opts, 'integrator', 'radau5', stat, msg)
        call chk%equal(stat, regdae_err_bad_input, 'integrator=radau5 refused')
        call chk%true(index(msg, 'radau') > 0, 'the message names radau among the values')
    end subroutine radau_option

    ! The slider crank at index 3 from the paper's start (th = (pi/2, pi/2), at rest),
    ! 20 outputs on [0, 5] through 3 singular passes, rtol = atol = 1e-8: th1 against
    ! the reduced ODE by CVODE at 1e-13, for each integrator, and radau against ida and
    ! dopri5. Measured: errors 1.6e-9 (radau), 2.0e-7 (ida), 1.3e-8 (dopri5); the bound
    ! 1e-6 = 100 rtol is the tolerance's global error with a margin (the passes amplify
    ! the local errors: ex52's max_err_th at rtol 1e-8 is 2.5e-8 on [0, 10]).
    subroutine radau_slider_crank(chk)
        type(checker), intent(inout) :: chk
        type(regdae_solver) :: solver
        type(solver_stats) :: st
        type(slider_crank_reduced) :: reduced
        real(wp) :: times(20), ref(2, 20), th(2, 20, 3), err(3)
        integer :: stat, k, i, rstat
        times = [(0.25_wp*k, k=1, 20)]
        call integrate_reference(reduced, 0.0_wp, [pi/2, 0.0_wp], times, ref, 1.0e-13_wp, 1.0e-13_wp, rstat)
        call chk%equal(rstat, 0, 'reference')
        do i = 1, 3
            call run_outputs(solver, new_slider_crank(9.8_wp), [pi/2, pi/2], integrators(i), times, th(:, :, i), stat)
            call chk%true(stat >= 0, 'slider crank, '//integrator_name(integrators(i))//': reaches t = 5')
            err(i) = maxval(abs(th(1, :, i) - ref(1, :)))
            call chk%true(err(i) <= 1.0e-6_wp, 'slider crank, '//integrator_name(integrators(i))//': th1 error <= 1e-6')
            if (i == 1) then
                st = solver%statistics()
                call chk%true(st%steps > 0 .and. st%jac_evals > 0 .and. st%lin_setups > 0 .and. &
                              st%nonlin_iters >= st%steps .and. st%switches == 0, 'radau''s statistics')
            end if
            call solver%destroy()
        end do
        call chk%true(maxval(abs(th(:, :, 1) - th(:, :, 2))) <= 2.0e-6_wp, 'slider crank: radau = ida within 2e-6')
        call chk%true(maxval(abs(th(:, :, 1) - th(:, :, 3))) <= 2.0e-6_wp, 'slider crank: radau = dopri5 within 2e-6')
        write (*, '(a,3es10.2)') '    slider crank th1 error (radau, ida, dopri5): ', err
    end subroutine radau_slider_crank

    ! The Cartesian pendulum from the horizontal, at rest, on [0, 2] (21 outputs),
    ! rtol = atol = 1e-8: the position against the angle ODE by CVODE at 1e-13, for
    ! each integrator. Measured: 9.2e-10 (radau), 6.9e-8 (ida), 9.4e-9 (dopri5); bound 1e-6.
    subroutine radau_pendulum(chk)
        type(checker), intent(inout) :: chk
        type(regdae_solver) :: solver
        type(pendulum_angle) :: angle
        real(wp) :: times(21), ref(2, 21), x(2, 21, 3), err(3)
        integer :: stat, k, i, rstat
        times = [(0.1_wp*k, k=0, 20)]
        call integrate_reference(angle, 0.0_wp, [pi/2, 0.0_wp], times, ref, 1.0e-13_wp, 1.0e-13_wp, rstat)
        call chk%equal(rstat, 0, 'reference')
        do i = 1, 3
            call run_outputs(solver, new_pendulum(9.81_wp), [1.0_wp, 0.0_wp], integrators(i), times, x(:, :, i), stat)
            err(i) = 0.0_wp
            do k = 1, size(times)
                err(i) = max(err(i), maxval(abs(x(:, k, i) - [sin(ref(1, k)), -cos(ref(1, k))])))
            end do
            call chk%equal(stat, regdae_success, 'pendulum, '//integrator_name(integrators(i))//': reaches t = 2')
            call chk%true(err(i) <= 1.0e-6_wp, 'pendulum, '//integrator_name(integrators(i))//': position error <= 1e-6')
            call solver%destroy()
        end do
        call chk%true(maxval(abs(x(:, :, 1) - x(:, :, 2))) <= 2.0e-6_wp, 'pendulum: radau = ida within 2e-6')
        call chk%true(maxval(abs(x(:, :, 1) - x(:, :, 3))) <= 2.0e-6_wp, 'pendulum: radau = dopri5 within 2e-6')
        write (*, '(a,3es10.2)') '    pendulum position error (radau, ida, dopri5): ', err
    end subroutine radau_pendulum

    ! The chain of 4 links (8 coordinates) falling from its start, to t = 0.5 at
    ! rtol = atol = 1e-8 (eliminated formulation): the positions of radau against ida's
    ! and dopri5's (no closed form: the three integrators agree within their
    ! tolerance). Measured: 4.9e-10 and 8.1e-9; bound 1e-6.
    subroutine radau_chain(chk)
        type(checker), intent(inout) :: chk
        type(regdae_solver) :: solver
        type(solver_options) :: opts
        type(chain) :: p
        real(wp) :: q0(8), v0(8), q(8, 3), diff(2)
        integer :: stat, i
        p = new_chain(4, .false., 9.81_wp)
        call chain_start(p, q0, v0)
        do i = 1, 3
            opts = solver_options()
            opts%rtol = 1.0e-8_wp
            opts%atol = 1.0e-8_wp
            opts%integrator = integrators(i)
            opts%formulation = formulation_eliminated
            call solver%init(p, 0.0_wp, q0, v0, opts, stat)
            if (stat >= 0) call solver%advance(0.5_wp, q(:, i), stat=stat)
            call chk%equal(stat, regdae_success, 'chain of 4, '//integrator_name(integrators(i)))
            call solver%destroy()
        end do
        diff = [maxval(abs(q(:, 1) - q(:, 2))), maxval(abs(q(:, 1) - q(:, 3)))]
        call chk%true(diff(1) <= 1.0e-6_wp, 'chain: radau = ida within 1e-6')
        call chk%true(diff(2) <= 1.0e-6_wp, 'chain: radau = dopri5 within 1e-6')
        write (*, '(a,2es10.2)') '    chain of 4, radau against ida and dopri5: ', diff
    end subroutine radau_chain

    ! The chain of 4 links at rtol = atol = 1e-4 to t = 1 in one advance, integrator=radau
    ! on the eliminated formulation: the monitor's automatic weights change at t = 0.95
    ! (gamma0 222 -> 910), and F(t0, u0) of the next step must be the new one (the adapter's
    ! refresh). With the old F kept the Jacobian was off by up to 2e5 and the error estimate
    ! by F's change: q(1) off by 6e-4 (6 rtol) against dopri5 at 1e-10; refreshed 5e-6.
    subroutine radau_refresh_eliminated(chk)
        type(checker), intent(inout) :: chk
        type(regdae_solver) :: solver
        type(solver_options) :: opts
        type(chain) :: p
        real(wp) :: q0(8), v0(8), q(8, 2), diff
        integer :: stat, i
        p = new_chain(4, .false., 9.81_wp)
        call chain_start(p, q0, v0)
        do i = 1, 2
            opts = solver_options()
            opts%rtol = merge(1.0e-4_wp, 1.0e-10_wp, i == 1)
            opts%atol = opts%rtol
            opts%integrator = merge(integrator_radau, integrator_dopri5, i == 1)
            opts%formulation = formulation_eliminated
            call solver%init(p, 0.0_wp, q0, v0, opts, stat)
            if (stat >= 0) call solver%advance(1.0_wp, q(:, i), stat=stat)
            call chk%equal(stat, regdae_success, 'chain of 4 to t = 1, '//integrator_name(opts%integrator))
            call solver%destroy()
        end do
        diff = maxval(abs(q(:, 1) - q(:, 2)))
        call chk%true(diff <= 1.0e-4_wp, 'chain at rtol 1e-4: radau within rtol of dopri5 after the weights changed')
        write (*, '(a,es10.2)') '    chain of 4 at 1e-4, radau against dopri5 at 1e-10: ', diff
    end subroutine radau_refresh_eliminated

    ! integrator=radau takes formulation=augmented (and auto, eliminated), refuses
    ! multiplier and the band and sparse linear solvers (IDA's), each with a message.
    subroutine radau_augmented_option(chk)
        type(checker), intent(inout) :: chk
        type(solver_options) :: opts
        character(len=:), allocatable :: msg
        integer :: stat
        opts%integrator = integrator_radau
        opts%formulation = formulation_augmented
        call validate_options(opts, stat, msg)
        call chk%equal(stat, regdae_success, 'integrator=radau formulation=augmented valid')
        opts%linear_solver = linear_solver_dense
        call validate_options(opts, stat, msg)
        call chk%equal(stat, regdae_success, 'with linear_solver=dense')
        opts%linear_solver = linear_solver_sparse
        call validate_options(opts, stat, msg)
        call chk%equal(stat, regdae_err_bad_input, 'with linear_solver=sparse refused')
        call chk%true(index(msg, 'integrator=radau factors its Newton matrices dense') > 0, 'sparse: the message says why')
        opts%linear_solver = linear_solver_band
        call validate_options(opts, stat, msg)
        call chk%equal(stat, regdae_err_bad_input, 'with linear_solver=band refused')
    end subroutine radau_augmented_option

    ! The slider crank of radau_slider_crank (index 3, the paper's start, 20 outputs on
    ! [0, 5] through 3 singular passes, rtol = atol = 1e-8) with integrator=radau on the
    ! augmented formulation (the multiplier and the damped least squares as algebraic
    ! unknowns, regdae_radau_augmented): th1 against the reduced ODE, and against
    ! Radau on the eliminated formulation. Measured: errors 6.5e-10 (augmented) and
    ! 4.0e-9 (eliminated), difference 4.5e-9; bounds as radau_slider_crank's (1e-6 =
    ! 100 rtol against the reference, 2e-6 between two solutions each within it).
    subroutine radau_augmented_slider_crank(chk)
        type(checker), intent(inout) :: chk
        type(slider_crank_reduced) :: reduced
        type(solver_stats) :: st
        real(wp) :: times(20), ref(2, 20), th(2, 20, 2), err(2)
        integer :: k, i, rstat
        times = [(0.25_wp*k, k=1, 20)]
        call integrate_reference(reduced, 0.0_wp, [pi/2, 0.0_wp], times, ref, 1.0e-13_wp, 1.0e-13_wp, rstat)
        call chk%equal(rstat, 0, 'reference')
        call run_both_formulations(chk, 'slider crank', new_slider_crank(9.8_wp), [pi/2, pi/2], times, th, st)
        call chk%true(st%steps > 0 .and. st%jac_evals > 0 .and. st%lin_setups > 0 .and. st%jac_res_evals > 0 .and. &
                      st%res_evals > st%jac_res_evals .and. st%singular_passes == 3, &
                      'radau augmented: statistics, 3 singular passes')
        do i = 1, 2
            err(i) = maxval(abs(th(1, :, i) - ref(1, :)))
            call chk%true(err(i) <= 1.0e-6_wp, 'slider crank, radau '//formulation_name(formulations(i))// &
                          ': th1 error <= 1e-6')
        end do
        write (*, '(a,3es10.2)') '    slider crank th1 error (radau augmented, eliminated; difference): ', err, &
            maxval(abs(th(:, :, 1) - th(:, :, 2)))
    end subroutine radau_augmented_slider_crank

    ! The pendulum of radau_pendulum as a mechanical problem with a declared structure
    ! (the chain of one unit link and unit mass, from the horizontal at rest: x = (sin
    ! phi, -cos phi) with phi'' = -g sin phi), 21 outputs on [0, 2], rtol = atol = 1e-8:
    ! integrator=radau on the augmented and the eliminated formulation against the
    ! angle ODE by CVODE at 1e-13 and against each other. Measured: 4.8e-10 and 9.2e-10,
    ! difference 1.3e-9; bounds as radau_pendulum's.
    subroutine radau_augmented_pendulum(chk)
        type(checker), intent(inout) :: chk
        type(pendulum_angle) :: angle
        type(solver_stats) :: st
        real(wp) :: times(21), ref(2, 21), x(2, 21, 2), err(2)
        integer :: k, i, rstat
        times = [(0.1_wp*k, k=0, 20)]
        call integrate_reference(angle, 0.0_wp, [pi/2, 0.0_wp], times, ref, 1.0e-13_wp, 1.0e-13_wp, rstat)
        call chk%equal(rstat, 0, 'reference')
        call run_both_formulations(chk, 'pendulum', new_chain(1, .false., 9.81_wp), [1.0_wp, 0.0_wp], times, x, st)
        do i = 1, 2
            err(i) = 0.0_wp
            do k = 1, size(times)
                err(i) = max(err(i), maxval(abs(x(:, k, i) - [sin(ref(1, k)), -cos(ref(1, k))])))
            end do
            call chk%true(err(i) <= 1.0e-6_wp, 'pendulum, radau '//formulation_name(formulations(i))// &
                          ': position error <= 1e-6')
        end do
        write (*, '(a,3es10.2)') '    pendulum position error (radau augmented, eliminated; difference): ', err, &
            maxval(abs(x(:, :, 1) - x(:, :, 2)))
    end subroutine radau_augmented_pendulum

    ! integrator=radau on the augmented (x(:, :, 1)) and the eliminated formulation
    ! (x(:, :, 2)) of the problem from (x0, 0), run_outputs' outputs: each reaches the
    ! last time, the first runs on dense LU, and they agree within 2e-6 (each within
    ! 1e-6 of the reference, the callers' bound). st: the augmented run's statistics.
    subroutine run_both_formulations(chk, name, problem, x0, times, x, st)
        type(checker), intent(inout) :: chk
        character(len=*), intent(in) :: name
        class(mechanical_problem), intent(in) :: problem
        real(wp), intent(in) :: x0(:), times(:)
        real(wp), intent(out) :: x(:, :, :)
        type(solver_stats), intent(out) :: st
        type(regdae_solver) :: solver
        integer :: stat, i
        do i = 1, 2
            call run_outputs(solver, problem, x0, integrator_radau, times, x(:, :, i), stat, formulations(i))
            call chk%true(stat >= 0, name//', radau '//formulation_name(formulations(i))//': reaches the last output')
            if (i == 1) then
                call chk%true(solver%formulation() == formulation_augmented .and. &
                              solver%linear_solver() == linear_solver_dense, name//': radau, augmented, dense LU')
                st = solver%statistics()
            end if
            call solver%destroy()
        end do
        call chk%true(maxval(abs(x(:, :, 1) - x(:, :, 2))) <= 2.0e-6_wp, &
                      name//': radau augmented = radau eliminated within 2e-6')
    end subroutine run_both_formulations

    ! The chain of 4 links of radau_chain to t = 0.5 at rtol = atol = 1e-8, and the stiff
    ! chain of 4 (mass 1e-2, stiffness 1e4, damping 10) to t = 0.05: integrator=radau on
    ! the augmented formulation against the eliminated one (no closed form; radau_chain
    ! holds the eliminated one against ida and dopri5), positions, velocities and the
    ! multiplier lambda. Measured: q 3.9e-10, v 6.4e-9, lambda 5.6e-9 (chain); 4.5e-15,
    ! 5.7e-12, 3.9e-11 (stiff chain, settled on its springs: lambda ~ 1e-12). Bounds 1e-6
    ! on positions and velocities, and 1e-5 on lambda (an algebraic unknown, outside
    ! the error test) relative to max(|lambda|, one joint's weight m g).
    subroutine radau_augmented_chain(chk)
        type(checker), intent(inout) :: chk
        type(regdae_solver) :: solver
        type(solver_options) :: opts
        type(chain) :: p
        real(wp) :: q0(8), v0(8), q(8, 2), v(8, 2), lam(4, 2), diff(3)
        integer :: stat, i, run
        character(len=*), parameter :: names(2) = [character(len=11) :: 'chain', 'stiff chain']
        do run = 1, 2
            p = new_chain(4, .false., 9.81_wp)
            if (run == 2) then
                p%joint_mass = 1.0e-2_wp
                p%stiffness = 1.0e4_wp
                p%damping = 10.0_wp
            end if
            call chain_start(p, q0, v0)
            do i = 1, 2
                opts = solver_options()
                opts%rtol = 1.0e-8_wp
                opts%atol = 1.0e-8_wp
                opts%integrator = integrator_radau
                opts%formulation = merge(formulation_augmented, formulation_eliminated, i == 1)
                call solver%init(p, 0.0_wp, q0, v0, opts, stat)
                if (stat >= 0) call solver%advance(merge(0.5_wp, 0.05_wp, run == 1), q(:, i), lam(:, i), stat, v(:, i))
                call chk%equal(stat, regdae_success, trim(names(run))//' of 4, radau '// &
                               formulation_name(opts%formulation))
                call solver%destroy()
            end do
            diff = [maxval(abs(q(:, 1) - q(:, 2))), maxval(abs(v(:, 1) - v(:, 2))), &
                    maxval(abs(lam(:, 1) - lam(:, 2)))/max(maxval(abs(lam(:, 2))), p%joint_mass*p%gravity)]
            call chk%true(diff(1) <= 1.0e-6_wp, trim(names(run))//': positions, augmented = eliminated within 1e-6')
            call chk%true(diff(2) <= 1.0e-6_wp, trim(names(run))//': velocities, augmented = eliminated within 1e-6')
            call chk%true(diff(3) <= 1.0e-5_wp, trim(names(run))//': lambda, augmented = eliminated within 1e-5 relative')
            write (*, '(a,3es10.2)') '    '//trim(names(run))//' of 4, radau augmented against eliminated (q, v, lambda): ', &
                diff
        end do
    end subroutine radau_augmented_chain

    ! The problem from (x0, 0) at rest with `which` at rtol = atol = 1e-8: x at the
    ! times (NaN after a failure); the solver left initialized (its statistics).
    subroutine run_outputs(solver, problem, x0, which, times, x, stat, formulation)
        type(regdae_solver), intent(inout) :: solver
        class(second_order_problem), intent(in) :: problem
        real(wp), intent(in) :: x0(:), times(:)
        integer, intent(in) :: which
        real(wp), intent(out) :: x(:, :)
        integer, intent(out) :: stat
        integer, intent(in), optional :: formulation   !! default: auto
        type(solver_options) :: opts
        integer :: k
        opts%rtol = 1.0e-8_wp
        opts%atol = 1.0e-8_wp
        opts%integrator = which
        if (present(formulation)) opts%formulation = formulation
        x = ieee_value(1.0_wp, ieee_quiet_nan)
        call solver%init(problem, 0.0_wp, x0, 0.0_wp*x0, opts, stat)
        do k = 1, size(times)
            if (stat < 0) exit
            call solver%advance(times(k), x(:, k), stat=stat)
        end do
    end subroutine run_outputs

    ! integrator=auto on the stiff chain (mass 1e-2, stiffness 1e4, damping 10), rtol 1e-8.
    ! On the eliminated formulation (formulation=eliminated) the stiffness test fires near
    ! t = 0.027: 4 links (16 states) go to Radau, 33 links (132 states > radau_max_n) to IDA.
    ! With formulation=auto the chain declares its structure: 4 links (16 states <=
    ! radau_structured_max_n = 20) go to Radau on the eliminated formulation (the switch
    ! near t = 0.043), 6 links (24 states) to IDA on the augmented formulation with KLU.
    ! Radau's runs agree with integrator=ida's at t = 0.05 (measured 6e-15: the dashpots
    ! have settled the chain on its springs by then; bound 1e-6).
    subroutine auto_picks_radau_when_small(chk)
        type(checker), intent(inout) :: chk
        type(regdae_solver) :: solver
        type(solver_options) :: opts
        type(chain) :: p
        real(wp), allocatable :: q0(:), v0(:), q(:, :)
        character(len=:), allocatable :: events
        character(len=*), parameter :: wants(5) = [character(len=40) :: 'dopri5 -> radau', '', 'dopri5 -> ida', &
                                                   'radau', 'ida, augmented formulation with KLU']
        integer, parameter :: links(5) = [4, 4, 33, 4, 6]
        integer :: stat, run
        allocate (q(8, 3))
        do run = 1, 5
            p = new_chain(links(run), .false., 9.81_wp)
            p%joint_mass = 1.0e-2_wp
            p%stiffness = 1.0e4_wp
            p%damping = 10.0_wp
            if (allocated(q0)) deallocate (q0, v0)
            allocate (q0(2*links(run)), v0(2*links(run)))
            call chain_start(p, q0, v0)
            opts = solver_options()
            opts%rtol = 1.0e-8_wp
            opts%atol = 1.0e-8_wp
            if (run <= 3) opts%formulation = formulation_eliminated
            if (run == 2) opts%integrator = integrator_ida
            call solver%init(p, 0.0_wp, q0, v0, opts, stat)
            if (links(run) == 4 .and. stat >= 0) call solver%advance(0.05_wp, q(:, min(run, 3)), stat=stat)
            if (links(run) /= 4 .and. stat >= 0) call solver%advance(0.05_wp, q0, stat=stat)
            call chk%equal(stat, regdae_success, 'stiff chain of '//format_int(links(run))//', run '// &
                           format_int(run))
            events = solver%events()
            if (run /= 2) call chk%true(index(events, trim(wants(run))) > 0, format_int(links(run))// &
                                        ' links, run '//format_int(run)//': auto takes '//trim(wants(run)))
            if (run == 4) call chk%true(index(events, 'augmented') == 0, '4 links, structured: Radau on the '// &
                                        'eliminated formulation')
            call solver%destroy()
        end do
        call chk%true(maxval(abs(q(:, 1) - q(:, 2))) <= 1.0e-6_wp, 'auto (Radau) = ida within 1e-6')
        call chk%true(maxval(abs(q(:, 3) - q(:, 2))) <= 1.0e-6_wp, 'auto (Radau, structured) = ida within 1e-6')
        write (*, '(a,2es10.2)') '    stiff chain of 4, auto (radau; structured) against ida: ', &
            maxval(abs(q(:, 1) - q(:, 2))), maxval(abs(q(:, 3) - q(:, 2)))
    end subroutine auto_picks_radau_when_small

    ! The car axis of the Test Set for IVP Solvers (drivers/problems/car_axis_problem.f90, stiff
    ! springs, a moving constraint) to t = 3 at rtol = atol = 1e-8, every option at its default but
    ! the integrator: the positions against the test set's published solution. A tolerance bounds
    ! the local error; over the 3 s of stiff oscillation the global error may exceed it, and 100 rtol
    ! = 1e-6 is the bound. Measured: radau 2.7e-10, ida 7.3e-8, dopri5 1.2e-9.
    subroutine radau_car_axis(chk)
        type(checker), intent(inout) :: chk
        type(regdae_solver) :: solver
        type(solver_options) :: opts
        type(car_axis) :: p
        real(wp) :: x(4), err(3)
        integer :: stat, i
        p = new_car_axis()
        do i = 1, 3
            opts = solver_options()
            opts%rtol = 1.0e-8_wp
            opts%atol = 1.0e-8_wp
            opts%integrator = integrators(i)
            call solver%init(p, 0.0_wp, car_axis_x0, car_axis_v0, opts, stat)
            x = huge(1.0_wp)
            if (stat >= 0) call solver%advance(car_axis_t_end, x, stat=stat)
            call chk%equal(stat, regdae_success, 'car axis, '//integrator_name(integrators(i))//': reaches t = 3')
            err(i) = maxval(abs(x - car_axis_reference(1:4)))
            call chk%true(err(i) <= 1.0e-6_wp, 'car axis, '//integrator_name(integrators(i))// &
                          ': positions within 1e-6 of the published solution')
            call solver%destroy()
        end do
        write (*, '(a,3es10.2)') '    car axis position error at t = 3 (radau, ida, dopri5): ', err
    end subroutine radau_car_axis

    ! The integrator alone on the car axis's index-3 form M u' = F (u = p, p', lambda), run as
    ! RADAU5 runs it (the velocities' error scaled by h, the multipliers' by h^2, RADAU5's
    ! tolerance transform, h0 = 1e-6): its accepted steps within 10% of RADAU5's 99 / 201 / 416
    ! at rtol = atol = 1e-4 / 1e-6 / 1e-8 (issue 21's reference point; the same method and
    ! step control, written from Hairer & Wanner IV.8: 10% for the Jacobian's difference
    ! quotients and rounding). Without the transform the positions' error at t = 3 is within
    ! 10 tol (1 + |p|) of the published solution.
    subroutine radau_car_axis_index3(chk)
        type(checker), intent(inout) :: chk
        integer, parameter :: radau5_steps(3) = [99, 201, 416]
        type(car_axis_index3) :: sys
        type(radau_integrator) :: integrator
        type(radau_options) :: opts
        type(radau_stats) :: stats
        real(wp) :: u0(10), u(10), tol, err
        integer :: stat, i, mode
        character(len=24) :: label
        do mode = 1, 2
            do i = 1, 3
                tol = 10.0_wp**(-2*i - 2)
                call car_axis_index3_setup(sys, tol, mode == 1, u0, opts)
                u = huge(1.0_wp)
                call integrator%start(sys, 0.0_wp, u0, opts, stat)
                if (stat == regdae_success) call integrator%advance(sys, car_axis_t_end, u, stat, land=.true.)
                stats = integrator%statistics()
                write (label, '(a, es8.1)') merge('radau5 ', 'index3 ', mode == 1)//'tol ', tol
                call chk%equal(stat, regdae_success, 'car axis index 3, '//trim(label)//': reaches t = 3')
                err = maxval(abs(u(1:4) - car_axis_reference(1:4))/(1 + abs(car_axis_reference(1:4))))
                if (mode == 1) then
                    call chk%true(abs(real(stats%accepted, wp)/radau5_steps(i) - 1) <= 0.1_wp, &
                                  'car axis index 3, '//trim(label)//': RADAU5''s steps within 10%')
                    write (*, '(4x, a, i0, a, i0, a, es9.2)') 'car axis index 3, '//trim(label)//': steps ', &
                        stats%accepted, ' (RADAU5 ', radau5_steps(i), '), position error ', err
                else
                    call chk%true(err <= 10*tol, 'car axis index 3, '//trim(label)//': positions within 10 tol')
                end if
            end do
        end do
    end subroutine radau_car_axis_index3

end module test_radau_solver
