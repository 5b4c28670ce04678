!> The coefficients of the three-stage Radau IIA method of order 5, computed from
!! exact formulas (Hairer & Wanner, Solving Ordinary Differential Equations II,
!! 2nd ed., section IV.5 for the method and IV.8 for its implementation).
!!
!! - nodes \(c_{1,2} = (4 \mp \sqrt 6)/10\), \(c_3 = 1\); the matrix A of the
!!   collocation method; its weights b are A's last row (stiffly accurate).
!! - The eigenvalues of \(A^{-1}\) are the poles of the stability function
!!   \(R(z) = P(z)/Q(z)\), \(Q(z) = 1 - 3z/5 + 3z^2/20 - z^3/60\), the roots of
!!   \(z^3 - 9z^2 + 36z - 60\). With \(z = x + 3\): \(x^3 + 9x - 6 = 0\), whose
!!   Cardano roots give, with \(u = 9^{1/3}\), \(v = 3^{1/3}\):
!!   \(\gamma = 3 + u - v\), \(\alpha = 3 - (u - v)/2\), \(\beta = \sqrt 3 (u + v)/2\).
!! - T has the columns (v_1, Im v, Re v), v_1 the real eigenvector of \(A^{-1}\) and
!!   v the one of \(\alpha + i\beta\), each the cross product of two rows of
!!   \(A^{-1} - \lambda I\); then \(T^{-1} A^{-1} T = \mathrm{diag}(\gamma, [\alpha, -\beta; \beta, \alpha])\).
!! - The embedded order-3 formula \(\hat y_1 = y_0 + h(\gamma_0 f(t_0, y_0) + \sum \hat b_i f(Y_i))\),
!!   \(\gamma_0 = 1/\gamma\) (the real eigenvalue of A), is exact on polynomials of degree 2:
!!   \(d = \hat b - b\) solves \(\sum d_i c_i^k = -\gamma_0 \delta_{k0}\) (k = 0, 1, 2). With
!!   \(h f(Y_i) = \sum_j (A^{-1})_{ij} z_j\): \(\hat y_1 - y_1 = \gamma_0 (h f_0 + \sum_j e_j z_j)\),
!!   \(e = (d/\gamma_0)^T A^{-1}\) (published: \(e = ((-13 - 7\sqrt 6)/3, (-13 + 7\sqrt 6)/3, -1/3)\)).
!! - The collocation polynomial of a step, \(u(t_0 + sh) = y_0 + \sum_{k=1}^3 q_k s^k\), through
!!   \(z_i = Y_i - y_0\) at \(s = c_i\): \(q = P z\), P the inverse of \((c_i^k)\).
module regdae_radau_tableau
    use regdae_kinds, only: wp
    implicit none
    private

    public :: radau_coefficients, radau_iia_coefficients, inverse3

    !> The Radau IIA (s = 3) coefficients and the matrices of its implementation.
    type :: radau_coefficients
        real(wp) :: c(3) = 0          !! nodes
        real(wp) :: a(3, 3) = 0       !! the Runge-Kutta matrix
        real(wp) :: a_inv(3, 3) = 0   !! its inverse
        real(wp) :: b(3) = 0          !! weights (= a(3, :))
        real(wp) :: gamma = 0         !! the real eigenvalue of a_inv
        real(wp) :: alpha = 0         !! real part of its complex pair
        real(wp) :: beta = 0          !! imaginary part (> 0)
        real(wp) :: t(3, 3) = 0       !! a_inv = t diag(gamma, [alpha -beta; beta alpha]) t_inv
        real(wp) :: t_inv(3, 3) = 0   !! the inverse of t
        real(wp) :: e(3) = 0          !! error estimate: (y_hat - y)/(gamma0 h) = f0 + sum_j e_j z_j / h
        real(wp) :: p(3, 3) = 0       !! collocation polynomial coefficients q = p z
    end type radau_coefficients

