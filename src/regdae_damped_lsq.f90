!> Dense damped least-squares and shifted solves with LAPACK.
!!
!! The multiplier of the trust-region regularization (paper, eq. 2.10) is the
!! damped least-squares (Levenberg-Marquardt) solution
!! $$ y = \arg\min_y \|A y - r\|_2^2 + \epsilon \|y\|_2^2
!!      = (A^T A + \epsilon I)^{-1} A^T r, \qquad A = GB. $$
!! Two ways are offered:
!! - `lsq_normal`: the normal equations by Cholesky (plain loops up to 8 unknowns,
!!   regdae_small_cholesky; `dposv` beyond); cheap, but the
!!   condition number is squared, so the relative error grows like
!!   u * (sigma_max^2 + eps) / (sigma_min^2 + eps);
!! - `lsq_stacked`: the stacked system [A; sqrt(eps) I] y ~ [r; 0] with
!!   `dgelsd` (SVD); as accurate as the problem allows, also for eps = 0
!!   (minimum-norm solution) and rank-deficient A;
!! - `lsq_checked` (what `lsq=auto` uses): the normal equations, and the stacked
!!   system for the solves where they are ill-conditioned: where the Cholesky
!!   factor L of A^T A + eps I has (max L_ii / min L_ii)^2 > 1e8 (a lower bound
!!   of its condition number; the normal equations' relative error could exceed
!!   u 1e8 ~ 2e-8 there) or the factorization fails. The test is a ratio, so it
!!   does not depend on the units of A or eps; a well-conditioned problem never
!!   pays for the SVD, a singular configuration pays only where it is near.
!! The direct regularization (eq. 2.12) solves (A + eps I) y = r by Cholesky
!! (`shifted_spd_solve`), and Baumgarte's (eq. 2.7) solves A y = r by LU
!! (`square_solve`).
!!
!! All scratch space lives in a `damped_lsq_workspace`, sized once by `init`,
!! so no routine here allocates in the integration loop.
module regdae_damped_lsq
    use regdae_kinds, only: wp
    use regdae_status, only: regdae_success, regdae_err_bad_input, regdae_err_singular, &
                             regdae_err_not_psd, regdae_err_lapack
    use regdae_lapack, only: dposv, dgelsd, dgesv, dgesvd
    use regdae_small_cholesky, only: small_cholesky, small_cholesky_solve, small_cholesky_max
    implicit none
    private

    integer, parameter, public :: lsq_normal = 1   !! normal equations, Cholesky
    integer, parameter, public :: lsq_stacked = 2  !! stacked system, `dgelsd`
    integer, parameter, public :: lsq_checked = 3  !! normal equations, stacked where they are ill-conditioned

    !> lsq_checked: the largest (max L_ii / min L_ii)^2 the normal equations are trusted with.
    real(wp), parameter :: normal_condition_limit = 1.0e8_wp

    !> Scratch space for solves with a p x q matrix (p rows, q unknowns).
    type, public :: damped_lsq_workspace
        private
        integer :: p = 0, q = 0
        real(wp), allocatable :: mat(:, :)   ! (p+q) x q copy of the matrix
        real(wp), allocatable :: vec(:)      ! p+q right-hand side / solution
        real(wp), allocatable :: sv(:)       ! singular values from dgelsd
        real(wp), allocatable :: work(:)
        integer, allocatable :: iwork(:)
        integer, allocatable :: ipiv(:)
        integer :: last_rank = 0
        integer :: deficiency = -1           ! smallest_singular_value: the structural rank deficiency
                                             ! (the smallest numerical one over the calls; -1: no call yet)
        integer(8), public :: stacked_solves = 0   !! lsq_checked: solves that took the stacked system
    contains
        !> Size the workspace for p x q matrices (queries dgelsd's workspace).
        procedure :: init => workspace_init
        !> Numerical rank of the stacked matrix in the last `lsq_stacked` solve.
        procedure :: rank => workspace_rank
        !> Smallest singular value of a p x q matrix (`dgesvd`, values only) on its
        !! structural rank: the smallest one above the rank deficiency that every
        !! call so far has shown (redundant constraints: GB rank-deficient everywhere).
        procedure :: smallest_singular_value
    end type damped_lsq_workspace

    public :: damped_lsq_solve, shifted_spd_solve, square_solve

contains

    subroutine workspace_init(self, p, q, stat)
        class(damped_lsq_workspace), intent(inout) :: self
        integer, intent(in) :: p   !! rows of the matrices to be solved with
        integer, intent(in) :: q   !! columns (unknowns)
        integer, intent(out), optional :: stat   !! nonzero: the system refused the workspace (absent: an error stop)
        real(wp) :: work_query(1), a_dummy(1, 1), b_dummy(1, 1), s_dummy(1)
        integer :: iwork_query(1), rank, info, lwork, liwork, rows, astat

        self%p = p
        self%q = q
        rows = max(p + q, 1)
        if (allocated(self%mat)) deallocate (self%mat, self%vec, self%sv, self%work, self%iwork, self%ipiv)
        if (present(stat)) then
            stat = 0
            allocate (self%mat(rows, max(q, 1)), self%vec(rows), self%sv(max(q, 1)), self%ipiv(max(q, 1)), stat=astat)
            if (astat /= 0) then
                stat = astat
                if (allocated(self%mat)) deallocate (self%mat)
                if (allocated(self%vec)) deallocate (self%vec)
                if (allocated(self%sv)) deallocate (self%sv)
                if (allocated(self%ipiv)) deallocate (self%ipiv)
                return
            end if
        else
            allocate (self%mat(rows, max(q, 1)), self%vec(rows), self%sv(max(q, 1)), self%ipiv(max(q, 1)))
        end if
        ! Workspace query for the stacked (p+q) x q problem with one right-hand side.
        call dgelsd(p + q, q, 1, a_dummy, rows, b_dummy, rows, s_dummy, -1.0_wp, rank, &
                    work_query, -1, iwork_query, info)
        lwork = max(1, int(work_query(1)))
        call dgesvd('N', 'N', max(p, 1), max(q, 1), a_dummy, rows, s_dummy, a_dummy, 1, a_dummy, 1, work_query, -1, info)
        lwork = max(lwork, int(work_query(1)))
        liwork = max(1, iwork_query(1))
        if (present(stat)) then
            allocate (self%work(lwork), self%iwork(liwork), stat=astat)
            if (astat /= 0) then
                stat = astat
                deallocate (self%mat, self%vec, self%sv, self%ipiv)
                if (allocated(self%work)) deallocate (self%work)
                if (allocated(self%iwork)) deallocate (self%iwork)
            end if
        else
            allocate (self%work(lwork), self%iwork(liwork))
        end if
        self%deficiency = -1
    end subroutine workspace_init

    pure integer function workspace_rank(self)
        class(damped_lsq_workspace), intent(in) :: self
        workspace_rank = self%last_rank
    end function workspace_rank

    !> Smallest singular value of `a` (p x q, the workspace's shape); for one
    !! column or row it is a norm, without LAPACK.
    function smallest_singular_value(self, a) result(sigma)
        class(damped_lsq_workspace), intent(inout) :: self
        real(wp), intent(in) :: a(:, :)
        real(wp) :: sigma, dummy(1, 1)
        integer :: info, p, q, k, d
        logical :: done
        p = size(a, 1)
        q = size(a, 2)
        if (p == 0 .or. q == 0) then
            sigma = 0.0_wp
        else if (q == 1) then
            sigma = norm2(a(:, 1))
        else if (p == 1) then
            sigma = norm2(a(1, :))
        else
            done = .false.
            if (p == 2 .and. q == 2) call singular_values_2x2(a, self%sv, done)
            if (.not. done) then
                self%mat(1:p, 1:q) = a
                call dgesvd('N', 'N', p, q, self%mat, size(self%mat, 1), self%sv, dummy, 1, dummy, 1, &
                            self%work, size(self%work), info)
            end if
            ! A matrix of constant rank r < min(p, q) (GB of redundant constraints) has
            ! sigma_(r+1..) zero in exact arithmetic and at rounding level in dgesvd's
            ! (0, 1e-16 |GB|, ... at random): their minimum says nothing about the
            ! configuration, and a threshold relative to it flips with the rounding (the
            ! pass check's chatter). The rank deficiency that all calls have shown (the
            ! numerical rank's tolerance is LAPACK's, max(p, q) u sigma_1) is the
            ! structure's; sigma_min is taken on the rest, sigma_r, which falls to 0 where
            ! the configuration is singular. A matrix of full rank somewhere (a singular
            ! configuration sampled on it included, once one regular sample is seen) has
            ! deficiency 0: its plain sigma_min, unchanged.
            k = min(p, q)
            d = count(self%sv(1:k) <= real(max(p, q), wp)*epsilon(1.0_wp)*self%sv(1))
            if (self%deficiency < 0) then
                self%deficiency = d
            else
                self%deficiency = min(self%deficiency, d)
            end if
            sigma = self%sv(max(1, k - self%deficiency))
        end if
    end function smallest_singular_value

    ! The singular values of a 2 x 2 matrix (s(1) >= s(2)) by the arithmetic that reference
    ! LAPACK's dgesvd('N', 'N') performs on it, operation for operation, so the same numbers
    ! without its calls (a quarter of the car axis's instructions under the defaults went to
    ! dgesvd on GB, mostly argument checks and block-size queries): a Householder reflection
    ! that annihilates a(2, 1) (dgebd2: dlarfg with dlapy2, applied to the second column as
    ! dlarf does, with dgemv's and dger's sums and their zero tests), then the 2 x 2
    ! bidiagonal's values (dbdsqr -> dlasq1 -> dlas2). done = .false. (the caller calls
    ! dgesvd) where dgesvd would scale the matrix first (max |a_ij| outside
    ! [sqrt(safe minimum)/eps, its inverse], a zero matrix or a NaN or Inf included) or
    ! dlarfg would rescale (|beta| below the safe minimum / eps).
    pure subroutine singular_values_2x2(a, s, done)
        real(wp), intent(in) :: a(:, :)
        real(wp), intent(inout) :: s(:)
        logical, intent(out) :: done
        real(wp), parameter :: lapack_eps = epsilon(1.0_wp)          ! dlamch('P')
        real(wp), parameter :: small_norm = sqrt(tiny(1.0_wp))/lapack_eps
        real(wp), parameter :: big_norm = 1.0_wp/small_norm
        real(wp), parameter :: safe_beta = tiny(1.0_wp)/(0.5_wp*epsilon(1.0_wp))   ! dlamch('S') / dlamch('E')
        real(wp) :: a11, a21, a12, a22, anrm, beta, tau, v2, w, xa, xb, d1, e1, d2
        logical :: two_rows
        a11 = a(1, 1)
        a21 = a(2, 1)
        a12 = a(1, 2)
        a22 = a(2, 2)
        done = .false.
        if (a11 /= a11 .or. a21 /= a21 .or. a12 /= a12 .or. a22 /= a22) return   ! a NaN
        anrm = max(abs(a11), abs(a21), abs(a12), abs(a22))
        if (.not. (anrm >= small_norm .and. anrm <= big_norm)) return
        d1 = a11
        if (abs(a21) /= 0.0_wp) then   ! dlarfg(2, a11, a21): xnorm = |a21|
            xa = max(abs(a11), abs(a21))   ! dlapy2(a11, xnorm)
            xb = min(abs(a11), abs(a21))
            if (xb == 0.0_wp) then
                beta = -sign(xa, a11)
            else
                beta = -sign(xa*sqrt(1.0_wp + (xb/xa)**2), a11)
            end if
            if (abs(beta) < safe_beta) return
            tau = (beta - a11)/beta
            v2 = (1.0_wp/(a11 - beta))*a21
            d1 = beta
            ! dlarf('Left'): the last nonzero entry of v = (1, v2), then w = C^T v and C - tau v w
            two_rows = (v2 /= 0.0_wp)
            if (a12 /= 0.0_wp .or. (two_rows .and. a22 /= 0.0_wp)) then
                w = 0.0_wp + a12
                if (two_rows) w = w + a22*v2
                w = 0.0_wp + w
                if (w /= 0.0_wp) then
                    w = -tau*w
                    a12 = a12 + w
                    if (two_rows) a22 = a22 + v2*w
                end if
            end if
        end if
        e1 = a12
        d2 = a22
        call lapack_las2(d1, e1, d2, s(2), s(1))
        done = .true.
    end subroutine singular_values_2x2

    ! The singular values of the upper bidiagonal [f g; 0 h] (dlas2's arithmetic).
    pure subroutine lapack_las2(f, g, h, ssmin, ssmax)
        real(wp), intent(in) :: f, g, h
        real(wp), intent(out) :: ssmin, ssmax
        real(wp) :: as, at, au, c, fa, fhmn, fhmx, ga, ha
        fa = abs(f)
        ga = abs(g)
        ha = abs(h)
        fhmn = min(fa, ha)
        fhmx = max(fa, ha)
        if (fhmn == 0.0_wp) then
            ssmin = 0.0_wp
            if (fhmx == 0.0_wp) then
                ssmax = ga
            else
                ssmax = max(fhmx, ga)*sqrt(1.0_wp + (min(fhmx, ga)/max(fhmx, ga))**2)
            end if
        else if (ga < fhmx) then
            as = 1.0_wp + fhmn/fhmx
            at = (fhmx - fhmn)/fhmx
            au = (ga/fhmx)**2
            c = 2.0_wp/(sqrt(as*as + au) + sqrt(at*at + au))
            ssmin = fhmn*c
            ssmax = fhmx/c
        else
            au = fhmx/ga
            if (au == 0.0_wp) then
                ssmin = (fhmn*fhmx)/ga
                ssmax = ga
            else
                as = 1.0_wp + fhmn/fhmx
                at = (fhmx - fhmn)/fhmx
                c = 1.0_wp/(sqrt(1.0_wp + (as*au)**2) + sqrt(1.0_wp + (at*au)**2))
                ssmin = (fhmn*c)*au
                ssmin = ssmin + ssmin
                ssmax = ga/(c + c)
            end if
        end if
    end subroutine lapack_las2

    !> Damped least-squares solution y = (A^T A + eps I)^{-1} A^T r.
    !!
    !! `stat` is `regdae_success`, `regdae_err_singular` (normal equations with
    !! a singular matrix, possible only for eps = 0), `regdae_err_bad_input`
    !! (shapes or eps < 0) or `regdae_err_lapack`.
    subroutine damped_lsq_solve(ws, a, r, eps, method, y, stat)
        type(damped_lsq_workspace), intent(inout) :: ws
        real(wp), intent(in) :: a(:, :)   !! p x q matrix (GB)
        real(wp), intent(in) :: r(:)      !! right-hand side, length p
        real(wp), intent(in) :: eps       !! damping, eps >= 0
        integer, intent(in) :: method     !! `lsq_normal` or `lsq_stacked`
        real(wp), intent(out) :: y(:)     !! solution, length q
        integer, intent(out) :: stat
        integer :: p, q, i, info, rows

        p = size(a, 1)
        q = size(a, 2)
        if (p /= ws%p .or. q /= ws%q .or. size(r) /= p .or. size(y) /= q .or. .not. (eps >= 0.0_wp)) then
            stat = regdae_err_bad_input
            return
        end if
        stat = regdae_success
        if (q == 0) return
        if (p == 1 .and. q == 1 .and. method >= lsq_normal .and. method <= lsq_checked) then
            ! One constraint: both ways are y = a r / (a^2 + eps), to rounding, without
            ! LAPACK's call overhead (the minimum-norm y = 0 when a = eps = 0).
            if (a(1, 1)**2 + eps > 0.0_wp) then
                y(1) = a(1, 1)*r(1)/(a(1, 1)**2 + eps)
            else if (method /= lsq_normal) then
                y(1) = 0.0_wp
            else
                stat = regdae_err_singular
            end if
            return
        end if
        select case (method)
        case (lsq_normal)
            call normal_solve()
            if (info > 0) stat = regdae_err_singular
        case (lsq_stacked)
            call stacked_solve()
        case (lsq_checked)
            call normal_solve()
            if (info /= 0 .or. .not. well_conditioned()) then
                ws%stacked_solves = ws%stacked_solves + 1
                call stacked_solve()
            end if
        case default
            stat = regdae_err_bad_input
            return
        end select
        if (info < 0) stat = regdae_err_lapack
    contains
        subroutine normal_solve()
            if (p == 2 .and. q == 2) then
                call normal_solve_2x2(a, r, eps, ws%mat, y, info)
                return
            else if (q <= small_cholesky_max) then
                call small_normal_equations(p, q, a, r, eps, ws%mat, size(ws%mat, 1), y)
            else
                ws%mat(1:q, 1:q) = matmul(transpose(a), a)
                do i = 1, q
                    ws%mat(i, i) = ws%mat(i, i) + eps
                end do
                y = matmul(r, a)
            end if
            call spd_solve(ws%mat, q, y, info)
        end subroutine normal_solve

        subroutine stacked_solve()
            rows = p + q
            ws%mat(1:p, 1:q) = a
            ws%mat(p + 1:rows, 1:q) = 0.0_wp
            do i = 1, q
                ws%mat(p + i, i) = sqrt(eps)
            end do
            ws%vec(1:p) = r
            ws%vec(p + 1:rows) = 0.0_wp
            call dgelsd(rows, q, 1, ws%mat, size(ws%mat, 1), ws%vec, size(ws%vec), ws%sv, -1.0_wp, &
                        ws%last_rank, ws%work, size(ws%work), ws%iwork, info)
            if (info > 0) stat = regdae_err_singular   ! SVD did not converge
            y = ws%vec(1:q)
        end subroutine stacked_solve

        ! (max L_ii / min L_ii)^2 of the Cholesky factor in ws%mat within the limit
        logical function well_conditioned()
            real(wp) :: dmax, dmin
            dmax = 0.0_wp
            dmin = huge(1.0_wp)
            do i = 1, q
                dmax = max(dmax, abs(ws%mat(i, i)))
                dmin = min(dmin, abs(ws%mat(i, i)))
            end do
            well_conditioned = (dmin > 0.0_wp)
            if (well_conditioned) well_conditioned = ((dmax/dmin)**2 <= normal_condition_limit)
        end function well_conditioned
    end subroutine damped_lsq_solve

    !> Solve (A + eps I) y = r by Cholesky, A symmetric positive semidefinite.
    !!
    !! A is first checked for symmetry (to a relative 1e-8 of its largest
    !! entry); a non-symmetric A or a failed Cholesky factorization gives
    !! `regdae_err_not_psd`.
    subroutine shifted_spd_solve(ws, a, r, eps, y, stat)
        type(damped_lsq_workspace), intent(inout) :: ws
        real(wp), intent(in) :: a(:, :)   !! q x q symmetric PSD matrix (GB)
        real(wp), intent(in) :: r(:)      !! right-hand side, length q
        real(wp), intent(in) :: eps       !! shift, eps >= 0
        real(wp), intent(out) :: y(:)     !! solution, length q
        integer, intent(out) :: stat
        real(wp), parameter :: symmetry_tol = 1.0e-8_wp
        integer :: q, i, info

        q = size(a, 2)
        if (size(a, 1) /= q .or. q /= ws%q .or. size(r) /= q .or. size(y) /= q .or. .not. (eps >= 0.0_wp)) then
            stat = regdae_err_bad_input
            return
        end if
        stat = regdae_success
        if (q == 0) return
        if (q == 1) then   ! one constraint: no LAPACK call
            if (a(1, 1) + eps > 0.0_wp) then
                y(1) = r(1)/(a(1, 1) + eps)
            else
                stat = regdae_err_not_psd
            end if
            return
        end if
        if (maxval(abs(a - transpose(a))) > symmetry_tol*maxval(abs(a))) then
            stat = regdae_err_not_psd
            return
        end if
        ws%mat(1:q, 1:q) = a
        do i = 1, q
            ws%mat(i, i) = ws%mat(i, i) + eps
        end do
        y = r
        call spd_solve(ws%mat, q, y, info)
        if (info > 0) stat = regdae_err_not_psd
        if (info < 0) stat = regdae_err_lapack
    end subroutine shifted_spd_solve

    ! The lower triangle of A^T A + eps I in mat and A^T r in y, by loops: each sum over
    ! k = 1..p from 0 in ascending k, the order of matmul's, so the same numbers as
    ! `matmul(transpose(a), a)` and `matmul(r, a)`, without their temporaries and zeroing
    ! (a tenth of the car axis's slope); the upper triangle, which the Cholesky factor
    ! does not read, is left alone.
    pure subroutine small_normal_equations(p, q, a, r, eps, mat, ldm, y)
        integer, intent(in) :: p, q, ldm
        real(wp), intent(in) :: a(p, q), r(p), eps
        real(wp), intent(inout) :: mat(ldm, q)
        real(wp), intent(out) :: y(q)
        integer :: i, j, k
        real(wp) :: s
        do j = 1, q
            do i = j, q
                s = 0.0_wp
                do k = 1, p
                    s = s + a(k, i)*a(k, j)
                end do
                mat(i, j) = s
            end do
            mat(j, j) = mat(j, j) + eps
            s = 0.0_wp
            do k = 1, p
                s = s + r(k)*a(k, j)
            end do
            y(j) = s
        end do
    end subroutine small_normal_equations

    ! Two constraints (the car axis): `small_normal_equations`, `small_cholesky` and
    ! `small_cholesky_solve` of a 2 x 2 system written out, the same operations in the same
    ! order (so the same numbers, the factor left in mat as they leave it), without the
    ! loops' and calls' overhead; info as spd_solve's.
    pure subroutine normal_solve_2x2(a, r, eps, mat, y, info)
        real(wp), intent(in) :: a(:, :), r(:), eps
        real(wp), intent(inout) :: mat(:, :)
        real(wp), intent(out) :: y(:)
        integer, intent(out) :: info
        real(wp) :: l11, l21, m22, s, b1, b2
        l11 = ((0.0_wp + a(1, 1)*a(1, 1)) + a(2, 1)*a(2, 1)) + eps
        l21 = (0.0_wp + a(1, 2)*a(1, 1)) + a(2, 2)*a(2, 1)
        m22 = ((0.0_wp + a(1, 2)*a(1, 2)) + a(2, 2)*a(2, 2)) + eps
        b1 = (0.0_wp + r(1)*a(1, 1)) + r(2)*a(2, 1)
        b2 = (0.0_wp + r(1)*a(1, 2)) + r(2)*a(2, 2)
        mat(2, 2) = m22
        y(1) = b1
        y(2) = b2
        if (.not. (l11 > 0.0_wp)) then
            mat(1, 1) = l11
            mat(2, 1) = l21
            info = 1
            return
        end if
        l11 = sqrt(l11)
        l21 = l21/l11
        mat(1, 1) = l11
        mat(2, 1) = l21
        s = m22 - l21**2
        if (.not. (s > 0.0_wp)) then
            info = 2
            return
        end if
        s = sqrt(s)
        mat(2, 2) = s
        info = 0
        b1 = b1/l11
        b2 = (b2 - l21*b1)/s
        b2 = b2/s
        b1 = (b1 - l21*b2)/l11
        y(1) = b1
        y(2) = b2
    end subroutine normal_solve_2x2

    ! Solve with the SPD matrix in mat(1:q, 1:q) (lower triangle; overwritten by its Cholesky
    ! factor) and the right-hand side y: plain loops up to small_cholesky_max unknowns, dposv
    ! beyond; info as dposv's.
    subroutine spd_solve(mat, q, y, info)
        real(wp), intent(inout) :: mat(:, :), y(:)
        integer, intent(in) :: q
        integer, intent(out) :: info

        if (q <= small_cholesky_max) then
            call small_cholesky(q, mat, size(mat, 1), info)
            if (info == 0) call small_cholesky_solve(q, mat, size(mat, 1), y)
        else
            call dposv('L', q, 1, mat, size(mat, 1), y, q, info)
        end if
    end subroutine spd_solve

    !> Solve A y = r by LU with partial pivoting (Baumgarte, eq. 2.7).
    !! A singular A (an exactly zero pivot) gives `regdae_err_singular`.
    subroutine square_solve(ws, a, r, y, stat)
        type(damped_lsq_workspace), intent(inout) :: ws
        real(wp), intent(in) :: a(:, :)   !! q x q matrix (GB)
        real(wp), intent(in) :: r(:)      !! right-hand side, length q
        real(wp), intent(out) :: y(:)     !! solution, length q
        integer, intent(out) :: stat
        integer :: q, info

        q = size(a, 2)
        if (size(a, 1) /= q .or. q /= ws%q .or. size(r) /= q .or. size(y) /= q) then
            stat = regdae_err_bad_input
            return
        end if
        stat = regdae_success
        if (q == 0) return
        if (q == 1) then   ! one constraint: no LAPACK call
            if (a(1, 1) /= 0.0_wp) then
                y(1) = r(1)/a(1, 1)
            else
                stat = regdae_err_singular
            end if
            return
        end if
        ws%mat(1:q, 1:q) = a
        y = r
        call dgesv(q, 1, ws%mat, size(ws%mat, 1), ws%ipiv, y, q, info)
        if (info > 0) stat = regdae_err_singular
        if (info < 0) stat = regdae_err_lapack
    end subroutine square_solve

end module regdae_damped_lsq
