!> Solver options: a typed record with documented defaults, settable from
!! `key=value` strings (the same keys the drivers accept).
!!
!! | key            | values                                | default        |
!! |----------------|---------------------------------------|----------------|
!! | method         | baumgarte, trust_region, direct       | trust_region   |
!! | formulation    | auto, eliminated, multiplier, augmented | auto (see below) |
!! | lsq            | auto, normal, stacked (auto: normal, stacked where ill-conditioned) | auto |
!! | exclusion      | suppress, weights, off                | suppress       |
!! | gamma          | > 0, or auto (20/T, T the time scale at t0) | auto     |
!! | eps            | >= 0, or auto (rtol^2 within [1e-14, 1e-6], times the scale of GB squared) | auto |
!! | rtol, atol     | 0 < rtol < 1, atol > 0                | 1e-5, 1e-5     |
!! | atol_v         | > 0, or auto (= atol): second order, the velocities' atol | auto |
!! | stop_at_output | yes, no                               | no             |
!! | max_steps      | >= 1 (per output interval)            | 100000         |
!! | max_order      | 1 ... 5 (IDA's largest BDF order)     | 5              |
!! | h_init, h_max  | >= 0 (0: IDA's choice / no limit)     | 0, 0           |
!! | ic_tol         | > 0                                   | 1e-8           |
!! | index          | 2, 3 (second-order problems)          | 3              |
!! | gamma0, gamma1 | > 0 (index 3: weights of g, G v + g_t), or auto (gamma1 = 20/T, gamma0 = gamma1^2/2) | auto |
!! | curvature      | yes, no (index 3: add g_xx(v,v) ...)  | yes            |
!! | excluded       | y, vy (index 3: left out of the error test) | y        |
!! | singular_threshold | >= 0 (sigma_min(GB) below: singular), or auto (0.05 times its running maximum) | auto |
!! | jump_tol       | >= 0 (order >= 2: velocity-jump alarm across a singular interval, 0: off) | 0.1 |
!! | drift_tol      | >= 0 (order >= 2: alarm when max abs(g(x, t)) exceeds it, 0: off), or auto (from the tolerances on x) | auto |
!! | invariant_tol  | >= 0 (order >= 2: alarm when the problem's invariant changes by more, 0: off) | 0 |
!! | resolution_tol | >= 0 (warning regdae_warn_unresolved when the integration errors of the approach to a singular configuration are amplified in x by more than this: the constraint's conditioning falls faster than the stabilization forgets; 0: off) | 1e4 |
!! | work_tol       | >= 0 or auto (mechanical: alarm when the work-energy defect exceeds this fraction of the energy scale, 0: off; auto: 0.05 (rtol/1e-3)^(1/5) within [0.02, 0.05]) | auto |
!! | taylor_h       | > 0 (order >= 3: h of the weights m!/(k! h^(m-k))) | 1e-2 |
!! | mass_damping   | >= 0 (mechanical: mu of (M^T M + mu I), 0: Cholesky of M) | 0 |
!! | integrator     | auto, ida, dopri5 (explicit, eliminated formulation only; auto: dopri5 while not stiff), radau (Radau IIA order 5, dense LU; the eliminated formulation as an ODE, the augmented one as an index-1 DAE) | auto |
!! | linear_solver  | auto, dense, band, sparse (IDA's Newton matrix; band and sparse: augmented, integrator=ida) | auto |
!! | check_jacobians | yes, no (at init: G against difference quotients of g; augmented: the grouped Newton matrix against the full one) | no |
!! | pass_check     | yes, no (order 1 and 2: each singular pass re-integrated at rtol/10 (and /100, /1000 while they disagree) and held against pass_tol; warning regdae_warn_unresolved if no level agrees) | yes |
!! | pass_tol       | > 0 (the largest difference of two levels over a pass, in units of the error weights rtol abs(z) + atol, that counts as agreement) | 3 |
!! | error_estimate | yes, no (a companion solution at rtol/10 alongside: the global error estimate of x at every output) | no |
!!
!! `formulation=auto` takes `augmented` for a mechanical problem that declares its
!! structure and has at least `augmented_min_n` coordinates (integrated by IDA, M
!! positive definite), `eliminated` otherwise. `linear_solver=auto` takes dense for
!! the eliminated and multiplier formulations and sparse (KLU) for the augmented one.
module regdae_options
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
    use regdae_kinds, only: wp
    use regdae_status, only: regdae_success, regdae_err_bad_input
    use regdae_damped_lsq, only: lsq_normal, lsq_stacked, lsq_checked
    use regdae_parse, only: parse_real, parse_integer
    use regdae_format, only: format_real, format_int
    implicit none
    private

    integer, parameter, public :: method_baumgarte = 1     !! (2.1a) with (2.5): gamma g + G x' + g_t = 0
    integer, parameter, public :: method_trust_region = 2  !! (2.10)/(2.11)
    integer, parameter, public :: method_direct = 3        !! (2.12)/(2.13)

    !> The value of a real option that regdae chooses itself (`key=auto`).
    real(wp), parameter, public :: option_auto = -huge(1.0_wp)

    integer, parameter, public :: formulation_auto = 0        !! augmented for large structured mechanical problems, else eliminated
    integer, parameter, public :: formulation_multiplier = 1  !! IDA unknowns (x, y)
    integer, parameter, public :: formulation_eliminated = 2  !! IDA unknowns x; y solved in the residual
    integer, parameter, public :: formulation_augmented = 3   !! mechanical: sparse unknowns (q, v, u, y, s), regdae_augmented_system

    !> formulation=auto takes `augmented` from this many coordinates on (with a declared structure).
    integer, parameter, public :: augmented_min_n = 16

    integer, parameter, public :: linear_solver_auto = 0    !! by formulation: dense, or KLU (augmented)
    integer, parameter, public :: linear_solver_dense = 1   !! SUNDIALS dense LU
    integer, parameter, public :: linear_solver_band = 2    !! SUNDIALS band LU (augmented formulation)
    integer, parameter, public :: linear_solver_sparse = 3  !! KLU (augmented formulation)

    integer, parameter, public :: lsq_auto = 0  !! normal equations, stacked per solve where they are ill-conditioned
    public :: lsq_normal, lsq_stacked, lsq_checked

    integer, parameter, public :: exclusion_suppress = 1  !! FIDASetId + FIDASetSuppressAlg
    integer, parameter, public :: exclusion_weights = 2   !! zero error weights (FIDAWFtolerances)
    integer, parameter, public :: exclusion_off = 3       !! y stays in the error test

    integer, parameter, public :: integrator_auto = 0    !! dopri5 while the system is not stiff, Radau or IDA where it is
    integer, parameter, public :: integrator_ida = 1     !! SUNDIALS IDA (BDF), any stiffness
    integer, parameter, public :: integrator_dopri5 = 2  !! explicit Dormand-Prince 5(4): non-stiff regularized systems
    integer, parameter, public :: integrator_radau = 3   !! Radau IIA of order 5 (implicit): small stiff systems

    integer, parameter, public :: excluded_y = 1    !! index 3: only y leaves the error test
    integer, parameter, public :: excluded_vy = 2   !! index 3: v and y leave it (the paper's choice)

    !> All options of a regdae solver, with their defaults.
    type, public :: solver_options
        integer :: method = method_trust_region        !! regularization
        integer :: formulation = formulation_auto      !! what IDA integrates
        integer :: lsq = lsq_auto                      !! damped least-squares solver
        integer :: exclusion = exclusion_suppress      !! how y leaves IDA's local error test
        real(wp) :: gamma = option_auto                !! Baumgarte parameter (paper: 1/h; auto: 20/T)
        real(wp) :: eps = option_auto                  !! damping of trust-region / direct (auto: see resolve)
        real(wp) :: rtol = 1.0e-5_wp                   !! relative tolerance (IDA)
        real(wp) :: atol = 1.0e-5_wp                   !! absolute tolerance (on x; second order: on the positions)
        real(wp) :: atol_v = option_auto               !! second order: absolute tolerance on the velocities (auto: atol);
                                                       !! per component: the argument atol_vector of init
        logical :: stop_at_output = .false.            !! make a step end at every output time
        integer :: max_steps = 100000                  !! IDA steps allowed per call of `advance`
        integer :: max_order = 5                       !! IDA's largest BDF order, 1 ... 5 (IDASetMaxOrd)
        real(wp) :: h_init = 0.0_wp                    !! first step size (0: IDA estimates it)
        real(wp) :: h_max = 0.0_wp                     !! largest step size (0: unlimited)
        real(wp) :: ic_tol = 1.0e-8_wp                 !! allowed max |g(x0, t0)| (and |G v0 + g_t|)
        integer :: index = 3                           !! second-order problems: 3, or 2 via G v + g_t = 0 (5.4)
        real(wp) :: gamma0 = option_auto               !! index 3: weight of g (paper: 2/h^2; auto: gamma1^2/2)
        real(wp) :: gamma1 = option_auto               !! index 3: weight of G v + g_t (paper: 2/h; auto: 20/T)
        logical :: curvature = .true.                  !! index 3: add g_xx(v,v) + 2 g_xt v + g_tt to r
        integer :: excluded = excluded_y               !! index 3: which variables leave the error test
        real(wp) :: singular_threshold = option_auto   !! sigma_min(GB) below this at a sample: singular (auto: 0.05 times
                                                       !! its running maximum)
        real(wp) :: jump_tol = 0.1_wp                  !! relative velocity jump across a singular interval
                                                       !! that stops the run (regdae_err_branch); 0: no check
        real(wp) :: drift_tol = option_auto            !! max |g(x, t)| that stops the run (regdae_err_drift); 0: no check
        real(wp) :: work_tol = option_auto             !! mechanical problems: work-energy defect (fraction of the
                                                       !! motion's energy scale) that stops the run (regdae_err_work); 0: off
        real(wp) :: invariant_tol = 0.0_wp             !! change of the problem's invariant that stops the run
                                                       !! (regdae_err_invariant); 0: no check
        real(wp) :: resolution_tol = 1.0e4_wp          !! amplification in x of the integration errors made on the
                                                       !! approach to a singular configuration above which advance
                                                       !! warns (regdae_warn_unresolved); 0: off
        real(wp) :: taylor_h = 1.0e-2_wp               !! order >= 3: h of the Taylor weights (eq. 4.16)
        real(wp) :: mass_damping = 0.0_wp              !! mechanical: mu of (4.11); 0: M must be SPD
        integer :: integrator = integrator_auto        !! auto, ida, dopri5 (explicit) or radau (eliminated or augmented)
        integer :: linear_solver = linear_solver_auto  !! IDA's linear solver
        logical :: check_jacobians = .false.           !! compare the user's G (and the grouped Newton matrix) with
                                                       !! difference quotients at init (regdae_err_jacobian)
        logical :: pass_check = .true.                 !! re-integrate each singular pass at tighter tolerances and
                                                       !! compare (regdae_solver_trust); a pass no level resolves warns
        real(wp) :: pass_tol = 3.0_wp                  !! agreement of two levels over a pass, in error weights
        logical :: error_estimate = .false.            !! a companion at rtol/10 gives the global error estimate of x
    end type solver_options

    public :: resolved_work_tol, option_text
    public :: set_option, validate_options, method_name, formulation_name, lsq_name, exclusion_name, excluded_name, &
              integrator_name, linear_solver_name

    ! The names of the codes, in the order of their values (method_name and the like).
    character(len=12), parameter :: method_names(3) = [character(len=12) :: 'baumgarte', 'trust_region', 'direct']
    character(len=12), parameter :: formulation_names(4) = [character(len=12) :: 'auto', 'multiplier', 'eliminated', 'augmented']
    character(len=12), parameter :: lsq_names(4) = [character(len=12) :: 'auto', 'normal', 'stacked', 'checked']
    character(len=12), parameter :: exclusion_names(3) = [character(len=12) :: 'suppress', 'weights', 'off']
    character(len=12), parameter :: linear_solver_names(4) = [character(len=12) :: 'auto', 'dense', 'band', 'sparse']
    character(len=12), parameter :: integrator_names(4) = [character(len=12) :: 'auto', 'ida', 'dopri5', 'radau']
    character(len=12), parameter :: excluded_names(2) = [character(len=12) :: 'y', 'vy']

contains

    !> Set one option from its `key` and textual `value`.
    !! An unknown key or a bad value gives `regdae_err_bad_input` and a message
    !! naming it.
    subroutine set_option(opts, key, value, stat, msg)
        type(solver_options), intent(inout) :: opts
        character(len=*), intent(in) :: key     !! option name (see the table above)
        character(len=*), intent(in) :: value   !! its value as text
        integer, intent(out) :: stat
        character(len=:), allocatable, intent(out) :: msg   !! empty on success
        type(solver_options) :: previous
        integer :: code

        previous = opts
        stat = regdae_success
        msg = ''
        select case (key)
        case ('method')
            call lookup(value, [character(len=12) :: 'baumgarte', 'trust_region', 'direct'], code)
            if (code > 0) opts%method = code
        case ('formulation')
            call lookup(value, [character(len=12) :: 'multiplier', 'eliminated', 'augmented', 'auto'], code)
            if (code > 0) opts%formulation = merge(formulation_auto, code, code == 4)
        case ('lsq')
            call lookup(value, [character(len=12) :: 'normal', 'stacked', 'auto'], code)
            if (code > 0) opts%lsq = merge(lsq_auto, code, code == 3)
        case ('exclusion')
            call lookup(value, [character(len=12) :: 'suppress', 'weights', 'off'], code)
            if (code > 0) opts%exclusion = code
        case ('stop_at_output')
            call lookup(value, [character(len=12) :: 'yes', 'no'], code)
            if (code > 0) opts%stop_at_output = (code == 1)
        case ('gamma')
            call read_real_or_auto(value, opts%gamma, code)
        case ('eps')
            call read_real_or_auto(value, opts%eps, code)
        case ('rtol')
            call read_real(value, opts%rtol, code)
        case ('atol')
            call read_real(value, opts%atol, code)
        case ('atol_v')
            call read_real_or_auto(value, opts%atol_v, code)
        case ('h_init')
            call read_real(value, opts%h_init, code)
        case ('h_max')
            call read_real(value, opts%h_max, code)
        case ('ic_tol')
            call read_real(value, opts%ic_tol, code)
        case ('max_steps')
            call read_integer(value, opts%max_steps, code)
        case ('max_order')
            call read_integer(value, opts%max_order, code)
        case ('index')
            call lookup(value, [character(len=12) :: '1', '2', '3'], code)
            if (code > 1) opts%index = code
            if (code == 1) code = 0
        case ('gamma0')
            call read_real_or_auto(value, opts%gamma0, code)
        case ('gamma1')
            call read_real_or_auto(value, opts%gamma1, code)
        case ('curvature')
            call lookup(value, [character(len=12) :: 'yes', 'no'], code)
            if (code > 0) opts%curvature = (code == 1)
        case ('excluded')
            call lookup(value, [character(len=12) :: 'y', 'vy'], code)
            if (code > 0) opts%excluded = code
        case ('singular_threshold')
            call read_real_or_auto(value, opts%singular_threshold, code)
        case ('jump_tol')
            call read_real(value, opts%jump_tol, code)
        case ('drift_tol')
            call read_real_or_auto(value, opts%drift_tol, code)
        case ('invariant_tol')
            call read_real(value, opts%invariant_tol, code)
        case ('resolution_tol')
            call read_real(value, opts%resolution_tol, code)
        case ('work_tol')
            call read_real_or_auto(value, opts%work_tol, code)
        case ('taylor_h')
            call read_real(value, opts%taylor_h, code)
        case ('mass_damping')
            call read_real(value, opts%mass_damping, code)
        case ('integrator')
            call lookup(value, [character(len=12) :: 'ida', 'dopri5', 'auto', 'radau'], code)
            if (code > 0) opts%integrator = merge(integrator_auto, code, code == 3)
            if (code == 4) opts%integrator = integrator_radau
        case ('check_jacobians')
            call lookup(value, [character(len=12) :: 'yes', 'no'], code)
            if (code > 0) opts%check_jacobians = (code == 1)
        case ('pass_check')
            call lookup(value, [character(len=12) :: 'yes', 'no'], code)
            if (code > 0) opts%pass_check = (code == 1)
        case ('pass_tol')
            call read_real(value, opts%pass_tol, code)
        case ('error_estimate')
            call lookup(value, [character(len=12) :: 'yes', 'no'], code)
            if (code > 0) opts%error_estimate = (code == 1)
        case ('linear_solver')
            call lookup(value, [character(len=12) :: 'dense', 'band', 'sparse', 'auto'], code)
            if (code > 0) opts%linear_solver = merge(linear_solver_auto, code, code == 4)
        case default
            stat = regdae_err_bad_input
            msg = 'unknown option "'//key//'"'
            return
        end select
        if (code <= 0) then
            stat = regdae_err_bad_input
            msg = 'bad value "'//value//'" for option "'//key//'"'//expected_form(key)
            return
        end if
        call validate_options(opts, stat, msg)
        if (stat /= regdae_success) opts = previous
    end subroutine set_option

    !> Check every option's range; the message names the first bad one.
    subroutine validate_options(opts, stat, msg)
        type(solver_options), intent(in) :: opts
        integer, intent(out) :: stat
        character(len=:), allocatable, intent(out) :: msg
        stat = regdae_err_bad_input
        msg = ''
        if (opts%gamma /= option_auto) call need_positive('gamma', opts%gamma)
        if (opts%eps /= option_auto) call need_nonnegative('eps', opts%eps)
        if (len(msg) == 0 .and. .not. (opts%rtol > 0.0_wp .and. opts%rtol < 1.0_wp)) &
            msg = 'rtol must be in (0, 1) (got '//format_real(opts%rtol)//')'
        call need_positive('atol', opts%atol)
        if (opts%atol_v /= option_auto) call need_positive('atol_v', opts%atol_v)

        call need_nonnegative('h_init', opts%h_init)
        call need_nonnegative('h_max', opts%h_max)
        call need_positive('ic_tol', opts%ic_tol)
        if (opts%gamma0 /= option_auto) call need_positive('gamma0', opts%gamma0)
        if (opts%gamma1 /= option_auto) call need_positive('gamma1', opts%gamma1)
        if (opts%singular_threshold /= option_auto) call need_nonnegative('singular_threshold', opts%singular_threshold)
        call need_nonnegative('jump_tol', opts%jump_tol)
        if (opts%drift_tol /= option_auto) call need_nonnegative('drift_tol', opts%drift_tol)
        call need_nonnegative('invariant_tol', opts%invariant_tol)
        call need_nonnegative('resolution_tol', opts%resolution_tol)
        if (opts%work_tol /= option_auto) call need_nonnegative('work_tol', opts%work_tol)
        call need_positive('taylor_h', opts%taylor_h)
        call need_positive('pass_tol', opts%pass_tol)
        call need_nonnegative('mass_damping', opts%mass_damping)
        if (len(msg) > 0) then
            return
        else if (opts%integrator < integrator_auto .or. opts%integrator > integrator_radau) then
            msg = 'integrator must be auto, ida, dopri5 or radau'
        else if (opts%integrator == integrator_dopri5 .and. &
                 opts%formulation /= formulation_eliminated .and. opts%formulation /= formulation_auto) then
            msg = 'integrator=dopri5 needs formulation=eliminated'
        else if (opts%integrator == integrator_radau .and. opts%formulation == formulation_multiplier) then
            msg = 'integrator=radau needs formulation=eliminated or augmented (or auto)'
        else if (opts%linear_solver < linear_solver_auto .or. opts%linear_solver > linear_solver_sparse) then
            msg = 'linear_solver must be auto, dense, band or sparse'
        else if (opts%integrator == integrator_radau .and. (opts%linear_solver == linear_solver_band .or. &
                                                             opts%linear_solver == linear_solver_sparse)) then
            msg = 'linear_solver='//linear_solver_name(opts%linear_solver)//' is for integrator=ida: integrator=radau '// &
                  'factors its Newton matrices dense (linear_solver=dense or auto)'
        else if ((opts%linear_solver == linear_solver_band .or. opts%linear_solver == linear_solver_sparse) .and. &
                 (opts%formulation == formulation_eliminated .or. opts%formulation == formulation_multiplier)) then
            msg = 'linear_solver='//linear_solver_name(opts%linear_solver)//' needs formulation=augmented (or auto): '// &
                  'the Newton matrix of the '//formulation_name(opts%formulation)//' formulation is dense'
        else if (opts%index /= 2 .and. opts%index /= 3) then
            msg = 'index must be 2 or 3'
        else if (opts%excluded /= excluded_y .and. opts%excluded /= excluded_vy) then
            msg = 'excluded must be y or vy'
        else if (opts%max_steps < 1) then
            msg = 'max_steps must be >= 1 (got '//format_int(opts%max_steps)//')'
        else if (opts%max_order < 1 .or. opts%max_order > 5) then
            msg = 'max_order must be 1 ... 5 (got '//format_int(opts%max_order)//')'
        else if (opts%method < method_baumgarte .or. opts%method > method_direct) then
            msg = 'unknown method'
        else if (opts%formulation < formulation_auto .or. opts%formulation > formulation_augmented) then
            msg = 'unknown formulation'
        else if (opts%lsq < lsq_auto .or. opts%lsq > lsq_stacked) then
            msg = 'unknown lsq solver'
        else if (opts%exclusion < exclusion_suppress .or. opts%exclusion > exclusion_off) then
            msg = 'unknown exclusion mechanism'
        else
            stat = regdae_success
            msg = ''
        end if
    contains
        subroutine need_positive(name, x)
            character(len=*), intent(in) :: name
            real(wp), intent(in) :: x
            if (len(msg) > 0) return
            if (.not. (ieee_is_finite(x) .and. x > 0.0_wp)) msg = name//' must be finite and > 0 (got '//format_real(x)//')'
        end subroutine need_positive

        subroutine need_nonnegative(name, x)
            character(len=*), intent(in) :: name
            real(wp), intent(in) :: x
            if (len(msg) > 0) return
            if (.not. (ieee_is_finite(x) .and. x >= 0.0_wp)) &
                msg = name//' must be finite and >= 0 (got '//format_real(x)//')'
        end subroutine need_nonnegative
    end subroutine validate_options

    !> work_tol=auto: the defect allowed, as a fraction of the motion's energy
    !! scale: 0.05 at rtol >= 1e-3, falling like rtol^(1/5) to 0.02 at rtol <= 1e-5.
    pure real(wp) function resolved_work_tol(opts) result(tol)
        type(solver_options), intent(in) :: opts
        tol = opts%work_tol
        ! auto: 0.05 (rtol/1e-3)^(1/5) within [0.02, 0.05]: the defect of correct runs
        ! shrinks with the tolerance (measured on the default-options grid: at most 4.7%
        ! at rtol 1e-3, 1.8% at rtol <= 1e-5; doc/methods.md)
        if (tol == option_auto) tol = min(0.05_wp, max(0.02_wp, 0.05_wp*(opts%rtol/1.0e-3_wp)**0.2_wp))
    end function resolved_work_tol

    !> A real option as text: its value, or 'auto'.
    pure function option_text(x) result(text)
        real(wp), intent(in) :: x
        character(len=len_trim(option_padded(x))) :: text
        text = option_padded(x)
    end function option_text

    pure function option_padded(x) result(text)
        real(wp), intent(in) :: x
        character(len=40) :: text
        text = 'auto'
        if (x /= option_auto) text = format_real(x, 4)
    end function option_padded

    ! The names of the codes: automatic-length results, no `character(len=:), allocatable`
    ! one (doc/methods.md, "No global state").

    !> Name of a method code, as accepted by `set_option`.
    pure function method_name(code) result(name)
        integer, intent(in) :: code
        character(len=len_trim(code_name(code, method_names, 1))) :: name
        name = code_name(code, method_names, 1)
    end function method_name

    !> Name of a formulation code.
    pure function formulation_name(code) result(name)
        integer, intent(in) :: code
        character(len=len_trim(code_name(code, formulation_names, 0))) :: name
        name = code_name(code, formulation_names, 0)
    end function formulation_name

    !> Name of a least-squares solver code.
    pure function lsq_name(code) result(name)
        integer, intent(in) :: code
        character(len=len_trim(code_name(code, lsq_names, 0))) :: name
        name = code_name(code, lsq_names, 0)
    end function lsq_name

    !> Name of an error-test exclusion code.
    pure function exclusion_name(code) result(name)
        integer, intent(in) :: code
        character(len=len_trim(code_name(code, exclusion_names, 1))) :: name
        name = code_name(code, exclusion_names, 1)
    end function exclusion_name

    !> Name of a linear-solver code.
    pure function linear_solver_name(code) result(name)
        integer, intent(in) :: code
        character(len=len_trim(code_name(code, linear_solver_names, 0))) :: name
        name = code_name(code, linear_solver_names, 0)
    end function linear_solver_name

    !> Name of an integrator code.
    pure function integrator_name(code) result(name)
        integer, intent(in) :: code
        character(len=len_trim(code_name(code, integrator_names, 0))) :: name
        name = code_name(code, integrator_names, 0)
    end function integrator_name

    !> Name of an error-test set code (index 3).
    pure function excluded_name(code) result(name)
        integer, intent(in) :: code
        character(len=len_trim(code_name(code, excluded_names, 1))) :: name
        name = code_name(code, excluded_names, 1)
    end function excluded_name

    ! names(code - first + 1), or 'unknown' for a code outside the table; padded with blanks.
    pure function code_name(code, names, first) result(name)
        integer, intent(in) :: code, first
        character(len=*), intent(in) :: names(:)
        character(len=12) :: name
        name = 'unknown'
        if (code >= first .and. code - first < size(names)) name = names(code - first + 1)
    end function code_name

    ! What a key's value looks like, for the message about a bad one.
    pure function expected_form(key) result(text)
        character(len=*), intent(in) :: key
        character(len=len_trim(expected_padded(key))) :: text
        text = expected_padded(key)
    end function expected_form

    pure function expected_padded(key) result(text)
        character(len=*), intent(in) :: key
        character(len=48) :: text
        select case (key)
        case ('method'); text = ' (baumgarte, trust_region or direct)'
        case ('formulation'); text = ' (auto, eliminated, multiplier or augmented)'
        case ('linear_solver'); text = ' (auto, dense, band or sparse)'
        case ('lsq'); text = ' (auto, normal or stacked)'
        case ('exclusion'); text = ' (suppress, weights or off)'
        case ('stop_at_output', 'curvature', 'check_jacobians', 'pass_check', 'error_estimate'); text = ' (yes or no)'
        case ('index'); text = ' (2 or 3)'
        case ('excluded'); text = ' (y or vy)'
        case ('integrator'); text = ' (auto, ida, dopri5 or radau)'
        case ('max_steps'); text = ' (an integer, e.g. 100000)'
        case ('max_order'); text = ' (an integer, 1 ... 5)'
        case ('work_tol', 'gamma', 'gamma0', 'gamma1', 'eps', 'singular_threshold', 'drift_tol')
            text = ' (a finite number, or auto)'
        case default; text = ' (a finite number, e.g. 1e-6, 2.5 or .5)'
        end select
    end function expected_padded

    ! Position of `value` in `names` (1-based), 0 if absent.
    pure subroutine lookup(value, names, code)
        character(len=*), intent(in) :: value
        character(len=*), intent(in) :: names(:)
        integer, intent(out) :: code
        integer :: i
        code = 0
        do i = 1, size(names)
            if (value == trim(names(i))) code = i
        end do
    end subroutine lookup

    ! Read a finite real (regdae_parse's forms); code = 1 on success, 0 otherwise.
    subroutine read_real(text, x, code)
        character(len=*), intent(in) :: text
        real(wp), intent(inout) :: x
        integer, intent(out) :: code
        logical :: ok
        call parse_real(text, x, ok)
        code = merge(1, 0, ok)
    end subroutine read_real

    ! A real or `auto` (option_auto); code = 1 on success, 0 otherwise.
    subroutine read_real_or_auto(text, x, code)
        character(len=*), intent(in) :: text
        real(wp), intent(inout) :: x
        integer, intent(out) :: code
        if (trim(adjustl(text)) == 'auto') then
            x = option_auto
            code = 1
        else
            call read_real(text, x, code)
        end if
    end subroutine read_real_or_auto

    ! Read an integer (regdae_parse's forms); code = 1 on success, 0 otherwise.
    subroutine read_integer(text, k, code)
        character(len=*), intent(in) :: text
        integer, intent(inout) :: k
        integer, intent(out) :: code
        logical :: ok
        call parse_integer(text, k, ok)
        code = merge(1, 0, ok)
    end subroutine read_integer

end module regdae_options