contains

    !> The coefficients, each from its exact formula (see the module's description).
    pure function radau_iia_coefficients() result(rc)
        type(radau_coefficients) :: rc
        real(wp) :: s6, u, v, w(3, 3), d(3), cv(3, 3), rows(3, 3)
        complex(wp) :: lam, rows_c(3, 3), vc(3)
        integer :: i, k

        s6 = sqrt(6.0_wp)
        rc%c = [(4.0_wp - s6)/10, (4.0_wp + s6)/10, 1.0_wp]
        rc%a(1, :) = [(88.0_wp - 7*s6)/360, (296.0_wp - 169*s6)/1800, (-2.0_wp + 3*s6)/225]
        rc%a(2, :) = [(296.0_wp + 169*s6)/1800, (88.0_wp + 7*s6)/360, (-2.0_wp - 3*s6)/225]
        rc%a(3, :) = [(16.0_wp - s6)/36, (16.0_wp + s6)/36, 1.0_wp/9]
        rc%b = rc%a(3, :)
        rc%a_inv = inverse3(rc%a)

        u = 9.0_wp**(1.0_wp/3)
        v = 3.0_wp**(1.0_wp/3)
        rc%gamma = 3 + u - v
        rc%alpha = 3 - (u - v)/2
        rc%beta = sqrt(3.0_wp)*(u + v)/2

        ! eigenvectors: (A^-1 - lambda I) has rank 2, its null vector is the cross product of two rows
        rows = rc%a_inv
        do i = 1, 3
            rows(i, i) = rows(i, i) - rc%gamma
        end do
        rc%t(:, 1) = cross(rows(1, :), rows(2, :))
        lam = cmplx(rc%alpha, rc%beta, wp)
        rows_c = rc%a_inv
        do i = 1, 3
            rows_c(i, i) = rows_c(i, i) - lam
        end do
        vc = [rows_c(1, 2)*rows_c(2, 3) - rows_c(1, 3)*rows_c(2, 2), &
              rows_c(1, 3)*rows_c(2, 1) - rows_c(1, 1)*rows_c(2, 3), &
              rows_c(1, 1)*rows_c(2, 2) - rows_c(1, 2)*rows_c(2, 1)]
        rc%t(:, 2) = aimag(vc)
        rc%t(:, 3) = real(vc, wp)
        ! scaled: v_1 to unit length, the complex pair by one common factor (or the
        ! 2 x 2 block would no longer be [alpha, -beta; beta, alpha])
        rc%t(:, 1) = rc%t(:, 1)/norm2(rc%t(:, 1))
        rc%t(:, 2:3) = rc%t(:, 2:3)/norm2(rc%t(:, 2:3))
        rc%t_inv = inverse3(rc%t)

        ! the embedded formula: d/gamma0 = -(first column of V^-1), V(k+1, i) = c_i^k
        do k = 0, 2
            cv(k + 1, :) = rc%c**k
        end do
        w = inverse3(cv)
        d = -w(:, 1)
        rc%e = matmul(d, rc%a_inv)

        ! collocation polynomial: (c_i^k), k = 1..3, inverted
        do k = 1, 3
            cv(:, k) = rc%c**k
        end do
        rc%p = inverse3(cv)
    end function radau_iia_coefficients

    !> The inverse of a nonsingular 3 x 3 matrix by its cofactors.
    pure function inverse3(m) result(r)
        real(wp), intent(in) :: m(3, 3)   !! the matrix
        real(wp) :: r(3, 3)               !! its inverse
        real(wp) :: det
        r(:, 1) = cross(m(2, :), m(3, :))
        r(:, 2) = cross(m(3, :), m(1, :))
        r(:, 3) = cross(m(1, :), m(2, :))
        det = dot_product(m(1, :), r(:, 1))
        r = r/det
    end function inverse3

    pure function cross(x, y) result(z)
        real(wp), intent(in) :: x(:), y(:)   ! size 3 (assumed shape: matrix rows without copies)
        real(wp) :: z(3)
        z = [x(2)*y(3) - x(3)*y(2), x(3)*y(1) - x(1)*y(3), x(1)*y(2) - x(2)*y(1)]
    end function cross

end module regdae_radau_tableau
