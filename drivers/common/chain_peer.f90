!> The benchmark peer of the chain driver: a planar N-link chain integrated with
!! plain SUNDIALS IDA, as a user would write it without regdae.
!!
!! The chain: N links of length \(L = 1\), unit point masses at joints 1..N,
!! joint 0 a fixed pivot at the origin, gravity 9.81 in \(-y\), optionally light joints on stiff
!! vertical springs and dashpots (forces \(-k y_i - c y_i'\)) as the stiff variant;
!! \(q = (x_1, y_1, \dots, x_N, y_N)\), link constraints
!! \(g_i = (|p_i - p_{i-1}|^2 - L^2)/(2L)\), \(i = 1, \dots, N\), and with the slider
!! (N even) every even joint on the horizontal line through the pivot,
!! \(g_{N+k} = y_{2k}\), \(k = 1, \dots, N/2\) (as in drivers/problems/chain_problem.f90;
!! N = 2 is the slider crank of Example 5.2).
!! Start: the straight horizontal chain \(p_i = (iL, 0)\) at rest.
!!
!! The formulation: stabilized index 2 (Gear-Gupta-Leimkuhler),
!! $$ q' = v + G^T\mu,\quad M v' = f + G^T\lambda,\quad G v = 0,\quad g(q) = 0, $$
!! \(\lambda, \mu\) algebraic and out of the error test (FIDASetId + FIDASetSuppressAlg).
!! The unknowns are ordered joint by joint, \((x_i, y_i, v_{x,i}, v_{y,i}, \lambda_i, \mu_i)\) with
!! \(\lambda_i, \mu_i\) those of link i (joint i-1 to joint i), and with the slider each even
!! joint 2k's block followed by its slider's \((\lambda_{N+k}, \mu_{N+k})\); each equation sits at
!! the row of its unknown, so the Jacobian is banded with bandwidths independent of N
!! (computed by `chain_bandwidth`: 11, with the slider 13).
!! IDA's band linear solver with its own difference-quotient band Jacobian. Only for the benchmark.
module chain_peer
    use, intrinsic :: iso_c_binding
    use, intrinsic :: iso_fortran_env, only: int64
    use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
    use fida_mod
    use fsundials_context_mod
    use fsundials_nvector_mod
    use fnvector_serial_mod
    use fsundials_matrix_mod
    use fsunmatrix_band_mod
    use fsundials_linearsolver_mod
    use fsunlinsol_band_mod
    use regdae, only: wp, format_real, c_string
    implicit none
    private

    public :: run_chain_peer

    !> Gravitational acceleration (in \(-y\)).
    real(wp), parameter :: gravity = 9.81_wp
    !> Unknowns per joint, and the offset of each inside a joint's block; with the slider an
    !! even joint's block has two more, its slider's multipliers (off_slider_lambda, off_slider_mu).
    integer, parameter :: block_size = 6, slider_block_size = 2
    integer, parameter :: off_x = 1, off_y = 2, off_vx = 3, off_vy = 4, off_lambda = 5, off_mu = 6
    integer, parameter :: off_slider_lambda = 7, off_slider_mu = 8
    !> IDA's step limit per output interval.
    integer(c_long), parameter :: max_steps = 100000_c_long
    !> Half bandwidth of \(G M^{-1} G^T\) in the constraint order link 1, link 2, slider 1,
    !! link 3, ... (the order of the multipliers in the unknowns).
    integer, parameter :: gram_width = 2
    !> A Cholesky pivot below this times its diagonal entry: \(G M^{-1} G^T\) singular.
    real(wp), parameter :: pivot_tol = 1.0e3_wp*epsilon(1.0_wp)

    !> The problem, passed to the residual through IDA's user_data.
    type :: chain_data
        integer :: n_links = 1
        logical :: slider = .false.
        real(wp) :: link = 1.0_wp        !! link length L (unit links)
        real(wp) :: mass = 1.0_wp        !! mass of each joint 1..N (unit masses)
        real(wp) :: stiffness = 0.0_wp   !! vertical spring k y under every joint (0: none)
        real(wp) :: damping = 0.0_wp     !! vertical dashpot c y' under every joint (0: none)
        character(len=:), allocatable :: ida_message   !! IDA's last error message
    end type chain_data

contains

    !> Integrate the chain to the times `times` (times(1) = t0, increasing; the chain
    !! starts there straight, horizontal, at rest) and return the positions q at each
    !! output time in `q_out(:, k)` (shape (2 n_links, size(times)); NaN after a failure).
    !! With `slider` (n_links even) every even joint rides on the line y = 0.
    !! `steps`, `res_evals` (including the difference-quotient Jacobian's) and
    !! `jac_evals` are IDA's counters; `seconds` the wall-clock time of the IDA setup
    !! (band matrix, linear solver, FIDACreate to FIDASetLinearSolver) and the FIDASolve
    !! calls, nothing else. `stat` is 0 or IDA's negative flag (IDA_ILL_INPUT for bad
    !! arguments, odd n_links with the slider), `message` empty on success, else the cause.
    !! `max_drift` is the largest
    !! \(|g_i(q)|\) over the outputs reached.
    subroutine run_chain_peer(n_links, slider, rtol, atol, times, q_out, steps, res_evals, jac_evals, seconds, stat, &
                              message, max_drift, joint_mass, stiffness, damping, v_out)
        integer, intent(in) :: n_links
        logical, intent(in) :: slider
        real(wp), intent(in) :: rtol, atol, times(:)
        real(wp), intent(out) :: q_out(:, :)
        integer, intent(out) :: steps, res_evals, jac_evals
        real(wp), intent(out) :: seconds
        integer, intent(out) :: stat
        character(len=:), allocatable, intent(out) :: message
        real(wp), intent(out), optional :: max_drift
        real(wp), intent(in), optional :: joint_mass   !! mass of each joint (default 1)
        real(wp), intent(in), optional :: stiffness    !! vertical springs k y under the joints (default 0)
        real(wp), intent(in), optional :: damping      !! vertical dashpots c y' under the joints (default 0)
        real(wp), intent(out), optional :: v_out(:, :) !! the joints' velocities at `times`, as q_out (NaN after a failure)
        type(chain_data), target :: data
        type(c_ptr) :: ctx, mem
        type(N_Vector), pointer :: uu, up, idv
        type(SUNMatrix), pointer :: a
        type(SUNLinearSolver), pointer :: ls
        real(c_double), pointer :: u(:), p(:)
        real(c_double) :: tret(1)
        integer(c_long) :: counter(1), neq, upper, lower
        integer(c_int) :: ierr
        integer(int64) :: c0, c1, rate, ticks
        real(wp) :: drift
        integer :: i, k
        logical :: consistent

        message = ''
        steps = 0
        res_evals = 0
        jac_evals = 0
        seconds = 0.0_wp
        stat = 0
        q_out = ieee_value(1.0_wp, ieee_quiet_nan)
        if (present(v_out)) v_out = ieee_value(1.0_wp, ieee_quiet_nan)
        drift = 0.0_wp
        consistent = .true.
        if (present(max_drift)) max_drift = ieee_value(1.0_wp, ieee_quiet_nan)
        call check_arguments(n_links, slider, rtol, atol, times, q_out, stat, message)
        if (stat /= 0) return

        data%n_links = n_links
        data%slider = slider
        data%link = 1.0_wp
        data%mass = 1.0_wp
        if (present(joint_mass)) data%mass = joint_mass
        if (present(stiffness)) data%stiffness = stiffness
        if (present(damping)) data%damping = damping
        data%ida_message = ''
        neq = int(unknown_count(data), c_long)
        call chain_bandwidth(data, upper, lower)

        ctx = c_null_ptr
        mem = c_null_ptr
        nullify (uu, up, idv, a, ls)
        ticks = 0_int64
        call system_clock(c0, rate)
        setup: block
            ierr = FSUNContext_Create(c_null_ptr, ctx)
            if (ierr /= 0) exit setup
            uu => FN_VNew_Serial(neq, ctx)
            up => FN_VNew_Serial(neq, ctx)
            idv => FN_VNew_Serial(neq, ctx)
            ierr = IDA_MEM_FAIL
            if (.not. (associated(uu) .and. associated(up) .and. associated(idv))) exit setup
            u => FN_VGetArrayPointer(uu)
            p => FN_VGetArrayPointer(up)
            call initial_state(data, u, p, consistent)
            if (.not. consistent) exit setup
            p => FN_VGetArrayPointer(idv)
            call differential_ids(data, p)

            call system_clock(c0, rate)
            a => FSUNBandMatrix(neq, upper, lower, ctx)
            if (.not. associated(a)) exit setup
            ls => FSUNLinSol_Band(uu, a, ctx)
            if (.not. associated(ls)) exit setup
            mem = FIDACreate(ctx)
            if (.not. c_associated(mem)) exit setup
            ierr = FIDASetErrHandlerFn(mem, c_funloc(chain_error_handler), c_loc(data))
            if (ierr == 0) ierr = FIDAInit(mem, c_funloc(chain_residual), times(1), uu, up)
            if (ierr == 0) ierr = FIDASStolerances(mem, rtol, atol)
            if (ierr == 0) ierr = FIDASetUserData(mem, c_loc(data))
            if (ierr == 0) ierr = FIDASetId(mem, idv)
            if (ierr == 0) ierr = FIDASetSuppressAlg(mem, 1_c_int)
            if (ierr == 0) ierr = FIDASetMaxNumSteps(mem, max_steps)
            if (ierr == 0) ierr = FIDASetLinearSolver(mem, ls, a)
            call system_clock(c1)
            ticks = ticks + (c1 - c0)
        end block setup
        if (.not. consistent) then
            stat = IDA_ILL_INPUT
            message = 'chain_peer: no consistent start (G M^-1 G^T is singular there)'
        else if (ierr /= 0) then
            stat = int(ierr)
            message = 'chain_peer: IDA setup failed (' // FIDAGetReturnFlagName(int(ierr, c_long)) // ')'
            if (len(data%ida_message) > 0) message = message // ': ' // data%ida_message
        else
            do k = 1, size(times)
                if (k > 1) then
                    call system_clock(c0)
                    ierr = FIDASolve(mem, times(k), tret, uu, up, IDA_NORMAL)
                    call system_clock(c1)
                    ticks = ticks + (c1 - c0)
                    if (ierr < 0) then
                        stat = int(ierr)
                        message = 'chain_peer: FIDASolve failed at t = ' // format_real(tret(1)) // ' (' &
                                  // FIDAGetReturnFlagName(int(ierr, c_long)) // ')'
                        if (len(data%ida_message) > 0) message = message // ': ' // data%ida_message
                        exit
                    end if
                end if
                do i = 1, n_links
                    q_out(2*i - 1, k) = u(position(data, i, off_x))
                    q_out(2*i, k) = u(position(data, i, off_y))
                end do
                ! A loop of its own: with the test inside the loop gfortran -O3 branched on the
                ! absent v_out's descriptor (valgrind: uninitialised value).
                if (present(v_out)) then
                    do i = 1, n_links
                        v_out(2*i - 1, k) = u(position(data, i, off_vx))
                        v_out(2*i, k) = u(position(data, i, off_vy))
                    end do
                end if
                drift = max(drift, constraint_drift(data, u))
            end do
            if (present(max_drift)) max_drift = drift
        end if
        seconds = real(ticks, wp)/real(rate, wp)

        if (c_associated(mem)) then
            ierr = FIDAGetNumSteps(mem, counter)
            steps = int(counter(1))
            ierr = FIDAGetNumResEvals(mem, counter)
            res_evals = int(counter(1))
            ierr = FIDAGetNumLinResEvals(mem, counter)
            res_evals = res_evals + int(counter(1))
            ierr = FIDAGetNumJacEvals(mem, counter)
            jac_evals = int(counter(1))
            call FIDAFree(mem)
        end if
        if (associated(ls)) ierr = FSUNLinSolFree(ls)
        if (associated(a)) call FSUNMatDestroy(a)
        if (associated(idv)) call FN_VDestroy(idv)
        if (associated(up)) call FN_VDestroy(up)
        if (associated(uu)) call FN_VDestroy(uu)
        if (c_associated(ctx)) ierr = FSUNContext_Free(ctx)
    end subroutine run_chain_peer

    ! Refuse what IDA would refuse later, or what would overrun q_out.
    subroutine check_arguments(n_links, slider, rtol, atol, times, q_out, stat, message)
        integer, intent(in) :: n_links
        logical, intent(in) :: slider
        real(wp), intent(in) :: rtol, atol, times(:), q_out(:, :)
        integer, intent(inout) :: stat
        character(len=:), allocatable, intent(inout) :: message

        if (n_links < 1) then
            message = 'chain_peer: n_links must be at least 1'
        else if (slider .and. modulo(n_links, 2) /= 0) then
            message = 'chain_peer: the slider variant needs an even n_links (every even joint on the line)'
        else if (size(times) < 1) then
            message = 'chain_peer: no output time'
        else if (size(q_out, 1) /= 2*n_links .or. size(q_out, 2) /= size(times)) then
            message = 'chain_peer: q_out must have shape (2 n_links, size(times))'
        else if (.not. (rtol >= 0.0_wp .and. atol >= 0.0_wp)) then
            message = 'chain_peer: negative or NaN tolerance'
        else if (size(times) > 1) then
            if (any(.not. (times(2:) > times(:size(times) - 1)))) message = 'chain_peer: times must increase'
        end if
        if (len(message) > 0) stat = IDA_ILL_INPUT
    end subroutine check_arguments

    ! Index in the unknown vector of unknown `offset` of joint (or link) i; with the slider
    ! the blocks of the even joints before joint i hold two more unknowns each, and the
    ! offsets off_slider_lambda, off_slider_mu of an even joint are its slider's multipliers.
    pure integer function position(data, i, offset)
        type(chain_data), intent(in) :: data
        integer, intent(in) :: i, offset
        position = block_size*(i - 1) + offset
        if (data%slider) position = position + slider_block_size*((i - 1)/2)
    end function position

    pure integer function unknown_count(data)
        type(chain_data), intent(in) :: data
        unknown_count = block_size*data%n_links
        if (data%slider) unknown_count = unknown_count + slider_block_size*(data%n_links/2)
    end function unknown_count

    !> The upper and lower bandwidths of the residual's Jacobian for the joint-by-joint
    !! ordering. Each constraint couples only the unknowns of its own group: link i the
    !! positions and velocities of joints i-1 and i with (lambda_i, mu_i) (through G, G^T
    !! and g), slider k joint 2k with (lambda_{N+k}, mu_{N+k}), and each joint's
    !! q' = v + ..., M v' = f + ... its own block; inside a group the extreme entries are
    !! row x_{i-1} on mu_i and row mu_i on x_{i-1}, so both bandwidths are the widest group's
    !! span: 2 block_size - 1 = 11 for N >= 2, with the slider 13 for N >= 4 (link 2k+1
    !! spans the 8 unknowns of joint 2k's block; 11 for N = 2), capped at neq - 1.
    pure subroutine chain_bandwidth(data, upper, lower)
        type(chain_data), intent(in) :: data
        integer(c_long), intent(out) :: upper, lower
        integer :: i, k, span

        span = off_vy - off_x
        do i = 1, data%n_links
            span = max(span, position(data, i, off_mu) - position(data, max(i - 1, 1), off_x))
        end do
        if (data%slider) then
            do k = 1, data%n_links/2
                span = max(span, position(data, 2*k, off_slider_mu) - position(data, 2*k, off_x))
            end do
        end if
        upper = int(min(span, unknown_count(data) - 1), c_long)
        lower = upper
    end subroutine chain_bandwidth

    ! 1 for positions and velocities, 0 for the multipliers.
    pure subroutine differential_ids(data, id)
        type(chain_data), intent(in) :: data
        real(c_double), intent(out) :: id(:)
        integer :: i
        id = 0.0_wp
        do i = 1, data%n_links
            id(position(data, i, off_x):position(data, i, off_vy)) = 1.0_wp
        end do
    end subroutine differential_ids

    ! Index of link i's constraint, or with `is_slider` of the slider of joint i (even), in the
    ! order of the multipliers in the unknowns: link 1, link 2, slider 1, link 3, link 4, ...
    pure integer function constraint_row(data, i, is_slider)
        type(chain_data), intent(in) :: data
        integer, intent(in) :: i
        logical, intent(in) :: is_slider
        constraint_row = i
        if (data%slider) constraint_row = i + (i - 1)/2
        if (is_slider) constraint_row = constraint_row + 1
    end function constraint_row

    ! The constraints acting on joint j: their rows (constraint_row) and the 2-blocks of G at
    ! p_j: link j (d_j), link j+1 (-d_{j+1}), the slider of an even joint ((0, 1)).
    pure subroutine joint_constraints(data, y, j, rows, blocks, count)
        type(chain_data), intent(in) :: data
        real(c_double), intent(in) :: y(:)
        integer, intent(in) :: j
        integer, intent(out) :: rows(3), count
        real(wp), intent(out) :: blocks(2, 3)
        count = 1
        rows(1) = constraint_row(data, j, .false.)
        blocks(:, 1) = link_vector(data, y, j)/data%link
        if (j < data%n_links) then
            count = count + 1
            rows(count) = constraint_row(data, j + 1, .false.)
            blocks(:, count) = -link_vector(data, y, j + 1)/data%link
        end if
        if (data%slider .and. modulo(j, 2) == 0) then
            count = count + 1
            rows(count) = constraint_row(data, j, .true.)
            blocks(:, count) = [0.0_wp, 1.0_wp]
        end if
    end subroutine joint_constraints

    ! The straight horizontal chain at rest with consistent (lambda, mu) and y':
    ! mu = 0 (G q' = G v = 0), and (v', lambda) from
    !   M v' - G^T lambda = f,   G v' = -c,  c_i = |v_i - v_{i-1}|^2 / L for a link, 0 for a slider
    ! (the second derivative of g), i.e. (G M^{-1} G^T) lambda = -c - G M^{-1} f, banded with half
    ! bandwidth gram_width in the constraint order, symmetric positive definite while G has full
    ! rank (it has at the start). `consistent` is false if the Cholesky factorization breaks down.
    subroutine initial_state(data, y, yp, consistent)
        type(chain_data), intent(in) :: data
        real(c_double), intent(out) :: y(:), yp(:)
        logical, intent(out) :: consistent
        real(wp) :: gram(0:gram_width, data%n_links + data%n_links/2), lambda(data%n_links + data%n_links/2)
        real(wp) :: acc(2, data%n_links), blocks(2, 3), dv(2)
        integer :: rows(3), i, j, a, b, k, count, n, m

        n = data%n_links
        m = constraint_row(data, n, .false.)
        if (data%slider) m = constraint_row(data, n, .true.)
        y = 0.0_wp
        yp = 0.0_wp
        do i = 1, n
            y(position(data, i, off_x)) = i*data%link
        end do
        acc(1, :) = 0.0_wp
        acc(2, :) = -gravity
        gram = 0.0_wp
        lambda = 0.0_wp
        do i = 1, n
            dv = y(position(data, i, off_vx):position(data, i, off_vy))
            if (i > 1) dv = dv - y(position(data, i - 1, off_vx):position(data, i - 1, off_vy))
            lambda(constraint_row(data, i, .false.)) = -sum(dv**2)/data%link
        end do
        do j = 1, n
            call joint_constraints(data, y, j, rows, blocks, count)
            do a = 1, count
                lambda(rows(a)) = lambda(rows(a)) - dot_product(blocks(:, a), acc(:, j))
                do b = 1, count
                    k = rows(a) - rows(b)
                    if (k >= 0) gram(k, rows(a)) = gram(k, rows(a)) + dot_product(blocks(:, a), blocks(:, b))/data%mass
                end do
            end do
        end do
        call band_cholesky_solve(gram(:, :m), lambda(:m), consistent)
        if (.not. consistent) return
        ! v' = M^{-1} (f + G^T lambda).
        do j = 1, n
            call joint_constraints(data, y, j, rows, blocks, count)
            do a = 1, count
                acc(:, j) = acc(:, j) + blocks(:, a)*lambda(rows(a))/data%mass
            end do
            y(position(data, j, off_lambda)) = lambda(constraint_row(data, j, .false.))
            if (data%slider .and. modulo(j, 2) == 0) then
                y(position(data, j, off_slider_lambda)) = lambda(constraint_row(data, j, .true.))
            end if
        end do
        do i = 1, n
            yp(position(data, i, off_x):position(data, i, off_y)) = y(position(data, i, off_vx):position(data, i, off_vy))
            yp(position(data, i, off_vx):position(data, i, off_vy)) = acc(:, i)
        end do
    end subroutine initial_state

    ! Solve A x = b in place (b becomes x) for the symmetric positive definite band matrix A
    ! given by its lower band, ab(k, i) = A(i, i-k), k = 0..ubound(ab, 1), by Cholesky
    ! (overwriting ab with L). `ok` is false if a pivot is not positive (A singular).
    pure subroutine band_cholesky_solve(ab, b, ok)
        real(wp), intent(inout) :: ab(0:, :), b(:)
        logical, intent(out) :: ok
        real(wp) :: s
        integer :: width, n, i, j, k

        width = ubound(ab, 1)
        n = size(b)
        ok = .false.
        do i = 1, n
            do j = max(1, i - width), i
                s = ab(i - j, i)
                do k = max(1, i - width), j - 1
                    s = s - ab(i - k, i)*ab(j - k, j)
                end do
                if (j < i) then
                    ab(i - j, i) = s/ab(0, j)
                else
                    if (.not. s > pivot_tol*ab(0, i)) return
                    ab(0, i) = sqrt(s)
                end if
            end do
        end do
        do i = 1, n
            do k = max(1, i - width), i - 1
                b(i) = b(i) - ab(i - k, i)*b(k)
            end do
            b(i) = b(i)/ab(0, i)
        end do
        do i = n, 1, -1
            do k = i + 1, min(n, i + width)
                b(i) = b(i) - ab(k - i, k)*b(k)
            end do
            b(i) = b(i)/ab(0, i)
        end do
        ok = .true.
    end subroutine band_cholesky_solve

    ! p_i - p_{i-1} from the unknown vector (p_0 = 0).
    pure function link_vector(data, y, i) result(d)
        type(chain_data), intent(in) :: data
        real(c_double), intent(in) :: y(:)
        integer, intent(in) :: i
        real(wp) :: d(2)
        d = y(position(data, i, off_x):position(data, i, off_y))
        if (i > 1) d = d - y(position(data, i - 1, off_x):position(data, i - 1, off_y))
    end function link_vector

    ! max |g_i(q)| over the link constraints and the sliders'.
    pure real(wp) function constraint_drift(data, y) result(drift)
        type(chain_data), intent(in) :: data
        real(c_double), intent(in) :: y(:)
        integer :: i
        drift = 0.0_wp
        do i = 1, data%n_links
            drift = max(drift, abs((sum(link_vector(data, y, i)**2) - data%link**2)/(2.0_wp*data%link)))
            if (data%slider .and. modulo(i, 2) == 0) drift = max(drift, abs(y(position(data, i, off_y))))
        end do
    end function constraint_drift

    ! The GGL residual, each equation at the row of its unknown:
    !   rows x_i, y_i:       q_i' - v_i - (G^T mu)_i
    !   rows vx_i, vy_i:     M v_i' - f_i - (G^T lambda)_i
    !   row lambda_i:        G_i v = d_i . (v_i - v_{i-1})
    !   row mu_i:            g_i(q)
    ! and for slider k the rows lambda_{N+k}: vy_{2k}, mu_{N+k}: y_{2k}.
    integer(c_int) function chain_residual(t, nv_u, nv_up, nv_r, user_data) result(ierr) bind(C)
        real(c_double), value :: t
        type(N_Vector) :: nv_u, nv_up, nv_r
        type(c_ptr), value :: user_data
        type(chain_data), pointer :: data
        real(c_double), pointer :: u(:), up(:), r(:)
        real(wp) :: d(2), dv(2), lambda, mu
        integer :: i, jx, jv, px, pv, ls, ms, n

        call c_f_pointer(user_data, data)
        u => FN_VGetArrayPointer(nv_u)
        up => FN_VGetArrayPointer(nv_up)
        r => FN_VGetArrayPointer(nv_r)
        n = data%n_links
        do i = 1, n
            jx = position(data, i, off_x)
            jv = position(data, i, off_vx)
            r(jx:jx + 1) = up(jx:jx + 1) - u(jv:jv + 1)
            r(jv) = data%mass*up(jv)
            r(jv + 1) = data%mass*(up(jv + 1) + gravity) + data%stiffness*u(jx + 1) + data%damping*u(jv + 1)
        end do
        do i = 1, n
            jx = position(data, i, off_x)
            jv = position(data, i, off_vx)
            d = link_vector(data, u, i)
            lambda = u(position(data, i, off_lambda))
            mu = u(position(data, i, off_mu))
            r(position(data, i, off_mu)) = (sum(d**2) - data%link**2)/(2.0_wp*data%link)
            d = d/data%link
            dv = u(jv:jv + 1)
            r(jx:jx + 1) = r(jx:jx + 1) - mu*d
            r(jv:jv + 1) = r(jv:jv + 1) - lambda*d
            if (i > 1) then
                px = position(data, i - 1, off_x)
                pv = position(data, i - 1, off_vx)
                dv = dv - u(pv:pv + 1)
                r(px:px + 1) = r(px:px + 1) + mu*d
                r(pv:pv + 1) = r(pv:pv + 1) + lambda*d
            end if
            r(position(data, i, off_lambda)) = dot_product(d, dv)
        end do
        if (data%slider) then
            do i = 2, n, 2
                jx = position(data, i, off_y)
                jv = position(data, i, off_vy)
                ls = position(data, i, off_slider_lambda)
                ms = position(data, i, off_slider_mu)
                r(jx) = r(jx) - u(ms)
                r(jv) = r(jv) - u(ls)
                r(ls) = u(jv)
                r(ms) = u(jx)
            end do
        end if
        ierr = 0
    end function chain_residual

    ! Keep IDA's last message in the problem data instead of printing it.
    subroutine chain_error_handler(error_code, module_name, function_name, msg, user_data) bind(C)
        integer(c_int), value :: error_code
        type(c_ptr), value :: module_name, function_name, msg
        type(c_ptr), value :: user_data
        type(chain_data), pointer :: data

        if (error_code >= 0) return
        call c_f_pointer(user_data, data)
        data%ida_message = c_string(function_name) // ': ' // c_string(msg)
    end subroutine chain_error_handler

end module chain_peer
