!> What an implicit integrator (IDA) integrates: a residual F(t, u, u') = 0 in
!! `neq` unknowns, and, if known, the sparsity pattern of its Newton matrix
!! dF/du + cj dF/du'. Concrete systems extend `implicit_system`: the regularized
!! DAE in its eliminated or multiplier formulation (`regdae_regularized_system`,
!! dense) and the augmented formulation of a mechanical problem
!! (`regdae_augmented_system`, structured).
module regdae_implicit_system
    use regdae_kinds, only: wp
    use regdae_sparsity, only: sparsity_pattern
    implicit none
    private

    !> A residual system F(t, u, u') = 0.
    type, abstract, public :: implicit_system
        integer :: neq = 0                              !! number of unknowns
        logical :: structured = .false.                 !! jac_pattern is set (else: dense)
        type(sparsity_pattern) :: jac_pattern           !! entries of dF/du + cj dF/du' that may be nonzero
        character(len=:), allocatable :: message        !! details of the last failure
    contains
        !> res = F(t, u, u'); stat = regdae status, `recoverable`: may a smaller step help?
        procedure(residual_interface), deferred :: residual
        !> Around a difference-quotient Jacobian at (t, u): `on` before its perturbed
        !! residuals, then off. A system may take parts of those residuals from the
        !! user's Jacobians meanwhile (`linearize_rhs` of the problem); default: nothing.
        procedure :: jacobian_phase => no_jacobian_phase
        !> The unknowns that must stay >= 0 (IDA's constraint option); default: none.
        procedure :: nonnegative_unknowns => no_nonnegative_unknowns
    end type implicit_system

    abstract interface
        subroutine residual_interface(self, t, u, up, res, stat, recoverable)
            import :: implicit_system, wp
            class(implicit_system), intent(inout) :: self
            real(wp), intent(in) :: t, u(:), up(:)
            real(wp), intent(out) :: res(:)
            integer, intent(out) :: stat
            logical, intent(out) :: recoverable
        end subroutine residual_interface
    end interface

contains

    subroutine no_jacobian_phase(self, t, u, on, stat, recoverable)
        class(implicit_system), intent(inout) :: self
        real(wp), intent(in) :: t, u(:)       !! the point of the Jacobian
        logical, intent(in) :: on             !! .true.: the perturbed residuals follow; .false.: done
        integer, intent(out) :: stat          !! regdae status (a failure of the user's Jacobian routine)
        logical, intent(out) :: recoverable   !! may a smaller step help?
        stat = 0
        recoverable = .true.
    end subroutine no_jacobian_phase

    function no_nonnegative_unknowns(self) result(mask)
        class(implicit_system), intent(in) :: self
        logical :: mask(self%neq)   !! true: the unknown must stay >= 0
        mask = .false.
    end function no_nonnegative_unknowns

end module regdae_implicit_system
