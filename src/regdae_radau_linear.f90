!> The two Newton matrices of the Radau IIA integrator (Hairer & Wanner, Solving
!! ODEs II, section IV.8): with the transformation T that brings \(A^{-1}\) to
!! \(\mathrm{diag}(\gamma, [\alpha, -\beta; \beta, \alpha])\), the simplified Newton
!! system of the 3n stage unknowns splits into
!! $$ E_1 = \frac{\gamma}{h} M - J \;(\text{real}, n \times n), \qquad
!!    E_2 = \frac{\alpha + i\beta}{h} M - J \;(\text{complex}, n \times n), $$
!! M the (diagonal) mass matrix and J the Jacobian of the right-hand side.
!!
!! Dense LU with partial pivoting (LAPACK dgetrf/dgetrs, zgetrf/zgetrs). The complex
!! system is factored as a complex n x n matrix, not as the real 2n x 2n matrix
!! [E_r, -E_i; E_i, E_r]: measured with the reference LAPACK of this machine, the
!! factorization (with its assembly) is 1.5x (n = 4), 1.9x (8), 2.8x (16), 3.3x (30),
!! 3.9x (45) and 4.1x (60) cheaper in complex form, one solve 1.5x-2.4x. Up to
!! `small_n` unknowns the LU and its solves are this module's own loops (the same
!! partial pivoting, first largest |a| and, complex, |Re| + |Im| as LAPACK's izamax):
!! on the car axis (n = 8) LAPACK's calls cost a quarter of Radau's instructions, most
!! of it in its argument checks and block-size queries (lsame, ilaenv), not in the
!! arithmetic.
module regdae_radau_linear
    use regdae_kinds, only: wp
    use regdae_status, only: regdae_success, regdae_err_singular, regdae_err_lapack
    use regdae_lapack, only: dgetrf, dgetrs, zgetrf, zgetrs
    implicit none
    private

    public :: radau_newton_matrices

    !> Up to this many unknowns the module's own LU, beyond it LAPACK's.
    integer, parameter :: small_n = 16

    !> The LU factors of E_1 and E_2 and a complex work vector.
    type :: radau_newton_matrices
        integer :: n = 0
        real(wp), allocatable :: e1(:, :)       !! LU factors of E_1
        integer, allocatable :: ipiv1(:)
        complex(wp), allocatable :: e2(:, :)    !! LU factors of E_2
        integer, allocatable :: ipiv2(:)
        complex(wp), allocatable :: work(:)
    contains
        !> Allocate for n unknowns.
        procedure :: init => matrices_init
        !> Form and factor E_1 and E_2 from J, M and the three factors.
        procedure :: factor => matrices_factor
        !> Solve E_1 x = b in place.
        procedure :: solve_real => matrices_solve_real
        !> Solve E_2 (x + i y) = b + i c in place (x, y overwrite b, c).
        procedure :: solve_complex => matrices_solve_complex
        !> The rounding floor of the Newton increments that the algebraic rows leave.
        procedure :: rounding_floor => matrices_rounding_floor
    end type radau_newton_matrices

