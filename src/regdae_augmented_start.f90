!> The augmented system's consistent start (`regdae_augmented_system`): at fixed (q, v)
!! the residual is linear in the rest (v', u, y, s), so IDA's consistent initial values
!! follow from solves with the saddle-point matrix K = [M G^T; G -shift I] (band storage,
!! the conditioning's) instead of IDACalcIC's Newton passes. With the residual at
!! (q, v) and the rest 0, f (the forces) and h = gamma1 (G v + g_t) + gamma0 g + c (the
!! defect without G v') are known, and K [x; z] = [f; -h] gives
!! $$ M x + G^T z = f, \quad G x - \mathrm{shift}\, z = -h, $$
!! so that with shift = 0 (Baumgarte: GB y = r) and shift = eps (direct: (GB + eps I) y = r)
!! v' = x and y = z solve every row. The trust region's ((GB)^2 + eps I) y = GB r
!! is the fixed point y = (GB)^{-1} (r - eps (GB)^{-1} y), which contracts by
!! eps / sigma_min(GB)^2: with p = (GB)^{-1} y_k (K [w; p] = [0; -y_k]),
!! K [x; y_{k+1}] = [f; eps p - h] gives v' = x, s = eps p = G x + h, and u = B s =
!! -w for K [w; z] = [0; -eps y_k] (G u = GB s = eps y_k). Where the fixed point does
!! not settle (a start near a singular configuration, eps / sigma_min(GB)^2 not small),
!! where K's factorization fails, or where the residual at the result is not at
!! rounding level, the start is left to IDACalcIC.
submodule (regdae_augmented_system) regdae_augmented_start
    implicit none

contains

    module procedure augmented_consistent_start
        ! at most this many fixed-point steps; settled: their relative change in y at the
        ! end; accept: the largest residual of the v and defect rows against their terms
        integer, parameter :: max_iterations = 12
        real(wp), parameter :: settled = 1.0e-13_wp, accept = 1.0e-9_wp
        real(wp) :: f(self%n), h(self%m), x(self%n), w(self%n), y(self%m), ynew(self%m), p(self%m), s(self%m)
        real(wp) :: res(self%neq), scale_v, scale_w
        real(wp) :: zero(self%n)
        integer :: stat, info, it, n, m, k
        logical :: recoverable, converged

        done = .false.
        n = self%n
        m = self%m
        if (m == 0 .or. .not. allocated(self%kband)) return
        ! f and h from the residual at (q, v) with v', u, y, s = 0 (natural order in rn)
        call self%residual(t, u, up, res, stat, recoverable)
        if (stat /= regdae_success) return
        f = -self%rn(self%iv + 1:self%iv + n)
        if (self%method == method_trust_region) then
            h = -self%rn(self%is + 1:self%is + m)
        else
            h = -self%rn(self%iy + 1:self%iy + m)
        end if
        call self%factor_saddle(merge(self%eps, 0.0_wp, self%method == method_direct), info)
        if (info /= 0) return
        call self%solve_saddle(f, -h, x, y)
        s = 0.0_wp
        w = 0.0_wp
        zero = 0.0_wp
        if (self%method == method_trust_region) then
            converged = .false.
            do it = 1, max_iterations
                call self%solve_saddle(zero, -y, w, p)              ! p = (GB)^{-1} y
                call self%solve_saddle(f, self%eps*p - h, x, ynew)
                converged = (maxval(abs(ynew - y)) <= settled*maxval(abs(ynew)))
                if (converged) exit
                y = ynew
            end do
            if (.not. converged) return
            s = self%eps*p
            call self%solve_saddle(zero, -self%eps*y, w, p)       ! w = -B s
            y = ynew
        end if
        if (.not. (all(abs(x) <= huge(1.0_wp)) .and. all(abs(y) <= huge(1.0_wp)) .and. all(abs(w) <= huge(1.0_wp)))) &
            return
        self%un = 0.0_wp
        self%upn = 0.0_wp
        do k = 1, self%neq
            self%un(self%perm(k)) = u(k)
            self%upn(self%perm(k)) = up(k)
        end do
        self%upn(self%iv + 1:self%iv + n) = x
        self%un(self%iy + 1:self%iy + m) = y
        if (self%method == method_trust_region) then
            self%un(self%iu + 1:self%iu + n) = -w
            self%un(self%is + 1:self%is + m) = s
        end if
        ! the residual at the result: every row at rounding level against its terms
        call self%residual(t, self%un(self%perm), self%upn(self%perm), res, stat, recoverable)
        if (stat /= regdae_success) return
        scale_v = max(maxval(abs(f)), tiny(1.0_wp))
        scale_w = max(maxval(abs(h)), maxval(abs(s)), tiny(1.0_wp))
        if (.not. (maxval(abs(self%rn(self%iv + 1:self%iv + n))) <= accept*scale_v)) return
        if (self%method == method_trust_region) then
            if (.not. (maxval(abs(self%rn(self%is + 1:self%is + m))) <= accept*scale_w)) return
        else
            if (.not. (maxval(abs(self%rn(self%iy + 1:self%iy + m))) <= accept*scale_w)) return
        end if
        u = self%un(self%perm)
        up = self%upn(self%perm)
        done = .true.
    end procedure augmented_consistent_start

end submodule regdae_augmented_start
