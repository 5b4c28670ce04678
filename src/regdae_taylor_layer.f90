!> The regularization layer of the Taylor weights (problems of order m >= 3,
!! doc/methods.md "Order m >= 3"). Where eps damps the multiplier, the constraint
!! error obeys s^m + d (w_{m-1} s^(m-1) + ... + w_0) = 0 with the damping
!! d = sigma^2/(sigma^2 + eps) (trust region; sigma/(sigma + eps) direct), sigma =
!! sigma_min(GB). At order 2 that polynomial is stable for every d > 0; with the
!! Taylor weights of order 3 it is not for d < 1/3 (Routh-Hurwitz: d w_1 w_2 > w_0),
!! of order 4 for d < 0.74, and its roots grow like 0.21/h (order 3) and 0.63/h
!! (order 4) there, h = taylor_h. A layer that lasts many h amplifies the errors of
!! the state by e^(that many): on the order-3 problem with taylor_h = 1e-5 and the
!! automatic eps = 1e-10 (`order3 taylor_h=1e-5`), x(0) was 10.8 off with status ok.
!! `taylor_layer_watch` adds up that growth over the accepted steps and says when it
!! passes layer_efolds_max; the integrators then raise the monitor's resolution
!! warning (regdae_warn_unresolved) with its message.
module regdae_taylor_layer
    use regdae_kinds, only: wp
    use regdae_options, only: method_trust_region, method_direct
    use regdae_format, only: format_real, format_int
    implicit none
    private

    !> Growth of the errors in one layer (e-folds) beyond which the run warns:
    !! e^18 = 6.6e7 ~ 1/sqrt(u). Measured on `order3` (rtol 1e-5, eps 1e-10): taylor_h =
    !! 1e-4, 11 e-folds by this bound, error 4.2e-9; taylor_h = 1e-5, 110, error 10.8;
    !! taylor_h = 1e-5 with eps = 1e-13, 20, error 4.2e-11.
    real(wp), parameter, public :: layer_efolds_max = 18.0_wp

    !> The growth in the layer along a run: the current stretch of steps where the
    !! damped polynomial is unstable.
    type, public :: taylor_layer_watch
        real(wp) :: efolds = 0.0_wp       !! the bound on the growth over the current stretch
        real(wp) :: t_enter = 0.0_wp      !! where the stretch began
        logical :: inside = .false.       !! the last step ended in the stretch
        logical :: reported = .false.     !! this stretch has warned already
        character(len=:), allocatable :: message   !! the warning (set when `step` returns true)
    contains
        !> One accepted step [t_old, t] ending at sigma_min(GB) = sigma: true when the
        !! growth of this stretch has just passed layer_efolds_max (then `message`).
        procedure :: step => watch_step
    end type taylor_layer_watch

contains

    logical function watch_step(self, order, w, method, eps, sigma, t_old, t) result(warn)
        class(taylor_layer_watch), intent(inout) :: self
        integer, intent(in) :: order      !! the problem's order m
        real(wp), intent(in) :: w(:)      !! the Taylor weights (w(1) = m!/h^m)
        integer, intent(in) :: method     !! the regularization
        real(wp), intent(in) :: eps, sigma, t_old, t
        real(wp) :: d, growth, d_crit, h
        warn = .false.
        if (order /= 3 .and. order /= 4) return   ! order 2: stable; order >= 5: unstable without any layer
        if (size(w) < 1 .or. .not. (w(1) > 0.0_wp) .or. .not. (eps > 0.0_wp) .or. .not. (sigma >= 0.0_wp)) return
        select case (method)
        case (method_trust_region)
            d = sigma**2/(sigma**2 + eps)
        case (method_direct)
            d = sigma/(sigma + eps)
        case default
            return   ! no damping
        end select
        ! the largest real part of the roots over d, in units of 1/h, and the d below which it is > 0
        if (order == 3) then
            growth = 0.2071_wp
            d_crit = 1.0_wp/3.0_wp
            h = (6.0_wp/w(1))**(1.0_wp/3.0_wp)
        else
            growth = 0.6343_wp
            d_crit = 0.7413_wp
            h = (24.0_wp/w(1))**0.25_wp
        end if
        if (d >= d_crit) then
            self%inside = .false.
            self%reported = .false.
            self%efolds = 0.0_wp
            return
        end if
        if (.not. self%inside) then
            self%inside = .true.
            self%t_enter = t_old
            self%efolds = 0.0_wp
        end if
        self%efolds = self%efolds + growth*(t - t_old)/h
        if (self%efolds > layer_efolds_max .and. .not. self%reported) then
            self%reported = .true.
            warn = .true.
            self%message = 'the layer of the Taylor weights from t = '//format_real(self%t_enter)//' (order '// &
                           format_int(order)//', taylor_h = '//format_real(h)//'): where eps damps the multiplier '// &
                           'the constraint dynamics are unstable, and by t = '//format_real(t)//' they may have '// &
                           'grown the errors by e^'//format_real(layer_efolds_max, 3)//' or more; x in the layer '// &
                           'may be far off (the pass check does not cover order >= 3): a smaller eps (the layer '// &
                           'lasts like eps^(1/4) at a rank-one singularity) or a larger taylor_h'
        end if
    end function watch_step

end module regdae_taylor_layer
