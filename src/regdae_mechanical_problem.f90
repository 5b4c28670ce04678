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
!!
!! Structure (large problems): override `structure` to declare which entries of
!! M, G and of the force Jacobians may be nonzero (`mechanical_structure`), and
!! `mass_values` and `constraint_jacobian_values` to give M and G in pattern order
!! without dense matrices. The augmented formulation (option `formulation`) then
!! costs O(nonzeros) per residual and IDA's Newton matrix keeps the structure
!! (band or sparse linear solver). A problem that declares nothing is dense.
module regdae_mechanical_problem
    use regdae_kinds, only: wp
    use regdae_status, only: regdae_err_mass_matrix, regdae_err_structure, regdae_err_memory
    use regdae_lapack, only: dpotrf, dpotrs
    use regdae_small_cholesky, only: small_cholesky, small_cholesky_solve, small_n => small_cholesky_max
    use regdae_sparsity, only: sparsity_pattern, sparse_times, empty_pattern
    use regdae_second_order_problem, only: second_order_problem
    implicit none
    private

    !> Which entries of a mechanical problem's matrices may be nonzero. Nothing
    !! declared (the default) means dense.
    type, public :: mechanical_structure
        logical :: declared = .false.            !! the patterns below are set
        type(sparsity_pattern) :: mass           !! n x n: M(q)
        type(sparsity_pattern) :: constraint     !! m x n: G = dg/dq
        type(sparsity_pattern) :: force_q        !! n x n: d(f - M(q) a)/dq for any a (how forces and mass
                                                 !! depend on q); not set: empty (constant M, q-free forces)
        type(sparsity_pattern) :: force_v        !! n x n: df/dq'; not set: empty (velocity-free forces)
        logical :: curvature_supplied = .false.  !! the problem overrides `constraint_curvature` (used as is;
                                                 !! otherwise a difference quotient of the sparse G)
        logical :: mass_constant = .false.       !! M depends on neither q nor t (the work-energy balance then
                                                 !! takes dM/dt = 0 instead of a difference quotient of M, and
                                                 !! M is factored once per run; verified at init)
    end type mechanical_structure

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
        logical :: factor_fixed = .false.       ! M declared constant: the factor is kept for every (q, t)
    contains
        !> M(q, t), n x n, symmetric positive definite.
        procedure(mass_matrix_iface), deferred :: mass_matrix
        !> f(q, q', t), length n: applied and velocity-dependent forces.
        procedure(forces_iface), deferred :: forces
        !> f of the order-2 form: M^{-1} f.
        procedure :: rhs => mechanical_rhs
        !> B of the order-2 form: M^{-1} G^T.
        procedure :: matrix_b => mechanical_b
        !> B = M^{-1} G^T from a known G.
        procedure :: matrix_b_from_jacobian => mechanical_b_from_jacobian
        !> The declared structure; default: nothing declared (dense).
        procedure :: structure => default_structure
        !> The entries of M(q, t) in the order of `pattern`; default: from
        !! `mass_matrix`, refusing (regdae_err_structure) a nonzero outside the pattern.
        procedure :: mass_values => default_mass_values
        !> The entries of G(q, t) in the order of `pattern`; default: from
        !! `constraint_jacobian`, refusing a nonzero outside the pattern.
        procedure :: constraint_jacobian_values => default_constraint_jacobian_values
        !> Forget M's factor, and keep the next one for every (q, t) if the declared
        !! structure says M is constant (`mass_constant`); the solver calls it at init.
        procedure :: reset_mass_factor
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

    ! The default `mass_values` and `constraint_jacobian_values` (public from `regdae`:
    ! callable from an override, e.g. for the points where an analytic form is not at hand).
    public :: default_mass_values, default_constraint_jacobian_values
    public :: structured_velocity_constraint, complete_structure

contains

    function default_structure(self) result(st)
        class(mechanical_problem), intent(in) :: self
        type(mechanical_structure) :: st
        st%declared = .false.
    end function default_structure

    !> The default `mass_values`: M from `mass_matrix` (a dense n x n array, O(n^2)
    !! memory), gathered in the order of `pattern`; `stat = regdae_err_structure` when M
    !! has a nonzero outside the pattern. Callable from an override:
    !! `call default_mass_values(self, t, q, pattern, vals, stat)`.
    subroutine default_mass_values(self, t, q, pattern, vals, stat)
        class(mechanical_problem), intent(inout) :: self
        real(wp), intent(in) :: t, q(:)
        type(sparsity_pattern), intent(in) :: pattern   !! the declared pattern of M
        real(wp), intent(out) :: vals(:)                !! pattern%nnz() entries
        integer, intent(inout) :: stat
        real(wp), allocatable :: dense(:, :)
        allocate (dense(self%n, self%n))
        call self%mass_matrix(t, q, dense, stat)
        if (stat /= 0) return
        call gather(pattern, dense, vals, stat)
    end subroutine default_mass_values

    !> The default `constraint_jacobian_values`: G from `constraint_jacobian` (dense m x n),
    !! gathered in the order of `pattern`; `stat = regdae_err_structure` when G has a
    !! nonzero outside the pattern. Callable from an override.
    subroutine default_constraint_jacobian_values(self, t, q, pattern, vals, stat)
        class(mechanical_problem), intent(inout) :: self
        real(wp), intent(in) :: t, q(:)
        type(sparsity_pattern), intent(in) :: pattern   !! the declared pattern of G
        real(wp), intent(out) :: vals(:)                !! pattern%nnz() entries
        integer, intent(inout) :: stat
        real(wp), allocatable :: dense(:, :)
        allocate (dense(self%m, self%n))
        call self%constraint_jacobian(t, q, dense, stat)
        if (stat /= 0) return
        call gather(pattern, dense, vals, stat)
    end subroutine default_constraint_jacobian_values

    !> A declared structure whose `force_q` or `force_v` was never set (no `empty_pattern`
    !! or other constructor assigned to it: 0 x 0, no rows) gets the empty n x n pattern:
    !! no dependence, as the component's documentation says. `mass` and `constraint`
    !! have no such default (an unset one does not fit and is refused by name).
    subroutine complete_structure(st, n)
        type(mechanical_structure), intent(inout) :: st
        integer, intent(in) :: n   !! the coordinates
        if (.not. st%declared) return
        if (never_set(st%force_q)) st%force_q = empty_pattern(n, n)
        if (never_set(st%force_v)) st%force_v = empty_pattern(n, n)
    contains
        pure logical function never_set(p)
            type(sparsity_pattern), intent(in) :: p
            never_set = (p%nrows == 0 .and. p%ncols == 0 .and. .not. allocated(p%row_start))
        end function never_set
    end subroutine complete_structure

    !> The velocity constraint G(q, t) v + g_t(q, t) (length m) of a problem that
    !! declares its structure, from `constraint_jacobian_values` in O(nonzeros)
    !! memory; `pattern` is the declared pattern of G.
    subroutine structured_velocity_constraint(problem, pattern, t, q, v, val, stat)
        class(mechanical_problem), intent(inout) :: problem
        type(sparsity_pattern), intent(in) :: pattern
        real(wp), intent(in) :: t, q(:), v(:)
        real(wp), intent(out) :: val(:)
        integer, intent(inout) :: stat
        real(wp), allocatable :: gv(:)
        integer :: astat

        allocate (gv(pattern%nnz()), stat=astat)
        if (astat /= 0) then
            stat = regdae_err_memory
            return
        end if
        call problem%constraint_jacobian_values(t, q, pattern, gv, stat)
        if (stat /= 0) return
        call problem%constraint_dt(t, q, val, stat)
        if (stat /= 0) return
        val = val + sparse_times(pattern, gv, v)
    end subroutine structured_velocity_constraint

    ! The entries of a dense matrix in pattern order; stat = regdae_err_structure
    ! if a nonzero lies outside the pattern.
    subroutine gather(pattern, dense, vals, stat)
        type(sparsity_pattern), intent(in) :: pattern
        real(wp), intent(inout) :: dense(:, :)
        real(wp), intent(out) :: vals(:)
        integer, intent(inout) :: stat
        integer :: i, k
        do i = 1, pattern%nrows
            do k = pattern%row_start(i), pattern%row_start(i + 1) - 1
                vals(k) = dense(i, pattern%cols(k))
                dense(i, pattern%cols(k)) = 0.0_wp
            end do
        end do
        if (any(dense /= 0.0_wp)) stat = regdae_err_structure
    end subroutine gather

    ! Cholesky factor of M(q, t) (or of M^T M + mu I), reused while (t, q) is
    ! unchanged: `rhs` and `matrix_b` are evaluated at the same point.
    ! stat = regdae_err_mass_matrix if M is not symmetric positive definite (mu = 0).
    subroutine factor_mass(self, t, n, q, stat)
        class(mechanical_problem), intent(inout) :: self
        integer, intent(in) :: n   !! size(q)
        real(wp), intent(in) :: t, q(n)   ! (explicit shape: no strides in its loops)
        integer, intent(inout) :: stat
        real(wp), parameter :: symmetry_tol = 1.0e-12_wp
        integer :: info, i, astat
        logical :: ok

        if (self%have_factor .and. self%factor_fixed) return
        if (self%have_factor .and. self%factor_t == t) then
            if (same_point(n, self%factor_q, q)) return
        end if
        if (.not. allocated(self%factor)) then
            allocate (self%factor(n, n), self%factor_q(n), self%mass(n, n), self%gx_work(self%m, n), &
                      self%bt_work(n, self%m), stat=astat)
            if (astat /= 0) then
                if (allocated(self%factor)) deallocate (self%factor)
                if (allocated(self%factor_q)) deallocate (self%factor_q)
                if (allocated(self%mass)) deallocate (self%mass)
                if (allocated(self%gx_work)) deallocate (self%gx_work)
                if (allocated(self%bt_work)) deallocate (self%bt_work)
                stat = regdae_err_memory
                return
            end if
        end if
        self%have_factor = .false.
        call self%mass_matrix(t, q, self%mass, stat)
        if (stat /= 0) return
        if (self%mass_damping > 0.0_wp) then
            self%factor = matmul(transpose(self%mass), self%mass)
            do i = 1, n
                self%factor(i, i) = self%factor(i, i) + self%mass_damping
            end do
        else
            call copy_if_symmetric(n, self%mass, self%factor, symmetry_tol, ok)
            if (.not. ok) then
                stat = regdae_err_mass_matrix
                return
            end if
        end if
        if (n <= small_n) then
            call small_cholesky(n, self%factor, n, info)
        else
            call dpotrf('L', n, self%factor, n, info)
        end if
        if (info /= 0) then
            stat = regdae_err_mass_matrix
            return
        end if
        self%factor_t = t
        do i = 1, n   ! (a loop: memcpy's call cost more than the few entries)
            self%factor_q(i) = q(i)
        end do
        self%have_factor = .true.
    end subroutine factor_mass

    subroutine reset_mass_factor(self)
        class(mechanical_problem), intent(inout) :: self
        type(mechanical_structure) :: st
        st = self%structure()
        self%factor_fixed = st%declared .and. st%mass_constant
        self%have_factor = .false.
    end subroutine reset_mass_factor

    ! a == b entry by entry (a loop that stops at the first difference).
    pure logical function same_point(n, a, b)
        integer, intent(in) :: n
        real(wp), intent(in) :: a(n), b(n)
        integer :: i
        same_point = .false.
        do i = 1, n
            if (a(i) /= b(i)) return
        end do
        same_point = .true.
    end function same_point

    subroutine mechanical_rhs(self, t, x, v, val, stat)
        class(mechanical_problem), intent(inout) :: self
        real(wp), intent(in) :: t, x(:), v(:)
        real(wp), intent(out) :: val(:)
        integer, intent(inout) :: stat
        integer :: info
        call factor_mass(self, t, size(x), x, stat)
        if (stat /= 0) return
        call self%forces(t, x, v, val, stat)
        if (stat /= 0) return
        if (self%mass_damping > 0.0_wp) val = matmul(val, self%mass)   ! M^T f
        if (self%n <= small_n) then
            call small_cholesky_solve(self%n, self%factor, self%n, val)
        else
            call dpotrs('L', self%n, 1, self%factor, self%n, val, self%n, info)
        end if
    end subroutine mechanical_rhs

    subroutine mechanical_b(self, t, x, v, a, stat)
        class(mechanical_problem), intent(inout) :: self
        real(wp), intent(in) :: t, x(:), v(:)
        real(wp), intent(out) :: a(:, :)
        integer, intent(inout) :: stat
        call factor_mass(self, t, size(x), x, stat)   ! allocates gx_work on first use
        if (stat /= 0) return
        call self%constraint_jacobian(t, x, self%gx_work, stat)
        if (stat /= 0) return
        call mechanical_b_from_jacobian(self, t, x, v, self%gx_work, a, stat)
    end subroutine mechanical_b

    subroutine mechanical_b_from_jacobian(self, t, x, v, gx, a, stat)
        class(mechanical_problem), intent(inout) :: self
        real(wp), intent(in) :: t, x(:), v(:)
        real(wp), intent(in) :: gx(:, :)
        real(wp), intent(out) :: a(:, :)
        integer, intent(inout) :: stat
        integer :: info, j
        call factor_mass(self, t, size(x), x, stat)
        if (stat /= 0) return
        if (self%n <= small_n .and. .not. self%mass_damping > 0.0_wp) then
            ! B = M^-1 G^T column by column, directly in a.
            do j = 1, self%m
                a(:, j) = gx(j, :)
                call small_cholesky_solve(self%n, self%factor, self%n, a(:, j))
            end do
            return
        end if
        associate (bt => self%bt_work)
            do j = 1, self%m
                bt(:, j) = gx(j, :)
            end do
            if (self%mass_damping > 0.0_wp) bt = matmul(transpose(self%mass), bt)   ! M^T G^T
            if (self%n <= small_n) then
                do j = 1, self%m
                    call small_cholesky_solve(self%n, self%factor, self%n, bt(:, j))
                end do
            else
                call dpotrs('L', self%n, self%m, self%factor, self%n, bt, self%n, info)
            end if
            a(:, :) = bt
        end associate
    end subroutine mechanical_b_from_jacobian

    ! Copy A into l (the Cholesky factorizations read its lower triangle only: one
    ! copy of the whole matrix is cheaper than n copies of the triangle's columns)
    ! and check symmetry: ok = max |A - A^T| <= tol max |A| (false for NaN).
    pure subroutine copy_if_symmetric(n, a, l, tol, ok)
        integer, intent(in) :: n
        real(wp), intent(in) :: a(n, n), tol
        real(wp), intent(inout) :: l(n, n)
        logical, intent(out) :: ok
        integer :: i, j
        real(wp) :: amax, asym
        if (n == 2) then
            ! the loops below unrolled, in their order (the same maxima, NaN included)
            l(1, 1) = a(1, 1)
            l(2, 1) = a(2, 1)
            l(1, 2) = a(1, 2)
            l(2, 2) = a(2, 2)
            amax = max(0.0_wp, abs(a(1, 1)), abs(a(1, 1)))
            asym = max(0.0_wp, abs(a(1, 1) - a(1, 1)))
            amax = max(amax, abs(a(2, 1)), abs(a(1, 2)))
            asym = max(asym, abs(a(2, 1) - a(1, 2)))
            amax = max(amax, abs(a(2, 2)), abs(a(2, 2)))
            asym = max(asym, abs(a(2, 2) - a(2, 2)))
            ok = (asym <= tol*amax)
            return
        end if
        l(:, :) = a
        amax = 0.0_wp
        asym = 0.0_wp
        do j = 1, n
            do i = j, n
                amax = max(amax, abs(a(i, j)), abs(a(j, i)))
                asym = max(asym, abs(a(i, j) - a(j, i)))
            end do
        end do
        ok = (asym <= tol*amax)
    end subroutine copy_if_symmetric

end module regdae_mechanical_problem
