!> Working precision of regdae.
!!
!! One real kind for the whole package: `wp`, the C `double` that SUNDIALS'
!! `realtype` and LAPACK's `double precision` use. Write literals as `1.0e-6_wp`.
module regdae_kinds
    use, intrinsic :: iso_c_binding, only: c_double
    implicit none
    private

    !> Working-precision real kind (C double, LAPACK double precision).
    integer, parameter, public :: wp = c_double

end module regdae_kinds
