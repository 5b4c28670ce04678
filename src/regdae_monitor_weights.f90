!> The Baumgarte weights of `regdae_monitor` following the motion (regdae_auto_rules): when a new
!! look at the rate is due, the look at a sample, and the rule's change of the weights.
submodule (regdae_monitor) regdae_monitor_weights
    implicit none

contains

    module procedure monitor_follow_weights
        self%weights%on = .true.
        self%weights%rate = rate
        self%weights%ell = ell
        self%weights%t_next = t0
        if (rate > 0.0_wp) self%weights%t_next = t0 + 0.5_wp/rate
        self%weights%changes = 0
        self%weight_nx = nx
        self%weight_order2 = order2
        self%weights_new = .false.
    end procedure monitor_follow_weights

    module procedure monitor_weights_due
        due = self%weights%on .and. t >= self%weights%t_next .and. .not. self%in_singular .and. .not. self%in_layer
    end procedure monitor_weights_due

    module procedure weights_sample
        real(wp) :: ell, rate, sigma_pred
        integer :: stat
        if (self%weight_nx > 0 .and. self%weights_due(t)) then
            call dense_motion_scales(model, t, z, dz, self%weight_nx, self%weight_order2, self%weights%ell, &
                                     .false., ell, rate, sigma_pred, stat)
            if (stat == 0) then
                self%weights%ell = ell
                if (self%new_rate(t, rate)) then
                    if (model%order == 1) then
                        model%w = [baumgarte_gamma(self%weights%rate)]
                    else if (model%order == 2) then
                        model%w = baumgarte_pair(self%weights%rate)
                    end if
                    self%model_changed = .true.
                end if
            end if
        end if
    end procedure weights_sample

    module procedure monitor_new_rate
        real(wp) :: before
        before = self%weights%rate
        change = self%weights%propose(t, rate)
        if (.not. change) return
        self%weights_new = .true.
        self%weights_message = 't = '//format_real(t)//': Baumgarte weights follow the motion, rate '// &
                               format_real(before)//' -> '//format_real(self%weights%rate)//' (gamma1 = '// &
                               format_real(baumgarte_gamma(self%weights%rate))//')'
    end procedure monitor_new_rate

    ! gamma (index 2) and (gamma0, gamma1) (index 3) of the automatic rule for a rate.
    pure real(wp) function baumgarte_gamma(rate) result(gamma)
        real(wp), intent(in) :: rate
        real(wp) :: g0, g1
        call baumgarte_weights(rate, gamma, g0, g1)
    end function baumgarte_gamma

    pure function baumgarte_pair(rate) result(w)
        real(wp), intent(in) :: rate
        real(wp) :: w(2), gamma
        call baumgarte_weights(rate, gamma, w(1), w(2))
    end function baumgarte_pair

end submodule regdae_monitor_weights
