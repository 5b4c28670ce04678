!> Explicit interfaces to the LAPACK routines regdae calls.
!!
!! LAPACK is external Fortran 77 code; these interfaces let the compiler check
!! every call's argument types and ranks.
module regdae_lapack
    use regdae_kinds, only: wp
    implicit none
    private

    public :: dposv, dpotrf, dpotrs, dgelsd, dgesv, dgesvd, dgbtrf, dgbtrs, dgetrf, dgetrs, zgetrf, zgetrs, dgeev

    interface
        !> Solve A X = B, A symmetric positive definite (Cholesky).
        subroutine dposv(uplo, n, nrhs, a, lda, b, ldb, info)
            import :: wp
            character, intent(in) :: uplo
            integer, intent(in) :: n, nrhs, lda, ldb
            real(wp), intent(inout) :: a(lda, *), b(ldb, *)
            integer, intent(out) :: info
        end subroutine dposv

        !> Cholesky factorization of a symmetric positive definite matrix.
        subroutine dpotrf(uplo, n, a, lda, info)
            import :: wp
            character, intent(in) :: uplo
            integer, intent(in) :: n, lda
            real(wp), intent(inout) :: a(lda, *)
            integer, intent(out) :: info
        end subroutine dpotrf

        !> Solve with a Cholesky factor computed by dpotrf.
        subroutine dpotrs(uplo, n, nrhs, a, lda, b, ldb, info)
            import :: wp
            character, intent(in) :: uplo
            integer, intent(in) :: n, nrhs, lda, ldb
            real(wp), intent(in) :: a(lda, *)
            real(wp), intent(inout) :: b(ldb, *)
            integer, intent(out) :: info
        end subroutine dpotrs

        !> Minimum-norm least-squares solution by the SVD (divide and conquer).
        subroutine dgelsd(m, n, nrhs, a, lda, b, ldb, s, rcond, rank, work, lwork, iwork, info)
            import :: wp
            integer, intent(in) :: m, n, nrhs, lda, ldb, lwork
            real(wp), intent(inout) :: a(lda, *), b(ldb, *)
            real(wp), intent(out) :: s(*)
            real(wp), intent(in) :: rcond
            integer, intent(out) :: rank, info
            real(wp), intent(inout) :: work(*)
            integer, intent(inout) :: iwork(*)
        end subroutine dgelsd

        !> Solve A X = B by LU factorization with partial pivoting.
        subroutine dgesv(n, nrhs, a, lda, ipiv, b, ldb, info)
            import :: wp
            integer, intent(in) :: n, nrhs, lda, ldb
            real(wp), intent(inout) :: a(lda, *), b(ldb, *)
            integer, intent(out) :: ipiv(*), info
        end subroutine dgesv

        !> Singular value decomposition (here: singular values only).
        subroutine dgesvd(jobu, jobvt, m, n, a, lda, s, u, ldu, vt, ldvt, work, lwork, info)
            import :: wp
            character, intent(in) :: jobu, jobvt
            integer, intent(in) :: m, n, lda, ldu, ldvt, lwork
            real(wp), intent(inout) :: a(lda, *)
            real(wp), intent(out) :: s(*)
            real(wp), intent(inout) :: u(ldu, *), vt(ldvt, *)
            real(wp), intent(inout) :: work(*)
            integer, intent(out) :: info
        end subroutine dgesvd

        !> LU factorization of a band matrix (band storage with kl extra rows for the fill).
        subroutine dgbtrf(m, n, kl, ku, ab, ldab, ipiv, info)
            import :: wp
            integer, intent(in) :: m, n, kl, ku, ldab
            real(wp), intent(inout) :: ab(ldab, *)
            integer, intent(out) :: ipiv(*), info
        end subroutine dgbtrf

        !> Solve with the band LU factors of dgbtrf.
        subroutine dgbtrs(trans, n, kl, ku, nrhs, ab, ldab, ipiv, b, ldb, info)
            import :: wp
            character, intent(in) :: trans
            integer, intent(in) :: n, kl, ku, nrhs, ldab, ldb
            real(wp), intent(in) :: ab(ldab, *)
            integer, intent(in) :: ipiv(*)
            real(wp), intent(inout) :: b(ldb, *)
            integer, intent(out) :: info
        end subroutine dgbtrs

        !> LU factorization of a general matrix with partial pivoting.
        subroutine dgetrf(m, n, a, lda, ipiv, info)
            import :: wp
            integer, intent(in) :: m, n, lda
            real(wp), intent(inout) :: a(lda, *)
            integer, intent(out) :: ipiv(*), info
        end subroutine dgetrf

        !> Solve with the LU factors of dgetrf.
        subroutine dgetrs(trans, n, nrhs, a, lda, ipiv, b, ldb, info)
            import :: wp
            character, intent(in) :: trans
            integer, intent(in) :: n, nrhs, lda, ldb
            real(wp), intent(in) :: a(lda, *)
            integer, intent(in) :: ipiv(*)
            real(wp), intent(inout) :: b(ldb, *)
            integer, intent(out) :: info
        end subroutine dgetrs

        !> Eigenvalues (wr + i wi) and optionally eigenvectors of a general real matrix.
        subroutine dgeev(jobvl, jobvr, n, a, lda, wr, wi, vl, ldvl, vr, ldvr, work, lwork, info)
            import :: wp
            character, intent(in) :: jobvl, jobvr
            integer, intent(in) :: n, lda, ldvl, ldvr, lwork
            real(wp), intent(inout) :: a(lda, *)
            real(wp), intent(out) :: wr(*), wi(*), vl(ldvl, *), vr(ldvr, *), work(*)
            integer, intent(out) :: info
        end subroutine dgeev

        !> LU factorization of a general complex matrix with partial pivoting.
        subroutine zgetrf(m, n, a, lda, ipiv, info)
            import :: wp
            integer, intent(in) :: m, n, lda
            complex(wp), intent(inout) :: a(lda, *)
            integer, intent(out) :: ipiv(*), info
        end subroutine zgetrf

        !> Solve with the complex LU factors of zgetrf.
        subroutine zgetrs(trans, n, nrhs, a, lda, ipiv, b, ldb, info)
            import :: wp
            character, intent(in) :: trans
            integer, intent(in) :: n, nrhs, lda, ldb
            complex(wp), intent(in) :: a(lda, *)
            integer, intent(in) :: ipiv(*)
            complex(wp), intent(inout) :: b(ldb, *)
            integer, intent(out) :: info
        end subroutine zgetrs
    end interface

end module regdae_lapack
