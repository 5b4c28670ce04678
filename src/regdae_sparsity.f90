!> Sparsity patterns: which entries of a matrix may be nonzero, stored by rows
!! (compressed sparse row, column indices sorted within each row).
!!
!! Used to declare the structure of a problem's matrices (M, G, the Jacobians
!! of the forces), to build the pattern of the Newton matrix IDA factors, to
!! group its columns for difference quotients (Curtis, Powell and Reid: columns
!! that share no row are perturbed together) and to order the unknowns so that
!! the matrix is banded (reverse Cuthill-McKee).
module regdae_sparsity
    use regdae_kinds, only: wp
    implicit none
    private

    !> The positions of the entries that may be nonzero, row by row.
    type, public :: sparsity_pattern
        integer :: nrows = 0                       !! rows
        integer :: ncols = 0                       !! columns
        integer, allocatable :: row_start(:)       !! nrows + 1: row i holds cols(row_start(i):row_start(i+1)-1)
        integer, allocatable :: cols(:)            !! column indices, increasing within a row
    contains
        !> Number of entries.
        procedure :: nnz => pattern_nnz
        !> Index k of entry (i, j) in `cols` (and in a values array in pattern order), 0 if absent.
        procedure :: position => pattern_position
        !> The pattern of the transpose.
        procedure :: transposed => pattern_transposed
        !> The row and column of every entry, in pattern order.
        procedure :: entries => pattern_entries
    end type sparsity_pattern

    public :: dense_pattern, empty_pattern, diagonal_pattern, band_pattern, pattern_from_entries, pattern_union
    public :: color_columns, column_groups, reverse_cuthill_mckee, permuted_bandwidths, sparse_times

