!> The rules behind regdae's automatic parameters (options left at `auto`;
!! doc/methods.md, "Automatic parameters"): the Baumgarte weights from the
!! rate of the motion, and the damping eps from the conditioning of GB. Each
!! rule is a pure function of the problem's own scales, so that a problem
!! written in other units gets the same trajectory; the solver front gathers
!! the scales (at t0 and at the samples along the run) and applies the rules.
!!
!! - The rate of the motion: omega = max(rms(v)/l, sqrt(max(rms(a), rms(f))/l)) for
!!   a problem of order 2 (f: the acceleration of the applied forces, a: the
!!   constrained one), max(rms(x'), rms(f))/l for order 1, l the length over which
!!   the constraint gradients turn (`constraint_length`). Continuous in the state:
!!   a start from rest, or one whose acceleration vanishes, still has a rate.
!! - gamma = gamma1 = weight_factor omega, gamma0 = gamma1^2/2: the constraint
!!   error decays at gamma1/2 with damping ratio 1/sqrt(2).
!! - eps = eps_factor(rtol) sigma_reg^2 (trust region), sqrt(eps_factor(rtol))
!!   sigma_reg (direct), sigma_reg the smallest singular value of GB in the
!!   regular part of the motion (the largest sigma_min(GB) seen; at a start on
!!   a singular configuration, predicted from the constraint curvature): the
!!   damping of the regular modes stays below rtol^2 at any size, and the layer
!!   is where sigma_min(GB) < rtol sigma_reg for both methods.
module regdae_auto_rules
    use regdae_kinds, only: wp
    use regdae_differences, only: central_difference_step
    use regdae_regularization, only: regularized_dae
    implicit none
    private

    !> gamma1 = weight_factor x the rate of the motion (doc/methods.md).
    real(wp), parameter, public :: weight_factor = 8.0_wp
    !> A row of G whose norm is below degenerate_row |H_i| l_x vanishes here: a
    !! singular configuration of that row, whose distance to it is no length of the mechanism.
    real(wp), parameter, public :: degenerate_row = 1.0e-4_wp
    !> At a singular start a vanishing row of G is moved by this fraction of the scale
    !! of x (rms of its representative, periodic_representative) along its curvature,
    !! for the prediction of the regular sigma_min(GB).
    real(wp), parameter, public :: predict_shift = 0.5_wp
    !> Along the run the weights change when the rate has grown by this factor.
    real(wp), parameter, public :: weight_hysteresis = 2.0_wp
    !> Along the run eps changes when its target has moved by this factor.
    real(wp), parameter, public :: eps_hysteresis = 4.0_wp
    !> eps_factor = rtol^2 within these bounds.
    real(wp), parameter, public :: eps_factor_min = 1.0e-14_wp, eps_factor_max = 1.0e-6_wp
    !> The layer stays this many roundoffs of GB's largest entry wide: eps >= (eps_round u s)^2.
    real(wp), parameter, public :: eps_round = 1.0e3_wp

    public :: constraint_length, motion_rate, baumgarte_weights, automatic_eps_factor, automatic_eps, rms
    public :: dense_motion_scales, row_curvatures, generic_direction, constraint_mode_step
    public :: periodic_representative, same_geometry, rest_in_equilibrium

    !> The explicit Dormand-Prince method's stable step on the constraint modes:
    !! h |s| within this radius (its stability boundary is 3.3 on the negative real axis
    !! and 3.3 at 135 degrees, where the automatic weights put the modes; at 2.8 a mode is
    !! damped by |R(h s)| = 0.44 per step). Measured: the crank's seed=2026 cell 566
    !! (th1 = 0.966, w1 = 0.1, rtol 1e-4), one 0.55 s step at h |s| = 6.5 after a pass
    !! took the energy 1.4% off (doc/methods.md, "The stable step after a restart").
    real(wp), parameter, public :: stable_radius = 2.8_wp

    !> The Baumgarte weights along the run: the rate behind the weights in force,
    !! and the running length of the constraints (it only grows: a singular pass,
    !! where a row's gradient shrinks, does not shorten it).
    type, public :: weight_rule
        logical :: on = .false.          !! the weights are automatic and follow the motion
        real(wp) :: rate = 0.0_wp        !! the rate behind the weights in force
        real(wp) :: ell = 0.0_wp         !! the running length l
        real(wp) :: t_next = -huge(1.0_wp)   !! no new look before this time (half a time scale on)
        integer :: changes = 0           !! weight changes after t0
    contains
        !> A new rate at t from the current state: true if the weights should
        !! change (the rate grew by weight_hysteresis); then `rate` is the new one.
        procedure :: propose => weight_rule_propose
    end type weight_rule

contains

    !> The length l over which the constraint gradients turn: min over the rows of
    !! |G_i| / |H_i|, |H_i| the largest change of G_i per unit length along the
    !! directions of the motion (gnorm, hnorm: these norms per row), each at most
    !! ell_x, the scale of x (rms(x), 1 if x = 0): a row that is linear at that
    !! scale, or that vanishes here (gnorm < degenerate_row hnorm ell_x: a singular
    !! configuration of that row, whose distance to it is no length of the
    !! mechanism), counts as ell_x; ell_x if no row has a gradient.
    pure real(wp) function constraint_length(gnorm, hnorm, ell_x) result(ell)
        real(wp), intent(in) :: gnorm(:), hnorm(:), ell_x
        integer :: i
        ell = ell_x
        do i = 1, size(gnorm)
            if (.not. (gnorm(i) == gnorm(i) .and. hnorm(i) == hnorm(i))) cycle
            if (gnorm(i) >= degenerate_row*hnorm(i)*ell_x .and. gnorm(i) < hnorm(i)*ell_x) &
                ell = min(ell, gnorm(i)/hnorm(i))
        end do
        if (.not. (ell > 0.0_wp)) ell = ell_x
    end function constraint_length

    !> The rate of the motion (1/time) at a state: the largest of rms(vel)/ell,
    !! sqrt(max(rms(acc), rms(free))/ell) and sqrt(stiff) for order 2 (vel = v,
    !! acc = v', free = the acceleration of the applied forces, stiff = |d free/dx| along a
    !! generic direction: the frequency of the forces, which a start at rest in an
    !! equilibrium still has), of max(rms(vel), rms(free))/ell and stiff for order 1
    !! (vel = x', free = f, stiff = |df/dx|). 0 for a problem at rest without forces.
    pure real(wp) function motion_rate(order2, vel, acc, free, ell, stiff) result(rate)
        logical, intent(in) :: order2
        real(wp), intent(in) :: vel(:), acc(:), free(:), ell
        real(wp), intent(in) :: stiff
        rate = 0.0_wp
        if (ell > 0.0_wp .and. ell < huge(1.0_wp)) then
            if (order2) then
                rate = max(rms(vel)/ell, sqrt(max(rms(acc), rms(free))/ell))
            else
                rate = max(rms(vel), rms(free))/ell
            end if
        end if
        if (stiff > 0.0_wp .and. stiff < huge(1.0_wp)) rate = max(rate, merge(sqrt(stiff), stiff, order2))
        if (.not. (rate == rate .and. rate < huge(1.0_wp))) rate = 0.0_wp
    end function motion_rate

    !> A fixed direction of max-norm 1 with no symmetry a mechanism is likely to share
    !! (for the force stiffness of motion_rate): w_i = cos(1.3 i).
    pure function generic_direction(n) result(w)
        integer, intent(in) :: n
        real(wp) :: w(n)
        integer :: i
        w = [(cos(1.3_wp*i), i=1, n)]
        w = w/maxval(abs(w))
    end function generic_direction

    !> The Baumgarte weights for a rate of the motion (rate 0: 1, a problem with
    !! no motion of its own has no time scale but its unit).
    pure subroutine baumgarte_weights(rate, gamma, gamma0, gamma1)
        real(wp), intent(in) :: rate
        real(wp), intent(out) :: gamma, gamma0, gamma1
        gamma1 = weight_factor*merge(rate, 1.0_wp, rate > 0.0_wp)
        gamma = gamma1
        gamma0 = 0.5_wp*gamma1**2
    end subroutine baumgarte_weights

    !> The longest step of the explicit method that keeps the constraint modes of the
    !! regularized system stable: stable_radius / |s|, s the largest root of the
    !! weights' polynomial s^m + w(m) s^(m-1) + ... + w(1) (in the regular part the
    !! constraint error obeys it: g' + gamma g = 0, g'' + gamma1 g' + gamma0 g = 0), for
    !! the orders 1 and 2; huge for the others (Taylor weights) and for weights <= 0.
    pure real(wp) function constraint_mode_step(order, w) result(h)
        integer, intent(in) :: order
        real(wp), intent(in) :: w(:)   !! the model's weights (regdae_regularization)
        real(wp) :: root, disc
        h = huge(1.0_wp)
        root = 0.0_wp
        if (order == 1 .and. size(w) >= 1) then
            root = abs(w(1))
        else if (order == 2 .and. size(w) >= 2) then
            if (w(1) < 0.0_wp .or. w(2) < 0.0_wp) return
            disc = w(2)**2 - 4.0_wp*w(1)
            if (disc < 0.0_wp) then
                root = sqrt(w(1))   ! a complex pair
            else
                root = 0.5_wp*(w(2) + sqrt(disc))
            end if
        end if
        if (root > 0.0_wp) h = stable_radius/root
    end function constraint_mode_step

    !> The factor rtol^2 (within [eps_factor_min, eps_factor_max]) of the automatic eps.
    pure real(wp) function automatic_eps_factor(rtol) result(factor)
        real(wp), intent(in) :: rtol
        factor = max(eps_factor_min, min(eps_factor_max, rtol**2))
    end function automatic_eps_factor

    !> The automatic eps for rtol, the regular conditioning sigma_reg of GB and
    !! GB's largest diagonal entry s (for the rounding floor): eps_factor sigma_reg^2
    !! (trust region), sqrt(eps_factor) sigma_reg (direct, whose damping acts on GB,
    !! not on its square); at least the rounding floor (eps_round u s)^2, resp.
    !! eps_round u s. 0 if sigma_reg and s are 0 (no constraint acts).
    pure real(wp) function automatic_eps(rtol, sigma_reg, s, direct) result(eps)
        real(wp), intent(in) :: rtol, sigma_reg, s
        logical, intent(in) :: direct
        real(wp) :: sigma, floor
        sigma = max(sigma_reg, 0.0_wp)
        if (.not. (sigma == sigma)) sigma = 0.0_wp
        floor = eps_round*epsilon(1.0_wp)*max(s, sigma)
        if (direct) then
            eps = max(sqrt(automatic_eps_factor(rtol))*sigma, floor)
        else
            eps = max(automatic_eps_factor(rtol)*sigma**2, floor**2)
        end if
    end function automatic_eps

    logical function weight_rule_propose(self, t, rate) result(change)
        class(weight_rule), intent(inout) :: self
        real(wp), intent(in) :: t, rate
        change = .false.
        if (.not. self%on .or. .not. (rate > 0.0_wp)) return
        self%t_next = t + 0.5_wp/rate
        ! up only: the rate of a swing varies within a factor of about 2 between its
        ! turning points and its fastest point; weights that followed it down would
        ! change at every swing, and a motion that slows down keeps safe weights
        if (self%rate > 0.0_wp .and. rate <= weight_hysteresis*self%rate) return
        self%rate = rate
        self%changes = self%changes + 1
        change = .true.
    end function weight_rule_propose

    !> Per row of the position constraint's G at (t, x): |G_i| and the largest
    !! change of G_i per unit length along the directions `dirs(:, k)` (each of
    !! max-norm 1; central differences, so that an even change does not count;
    !! changes at the rounding level of G_i count as 0). `dg` holds that change
    !! of each row along its worst direction (for the prediction of GB at a
    !! singular start). stat /= 0: the user's constraint_jacobian failed.
    subroutine row_curvatures(model, t, x, dirs, gnorm, hnorm, dg, stat)
        type(regularized_dae), intent(inout) :: model
        real(wp), intent(in) :: t, x(:), dirs(:, :)
        real(wp), intent(out) :: gnorm(:), hnorm(:), dg(:, :)
        integer, intent(out) :: stat
        real(wp), allocatable :: gx0(:, :), gx1(:, :)
        real(wp) :: d, change, size_g
        integer :: i, k
        stat = 0
        gnorm = 0.0_wp
        hnorm = 0.0_wp
        dg = 0.0_wp
        allocate (gx0(model%m, size(x)), gx1(model%m, size(x)))
        d = central_difference_step(maxval(abs(x)))
        do k = 1, size(dirs, 2)
            call model%position_jacobian(t, x - d*dirs(:, k), gx0, stat)
            if (stat == 0) call model%position_jacobian(t, x + d*dirs(:, k), gx1, stat)
            if (stat /= 0) return
            do i = 1, model%m
                change = norm2(gx1(i, :) - gx0(i, :))/(2.0_wp*d)
                size_g = 0.5_wp*norm2(gx1(i, :) + gx0(i, :))
                if (k == 1) gnorm(i) = size_g
                if (.not. (change*d > 1.0e3_wp*epsilon(1.0_wp)*size_g)) change = 0.0_wp
                if (change > hnorm(i)) then
                    hnorm(i) = change
                    dg(i, :) = (gx1(i, :) - gx0(i, :))/(2.0_wp*d)
                end if
            end do
        end do
    end subroutine row_curvatures

    !> The scales of a dense model at (t, z), its slope dz, the model evaluated
    !! there: the constraint length `ell` (the largest of constraint_length here and
    !! ell_before), the rate of the motion, and, if some row of G vanishes here (a
    !! start on a singular configuration), `sigma_pred`: sigma_min(GB) with those rows
    !! moved by the scale of x along their curvature, both measured at the angles'
    !! representative periodic_representative(x) where G is the same there (-1 if no
    !! row vanishes, or predict is false). nx: the size of x; order2: z = (x, v, ...). With `stiffness`,
    !! the rate counts the frequency of the applied forces too (motion_rate).
    subroutine dense_motion_scales(model, t, z, dz, nx, order2, ell_before, predict, ell, rate, sigma_pred, stat, &
                                   stiffness)
        type(regularized_dae), intent(inout) :: model
        real(wp), intent(in) :: t, z(:), dz(:), ell_before
        integer, intent(in) :: nx
        logical, intent(in) :: order2, predict
        real(wp), intent(out) :: ell, rate, sigma_pred
        integer, intent(out) :: stat
        logical, intent(in), optional :: stiffness   !! the forces' frequency counts (at t0; along the run
                                                     !! the weights follow the motion alone)
        real(wp) :: x(nx), vel(nx), acc(nx), free(nx), ell_x, stiff
        real(wp), allocatable :: dirs(:, :), gnorm(:), hnorm(:), dg(:, :), gx(:, :)
        integer :: ndir, i
        logical :: degenerate
        stat = 0
        sigma_pred = -1.0_wp
        x = z(1:nx)
        free = model%f(size(model%f) - nx + 1:)
        if (order2) then
            vel = z(nx + 1:2*nx)
            acc = dz(nx + 1:2*nx)
        else
            vel = dz(1:nx)
            acc = 0.0_wp
        end if
        ell_x = rms(x)
        if (.not. (ell_x > 0.0_wp)) ell_x = 1.0_wp
        allocate (dirs(nx, 2))
        ndir = 0
        call add_direction(vel)
        if (maxval(abs(acc)) > 0.0_wp) then
            call add_direction(acc)
        else
            call add_direction(free)
        end if
        ell = huge(1.0_wp)
        if (model%m > 0 .and. ndir > 0) then
            allocate (gnorm(model%m), hnorm(model%m), dg(model%m, nx))
            call row_curvatures(model, t, x, dirs(:, 1:ndir), gnorm, hnorm, dg, stat)
            if (stat /= 0) return
            ell = constraint_length(gnorm, hnorm, ell_x)
            if (predict) then
                degenerate = .false.
                allocate (gx(model%m, nx))
                call model%position_jacobian(t, x, gx, stat)
                if (stat /= 0) return
                if (any(gnorm < degenerate_row*hnorm*ell_x)) then
                    ! a singular start: its geometry and the scale of x from the angles'
                    ! representative in (-pi, pi] where G is the same there
                    call measure_at_representative()
                    if (stat /= 0) return
                end if
                do i = 1, model%m
                    if (gnorm(i) < degenerate_row*hnorm(i)*ell_x) then
                        gx(i, :) = gx(i, :) + predict_shift*ell_x*dg(i, :)
                        degenerate = .true.
                    end if
                end do
                if (degenerate) sigma_pred = model%conditioning_with(t, z, gx, stat)
                if (stat /= 0) return
            end if
        else
            ell = ell_x
        end if
        ell = max(ell, ell_before)
        stiff = 0.0_wp
        if (present(stiffness)) then
            if (stiffness) stiff = force_stiffness()
        end if
        rate = motion_rate(order2, vel, acc, free, ell, stiff)
    contains
        ! gnorm, hnorm, dg, gx and ell_x at periodic_representative(x) if G is the same there
        subroutine measure_at_representative()
            real(wp) :: xr(nx)
            real(wp), allocatable :: gr(:, :)
            xr = periodic_representative(x)
            if (all(xr == x)) return
            allocate (gr(model%m, nx))
            call model%position_jacobian(t, xr, gr, stat)
            if (stat /= 0) return
            if (.not. same_geometry(reshape(gx, [size(gx)]), reshape(gr, [size(gr)]), x, maxval(hnorm))) return
            call row_curvatures(model, t, xr, dirs(:, 1:ndir), gnorm, hnorm, dg, stat)
            if (stat /= 0) return
            gx = gr
            ell_x = rms(xr)
            if (.not. (ell_x > 0.0_wp)) ell_x = 1.0_wp
        end subroutine measure_at_representative
        ! |d free/dx| along the generic direction (central differences of the model's f)
        real(wp) function force_stiffness() result(k)
            real(wp) :: fp(size(model%f)), fm(size(model%f)), zp(size(z)), w(nx), d
            integer :: s1, s2
            k = 0.0_wp
            w = generic_direction(nx)
            d = central_difference_step(maxval(abs(x)))
            zp = z
            zp(1:nx) = x + d*w
            call model%free_slope(t, zp, fp, s1)
            zp(1:nx) = x - d*w
            call model%free_slope(t, zp, fm, s2)
            if (s1 /= 0 .or. s2 /= 0) return
            k = rms(fp(size(fp) - nx + 1:) - fm(size(fm) - nx + 1:))/(2.0_wp*d)
            if (.not. (k*d > 1.0e3_wp*epsilon(1.0_wp)*max(rms(free), tiny(1.0_wp)))) k = 0.0_wp
        end function force_stiffness
        subroutine add_direction(w)
            real(wp), intent(in) :: w(:)
            real(wp) :: big
            big = maxval(abs(w))
            if (.not. (big > 0.0_wp .and. big < huge(1.0_wp))) return
            ndir = ndir + 1
            dirs(:, ndir) = w/big
        end subroutine add_direction
    end subroutine dense_motion_scales

    !> The representative of x in the period of an angle: each x_j beyond +-pi
    !! measured from its nearest multiple of 2 pi (x_j itself where |x_j| <= pi). It is
    !! the state a singular start's prediction measures when the constraint's G is the
    !! same there (same_geometry): an angle's 2 pi representatives are one configuration,
    !! and the scale of x (its rms) is then that of the representative, not of the winding.
    pure function periodic_representative(x) result(xr)
        real(wp), intent(in) :: x(:)
        real(wp) :: xr(size(x))
        real(wp), parameter :: two_pi = 6.283185307179586476925286766559_wp
        integer :: j
        xr = x
        do j = 1, size(x)
            if (abs(x(j)) > 0.5_wp*two_pi .and. abs(x(j)) < huge(1.0_wp)) &
                xr(j) = x(j) - two_pi*anint(x(j)/two_pi)
        end do
    end function periodic_representative

    !> True if the constraint Jacobian's values ga (at x) and gb (at another state
    !! that should be the same configuration, e.g. periodic_representative(x)) agree
    !! to the rounding of x: max |ga - gb| <= 1e3 u max(1, max|x|) max(max|ga|, slope),
    !! slope the largest change of G per unit length (the rows' hnorm of row_curvatures).
    pure logical function same_geometry(ga, gb, x, slope) result(same)
        real(wp), intent(in) :: ga(:), gb(:), x(:), slope
        same = .true.
        if (size(ga) == 0 .or. size(x) == 0) return
        same = maxval(abs(ga - gb)) <= 1.0e3_wp*epsilon(1.0_wp)*max(1.0_wp, maxval(abs(x)))*max(maxval(abs(ga)), slope)
    end function same_geometry

    !> A start at rest in an equilibrium of the constrained motion: every velocity zero, a
    !! load (f /= 0), and the constrained acceleration a at t0 no larger than 10 times the
    !! damped least squares' bias, eps/sigma^2 of the applied acceleration f (with a floor
    !! of 1e3 roundoffs), where that bias is small (eps < 1e-2 sigma^2, sigma = sigma_min(GB)):
    !! the exact motion stays at rest, the regularized one only by that bias.
    pure logical function rest_in_equilibrium(v, a, f, eps, sigma) result(rest)
        real(wp), intent(in) :: v(:)      !! the velocities at t0
        real(wp), intent(in) :: a(:)      !! the constrained (regularized) acceleration at t0
        real(wp), intent(in) :: f(:)      !! the acceleration of the applied forces at t0
        real(wp), intent(in) :: eps       !! the damping in force at a
        real(wp), intent(in) :: sigma     !! sigma_min(GB) at t0
        real(wp) :: bias
        rest = .false.
        if (size(v) == 0 .or. .not. (sigma > 0.0_wp)) return
        if (any(v /= 0.0_wp) .or. .not. (rms(f) > 0.0_wp)) return
        bias = max(eps, 0.0_wp)/sigma**2
        if (.not. (bias < 1.0e-2_wp)) return
        rest = (rms(a) <= 10.0_wp*max(bias, 1.0e3_wp*epsilon(1.0_wp))*rms(f))
    end function rest_in_equilibrium

    !> Root mean square of a vector (0 if empty).
    pure real(wp) function rms(a)
        real(wp), intent(in) :: a(:)
        rms = 0.0_wp
        if (size(a) > 0) rms = norm2(a)/sqrt(real(size(a), wp))
    end function rms

end module regdae_auto_rules
