!> The problem's own scales along its solution, for the automatic parameters
!! (doc/methods.md, "Automatic parameters"; the rules are regdae_auto_rules'):
!! the largest diagonal entry of GB, the largest row norm of G, the largest |x|
!! and the regular conditioning of GB seen at the samples so far.
!!
!! - eps = automatic_eps(rtol, sigma_reg, s): sigma_reg the largest sigma_min(GB)
!!   seen (the conditioning of the regular part of the motion; a start on a
!!   singular configuration has its predicted value until the motion has left
!!   it: until a sample reaches release_fraction of the prediction). eps follows
!!   its target both ways when the target has moved by eps_hysteresis, at a
!!   sample where neither eps acts on the solution beyond the tolerance
!!   (sigma_min(GB)^2 >= max(eps_old, eps_new)/rtol; direct: sigma_min(GB) >=
!!   max(eps_old, eps_new)/rtol).
!! - drift bound = drift_factor g (rtol x + atol), g the largest |G_i| and x the
!!   largest |x| seen: the constraint violation that drift_factor times the
!!   tolerances on x can produce, measured away from a singular start too; times
!!   eps / eps_auto when a user's eps exceeds the automatic one, whose
!!   regularization error grows like eps.
module regdae_scales
    use regdae_kinds, only: wp
    use regdae_auto_rules, only: automatic_eps, automatic_eps_factor, eps_hysteresis
    implicit none
    private

    !> Running maxima of the scales and the automatic eps and drift bound they give.
    type, public :: running_scales
        real(wp) :: gb = 0.0_wp            !! largest max_i (GB)_ii seen
        real(wp) :: g = 0.0_wp             !! largest max_i |G_i| seen
        real(wp) :: x = 0.0_wp             !! largest max |x| seen
        real(wp) :: sigma = 0.0_wp         !! largest sigma_min(GB) seen
        real(wp) :: sigma_pred = -1.0_wp   !! predicted sigma_reg at a singular start (< 0: none, or released)
        logical :: direct = .false.        !! method=direct (eps acts on GB, not on its square)
        real(wp) :: eps_factor = 0.0_wp    !! > 0: eps is automatic (the factor of rtol)
        real(wp) :: eps = 0.0_wp           !! the automatic eps in force
        integer :: eps_changes = 0         !! times eps was changed after t0
        real(wp) :: eps_changed_at = 0.0_wp !! the time of the last change
        real(wp) :: drift_factor = 0.0_wp  !! > 0: the drift bound is automatic
        real(wp) :: rtol = 0.0_wp, atol = 0.0_wp
    contains
        !> Take the scales of one sample (the maxima only grow).
        procedure :: observe => scales_observe
        !> True if the automatic eps should change now (sigma: sigma_min(GB) at the
        !! sample); then `eps` holds the new value.
        procedure :: retarget_eps => scales_retarget_eps
        !> The automatic eps the scales seen so far ask for.
        procedure :: eps_target => scales_eps_target
        !> The automatic drift bound from the scales seen so far and the eps in force.
        procedure :: drift_bound => scales_drift_bound
    end type running_scales

    !> The drift bound's tolerances are at least this (its floor at very tight tolerances).
    real(wp), parameter, public :: drift_rtol_min = 1.0e-12_wp
    !> A predicted sigma_reg gives way to the measured one when a sample reaches this fraction of it.
    real(wp), parameter, public :: release_fraction = 0.05_wp

    public :: automatic_eps_factor

contains

    subroutine scales_observe(self, gb, g, x, sigma)
        class(running_scales), intent(inout) :: self
        real(wp), intent(in) :: gb, g, x   !! max_i (GB)_ii, max_i |G_i|, max |x| at the sample
        real(wp), intent(in) :: sigma      !! sigma_min(GB) at the sample
        if (gb == gb) self%gb = max(self%gb, gb)
        if (g == g) self%g = max(self%g, g)
        if (x == x) self%x = max(self%x, x)
        if (sigma == sigma .and. sigma < huge(1.0_wp)) self%sigma = max(self%sigma, sigma)
        if (self%sigma_pred > 0.0_wp) then
            if (self%sigma >= release_fraction*self%sigma_pred) self%sigma_pred = -1.0_wp
        end if
    end subroutine scales_observe

    pure real(wp) function scales_eps_target(self) result(eps)
        class(running_scales), intent(in) :: self
        eps = automatic_eps(self%rtol, max(self%sigma, self%sigma_pred), self%gb, self%direct)
    end function scales_eps_target

    logical function scales_retarget_eps(self, t, sigma) result(change)
        class(running_scales), intent(inout) :: self
        real(wp), intent(in) :: t, sigma
        real(wp) :: wanted, acting
        change = .false.
        if (.not. (self%eps_factor > 0.0_wp)) return
        wanted = self%eps_target()
        if (.not. (wanted > 0.0_wp)) return
        if (wanted < eps_hysteresis*self%eps .and. wanted*eps_hysteresis > self%eps) return
        ! neither eps acts on the solution here beyond the tolerance
        acting = max(self%eps, wanted)/max(self%rtol, tiny(1.0_wp))
        if (self%direct) then
            if (.not. (sigma >= acting)) return
        else
            if (.not. (sigma**2 >= acting)) return
        end if
        self%eps = wanted
        self%eps_changes = self%eps_changes + 1
        self%eps_changed_at = t
        change = .true.
    end function scales_retarget_eps

    pure real(wp) function scales_drift_bound(self, eps) result(bound)
        class(running_scales), intent(in) :: self
        real(wp), intent(in) :: eps   !! the eps in force
        real(wp) :: eps_auto
        ! (the tolerances at least drift_rtol_min: the automatic eps's regularization leaves a
        ! constraint error of about 1e-10 whatever rtol; rtol 1e-13 stopped correct runs)
        bound = self%drift_factor*self%g*(max(self%rtol, drift_rtol_min)*self%x + max(self%atol, drift_rtol_min))
        ! a user's eps above the automatic one: the regularization's own constraint error
        ! grows like eps, beyond what the tolerances allow
        eps_auto = self%eps_target()
        if (eps_auto > 0.0_wp) bound = bound*max(1.0_wp, eps/eps_auto)
    end function scales_drift_bound

end module regdae_scales
