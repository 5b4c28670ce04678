!> The problem's own scales along its solution, for the automatic parameters
!! (doc/methods.md, "Automatic parameters"): the largest diagonal entry of GB,
!! the largest row norm of G and the largest |x| seen at the samples so far.
!!
!! - eps = eps_factor s^2, s the largest (GB)_ii seen, eps_factor = rtol^2 within
!!   [1e-14, 1e-6]. A run that starts near a singular configuration sees a small
!!   s at t0 (the slider crank from th1 = 1e-3: s = 5e-6, eps = 2.5e-21, layers
!!   too thin to be passed on the branch at rtol 1e-5); eps is raised when s has
!!   grown 2x (eps 4x), at a sample outside any regularization layer
!!   (sigma_min(GB)^2 >= 100 eps_new), where the regularization does not act.
!! - drift bound = drift_factor g (rtol x + atol), g the largest |G_i| and x the
!!   largest |x| seen: the constraint violation that drift_factor times the
!!   tolerances on x can produce, measured away from a singular start too; times
!!   eps / eps_auto when a user's eps exceeds the automatic one (eps_auto =
!!   eps_factor(rtol) s^2), whose regularization error grows like eps.
module regdae_scales
    use regdae_kinds, only: wp
    implicit none
    private

    !> Running maxima of the scales and the automatic eps and drift bound they give.
    type, public :: running_scales
        real(wp) :: gb = 0.0_wp            !! largest max_i (GB)_ii seen
        real(wp) :: g = 0.0_wp             !! largest max_i |G_i| seen
        real(wp) :: x = 0.0_wp             !! largest max |x| seen
        real(wp) :: eps_factor = 0.0_wp    !! > 0: eps is automatic, eps_factor s^2
        real(wp) :: eps = 0.0_wp           !! the automatic eps in force
        integer :: eps_raises = 0          !! times eps was raised after t0
        real(wp) :: eps_raised_at = 0.0_wp !! the time of the last raise
        real(wp) :: drift_factor = 0.0_wp  !! > 0: the drift bound is automatic
        real(wp) :: rtol = 0.0_wp, atol = 0.0_wp
    contains
        !> Take the scales of one sample (the maxima only grow).
        procedure :: observe => scales_observe
        !> True if the automatic eps should be raised now (sigma: sigma_min(GB) at the
        !! sample); then `eps` holds the new value.
        procedure :: raise_eps => scales_raise_eps
        !> The automatic drift bound from the scales seen so far and the eps in force.
        procedure :: drift_bound => scales_drift_bound
    end type running_scales

    !> eps_factor: rtol^2 within these bounds (doc/methods.md).
    real(wp), parameter, public :: eps_factor_min = 1.0e-14_wp, eps_factor_max = 1.0e-6_wp

    public :: automatic_eps_factor

contains

    !> The factor of s^2 in the automatic eps for a relative tolerance rtol.
    pure real(wp) function automatic_eps_factor(rtol) result(factor)
        real(wp), intent(in) :: rtol
        factor = max(eps_factor_min, min(eps_factor_max, rtol**2))
    end function automatic_eps_factor

    subroutine scales_observe(self, gb, g, x)
        class(running_scales), intent(inout) :: self
        real(wp), intent(in) :: gb, g, x   !! max_i (GB)_ii, max_i |G_i|, max |x| at the sample
        if (gb == gb) self%gb = max(self%gb, gb)
        if (g == g) self%g = max(self%g, g)
        if (x == x) self%x = max(self%x, x)
    end subroutine scales_observe

    logical function scales_raise_eps(self, t, sigma) result(raise)
        class(running_scales), intent(inout) :: self
        real(wp), intent(in) :: t, sigma
        real(wp) :: wanted
        raise = .false.
        if (.not. (self%eps_factor > 0.0_wp .and. self%gb > 0.0_wp)) return
        wanted = self%eps_factor*self%gb**2
        if (wanted < 4.0_wp*self%eps) return
        if (.not. (sigma**2 >= 100.0_wp*wanted)) return   ! not inside a layer of the new eps
        self%eps = wanted
        self%eps_raises = self%eps_raises + 1
        self%eps_raised_at = t
        raise = .true.
    end function scales_raise_eps

    pure real(wp) function scales_drift_bound(self, eps) result(bound)
        class(running_scales), intent(in) :: self
        real(wp), intent(in) :: eps   !! the eps in force
        real(wp) :: eps_auto
        bound = self%drift_factor*self%g*(self%rtol*self%x + self%atol)
        ! a user's eps above the automatic one: the regularization's own constraint error
        ! grows like eps, beyond what the tolerances allow
        eps_auto = automatic_eps_factor(self%rtol)*self%gb**2
        if (eps_auto > 0.0_wp) bound = bound*max(1.0_wp, eps/eps_auto)
    end function scales_drift_bound

end module regdae_scales
