!> The regularized systems of sections 2 and 4 of the paper, independent of
!! the integrator.
!!
!! Order 1 (index 2, eq. 2.1): state z = x, x' = f(x, t) - B y, 0 = g(x, t), and
!! $$ r = G f + g_t + \gamma g. $$
!! Order m >= 3 (eq. 4.12): z = (x, ..., x^(m-1)) and r = G f + sum_k w_k G x^(k) + w_1 g_t
!! + w_0 g with the Taylor weights w_k = m!/(k! h^(m-k)) (eq. 4.16).
!! Order 2 (index 3, eq. 4.1): state z = (x, v), x' = v, v' = f(x, v, t) - B y,
!! 0 = g(x, t), and (paper, 4.4-4.8, with gamma0 = 2/h^2, gamma1 = 2/h)
!! $$ r = G f + \gamma_1 (G v + g_t) + \gamma_0 g \; [+\, c], $$
!! where the optional curvature term c = g_xx(v, v) + 2 g_xt v + g_tt completes
!! d^2 g/dt^2 (option `curvature`): with it the regularized system is exact
!! wherever GB is invertible, like Baumgarte's.
!!
!! The multiplier of each method solves
!! - Baumgarte (2.7 / 4.4):  GB y = r                           (LU);
!! - trust region (2.10 / 4.6): ((GB)^T GB + eps I) y = (GB)^T r;
!! - direct (2.12 / 4.8):    (GB + eps I) y = r, GB symmetric PSD (Cholesky).
!! The residuals IDA integrates are the eliminated form (y(z) solved inside) and
!! the multiplier form with (z, y) as unknowns, whose algebraic rows are the
!! regularized equations themselves (Baumgarte: r - G f with G v' in place of G f).
module regdae_regularization
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
    use regdae_kinds, only: wp
    use regdae_format, only: format_real, format_int
    use regdae_status, only: regdae_success, regdae_err_user_callback, regdae_err_nonfinite, &
                             regdae_err_not_psd, regdae_err_singular, regdae_err_mass_matrix, status_message
    use regdae_problem, only: dae_problem
    use regdae_second_order_problem, only: second_order_problem
    use regdae_higher_order_problem, only: higher_order_problem, taylor_weights
    use regdae_options, only: solver_options, method_baumgarte, method_trust_region, method_direct
    use regdae_damped_lsq, only: damped_lsq_workspace, damped_lsq_solve, shifted_spd_solve, square_solve
    implicit none
    private

    !> A problem with its regularization: the pieces at the last evaluated point
    !! and the scratch space of the multiplier solves.
    type, public :: regularized_dae
        class(dae_problem), allocatable :: first            !! order-1 problem (a copy), or
        class(second_order_problem), allocatable :: second  !! order-2 problem (a copy), or
        class(higher_order_problem), allocatable :: higher  !! order >= 3 problem (a copy)
        integer :: order = 1        !! 1 (index 2), 2 (index 3), m (index m + 1)
        integer :: n = 0            !! size of x
        integer :: m = 0            !! number of constraints
        integer :: method = method_trust_region
        integer :: lsq = 0          !! `lsq_normal` or `lsq_stacked` (resolved)
        real(wp), allocatable :: w(:)   !! w(k+1): weight of G x^(k) (k = 0: of g; w(2) also of g_t)
        real(wp) :: eps = 0.0_wp    !! damping
        logical :: curvature = .false.  !! add c to r (order 2)
        real(wp), allocatable :: f(:)        !! f, n
        real(wp), allocatable :: b(:, :)     !! B, n x m
        real(wp), allocatable :: g(:)        !! g, m
        real(wp), allocatable :: gx(:, :)    !! G = g_x, m x n
        real(wp), allocatable :: gt(:)       !! g_t, m
        real(wp), allocatable :: curv(:)     !! c (order 2 with curvature), m
        real(wp), allocatable :: gb(:, :)    !! G B, m x m
        real(wp), allocatable :: r(:)        !! right-hand side of the multiplier equation, m
        real(wp), allocatable :: q(:)        !! scratch: r - G f, m
        type(damped_lsq_workspace) :: lsq_ws
        character(len=:), allocatable :: message  !! details of the last failure
    contains
        !> Take an order-1 problem.
        procedure :: init_first_order
        !> Take an order-2 problem.
        procedure :: init_second_order
        !> Take a problem of order >= 3.
        procedure :: init_higher_order
        !> Evaluate f, B, g, G, g_t (c), GB and r at (t, z).
        procedure :: evaluate
        !> Multiplier y from the pieces of the last `evaluate`.
        procedure :: solve_multiplier
        !> Smallest singular value of GB from the last `evaluate`.
        procedure :: sigma_min_gb
        !> Residual of the eliminated formulation, unknowns z.
        procedure :: residual_eliminated
        !> Residual of the multiplier formulation, unknowns (z, y).
        procedure :: residual_multiplier
        procedure, private :: allocate_pieces, constraint_terms, dynamics_residual, release
    end type regularized_dae

contains

    subroutine init_first_order(self, problem, opts, lsq)
        class(regularized_dae), intent(inout) :: self
        class(dae_problem), intent(in) :: problem    !! copied into self
        type(solver_options), intent(in) :: opts
        integer, intent(in) :: lsq                   !! resolved least-squares method
        call self%release()
        allocate (self%first, source=problem)
        self%order = 1
        self%w = [opts%gamma]
        self%curvature = .false.
        call self%allocate_pieces(problem%n, problem%m, opts, lsq)
    end subroutine init_first_order

    subroutine init_second_order(self, problem, opts, lsq)
        class(regularized_dae), intent(inout) :: self
        class(second_order_problem), intent(in) :: problem    !! copied into self
        type(solver_options), intent(in) :: opts
        integer, intent(in) :: lsq
        call self%release()
        allocate (self%second, source=problem)
        self%order = 2
        self%w = [opts%gamma0, opts%gamma1]
        self%curvature = opts%curvature
        call self%allocate_pieces(problem%n, problem%m, opts, lsq)
    end subroutine init_second_order

    subroutine init_higher_order(self, problem, opts, lsq)
        class(regularized_dae), intent(inout) :: self
        class(higher_order_problem), intent(in) :: problem    !! copied into self
        type(solver_options), intent(in) :: opts
        integer, intent(in) :: lsq
        call self%release()
        allocate (self%higher, source=problem)
        self%order = problem%order
        self%w = taylor_weights(problem%order, opts%taylor_h)
        self%curvature = .false.
        call self%allocate_pieces(problem%n, problem%m, opts, lsq)
    end subroutine init_higher_order

    subroutine release(self)
        class(regularized_dae), intent(inout) :: self
        if (allocated(self%first)) deallocate (self%first)
        if (allocated(self%second)) deallocate (self%second)
        if (allocated(self%higher)) deallocate (self%higher)
    end subroutine release

    subroutine allocate_pieces(self, n, m, opts, lsq)
        class(regularized_dae), intent(inout) :: self
        integer, intent(in) :: n, m, lsq
        type(solver_options), intent(in) :: opts
        self%n = n
        self%m = m
        self%method = opts%method
        self%lsq = lsq
        self%eps = opts%eps
        if (allocated(self%f)) deallocate (self%f, self%b, self%g, self%gx, self%gt, self%curv, self%gb, self%r, self%q)
        allocate (self%f(n), self%b(n, m), self%g(m), self%gx(m, n), self%gt(m), self%curv(m), self%gb(m, m), &
                  self%r(m), self%q(m), source=0.0_wp)
        call self%lsq_ws%init(m, m)
        self%message = ''
    end subroutine allocate_pieces

    !> Evaluate the pieces at (t, z). A failing user routine gives
    !! `regdae_err_user_callback` (or `regdae_err_mass_matrix`) with the user's
    !! sign in `recoverable`; a NaN or Inf gives `regdae_err_nonfinite` (recoverable).
    subroutine evaluate(self, t, z, stat, recoverable)
        class(regularized_dae), intent(inout) :: self
        real(wp), intent(in) :: t       !! time
        real(wp), intent(in) :: z(:)    !! state: x (order 1) or (x, v) (order 2)
        integer, intent(out) :: stat
        logical, intent(out) :: recoverable   !! may a smaller step help?
        integer :: ustat, n

        stat = regdae_success
        recoverable = .true.
        ustat = 0
        n = self%n
        if (self%order == 1) then
            call self%first%rhs(t, z, self%f, ustat)
            if (failed('rhs')) return
            call self%first%matrix_b(t, z, self%b, ustat)
            if (failed('matrix_b')) return
            call self%first%constraint(t, z, self%g, ustat)
            if (failed('constraint')) return
            call self%first%constraint_jacobian(t, z, self%gx, ustat)
            if (failed('constraint_jacobian')) return
            call self%first%constraint_dt(t, z, self%gt, ustat)
            if (failed('constraint_dt')) return
        else if (self%order >= 3) then
            call self%higher%rhs(t, reshape(z(1:self%order*n), [n, self%order]), self%f, ustat)
            if (failed('rhs')) return
            call self%higher%matrix_b(t, reshape(z(1:self%order*n), [n, self%order]), self%b, ustat)
            if (failed('matrix_b')) return
            call self%higher%constraint(t, z(1:n), self%g, ustat)
            if (failed('constraint')) return
            call self%higher%constraint_jacobian(t, z(1:n), self%gx, ustat)
            if (failed('constraint_jacobian')) return
            call self%higher%constraint_dt(t, z(1:n), self%gt, ustat)
            if (failed('constraint_dt')) return
        else
            call self%second%rhs(t, z(1:n), z(n + 1:2*n), self%f, ustat)
            if (failed('rhs')) return
            call self%second%matrix_b(t, z(1:n), z(n + 1:2*n), self%b, ustat)
            if (failed('matrix_b')) return
            call self%second%constraint(t, z(1:n), self%g, ustat)
            if (failed('constraint')) return
            call self%second%constraint_jacobian(t, z(1:n), self%gx, ustat)
            if (failed('constraint_jacobian')) return
            call self%second%constraint_dt(t, z(1:n), self%gt, ustat)
            if (failed('constraint_dt')) return
            if (self%curvature) then
                call self%second%constraint_curvature(t, z(1:n), z(n + 1:2*n), self%curv, ustat)
                if (failed('constraint_curvature')) return
            end if
        end if
        if (.not. (all(ieee_is_finite(self%f)) .and. all(ieee_is_finite(self%b)) .and. &
                   all(ieee_is_finite(self%g)) .and. all(ieee_is_finite(self%gx)) .and. &
                   all(ieee_is_finite(self%gt)) .and. all(ieee_is_finite(self%curv)))) then
            stat = regdae_err_nonfinite
            self%message = 'NaN or Inf in f, B, g, G, g_t or c at t = '//format_real(t)
            return
        end if
        self%gb = matmul(self%gx, self%b)
        call self%constraint_terms(z, self%q)
        self%r = matmul(self%gx, self%f) + self%q
    contains
        logical function failed(name)
            character(len=*), intent(in) :: name
            failed = (ustat /= 0)
            if (.not. failed) return
            recoverable = (ustat > 0)
            if (ustat == regdae_err_mass_matrix) then
                stat = regdae_err_mass_matrix
                self%message = status_message(stat)//' at t = '//format_real(t)//' (in '//name//')'
            else
                stat = regdae_err_user_callback
                self%message = 'user routine '//name//' reported failure (stat = '// &
                               format_int(ustat)//') at t = '//format_real(t)
            end if
        end function failed
    end subroutine evaluate

    ! q = r - G f = w0 g + w1 g_t + sum_{k=1}^{m-1} w_k G x^(k) [+ c] (order 1: g_t with weight 1).
    subroutine constraint_terms(self, z, q)
        class(regularized_dae), intent(in) :: self
        real(wp), intent(in) :: z(:)
        real(wp), intent(out) :: q(:)
        integer :: k, n
        n = self%n
        if (self%order == 1) then
            q = self%w(1)*self%g + self%gt
        else
            q = self%w(1)*self%g + self%w(2)*self%gt
            do k = 1, self%order - 1
                q = q + self%w(k + 1)*matmul(self%gx, z(k*n + 1:(k + 1)*n))
            end do
            if (self%curvature) q = q + self%curv
        end if
    end subroutine constraint_terms

    !> The multiplier of the chosen regularization from the last `evaluate`.
    !! Failures: `regdae_err_not_psd` (direct, GB not symmetric PSD),
    !! `regdae_err_singular` (Baumgarte with singular GB, or eps = 0 with the
    !! normal equations).
    subroutine solve_multiplier(self, t, y, stat)
        class(regularized_dae), intent(inout) :: self
        real(wp), intent(in) :: t       !! time (for messages)
        real(wp), intent(out) :: y(:)   !! multiplier, length m
        integer, intent(out) :: stat

        select case (self%method)
        case (method_trust_region)
            call damped_lsq_solve(self%lsq_ws, self%gb, self%r, self%eps, self%lsq, y, stat)
        case (method_direct)
            call shifted_spd_solve(self%lsq_ws, self%gb, self%r, self%eps, y, stat)
        case default
            call square_solve(self%lsq_ws, self%gb, self%r, y, stat)
        end select
        if (stat == regdae_success) then
            if (.not. all(ieee_is_finite(y))) stat = regdae_err_nonfinite
        end if
        select case (stat)
        case (regdae_success)
        case (regdae_err_not_psd)
            self%message = 'method=direct: GB + eps I is not symmetric positive definite at t = '// &
                           format_real(t)//' (GB must be symmetric positive semidefinite, as for '// &
                           'B = M^-1 G^T; use method=trust_region)'
        case (regdae_err_singular)
            self%message = 'singular matrix in the multiplier equation at t = '//format_real(t)
            if (self%method == method_baumgarte) self%message = 'method=baumgarte: GB is singular at t = '// &
                                                                format_real(t)
        case default
            self%message = status_message(stat)//' in the multiplier solve at t = '//format_real(t)
        end select
    end subroutine solve_multiplier

    !> sigma_min(GB) at the last evaluated point.
    function sigma_min_gb(self) result(sigma)
        class(regularized_dae), intent(inout) :: self
        real(wp) :: sigma
        sigma = self%lsq_ws%smallest_singular_value(self%gb)
    end function sigma_min_gb

    !> Eliminated formulation: res = z' - (v, f - B y(z)) (order 2) or
    !! x' - f + B y(x) (order 1), y from `solve_multiplier`.
    subroutine residual_eliminated(self, t, z, zp, res, y, stat, recoverable)
        class(regularized_dae), intent(inout) :: self
        real(wp), intent(in) :: t, z(:), zp(:)
        real(wp), intent(out) :: res(:)   !! residual, length of z
        real(wp), intent(out) :: y(:)     !! multiplier used, length m
        integer, intent(out) :: stat
        logical, intent(out) :: recoverable

        call self%evaluate(t, z, stat, recoverable)
        if (stat /= regdae_success) return
        call self%solve_multiplier(t, y, stat)
        if (stat /= regdae_success) then
            ! A singular GB (Baumgarte) may be avoided by a smaller step; a GB that
            ! is not PSD is a property of the problem.
            recoverable = (stat == regdae_err_singular .or. stat == regdae_err_nonfinite)
            return
        end if
        call self%dynamics_residual(z, zp, y, res)
    end subroutine residual_eliminated

    ! The differential rows: x^(k)' - x^(k+1) for k < m-1, and x^(m-1)' - f + B y.
    subroutine dynamics_residual(self, z, zp, y, res)
        class(regularized_dae), intent(in) :: self
        real(wp), intent(in) :: z(:), zp(:), y(:)
        real(wp), intent(out) :: res(:)
        integer :: k, n, last
        n = self%n
        do k = 0, self%order - 2
            res(k*n + 1:(k + 1)*n) = zp(k*n + 1:(k + 1)*n) - z((k + 1)*n + 1:(k + 2)*n)
        end do
        last = (self%order - 1)*n
        res(last + 1:last + n) = zp(last + 1:last + n) - self%f + matmul(self%b, y)
    end subroutine dynamics_residual

    !> Multiplier formulation: the differential rows with the given y, and
    !! res_y the regularized equation (trust region: (GB)^T (GB y - r) + eps y;
    !! direct: (GB + eps I) y - r; Baumgarte: r - G f + G (last block of z')).
    subroutine residual_multiplier(self, t, z, y, zp, res_z, res_y, stat, recoverable)
        class(regularized_dae), intent(inout) :: self
        real(wp), intent(in) :: t, z(:), y(:), zp(:)
        real(wp), intent(out) :: res_z(:)   !! length of z
        real(wp), intent(out) :: res_y(:)   !! length m
        integer, intent(out) :: stat
        logical, intent(out) :: recoverable
        real(wp), parameter :: psd_tol = 1.0e-8_wp
        integer :: i, n

        call self%evaluate(t, z, stat, recoverable)
        if (stat /= regdae_success) return
        call self%dynamics_residual(z, zp, y, res_z)
        n = self%n
        select case (self%method)
        case (method_trust_region)
            res_y = matmul(matmul(self%gb, y) - self%r, self%gb) + self%eps*y
        case (method_direct)
            ! Necessary conditions for GB symmetric PSD, cheap enough for every
            ! residual: symmetry and a nonnegative diagonal.
            if (maxval(abs(self%gb - transpose(self%gb))) > psd_tol*maxval(abs(self%gb)) &
                .or. any([(self%gb(i, i), i=1, self%m)] < -psd_tol*maxval(abs(self%gb)))) then
                stat = regdae_err_not_psd
                recoverable = .false.
                self%message = 'method=direct: GB is not symmetric positive semidefinite at t = '// &
                               format_real(t)//' (use method=trust_region)'
                return
            end if
            res_y = matmul(self%gb, y) + self%eps*y - self%r
        case default
            call self%constraint_terms(z, self%q)
            res_y = self%q + matmul(self%gx, zp((self%order - 1)*n + 1:self%order*n))
        end select
    end subroutine residual_multiplier

end module regdae_regularization
