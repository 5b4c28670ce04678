!> The augmented system's conditioning (`regdae_augmented_system`): sigma_min(GB) for
!! the monitor and the diagonal scales of M and G (regdae_scales). GB = G M^{-1} G^T is symmetric positive
!! semidefinite, so its smallest singular value is its smallest eigenvalue,
!! estimated by inverse iteration with solves of the saddle-point matrix
!! K = [M G^T; G 0] (K [w; z] = [0; x] gives z = -(GB)^{-1} x), K in band
!! storage after reverse Cuthill-McKee (LAPACK dgbtrf): O(n + m) for a chain. A
!! singular K (GB singular) gives 0.
submodule (regdae_augmented_system) regdae_augmented_conditioning
    implicit none

contains

    module procedure augmented_sigma_min
        ! Inverse iteration on the symmetric positive definite G M^{-1} G^T (= GB), from a
        ! fixed generic vector plus the last call's singular vector (the last vector alone
        ! misses a new smallest mode: 400x too large at a 512-link chain's fold): stops when
        ! the Rayleigh quotient moves by less than `settled` (relative) after at least
        ! `min_iterations` solves, at most `iterations`. An upper estimate; against 200
        ! iterations on the slider chain (tf = 3, 30 outputs) within 1% at N = 64, 30% at
        ! N = 8, a factor 2.4 at N = 1024 where the smallest eigenvalues cluster. The monitor
        ! compares it with thresholds, so that is enough.
        !
        ! Redundant constraints (GB of constant rank r < m): K is singular, or its LU
        ! has a pivot at rounding level, and the quotient is rounding noise (0 or u |GB|
        ! at random), which says nothing about the configuration (the pass check chattered
        ! on it). As the dense models' smallest_singular_value (regdae_damped_lsq), the
        ! estimate is then taken on GB's structural rank: a quotient at most
        ! (n + m) u max_i (GB)_ii is numerically zero; such modes are deflated (the
        ! iteration goes on orthogonal to them, on K with GB shifted by sqrt(u) times that
        ! scale, so that the null modes do not make it singular, the shift subtracted
        ! again), as many as every estimate so far has found (`deficiency`, the smallest
        ! count over the calls), and the next quotient is the estimate. At most
        ! `max_deflation` modes: a large regular mechanism whose softest modes all lie
        ! below that tolerance (the straight chain of 10^6 links: sigma_min(GB) ~ 1e-24)
        ! would otherwise cost an m x (m - 1) array and thousands of iterations per sample
        ! (issue 20: memory O(nonzeros)); more redundant constraints than that are not
        ! recognized as such.
        !
        ! With `far`, the last plain estimate sigma_e stands (no factorization, no solve) where a
        ! rigorous bound shows that sigma_min(GB) cannot have moved by more than `settled` (the
        ! iteration's own resolution) since it was made, nor below `far`: with M diagonal,
        ! GB = A A^T for A = G M^{-1/2}, whose m-th singular value moves by at most
        ! ||A - A_e||_2 <= ||A - A_e||_F =: d (Weyl), A_e the A of the estimate; so
        ! sqrt(sigma_min(GB)) is within d of its value there, and d <= (sqrt(1 + settled) - 1)
        ! sqrt(sigma_e) with (sqrt(sigma_e) - d)^2 >= far is the test.
        integer, parameter :: iterations = 8, min_iterations = 3, max_deflation = 8
        real(wp), parameter :: settled = 1.0e-3_wp
        real(wp) :: q(self%n), x(self%m), z(self%m), znorm, previous, scale, null_tol, shift, diag_gb, gs
        real(wp) :: scaled_g(self%st%constraint%nnz()), d
        real(wp), allocatable :: nullv(:, :)
        integer :: i, k, nk, info, it, found, limit
        logical :: ok
        stat = 0
        sigma = huge(1.0_wp)
        if (present(gb)) gb = 0.0_wp
        if (present(g)) g = 0.0_wp
        if (self%m == 0) return
        nk = self%n + self%m
        call self%unpack(u, u, q=q)
        call self%problem%mass_values(t, q, self%st%mass, self%mvals, stat)
        if (stat /= 0) return
        call self%problem%constraint_jacobian_values(t, q, self%st%constraint, self%gvals, stat)
        if (stat /= 0) return
        call self%diagonal_scales(diag_gb, gs)
        if (present(gb)) gb = diag_gb
        if (present(g)) g = gs
        if (present(far) .and. self%deficiency == 0 .and. self%mass_diagonal .and. self%sigma_estimate >= 0.0_wp) then
            call scale_constraint_jacobian(scaled_g)
            d = norm2(scaled_g - self%sigma_scaled_g)
            if (d <= (sqrt(1.0_wp + settled) - 1.0_wp)*sqrt(self%sigma_estimate) .and. &
                (sqrt(self%sigma_estimate) - d)**2 >= far) then
                sigma = self%sigma_estimate
                return
            end if
        end if
        self%sigma_estimate = -1.0_wp
        scale = diag_gb
        null_tol = real(nk, wp)*epsilon(1.0_wp)*scale
        shift = 0.0_wp
        if (self%deficiency <= 0) then
            ! full rank seen (or the first call): the plain estimate
            call self%factor_saddle(0.0_wp, info)
            ok = (info == 0)
            if (ok) call iterate(0, sigma, ok)
            if (ok .and. (sigma > null_tol .or. self%deficiency == 0)) then
                self%deficiency = 0
                self%sigma_vector = x
                sigma = max(0.0_wp, sigma)
                if (self%mass_diagonal) then   ! the estimate a later call may reuse
                    call scale_constraint_jacobian(scaled_g)
                    self%sigma_scaled_g = scaled_g
                    self%sigma_estimate = sigma
                end if
                return
            end if
            if (self%deficiency == 0) then   ! K singular at a sample of a full-rank GB: singular here
                sigma = 0.0_wp
                return
            end if
        end if
        ! numerically rank-deficient: deflate up to the structural deficiency (the first call: m - 1)
        if (.not. (scale > 0.0_wp)) then
            sigma = 0.0_wp
            return
        end if
        shift = sqrt(epsilon(1.0_wp))*scale
        call self%factor_saddle(shift, info)
        if (info /= 0) then
            sigma = 0.0_wp
            return
        end if
        limit = min(self%m - 1, max_deflation)
        if (self%deficiency > 0) limit = min(self%deficiency, max_deflation)
        allocate (nullv(self%m, limit))
        found = 0
        do
            call iterate(found, sigma, ok)
            if (.not. ok) then
                sigma = 0.0_wp
                return
            end if
            sigma = sigma - shift
            if (sigma > null_tol .or. found == limit) exit
            found = found + 1
            nullv(:, found) = x
        end do
        if (sigma <= null_tol) found = found + 1   ! this mode too: numerically null here
        if (self%deficiency < 0) then
            self%deficiency = found
        else
            self%deficiency = min(self%deficiency, found)
        end if
        self%sigma_vector = x
        sigma = max(0.0_wp, sigma)
    contains
        ! A = G M^{-1/2} in G's pattern order (M diagonal; a diagonal entry <= 0 gives NaN: no reuse)
        subroutine scale_constraint_jacobian(a)
            real(wp), intent(out) :: a(:)
            associate (gp => self%st%constraint)
                do i = 1, self%m
                    do k = gp%row_start(i), gp%row_start(i + 1) - 1
                        a(k) = self%gvals(k)/sqrt(self%mvals(gp%cols(k)))
                    end do
                end do
            end associate
        end subroutine scale_constraint_jacobian

        ! Inverse iteration on (GB + shift I) orthogonal to nullv(:, 1:nn): the quotient in est
        subroutine iterate(nn, est, ok)
            integer, intent(in) :: nn
            real(wp), intent(out) :: est
            logical, intent(out) :: ok
            integer :: j
            ok = .true.
            est = 0.0_wp
            ! the start: a fixed vector with generic components (a constant one is orthogonal to
            ! every antisymmetric mode), plus the last call's singular vector
            x = [(modulo(0.6180339887498949_wp*i, 1.0_wp) - 0.5_wp, i=1, self%m)]
            x = x/norm2(x)
            if (allocated(self%sigma_vector)) x = x + self%sigma_vector
            do j = 1, nn
                x = x - dot_product(nullv(:, j), x)*nullv(:, j)
            end do
            znorm = norm2(x)
            if (.not. (znorm > 0.0_wp)) then
                x = [(modulo(0.6180339887498949_wp*i, 1.0_wp) - 0.5_wp, i=1, self%m)]
                do j = 1, nn
                    x = x - dot_product(nullv(:, j), x)*nullv(:, j)
                end do
                znorm = norm2(x)
            end if
            x = x/znorm
            previous = -1.0_wp
            do it = 1, iterations
                self%kwork = 0.0_wp
                self%kwork(self%knew(self%n + 1:nk)) = x
                call dgbtrs('N', nk, self%kl, self%ku, 1, self%kband, size(self%kband, 1), self%kpiv, self%kwork, &
                            nk, info)
                z = -self%kwork(self%knew(self%n + 1:nk))   ! (GB + shift I)^{-1} x
                do j = 1, nn
                    z = z - dot_product(nullv(:, j), z)*nullv(:, j)
                end do
                znorm = norm2(z)
                if (.not. (znorm > 0.0_wp .and. znorm <= huge(1.0_wp))) then
                    ok = .false.
                    return
                end if
                est = dot_product(x, x)/dot_product(x, z)   ! Rayleigh quotient of (GB + shift I)^{-1}
                x = z/znorm
                if (it >= min_iterations .and. abs(est - previous) <= settled*abs(est)) exit
                previous = est
            end do
        end subroutine iterate
    end procedure augmented_sigma_min

    module procedure augmented_factor_saddle
        integer :: i, k, nk
        nk = self%n + self%m
        self%kband = 0.0_wp
        associate (mp => self%st%mass, gp => self%st%constraint)
            do i = 1, self%n
                do k = mp%row_start(i), mp%row_start(i + 1) - 1
                    call put(i, mp%cols(k), self%mvals(k))
                end do
            end do
            do i = 1, self%m
                do k = gp%row_start(i), gp%row_start(i + 1) - 1
                    call put(self%n + i, gp%cols(k), self%gvals(k))
                    call put(gp%cols(k), self%n + i, self%gvals(k))
                end do
                if (shift > 0.0_wp) call put(self%n + i, self%n + i, -shift)
            end do
        end associate
        call dgbtrf(nk, nk, self%kl, self%ku, self%kband, size(self%kband, 1), self%kpiv, info)
    contains
        ! K(i, j) = val in LAPACK band storage (row kl + ku + 1 + i - j of column j)
        subroutine put(i, j, val)
            integer, intent(in) :: i, j
            real(wp), intent(in) :: val
            integer :: a, b
            a = self%knew(i)
            b = self%knew(j)
            self%kband(self%kl + self%ku + 1 + a - b, b) = self%kband(self%kl + self%ku + 1 + a - b, b) + val
        end subroutine put
    end procedure augmented_factor_saddle

    module procedure augmented_solve_saddle
        integer :: nk, info
        nk = self%n + self%m
        self%kwork(self%knew(1:self%n)) = a
        self%kwork(self%knew(self%n + 1:nk)) = b
        call dgbtrs('N', nk, self%kl, self%ku, 1, self%kband, size(self%kband, 1), self%kpiv, self%kwork, nk, info)
        x = self%kwork(self%knew(1:self%n))
        z = self%kwork(self%knew(self%n + 1:nk))
    end procedure augmented_solve_saddle

    module procedure augmented_diagonal_scales
        real(wp) :: row, diag
        integer :: i, k, j
        gb = 0.0_wp
        g = 0.0_wp
        associate (mp => self%st%mass, gp => self%st%constraint)
            do i = 1, self%m
                row = 0.0_wp
                do k = gp%row_start(i), gp%row_start(i + 1) - 1
                    if (self%mass_diagonal) then   ! M(j, j) is entry j
                        j = gp%cols(k)
                    else
                        j = mp%position(gp%cols(k), gp%cols(k))
                    end if
                    diag = 1.0_wp
                    if (j > 0) diag = self%mvals(j)
                    if (diag > 0.0_wp) row = row + self%gvals(k)**2/diag
                end do
                gb = max(gb, row)
                g = max(g, norm2(self%gvals(gp%row_start(i):gp%row_start(i + 1) - 1)))
            end do
        end associate
    end procedure augmented_diagonal_scales

end submodule regdae_augmented_conditioning