contains

    pure integer function pattern_nnz(self)
        class(sparsity_pattern), intent(in) :: self
        pattern_nnz = 0
        if (allocated(self%row_start)) pattern_nnz = self%row_start(self%nrows + 1) - 1
    end function pattern_nnz

    pure integer function pattern_position(self, i, j) result(k)
        class(sparsity_pattern), intent(in) :: self
        integer, intent(in) :: i, j
        integer :: lo, hi, mid
        k = 0
        if (i < 1 .or. i > self%nrows) return
        lo = self%row_start(i)
        hi = self%row_start(i + 1) - 1
        do while (lo <= hi)   ! binary search in the sorted row
            mid = (lo + hi)/2
            if (self%cols(mid) == j) then
                k = mid
                return
            else if (self%cols(mid) < j) then
                lo = mid + 1
            else
                hi = mid - 1
            end if
        end do
    end function pattern_position

    !> y = A x for the matrix A with pattern p and its entries `vals` in pattern order.
    pure function sparse_times(p, vals, x) result(y)
        type(sparsity_pattern), intent(in) :: p
        real(wp), intent(in) :: vals(:)   !! p%nnz() entries
        real(wp), intent(in) :: x(:)      !! length p%ncols
        real(wp) :: y(p%nrows)
        integer :: i, k
        do i = 1, p%nrows
            y(i) = 0.0_wp
            do k = p%row_start(i), p%row_start(i + 1) - 1
                y(i) = y(i) + vals(k)*x(p%cols(k))
            end do
        end do
    end function sparse_times

    subroutine pattern_entries(self, rows, cols)
        class(sparsity_pattern), intent(in) :: self
        integer, allocatable, intent(out) :: rows(:), cols(:)
        integer :: i
        allocate (rows(self%nnz()))
        do i = 1, self%nrows
            rows(self%row_start(i):self%row_start(i + 1) - 1) = i
        end do
        cols = self%cols(1:self%nnz())
    end subroutine pattern_entries

    function pattern_transposed(self) result(t)
        class(sparsity_pattern), intent(in) :: self
        type(sparsity_pattern) :: t
        integer, allocatable :: rows(:), cols(:), fill(:)
        integer :: i, j, k
        logical :: ok
        ! counting by columns: the rows come in increasing order, so each row of the
        ! transpose is sorted and free of duplicates as it is filled (where self holds
        ! the type's invariant; else by pattern_from_entries)
        ok = rows_delimited(self)
        if (ok) then
            allocate (t%row_start(self%ncols + 1), source=0)
            rows_of_self: do i = 1, self%nrows
                do k = self%row_start(i), self%row_start(i + 1) - 1
                    j = self%cols(k)
                    ok = j >= 1 .and. j <= self%ncols
                    if (ok .and. k > self%row_start(i)) ok = j > self%cols(k - 1)
                    if (.not. ok) exit rows_of_self
                    t%row_start(j + 1) = t%row_start(j + 1) + 1
                end do
            end do rows_of_self
        end if
        if (.not. ok) then
            call self%entries(rows, cols)
            t = pattern_from_entries(self%ncols, self%nrows, cols, rows)
            return
        end if
        t%nrows = self%ncols
        t%ncols = self%nrows
        t%row_start(1) = 1
        do j = 1, self%ncols
            t%row_start(j + 1) = t%row_start(j + 1) + t%row_start(j)
        end do
        allocate (t%cols(self%nnz()), fill(self%ncols))
        fill = t%row_start(1:self%ncols)
        do i = 1, self%nrows
            do k = self%row_start(i), self%row_start(i + 1) - 1
                j = self%cols(k)
                t%cols(fill(j)) = i
                fill(j) = fill(j) + 1
            end do
        end do
    end function pattern_transposed

    ! Are p's rows delimited as the type says: row_start of size nrows + 1, increasing
    ! from 1, within cols? (The columns in each row are checked where they are read.)
    pure logical function rows_delimited(p)
        type(sparsity_pattern), intent(in) :: p
        integer :: i
        rows_delimited = .false.
        if (.not. (allocated(p%row_start) .and. allocated(p%cols))) return
        if (size(p%row_start) /= p%nrows + 1) return
        if (p%row_start(1) /= 1) return
        do i = 1, p%nrows
            if (p%row_start(i + 1) < p%row_start(i)) return
        end do
        rows_delimited = p%row_start(p%nrows + 1) - 1 <= size(p%cols)
    end function rows_delimited

    !> Every entry of an m x n matrix.
    function dense_pattern(m, n) result(p)
        integer, intent(in) :: m, n
        type(sparsity_pattern) :: p
        integer :: i, j
        p%nrows = m
        p%ncols = n
        allocate (p%row_start(m + 1), p%cols(m*n))
        do i = 1, m
            p%row_start(i) = (i - 1)*n + 1
            p%cols((i - 1)*n + 1:i*n) = [(j, j=1, n)]
        end do
        p%row_start(m + 1) = m*n + 1
    end function dense_pattern

    !> No entry.
    function empty_pattern(m, n) result(p)
        integer, intent(in) :: m, n
        type(sparsity_pattern) :: p
        p%nrows = m
        p%ncols = n
        allocate (p%row_start(m + 1), p%cols(0))
        p%row_start = 1
    end function empty_pattern

    !> The diagonal of an n x n matrix.
    function diagonal_pattern(n) result(p)
        integer, intent(in) :: n
        type(sparsity_pattern) :: p
        integer :: i
        p = pattern_from_entries(n, n, [(i, i=1, n)], [(i, i=1, n)])
    end function diagonal_pattern

    !> The entries with -lower <= j - i <= upper of an n x n matrix.
    function band_pattern(n, lower, upper) result(p)
        integer, intent(in) :: n, lower, upper
        type(sparsity_pattern) :: p
        integer :: i, j, k
        p%nrows = n
        p%ncols = n
        allocate (p%row_start(n + 1))
        allocate (p%cols(n*(lower + upper + 1)))
        k = 0
        do i = 1, n
            p%row_start(i) = k + 1
            do j = max(1, i - lower), min(n, i + upper)
                k = k + 1
                p%cols(k) = j
            end do
        end do
        p%row_start(n + 1) = k + 1
        p%cols = p%cols(1:k)
    end function band_pattern

    !> The pattern of an m x n matrix from the (row, column) pairs of its
    !! entries, in any order; duplicates count once. Pairs outside the matrix
    !! are dropped (check sizes before if they matter).
    function pattern_from_entries(m, n, rows, cols) result(p)
        integer, intent(in) :: m, n
        integer, intent(in) :: rows(:), cols(:)
        type(sparsity_pattern) :: p
        integer, allocatable :: count_row(:), fill(:), tmp(:)
        integer :: k, i, a, b, c, last, w, x, y
        p%nrows = m
        p%ncols = n
        allocate (count_row(m + 1), source=0)
        do k = 1, size(rows)
            i = rows(k)
            if (i >= 1 .and. i <= m .and. cols(k) >= 1 .and. cols(k) <= n) count_row(i) = count_row(i) + 1
        end do
        allocate (p%row_start(m + 1))
        p%row_start(1) = 1
        do i = 1, m
            p%row_start(i + 1) = p%row_start(i) + count_row(i)
        end do
        allocate (tmp(p%row_start(m + 1) - 1), fill(m))
        fill = p%row_start(1:m)
        do k = 1, size(rows)
            i = rows(k)
            if (i >= 1 .and. i <= m .and. cols(k) >= 1 .and. cols(k) <= n) then
                tmp(fill(i)) = cols(k)
                fill(i) = fill(i) + 1
            end if
        end do
        ! sort each row (insertion sort: rows are short) and drop duplicates
        allocate (p%cols(size(tmp)))
        w = 0
        do i = 1, m
            a = p%row_start(i)
            b = p%row_start(i + 1) - 1
            do x = a + 1, b
                c = tmp(x)
                y = x - 1
                do while (y >= a)
                    if (tmp(y) <= c) exit
                    tmp(y + 1) = tmp(y)
                    y = y - 1
                end do
                tmp(y + 1) = c
            end do
            p%row_start(i) = w + 1
            last = 0
            do x = a, b
                if (tmp(x) /= last) then
                    w = w + 1
                    p%cols(w) = tmp(x)
                    last = tmp(x)
                end if
            end do
        end do
        p%row_start(m + 1) = w + 1
        p%cols = p%cols(1:w)
    end function pattern_from_entries

    !> The entries of a or b (same sizes).
    function pattern_union(a, b) result(p)
        type(sparsity_pattern), intent(in) :: a, b
        type(sparsity_pattern) :: p
        integer, allocatable :: ra(:), ca(:), rb(:), cb(:)
        integer :: i, ka, kb, w, c
        logical :: ok
        ! merge the sorted rows; a merged row that is not strictly increasing within
        ! 1..ncols means an input without the type's invariant: then by pattern_from_entries
        ok = rows_delimited(a) .and. rows_delimited(b) .and. a%nrows == b%nrows .and. a%ncols == b%ncols
        if (ok) then
            p%nrows = a%nrows
            p%ncols = a%ncols
            allocate (p%row_start(a%nrows + 1), p%cols(a%nnz() + b%nnz()))
            w = 0
            rows_of_a: do i = 1, a%nrows
                p%row_start(i) = w + 1
                ka = a%row_start(i)
                kb = b%row_start(i)
                do while (ka < a%row_start(i + 1) .or. kb < b%row_start(i + 1))
                    if (kb >= b%row_start(i + 1)) then
                        c = a%cols(ka)
                        ka = ka + 1
                    else if (ka >= a%row_start(i + 1)) then
                        c = b%cols(kb)
                        kb = kb + 1
                    else if (a%cols(ka) < b%cols(kb)) then
                        c = a%cols(ka)
                        ka = ka + 1
                    else if (b%cols(kb) < a%cols(ka)) then
                        c = b%cols(kb)
                        kb = kb + 1
                    else
                        c = a%cols(ka)
                        ka = ka + 1
                        kb = kb + 1
                    end if
                    ok = c >= 1 .and. c <= a%ncols
                    if (ok .and. w >= p%row_start(i)) ok = c > p%cols(w)
                    if (.not. ok) exit rows_of_a
                    w = w + 1
                    p%cols(w) = c
                end do
            end do rows_of_a
        end if
        if (.not. ok) then
            call a%entries(ra, ca)
            call b%entries(rb, cb)
            p = pattern_from_entries(a%nrows, a%ncols, [ra, rb], [ca, cb])
            return
        end if
        p%row_start(a%nrows + 1) = w + 1
        p%cols = p%cols(1:w)
    end function pattern_union

    !> Groups of columns that share no row (Curtis, Powell and Reid): a greedy
    !! coloring of the columns' intersection graph (two columns adjacent when they
    !! share a row) in smallest-last order (Matula and Beck; Coleman and More: the
    !! column removed first, of least degree among those left, is colored last), which
    !! needs fewer colors than the column order on banded and block patterns (the
    !! augmented chain's Newton matrix: 10 instead of 12, its longest row has 9).
    !! color(j) in 1..ncolors; one residual evaluation per color gives every column of
    !! that color by difference quotients. Time O(sum over the rows of their length
    !! squared), memory O(columns) besides the transpose.
    subroutine color_columns(p, color, ncolors, columns)
        type(sparsity_pattern), intent(in) :: p
        integer, intent(out), allocatable :: color(:)
        integer, intent(out) :: ncolors
        type(sparsity_pattern), intent(in), optional :: columns   !! p's transpose, if the caller has it
        type(sparsity_pattern) :: pt
        integer, allocatable :: degree(:), stamp(:), order(:), forbidden(:), head(:), next(:), prev(:)
        integer :: n, j, k, r, q, c, idx, low
        n = p%ncols
        if (present(columns)) then
            pt = columns
        else
            pt = p%transposed()   ! rows of pt: the columns of p, with the rows they touch
        end if
        allocate (color(n), source=0)
        ncolors = 0
        if (n == 0) return
        ! the degrees: the distinct columns sharing a row with j (the neighbours are found
        ! again through the rows where needed: memory O(n), no adjacency lists)
        allocate (degree(n), source=0)
        allocate (stamp(n), source=0)
        do j = 1, n
            stamp(j) = j
            do k = pt%row_start(j), pt%row_start(j + 1) - 1
                r = pt%cols(k)
                do q = p%row_start(r), p%row_start(r + 1) - 1
                    c = p%cols(q)
                    if (stamp(c) /= j) then
                        stamp(c) = j
                        degree(j) = degree(j) + 1
                    end if
                end do
            end do
        end do
        ! smallest-last: the columns left in buckets by degree (doubly linked; a removed column
        ! gets stamp -1); removed from the least bucket, its neighbours move one bucket down
        allocate (head(0:maxval(degree)), source=0)
        allocate (next(n), prev(n), order(n))
        do j = n, 1, -1
            prev(j) = 0
            next(j) = head(degree(j))
            if (next(j) /= 0) prev(next(j)) = j
            head(degree(j)) = j
        end do
        low = 0
        do idx = n, 1, -1
            do while (head(low) == 0)
                low = low + 1
            end do
            j = head(low)
            head(low) = next(j)
            if (next(j) /= 0) prev(next(j)) = 0
            stamp(j) = -1
            order(idx) = j
            do k = pt%row_start(j), pt%row_start(j + 1) - 1
                r = pt%cols(k)
                do q = p%row_start(r), p%row_start(r + 1) - 1
                    c = p%cols(q)
                    if (stamp(c) < 0 .or. stamp(c) == n + idx) cycle
                    stamp(c) = n + idx
                    ! c from bucket degree(c) to degree(c) - 1
                    if (prev(c) /= 0) then
                        next(prev(c)) = next(c)
                    else
                        head(degree(c)) = next(c)
                    end if
                    if (next(c) /= 0) prev(next(c)) = prev(c)
                    degree(c) = degree(c) - 1
                    prev(c) = 0
                    next(c) = head(degree(c))
                    if (next(c) /= 0) prev(next(c)) = c
                    head(degree(c)) = c
                end do
            end do
            low = max(0, low - 1)
        end do
        ! greedy in that order: the least color no column sharing a row has
        allocate (forbidden(n + 1), source=0)
        do idx = 1, n
            j = order(idx)
            do k = pt%row_start(j), pt%row_start(j + 1) - 1
                r = pt%cols(k)
                do q = p%row_start(r), p%row_start(r + 1) - 1
                    c = color(p%cols(q))
                    if (c > 0) forbidden(c) = idx
                end do
            end do
            c = 1
            do while (forbidden(c) == idx)
                c = c + 1
            end do
            color(j) = c
            ncolors = max(ncolors, c)
        end do
    end subroutine color_columns

    !> The groups of `color_columns` as lists: the columns of group c are
    !! group_cols(group_start(c):group_start(c+1)-1), in increasing order.
    subroutine column_groups(p, ngroups, group_start, group_cols, columns)
        type(sparsity_pattern), intent(in) :: p
        integer, intent(out) :: ngroups
        integer, allocatable, intent(out) :: group_start(:)   !! ngroups + 1
        integer, allocatable, intent(out) :: group_cols(:)    !! ncols
        type(sparsity_pattern), intent(in), optional :: columns   !! p's transpose, if the caller has it
        integer, allocatable :: color(:), fill(:)
        integer :: j, c
        call color_columns(p, color, ngroups, columns)
        allocate (group_start(ngroups + 1), group_cols(p%ncols), fill(ngroups))
        group_start = 0
        do j = 1, p%ncols
            group_start(color(j) + 1) = group_start(color(j) + 1) + 1
        end do
        group_start(1) = 1
        do c = 1, ngroups
            group_start(c + 1) = group_start(c + 1) + group_start(c)
        end do
        fill = group_start(1:ngroups)
        do j = 1, p%ncols
            group_cols(fill(color(j))) = j
            fill(color(j)) = fill(color(j)) + 1
        end do
    end subroutine column_groups

    !> A reverse Cuthill-McKee ordering of the graph of a square pattern
    !! (symmetrized): perm(k) is the old index of the k-th unknown. Each
    !! connected part starts from a pseudo-peripheral node of low degree.
    function reverse_cuthill_mckee(p) result(perm)
        type(sparsity_pattern), intent(in) :: p
        integer, allocatable :: perm(:)
        type(sparsity_pattern) :: g
        integer, allocatable :: degree(:), order(:), level(:)
        logical, allocatable :: placed(:)
        integer :: n, nplaced, start, i, k, head, tail, node, nb, best, far, sweep, first, pos
        n = p%nrows
        g = pattern_union(p, p%transposed())
        allocate (degree(n), order(n), level(n), placed(n))
        do i = 1, n
            degree(i) = g%row_start(i + 1) - g%row_start(i)
        end do
        placed = .false.
        nplaced = 0
        do while (nplaced < n)
            ! an unplaced node of least degree, then two sweeps towards a far node
            best = 0
            do i = 1, n
                if (.not. placed(i)) then
                    if (best == 0) then
                        best = i
                    else if (degree(i) < degree(best)) then
                        best = i
                    end if
                end if
            end do
            start = best
            do sweep = 1, 2
                call breadth_first(start, far)
                start = far
            end do
            ! Cuthill-McKee from `start`: neighbours in increasing degree
            head = nplaced + 1
            tail = nplaced + 1
            order(tail) = start
            placed(start) = .true.
            do while (head <= tail)
                node = order(head)
                head = head + 1
                ! the unplaced neighbours, appended in increasing degree (ties in
                ! column order: a stable insertion sort)
                first = tail + 1
                do k = g%row_start(node), g%row_start(node + 1) - 1
                    nb = g%cols(k)
                    if (placed(nb)) cycle
                    placed(nb) = .true.
                    pos = tail
                    do while (pos >= first)
                        if (degree(order(pos)) <= degree(nb)) exit
                        order(pos + 1) = order(pos)
                        pos = pos - 1
                    end do
                    order(pos + 1) = nb
                    tail = tail + 1
                end do
            end do
            nplaced = tail
        end do
        perm = order(n:1:-1)
    contains
        ! The last node reached by a breadth-first search from s among the
        ! unplaced nodes (of least degree in the last level).
        subroutine breadth_first(s, last)
            integer, intent(in) :: s
            integer, intent(out) :: last
            integer, allocatable :: queue(:)
            integer :: qh, qt, v, kk, w
            allocate (queue(n))
            level = -1
            qh = 1
            qt = 1
            queue(1) = s
            level(s) = 0
            do while (qh <= qt)
                v = queue(qh)
                qh = qh + 1
                do kk = g%row_start(v), g%row_start(v + 1) - 1
                    w = g%cols(kk)
                    if (placed(w) .or. level(w) >= 0) cycle
                    level(w) = level(v) + 1
                    qt = qt + 1
                    queue(qt) = w
                end do
            end do
            last = queue(qt)
            do kk = 1, qt
                v = queue(kk)
                if (level(v) == level(last) .and. degree(v) < degree(last)) last = v
            end do
        end subroutine breadth_first
    end function reverse_cuthill_mckee

    !> Lower and upper bandwidths of the square pattern p with its unknowns
    !! renumbered: old index perm(k) becomes k.
    subroutine permuted_bandwidths(p, perm, lower, upper)
        type(sparsity_pattern), intent(in) :: p
        integer, intent(in) :: perm(:)
        integer, intent(out) :: lower, upper
        integer, allocatable :: new_index(:)
        integer :: i, k, d
        allocate (new_index(size(perm)))
        new_index(perm) = [(k, k=1, size(perm))]
        lower = 0
        upper = 0
        do i = 1, p%nrows
            do k = p%row_start(i), p%row_start(i + 1) - 1
                d = new_index(p%cols(k)) - new_index(i)
                upper = max(upper, d)
                lower = max(lower, -d)
            end do
        end do
    end subroutine permuted_bandwidths

end module regdae_sparsity
