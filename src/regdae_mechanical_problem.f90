!> Constrained mechanical systems (paper, eq. 1.2 / 4.9):
!! $$ M(q)\,q'' = f(q, q', t) + G^T \lambda, \qquad 0 = g(q, t). $$
!!
!! Extend `mechanical_problem`, set `n` (coordinates) and `m` (constraints), and
!! implement `mass_matrix`, `forces`, `constraint` and `constraint_jacobian`
!! (optionally `constraint_dt` and `constraint_curvature`, as for a
!! `second_order_problem`). regdae forms the order-2 Hessenberg form
!! q'' = M^{-1} f - B y with B = M^{-1} G^T and y = -lambda, factoring M once
!! per evaluation point by Cholesky (`dpotrf`); M must be symmetric positive
!! definite. The solver reports lambda, in this type's sign convention.
!!
!! With `mass_damping` mu > 0 (solver option `mass_damping`) M may be singular
!! (a massless coordinate, section 4.3): regdae uses (4.11),
!! (M^T M + mu I) q'' = M^T f + M^T G^T lambda, i.e. f~ = (M^T M + mu I)^{-1} M^T f and
!! B = (M^T M + mu I)^{-1} M^T G^T. Note what this does: q'' lies in the range of
!! M^T, so a coordinate without mass gets no acceleration from it.
module regdae_mechanical_problem
    use regdae_kinds, only: wp
    use regdae_status, only: regdae_err_mass_matrix
    use regdae_lapack, only: dpotrf, dpotrs
    use regdae_second_order_problem, only: second_order_problem
    implicit none
    private

    ! Up to this size M is factored by the loops below instead of LAPACK, whose
    ! call overhead dominates for a handful of coordinates.
    integer, parameter :: small_n = 8

    !> Abstract constrained mechanical system.
    type, abstract, extends(second_order_problem), public :: mechanical_problem
        private
        real(wp), public :: mass_damping = 0.0_wp   !! mu of (4.11); 0: M must be SPD (set by the solver)
        real(wp), allocatable :: mass(:, :)     ! M at (factor_t, factor_q), kept when mu > 0
        real(wp), allocatable :: gx_work(:, :), bt_work(:, :)   ! scratch of matrix_b: G, B
        real(wp), allocatable :: factor(:, :)   ! Cholesky factor of M (mu = 0) or M^T M + mu I
        real(wp), allocatable :: factor_q(:)
        real(wp) :: factor_t = 0.0_wp
        logical :: have_factor = .false.
    contains
        !> M(q, t), n x n, symmetric positive definite.
        procedure(mass_matrix_iface), deferred :: mass_matrix
        !> f(q, q', t), length n: applied and velocity-dependent forces.
        procedure(forces_iface), deferred :: forces
        !> f of the order-2 form: M^{-1} f.
        procedure :: rhs => mechanical_rhs
        !> B of the order-2 form: M^{-1} G^T.
        procedure :: matrix_b => mechanical_b
    end type mechanical_problem

    abstract interface
        subroutine mass_matrix_iface(self, t, q, mass, stat)
            import :: mechanical_problem, wp
            class(mechanical_problem), intent(inout) :: self
            real(wp), intent(in) :: t, q(:)
            real(wp), intent(out) :: mass(:, :)   !! n x n
            integer, intent(inout) :: stat
        end subroutine mass_matrix_iface

        subroutine forces_iface(self, t, q, qd, f, stat)
            import :: mechanical_problem, wp
            class(mechanical_problem), intent(inout) :: self
            real(wp), intent(in) :: t, q(:), qd(:)
            real(wp), intent(out) :: f(:)          !! length n
            integer, intent(inout) :: stat
        end subroutine forces_iface
    end interface

contains

    ! Cholesky factor of M(q, t) (or of M^T M + mu I), reused while (t, q) is
    ! unchanged: `rhs` and `matrix_b` are evaluated at the same point.
    ! stat = regdae_err_mass_matrix if M is not symmetric positive definite (mu = 0).
    subroutine factor_mass(self, t, q, stat)
        class(mechanical_problem), intent(inout) :: self
        real(wp), intent(in) :: t, q(:)
        integer, intent(inout) :: stat
        real(wp), parameter :: symmetry_tol = 1.0e-12_wp
        integer :: info, n, i

        n = size(q)
        if (self%have_factor) then
            if (self%factor_t == t .and. all(self%factor_q == q)) return
        end if
        if (.not. allocated(self%factor)) allocate (self%factor(n, n), self%factor_q(n), self%mass(n, n), &
                                                    self%gx_work(self%m, n), self%bt_work(n, self%m))
        self%have_factor = .false.
        call self%mass_matrix(t, q, self%mass, stat)
        if (stat /= 0) return
        if (self%mass_damping > 0.0_wp) then
            self%factor = matmul(transpose(self%mass), self%mass)
            do i = 1, n
                self%factor(i, i) = self%factor(i, i) + self%mass_damping
            end do
        else
            if (.not. symmetric(self%mass, symmetry_tol)) then
                stat = regdae_err_mass_matrix
                return
            end if
            self%factor = self%mass
        end if
        if (n <= small_n) then
            call small_cholesky(self%factor, info)
        else
            call dpotrf('L', n, self%factor, n, info)
        end if
        if (info /= 0) then
            stat = regdae_err_mass_matrix
            return
        end if
        self%factor_t = t
        self%factor_q = q
        self%have_factor = .true.
    end subroutine factor_mass

    subroutine mechanical_rhs(self, t, x, v, val, stat)
        class(mechanical_problem), intent(inout) :: self
        real(wp), intent(in) :: t, x(:), v(:)
        real(wp), intent(out) :: val(:)
        integer, intent(inout) :: stat
        integer :: info
        call factor_mass(self, t, x, stat)
        if (stat /= 0) return
        call self%forces(t, x, v, val, stat)
        if (stat /= 0) return
        if (self%mass_damping > 0.0_wp) val = matmul(val, self%mass)   ! M^T f
        if (self%n <= small_n) then
            call small_cholesky_solve(self%factor, val)
        else
            call dpotrs('L', self%n, 1, self%factor, self%n, val, self%n, info)
        end if
    end subroutine mechanical_rhs

    subroutine mechanical_b(self, t, x, v, a, stat)
        class(mechanical_problem), intent(inout) :: self
        real(wp), intent(in) :: t, x(:), v(:)
        real(wp), intent(out) :: a(:, :)
        integer, intent(inout) :: stat
        integer :: info, j
        call factor_mass(self, t, x, stat)
        if (stat /= 0) return
        associate (gx => self%gx_work, bt => self%bt_work)
            call self%constraint_jacobian(t, x, gx, stat)
            if (stat /= 0) return
            bt = transpose(gx)
            if (self%mass_damping > 0.0_wp) bt = matmul(transpose(self%mass), bt)   ! M^T G^T
            if (self%n <= small_n) then
                do j = 1, self%m
                    call small_cholesky_solve(self%factor, bt(:, j))
                end do
            else
                call dpotrs('L', self%n, self%m, self%factor, self%n, bt, self%n, info)
            end if
            a = bt
        end associate
    end subroutine mechanical_b

    ! max |A - A^T| <= tol max |A|, without a temporary.
    pure logical function symmetric(a, tol)
        real(wp), intent(in) :: a(:, :), tol
        integer :: i, j
        real(wp) :: bound
        bound = tol*maxval(abs(a))
        symmetric = .true.
        do j = 1, size(a, 2)
            do i = j + 1, size(a, 1)
                if (abs(a(i, j) - a(j, i)) > bound) symmetric = .false.
            end do
        end do
    end function symmetric

    ! In-place Cholesky factor L (lower triangle) of a small SPD matrix; info > 0
    ! if it is not positive definite.
    pure subroutine small_cholesky(a, info)
        real(wp), intent(inout) :: a(:, :)
        integer, intent(out) :: info
        integer :: j, n
        n = size(a, 1)
        info = 0
        do j = 1, n
            a(j, j) = a(j, j) - sum(a(j, 1:j - 1)**2)
            if (.not. (a(j, j) > 0.0_wp)) then
                info = j
                return
            end if
            a(j, j) = sqrt(a(j, j))
            a(j + 1:n, j) = (a(j + 1:n, j) - matmul(a(j + 1:n, 1:j - 1), a(j, 1:j - 1)))/a(j, j)
        end do
    end subroutine small_cholesky

    ! Solve L L^T x = b in place with the factor of `small_cholesky`.
    pure subroutine small_cholesky_solve(l, b)
        real(wp), intent(in) :: l(:, :)
        real(wp), intent(inout) :: b(:)
        integer :: j, n
        n = size(b)
        do j = 1, n
            b(j) = (b(j) - dot_product(l(j, 1:j - 1), b(1:j - 1)))/l(j, j)
        end do
        do j = n, 1, -1
            b(j) = (b(j) - dot_product(l(j + 1:n, j), b(j + 1:n)))/l(j, j)
        end do
    end subroutine small_cholesky_solve

end module regdae_mechanical_problem