contains

    subroutine matrices_init(self, n)
        class(radau_newton_matrices), intent(inout) :: self
        integer, intent(in) :: n   !! number of unknowns
        if (allocated(self%e1)) deallocate (self%e1, self%ipiv1, self%e2, self%ipiv2, self%work)
        self%n = n
        allocate (self%e1(n, n), self%ipiv1(n), self%e2(n, n), self%ipiv2(n), self%work(n))
    end subroutine matrices_init

    !> E_1 = fac_real M - J, E_2 = (fac_alpha + i fac_beta) M - J, both factored.
    !! stat: regdae_success, regdae_err_singular (an exactly zero pivot: the caller
    !! reduces the step) or regdae_err_lapack.
    subroutine matrices_factor(self, jac, mass, fac_real, fac_alpha, fac_beta, stat)
        class(radau_newton_matrices), intent(inout) :: self
        real(wp), intent(in) :: jac(:, :)    !! J, n x n
        real(wp), intent(in) :: mass(:)      !! the diagonal of M
        real(wp), intent(in) :: fac_real     !! gamma / h
        real(wp), intent(in) :: fac_alpha    !! alpha / h
        real(wp), intent(in) :: fac_beta     !! beta / h
        integer, intent(out) :: stat
        integer :: i, info
        complex(wp) :: fac_c
        fac_c = cmplx(fac_alpha, fac_beta, wp)
        self%e1(:, :) = -jac
        self%e2(:, :) = cmplx(-jac, 0.0_wp, wp)
        do i = 1, self%n
            self%e1(i, i) = self%e1(i, i) + fac_real*mass(i)
            self%e2(i, i) = self%e2(i, i) + fac_c*mass(i)
        end do
        if (self%n <= small_n) then
            call small_lu_real(self%n, self%e1, self%ipiv1, info)
            if (info == 0) call small_lu_complex(self%n, self%e2, self%ipiv2, info)
        else
            call dgetrf(self%n, self%n, self%e1, self%n, self%ipiv1, info)
            if (info == 0) call zgetrf(self%n, self%n, self%e2, self%n, self%ipiv2, info)
        end if
        stat = regdae_success
        if (info > 0) stat = regdae_err_singular
        if (info < 0) stat = regdae_err_lapack
    end subroutine matrices_factor

    subroutine matrices_solve_real(self, b)
        class(radau_newton_matrices), intent(inout) :: self
        real(wp), intent(inout) :: b(:)   !! right-hand side in, solution out
        integer :: info, n
        n = self%n
        if (n > small_n) then
            call dgetrs('N', n, 1, self%e1, n, self%ipiv1, b, n, info)
            return
        end if
        call small_solve_real(n, self%e1, self%ipiv1, b)
    end subroutine matrices_solve_real

    subroutine matrices_solve_complex(self, b, c)
        class(radau_newton_matrices), intent(inout) :: self
        real(wp), intent(inout) :: b(:)   !! real part of the right-hand side in, of the solution out
        real(wp), intent(inout) :: c(:)   !! imaginary part, likewise
        integer :: info, n
        n = self%n
        associate (w => self%work, e => self%e2, ipiv => self%ipiv2)
            w = cmplx(b, c, wp)
            if (n > small_n) then
                call zgetrs('N', n, 1, e, n, ipiv, w, n, info)
            else
                call small_solve_complex(n, e, ipiv, w)
            end if
            b = real(w, wp)
            c = aimag(w)
        end associate
    end subroutine matrices_solve_complex

    !> The size of the Newton increments that the rounding of F's algebraic rows
    !! (M_ii = 0) leaves in each unknown, with the factors of E_1 at hand. F_i(u) is
    !! known to rho_i = eps_m (|F_i| + sum_j |J_ij| |u_j|) (eps_m the machine epsilon: the
    !! rounding of F_i's value and of the arguments it is computed from), and on an
    !! algebraic row the stage equation is 0 = F_i: no factor h damps that error,
    !! and the iteration's increments settle at about E_1^{-1} rho, whatever h.
    !! floor = |E_1^{-1} rho|, rho = 0 on the differential rows (their rounding
    !! enters times h/gamma). Large where a row is computed from terms much larger
    !! than its value (the stiff chain's Baumgarte rows: gamma0 g(q), gamma0 = 1.3e7,
    !! g rounded to 1e-16 |q|^2, leave 1e-8 in the accelerations).
    subroutine matrices_rounding_floor(self, jac, mass, u, f, floor)
        class(radau_newton_matrices), intent(inout) :: self
        real(wp), intent(in) :: jac(:, :)    !! J = dF/du, n x n
        real(wp), intent(in) :: mass(:)      !! the diagonal of M
        real(wp), intent(in) :: u(:)         !! the point of J
        real(wp), intent(in) :: f(:)         !! F(t, u)
        real(wp), intent(out) :: floor(:)    !! the floor per unknown, size n
        integer :: i
        do i = 1, self%n
            floor(i) = 0
            if (mass(i) == 0) floor(i) = epsilon(1.0_wp)*(abs(f(i)) + sum(abs(jac(i, :))*abs(u)))
        end do
        call self%solve_real(floor)
        floor = abs(floor)
    end subroutine matrices_rounding_floor

    !> LU with partial pivoting of a small real matrix in place (LAPACK's dgetrf
    !! layout: unit L below the diagonal, U on and above it, row k swapped with
    !! ipiv(k)); info = k > 0 at the first exactly zero pivot.
    pure subroutine small_lu_real(n, a, ipiv, info)
        integer, intent(in) :: n
        real(wp), intent(inout) :: a(n, n)
        integer, intent(out) :: ipiv(n)
        integer, intent(out) :: info
        real(wp) :: swap, pivot
        integer :: i, j, k, p
        info = 0
        do k = 1, n
            p = k
            do i = k + 1, n
                if (abs(a(i, k)) > abs(a(p, k))) p = i
            end do
            ipiv(k) = p
            if (a(p, k) == 0) then
                info = k
                return
            end if
            if (p /= k) then
                do j = 1, n
                    swap = a(k, j)
                    a(k, j) = a(p, j)
                    a(p, j) = swap
                end do
            end if
            pivot = a(k, k)
            a(k + 1:n, k) = a(k + 1:n, k)/pivot
            do j = k + 1, n
                a(k + 1:n, j) = a(k + 1:n, j) - a(k + 1:n, k)*a(k, j)
            end do
        end do
    end subroutine small_lu_real

    !> The same for a complex matrix, the pivot the first largest |Re| + |Im|.
    pure subroutine small_lu_complex(n, a, ipiv, info)
        integer, intent(in) :: n
        complex(wp), intent(inout) :: a(n, n)
        integer, intent(out) :: ipiv(n)
        integer, intent(out) :: info
        complex(wp) :: swap, pivot
        real(wp) :: big
        integer :: i, j, k, p
        info = 0
        do k = 1, n
            p = k
            big = abs(a(k, k)%re) + abs(a(k, k)%im)
            do i = k + 1, n
                if (abs(a(i, k)%re) + abs(a(i, k)%im) > big) then
                    p = i
                    big = abs(a(i, k)%re) + abs(a(i, k)%im)
                end if
            end do
            ipiv(k) = p
            if (big == 0) then
                info = k
                return
            end if
            if (p /= k) then
                do j = 1, n
                    swap = a(k, j)
                    a(k, j) = a(p, j)
                    a(p, j) = swap
                end do
            end if
            pivot = a(k, k)
            a(k + 1:n, k) = a(k + 1:n, k)/pivot
            do j = k + 1, n
                a(k + 1:n, j) = a(k + 1:n, j) - a(k + 1:n, k)*a(k, j)
            end do
        end do
    end subroutine small_lu_complex

    !> Solve with the factors of `small_lu_real` in place: the row swaps in their
    !! order, then L y = P b and U x = y column by column (explicit shapes and scalar
    !! swaps: no temporaries).
    pure subroutine small_solve_real(n, e, ipiv, b)
        integer, intent(in) :: n
        real(wp), intent(in) :: e(n, n)
        integer, intent(in) :: ipiv(n)
        real(wp), intent(inout) :: b(n)
        real(wp) :: swap, bk
        integer :: i, k
        do k = 1, n
            if (ipiv(k) /= k) then
                swap = b(k)
                b(k) = b(ipiv(k))
                b(ipiv(k)) = swap
            end if
        end do
        do k = 1, n
            bk = b(k)
            do i = k + 1, n
                b(i) = b(i) - e(i, k)*bk
            end do
        end do
        do k = n, 1, -1
            b(k) = b(k)/e(k, k)
            bk = b(k)
            do i = 1, k - 1
                b(i) = b(i) - e(i, k)*bk
            end do
        end do
    end subroutine small_solve_real

    !> The same with the factors of `small_lu_complex`.
    pure subroutine small_solve_complex(n, e, ipiv, w)
        integer, intent(in) :: n
        complex(wp), intent(in) :: e(n, n)
        integer, intent(in) :: ipiv(n)
        complex(wp), intent(inout) :: w(n)
        complex(wp) :: swap, wk
        integer :: i, k
        do k = 1, n
            if (ipiv(k) /= k) then
                swap = w(k)
                w(k) = w(ipiv(k))
                w(ipiv(k)) = swap
            end if
        end do
        do k = 1, n
            wk = w(k)
            do i = k + 1, n
                w(i) = w(i) - e(i, k)*wk
            end do
        end do
        do k = n, 1, -1
            w(k) = w(k)/e(k, k)
            wk = w(k)
            do i = 1, k - 1
                w(i) = w(i) - e(i, k)*wk
            end do
        end do
    end subroutine small_solve_complex

end module regdae_radau_linear
