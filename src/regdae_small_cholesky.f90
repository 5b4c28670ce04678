!> Cholesky factorization and solves of small symmetric positive definite matrices by plain
!! loops: for a handful of unknowns LAPACK's call overhead (argument checks, block-size queries)
!! costs more than the arithmetic (dposv on a 2 x 2 system was a third of the car axis's slope).
!! Used for the mass matrix (regdae_mechanical_problem) and the damped least squares' normal
!! equations (regdae_damped_lsq) up to `small_cholesky_max` unknowns; LAPACK beyond.
module regdae_small_cholesky
    use regdae_kinds, only: wp
    implicit none
    private

    !> The largest order factored here (LAPACK's dpotrf/dposv beyond).
    integer, parameter, public :: small_cholesky_max = 8

    public :: small_cholesky, small_cholesky_solve

contains

    !> In-place Cholesky factor L (lower triangle) of a small SPD matrix; info > 0
    !! if it is not positive definite.
    pure subroutine small_cholesky(n, a, lda, info)
        integer, intent(in) :: n, lda
        real(wp), intent(inout) :: a(lda, n)
        integer, intent(out) :: info
        integer :: i, j, k
        real(wp) :: s
        info = 0
        if (n == 2) then   ! the loops below, unrolled (same operations, same rounding)
            if (.not. (a(1, 1) > 0.0_wp)) then
                info = 1
                return
            end if
            a(1, 1) = sqrt(a(1, 1))
            a(2, 1) = a(2, 1)/a(1, 1)
            s = a(2, 2) - a(2, 1)**2
            if (.not. (s > 0.0_wp)) then
                info = 2
                return
            end if
            a(2, 2) = sqrt(s)
            return
        end if
        do j = 1, n
            s = a(j, j)
            do k = 1, j - 1
                s = s - a(j, k)**2
            end do
            if (.not. (s > 0.0_wp)) then
                info = j
                return
            end if
            a(j, j) = sqrt(s)
            do i = j + 1, n
                s = a(i, j)
                do k = 1, j - 1
                    s = s - a(i, k)*a(j, k)
                end do
                a(i, j) = s/a(j, j)
            end do
        end do
    end subroutine small_cholesky

    !> Solve L L^T x = b in place with the factor of `small_cholesky`.
    pure subroutine small_cholesky_solve(n, l, ldl, b)
        integer, intent(in) :: n, ldl
        real(wp), intent(in) :: l(ldl, n)
        real(wp), intent(inout) :: b(n)
        integer :: j, k
        real(wp) :: s
        if (n == 2) then   ! the loops below, unrolled (same operations, same rounding)
            b(1) = b(1)/l(1, 1)
            b(2) = (b(2) - l(2, 1)*b(1))/l(2, 2)
            b(2) = b(2)/l(2, 2)
            b(1) = (b(1) - l(2, 1)*b(2))/l(1, 1)
            return
        end if
        do j = 1, n
            s = b(j)
            do k = 1, j - 1
                s = s - l(j, k)*b(k)
            end do
            b(j) = s/l(j, j)
        end do
        do j = n, 1, -1
            s = b(j)
            do k = j + 1, n
                s = s - l(k, j)*b(k)
            end do
            b(j) = s/l(j, j)
        end do
    end subroutine small_cholesky_solve

end module regdae_small_cholesky
