!> A planar chain of N links in Cartesian coordinates: the scalable benchmark
!! (drivers/chain). Unit links (L = 1) and unit point masses at the joints
!! 1..N; joint 0 is a pivot at the origin; gravity g in -y. Coordinates q = (x1, y1, ..., xN, yN), n = 2N; constraints
!! $$ g_i = \frac{|p_i - p_{i-1}|^2 - L^2}{2L}, \quad i = 1, \dots, N, $$
!! scaled so that a row of G holds the unit vector of its link. With the slider
!! (`slider = .true.`, N even) the free end and every other joint ride on the
!! horizontal line through the pivot: g_{N+k} = y_{2k}, k = 1..N/2. The chain is
!! then N/2 slider cranks in series (links 2k-1, 2k: the crank hangs from joint
!! 2k-2, the rod ends at joint 2k on the line), each with one degree of freedom
!! relative to its left end; G loses rank whenever a pair folds vertically (crank
!! straight down, rod straight back up), which every pair does when its crank
!! swings through the bottom: the rank-deficient path at any scale. For N = 2 it
!! is the slider crank of Example 5.2 in Cartesian coordinates (unit masses and
!! links), so the reduced ODE of `slider_crank_problem` is its exact reference.
!!
!! The problem declares its structure (M diagonal, G two 2-blocks per link row,
!! forces independent of q and q') and gives M and G in pattern order, so that
!! regdae's augmented formulation costs O(N) per residual. The curvature term
!! c_i = |v_i - v_{i-1}|^2 / L is supplied analytically; the energy is the invariant.
!!
!! The stiff variant (`stiffness` k, `damping` c, light `joint_mass`): every joint
!! also hangs on a vertical spring and dashpot, forces -k y_i - c y_i' (light
!! bodies on stiff springs: fast damped modes of frequency sqrt(k/m)).
!!
!! The slider chain's reduced ODE (`chain_slider_reduced`, unit links and masses, no springs):
!! its exact reference for any even N, as the slider crank's is for N = 2; the plain chain's
!! (`chain_plain_reduced`): the pendulum chain in its N joint angles. Their slopes are dense
!! (O(N^3) per evaluation); `chain_slider_recursive` and `chain_plain_recursive` give the same
!! slopes in O(N) by articulated-body recursions (drivers/trust's references of the long chains).
module chain_problem
    use regdae, only: wp, mechanical_problem, mechanical_structure, sparsity_pattern, diagonal_pattern, &
                      empty_pattern, pattern_from_entries
    use reference_ode, only: ode_system
    implicit none
    private

    !> The chain (and, with `slider`, its end on the line y = 0).
    type, extends(mechanical_problem), public :: chain
        integer :: links = 1
        logical :: slider = .false.
        real(wp) :: gravity = 9.81_wp
        real(wp) :: length = 1.0_wp    !! of one link
        real(wp) :: joint_mass = 1.0_wp   !! of one joint
        real(wp) :: stiffness = 0.0_wp    !! vertical springs k y under the joints
        real(wp) :: damping = 0.0_wp      !! vertical dashpots c y' under the joints
    contains
        procedure :: mass_matrix => chain_mass
        procedure :: forces => chain_forces
        procedure :: constraint => chain_g
        procedure :: constraint_jacobian => chain_gx
        procedure :: constraint_dt => chain_gt
        procedure :: constraint_curvature => chain_curvature
        procedure :: structure => chain_structure
        procedure :: mass_values => chain_mass_values
        procedure :: constraint_jacobian_values => chain_gx_values
        procedure :: invariant => chain_energy
    end type chain

    !> A chain of unit links and masses written as an ODE in its angles (no springs).
    type, abstract, extends(ode_system), public :: chain_reduced
        integer :: links = 2   !! N
        real(wp) :: gravity = 9.81_wp
    end type chain_reduced

    !> The slider chain (unit links and masses, gravity g, N = 2K even) in the angles
    !! \(\varphi_k\) of its cranks (link 2k-1 from the vertical), on the branch where each rod
    !! mirrors its crank, the one through the start chain_start (\(\varphi_k = \pi/2\)):
    !! \(p_{2k-1} = (X_{k-1} + \sin\varphi_k, -\cos\varphi_k)\), \(p_{2k} = (X_k, 0)\),
    !! \(X_k = X_{k-1} + 2\sin\varphi_k\), \(X_0 = 0\). With \(q = \Phi(\varphi)\), \(J = \Phi'\):
    !! \(J^T J \ddot\varphi = J^T (f - h)\), \(h = \sum_k \partial^2\Phi/\partial\varphi_k^2\,
    !! \dot\varphi_k^2\), f the weights. J has full column rank everywhere (column k holds the
    !! unit vector \((\cos\varphi_k, \sin\varphi_k)\) at joint 2k-1, where the earlier columns
    !! are 0), so the ODE is regular through the folds (\(\sin\varphi_k = 0\)) where G loses rank;
    !! the smooth motion stays on this branch there unless \(\dot\varphi_k = 0\) at the fold.
    !! N = 2 is slider_crank_reduced. State y = (\(\varphi_1 \dots \varphi_K, \dot\varphi_1 \dots
    !! \dot\varphi_K\)).
    type, extends(chain_reduced), public :: chain_slider_reduced
    contains
        procedure :: rhs => slider_reduced_rhs
    end type chain_slider_reduced

    !> The plain chain (unit links and masses, gravity g, no springs) in the angles \(\theta_i\)
    !! of its links from the downward vertical: \(p_i = \sum_{j \le i} (\sin\theta_j, -\cos\theta_j)\).
    !! Lagrange's equations, with \(c_{jk} = N + 1 - \max(j, k)\) (the joints beyond both links):
    !! \(\sum_k c_{jk} [\cos(\theta_j - \theta_k) \ddot\theta_k + \sin(\theta_j - \theta_k)
    !! \dot\theta_k^2] = -g (N + 1 - j) \sin\theta_j\); the mass matrix
    !! \(c_{jk} \cos(\theta_j - \theta_k)\) is positive definite at every configuration (the plain
    !! chain has no singular one), solved dense by Cholesky: O(N^3) per evaluation. The start
    !! chain_start is \(\theta_i = \pi/2\) at rest. State y = (\(\theta_1 \dots \theta_N,
    !! \dot\theta_1 \dots \dot\theta_N\)).
    type, extends(chain_reduced), public :: chain_plain_reduced
    contains
        procedure :: rhs => plain_reduced_rhs
    end type chain_plain_reduced

    !> chain_slider_reduced's ODE with its slope in O(N) (the same equations, the same state): an
    !! articulated-body recursion over the pairs. The pairs k..K, hung from joint 2k-2 (which
    !! moves along the line with acceleration \(\ddot X_{k-1}\)), need the horizontal force
    !! \(\alpha_k \ddot X_{k-1} + \beta_k\) there (the vertical one is the slider's or the pivot's).
    !! With \(s, c = \sin\varphi_k, \cos\varphi_k\), \(\omega = \dot\varphi_k\), \(\alpha' , \beta'\) those of
    !! the pairs beyond (0 after the last), \(\kappa = 3 + 2\alpha'\), \(D = 1 + 4c^2(1 + \alpha')\),
    !! \(r = g s - 4 c s (1 + \alpha') \omega^2 + 2 c \beta'\), pair k's equation (virtual work along
    !! \(\delta\varphi_k\), the elbow moving by \((c, s)\,\delta\varphi_k\), joint 2k by \(2c\,\delta\varphi_k\)) is
    !! \(D \ddot\varphi_k = -(c \kappa \ddot X_{k-1} + r)\), and the horizontal momentum of the pairs k..K gives
    !! \(\alpha_k = 2 + \alpha' - c^2\kappa^2/D\), \(\beta_k = \beta' - s\kappa\omega^2 - c\kappa r/D\). Inward
    !! for \(\alpha, \beta\), outward from \(\ddot X_0 = 0\) with \(\ddot X_k = \ddot X_{k-1} + 2c\ddot\varphi_k -
    !! 2s\omega^2\). D >= 1: regular through the folds.
    type, extends(chain_slider_reduced), public :: chain_slider_recursive
    contains
        procedure :: rhs => slider_recursive_rhs
    end type chain_slider_recursive

    !> chain_plain_reduced's ODE with its slope in O(N) (the same equations, the same state): the
    !! articulated-body recursion of a chain of point masses on massless pinned links. The links
    !! i+1..N with their masses, seen at joint i, need the force \(A_i \ddot p_i + b_i\) there
    !! (A_i 2 x 2 symmetric positive definite); link i carries only a force along
    !! \(u_i = (\sin\theta_i, -\cos\theta_i)\), so with \(n_i = (\cos\theta_i, \sin\theta_i)\) and
    !! \(\ddot p_i = \ddot p_{i-1} + \ddot\theta_i n_i - \dot\theta_i^2 u_i\),
    !! \(n_i^T (A_i \ddot p_i + b_i) = 0\) gives \(\ddot\theta_i = -(n_i^T A_i (\ddot p_{i-1} - \dot\theta_i^2
    !! u_i) + n_i^T b_i) / n_i^T A_i n_i\). Inward from \(A_N = I\), \(b_N = (0, g)\): with
    !! \(w = b_i - \dot\theta_i^2 A_i u_i\), \(A_{i-1} = I + A_i - A_i n_i n_i^T A_i / n_i^T A_i n_i\),
    !! \(b_{i-1} = (0, g) + w - A_i n_i\, n_i^T w / n_i^T A_i n_i\); outward from \(\ddot p_0 = 0\).
    type, extends(chain_plain_reduced), public :: chain_plain_recursive
    contains
        procedure :: rhs => plain_recursive_rhs
    end type chain_plain_recursive

    public :: new_chain, chain_start, chain_energy_of, chain_violation, chain_slider_joints, chain_plain_joints

contains

    function new_chain(links, slider, gravity) result(p)
        integer, intent(in) :: links
        logical, intent(in) :: slider
        real(wp), intent(in) :: gravity
        type(chain) :: p
        p%links = links
        p%slider = slider
        p%gravity = gravity
        p%length = 1.0_wp
        p%joint_mass = 1.0_wp
        p%n = 2*links
        p%m = links + merge(links/2, 0, slider)
    end function new_chain

    !> The straight horizontal chain along +x at rest (consistent with the slider too).
    subroutine chain_start(p, q0, v0)
        type(chain), intent(in) :: p
        real(wp), intent(out) :: q0(:), v0(:)
        integer :: i
        do i = 1, p%links
            q0(2*i - 1) = i*p%length
            q0(2*i) = 0.0_wp
        end do
        v0 = 0.0_wp
    end subroutine chain_start

    function chain_structure(self) result(st)
        class(chain), intent(in) :: self
        type(mechanical_structure) :: st
        integer, allocatable :: rows(:), cols(:)
        integer :: i, k
        st%declared = .true.
        st%curvature_supplied = .true.
        st%mass_constant = .true.   ! every joint's mass, whatever q
        st%mass = diagonal_pattern(self%n)
        st%force_q = empty_pattern(self%n, self%n)
        st%force_v = empty_pattern(self%n, self%n)
        if (self%stiffness /= 0.0_wp) st%force_q = vertical_diagonal(self%n)
        if (self%damping /= 0.0_wp) st%force_v = vertical_diagonal(self%n)
        allocate (rows(5*self%links), cols(5*self%links))
        k = 0
        do i = 1, self%links   ! row i: x_{i-1}, y_{i-1}, x_i, y_i (the pivot has no coordinates)
            if (i > 1) call add(i, 2*i - 3)
            if (i > 1) call add(i, 2*i - 2)
            call add(i, 2*i - 1)
            call add(i, 2*i)
        end do
        if (self%slider) then
            do i = 1, self%links/2
                call add(self%links + i, 4*i)   ! y of joint 2i
            end do
        end if
        st%constraint = pattern_from_entries(self%m, self%n, rows(1:k), cols(1:k))
    contains
        subroutine add(r, c)
            integer, intent(in) :: r, c
            k = k + 1
            rows(k) = r
            cols(k) = c
        end subroutine add
    end function chain_structure

    ! The y entries of the diagonal (the springs and dashpots act on y_i alone).
    function vertical_diagonal(n) result(p)
        integer, intent(in) :: n
        type(sparsity_pattern) :: p
        integer :: i
        p = pattern_from_entries(n, n, [(2*i, i=1, n/2)], [(2*i, i=1, n/2)])
    end function vertical_diagonal

    ! p_i - p_{i-1} and v_i - v_{i-1} (the pivot is fixed at the origin).
    pure subroutine link(self, i, q, d)
        class(chain), intent(in) :: self
        integer, intent(in) :: i
        real(wp), intent(in) :: q(:)
        real(wp), intent(out) :: d(2)
        d = q(2*i - 1:2*i)
        if (i > 1) d = d - q(2*i - 3:2*i - 2)
    end subroutine link

    subroutine chain_mass(self, t, q, mass, stat)
        class(chain), intent(inout) :: self
        real(wp), intent(in) :: t, q(:)
        real(wp), intent(out) :: mass(:, :)
        integer, intent(inout) :: stat
        integer :: i
        mass = 0.0_wp
        do i = 1, self%n
            mass(i, i) = self%joint_mass
        end do
    end subroutine chain_mass

    subroutine chain_mass_values(self, t, q, pattern, vals, stat)
        class(chain), intent(inout) :: self
        real(wp), intent(in) :: t, q(:)
        type(sparsity_pattern), intent(in) :: pattern
        real(wp), intent(out) :: vals(:)
        integer, intent(inout) :: stat
        vals = self%joint_mass
    end subroutine chain_mass_values

    subroutine chain_forces(self, t, q, qd, f, stat)
        class(chain), intent(inout) :: self
        real(wp), intent(in) :: t, q(:), qd(:)
        real(wp), intent(out) :: f(:)
        integer, intent(inout) :: stat
        f(1::2) = 0.0_wp
        f(2::2) = -self%gravity*self%joint_mass - self%stiffness*q(2::2) - self%damping*qd(2::2)
    end subroutine chain_forces

    subroutine chain_g(self, t, x, val, stat)
        class(chain), intent(inout) :: self
        real(wp), intent(in) :: t, x(:)
        real(wp), intent(out) :: val(:)
        integer, intent(inout) :: stat
        real(wp) :: d(2)
        integer :: i
        do i = 1, self%links
            call link(self, i, x, d)
            val(i) = (d(1)**2 + d(2)**2 - self%length**2)/(2.0_wp*self%length)
        end do
        if (self%slider) val(self%links + 1:self%m) = x(4::4)
    end subroutine chain_g

    subroutine chain_gx(self, t, x, a, stat)
        class(chain), intent(inout) :: self
        real(wp), intent(in) :: t, x(:)
        real(wp), intent(out) :: a(:, :)
        integer, intent(inout) :: stat
        real(wp) :: d(2)
        integer :: i
        a = 0.0_wp
        do i = 1, self%links
            call link(self, i, x, d)
            a(i, 2*i - 1:2*i) = d/self%length
            if (i > 1) a(i, 2*i - 3:2*i - 2) = -d/self%length
        end do
        if (self%slider) then
            do i = 1, self%links/2
                a(self%links + i, 4*i) = 1.0_wp
            end do
        end if
    end subroutine chain_gx

    ! G in the order of chain_structure's pattern (rows by link, columns increasing).
    subroutine chain_gx_values(self, t, q, pattern, vals, stat)
        class(chain), intent(inout) :: self
        real(wp), intent(in) :: t, q(:)
        type(sparsity_pattern), intent(in) :: pattern
        real(wp), intent(out) :: vals(:)
        integer, intent(inout) :: stat
        real(wp) :: d(2)
        integer :: i, k
        k = 0
        do i = 1, self%links
            call link(self, i, q, d)
            d = d/self%length
            if (i > 1) then
                vals(k + 1:k + 2) = -d
                k = k + 2
            end if
            vals(k + 1:k + 2) = d
            k = k + 2
        end do
        if (self%slider) vals(k + 1:k + self%links/2) = 1.0_wp
    end subroutine chain_gx_values

    subroutine chain_gt(self, t, x, val, stat)
        class(chain), intent(inout) :: self
        real(wp), intent(in) :: t, x(:)
        real(wp), intent(out) :: val(:)
        integer, intent(inout) :: stat
        val = 0.0_wp
    end subroutine chain_gt

    subroutine chain_curvature(self, t, x, v, val, stat)
        class(chain), intent(inout) :: self
        real(wp), intent(in) :: t, x(:), v(:)
        real(wp), intent(out) :: val(:)
        integer, intent(inout) :: stat
        real(wp) :: dv(2)
        integer :: i
        do i = 1, self%links
            call link(self, i, v, dv)
            val(i) = (dv(1)**2 + dv(2)**2)/self%length
        end do
        if (self%slider) val(self%links + 1:self%m) = 0.0_wp
    end subroutine chain_curvature

    !> The energy of the state (q, v) (the invariant; the chain's energy does not depend on t).
    real(wp) function chain_energy_of(p, q, v) result(e)
        type(chain), intent(inout) :: p
        real(wp), intent(in) :: q(:), v(:)
        integer :: ustat
        ustat = 0
        call p%invariant(0.0_wp, q, v, e, ustat)
    end function chain_energy_of

    !> max |g(q)|: how far q is from the constraints.
    real(wp) function chain_violation(p, q) result(drift)
        type(chain), intent(inout) :: p
        real(wp), intent(in) :: q(:)
        real(wp) :: g(p%m)
        integer :: ustat
        ustat = 0
        call p%constraint(0.0_wp, q, g, ustat)
        drift = maxval(abs(g))
    end function chain_violation

    !> Kinetic plus potential energy.
    subroutine chain_energy(self, t, x, v, val, stat)
        class(chain), intent(inout) :: self
        real(wp), intent(in) :: t, x(:), v(:)
        real(wp), intent(out) :: val
        integer, intent(inout) :: stat
        val = 0.5_wp*self%joint_mass*sum(v**2) + self%joint_mass*self%gravity*sum(x(2::2)) + &
              0.5_wp*self%stiffness*sum(x(2::2)**2)
    end subroutine chain_energy

    !> The joints q and their velocities v (2N each) of the slider chain at the reduced state
    !! y (chain_slider_reduced), and J (2N, K) = dq/dphi, h (2N) = the quadratic part of q''.
    pure subroutine chain_slider_joints(y, q, v, jac, h)
        real(wp), intent(in) :: y(:)   !! (2K): the angles, then their rates
        real(wp), intent(out) :: q(:), v(:)
        real(wp), intent(out), optional :: jac(:, :), h(:)
        real(wp) :: jl(2*size(y), size(y)/2), hl(2*size(y)), s, c, w, x_left, hx_left
        integer :: k, n_pairs, col
        n_pairs = size(y)/2
        jl = 0.0_wp
        hl = 0.0_wp
        x_left = 0.0_wp
        hx_left = 0.0_wp
        do k = 1, n_pairs
            s = sin(y(k))
            c = cos(y(k))
            w = y(n_pairs + k)
            q(4*k - 3) = x_left + s
            q(4*k - 2) = -c
            q(4*k - 1) = x_left + 2.0_wp*s
            q(4*k) = 0.0_wp
            x_left = q(4*k - 1)
            ! the x of joints 2k-1 and 2k move with every earlier crank (2 cos each), y only with its own
            do col = 1, k - 1
                jl(4*k - 3, col) = jl(4*k - 5, col)
                jl(4*k - 1, col) = jl(4*k - 5, col)
            end do
            jl(4*k - 3, k) = c
            jl(4*k - 2, k) = s
            jl(4*k - 1, k) = 2.0_wp*c
            hl(4*k - 3) = hx_left - s*w**2
            hl(4*k - 2) = c*w**2
            hl(4*k - 1) = hx_left - 2.0_wp*s*w**2
            hx_left = hl(4*k - 1)
        end do
        v = matmul(jl, y(n_pairs + 1:))
        if (present(jac)) jac = jl
        if (present(h)) h = hl
    end subroutine chain_slider_joints

    ! The reduced ODE: J^T J phi'' = J^T (f - h), by Cholesky (J^T J is positive definite).
    subroutine slider_reduced_rhs(self, t, y, ydot)
        class(chain_slider_reduced), intent(inout) :: self
        real(wp), intent(in) :: t, y(:)
        real(wp), intent(out) :: ydot(:)
        real(wp) :: q(2*self%links), v(2*self%links), jac(2*self%links, self%links/2), h(2*self%links)
        real(wp) :: f(2*self%links), a(self%links/2, self%links/2), b(self%links/2)
        integer :: n_pairs
        n_pairs = self%links/2
        call chain_slider_joints(y, q, v, jac, h)
        f = 0.0_wp
        f(2::2) = -self%gravity
        a = matmul(transpose(jac), jac)
        b = matmul(transpose(jac), f - h)
        call cholesky_solve(a, b)
        ydot(:n_pairs) = y(n_pairs + 1:)
        ydot(n_pairs + 1:) = b
    end subroutine slider_reduced_rhs

    !> The joints q and their velocities v (2N each) of the plain chain at the reduced state y
    !! (chain_plain_reduced): \(p_i = \sum_{j \le i} (\sin\theta_j, -\cos\theta_j)\).
    pure subroutine chain_plain_joints(y, q, v)
        real(wp), intent(in) :: y(:)   !! (2N): the angles, then their rates
        real(wp), intent(out) :: q(:), v(:)
        real(wp) :: p(2), w(2)
        integer :: i, links
        links = size(y)/2
        p = 0.0_wp
        w = 0.0_wp
        do i = 1, links
            p = p + [sin(y(i)), -cos(y(i))]
            w = w + [cos(y(i)), sin(y(i))]*y(links + i)
            q(2*i - 1:2*i) = p
            v(2*i - 1:2*i) = w
        end do
    end subroutine chain_plain_joints

    ! The plain chain's Lagrange equations (chain_plain_reduced), with cos(a - b) and sin(a - b)
    ! expanded so that the right side costs O(N^2) trigonometric-free products.
    subroutine plain_reduced_rhs(self, t, y, ydot)
        class(chain_plain_reduced), intent(inout) :: self
        real(wp), intent(in) :: t, y(:)
        real(wp), intent(out) :: ydot(:)
        real(wp) :: s(self%links), c(self%links), w2(self%links), a(self%links, self%links), b(self%links)
        real(wp) :: weight, sum_c, sum_s
        integer :: j, k, n
        n = self%links
        s = sin(y(:n))
        c = cos(y(:n))
        w2 = y(n + 1:)**2
        do j = 1, n
            do k = 1, j
                a(k, j) = real(n + 1 - j, wp)*(c(j)*c(k) + s(j)*s(k))   ! upper triangle, max(j, k) = j
            end do
        end do
        do j = 1, n
            sum_c = 0.0_wp
            sum_s = 0.0_wp
            do k = 1, n
                weight = real(n + 1 - max(j, k), wp)*w2(k)
                sum_c = sum_c + weight*c(k)
                sum_s = sum_s + weight*s(k)
            end do
            ! - sum_k c_jk sin(th_j - th_k) w_k^2 - g (N + 1 - j) sin th_j
            b(j) = -(s(j)*sum_c - c(j)*sum_s) - self%gravity*real(n + 1 - j, wp)*s(j)
        end do
        call cholesky_solve(a, b)
        ydot(:n) = y(n + 1:)
        ydot(n + 1:) = b
    end subroutine plain_reduced_rhs

    ! chain_slider_recursive's slope: alpha, beta inward, the accelerations outward (O(K)).
    subroutine slider_recursive_rhs(self, t, y, ydot)
        class(chain_slider_recursive), intent(inout) :: self
        real(wp), intent(in) :: t, y(:)
        real(wp), intent(out) :: ydot(:)
        real(wp) :: s(self%links/2), c(self%links/2), w2(self%links/2), ck(self%links/2), d(self%links/2), &
                    r(self%links/2)
        real(wp) :: alpha, beta, kappa, xdd
        integer :: k, n_pairs
        n_pairs = self%links/2
        s = sin(y(:n_pairs))
        c = cos(y(:n_pairs))
        w2 = y(n_pairs + 1:)**2
        alpha = 0.0_wp   ! the pairs beyond the last
        beta = 0.0_wp
        do k = n_pairs, 1, -1
            kappa = 3.0_wp + 2.0_wp*alpha
            d(k) = 1.0_wp + 4.0_wp*c(k)**2*(1.0_wp + alpha)
            r(k) = self%gravity*s(k) - 4.0_wp*c(k)*s(k)*(1.0_wp + alpha)*w2(k) + 2.0_wp*c(k)*beta
            ck(k) = c(k)*kappa
            alpha = 2.0_wp + alpha - ck(k)**2/d(k)
            beta = beta - s(k)*kappa*w2(k) - ck(k)*r(k)/d(k)
        end do
        xdd = 0.0_wp   ! the pivot
        do k = 1, n_pairs
            ydot(n_pairs + k) = -(ck(k)*xdd + r(k))/d(k)
            xdd = xdd + 2.0_wp*(c(k)*ydot(n_pairs + k) - s(k)*w2(k))
        end do
        ydot(:n_pairs) = y(n_pairs + 1:)
    end subroutine slider_recursive_rhs

    ! chain_plain_recursive's slope: A_i, b_i inward, the accelerations outward (O(N)).
    subroutine plain_recursive_rhs(self, t, y, ydot)
        class(chain_plain_recursive), intent(inout) :: self
        real(wp), intent(in) :: t, y(:)
        real(wp), intent(out) :: ydot(:)
        real(wp) :: an(2, self%links), z(self%links), d(self%links), u(2, self%links), nv(2, self%links)
        real(wp) :: a11, a12, a22, b(2), w(2), au(2), pdd(2), w2
        integer :: i, n
        n = self%links
        nv(1, :) = cos(y(:n))
        nv(2, :) = sin(y(:n))
        u(1, :) = nv(2, :)
        u(2, :) = -nv(1, :)
        a11 = 1.0_wp   ! joint N alone
        a12 = 0.0_wp
        a22 = 1.0_wp
        b = [0.0_wp, self%gravity]
        do i = n, 1, -1
            w2 = y(n + i)**2
            an(:, i) = [a11*nv(1, i) + a12*nv(2, i), a12*nv(1, i) + a22*nv(2, i)]
            d(i) = nv(1, i)*an(1, i) + nv(2, i)*an(2, i)
            au = [a11*u(1, i) + a12*u(2, i), a12*u(1, i) + a22*u(2, i)]
            w = b - w2*au
            z(i) = nv(1, i)*w(1) + nv(2, i)*w(2)
            ! joint i-1 with what links i..N pass on to it
            a11 = 1.0_wp + a11 - an(1, i)**2/d(i)
            a12 = a12 - an(1, i)*an(2, i)/d(i)
            a22 = 1.0_wp + a22 - an(2, i)**2/d(i)
            b = [0.0_wp, self%gravity] + w - an(:, i)*(z(i)/d(i))
        end do
        pdd = 0.0_wp   ! the pivot
        do i = 1, n
            ydot(n + i) = -(an(1, i)*pdd(1) + an(2, i)*pdd(2) + z(i))/d(i)
            pdd = pdd + ydot(n + i)*nv(:, i) - y(n + i)**2*u(:, i)
        end do
        ydot(:n) = y(n + 1:)
    end subroutine plain_recursive_rhs

    ! b := A^-1 b for A symmetric positive definite, given in its upper triangle (overwritten by
    ! U, A = U^T U; columns contiguous).
    pure subroutine cholesky_solve(a, b)
        real(wp), intent(inout) :: a(:, :), b(:)
        integer :: j, k, n
        n = size(b)
        do k = 1, n
            a(k, k) = sqrt(a(k, k) - sum(a(:k - 1, k)**2))
            do j = k + 1, n
                a(k, j) = (a(k, j) - sum(a(:k - 1, k)*a(:k - 1, j)))/a(k, k)
            end do
        end do
        do k = 1, n
            b(k) = (b(k) - sum(a(:k - 1, k)*b(:k - 1)))/a(k, k)
        end do
        do k = n, 1, -1
            b(k) = (b(k) - sum(a(k, k + 1:)*b(k + 1:)))/a(k, k)
        end do
    end subroutine cholesky_solve

end module chain_problem
