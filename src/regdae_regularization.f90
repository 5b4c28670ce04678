!> The regularized index-2 system of section 2 of the paper, independent of
!! the integrator.
!!
!! At a point (t, x) it evaluates the problem's pieces f, B, g, G, g_t, forms
!! GB and the right-hand side
!! $$ r = G f + g_t + \gamma g $$
!! and gives the multiplier of the chosen regularization:
!! - Baumgarte (2.7), gamma = 1/h:   GB y = r                      (LU);
!! - trust region (2.10):             ((GB)^T GB + eps I) y = (GB)^T r;
!! - direct (2.12):                   (GB + eps I) y = r, GB symmetric PSD (Cholesky).
!! From these it builds the residuals IDA integrates: the eliminated form
!! x' - f + B y(x) = 0, and the multiplier form with (x, y) as unknowns, whose
!! algebraic rows are the regularized equations themselves (for Baumgarte,
!! (2.5): gamma g + G x' + g_t = 0).
module regdae_regularization
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
    use regdae_kinds, only: wp
    use regdae_format, only: format_real, format_int
    use regdae_status, only: regdae_success, regdae_err_user_callback, regdae_err_nonfinite, &
                             regdae_err_not_psd, regdae_err_singular, status_message
    use regdae_problem, only: dae_problem
    use regdae_options, only: solver_options, method_baumgarte, method_trust_region, method_direct
    use regdae_damped_lsq, only: damped_lsq_workspace, damped_lsq_solve, shifted_spd_solve, square_solve
    implicit none
    private

    !> A problem with its regularization: the pieces at the last evaluated point
    !! and the scratch space of the multiplier solves.
    type, public :: regularized_dae
        class(dae_problem), allocatable :: problem  !! the user's problem (a copy)
        integer :: method = method_trust_region     !! regularization
        integer :: lsq = 0                          !! `lsq_normal` or `lsq_stacked` (resolved)
        real(wp) :: gamma = 0.0_wp                  !! Baumgarte parameter
        real(wp) :: eps = 0.0_wp                    !! damping
        real(wp), allocatable :: f(:)        !! f(x, t), n
        real(wp), allocatable :: b(:, :)     !! B(x, t), n x m
        real(wp), allocatable :: g(:)        !! g(x, t), m
        real(wp), allocatable :: gx(:, :)    !! G = g_x, m x n
        real(wp), allocatable :: gt(:)       !! g_t, m
        real(wp), allocatable :: gb(:, :)    !! G B, m x m
        real(wp), allocatable :: r(:)        !! G f + g_t + gamma g, m
        type(damped_lsq_workspace) :: lsq_ws
        character(len=:), allocatable :: message  !! details of the last failure
    contains
        !> Copy the problem and options in and size the work arrays.
        procedure :: init => regularized_init
        !> Evaluate f, B, g, G, g_t, GB and r at (t, x).
        procedure :: evaluate
        !> Multiplier y from the pieces of the last `evaluate`.
        procedure :: solve_multiplier
        !> Residual x' - f + B y(x) of the eliminated formulation.
        procedure :: residual_eliminated
        !> Residual of the multiplier formulation, unknowns (x, y).
        procedure :: residual_multiplier
    end type regularized_dae

contains

    subroutine regularized_init(self, problem, opts, lsq)
        class(regularized_dae), intent(inout) :: self
        class(dae_problem), intent(in) :: problem    !! copied into self
        type(solver_options), intent(in) :: opts
        integer, intent(in) :: lsq                   !! resolved least-squares method
        integer :: n, m

        if (allocated(self%problem)) deallocate (self%problem)
        allocate (self%problem, source=problem)
        n = problem%n
        m = problem%m
        self%method = opts%method
        self%lsq = lsq
        self%gamma = opts%gamma
        self%eps = opts%eps
        self%f = zeros(n)
        self%g = zeros(m)
        self%gt = zeros(m)
        self%r = zeros(m)
        allocate (self%b(n, m), self%gx(m, n), self%gb(m, m), source=0.0_wp)
        call self%lsq_ws%init(m, m)
        self%message = ''
    end subroutine regularized_init

    pure function zeros(k) result(v)
        integer, intent(in) :: k
        real(wp) :: v(k)
        v = 0.0_wp
    end function zeros

    !> Evaluate the pieces at (t, x). A failing user routine gives
    !! `regdae_err_user_callback` with the user's sign in `recoverable`; a NaN
    !! or Inf in any piece gives `regdae_err_nonfinite` (recoverable).
    subroutine evaluate(self, t, x, stat, recoverable)
        class(regularized_dae), intent(inout) :: self
        real(wp), intent(in) :: t       !! time
        real(wp), intent(in) :: x(:)    !! state, length n
        integer, intent(out) :: stat
        logical, intent(out) :: recoverable   !! may a smaller step help?
        integer :: ustat

        stat = regdae_success
        recoverable = .true.
        ustat = 0
        call self%problem%rhs(t, x, self%f, ustat)
        if (failed('rhs')) return
        call self%problem%matrix_b(t, x, self%b, ustat)
        if (failed('matrix_b')) return
        call self%problem%constraint(t, x, self%g, ustat)
        if (failed('constraint')) return
        call self%problem%constraint_jacobian(t, x, self%gx, ustat)
        if (failed('constraint_jacobian')) return
        call self%problem%constraint_dt(t, x, self%gt, ustat)
        if (failed('constraint_dt')) return
        if (.not. (all(ieee_is_finite(self%f)) .and. all(ieee_is_finite(self%b)) .and. &
                   all(ieee_is_finite(self%g)) .and. all(ieee_is_finite(self%gx)) .and. &
                   all(ieee_is_finite(self%gt)))) then
            stat = regdae_err_nonfinite
            self%message = 'NaN or Inf in f, B, g, G or g_t at t = '//format_real(t)
            return
        end if
        self%gb = matmul(self%gx, self%b)
        self%r = matmul(self%gx, self%f) + self%gt + self%gamma*self%g
    contains
        logical function failed(name)
            character(len=*), intent(in) :: name
            failed = (ustat /= 0)
            if (failed) then
                stat = regdae_err_user_callback
                recoverable = (ustat > 0)
                self%message = 'user routine '//name//' reported failure (stat = '// &
                               format_int(ustat)//') at t = '//format_real(t)
            end if
        end function failed
    end subroutine evaluate

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

    !> Eliminated formulation: res = x' - f + B y(x), y from `solve_multiplier`.
    subroutine residual_eliminated(self, t, x, xp, res, y, stat, recoverable)
        class(regularized_dae), intent(inout) :: self
        real(wp), intent(in) :: t, x(:), xp(:)
        real(wp), intent(out) :: res(:)   !! residual, length n
        real(wp), intent(out) :: y(:)     !! multiplier used, length m
        integer, intent(out) :: stat
        logical, intent(out) :: recoverable

        call self%evaluate(t, x, stat, recoverable)
        if (stat /= regdae_success) return
        call self%solve_multiplier(t, y, stat)
        if (stat /= regdae_success) then
            ! A singular GB (Baumgarte) may be avoided by a smaller step; a GB that
            ! is not PSD is a property of the problem.
            recoverable = (stat == regdae_err_singular .or. stat == regdae_err_nonfinite)
            return
        end if
        res = xp - self%f + matmul(self%b, y)
    end subroutine residual_eliminated

    !> Multiplier formulation: res_x = x' - f + B y, and res_y the regularized
    !! equation of the method (trust region: (GB)^T (GB y - r) + eps y; direct:
    !! (GB + eps I) y - r; Baumgarte: gamma g + G x' + g_t).
    subroutine residual_multiplier(self, t, x, y, xp, res_x, res_y, stat, recoverable)
        class(regularized_dae), intent(inout) :: self
        real(wp), intent(in) :: t, x(:), y(:), xp(:)
        real(wp), intent(out) :: res_x(:)   !! length n
        real(wp), intent(out) :: res_y(:)   !! length m
        integer, intent(out) :: stat
        logical, intent(out) :: recoverable
        real(wp), parameter :: psd_tol = 1.0e-8_wp
        integer :: i

        call self%evaluate(t, x, stat, recoverable)
        if (stat /= regdae_success) return
        res_x = xp - self%f + matmul(self%b, y)
        select case (self%method)
        case (method_trust_region)
            res_y = matmul(matmul(self%gb, y) - self%r, self%gb) + self%eps*y
        case (method_direct)
            ! Necessary conditions for GB symmetric PSD, cheap enough for every
            ! residual: symmetry and a nonnegative diagonal.
            if (maxval(abs(self%gb - transpose(self%gb))) > psd_tol*maxval(abs(self%gb)) &
                .or. any([(self%gb(i, i), i=1, self%problem%m)] < -psd_tol*maxval(abs(self%gb)))) then
                stat = regdae_err_not_psd
                recoverable = .false.
                self%message = 'method=direct: GB is not symmetric positive semidefinite at t = '// &
                               format_real(t)//' (use method=trust_region)'
                return
            end if
            res_y = matmul(self%gb, y) + self%eps*y - self%r
        case default
            res_y = self%gamma*self%g + matmul(self%gx, xp) + self%gt
        end select
    end subroutine residual_multiplier

end module regdae_regularization
