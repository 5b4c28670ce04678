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

end module regdae_implicit_system
