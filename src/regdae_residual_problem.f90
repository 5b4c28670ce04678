!> A general implicit DAE F(t, y, y') = 0, for `regdae_residual_solver` (IDA as it
!! is, in the manner of DASSL and DDASKR).
!!
!! No constraint structure is declared, so nothing is regularized: this is the door
!! for a DAE that is integrated as written. A mechanism that passes through
!! kinematic singularities (GB singular) needs regdae's regularization: describe it
!! as a `dae_problem` or `mechanical_problem` (doc/api.md, sections 1-3) or call
!! DREGDAE / DREGDAEM (section 8).
!!
!! Extend `residual_problem`, give `neq` (and `nroots`), and override `residual`;
!! `jacobian` and `roots` are optional. Callbacks set `stat` as regdae's do: 0 on
!! success, > 0 a recoverable failure (IDA retries with a smaller step), < 0 stop.
module regdae_residual_problem
    use regdae_kinds, only: wp
    implicit none
    private

    !> F(t, y, y') = 0 with neq unknowns and nroots event functions.
    type, abstract, public :: residual_problem
        integer :: neq = 0      !! number of unknowns and equations
        integer :: nroots = 0   !! number of event functions r_i(t, y, y') (0: none)
        !> IDA's current cj (dy'/dy of its BDF formula), set by the solver before each
        !! call of `residual` (DDASKR's RES receives it; a residual rarely needs it).
        real(wp) :: cj = 0.0_wp
    contains
        !> r = F(t, y, y').
        procedure(residual_interface), deferred :: residual
        !> True if `jacobian` is overridden (the default: false, IDA's difference quotients).
        procedure :: has_jacobian => default_has_jacobian
        !> pd = dF/dy + cj dF/dy' (the Newton matrix), dense pd(neq, neq) or, with a band
        !! solver of half-widths ml, mu, LINPACK band storage pd(2 ml + mu + 1, neq):
        !! the entry (i, j) in pd(i - j + ml + mu + 1, j). pd is zero on entry.
        procedure :: jacobian => default_jacobian
        !> rval(1:nroots) = the event functions at (t, y, y'); IDA locates their sign changes.
        procedure :: roots => default_roots
    end type residual_problem

    abstract interface
        subroutine residual_interface(self, t, y, yp, r, stat)
            import :: residual_problem, wp
            class(residual_problem), intent(inout) :: self
            real(wp), intent(in) :: t, y(:), yp(:)
            real(wp), intent(out) :: r(:)
            integer, intent(inout) :: stat   !! 0 on entry
        end subroutine residual_interface
    end interface

contains

    logical function default_has_jacobian(self)
        class(residual_problem), intent(in) :: self
        default_has_jacobian = .false.
    end function default_has_jacobian

    subroutine default_jacobian(self, t, y, yp, cj, pd, stat)
        class(residual_problem), intent(inout) :: self
        real(wp), intent(in) :: t           !! time
        real(wp), intent(in) :: y(:), yp(:) !! the state and its derivative
        real(wp), intent(in) :: cj          !! IDA's coefficient: dy'/dy of the BDF formula
        real(wp), intent(inout) :: pd(:, :) !! the matrix (zero on entry)
        integer, intent(inout) :: stat      !! 0 on entry
        stat = -1   ! not called unless has_jacobian is overridden
    end subroutine default_jacobian

    subroutine default_roots(self, t, y, yp, rval, stat)
        class(residual_problem), intent(inout) :: self
        real(wp), intent(in) :: t, y(:), yp(:)
        real(wp), intent(out) :: rval(:)    !! length nroots
        integer, intent(inout) :: stat      !! 0 on entry
        rval = 0.0_wp
    end subroutine default_roots

end module regdae_residual_problem
