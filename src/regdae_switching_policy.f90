!> The switching policy of integrator=auto, the decisions only: which implicit
!! integrator takes a stiff system (radau_preferred), whether a structured one is
!! stiff already at t0 (stiff_at_start), and when the implicit
!! integrator hands back to the explicit one (explicit_would_do). (The explicit method's own
!! stiffness test, Hairer's, decides the hand-over to the implicit one inside
!! `regdae_explicit_rk`; the switches themselves, which create and start the
!! integrators, are `regdae_integrator_switching`'s.) The spectral radius of the
!! eliminated formulation's Jacobian by power iteration is the stiffness estimate
!! of the implicit integrators (`regdae_ida_integrator`).
module regdae_switching_policy
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
    use regdae_kinds, only: wp
    use regdae_status, only: regdae_success
    use regdae_solver_core, only: solver_core
    use regdae_lapack, only: dgeev
    use regdae_radau_system, only: difference_jacobian
    use regdae_eliminated_ode, only: eliminated_ode
    implicit none
    private

    public :: spectral_radius, explicit_would_do, radau_preferred, stiff_at_start

    !> The largest state (size of z) that integrator=auto gives to Radau IIA where
    !! the system is stiff (above it: IDA). Measured on the stiff chain (mass 1e-2,
    !! stiffness 1e4, damping 10, rtol 1e-7, eliminated formulation; doc/methods.md,
    !! "Which implicit integrator"): Radau takes 41-43 steps against IDA's 130 at
    !! 1-3x IDA's cost per step, 1.0-3.4x less time per run at 4 ... 128 states
    !! (1 ... 32 links; even at 16 links); both cost O(n^3) per step there (the dense
    !! eliminated formulation). No crossover was found up to 128: the bound keeps
    !! Radau's n x n dense LU and n-column Jacobian where it was measured.
    integer, parameter, public :: radau_max_n = 128

    !> The largest state (size of z = (q, v)) of a mechanical problem that declares
    !! its structure that integrator=auto gives to Radau IIA on the eliminated
    !! formulation where it is stiff (above it: IDA on the augmented formulation with
    !! KLU). Measured on the stiff chain (mass 1e-2, stiffness 1e4, damping 10, tf 1,
    !! 100 outputs; callgrind's instructions of init and advances at matched accuracy
    !! 1e-7 ... 1e-12, doc/methods.md, "Which implicit integrator"): Radau 1.3-3.6x
    !! cheaper than IDA with KLU up to 4 links (16 states; but 1.05x at 4 links and
    !! 1e-12), even at 5 (20 states: 0.79-1.08x), dearer from 6 (24 states:
    !! 0.95-1.36x; 8 links 1.4-2.0x). Radau on the augmented formulation (dense LU)
    !! was dearer than on the eliminated one at every size.
    integer, parameter, public :: radau_structured_max_n = 20

    !> integrator=auto, a mechanical problem that declares its structure: it starts on
    !! the implicit integrator where the step that accuracy allows at t0 exceeds this
    !! factor times the explicit method's stable step (stiff_at_start).
    real(wp), parameter, public :: stiff_start_factor = 7.0_wp

    !> stiff_start_factor where the implicit integrator would be Radau IIA (radau_preferred):
    !! Radau from t0 was cheaper at matched accuracy than the explicit start and the switch
    !! at every rtol down to 1e-9 on the stiff 4-link chain (doc/methods.md, "Which implicit
    !! integrator"), where h_accurate is 20 ... 1.3 times the stable step.
    real(wp), parameter, public :: stiff_start_factor_radau = 1.0_wp

    !> stiff_at_start: a mode lighter than this damping ratio (-Re lambda/|lambda|) that
    !! the accurate step does not resolve keeps the explicit start.
    real(wp), parameter, public :: stiff_start_damping = 0.1_wp

    !> stiff_at_start: the largest state whose dense Jacobian and eigenvalues it computes.
    integer, parameter, public :: stiff_start_max_n = 64

contains

    !> The spectral radius of dF/dz at (t, z), F the eliminated formulation's slope:
    !! five power iterations with difference quotients of F, from the last estimate's
    !! vector, rho = sqrt(|J w_4| |J w_5|) (0: F failed). The model is left evaluated
    !! at (t, z).
    real(wp) function spectral_radius(core, t, z) result(rho)
        type(solver_core), intent(inout) :: core
        real(wp), intent(in) :: t, z(:)
        real(wp) :: f0(core%n), f1(core%n), y(core%m), d, wn, norm_now, norm_last
        integer :: it, stat
        logical :: recoverable
        rho = 0.0_wp
        norm_now = 0.0_wp
        call core%model%slope_eliminated(t, z, f0, y, stat, recoverable)
        if (stat /= regdae_success) return
        if (.not. allocated(core%rho_w)) then
            allocate (core%rho_w(core%n))
            core%rho_w = 1.0_wp
        end if
        d = sqrt(epsilon(1.0_wp))*max(1.0_wp, maxval(abs(z)))
        do it = 1, 5
            wn = norm2(core%rho_w)
            if (.not. (wn > 0.0_wp)) core%rho_w = 1.0_wp
            core%rho_w = core%rho_w/norm2(core%rho_w)
            call core%model%slope_eliminated(t, z + d*core%rho_w, f1, y, stat, recoverable)
            if (stat /= regdae_success) then
                rho = 0.0_wp
                exit
            end if
            core%rho_w = (f1 - f0)/d
            norm_last = norm_now
            norm_now = norm2(core%rho_w)
            if (.not. (norm_now > 0.0_wp)) exit
            ! |J^2 w| / |w| over two iterations: a dominant complex pair (the oscillation
            ! of a second-order system) makes the single ratios alternate
            if (it >= 2) rho = sqrt(norm_now*norm_last)
        end do
        call core%model%evaluate(t, z, stat, recoverable)   ! the model back at the state
    end function spectral_radius

    !> integrator=auto, the system found stiff (or stiff at t0): Radau IIA on the
    !! eliminated formulation for a problem of order 2 (stiff springs, large weights)
    !! with a state of at most radau_max_n components, or of at most
    !! radau_structured_max_n where it declares its structure (structured: it would
    !! otherwise take IDA on the augmented formulation with KLU); IDA otherwise.
    !! First-order problems stay with IDA: on a stiff forcing that moves in time
    !! (test_defaults' stiff_middle, x1' = -1e5 (x1 - sin 50t) + ...) Radau's error
    !! estimate, filtered by (gamma/h - J)^-1, lets steps grow past the accuracy
    !! (measured at rtol 1e-6: error 9.2e-4 against IDA's 6.4e-6).
    logical function radau_preferred(core, structured) result(yes)
        type(solver_core), intent(in) :: core
        logical, intent(in) :: structured
        yes = core%second_order .and. core%model%order == 2 .and. &
              core%n <= merge(radau_structured_max_n, radau_max_n, structured)
    end function radau_preferred

    !> integrator=auto, before the first explicit step: is the system already stiff at
    !! (t0, z0)? The step that accuracy allows there, h_accurate (Hairer's starting step for
    !! an order-5 method: (0.01/max(d1, d2))^(1/5) with d1 = |F(z0)|_w and d2 =
    !! |F(z0 + h0 F(z0)) - F(z0)|_w/h0, h0 = 0.01 |z0|_w/d1, the error weights
    !! w = 1/(rtol |z0| + atol); at most 100 h0), against the explicit method's stable
    !! step 3.3/rho (rho: spectral_radius): stiff where h_accurate exceeds
    !! factor times the stable step, unless a mode that the accurate step
    !! does not resolve (|lambda| h_accurate > 1) is lightly damped (-Re lambda <
    !! stiff_start_damping |lambda|, or growing): every method must then follow it with
    !! steps below its period, and the explicit one does that at less cost. The
    !! eigenvalues of dF/dz (n difference quotients of F, Radau's: difference_jacobian;
    !! dgeev) only where the first test says stiff, for states of at most
    !! stiff_start_max_n components. h_accurate and rho are returned for the event (0:
    !! not computed), and where the answer is yes, that Jacobian (jac), which Radau
    !! starting at (t0, z0) takes as its first.
    logical function stiff_at_start(core, t0, z0, factor, h_accurate, rho, jac) result(yes)
        type(solver_core), intent(inout) :: core
        real(wp), intent(in) :: t0, z0(:)
        real(wp), intent(in) :: factor   !! stiff_start_factor or stiff_start_factor_radau
        real(wp), intent(out) :: h_accurate, rho
        real(wp), allocatable, intent(out), optional :: jac(:, :)   !! dF/dz at (t0, z0), n x n (only where yes)
        real(wp) :: f0(core%n), f1(core%n), y(core%m), w(core%n), d0, d1, d2, h0, dfdz(core%n, core%n)
        integer :: stat
        logical :: recoverable
        yes = .false.
        h_accurate = 0.0_wp
        rho = 0.0_wp
        if (core%n > stiff_start_max_n) return
        call core%model%slope_eliminated(t0, z0, f0, y, stat, recoverable)
        if (stat /= regdae_success) return
        w = 1.0_wp/(core%opts%rtol*abs(z0) + core%atol_z(1:core%n))
        d0 = norm2(z0*w)/sqrt(real(core%n, wp))
        d1 = norm2(f0*w)/sqrt(real(core%n, wp))
        h0 = 1.0e-6_wp
        if (d0 > 1.0e-5_wp .and. d1 > 1.0e-5_wp) h0 = 0.01_wp*d0/d1
        call core%model%slope_eliminated(t0 + h0, z0 + h0*f0, f1, y, stat, recoverable)
        if (stat /= regdae_success) then
            call core%model%evaluate(t0, z0, stat, recoverable)
            return
        end if
        d2 = norm2((f1 - f0)*w)/sqrt(real(core%n, wp))/h0
        if (max(d1, d2) <= 1.0e-15_wp) then
            h_accurate = max(1.0e-6_wp, 1.0e-3_wp*h0)
        else
            h_accurate = (0.01_wp/max(d1, d2))**0.2_wp
        end if
        h_accurate = min(100.0_wp*h0, h_accurate)
        rho = spectral_radius(core, t0, z0)
        yes = rho > 0.0_wp .and. h_accurate > factor*3.3_wp/rho
        if (yes) yes = .not. lightly_damped_mode(core, t0, z0, f0, h_accurate, dfdz)
        if (yes .and. present(jac)) jac = dfdz
    end function stiff_at_start

    ! stiff_at_start: has dF/dz at (t0, z0) (f0 = F there; returned in jac) an eigenvalue
    ! with |lambda| h > 1 and -Re lambda < stiff_start_damping |lambda|? (Also yes where the
    ! Jacobian or its eigenvalues fail: the explicit start stays.) The model is left
    ! evaluated at (t0, z0).
    logical function lightly_damped_mode(core, t0, z0, f0, h, jac) result(light)
        type(solver_core), intent(inout) :: core
        real(wp), intent(in) :: t0, z0(:), f0(:), h
        real(wp), intent(out) :: jac(:, :)
        type(eliminated_ode) :: ode
        real(wp) :: a(core%n, core%n), wr(core%n), wi(core%n), vdum(1, 1), work(4*core%n)
        integer :: stat, evals, info
        logical :: recoverable
        light = .true.
        ode%model => core%model
        allocate (ode%y(core%m))
        call difference_jacobian(ode, t0, z0, f0, jac, stat, recoverable, evals)
        call core%model%evaluate(t0, z0, info, recoverable)   ! the model back at the state
        if (stat /= regdae_success .or. .not. all(ieee_is_finite(jac))) return
        a = jac   ! (dgeev overwrites its matrix)
        call dgeev('N', 'N', core%n, a, core%n, wr, wi, vdum, 1, vdum, 1, work, size(work), info)
        if (info /= 0) return
        light = any(hypot(wr, wi)*h > 1.0_wp .and. -wr < stiff_start_damping*hypot(wr, wi))
    end function lightly_damped_mode

    !> integrator=auto, the implicit integrator active: would the explicit method do
    !! here? Its stable step 3.3/rho (rho: the implicit integrator's stiffness
    !! estimate, spectral_radius) against the implicit integrator's last step: larger
    !! than twice that at two checks in a row (20 steps apart) means that its steps
    !! are set by accuracy, not stiffness. No vote inside a singular interval.
    logical function explicit_would_do(core, t) result(yes)
        type(solver_core), intent(inout), target :: core
        real(wp), intent(in) :: t
        real(wp) :: rho
        yes = .false.
        if (core%augmented) return   ! no switch back from the augmented formulation
        rho = core%stiff%stiffness(t)
        ! not inside a singular interval: the damped multiplier softens the constraint
        ! modes there for a moment (gamma sigma^2/(sigma^2 + eps) -> 0), and the explicit
        ! method would take the pass with the steps of the regular motion (measured:
        ! ex52 index=2 gamma=1e6 rtol=1e-6 switched back at t = 9.507 and lost 3e-2 rad)
        if (rho > 0.0_wp .and. 3.3_wp/rho > 2.0_wp*core%stiff%last_step() .and. .not. core%monitor%in_singular) then
            core%explicit_votes = core%explicit_votes + 1
        else
            core%explicit_votes = 0
        end if
        ! two checks in a row; after each return to IDA twice as many (at most 64), so that
        ! a problem at the border between the two does not switch at every check
        yes = (core%explicit_votes >= 2*2**min(core%back_switches, 5))
    end function explicit_would_do

end module regdae_switching_policy
