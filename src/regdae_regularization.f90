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
!! What the monitor and the checks ask of the model (drift, invariant, sigma_min(GB),
!! work): submodule `regdae_regularization_queries`.
module regdae_regularization
    use regdae_kinds, only: wp
    use regdae_format, only: format_real, format_int
    use regdae_status, only: regdae_success, regdae_err_user_callback, regdae_err_nonfinite, &
                             regdae_err_not_psd, regdae_err_singular, regdae_err_mass_matrix, regdae_err_memory, &
                             status_message
    use regdae_problem, only: dae_problem
    use regdae_second_order_problem, only: second_order_problem
    use regdae_higher_order_problem, only: higher_order_problem, taylor_weights
    use regdae_options, only: solver_options, method_baumgarte, method_trust_region, method_direct, option_auto
    use regdae_damped_lsq, only: damped_lsq_workspace, damped_lsq_solve, shifted_spd_solve, square_solve
    use regdae_mechanical_problem, only: mechanical_problem
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
        integer :: lsq = 0          !! `lsq_normal`, `lsq_stacked` or `lsq_checked` (resolved)
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
        !> max |g(x, t)| of the position constraint at the last evaluated point,
        !! for models of a second-order problem (index 3: the model's g; index 2:
        !! the wrapped problem's g, which that formulation does not enforce); -1
        !! for a first-order problem.
        procedure :: position_drift
        !> The second-order problem's invariant I(x, v, t) at z = (x, v, ...), NaN if
        !! it has none or the problem is of order 1.
        procedure :: invariant_value
        !> Mechanical problems (index 3, or index 2 through the velocity constraint):
        !! the kinetic energy and the power of the applied forces at the last
        !! evaluated point (regdae_work_energy); stat /= 0 for other problems.
        procedure :: work_sample
        !> Whether the problem is a mechanical one (the work-energy check applies).
        procedure :: is_mechanical
        !> The mechanical problem behind the model (null for other problems).
        procedure :: mechanical
        !> G = dg/dx of the user's position constraint at (t, x).
        procedure :: position_jacobian
        !> f alone at (t, z) (order 2: the acceleration of the applied forces, M^-1 f for a
        !! mechanical problem; order 1: x' without the multiplier), the model's pieces untouched.
        procedure :: free_slope
        !> sigma_min(GB) at the last evaluated point with G replaced by a given
        !! position Jacobian (B from it, as the problem builds B from G).
        procedure :: conditioning_with
        !> From on = .true. to .false.: the problem's f at points near z (the perturbed
        !! points of a difference-quotient Jacobian) from the user's Jacobian of f at
        !! (t, z), where the problem has one (`linearize_rhs` of the problem).
        procedure :: linearize_rhs
        !> The components of the state z that must stay >= 0 (`nonnegative` of the
        !! problem: x, none of v = x'); length order * n.
        procedure :: nonnegative_state
        !> Residual of the eliminated formulation, unknowns z.
        procedure :: residual_eliminated
        !> The eliminated formulation's right-hand side F (z' = F(z, t)).
        procedure :: slope_eliminated
        !> Residual of the multiplier formulation, unknowns (z, y).
        procedure :: residual_multiplier
        procedure, private :: allocate_pieces, constraint_terms, release
        !> F(z) at the last evaluated point for a given y: (x', ..., f - B y).
        procedure :: dynamics_slope
    end type regularized_dae

    ! What the monitor and the checks ask of the model (submodule regdae_regularization_queries).
    interface
        module function position_drift(self, t, z, stat) result(drift)
            class(regularized_dae), intent(inout) :: self
            real(wp), intent(in) :: t, z(:)   !! the last evaluated point
            integer, intent(out) :: stat      !! the user routine's status (index 2)
            real(wp) :: drift
        end function position_drift

        module function invariant_value(self, t, z, stat) result(val)
            class(regularized_dae), intent(inout) :: self
            real(wp), intent(in) :: t, z(:)
            integer, intent(out) :: stat
            real(wp) :: val
        end function invariant_value

        !> G of the user's position constraint at (t, x) (for a second-order problem
        !! integrated at index 2: of its g, not of the velocity constraint).
        module subroutine position_jacobian(self, t, x, gx, stat)
            class(regularized_dae), intent(inout) :: self
            real(wp), intent(in) :: t, x(:)
            real(wp), intent(out) :: gx(:, :)
            integer, intent(out) :: stat
        end subroutine position_jacobian

        module subroutine free_slope(self, t, z, f, stat)
            class(regularized_dae), intent(inout) :: self
            real(wp), intent(in) :: t, z(:)
            real(wp), intent(out) :: f(:)    !! length n (the model's f)
            integer, intent(out) :: stat
        end subroutine free_slope

        module function conditioning_with(self, t, z, gx, stat) result(sigma)
            class(regularized_dae), intent(inout) :: self
            real(wp), intent(in) :: t, z(:)     !! the last evaluated point
            real(wp), intent(in) :: gx(:, :)    !! a position Jacobian, m x n of the user's problem
            integer, intent(out) :: stat
            real(wp) :: sigma
        end function conditioning_with

        module logical function is_mechanical(self)
            class(regularized_dae), intent(in) :: self
        end function is_mechanical

        !> The mechanical problem behind the model (order 2, or under the velocity form of
        !! index 2), null for other problems. A pointer into the model: the caller's model
        !! must be a target, and the pointer is not kept beyond the caller's use of it.
        module function mechanical(self) result(problem)
            class(regularized_dae), intent(in), target :: self
            class(mechanical_problem), pointer :: problem
        end function mechanical

        module subroutine work_sample(self, t, z, kinetic, power, stat, sums)
            class(regularized_dae), intent(inout), target :: self
            real(wp), intent(in) :: t, z(:)     !! the last evaluated point
            real(wp), intent(out) :: kinetic, power
            integer, intent(out) :: stat
            real(wp), intent(out), optional :: sums(2)   !! see kinetic_energy_and_power
        end subroutine work_sample

        !> sigma_min(GB) at the last evaluated point.
        module function sigma_min_gb(self) result(sigma)
            class(regularized_dae), intent(inout) :: self
            real(wp) :: sigma
        end function sigma_min_gb
    end interface

contains

    subroutine init_first_order(self, problem, opts, lsq, stat)
        class(regularized_dae), intent(inout) :: self
        class(dae_problem), intent(in) :: problem    !! copied into self
        type(solver_options), intent(in) :: opts
        integer, intent(in) :: lsq                   !! resolved least-squares method
        integer, intent(out), optional :: stat       !! regdae_err_memory: the dense pieces did not fit
        call self%release()
        allocate (self%first, source=problem)
        self%order = 1
        self%w = [provisional(opts%gamma)]
        self%curvature = .false.
        call self%allocate_pieces(problem%n, problem%m, opts, lsq, stat)
    end subroutine init_first_order

    subroutine init_second_order(self, problem, opts, lsq, stat)
        class(regularized_dae), intent(inout) :: self
        class(second_order_problem), intent(in) :: problem    !! copied into self
        type(solver_options), intent(in) :: opts
        integer, intent(in) :: lsq
        integer, intent(out), optional :: stat
        call self%release()
        allocate (self%second, source=problem)
        self%order = 2
        self%w = [provisional(opts%gamma0), provisional(opts%gamma1)]
        self%curvature = opts%curvature
        call self%allocate_pieces(problem%n, problem%m, opts, lsq, stat)
    end subroutine init_second_order

    subroutine init_higher_order(self, problem, opts, lsq, stat)
        class(regularized_dae), intent(inout) :: self
        class(higher_order_problem), intent(in) :: problem    !! copied into self
        type(solver_options), intent(in) :: opts
        integer, intent(in) :: lsq
        integer, intent(out), optional :: stat
        call self%release()
        allocate (self%higher, source=problem)
        self%order = problem%order
        self%w = taylor_weights(problem%order, opts%taylor_h)
        self%curvature = .false.
        call self%allocate_pieces(problem%n, problem%m, opts, lsq, stat)
    end subroutine init_higher_order

    ! An `auto` weight is 1 until the solver resolves it (at a consistent start
    ! the weighted terms vanish: the resolution's evaluation does not depend on it).
    pure real(wp) function provisional(x)
        real(wp), intent(in) :: x
        provisional = x
        if (x == option_auto) provisional = 1.0_wp
    end function provisional

    subroutine release(self)
        class(regularized_dae), intent(inout) :: self
        if (allocated(self%first)) deallocate (self%first)
        if (allocated(self%second)) deallocate (self%second)
        if (allocated(self%higher)) deallocate (self%higher)
    end subroutine release

    subroutine allocate_pieces(self, n, m, opts, lsq, stat)
        class(regularized_dae), intent(inout) :: self
        integer, intent(in) :: n, m, lsq
        type(solver_options), intent(in) :: opts
        integer, intent(out), optional :: stat
        integer :: astat
        self%n = n
        self%m = m
        self%method = opts%method
        self%lsq = lsq
        self%eps = opts%eps
        if (opts%eps == option_auto) self%eps = 0.0_wp   ! until the solver resolves it
        if (allocated(self%f)) deallocate (self%f, self%b, self%g, self%gx, self%gt, self%curv, self%gb, self%r, self%q)
        self%message = ''
        allocate (self%f(n), self%b(n, m), self%g(m), self%gx(m, n), self%gt(m), self%curv(m), self%gb(m, m), &
                  self%r(m), self%q(m), source=0.0_wp, stat=astat)
        if (astat == 0) call self%lsq_ws%init(m, m, astat)
        if (astat /= 0) then
            if (allocated(self%f)) deallocate (self%f)
            if (allocated(self%b)) deallocate (self%b)
            if (allocated(self%g)) deallocate (self%g)
            if (allocated(self%gx)) deallocate (self%gx)
            if (allocated(self%gt)) deallocate (self%gt)
            if (allocated(self%curv)) deallocate (self%curv)
            if (allocated(self%gb)) deallocate (self%gb)
            if (allocated(self%r)) deallocate (self%r)
            if (allocated(self%q)) deallocate (self%q)
            self%message = 'out of memory: the dense pieces of the eliminated formulation (G, B: 2 x '// &
                           format_int(m)//' x '//format_int(n)//' reals) were refused'
            if (present(stat)) stat = regdae_err_memory
            return
        end if
        if (present(stat)) stat = 0
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
        real(wp) :: probe

        stat = regdae_success
        recoverable = .true.
        ustat = 0
        n = self%n
        if (self%order == 1) then
            call self%first%rhs(t, z, self%f, ustat)
            if (ustat /= 0) then
                call report_failure(self, 'rhs', t, ustat, stat, recoverable)
                return
            end if
            call self%first%matrix_b(t, z, self%b, ustat)
            if (ustat /= 0) then
                call report_failure(self, 'matrix_b', t, ustat, stat, recoverable)
                return
            end if
            call self%first%constraint(t, z, self%g, ustat)
            if (ustat /= 0) then
                call report_failure(self, 'constraint', t, ustat, stat, recoverable)
                return
            end if
            call self%first%constraint_jacobian(t, z, self%gx, ustat)
            if (ustat /= 0) then
                call report_failure(self, 'constraint_jacobian', t, ustat, stat, recoverable)
                return
            end if
            call self%first%constraint_dt(t, z, self%gt, ustat)
            if (ustat /= 0) then
                call report_failure(self, 'constraint_dt', t, ustat, stat, recoverable)
                return
            end if
        else if (self%order >= 3) then
            call self%higher%rhs(t, reshape(z(1:self%order*n), [n, self%order]), self%f, ustat)
            if (ustat /= 0) then
                call report_failure(self, 'rhs', t, ustat, stat, recoverable)
                return
            end if
            call self%higher%matrix_b(t, reshape(z(1:self%order*n), [n, self%order]), self%b, ustat)
            if (ustat /= 0) then
                call report_failure(self, 'matrix_b', t, ustat, stat, recoverable)
                return
            end if
            call self%higher%constraint(t, z(1:n), self%g, ustat)
            if (ustat /= 0) then
                call report_failure(self, 'constraint', t, ustat, stat, recoverable)
                return
            end if
            call self%higher%constraint_jacobian(t, z(1:n), self%gx, ustat)
            if (ustat /= 0) then
                call report_failure(self, 'constraint_jacobian', t, ustat, stat, recoverable)
                return
            end if
            call self%higher%constraint_dt(t, z(1:n), self%gt, ustat)
            if (ustat /= 0) then
                call report_failure(self, 'constraint_dt', t, ustat, stat, recoverable)
                return
            end if
        else
            associate (x => z(1:n), v => z(n + 1:2*n))   ! the sections built once for the six calls
                call self%second%rhs(t, x, v, self%f, ustat)
                if (ustat /= 0) then
                    call report_failure(self, 'rhs', t, ustat, stat, recoverable)
                    return
                end if
                call self%second%constraint_jacobian(t, x, self%gx, ustat)
                if (ustat /= 0) then
                    call report_failure(self, 'constraint_jacobian', t, ustat, stat, recoverable)
                    return
                end if
                call self%second%matrix_b_from_jacobian(t, x, v, self%gx, self%b, ustat)
                if (ustat /= 0) then
                    call report_failure(self, 'matrix_b', t, ustat, stat, recoverable)
                    return
                end if
                call self%second%constraint(t, x, self%g, ustat)
                if (ustat /= 0) then
                    call report_failure(self, 'constraint', t, ustat, stat, recoverable)
                    return
                end if
                call self%second%constraint_dt(t, x, self%gt, ustat)
                if (ustat /= 0) then
                    call report_failure(self, 'constraint_dt', t, ustat, stat, recoverable)
                    return
                end if
                if (self%curvature) then
                    call self%second%constraint_curvature(t, x, v, self%curv, ustat)
                    if (ustat /= 0) then
                        call report_failure(self, 'constraint_curvature', t, ustat, stat, recoverable)
                        return
                    end if
                end if
            end associate
        end if
        call self%constraint_terms(z, self%q)
        call multiplier_pieces(n, self%m, self%gx, self%b, self%f, self%q, self%gb, self%r, probe)
        if (probe /= 0.0_wp) then
            stat = regdae_err_nonfinite
            self%message = 'NaN or Inf in f, B, g, G, g_t or c at t = '//format_real(t)
            return
        end if
    end subroutine evaluate

    subroutine linearize_rhs(self, t, z, on, stat, recoverable)
        class(regularized_dae), intent(inout) :: self
        real(wp), intent(in) :: t       !! time
        real(wp), intent(in) :: z(:)    !! state: x (order 1) or (x, v) (order 2)
        logical, intent(in) :: on       !! .true.: linearize at (t, z); .false.: evaluate f again
        integer, intent(out) :: stat
        logical, intent(out) :: recoverable
        integer :: ustat
        stat = regdae_success
        recoverable = .true.
        ustat = 0
        if (self%order == 1) then
            call self%first%linearize_rhs(t, z, on, ustat)
        else if (self%order == 2) then
            call self%second%linearize_rhs(t, z(1:self%n), z(self%n + 1:2*self%n), on, ustat)
        end if
        if (ustat /= 0) call report_failure(self, 'rhs_jacobian', t, ustat, stat, recoverable)
    end subroutine linearize_rhs

    function nonnegative_state(self) result(mask)
        class(regularized_dae), intent(in) :: self
        logical :: mask(self%order*self%n)
        mask = .false.
        if (self%order == 1) mask = self%first%nonnegative()
        if (self%order == 2) mask(1:self%n) = self%second%nonnegative()
    end function nonnegative_state

    ! A user routine of `evaluate` returned ustat /= 0: stat, recoverable and the message.
    subroutine report_failure(self, name, t, ustat, stat, recoverable)
        class(regularized_dae), intent(inout) :: self
        character(len=*), intent(in) :: name
        real(wp), intent(in) :: t
        integer, intent(in) :: ustat
        integer, intent(out) :: stat
        logical, intent(out) :: recoverable
        recoverable = (ustat > 0)
        if (ustat == regdae_err_mass_matrix) then
            stat = regdae_err_mass_matrix
            self%message = status_message(stat)//' at t = '//format_real(t)//' (in '//name//')'
        else
            stat = regdae_err_user_callback
            self%message = 'user routine '//name//' reported failure (stat = '// &
                           format_int(ustat)//') at t = '//format_real(t)
        end if
    end subroutine report_failure

    ! GB and r = q + G f from the evaluated pieces, by loops over explicit shapes (each
    ! entry a sum in ascending index from the first term, the order of `add_matvec`:
    ! GB from 0, r from q), and a probe that is 0 exactly when f, GB and r are finite: a
    ! NaN or Inf in B, g, G, g_t or c reaches GB or r (0 * NaN and 0 * Inf are NaN).
    pure subroutine multiplier_pieces(n, m, gx, b, f, q, gb, r, probe)
        integer, intent(in) :: n, m
        real(wp), intent(in) :: gx(m, n), b(n, m), f(n), q(m)
        real(wp), intent(out) :: gb(m, m), r(m), probe
        integer :: i, j, k
        real(wp) :: s
        probe = 0.0_wp
        do i = 1, n
            probe = probe + 0.0_wp*f(i)
        end do
        if (m == 1) then
            call pieces_one(n, gx, b, f, q, gb, r, probe)
            return
        else if (m == 2) then
            call pieces_two(n, gx, b, f, q, gb, r, probe)
            return
        end if
        do j = 1, m
            do i = 1, m
                s = 0.0_wp
                do k = 1, n
                    s = s + gx(i, k)*b(k, j)
                end do
                gb(i, j) = s
                probe = probe + 0.0_wp*s
            end do
        end do
        do i = 1, m
            s = q(i)
            do k = 1, n
                s = s + gx(i, k)*f(k)
            end do
            r(i) = s
            probe = probe + 0.0_wp*s
        end do
    end subroutine multiplier_pieces

    ! multiplier_pieces for one constraint: GB and r in one pass over k, as pieces_two.
    pure subroutine pieces_one(n, gx, b, f, q, gb, r, probe)
        integer, intent(in) :: n
        real(wp), intent(in) :: gx(1, n), b(n, 1), f(n), q(1)
        real(wp), intent(out) :: gb(1, 1), r(1)
        real(wp), intent(inout) :: probe
        real(wp) :: s11, r1
        integer :: k
        s11 = 0.0_wp
        r1 = q(1)
        do k = 1, n
            s11 = s11 + gx(1, k)*b(k, 1)
            r1 = r1 + gx(1, k)*f(k)
        end do
        gb(1, 1) = s11
        r(1) = r1
        probe = probe + 0.0_wp*s11
        probe = probe + 0.0_wp*r1
    end subroutine pieces_one

    ! multiplier_pieces for two constraints: the six sums in one pass over k, each in the
    ! general loops' order (from 0 or q, ascending k), so the same numbers; the probe's
    ! terms in the general order too (a quarter of the car axis's evaluation went to the
    ! general loops' setup for these 24 products).
    pure subroutine pieces_two(n, gx, b, f, q, gb, r, probe)
        integer, intent(in) :: n
        real(wp), intent(in) :: gx(2, n), b(n, 2), f(n), q(2)
        real(wp), intent(out) :: gb(2, 2), r(2)
        real(wp), intent(inout) :: probe
        real(wp) :: s11, s21, s12, s22, r1, r2
        integer :: k
        s11 = 0.0_wp
        s21 = 0.0_wp
        s12 = 0.0_wp
        s22 = 0.0_wp
        r1 = q(1)
        r2 = q(2)
        do k = 1, n
            s11 = s11 + gx(1, k)*b(k, 1)
            s21 = s21 + gx(2, k)*b(k, 1)
            s12 = s12 + gx(1, k)*b(k, 2)
            s22 = s22 + gx(2, k)*b(k, 2)
            r1 = r1 + gx(1, k)*f(k)
            r2 = r2 + gx(2, k)*f(k)
        end do
        gb(1, 1) = s11
        gb(2, 1) = s21
        gb(1, 2) = s12
        gb(2, 2) = s22
        r(1) = r1
        r(2) = r2
        probe = probe + 0.0_wp*s11
        probe = probe + 0.0_wp*s21
        probe = probe + 0.0_wp*s12
        probe = probe + 0.0_wp*s22
        probe = probe + 0.0_wp*r1
        probe = probe + 0.0_wp*r2
    end subroutine pieces_two

    ! q = r - G f = w0 g + w1 g_t + sum_{k=1}^{m-1} w_k G x^(k) [+ c] (order 1: g_t with weight 1).
    subroutine constraint_terms(self, z, q)
        class(regularized_dae), intent(in) :: self
        real(wp), intent(in) :: z(:)
        real(wp), intent(out) :: q(:)
        integer :: k, n
        n = self%n
        if (self%order == 1) then
            q(:) = self%w(1)*self%g + self%gt
        else if (self%order == 2) then
            call velocity_terms(n, self%m, self%w(1), self%w(2), self%g, self%gt, self%gx, z(n + 1:2*n), &
                                self%curvature, self%curv, q)
        else
            q(:) = self%w(1)*self%g + self%w(2)*self%gt
            do k = 1, self%order - 1
                call add_matvec(self%m, n, self%gx, z(k*n + 1:(k + 1)*n), self%w(k + 1), q)
            end do
            if (self%curvature) q = q + self%curv
        end if
    end subroutine constraint_terms

    ! Order 2: q = w0 g + w1 g_t + w1 G v [+ c], the operations of the general case in
    ! its order, by loops over explicit shapes.
    pure subroutine velocity_terms(n, m, w0, w1, g, gt, gx, v, curvature, curv, q)
        integer, intent(in) :: n, m
        real(wp), intent(in) :: w0, w1, g(m), gt(m), gx(m, n), v(n), curv(m)
        logical, intent(in) :: curvature
        real(wp), intent(out) :: q(m)
        integer :: i
        do i = 1, m
            q(i) = w0*g(i) + w1*gt(i)
        end do
        call add_matvec(m, n, gx, v, w1, q)
        if (curvature) then
            do i = 1, m
                q(i) = q(i) + curv(i)
            end do
        end if
    end subroutine velocity_terms

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
            if (.not. all_finite(y)) stat = regdae_err_nonfinite
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

    !> Eliminated formulation: res = z' - (v, f - B y(z)) (order 2) or
    !! x' - f + B y(x) (order 1), y from `solve_multiplier`.
    subroutine residual_eliminated(self, t, z, zp, res, y, stat, recoverable)
        class(regularized_dae), intent(inout) :: self
        real(wp), intent(in) :: t, z(:), zp(:)
        real(wp), intent(out) :: res(:)   !! residual, length of z
        real(wp), intent(out) :: y(:)     !! multiplier used, length m
        integer, intent(out) :: stat
        logical, intent(out) :: recoverable

        call self%slope_eliminated(t, z, res, y, stat, recoverable)
        if (stat /= regdae_success) return
        res = zp - res
    end subroutine residual_eliminated

    !> The eliminated formulation as an ODE z' = F(z, t): F = (v, f - B y(z))
    !! (order 2; order m: (x', ..., x^(m-1), f - B y)) or f - B y (order 1).
    subroutine slope_eliminated(self, t, z, dz, y, stat, recoverable)
        class(regularized_dae), intent(inout) :: self
        real(wp), intent(in) :: t, z(:)
        real(wp), intent(out) :: dz(:)    !! F(z, t), length of z
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
        call self%dynamics_slope(z, y, dz)
    end subroutine slope_eliminated

    ! The right-hand side of the differential rows for a given y:
    ! x^(k+1) for k < m-1, and f - B y for the last block.
    subroutine dynamics_slope(self, z, y, dz)
        class(regularized_dae), intent(in) :: self
        real(wp), intent(in) :: z(:), y(:)
        real(wp), intent(out) :: dz(:)
        integer :: n, last, i
        n = self%n
        last = (self%order - 1)*n
        do i = 1, last   ! loops: a few entries, not worth memcpy's call
            dz(i) = z(n + i)
        end do
        do i = 1, n
            dz(last + i) = self%f(i)
        end do
        call add_matvec(n, self%m, self%b, y, -1.0_wp, dz(last + 1:last + n))
    end subroutine dynamics_slope

    ! y = y + alpha A x by loops: no temporary, no library call (the hot path's
    ! matrices have a few rows and columns).
    pure subroutine add_matvec(m, n, a, x, alpha, y)
        integer, intent(in) :: m, n
        real(wp), intent(in) :: a(m, n), x(n), alpha
        real(wp), intent(inout) :: y(m)
        integer :: i, j
        real(wp) :: s
        do j = 1, n
            s = alpha*x(j)
            do i = 1, m
                y(i) = y(i) + a(i, j)*s
            end do
        end do
    end subroutine add_matvec

    ! True if no entry is NaN or Inf (a loop that stops at the first one).
    pure logical function all_finite(a) result(finite)
        real(wp), intent(in) :: a(:)
        integer :: i
        finite = .true.
        do i = 1, size(a)
            if (.not. (abs(a(i)) <= huge(a))) then
                finite = .false.
                return
            end if
        end do
    end function all_finite


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
        call self%dynamics_slope(z, y, res_z)
        res_z = zp - res_z
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
