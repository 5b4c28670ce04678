!> The options of `regdae_residual_solver` (F(t, y, y') = 0 by IDA, no regularization),
!! a typed record with IDA's defaults, and their check.
module regdae_residual_options
    use regdae_kinds, only: wp
    use regdae_status, only: regdae_success, regdae_err_bad_input
    use regdae_format, only: format_int, format_real
    implicit none
    private

    !> Consistent initial values: none (y0, y0' are consistent), IDA_YA_YDP_INIT (given
    !! the differential components of y, compute the algebraic ones and y'_d: needs
    !! `algebraic`), IDA_Y_INIT (given y', compute y). DDASKR's INFO(11) = 0, 1, 2.
    integer, parameter, public :: initial_given = 0, initial_algebraic = 1, initial_from_slope = 2

    !> Tolerances, linear solver, step and order limits, constraints, initial values.
    type, public :: residual_options
        real(wp) :: rtol = 1.0e-6_wp              !! relative tolerance (all components)
        real(wp) :: atol = 1.0e-6_wp              !! absolute tolerance (all components)
        real(wp), allocatable :: rtol_v(:)        !! per component (length neq): replaces rtol
        real(wp), allocatable :: atol_v(:)        !! per component (length neq): replaces atol
        !> Band solver half-widths (lower, upper): both >= 0 select SUNLinSol_Band; -1 (the
        !! default): dense.
        integer :: band_lower = -1, band_upper = -1
        integer :: max_order = 5                  !! IDA's largest BDF order, 1 ... 5
        integer :: max_steps = 500                !! steps per advance before regdae_err_integration (IDA's mxstep)
        real(wp) :: h_max = 0.0_wp                !! largest |step| (0: none)
        real(wp) :: h_init = 0.0_wp               !! first step (0: IDA's choice)
        !> IDA's constraint codes per component in the integration (IDASetConstraints):
        !! 1: y_i >= 0, 2: > 0, -1: <= 0, -2: < 0, 0: free. Unallocated: none.
        integer, allocatable :: constraints(:)
        !> The same codes for the initial-value computation only (DDASKR's INFO(10) = 1, 3);
        !! unallocated: `constraints` there too.
        integer, allocatable :: ic_constraints(:)
        !> True for the algebraic components (their derivative does not appear in F).
        !! Needed by initial_algebraic and suppress_alg.
        logical, allocatable :: algebraic(:)
        integer :: initial = initial_given        !! initial_given, initial_algebraic or initial_from_slope
        logical :: suppress_alg = .false.         !! leave the algebraic components out of the error test
    end type residual_options

    public :: check_residual_options

contains

    !> stat = regdae_err_bad_input and a message naming the option if `opts` does not
    !! fit a problem of neq unknowns; regdae_success and '' otherwise.
    subroutine check_residual_options(opts, neq, stat, msg)
        type(residual_options), intent(in) :: opts
        integer, intent(in) :: neq
        integer, intent(out) :: stat
        character(len=:), allocatable, intent(out) :: msg
        msg = ''
        if (neq < 1) then
            msg = 'neq = '//format_int(neq)//' must be >= 1'
        else if (.not. allocated(opts%rtol_v) .and. .not. (opts%rtol >= 0.0_wp)) then
            msg = 'rtol = '//format_real(opts%rtol)//' must be >= 0'
        else if (.not. allocated(opts%atol_v) .and. .not. (opts%atol >= 0.0_wp)) then
            msg = 'atol = '//format_real(opts%atol)//' must be >= 0'
        else if (.not. vector_ok(opts%rtol_v)) then
            msg = 'rtol_v must have neq = '//format_int(neq)//' entries >= 0'
        else if (.not. vector_ok(opts%atol_v)) then
            msg = 'atol_v must have neq = '//format_int(neq)//' entries >= 0'
        else if ((opts%band_lower >= 0 .neqv. opts%band_upper >= 0) .or. opts%band_lower >= neq .or. &
                 opts%band_upper >= neq) then
            msg = 'band_lower = '//format_int(opts%band_lower)//', band_upper = '//format_int(opts%band_upper)// &
                  ': both -1 (dense) or both 0 ... neq - 1'
        else if (opts%max_order < 1 .or. opts%max_order > 5) then
            msg = 'max_order = '//format_int(opts%max_order)//' must be 1 ... 5 (IDA''s orders)'
        else if (opts%max_steps < 1) then
            msg = 'max_steps = '//format_int(opts%max_steps)//' must be >= 1'
        else if (.not. (opts%h_max >= 0.0_wp .and. opts%h_init >= 0.0_wp)) then
            msg = 'h_max and h_init must be >= 0 (0: IDA''s choice)'
        else if (.not. (codes_ok(opts%constraints) .and. codes_ok(opts%ic_constraints))) then
            msg = 'constraints and ic_constraints must have neq = '//format_int(neq)//' entries in -2 ... 2'
        else if (opts%initial < initial_given .or. opts%initial > initial_from_slope) then
            msg = 'initial = '//format_int(opts%initial)//' must be 0, 1 or 2'
        else if ((opts%initial == initial_algebraic .or. opts%suppress_alg) .and. .not. allocated(opts%algebraic)) then
            msg = 'initial = initial_algebraic and suppress_alg need algebraic (the algebraic components)'
        else if (allocated(opts%algebraic)) then
            if (size(opts%algebraic) /= neq) msg = 'algebraic must have neq = '//format_int(neq)//' entries'
        end if
        stat = merge(regdae_success, regdae_err_bad_input, len(msg) == 0)
    contains
        logical function vector_ok(v)
            real(wp), allocatable, intent(in) :: v(:)
            vector_ok = .true.
            if (allocated(v)) vector_ok = size(v) == neq .and. all(v >= 0.0_wp)
        end function vector_ok
        logical function codes_ok(c)
            integer, allocatable, intent(in) :: c(:)
            codes_ok = .true.
            if (allocated(c)) codes_ok = size(c) == neq .and. all(abs(c) <= 2)
        end function codes_ok
    end subroutine check_residual_options

end module regdae_residual_options
