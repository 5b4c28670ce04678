!> The augmented formulation of a mechanical problem (`regdae_augmented_system`)
!! as a semi-explicit DAE \(M U' = F(t, U)\) with a constant diagonal M, the form
!! the Radau IIA integrator (`regdae_radau_iia`) takes (integrator=radau
!! formulation=augmented).
!!
!! The augmented residual has the rows \(M(q) v' - f + G^T y\) and (in the defect)
!! \(G(q) v'\): a state-dependent mass. With the accelerations \(a = v'\) as
!! algebraic unknowns it becomes, in the unknowns \(U = (x, a)\), x the augmented
!! vector (q, v, [u], y, [s]) in IDA's order and a (n),
!! $$ q' = v, \quad v' = a, \quad 0 = R_{alg}(t, x, x'), \; x' = (v, a, 0), $$
!! \(R_{alg}\) the augmented residual's rows other than the q rows: the v rows
!! \(M a - f + G^T y\) (held in the a rows of U) and the damped least squares'
!! rows u, y, s. The mass matrix is diag(1 on q and v, 0 elsewhere). For fixed
!! (q, v) the algebraic rows are linear in (a, u, y, s), and their matrix is
!! nonsingular wherever the regularized multiplier is defined: eliminating a, u, s
!! leaves \(((GB)^2 + \varepsilon I) y = GB\, r\) (trust region), \((GB + \varepsilon I) y = r\)
!! (direct) or \(GB\, y = r\) (Baumgarte), B = M^{-1} G^T. The regularized system is
!! thus of index 1 (Hairer & Wanner, Solving ODEs II, VI.1), and Radau IIA runs it
!! as RADAU5 runs index-1 problems, every component of index 1.
!!
!! The Jacobian dF/dU by grouped forward differences (Curtis, Powell and Reid) on
!! the augmented system's pattern (`jac_pattern`, with the a columns where v'
!! enters): one residual per group of columns that share no row. The consistent
!! initial values of the algebraic unknowns from (q, v): two Newton steps on
!! the algebraic rows (linear in those unknowns), dense LU.
module regdae_radau_augmented
    use regdae_kinds, only: wp
    use regdae_status, only: regdae_success, regdae_err_singular, regdae_err_lapack
    use regdae_sparsity, only: sparsity_pattern, pattern_from_entries, column_groups
    use regdae_lapack, only: dgetrf, dgetrs
    use regdae_augmented_system, only: augmented_system
    use regdae_radau_system, only: radau_system
    implicit none
    private

    !> The augmented formulation as \(M U' = F(t, U)\) (see the module documentation).
    type, extends(radau_system), public :: augmented_dae
        type(augmented_system) :: sys        !! the augmented residual (its eps and weights follow the monitor)
        integer :: neq = 0                   !! size of the augmented vector x
        integer :: n = 0                     !! coordinates (size of q, v and a)
        integer, allocatable :: q_at(:)      !! positions of q in x (IDA's order)
        integer, allocatable :: v_at(:)      !! positions of v in x
        integer, allocatable :: v_index(:)   !! v_index(k) = i where x(k) = v_i, else 0
        real(wp), allocatable :: mass(:)     !! the diagonal of M, size neq + n
        integer :: jacobian_evals = 0        !! residual evaluations of the grouped Jacobians
        character(len=:), allocatable :: failure   !! the residual's message at its last failure ('' none)
        real(wp) :: seen(3) = 0.0_wp         !! (eps, gamma0, gamma1) at the last `note_parameters`
        ! the groups of columns (group_cols(group_start(c):group_start(c+1)-1)) and column j's rows
        integer :: ngroups = 0
        integer, allocatable :: group_start(:), group_cols(:)
        type(sparsity_pattern) :: column_rows
        ! workspace
        real(wp), allocatable :: x(:), xp(:), res(:), u_pert(:), f_pert(:), delta(:)
    contains
        procedure :: rhs => dae_rhs
        procedure :: has_jacobian => dae_has_jacobian
        procedure :: jacobian => dae_jacobian
        !> Take a copy of the augmented system; build the mass, the pattern and the groups.
        procedure :: setup => dae_setup
        !> U at (t, q, v) with the algebraic unknowns solving their rows.
        procedure :: consistent => dae_consistent
        !> The absolute tolerances of U: those of x, and atol_a on a.
        procedure :: tolerances => dae_tolerances
        !> x and x' (IDA's order) from U and U': q' = v, v' = a, the rest from U'.
        procedure :: augmented_pair => dae_augmented_pair
        !> Whether eps, gamma0 or gamma1 changed since the last call (which records them).
        procedure :: note_parameters => dae_note_parameters
    end type augmented_dae

contains

    !> A copy of sys (set up, its eps and weights resolved) as a Radau system.
    subroutine dae_setup(self, sys)
        class(augmented_dae), intent(inout) :: self
        type(augmented_system), intent(in) :: sys
        integer :: i, neq, n
        self%sys = sys
        neq = sys%neq
        n = sys%n
        self%neq = neq
        self%n = n
        self%q_at = sys%iperm(sys%iq + 1:sys%iq + n)
        self%v_at = sys%iperm(sys%iv + 1:sys%iv + n)
        allocate (self%v_index(neq), source=0)
        self%v_index(self%v_at) = [(i, i=1, n)]
        allocate (self%mass(neq + n), source=0.0_wp)
        self%mass(self%q_at) = 1.0_wp
        self%mass(self%v_at) = 1.0_wp
        allocate (self%x(neq), self%xp(neq), self%res(neq), self%u_pert(neq + n), self%f_pert(neq + n), &
                  self%delta(neq + n), source=0.0_wp)
        self%failure = ''
        call prepare_groups(self)
    end subroutine dae_setup

    ! The pattern of dF/dU and its groups of columns.
    subroutine prepare_groups(self)
        class(augmented_dae), intent(inout) :: self
        type(sparsity_pattern) :: p
        integer, allocatable :: rows(:), cols(:)
        integer :: i, k, r, nent
        associate (jp => self%sys%jac_pattern, neq => self%neq, n => self%n)
            allocate (rows(2*n + 2*jp%nnz()), cols(2*n + 2*jp%nnz()))
            nent = 0
            do i = 1, n
                call push(self%q_at(i), self%v_at(i))   ! q' = v
                call push(self%v_at(i), neq + i)         ! v' = a
            end do
            do r = 1, neq   ! the algebraic rows: the a rows hold the residual's v rows
                if (self%mass(r) /= 0.0_wp .and. self%v_index(r) == 0) cycle   ! a q row
                do k = jp%row_start(r), jp%row_start(r + 1) - 1
                    call push(row_of(r), jp%cols(k))
                    if (self%v_index(jp%cols(k)) > 0) call push(row_of(r), neq + self%v_index(jp%cols(k)))
                end do
            end do
            p = pattern_from_entries(neq + n, neq + n, rows(1:nent), cols(1:nent))
        end associate
        self%column_rows = p%transposed()
        call column_groups(p, self%ngroups, self%group_start, self%group_cols, self%column_rows)
    contains
        ! the row of U's system that holds the residual's row r
        integer function row_of(r)
            integer, intent(in) :: r
            row_of = r
            if (self%v_index(r) > 0) row_of = self%neq + self%v_index(r)
        end function row_of

        subroutine push(i, j)
            integer, intent(in) :: i, j
            nent = nent + 1
            rows(nent) = i
            cols(nent) = j
        end subroutine push
    end subroutine prepare_groups

    !> F(t, U): q' = v, v' = a on the q and v rows; minus the augmented residual at
    !! (x, x' = (v, a, 0)) on the others, its v rows in the a rows.
    subroutine dae_rhs(self, t, u, f, stat, recoverable)
        class(augmented_dae), intent(inout) :: self
        real(wp), intent(in) :: t, u(:)
        real(wp), intent(out) :: f(:)
        integer, intent(out) :: stat
        logical, intent(out) :: recoverable
        associate (neq => self%neq, n => self%n)
            self%x = u(1:neq)
            self%xp = 0.0_wp
            self%xp(self%q_at) = self%x(self%v_at)
            self%xp(self%v_at) = u(neq + 1:neq + n)
            call self%sys%residual(t, self%x, self%xp, self%res, stat, recoverable)
            if (stat /= regdae_success) then
                self%failure = self%sys%message
                f = 0.0_wp
                return
            end if
            f(1:neq) = -self%res
            f(neq + 1:neq + n) = -self%res(self%v_at)
            f(self%q_at) = self%x(self%v_at)
            f(self%v_at) = u(neq + 1:neq + n)
        end associate
    end subroutine dae_rhs

    logical function dae_has_jacobian(self)
        class(augmented_dae), intent(in) :: self
        dae_has_jacobian = .true.
    end function dae_has_jacobian

    !> dF/dU at (t, U), f = F(t, U): forward differences, one F per group of columns.
    subroutine dae_jacobian(self, t, u, f, dfdu, stat, recoverable)
        class(augmented_dae), intent(inout) :: self
        real(wp), intent(in) :: t, u(:), f(:)
        real(wp), intent(out) :: dfdu(:, :)
        integer, intent(out) :: stat
        logical, intent(out) :: recoverable
        integer :: c, k, j, i
        dfdu = 0.0_wp
        stat = regdae_success
        recoverable = .true.
        self%u_pert = u
        do c = 1, self%ngroups
            do k = self%group_start(c), self%group_start(c + 1) - 1
                j = self%group_cols(k)
                self%u_pert(j) = u(j) + sqrt(epsilon(1.0_wp)*max(1.0e-5_wp, abs(u(j))))
                self%delta(j) = self%u_pert(j) - u(j)
            end do
            self%jacobian_evals = self%jacobian_evals + 1
            call self%rhs(t, self%u_pert, self%f_pert, stat, recoverable)
            if (stat /= regdae_success) return
            do k = self%group_start(c), self%group_start(c + 1) - 1
                j = self%group_cols(k)
                do i = self%column_rows%row_start(j), self%column_rows%row_start(j + 1) - 1
                    associate (r => self%column_rows%cols(i))
                        dfdu(r, j) = (self%f_pert(r) - f(r))/self%delta(j)
                    end associate
                end do
                self%u_pert(j) = u(j)
            end do
        end do
    end subroutine dae_jacobian

    !> U at (t, q, v): x from the augmented system's initial guess, its algebraic
    !! unknowns and a from two Newton steps on the algebraic rows (linear in them;
    !! the second step takes the rounding of the first). stat: the residual's
    !! (msg: its message), or regdae_err_singular where the algebraic rows are
    !! singular (the regularized multiplier undefined at q).
    subroutine dae_consistent(self, t, q, v, u, stat, msg)
        class(augmented_dae), intent(inout) :: self
        real(wp), intent(in) :: t, q(:), v(:)
        real(wp), intent(out) :: u(:)           !! size neq + n
        integer, intent(out) :: stat
        character(len=:), allocatable, intent(out) :: msg
        real(wp) :: xp0(self%neq), id(self%neq), f(self%neq + self%n)
        real(wp), allocatable :: jac(:, :), block(:, :)
        integer, allocatable :: alg(:), ipiv(:)
        integer :: nalg, iter, info, i
        logical :: recoverable
        msg = ''
        call self%sys%initial_guess(q, v, u(1:self%neq), xp0, id)
        u(self%neq + 1:) = 0.0_wp
        alg = pack([(i, i=1, self%neq + self%n)], self%mass == 0.0_wp)
        nalg = size(alg)
        allocate (jac(self%neq + self%n, self%neq + self%n), block(nalg, nalg), ipiv(nalg))
        do iter = 1, 2
            call self%rhs(t, u, f, stat, recoverable)
            if (stat == regdae_success) call self%jacobian(t, u, f, jac, stat, recoverable)
            if (stat /= regdae_success) then
                msg = self%failure
                return
            end if
            block = jac(alg, alg)
            call dgetrf(nalg, nalg, block, nalg, ipiv, info)
            if (info /= 0) then
                stat = merge(regdae_err_singular, regdae_err_lapack, info > 0)
                msg = 'the algebraic rows of the augmented formulation are singular at the initial point '// &
                      '(the regularized multiplier is undefined there)'
                return
            end if
            f(1:nalg) = -f(alg)
            call dgetrs('N', nalg, 1, block, nalg, ipiv, f, nalg, info)
            u(alg) = u(alg) + f(1:nalg)
        end do
    end subroutine dae_consistent

    !> The absolute tolerances of U: atol_x on x (IDA's order), atol_a on a.
    pure function dae_tolerances(self, atol_x, atol_a) result(atol)
        class(augmented_dae), intent(in) :: self
        real(wp), intent(in) :: atol_x(:), atol_a
        real(wp) :: atol(self%neq + self%n)
        atol(1:self%neq) = atol_x
        atol(self%neq + 1:) = atol_a
    end function dae_tolerances

    !> Whether the augmented system's eps, gamma0 or gamma1 (which the monitor sets
    !! between steps) differ from their values at the last call; records them.
    subroutine dae_note_parameters(self, changed)
        class(augmented_dae), intent(inout) :: self
        logical, intent(out) :: changed
        real(wp) :: now(3)
        now = [self%sys%eps, self%sys%gamma0, self%sys%gamma1]
        changed = any(now /= self%seen)
        self%seen = now
    end subroutine dae_note_parameters

    !> x = U(1:neq) and x' (IDA's order): q' = v and v' = a from U, the algebraic
    !! unknowns' derivatives from U'.
    pure subroutine dae_augmented_pair(self, u, up, x, xp)
        class(augmented_dae), intent(in) :: self
        real(wp), intent(in) :: u(:), up(:)
        real(wp), intent(out) :: x(:), xp(:)
        x = u(1:self%neq)
        xp = up(1:self%neq)
        xp(self%q_at) = u(self%v_at)
        xp(self%v_at) = u(self%neq + 1:self%neq + self%n)
    end subroutine dae_augmented_pair

end module regdae_radau_augmented
