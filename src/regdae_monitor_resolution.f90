!> The resolution check of `regdae_monitor` (its header describes it): the amplification R of the
!! integration errors made on the approach to a singular configuration.
submodule (regdae_monitor) regdae_monitor_resolution
    implicit none

contains

    module procedure monitor_set_resolution
        self%resolution_tol = max(0.0_wp, tol)
    end procedure monitor_set_resolution

    ! The resolution check at a sample (the model's last evaluation is at (t, z)):
    ! the memory of sigma_G, and R on the approach to a layer (module doc).
    module procedure resolution_sample
        real(wp) :: sigma, sigma_g, rate, ratio
        integer :: i
        if (model%m == 0 .or. model%order > 2 .or. model%method == method_baumgarte) return
        if (present(row_norm_min)) then
            sigma_g = row_norm_min
        else
            sigma_g = huge(1.0_wp)
            do i = 1, model%m
                sigma_g = min(sigma_g, norm2(model%gx(i, :)))
            end do
        end if
        if (.not. (sigma_g == sigma_g)) return
        if (model%order == 1) then
            rate = model%w(1)
        else   ! the slower root of s^2 + gamma1 s + gamma0: its real part
            rate = forgetting_rate(model%w(1), model%w(2))
        end if
        if (self%memory < 0.0_wp .or. .not. (t > self%t_memory)) then
            self%memory = max(self%memory, sigma_g)
        else
            self%memory = max(sigma_g, self%memory*exp(-max(rate, 0.0_wp)*(t - self%t_memory)))
        end if
        self%t_memory = t
        if (.not. self%in_singular) then
            self%layer_reached = .false.
            self%pass_flagged = .false.
            return
        end if
        sigma = self%sigma_last
        if (model%method == method_direct) then
            if (sigma < 100.0_wp*model%eps) self%layer_reached = .true.
        else
            if (sigma**2 < 100.0_wp*model%eps) self%layer_reached = .true.
        end if
        if (self%layer_reached .or. .not. (sigma_g > 0.0_wp)) return
        ratio = self%memory/sigma_g
        self%resolution_ratio = max(self%resolution_ratio, ratio)
        if (ratio > self%resolution_tol .and. .not. self%pass_flagged) then
            self%pass_flagged = .true.
            self%unresolved = self%unresolved + 1
            self%unresolved_new = .true.
            self%unresolved_message = 'approaching the singular configuration at t = '//format_real(t)// &
                ' (sigma_min(GB) = '//format_real(sigma)//'), the integration errors made on the approach are '// &
                'amplified in x by about '//format_real(ratio)//' (the constraint''s conditioning fell by that '// &
                'factor faster than the stabilization forgets; > resolution_tol = '// &
                format_real(self%resolution_tol)//'): x near it is not converged in the tolerance; tighten rtol '// &
                'and atol (or raise eps); resolution_tol=0 turns this warning off'
        end if
    end procedure resolution_sample

end submodule regdae_monitor_resolution
