!> The structured engine (issue 10): the augmented formulation against the
!! eliminated one, the band and sparse linear solvers against dense, the
!! sigma_min(GB) estimate against the SVD, the Jacobian checks, and the refusal
!! of patterns that miss an entry or do not fit.
module test_structure
    use regdae
    use chain_problem, only: chain, new_chain, chain_start
    use slider_crank_problem, only: slider_crank, new_slider_crank
    use regdae_testing, only: checker, test_case, new_test
    use regdae_projection, only: project_second_order
    use regdae_sparse_projection, only: project_structured
    use, intrinsic :: iso_fortran_env, only: int64
    use regdae_sparsity, only: column_groups, band_pattern
    implicit none
    private
    public :: structure_tests

    real(wp), parameter :: pi = acos(-1.0_wp)

    !> The chain with a spring that pulls joint 1 by the height of joint 3 (a
    !! force that depends on q outside the constraints' couplings) while the
    !! inherited structure declares force_q empty.
    type, extends(chain) :: sprung_chain
    contains
        procedure :: forces => sprung_forces
    end type sprung_chain

    !> The chain with a dashpot that pulls joint 1 by the velocity of joint 2
    !! (x1'' gets -c x2'), force_v declared empty by the inherited structure.
    type, extends(chain) :: damped_chain
    contains
        procedure :: forces => damped_forces
    end type damped_chain

    !> The chain whose mass_matrix couples x1 and x2 (mass_values, diagonal, does not).
    type, extends(chain) :: coupled_mass_chain
    contains
        procedure :: mass_matrix => coupled_mass
    end type coupled_mass_chain

    !> The chain declaring M and G only: force_q and force_v never set.
    type, extends(chain) :: unset_forces_chain
    contains
        procedure :: structure => unset_forces_structure
    end type unset_forces_chain

    !> The chain whose values routines fall back on the public defaults (dense M and G
    !! gathered in pattern order).
    type, extends(chain) :: fallback_chain
    contains
        procedure :: mass_values => fallback_mass_values
        procedure :: constraint_jacobian_values => fallback_gx_values
    end type fallback_chain

    !> The chain with one wrong entry in its sparse G.
    type, extends(chain) :: wrong_g_chain
    contains
        procedure :: constraint_jacobian_values => wrong_g_values
    end type wrong_g_chain

    !> The slider crank declaring a G pattern without column 1 (the dense G has it).
    type, extends(slider_crank) :: short_pattern_crank
    contains
        procedure :: structure => short_structure
    end type short_pattern_crank

    !> The slider crank declaring a 3 x 3 mass pattern (n = 2).
    type, extends(slider_crank) :: misfit_crank
    contains
        procedure :: structure => misfit_structure
    end type misfit_crank

    !> The chain whose joint masses vary (`dependence`: 1 with x1, 2 with y2 - y1, 3 with t) while
    !! the inherited structure declares M constant.
    type, extends(chain) :: varying_mass_chain
        integer :: dependence = 1
    contains
        procedure :: mass_matrix => varying_mass
        procedure :: mass_values => varying_mass_values
    end type varying_mass_chain

contains

    function structure_tests() result(tests)
        type(test_case), allocatable :: tests(:)
        tests = [new_test('linear_solvers_agree', linear_solvers_agree), &
                 new_test('augmented_matches_eliminated', augmented_matches_eliminated), &
                 new_test('sigma_min_matches_svd', sigma_min_matches_svd), &
                 new_test('jacobian_checks_pass', jacobian_checks_pass), &
                 new_test('missing_force_dependence_reported', missing_force_dependence_reported), &
                 new_test('missing_velocity_dependence_reported', missing_velocity_dependence_reported), &
                 new_test('mass_outside_its_pattern_reported', mass_outside_its_pattern_reported), &
                 new_test('unset_force_patterns_are_empty', unset_force_patterns_are_empty), &
                 new_test('options_report_the_integrator', options_report_the_integrator), &
                 new_test('default_values_callable_from_an_override', default_values_callable_from_an_override), &
                 new_test('wrong_g_reported', wrong_g_reported), &
                 new_test('pattern_missing_an_entry', pattern_missing_an_entry), &
                 new_test('structure_that_does_not_fit', structure_that_does_not_fit), &
                 new_test('dense_formulations_refuse_band', dense_formulations_refuse_band), &
                 new_test('sparse_projection_matches_dense', sparse_projection_matches_dense), &
                 new_test('varying_mass_declared_constant_refused', varying_mass_declared_constant_refused), &
                 new_test('pattern_transpose_and_union_by_entries', pattern_transpose_and_union_by_entries), &
                 new_test('column_groups_share_no_row', column_groups_share_no_row)]
    end function structure_tests

    subroutine sprung_forces(self, t, q, qd, f, stat)
        class(sprung_chain), intent(inout) :: self
        real(wp), intent(in) :: t, q(:), qd(:)
        real(wp), intent(out) :: f(:)
        integer, intent(inout) :: stat
        call self%chain%forces(t, q, qd, f, stat)
        f(2) = f(2) - 50.0_wp*q(6)
    end subroutine sprung_forces

    subroutine damped_forces(self, t, q, qd, f, stat)
        class(damped_chain), intent(inout) :: self
        real(wp), intent(in) :: t, q(:), qd(:)
        real(wp), intent(out) :: f(:)
        integer, intent(inout) :: stat
        call self%chain%forces(t, q, qd, f, stat)
        f(1) = f(1) - 3.0_wp*qd(3)
    end subroutine damped_forces

    subroutine coupled_mass(self, t, q, mass, stat)
        class(coupled_mass_chain), intent(inout) :: self
        real(wp), intent(in) :: t, q(:)
        real(wp), intent(out) :: mass(:, :)
        integer, intent(inout) :: stat
        call self%chain%mass_matrix(t, q, mass, stat)
        mass(1, 2) = 0.25_wp
        mass(2, 1) = 0.25_wp
    end subroutine coupled_mass

    ! The chain's M with the joint mass of varying_mass_chain at (t, q).
    subroutine vary_joint_mass(self, t, q)
        class(varying_mass_chain), intent(inout) :: self
        real(wp), intent(in) :: t, q(:)
        select case (self%dependence)
        case (1); self%joint_mass = 1.0_wp + 0.1_wp*q(1)**2
        case (2); self%joint_mass = 1.0_wp + (q(4) - q(2))**2   ! 0 at the start: quadratic
        case default; self%joint_mass = 1.0_wp + 0.1_wp*t
        end select
    end subroutine vary_joint_mass

    subroutine varying_mass(self, t, q, mass, stat)
        class(varying_mass_chain), intent(inout) :: self
        real(wp), intent(in) :: t, q(:)
        real(wp), intent(out) :: mass(:, :)
        integer, intent(inout) :: stat
        call vary_joint_mass(self, t, q)
        call self%chain%mass_matrix(t, q, mass, stat)
    end subroutine varying_mass

    subroutine varying_mass_values(self, t, q, pattern, vals, stat)
        class(varying_mass_chain), intent(inout) :: self
        real(wp), intent(in) :: t, q(:)
        type(sparsity_pattern), intent(in) :: pattern
        real(wp), intent(out) :: vals(:)
        integer, intent(inout) :: stat
        call vary_joint_mass(self, t, q)
        call self%chain%mass_values(t, q, pattern, vals, stat)
    end subroutine varying_mass_values

    function unset_forces_structure(self) result(st)
        class(unset_forces_chain), intent(in) :: self
        type(mechanical_structure) :: st
        type(mechanical_structure) :: full
        full = self%chain%structure()
        st%declared = .true.
        st%curvature_supplied = .true.
        st%mass = full%mass
        st%constraint = full%constraint
    end function unset_forces_structure

    subroutine fallback_mass_values(self, t, q, pattern, vals, stat)
        class(fallback_chain), intent(inout) :: self
        real(wp), intent(in) :: t, q(:)
        type(sparsity_pattern), intent(in) :: pattern
        real(wp), intent(out) :: vals(:)
        integer, intent(inout) :: stat
        call default_mass_values(self, t, q, pattern, vals, stat)
    end subroutine fallback_mass_values

    subroutine fallback_gx_values(self, t, q, pattern, vals, stat)
        class(fallback_chain), intent(inout) :: self
        real(wp), intent(in) :: t, q(:)
        type(sparsity_pattern), intent(in) :: pattern
        real(wp), intent(out) :: vals(:)
        integer, intent(inout) :: stat
        call default_constraint_jacobian_values(self, t, q, pattern, vals, stat)
    end subroutine fallback_gx_values

    subroutine wrong_g_values(self, t, q, pattern, vals, stat)
        class(wrong_g_chain), intent(inout) :: self
        real(wp), intent(in) :: t, q(:)
        type(sparsity_pattern), intent(in) :: pattern
        real(wp), intent(out) :: vals(:)
        integer, intent(inout) :: stat
        call self%chain%constraint_jacobian_values(t, q, pattern, vals, stat)
        vals(3) = vals(3) + 0.5_wp
    end subroutine wrong_g_values

    function short_structure(self) result(st)
        class(short_pattern_crank), intent(in) :: self
        type(mechanical_structure) :: st
        st%declared = .true.
        st%mass = dense_pattern(2, 2)
        st%constraint = pattern_from_entries(1, 2, [1], [2])
        st%force_q = dense_pattern(2, 2)
        st%force_v = dense_pattern(2, 2)
    end function short_structure

    function misfit_structure(self) result(st)
        class(misfit_crank), intent(in) :: self
        type(mechanical_structure) :: st
        st%declared = .true.
        st%mass = dense_pattern(3, 3)
        st%constraint = dense_pattern(1, 2)
        st%force_q = dense_pattern(2, 2)
        st%force_v = dense_pattern(2, 2)
    end function misfit_structure

    ! Positions of a chain at t = 0.5 and 1 with the given options.
    subroutine run_chain(links, slider, opts, q_end, stat, solver_used)
        integer, intent(in) :: links
        logical, intent(in) :: slider
        type(solver_options), intent(in) :: opts
        real(wp), intent(out) :: q_end(:, :)   ! (2 links, 2)
        integer, intent(out) :: stat
        integer, intent(out), optional :: solver_used
        type(regdae_solver) :: solver
        type(chain) :: p
        real(wp) :: q0(2*links), v0(2*links)
        integer :: k
        p = new_chain(links, slider, 9.81_wp)
        call chain_start(p, q0, v0)
        call solver%init(p, 0.0_wp, q0, v0, opts, stat)
        if (present(solver_used)) solver_used = solver%linear_solver()
        if (stat /= regdae_success) return
        do k = 1, 2
            call solver%advance(0.5_wp*k, q_end(:, k), stat=stat)
            if (stat < 0) return
        end do
        stat = regdae_success
        call solver%destroy()
    end subroutine run_chain

    ! Dense, band and sparse LU solve the same Newton systems (the same grouped
    ! Jacobian): the runs differ by rounding only. Bound 1e-7 at rtol = 1e-8:
    ! 10 rtol times the largest coordinate (about 8).
    subroutine linear_solvers_agree(chk)
        type(checker), intent(inout) :: chk
        type(solver_options) :: opts
        real(wp) :: q(16, 2, 3)
        integer :: ls, stat, used, pass
        logical :: slider
        do pass = 1, 2
            slider = (pass == 2)
            do ls = linear_solver_dense, linear_solver_sparse
                opts = solver_options()
                opts%formulation = formulation_augmented
                opts%linear_solver = ls
                opts%rtol = 1.0e-8_wp
                opts%atol = 1.0e-8_wp
                call run_chain(8, slider, opts, q(:, :, ls), stat, used)
                call chk%equal(stat, regdae_success, linear_solver_name(ls)//' run')
                call chk%equal(used, ls, 'the solver asked for is used')
            end do
            call chk%true(maxval(abs(q(:, :, 2) - q(:, :, 1))) <= 8.0e-7_wp, 'band agrees with dense')
            call chk%true(maxval(abs(q(:, :, 3) - q(:, :, 1))) <= 8.0e-7_wp, 'sparse agrees with dense')
            write (*, '(a,2es10.2)') '    max |band - dense|, |sparse - dense|: ', maxval(abs(q(:, :, 2) - q(:, :, 1))), &
                maxval(abs(q(:, :, 3) - q(:, :, 1)))
        end do
    end subroutine linear_solvers_agree

    ! The augmented and eliminated formulations integrate the same regularized
    ! equations: at rtol = 1e-9 they agree to the integration error (bound 1e-6).
    subroutine augmented_matches_eliminated(chk)
        type(checker), intent(inout) :: chk
        type(solver_options) :: opts
        type(regdae_solver) :: solver
        real(wp) :: q(8, 2, 2), th(2, 2), lam(1)
        integer :: form, stat, k
        do form = 1, 2
            opts = solver_options()
            opts%rtol = 1.0e-9_wp
            opts%atol = 1.0e-9_wp
            opts%formulation = merge(formulation_eliminated, formulation_augmented, form == 1)
            call run_chain(4, .false., opts, q(:, :, form), stat)
            call chk%equal(stat, regdae_success, 'chain run '//formulation_name(opts%formulation))
            ! the slider crank (no structure declared: dense patterns), through t = 1
            call solver%init(new_slider_crank(9.8_wp), 0.0_wp, [pi/2, pi/2], [0.0_wp, 0.0_wp], opts, stat)
            do k = 1, 2
                call solver%advance(0.5_wp*k, th(:, form), lam, stat)
            end do
            call chk%equal(stat, regdae_success, 'slider crank '//formulation_name(opts%formulation))
        end do
        call chk%true(maxval(abs(q(:, :, 1) - q(:, :, 2))) <= 1.0e-6_wp, 'chain: augmented = eliminated')
        call chk%true(maxval(abs(th(:, 1) - th(:, 2))) <= 1.0e-6_wp, 'slider crank: augmented = eliminated')
        write (*, '(a,2es10.2)') '    chain, slider crank: max |augmented - eliminated|: ', &
            maxval(abs(q(:, :, 1) - q(:, :, 2))), maxval(abs(th(:, 1) - th(:, 2)))
        call solver%destroy()
    end subroutine augmented_matches_eliminated

    ! The inverse-iteration estimate of sigma_min(GB) on the banded saddle-point
    ! matrix against the dense SVD (eliminated formulation), at t0 of a chain: the
    ! iteration stops when the Rayleigh quotient moves by less than 1e-3 (relative), and
    ! its error is below that step with a spectral gap of about 4 (measured 6e-7); the
    ! Rayleigh quotient of (GB)^-1 bounds sigma_min from above.
    subroutine sigma_min_matches_svd(chk)
        type(checker), intent(inout) :: chk
        type(solver_options) :: opts
        type(regdae_solver) :: a, b
        type(chain) :: p
        real(wp) :: q0(16), v0(16)
        integer :: stat
        p = new_chain(8, .true., 9.81_wp)
        call chain_start(p, q0, v0)
        opts%formulation = formulation_augmented
        call a%init(p, 0.0_wp, q0, v0, opts, stat)
        opts%formulation = formulation_eliminated
        call b%init(p, 0.0_wp, q0, v0, opts, stat)
        call chk%close_rel([a%sigma_min()], [b%sigma_min()], 1.0e-3_wp, 'sigma_min(GB): estimate = SVD')
        call chk%true(a%sigma_min() >= b%sigma_min()*(1.0_wp - 1.0e-12_wp), 'sigma_min(GB): the estimate is an upper bound')
        write (*, '(a,2es22.14)') '    sigma_min estimate, SVD: ', a%sigma_min(), b%sigma_min()
        call a%destroy()
        call b%destroy()
    end subroutine sigma_min_matches_svd

    subroutine jacobian_checks_pass(chk)
        type(checker), intent(inout) :: chk
        type(solver_options) :: opts
        real(wp) :: q(32, 2)
        integer :: stat
        opts%check_jacobians = .true.
        opts%formulation = formulation_augmented
        call run_chain(16, .true., opts, q, stat)
        call chk%equal(stat, regdae_success, 'the chain passes the checks')
    end subroutine jacobian_checks_pass

    ! Forces that depend on q with force_q declared empty: the grouped Newton
    ! matrix misses entries; check_jacobians says so.
    subroutine missing_force_dependence_reported(chk)
        type(checker), intent(inout) :: chk
        type(solver_options) :: opts
        type(regdae_solver) :: solver
        type(sprung_chain) :: p
        real(wp) :: q0(16), v0(16)
        integer :: stat, i
        p%chain = new_chain(8, .false., 9.81_wp)
        call chain_start(p%chain, q0, v0)
        q0(2::2) = [(0.1_wp*i, i=1, 8)]   ! off the axis: nonzero spring forces
        q0(1::2) = [(sqrt(real(i, wp)**2 - (0.1_wp*i)**2), i=1, 8)]   ! unit links along one ray
        opts%formulation = formulation_augmented
        opts%check_jacobians = .true.
        call solver%init(p, 0.0_wp, q0, v0, opts, stat)
        call chk%equal(stat, regdae_err_jacobian, 'reported')
        call chk%true(index(solver%message(), 'force_q pattern misses entry (2, 6)') > 0, &
                      'the message names force_q and the entry (row 2, column 6) of the user''s numbering')
        if (index(solver%message(), '(2, 6)') == 0) write (*, '(a)') '    '//solver%message()
    end subroutine missing_force_dependence_reported

    ! A dashpot f_1 = -3 v_3 with force_v declared empty: the entry (1, 3) is named.
    subroutine missing_velocity_dependence_reported(chk)
        type(checker), intent(inout) :: chk
        type(damped_chain) :: p
        character(len=:), allocatable :: msg
        integer :: stat
        p%chain = new_chain(8, .false., 9.81_wp)
        call checked_init(p, stat, msg)
        call chk%equal(stat, regdae_err_jacobian, 'reported')
        call chk%true(index(msg, 'force_v pattern misses entry (1, 3) of df/dv') > 0, &
                      'the message names force_v and the entry (1, 3)')
        call chk%true(index(msg, '-3.0') > 0, 'and its value, -3')
        write (*, '(a)') '    '//msg
    end subroutine missing_velocity_dependence_reported

    ! init of a chain (p%chain set; straight, at rest) with formulation=augmented and
    ! check_jacobians=yes: the status and the message.
    subroutine checked_init(p, stat, msg)
        class(chain), intent(in) :: p
        integer, intent(out) :: stat
        character(len=:), allocatable, intent(out) :: msg
        type(solver_options) :: opts
        type(regdae_solver) :: solver
        real(wp) :: q0(p%n), v0(p%n)
        call chain_start(p, q0, v0)
        opts%formulation = formulation_augmented
        opts%check_jacobians = .true.
        call solver%init(p, 0.0_wp, q0, v0, opts, stat)
        msg = solver%message()
        call solver%destroy()
    end subroutine checked_init

    ! mass_matrix with M(1, 2) = M(2, 1) = 0.25 against a diagonal mass pattern (the
    ! chain's mass_values give the diagonal): the entry is named in M's terms.
    subroutine mass_outside_its_pattern_reported(chk)
        type(checker), intent(inout) :: chk
        type(coupled_mass_chain) :: p
        character(len=:), allocatable :: msg
        integer :: stat
        p%chain = new_chain(8, .false., 9.81_wp)
        call checked_init(p, stat, msg)
        call chk%equal(stat, regdae_err_jacobian, 'reported')
        call chk%true(index(msg, 'M (mass_matrix) has the nonzero entry (1, 2)') > 0, &
                      'the message names the entry (1, 2) of M')
    end subroutine mass_outside_its_pattern_reported

    ! force_q and force_v left unset mean empty: the run is the chain's own (which sets
    ! both to empty_pattern(n, n)), bit for bit, and passes check_jacobians.
    subroutine unset_force_patterns_are_empty(chk)
        type(checker), intent(inout) :: chk
        type(solver_options) :: opts
        type(regdae_solver) :: a, b
        type(unset_forces_chain) :: p
        type(chain) :: c
        real(wp) :: q0(16), v0(16), qa(16), qb(16)
        integer :: stat
        c = new_chain(8, .true., 9.81_wp)
        p%chain = c
        call chain_start(c, q0, v0)
        opts%check_jacobians = .true.
        call a%init(p, 0.0_wp, q0, v0, opts, stat)
        call chk%equal(stat, regdae_success, 'unset force patterns: init')
        call chk%equal(a%formulation(), formulation_augmented, 'the augmented formulation')
        call a%advance(1.0_wp, qa, stat=stat)
        call chk%equal(stat, regdae_success, 'unset force patterns: advance')
        call b%init(c, 0.0_wp, q0, v0, opts, stat)
        call b%advance(1.0_wp, qb, stat=stat)
        call chk%true(all(qa == qb), 'the same run as with empty_pattern(n, n), bit for bit')
        call a%destroy()
        call b%destroy()
    end subroutine unset_force_patterns_are_empty

    ! Overrides that call default_mass_values and default_constraint_jacobian_values
    ! (public from regdae): the chain's M and G are the same numbers (differences of
    ! positions, the masses), so the run is the chain's own, bit for bit.
    subroutine default_values_callable_from_an_override(chk)
        type(checker), intent(inout) :: chk
        type(solver_options) :: opts
        type(regdae_solver) :: a, b
        type(fallback_chain) :: p
        type(chain) :: c
        real(wp) :: q0(16), v0(16), qa(16), qb(16)
        integer :: stat
        c = new_chain(8, .true., 9.81_wp)
        p%chain = c
        call chain_start(c, q0, v0)
        call a%init(p, 0.0_wp, q0, v0, opts, stat)
        call a%advance(1.0_wp, qa, stat=stat)
        call chk%equal(stat, regdae_success, 'the run with the default values routines')
        call chk%equal(a%formulation(), formulation_augmented, 'the augmented formulation')
        call b%init(c, 0.0_wp, q0, v0, opts, stat)
        call b%advance(1.0_wp, qb, stat=stat)
        call chk%true(all(qa == qb), 'the chain''s own run, bit for bit')
        if (.not. all(qa == qb)) write (*, '(a, es10.2)') '    max difference ', maxval(abs(qa - qb))
        call a%destroy()
        call b%destroy()
    end subroutine default_values_callable_from_an_override

    ! options() reports the integrator in charge, not `auto`: IDA on the augmented
    ! formulation (a declared structure, n = 16), dopri5 at the start of the slider
    ! crank's eliminated formulation (not stiff there), and what was asked for otherwise.
    subroutine options_report_the_integrator(chk)
        type(checker), intent(inout) :: chk
        type(solver_options) :: opts, used
        type(regdae_solver) :: solver
        type(chain) :: c
        real(wp) :: q0(16), v0(16)
        integer :: stat
        c = new_chain(8, .true., 9.81_wp)
        call chain_start(c, q0, v0)
        call solver%init(c, 0.0_wp, q0, v0, opts, stat)
        used = solver%options()
        call chk%equal(used%integrator, integrator_ida, 'the chain (augmented): ida')
        call solver%init(new_slider_crank(9.8_wp), 0.0_wp, [pi/2, pi/2], [1.0_wp, -1.0_wp], opts, stat)
        used = solver%options()
        call chk%equal(solver%formulation(), formulation_eliminated, 'the slider crank: eliminated')
        call chk%equal(used%integrator, integrator_dopri5, 'the slider crank at t0: dopri5')
        opts%integrator = integrator_ida
        call solver%init(new_slider_crank(9.8_wp), 0.0_wp, [pi/2, pi/2], [1.0_wp, -1.0_wp], opts, stat)
        used = solver%options()
        call chk%equal(used%integrator, integrator_ida, 'integrator=ida: ida')
        call solver%destroy()
    end subroutine options_report_the_integrator

    subroutine wrong_g_reported(chk)
        type(checker), intent(inout) :: chk
        type(solver_options) :: opts
        type(regdae_solver) :: solver
        type(wrong_g_chain) :: p
        real(wp) :: q0(8), v0(8)
        integer :: stat
        p%chain = new_chain(4, .false., 9.81_wp)
        call chain_start(p%chain, q0, v0)
        opts%formulation = formulation_augmented
        opts%check_jacobians = .true.
        call solver%init(p, 0.0_wp, q0, v0, opts, stat)
        call chk%equal(stat, regdae_err_jacobian, 'reported')
        call chk%true(index(solver%message(), 'constraint_jacobian_values') > 0, 'the message names the routine')
        opts%check_jacobians = .false.   ! without the check: the run goes on (wrong)
        call solver%init(p, 0.0_wp, q0, v0, opts, stat)
        call chk%equal(stat, regdae_success, 'not checked by default')
        call solver%destroy()
    end subroutine wrong_g_reported

    ! Issue 20: the projection on the declared pattern (KLU on [I G^T; G -delta I]) against
    ! the dense one (dgelsd), from a state off the constraints by 1e-3: the same Gauss-Newton
    ! iterates up to rounding (delta = 100 u max|G|^2 perturbs a correction by ~1e-14 of it),
    ! and both end on g = 0, G v + g_t = 0 to rounding.
    subroutine sparse_projection_matches_dense(chk)
        type(checker), intent(inout) :: chk
        type(chain) :: p, pd
        type(mechanical_structure) :: st
        real(wp) :: q0(16), v0(16), xs(16), vs(16), xd(16), vd(16), g(8), gv(8)
        integer :: stat, i

        p = new_chain(8, .false., 9.81_wp)
        pd = p
        call chain_start(p, q0, v0)
        do i = 1, 16
            q0(i) = q0(i) + 1.0e-3_wp*sin(3.7_wp*i)
            v0(i) = cos(1.3_wp*i)
        end do
        st = p%structure()
        xs = q0
        vs = v0
        call project_structured(p, st%constraint, 0.0_wp, xs, vs, stat)
        call chk%equal(stat, 0, 'sparse projection: status')
        xd = q0
        vd = v0
        call project_second_order(pd, 0.0_wp, xd, vd, stat)
        call chk%equal(stat, 0, 'dense projection: status')
        call chk%true(maxval(abs(xs - xd)) <= 1.0e-12_wp, 'positions agree with the dense projection')
        call chk%true(maxval(abs(vs - vd)) <= 1.0e-12_wp, 'velocities agree with the dense projection')
        stat = 0
        call p%constraint(0.0_wp, xs, g, stat)
        call velocity_constraint(p, 0.0_wp, xs, vs, gv, stat)
        call chk%true(maxval(abs(g)) <= 1.0e-13_wp, 'on g = 0')
        call chk%true(maxval(abs(gv)) <= 1.0e-13_wp, 'on G v + g_t = 0')
    end subroutine sparse_projection_matches_dense

    ! The dense G has an entry outside the declared pattern: the default
    ! constraint_jacobian_values refuses it with a clear status.
    subroutine pattern_missing_an_entry(chk)
        type(checker), intent(inout) :: chk
        type(solver_options) :: opts
        type(regdae_solver) :: solver
        type(short_pattern_crank) :: p
        integer :: stat
        p%slider_crank = new_slider_crank(9.8_wp)
        opts%formulation = formulation_augmented
        call solver%init(p, 0.0_wp, [pi/2, pi/2], [0.0_wp, 0.0_wp], opts, stat)
        call chk%equal(stat, regdae_err_structure, 'refused')
        call chk%true(index(solver%message(), 'constraint_jacobian_values') > 0, 'the message names the routine')
    end subroutine pattern_missing_an_entry

    subroutine structure_that_does_not_fit(chk)
        type(checker), intent(inout) :: chk
        type(solver_options) :: opts
        type(regdae_solver) :: solver
        type(misfit_crank) :: p
        integer :: stat
        p%slider_crank = new_slider_crank(9.8_wp)
        opts%formulation = formulation_augmented
        call solver%init(p, 0.0_wp, [pi/2, pi/2], [0.0_wp, 0.0_wp], opts, stat)
        call chk%equal(stat, regdae_err_bad_input, 'refused')
        call chk%true(index(solver%message(), 'mass pattern is 3 x 3, expected 2 x 2') > 0, 'the message says what')
    end subroutine structure_that_does_not_fit

    ! mass_constant declared where M varies with a coordinate, with a difference of two (0 at
    ! the start, so that only a shift of its own size shows it) or with t: init refuses it on the
    ! augmented and on the eliminated formulation, naming the declaration; the chain's own
    ! constant M is accepted.
    subroutine varying_mass_declared_constant_refused(chk)
        type(checker), intent(inout) :: chk
        type(solver_options) :: opts
        type(regdae_solver) :: solver
        type(varying_mass_chain) :: p
        real(wp) :: q0(8), v0(8)
        integer :: stat, dependence, formulation
        character(len=40) :: what
        p%chain = new_chain(4, .false., 9.81_wp)
        call chain_start(p%chain, q0, v0)
        do dependence = 1, 3
            do formulation = 1, 2
                opts = solver_options()
                opts%formulation = merge(formulation_augmented, formulation_eliminated, formulation == 1)
                p%dependence = dependence
                write (what, '(a,i0,a,a)') 'dependence ', dependence, ', ', trim(merge('augmented ', 'eliminated', &
                                                                                     formulation == 1))
                call solver%init(p, 0.0_wp, q0, v0, opts, stat)
                call chk%equal(stat, regdae_err_structure, trim(what)//': refused')
                call chk%true(index(solver%message(), 'declares M constant (mass_constant), but M varies') > 0, &
                              trim(what)//': the message names the declaration')
            end do
        end do
        call solver%init(p%chain, 0.0_wp, q0, v0, opts, stat)
        call chk%equal(stat, regdae_success, 'the chain''s constant M accepted')
        call solver%destroy()
    end subroutine varying_mass_declared_constant_refused

    subroutine dense_formulations_refuse_band(chk)
        type(checker), intent(inout) :: chk
        type(solver_options) :: opts
        type(regdae_solver) :: solver
        integer :: stat
        opts%linear_solver = linear_solver_band
        call solver%init(new_slider_crank(9.8_wp), 0.0_wp, [pi/2, pi/2], [0.0_wp, 0.0_wp], opts, stat)
        call chk%equal(stat, regdae_err_bad_input, 'band on the dense formulation refused')
        call chk%true(index(solver%message(), 'augmented') > 0, 'the message says what is needed')
    end subroutine dense_formulations_refuse_band

    ! The transpose and the union (merged row by row where the patterns hold the type's
    ! invariant) against pattern_from_entries of their entries, on pseudo-random patterns,
    ! and on patterns without the invariant (an unsorted row, a repeated column, a column
    ! outside the matrix), which take pattern_from_entries itself.
    subroutine pattern_transpose_and_union_by_entries(chk)
        type(checker), intent(inout) :: chk
        type(sparsity_pattern) :: a, b, expected, got
        integer, allocatable :: ra(:), ca(:), rb(:), cb(:)
        integer :: trial, m, n
        integer(int64) :: seed
        character(len=24) :: what
        seed = 12345
        do trial = 1, 40
            m = 1 + lcg_next(seed, 7)
            n = 1 + lcg_next(seed, 9)
            a = random_pattern(m, n)
            b = random_pattern(m, n)
            if (trial > 30 .and. mod(trial, 3) == 0) then   ! break a's invariant: a descent in the last row
                a%cols = [a%cols, n, 1]
                a%row_start(m + 1) = size(a%cols) + 1
            else if (trial > 30 .and. mod(trial, 3) == 1) then   ! a repeated column in the last row
                if (a%row_start(m + 1) > a%row_start(m)) then
                    a%cols = [a%cols, a%cols(a%nnz())]
                else
                    a%cols = [a%cols, 1, 1]
                end if
                a%row_start(m + 1) = size(a%cols) + 1
            else if (trial > 30) then   ! a column outside the matrix (0 or n + 1)
                a%cols = [a%cols, 1, n, n + 1 - mod(trial, 2)*(n + 1)]
                a%row_start(m + 1) = size(a%cols) + 1
            end if
            write (what, '(a,i0)') 'trial ', trial
            call a%entries(ra, ca)
            call b%entries(rb, cb)
            expected = pattern_from_entries(n, m, ca, ra)
            got = a%transposed()
            call chk%true(same(got, expected), trim(what)//': transpose')
            expected = pattern_from_entries(m, n, [ra, rb], [ca, cb])
            got = pattern_union(a, b)
            call chk%true(same(got, expected), trim(what)//': union')
        end do
    contains
        function random_pattern(rows, cols) result(p)
            integer, intent(in) :: rows, cols
            type(sparsity_pattern) :: p
            integer, allocatable :: r(:), c(:)
            call random_entries(seed, rows, cols, r, c)
            p = pattern_from_entries(rows, cols, r, c)
            call chk%true(same(p, brute_force(rows, cols, r, c)), 'pattern_from_entries against a dense table')
        end function random_pattern

        ! The pattern of the entries (r, c) by a dense table, row by row.
        function brute_force(rows, cols, r, c) result(p)
            integer, intent(in) :: rows, cols, r(:), c(:)
            type(sparsity_pattern) :: p
            logical :: table(rows, cols)
            integer :: i, j, k
            table = .false.
            do k = 1, size(r)
                table(r(k), c(k)) = .true.
            end do
            p%nrows = rows
            p%ncols = cols
            allocate (p%row_start(rows + 1), p%cols(count(table)))
            p%row_start(1) = 1
            k = 0
            do i = 1, rows
                do j = 1, cols
                    if (.not. table(i, j)) cycle
                    k = k + 1
                    p%cols(k) = j
                end do
                p%row_start(i + 1) = k + 1
            end do
        end function brute_force

        logical function same(x, y)
            type(sparsity_pattern), intent(in) :: x, y
            same = x%nrows == y%nrows .and. x%ncols == y%ncols .and. size(x%row_start) == size(y%row_start)
            if (same) same = all(x%row_start == y%row_start)
            if (same) same = x%nnz() == y%nnz()
            if (same) same = all(x%cols(1:x%nnz()) == y%cols(1:y%nnz()))
        end function same
    end subroutine pattern_transpose_and_union_by_entries

    ! column_groups (smallest-last greedy coloring): every column in exactly one group, no two
    ! columns of a group in the same row, on pseudo-random patterns and on a tridiagonal one
    ! (3 groups, its longest row); at least as many groups as the longest row has entries.
    subroutine column_groups_share_no_row(chk)
        type(checker), intent(inout) :: chk
        type(sparsity_pattern) :: p
        integer, allocatable :: r(:), c(:), group_start(:), group_cols(:), seen(:), owner(:)
        integer :: trial, i, g, a, ngroups, m, n
        integer(int64) :: seed
        logical :: valid
        character(len=24) :: what
        seed = 4711
        do trial = 0, 30
            if (trial == 0) then
                p = band_pattern(12, 1, 1)
            else
                m = 1 + lcg_next(seed, 12)
                n = 1 + lcg_next(seed, 12)
                call random_entries(seed, m, n, r, c)
                p = pattern_from_entries(m, n, r, c)
            end if
            write (what, '(a,i0)') 'trial ', trial
            call column_groups(p, ngroups, group_start, group_cols)
            allocate (seen(p%ncols), source=0)
            allocate (owner(p%nrows))
            valid = size(group_start) == ngroups + 1 .and. size(group_cols) == p%ncols
            do g = 1, ngroups
                if (.not. valid) exit
                owner = 0
                do a = group_start(g), group_start(g + 1) - 1
                    seen(group_cols(a)) = seen(group_cols(a)) + 1
                    do i = 1, p%nrows
                        if (p%position(i, group_cols(a)) == 0) cycle
                        if (owner(i) /= 0) valid = .false.
                        owner(i) = group_cols(a)
                    end do
                end do
            end do
            call chk%true(valid .and. all(seen == 1), trim(what)//': each column once, no row shared')
            if (p%nrows > 0) call chk%true(ngroups >= maxval(p%row_start(2:) - p%row_start(:p%nrows)), &
                                           trim(what)//': at least the longest row')
            if (trial == 0) call chk%equal(ngroups, 3, 'tridiagonal: 3 groups')
            deallocate (seen, owner)
        end do
    end subroutine column_groups_share_no_row

    ! Random entries (r(k), c(k)) of an m x n matrix, as many as a random draw in 0 .. m n (seed updated).
    subroutine random_entries(seed, m, n, r, c)
        integer(int64), intent(inout) :: seed
        integer, intent(in) :: m, n
        integer, allocatable, intent(out) :: r(:), c(:)
        integer :: nent, k
        nent = lcg_next(seed, m*n + 1)
        allocate (r(nent), c(nent))
        do k = 1, nent
            r(k) = 1 + lcg_next(seed, m)
            c(k) = 1 + lcg_next(seed, n)
        end do
    end subroutine random_entries

    ! The next of a linear congruential sequence (seed updated), as an integer in 0 .. range - 1.
    integer function lcg_next(seed, range) result(k)
        integer(int64), intent(inout) :: seed
        integer, intent(in) :: range
        seed = mod(1103515245_int64*seed + 12345_int64, 2147483648_int64)
        k = int(mod(seed/65536_int64, int(range, int64)))
    end function lcg_next

end module test_structure
