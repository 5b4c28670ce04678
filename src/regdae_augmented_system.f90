!> The augmented formulation of a regularized mechanical system: a residual
!! that costs O(nonzeros of M and G) and a Newton matrix that keeps their
!! structure, for large mechanisms (option `formulation=augmented`).
!!
!! The mechanical system M(q) q'' = f(q, q', t) - G^T y, 0 = g(q, t) (y = -lambda)
!! with the index-3 regularization of section 4: the multiplier solves
!! ((GB)^T GB + eps I) y = (GB)^T r (trust region), (GB + eps I) y = r (direct)
!! or GB y = r (Baumgarte), with B = M^{-1} G^T and
!! $$ r = G M^{-1} f + \gamma_1 (G v + g_t) + \gamma_0 g \; [+\, c]. $$
!! None of M^{-1}, GB or (GB)^T GB is formed. With a = q'' = M^{-1}(f - G^T y),
!! G a = G M^{-1} f - GB y, so s = r - GB y is the defect
!! $$ s = G v' + \gamma_1 (G v + g_t) + \gamma_0 g + c, $$
!! and, GB being symmetric, (GB)^T s = G u with M u = G^T s. The unknowns and
!! rows (IDA's residual F = 0):
!!
!! | unknown | row |
!! |---|---|
!! | q (n) | q' - v |
!! | v (n) | M v' - f + G^T y |
!! | u (n, trust region) | M u - G^T s |
!! | y (m) | trust region: G u - eps y; direct: eps y - s; Baumgarte: -s |
!! | s (m, trust region) | s - (G v' + gamma1 (G v + g_t) + gamma0 g + c) |
!!
!! (direct and Baumgarte use the defect itself in the y row and have no u, s).
!! Index 2 (option `index=2`) is the same with gamma0 = 0, gamma1 = gamma and c:
!! the regularized velocity constraint. The algebraic unknowns u, y, s leave
!! the error test; their initial values at a start come from solves of the
!! saddle-point matrix (`consistent_start`, submodule `regdae_augmented_start`),
!! else (and at a restart or a switch to IDA) from IDA's IDACalcIC.
!!
!! The unknowns are renumbered by reverse Cuthill-McKee on the Newton matrix's
!! pattern, so that a chain of bodies gives a band of fixed width.
!!
!! sigma_min(GB) for the monitor, by inverse iteration with solves of the saddle-point
!! matrix [M G^T; G 0] in band storage: submodule `regdae_augmented_conditioning`.
module regdae_augmented_system
    use regdae_kinds, only: wp
    use regdae_status
    use regdae_format, only: format_real, format_int
    use regdae_sparsity, only: sparsity_pattern, dense_pattern, pattern_from_entries, reverse_cuthill_mckee, &
                               permuted_bandwidths
    use regdae_lapack, only: dgbtrf, dgbtrs
    use regdae_differences, only: central_difference_step
    use regdae_mechanical_problem, only: mechanical_problem, mechanical_structure, complete_structure
    use regdae_implicit_system, only: implicit_system
    use regdae_options, only: solver_options, method_trust_region, method_direct, excluded_vy, option_auto
    implicit none
    private

    public :: user_routine_failure

    !> The augmented residual of one mechanical problem (a copy).
    type, extends(implicit_system), public :: augmented_system
        class(mechanical_problem), allocatable :: problem
        ! the patterns (dense where nothing was declared); allocatable because gfortran 12
        ! leaks the last of its four patterns when a polymorphic copy of this type holding
        ! it as a plain component is deallocated (measured with valgrind)
        type(mechanical_structure), allocatable :: st
        integer :: n = 0, m = 0
        integer :: method = method_trust_region
        real(wp) :: eps = 0.0_wp, gamma0 = 0.0_wp, gamma1 = 0.0_wp
        logical :: curvature = .true.
        ! offsets of the blocks in the natural numbering (u, s: -1 when absent)
        integer :: iq = 0, iv = 0, iu = -1, iy = 0, is = -1
        integer, allocatable :: perm(:)               !! perm(k): natural index of IDA's unknown k
        integer, allocatable :: iperm(:)              !! iperm(i): IDA's index of natural unknown i
        ! workspace, natural numbering
        real(wp), allocatable :: un(:), upn(:), rn(:)
        real(wp), allocatable :: mvals(:), gvals(:), f(:), g(:), gt(:), c(:), w(:), gvals2(:), tmp_m(:)
        real(wp), allocatable :: qshift(:)   ! q +- d v of the curvature's difference quotient
        ! the saddle-point matrix K = [M G^T; G 0] of the sigma_min estimate: its ordering
        ! (kperm(k): the natural index of K's unknown k), bandwidths, band storage, pivots
        integer, allocatable :: kperm(:), knew(:), kpiv(:)
        integer :: kl = 0, ku = 0
        real(wp), allocatable :: kband(:, :), kwork(:)
        ! the last estimate's singular vector: the next estimate starts from it
        real(wp), allocatable :: sigma_vector(:)
        ! the last plain estimate (< 0: none to reuse) and G M^{-1/2} where it was made (M diagonal)
        real(wp) :: sigma_estimate = -1.0_wp
        real(wp), allocatable :: sigma_scaled_g(:)
        logical :: mass_diagonal = .false.   !! M's pattern is its diagonal: sigma_min_gb may reuse an estimate
        ! GB's structural rank deficiency: the smallest numerical one over the estimates (-1: none yet)
        integer :: deficiency = -1
    contains
        procedure :: residual => augmented_residual
        !> Take the problem and the options; build the patterns and the ordering.
        procedure :: setup => augmented_setup
        !> IDA's u(t0), u'(t0) guess from q0, v0 (algebraic parts 0) and the id
        !! vector (1: differential, 0: algebraic).
        procedure :: initial_guess => augmented_initial_guess
        !> IDA's absolute tolerances (IDA's order, length neq): atol_q on q, atol_v on v,
        !! atol_other on the rest (u, y, s, which leave the error test by default).
        procedure :: tolerance_vector => augmented_tolerance_vector
        !> The unknowns left out of the error test (u, y, s; and v with excluded=vy).
        procedure :: excluded_unknowns
        !> q, v, y, and v' (the accelerations) from IDA's u and u'.
        procedure :: unpack => augmented_unpack
        !> max |g(q, t)| at IDA's u (stat: the user routine's).
        procedure :: drift => augmented_drift
        !> sigma_min(GB) at IDA's u, by inverse iteration (stat: the user routines'); optionally
        !! the diagonal_scales of M and G there.
        procedure :: sigma_min_gb => augmented_sigma_min
        !> max_i (GB)_ii (with M's diagonal) and max_i |G_i| of the M and G of the last
        !! sigma_min_gb (the automatic eps and drift bound, regdae_scales).
        procedure :: diagonal_scales => augmented_diagonal_scales
        !> K = [M G^T; G -shift I] with the M and G in mvals, gvals, factored in band storage
        !! (info: LAPACK dgbtrf's).
        procedure :: factor_saddle => augmented_factor_saddle
        !> [x; z] = K^{-1} [a; b] with the K of the last factor_saddle.
        procedure :: solve_saddle => augmented_solve_saddle
        !> IDA's consistent u(t0), u'(t0) from q0, v0 by solves of K (submodule
        !! regdae_augmented_start); .false. where that does not serve (IDACalcIC then).
        procedure :: consistent_start => augmented_consistent_start
    end type augmented_system

    ! The conditioning (submodule regdae_augmented_conditioning).
    interface
        module real(wp) function augmented_sigma_min(self, t, u, stat, gb, g, far) result(sigma)
            class(augmented_system), intent(inout) :: self
            real(wp), intent(in) :: t, u(:)
            integer, intent(out) :: stat
            real(wp), intent(out), optional :: gb, g   !! diagonal_scales at q (set when stat = 0)
            real(wp), intent(in), optional :: far      !! present: the last estimate may stand where sigma >= far
        end function augmented_sigma_min

        module subroutine augmented_diagonal_scales(self, gb, g)
            class(augmented_system), intent(in) :: self
            real(wp), intent(out) :: gb, g
        end subroutine augmented_diagonal_scales

        module subroutine augmented_factor_saddle(self, shift, info)
            class(augmented_system), intent(inout) :: self
            real(wp), intent(in) :: shift   !! >= 0: -shift I in the (2, 2) block
            integer, intent(out) :: info
        end subroutine augmented_factor_saddle

        module subroutine augmented_solve_saddle(self, a, b, x, z)
            class(augmented_system), intent(inout) :: self
            real(wp), intent(in) :: a(:), b(:)    !! lengths n, m
            real(wp), intent(out) :: x(:), z(:)   !! lengths n, m
        end subroutine augmented_solve_saddle
    end interface

    ! The consistent start (submodule regdae_augmented_start).
    interface
        module logical function augmented_consistent_start(self, t, u, up) result(done)
            class(augmented_system), intent(inout) :: self
            real(wp), intent(in) :: t
            real(wp), intent(inout) :: u(:), up(:)   !! in: initial_guess's; out (done): consistent
        end function augmented_consistent_start
    end interface


contains

    !> stat /= 0 with `self%message` when the declared structure does not fit
    !! the problem or the options do not suit the formulation.
    subroutine augmented_setup(self, problem, opts, stat)
        class(augmented_system), intent(inout) :: self
        class(mechanical_problem), intent(in) :: problem
        type(solver_options), intent(in) :: opts
        integer, intent(out) :: stat
        type(sparsity_pattern) :: natural
        integer :: n, m, neq, k

        stat = regdae_err_bad_input
        allocate (self%problem, source=problem)
        n = problem%n
        m = problem%m
        self%n = n
        self%m = m
        self%message = ''
        if (opts%mass_damping > 0.0_wp) then
            self%message = 'formulation=augmented needs a positive definite M (mass_damping = 0)'
            return
        end if
        self%st = self%problem%structure()
        call complete_structure(self%st, n)   ! force_q, force_v not set: empty
        if (.not. self%st%declared) then
            self%st%mass = dense_pattern(n, n)
            self%st%constraint = dense_pattern(m, n)
            self%st%force_q = dense_pattern(n, n)
            self%st%force_v = dense_pattern(n, n)
        end if
        if (.not. sizes_fit(self%st%mass, n, n, 'mass') .or. .not. sizes_fit(self%st%constraint, m, n, 'constraint') &
            .or. .not. sizes_fit(self%st%force_q, n, n, 'force_q') .or. .not. sizes_fit(self%st%force_v, n, n, &
                                                                                          'force_v')) return
        self%method = opts%method
        self%eps = merge(0.0_wp, opts%eps, opts%eps == option_auto)   ! auto: set by the solver
        if (opts%index == 3) then
            self%gamma0 = merge(1.0_wp, opts%gamma0, opts%gamma0 == option_auto)
            self%gamma1 = merge(1.0_wp, opts%gamma1, opts%gamma1 == option_auto)
            self%curvature = opts%curvature
        else   ! the regularized velocity constraint: d/dt (G v + g_t) + gamma (G v + g_t)
            self%gamma0 = 0.0_wp
            self%gamma1 = merge(1.0_wp, opts%gamma, opts%gamma == option_auto)
            self%curvature = .true.
        end if
        ! the natural numbering: q, v, [u], y, [s]
        self%iq = 0
        self%iv = n
        if (self%method == method_trust_region) then
            self%iu = 2*n
            self%iy = 3*n
            self%is = 3*n + m
            neq = 3*n + 2*m
        else
            self%iu = -1
            self%iy = 2*n
            self%is = -1
            neq = 2*n + m
        end if
        self%neq = neq
        natural = natural_pattern(self)
        self%perm = reverse_cuthill_mckee(natural)
        allocate (self%iperm(self%neq))
        self%iperm(self%perm) = [(k, k=1, self%neq)]
        self%jac_pattern = renumbered(natural, self%perm)
        self%structured = .true.
        call prepare_saddle_point(self)
        allocate (self%un(neq), self%upn(neq), self%rn(neq), source=0.0_wp)
        allocate (self%mvals(self%st%mass%nnz()), self%gvals(self%st%constraint%nnz()), &
                  self%gvals2(self%st%constraint%nnz()), self%f(n), self%g(m), self%gt(m), self%c(m), self%w(m), &
                  self%tmp_m(m), self%qshift(n), source=0.0_wp)
        stat = regdae_success
    contains
        logical function sizes_fit(p, rows, cols, name)
            type(sparsity_pattern), intent(in) :: p
            integer, intent(in) :: rows, cols
            character(len=*), intent(in) :: name
            sizes_fit = (p%nrows == rows .and. p%ncols == cols .and. allocated(p%row_start))
            if (.not. sizes_fit) self%message = 'the declared structure does not fit the problem: the '//name// &
                ' pattern is '//format_int(p%nrows)//' x '//format_int(p%ncols)//', expected '// &
                format_int(rows)//' x '//format_int(cols)
        end function sizes_fit
    end subroutine augmented_setup

    ! The pattern of dF/du + cj dF/du' in the natural numbering, block by block
    ! (see the module's table). H: the coupling of q through the constraint
    ! Hessians, supp(G_j) x supp(G_j) for every constraint j.
    function natural_pattern(self) result(p)
        type(augmented_system), intent(in) :: self
        type(sparsity_pattern) :: p
        integer, allocatable :: rows(:), cols(:)
        integer :: nent
        associate (n => self%n, gp => self%st%constraint, mp => self%st%mass)
            nent = 0
            allocate (rows(1024), cols(1024))
            call add_identity(self%iq, self%iq, n)           ! q' (cj)
            call add_identity(self%iq, self%iv, n)           ! -v
            call add_block(self%iv, self%iv, mp)             ! M v' (cj)
            call add_block(self%iv, self%iq, self%st%force_q)
            call add_hessian(self%iv, self%iq)               ! d(G^T y)/dq
            call add_block(self%iv, self%iv, self%st%force_v)
            call add_transpose(self%iv, self%iy, gp)         ! G^T y
            if (self%method == method_trust_region) then
                call add_block(self%iu, self%iu, mp)         ! M u
                call add_block(self%iu, self%iq, self%st%force_q)   ! d(M u)/dq lies within force_q
                call add_hessian(self%iu, self%iq)           ! d(G^T s)/dq
                call add_transpose(self%iu, self%is, gp)     ! -G^T s
                call add_block(self%iy, self%iu, gp)         ! G u
                call add_block(self%iy, self%iq, gp)
                call add_identity(self%iy, self%iy, self%m)  ! -eps y
                call add_identity(self%is, self%is, self%m)  ! s
                call add_defect(self%is)
            else
                call add_identity(self%iy, self%iy, self%m)  ! eps y
                call add_defect(self%iy)
            end if
            p = pattern_from_entries(self%neq, self%neq, rows(1:nent), cols(1:nent))
        end associate
    contains
        subroutine push(i, j)
            integer, intent(in) :: i, j
            integer, allocatable :: grown(:)
            if (nent == size(rows)) then
                allocate (grown(2*size(rows)))
                grown(1:nent) = rows(1:nent)
                call move_alloc(grown, rows)
                allocate (grown(2*size(cols)))
                grown(1:nent) = cols(1:nent)
                call move_alloc(grown, cols)
            end if
            nent = nent + 1
            rows(nent) = i
            cols(nent) = j
        end subroutine push

        subroutine add_identity(r0, c0, k)
            integer, intent(in) :: r0, c0, k
            integer :: i
            do i = 1, k
                call push(r0 + i, c0 + i)
            end do
        end subroutine add_identity

        subroutine add_block(r0, c0, b)
            integer, intent(in) :: r0, c0
            type(sparsity_pattern), intent(in) :: b
            integer :: i, k
            do i = 1, b%nrows
                do k = b%row_start(i), b%row_start(i + 1) - 1
                    call push(r0 + i, c0 + b%cols(k))
                end do
            end do
        end subroutine add_block

        subroutine add_transpose(r0, c0, b)
            integer, intent(in) :: r0, c0
            type(sparsity_pattern), intent(in) :: b
            integer :: i, k
            do i = 1, b%nrows
                do k = b%row_start(i), b%row_start(i + 1) - 1
                    call push(r0 + b%cols(k), c0 + i)
                end do
            end do
        end subroutine add_transpose

        subroutine add_hessian(r0, c0)
            integer, intent(in) :: r0, c0
            integer :: j, a, b
            associate (gp => self%st%constraint)
                do j = 1, gp%nrows
                    do a = gp%row_start(j), gp%row_start(j + 1) - 1
                        do b = gp%row_start(j), gp%row_start(j + 1) - 1
                            call push(r0 + gp%cols(a), c0 + gp%cols(b))
                        end do
                    end do
                end do
            end associate
        end subroutine add_hessian

        ! the defect G v' + gamma1 (G v + g_t) + gamma0 g + c in the rows r0 + j:
        ! it depends on v', v and q through supp(G_j)
        subroutine add_defect(r0)
            integer, intent(in) :: r0
            call add_block(r0, self%iv, self%st%constraint)
            call add_block(r0, self%iq, self%st%constraint)
        end subroutine add_defect
    end function natural_pattern

    ! The pattern with old index perm(k) renumbered k.
    function renumbered(p, perm) result(q)
        type(sparsity_pattern), intent(in) :: p
        integer, intent(in) :: perm(:)
        type(sparsity_pattern) :: q
        integer, allocatable :: rows(:), cols(:), new_index(:)
        integer :: k
        allocate (new_index(size(perm)))
        new_index(perm) = [(k, k=1, size(perm))]
        call p%entries(rows, cols)
        q = pattern_from_entries(p%nrows, p%ncols, new_index(rows), new_index(cols))
    end function renumbered

    ! The ordering and band storage of K = [M G^T; G 0], n + m unknowns.
    subroutine prepare_saddle_point(self)
        type(augmented_system), intent(inout) :: self
        type(sparsity_pattern) :: k_pattern
        integer, allocatable :: rows(:), cols(:), mr(:), mc(:), gr(:), gc(:)
        integer :: nk, k
        nk = self%n + self%m
        call self%st%mass%entries(mr, mc)
        call self%st%constraint%entries(gr, gc)
        rows = [mr, self%n + gr, gc, [(k, k=1, nk)]]
        cols = [mc, gc, self%n + gr, [(k, k=1, nk)]]
        k_pattern = pattern_from_entries(nk, nk, rows, cols)
        self%kperm = reverse_cuthill_mckee(k_pattern)
        call permuted_bandwidths(k_pattern, self%kperm, self%kl, self%ku)
        allocate (self%knew(nk), self%kpiv(nk), self%kwork(nk))
        self%knew(self%kperm) = [(k, k=1, nk)]
        allocate (self%kband(2*self%kl + self%ku + 1, nk))
        self%deficiency = -1
        self%sigma_estimate = -1.0_wp
        associate (mp => self%st%mass)
            self%mass_diagonal = (mp%nnz() == self%n)
            if (self%mass_diagonal) self%mass_diagonal = all(mp%row_start == [(k, k=1, self%n + 1)]) .and. &
                                                         all(mp%cols(1:self%n) == [(k, k=1, self%n)])
        end associate
    end subroutine prepare_saddle_point

    subroutine augmented_initial_guess(self, q0, v0, u, up, id)
        class(augmented_system), intent(in) :: self
        real(wp), intent(in) :: q0(:), v0(:)
        real(wp), intent(out) :: u(:), up(:), id(:)   !! IDA's order, length neq
        real(wp) :: un(self%neq), upn(self%neq), idn(self%neq)
        un = 0.0_wp
        upn = 0.0_wp
        idn = 0.0_wp
        un(self%iq + 1:self%iq + self%n) = q0
        un(self%iv + 1:self%iv + self%n) = v0
        upn(self%iq + 1:self%iq + self%n) = v0
        idn(1:2*self%n) = 1.0_wp   ! q and v are differential: the first 2n natural unknowns
        u = un(self%perm)
        up = upn(self%perm)
        id = idn(self%perm)
    end subroutine augmented_initial_guess

    function augmented_tolerance_vector(self, atol_q, atol_v, atol_other) result(atol_u)
        class(augmented_system), intent(in) :: self
        real(wp), intent(in) :: atol_q(:), atol_v(:), atol_other
        real(wp) :: atol_u(self%neq)
        real(wp) :: natural(self%neq)
        natural = atol_other
        natural(self%iq + 1:self%iq + self%n) = atol_q
        natural(self%iv + 1:self%iv + self%n) = atol_v
        atol_u = natural(self%perm)
    end function augmented_tolerance_vector

    function excluded_unknowns(self, excluded) result(mask)
        class(augmented_system), intent(in) :: self
        integer, intent(in) :: excluded   !! the option `excluded`
        logical :: mask(self%neq)
        logical :: natural(self%neq)
        natural = .true.
        natural(self%iq + 1:self%iq + self%n) = .false.
        if (excluded /= excluded_vy) natural(self%iv + 1:self%iv + self%n) = .false.
        mask = natural(self%perm)
    end function excluded_unknowns

    subroutine augmented_unpack(self, u, up, q, v, y, a)
        class(augmented_system), intent(in) :: self
        real(wp), intent(in) :: u(:), up(:)            !! IDA's order
        real(wp), intent(out), optional :: q(:), v(:), y(:), a(:)
        if (present(q)) q = u(self%iperm(self%iq + 1:self%iq + self%n))
        if (present(v)) v = u(self%iperm(self%iv + 1:self%iv + self%n))
        if (present(a)) a = up(self%iperm(self%iv + 1:self%iv + self%n))
        if (present(y)) y = u(self%iperm(self%iy + 1:self%iy + self%m))
    end subroutine augmented_unpack

    real(wp) function augmented_drift(self, t, u, stat) result(drift)
        class(augmented_system), intent(inout) :: self
        real(wp), intent(in) :: t, u(:)
        integer, intent(out) :: stat
        real(wp) :: q(self%n)
        stat = 0
        call self%unpack(u, u, q=q)
        call self%problem%constraint(t, q, self%g, stat)
        drift = 0.0_wp
        if (self%m > 0) drift = maxval(abs(self%g))
    end function augmented_drift

    subroutine augmented_residual(self, t, u, up, res, stat, recoverable)
        class(augmented_system), intent(inout) :: self
        real(wp), intent(in) :: t, u(:), up(:)
        real(wp), intent(out) :: res(:)
        integer, intent(out) :: stat
        logical, intent(out) :: recoverable
        integer :: ustat, n, m, i, k
        real(wp) :: d

        stat = regdae_success
        recoverable = .true.
        n = self%n
        m = self%m
        do k = 1, self%neq   ! (a loop: the vector subscript on the left made a heap temporary)
            self%un(self%perm(k)) = u(k)
            self%upn(self%perm(k)) = up(k)
        end do
        associate (q => self%un(self%iq + 1:self%iq + n), v => self%un(self%iv + 1:self%iv + n), &
                   qp => self%upn(self%iq + 1:self%iq + n), vp => self%upn(self%iv + 1:self%iv + n), &
                   y => self%un(self%iy + 1:self%iy + m), rn => self%rn, gp => self%st%constraint, &
                   mp => self%st%mass)
            ustat = 0
            call self%problem%mass_values(t, q, mp, self%mvals, ustat)
            if (failed('mass_values')) return
            call self%problem%constraint_jacobian_values(t, q, gp, self%gvals, ustat)
            if (failed('constraint_jacobian_values')) return
            call self%problem%forces(t, q, v, self%f, ustat)
            if (failed('forces')) return
            call self%problem%constraint(t, q, self%g, ustat)
            if (failed('constraint')) return
            call self%problem%constraint_dt(t, q, self%gt, ustat)
            if (failed('constraint_dt')) return
            self%c = 0.0_wp
            if (self%curvature) then
                if (self%st%curvature_supplied) then
                    call self%problem%constraint_curvature(t, q, v, self%c, ustat)
                    if (failed('constraint_curvature')) return
                else
                    ! c = d/ds [G v + g_t](q + s v, t + s) at s = 0, central difference
                    ! with the sparse G (the rule of `curvature_difference`)
                    d = central_difference_step(max(maxval(abs(q)), abs(t)))/max(1.0_wp, maxval(abs(v)))
                    self%qshift = q + d*v
                    call velocity_defect(t + d, self%qshift, v, self%c)
                    if (ustat /= 0) return
                    self%qshift = q - d*v
                    call velocity_defect(t - d, self%qshift, v, self%tmp_m)
                    if (ustat /= 0) return
                    self%c = (self%c - self%tmp_m)/(2.0_wp*d)
                end if
            end if
            ! q rows
            rn(self%iq + 1:self%iq + n) = qp - v
            ! v rows: M v' - f + G^T y
            call csr_multiply(mp, self%mvals, vp, rn(self%iv + 1:self%iv + n))
            rn(self%iv + 1:self%iv + n) = rn(self%iv + 1:self%iv + n) - self%f
            call csr_transpose_add(gp, self%gvals, y, rn(self%iv + 1:self%iv + n))
            ! the defect w = G v' + gamma1 (G v + g_t) + gamma0 g + c
            call csr_multiply(gp, self%gvals, vp, self%w)
            call csr_multiply(gp, self%gvals, v, self%tmp_m)
            do i = 1, m
                self%w(i) = self%w(i) + self%gamma1*(self%tmp_m(i) + self%gt(i)) + self%gamma0*self%g(i) + self%c(i)
            end do
            if (self%method == method_trust_region) then
                associate (uu => self%un(self%iu + 1:self%iu + n), s => self%un(self%is + 1:self%is + m))
                    ! u rows: M u - G^T s
                    call csr_multiply(mp, self%mvals, uu, rn(self%iu + 1:self%iu + n))
                    rn(self%iu + 1:self%iu + n) = -rn(self%iu + 1:self%iu + n)
                    call csr_transpose_add(gp, self%gvals, s, rn(self%iu + 1:self%iu + n))
                    rn(self%iu + 1:self%iu + n) = -rn(self%iu + 1:self%iu + n)
                    ! y rows: G u - eps y;  s rows: s - w
                    call csr_multiply(gp, self%gvals, uu, rn(self%iy + 1:self%iy + m))
                    rn(self%iy + 1:self%iy + m) = rn(self%iy + 1:self%iy + m) - self%eps*y
                    rn(self%is + 1:self%is + m) = s - self%w
                end associate
            else if (self%method == method_direct) then
                rn(self%iy + 1:self%iy + m) = self%eps*y - self%w
            else
                rn(self%iy + 1:self%iy + m) = -self%w
            end if
        end associate
        do k = 1, self%neq
            res(k) = self%rn(self%perm(k))
        end do
    contains
        ! The user routine `name` returned ustat /= 0: set stat, recoverable and the message.
        logical function failed(name)
            character(len=*), intent(in) :: name
            failed = (ustat /= 0)
            if (.not. failed) return
            call user_routine_failure(ustat, name, t, stat, self%message, recoverable)
        end function failed

        ! G(qq, tt) vv + g_t(qq, tt) with the sparse G
        subroutine velocity_defect(tt, qq, vv, out)
            real(wp), intent(in) :: tt, qq(:), vv(:)
            real(wp), intent(out) :: out(:)
            call self%problem%constraint_jacobian_values(tt, qq, self%st%constraint, self%gvals2, ustat)
            if (failed('constraint_jacobian_values')) return
            call self%problem%constraint_dt(tt, qq, out, ustat)
            if (failed('constraint_dt')) return
            call csr_multiply_add(self%st%constraint, self%gvals2, vv, out)
        end subroutine velocity_defect
    end subroutine augmented_residual

    ! y = A x for A in pattern order.
    pure subroutine csr_multiply(p, vals, x, y)
        type(sparsity_pattern), intent(in) :: p
        real(wp), intent(in) :: vals(:), x(:)
        real(wp), intent(out) :: y(:)
        y = 0.0_wp
        call csr_multiply_add(p, vals, x, y)
    end subroutine csr_multiply

    ! y = y + A x.
    pure subroutine csr_multiply_add(p, vals, x, y)
        type(sparsity_pattern), intent(in) :: p
        real(wp), intent(in) :: vals(:), x(:)
        real(wp), intent(inout) :: y(:)
        integer :: i, k
        real(wp) :: acc
        do i = 1, p%nrows
            acc = y(i)
            do k = p%row_start(i), p%row_start(i + 1) - 1
                acc = acc + vals(k)*x(p%cols(k))
            end do
            y(i) = acc
        end do
    end subroutine csr_multiply_add

    ! y = y + A^T x.
    pure subroutine csr_transpose_add(p, vals, x, y)
        type(sparsity_pattern), intent(in) :: p
        real(wp), intent(in) :: vals(:), x(:)
        real(wp), intent(inout) :: y(:)
        integer :: i, k
        do i = 1, p%nrows
            do k = p%row_start(i), p%row_start(i + 1) - 1
                y(p%cols(k)) = y(p%cols(k)) + vals(k)*x(i)
            end do
        end do
    end subroutine csr_transpose_add

    !> The status, message and recoverability of a user routine `name` of a mechanical
    !! problem that returned ustat /= 0 at t: the library's own codes (M not positive
    !! definite, an entry outside the declared pattern) pass through and are fatal; any
    !! other is regdae_err_user_callback, recoverable when ustat > 0.
    subroutine user_routine_failure(ustat, name, t, stat, message, recoverable)
        integer, intent(in) :: ustat
        character(len=*), intent(in) :: name
        real(wp), intent(in) :: t
        integer, intent(out) :: stat
        character(len=:), allocatable, intent(out) :: message
        logical, intent(out) :: recoverable
        recoverable = (ustat > 0)
        if (ustat == regdae_err_mass_matrix .or. ustat == regdae_err_structure .or. ustat == regdae_err_memory) then
            stat = ustat
            recoverable = .false.
            message = status_message(stat)//' at t = '//format_real(t)//' (in '//name//')'
        else
            stat = regdae_err_user_callback
            message = 'user routine '//name//' reported failure (stat = '//format_int(ustat)//') at t = '//format_real(t)
        end if
    end subroutine user_routine_failure

end module regdae_augmented_system
