!> Projection onto the constraint manifold for a mechanical problem that declares
!! its structure, in O(nonzeros) memory: the sparse counterpart of
!! `regdae_projection`. Each Gauss-Newton step x <- x - dx solves the
!! quasi-definite augmented system
!! $$ \begin{pmatrix} I & G^T \\ G & -\delta I \end{pmatrix}
!!    \begin{pmatrix} dx \\ w \end{pmatrix} = \begin{pmatrix} 0 \\ g \end{pmatrix}, $$
!! i.e. dx = G^T (G G^T + delta I)^{-1} g, the minimum-norm correction damped by
!! delta = 100 u max|G|^2 (u the unit roundoff) so that a rank-deficient G (a
!! singular configuration, redundant constraints) keeps the matrix regular; the
!! velocity is then corrected the same way, v <- v - G^T (G G^T + delta I)^{-1}
!! (G v + g_t). The matrix is factored by KLU (SUNDIALS' SUNLinSol_KLU) on the
!! declared pattern of G: no dense m x n array.
module regdae_sparse_projection
    use, intrinsic :: iso_c_binding
    use fsundials_context_mod
    use fsundials_nvector_mod
    use fnvector_serial_mod
    use fsundials_matrix_mod
    use fsunmatrix_sparse_mod
    use fsundials_linearsolver_mod
    use fsunlinsol_klu_mod
    use regdae_kinds, only: wp
    use regdae_status, only: regdae_err_memory, regdae_err_sundials, regdae_err_singular
    use regdae_sparsity, only: sparsity_pattern, sparse_times
    use regdae_mechanical_problem, only: mechanical_problem
    implicit none
    private

    public :: project_structured

    !> Gauss-Newton steps at most (as in regdae_projection).
    integer, parameter :: max_steps = 4

    ! The augmented matrix on KLU and its index maps.
    type :: projection_system
        integer :: n = 0, m = 0, dim = 0
        integer, allocatable :: diag_pos(:)      ! n + m: position of (i, i) in the CSR values
        integer, allocatable :: g_pos(:)         ! nnz(G): position of G(j, k) in row n + j
        integer, allocatable :: gt_pos(:)        ! nnz(G): position of G(j, k)^T in row k
        type(c_ptr) :: ctx = c_null_ptr
        type(SUNMatrix), pointer :: a => null()
        type(SUNLinearSolver), pointer :: ls => null()
        type(N_Vector), pointer :: sol => null(), rhs => null()
    contains
        procedure :: build => system_build
        procedure :: solve => system_solve
        procedure :: release => system_release
    end type projection_system

contains

    !> (x, v) onto g(x, t) = 0 and G v + g_t = 0. stat: a user routine's, or
    !! regdae_err_memory, regdae_err_sundials, regdae_err_singular.
    subroutine project_structured(problem, pattern, t, x, v, stat)
        class(mechanical_problem), intent(inout) :: problem
        type(sparsity_pattern), intent(in) :: pattern   !! the declared pattern of G (m x n)
        real(wp), intent(in) :: t
        real(wp), intent(inout) :: x(:), v(:)
        integer, intent(out) :: stat
        type(projection_system) :: sys
        real(wp), allocatable :: g(:), gt(:), gv(:), dx(:)
        integer :: it, astat

        stat = 0
        if (problem%m == 0) return
        allocate (g(problem%m), gt(problem%m), gv(pattern%nnz()), dx(problem%n), stat=astat)
        if (astat /= 0) then
            stat = regdae_err_memory
            return
        end if
        call sys%build(pattern, problem%n, problem%m, stat)
        do it = 1, max_steps
            if (stat /= 0) exit
            call problem%constraint(t, x, g, stat)
            if (stat == 0) call problem%constraint_jacobian_values(t, x, pattern, gv, stat)
            if (stat /= 0) exit
            call sys%solve(pattern, gv, g, dx, stat)
            if (stat /= 0) exit
            x = x - dx
            if (maxval(abs(dx)) <= 4.0_wp*epsilon(1.0_wp)*max(1.0_wp, maxval(abs(x)))) exit
        end do
        if (stat == 0) call problem%constraint_jacobian_values(t, x, pattern, gv, stat)
        if (stat == 0) call problem%constraint_dt(t, x, gt, stat)
        if (stat == 0) then
            g = gt + sparse_times(pattern, gv, v)
            call sys%solve(pattern, gv, g, dx, stat)
            if (stat == 0) v = v - dx
        end if
        call sys%release()
    end subroutine project_structured

    ! The CSR pattern of [I G^T; G -delta I] (rows 1..n: the diagonal, then G^T by
    ! increasing constraint; rows n+1..n+m: the row of G, then the diagonal) on a
    ! SUNDIALS sparse matrix with KLU.
    subroutine system_build(self, pattern, n, m, stat)
        class(projection_system), intent(inout) :: self
        type(sparsity_pattern), intent(in) :: pattern
        integer, intent(in) :: n, m
        integer, intent(out) :: stat
        integer, allocatable :: start(:), fill(:)
        integer(c_long_long), pointer :: ptr(:), idx(:)
        integer :: nnz, total, i, j, k, p, astat

        stat = 0
        self%n = n
        self%m = m
        self%dim = n + m
        nnz = pattern%nnz()
        total = n + m + 2*nnz
        allocate (self%diag_pos(n + m), self%g_pos(nnz), self%gt_pos(nnz), start(n + m + 1), fill(n), stat=astat)
        if (astat /= 0) then
            stat = regdae_err_memory
            return
        end if
        ! row lengths: 1 + (entries of column i of G) for i <= n; 1 + (entries of row j) below
        start = 0
        start(2:n + 1) = 1
        do k = 1, nnz
            start(pattern%cols(k) + 1) = start(pattern%cols(k) + 1) + 1
        end do
        do j = 1, m
            start(n + j + 1) = 1 + pattern%row_start(j + 1) - pattern%row_start(j)
        end do
        start(1) = 1
        do i = 1, n + m
            start(i + 1) = start(i + 1) + start(i)
        end do
        if (FSUNContext_Create(c_null_ptr, self%ctx) /= 0) then
            stat = regdae_err_sundials
            return
        end if
        self%a => FSUNSparseMatrix(int(self%dim, c_long), int(self%dim, c_long), int(total, c_long), CSR_MAT, self%ctx)
        self%sol => FN_VNew_Serial(int(self%dim, c_long), self%ctx)
        self%rhs => FN_VNew_Serial(int(self%dim, c_long), self%ctx)
        if (.not. (associated(self%a) .and. associated(self%sol) .and. associated(self%rhs))) then
            stat = regdae_err_memory
            return
        end if
        ptr => FSUNSparseMatrix_IndexPointers(self%a)
        idx => FSUNSparseMatrix_IndexValues(self%a)
        call c_f_pointer(c_loc(ptr(1)), ptr, [self%dim + 1])
        call c_f_pointer(c_loc(idx(1)), idx, [total])
        ptr = int(start - 1, c_long_long)
        do i = 1, n
            self%diag_pos(i) = start(i)
            idx(start(i)) = i - 1
            fill(i) = start(i) + 1
        end do
        do j = 1, m
            do k = pattern%row_start(j), pattern%row_start(j + 1) - 1
                i = pattern%cols(k)
                p = fill(i)                     ! G^T: row i, column n + j (j increasing)
                self%gt_pos(k) = p
                idx(p) = n + j - 1
                fill(i) = p + 1
                p = start(n + j) + k - pattern%row_start(j)   ! G: row n + j, column i
                self%g_pos(k) = p
                idx(p) = i - 1
            end do
            self%diag_pos(n + j) = start(n + j + 1) - 1
            idx(start(n + j + 1) - 1) = n + j - 1
        end do
        self%ls => FSUNLinSol_KLU(self%sol, self%a, self%ctx)
        if (.not. associated(self%ls)) then
            stat = regdae_err_sundials
            return
        end if
        if (FSUNLinSolInitialize(self%ls) /= 0) stat = regdae_err_sundials
    end subroutine system_build

    ! dx = G^T (G G^T + delta I)^{-1} r with G's values gv: the values into the
    ! matrix, a factorization, a solve.
    subroutine system_solve(self, pattern, gv, r, dx, stat)
        class(projection_system), intent(inout) :: self
        type(sparsity_pattern), intent(in) :: pattern
        real(wp), intent(in) :: gv(:), r(:)
        real(wp), intent(out) :: dx(:)
        integer, intent(out) :: stat
        real(c_double), pointer :: vals(:), s(:), b(:)
        real(wp) :: delta
        integer :: k

        stat = 0
        vals => FSUNSparseMatrix_Data(self%a)
        call c_f_pointer(c_loc(vals(1)), vals, [self%n + self%m + 2*pattern%nnz()])
        delta = 0.0_wp
        if (size(gv) > 0) delta = 100.0_wp*epsilon(1.0_wp)*maxval(abs(gv))**2
        delta = max(delta, tiny(1.0_wp))
        vals(self%diag_pos(1:self%n)) = 1.0_wp
        vals(self%diag_pos(self%n + 1:)) = -delta
        do k = 1, size(gv)
            vals(self%g_pos(k)) = gv(k)
            vals(self%gt_pos(k)) = gv(k)
        end do
        if (FSUNLinSolSetup(self%ls, self%a) /= 0) then
            stat = regdae_err_singular
            return
        end if
        b => FN_VGetArrayPointer(self%rhs)
        b(1:self%n) = 0.0_wp
        b(self%n + 1:self%dim) = r
        if (FSUNLinSolSolve(self%ls, self%a, self%sol, self%rhs, 0.0_wp) /= 0) then
            stat = regdae_err_singular
            return
        end if
        s => FN_VGetArrayPointer(self%sol)
        dx = s(1:self%n)
    end subroutine system_solve

    subroutine system_release(self)
        class(projection_system), intent(inout) :: self
        integer(c_int) :: ierr
        if (associated(self%ls)) ierr = FSUNLinSolFree(self%ls)
        if (associated(self%a)) call FSUNMatDestroy(self%a)
        if (associated(self%sol)) call FN_VDestroy(self%sol)
        if (associated(self%rhs)) call FN_VDestroy(self%rhs)
        if (c_associated(self%ctx)) ierr = FSUNContext_Free(self%ctx)
        self%ls => null()
        self%a => null()
        self%sol => null()
        self%rhs => null()
        self%ctx = c_null_ptr
    end subroutine system_release

end module regdae_sparse_projection
