!> The step rule of regdae's central difference quotients (g_t, the curvature
!! term, the index-2 adapter's Jacobian): h = u^(1/3) max(1, scale), u the unit
!! roundoff, which balances the O(h^2) truncation error against the O(u/h)
!! rounding error of a central difference.
module regdae_differences
    use regdae_kinds, only: wp
    implicit none
    private
    public :: central_difference_step

contains

    !> u^(1/3) max(1, scale).
    pure real(wp) function central_difference_step(scale) result(h)
        real(wp), intent(in) :: scale   !! magnitude of the variable being perturbed
        h = epsilon(1.0_wp)**(1.0_wp/3.0_wp)*max(abs(scale), 1.0_wp)
    end function central_difference_step

end module regdae_differences
