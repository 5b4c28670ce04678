!> What an implicit integrator (IDA) integrates: a residual F(t, u, u') = 0 in
!! `neq` unknowns, with the unknowns that leave the local error test. Concrete
!! systems extend `implicit_system`: the regularized DAE in its eliminated or
!! multiplier formulation (`regdae_regularized_system`).
module regdae_implicit_system
    use regdae_kinds, only: wp
    implicit none
    private

    !> A residual system F(t, u, u') = 0.
    type, abstract, public :: implicit_system
        integer :: neq = 0                              !! number of unknowns
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
