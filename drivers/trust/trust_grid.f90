!> What drivers/trust's families share: the settings of one run (the command line's cell
!! selection, budget, seed, start and option overrides), the grids' tolerances, the problems'
!! parameters, the references' tolerances and the seeded grids' draws.
module trust_grid
    use, intrinsic :: iso_fortran_env, only: int64
    use regdae, only: wp, solver_options
    use xorshift_random, only: xorshift64, new_xorshift64
    use trust_support, only: cell_filter
    use trust_text, only: itext
    implicit none
    private
    public :: signed_log_uniform

    !> pi.
    real(wp), parameter, public :: pi = acos(-1.0_wp)
    !> The tolerances R of the mechanical families' grids (crank, chain, chain_long, fourbar).
    real(wp), parameter, public :: mech_rtols(6) = [1.0e-3_wp, 1.0e-4_wp, 1.0e-5_wp, 1.0e-6_wp, 1.0e-7_wp, 1.0e-8_wp]
    !> The tolerances R of the linear family.
    real(wp), parameter, public :: linear_rtols(8) = [1.0e-3_wp, 1.0e-4_wp, 1.0e-5_wp, 1.0e-6_wp, 1.0e-7_wp, &
                                                      1.0e-8_wp, 1.0e-9_wp, 1.0e-10_wp]
    !> The problems' parameters: the slider crank's gravity (Example 5.2); the four-bar's r, L, g.
    real(wp), parameter, public :: crank_gravity = 9.8_wp, fourbar_r = 1.0_wp, fourbar_l = 2.0_wp, fourbar_g = 9.81_wp
    real(wp), parameter, public :: chain_gravity = 9.81_wp   !! chain_peer's, fixed there
    !> The tight tolerance of the reduced ODEs' references (CVODE) and the looser one of their checks.
    real(wp), parameter, public :: ref_tol = 1.0e-13_wp, ref_check_tol = 1.0e-12_wp

    !> The settings of one run of the driver, from its command line.
    type, public :: trust_setup
        type(cell_filter) :: filter           !! part=k/K, rtol=R, cell=I
        real(wp) :: budget = -1.0_wp          !! budget=S: the wall budget (s) of a regdae run (< 0: the family's)
        real(wp) :: start_th1 = -1.0_wp       !! th1=A: the crank family at this start only (< 0: the grid)
        real(wp) :: start_w1 = 0.0_wp         !! w1=W: with th1=A
        integer(int64) :: grid_seed = 0_int64 !! seed=S: the crank, fourbar, linear grids from seed S (0: the fixed grids)
        type(solver_options) :: overrides     !! the defaults with the option.KEY=VALUE arguments applied
        real(wp), allocatable :: rtols(:)     !! rtols=R1,R2,...: the mechanical grids' R instead of mech_rtols
        integer :: max_links = huge(1)        !! max_links=L: the chain families' cells with N <= L only
        logical :: tight_check = .true.       !! tight_check=no: no regdae cross-check of a chain's reduced-ODE reference
        logical :: reduced_only = .false.     !! reference=reduced: the plain chain against its reduced ODE, not the peer
    contains
        !> The tolerances R of the mechanical families' grids: rtols=..., else mech_rtols.
        procedure :: grid_rtols => setup_grid_rtols
        !> The wall budget (s) of one regdae run: budget=S, else the family's default.
        procedure :: run_budget => setup_run_budget
        !> The options of a cell at rtol = atol = R.
        procedure :: cell_options => setup_cell_options
        !> The generator of the seeded grids.
        procedure :: seeded_generator => setup_seeded_generator
        !> The tag of this process's child files.
        procedure :: child_tag => setup_child_tag
    end type trust_setup

contains

    !> The wall budget of one regdae run: budget=S, else `default`.
    real(wp) function setup_run_budget(setup, default) result(seconds)
        class(trust_setup), intent(in) :: setup
        real(wp), intent(in) :: default
        seconds = merge(setup%budget, default, setup%budget > 0.0_wp)
    end function setup_run_budget

    !> The mechanical grids' tolerances: rtols=R1,R2,... (cells numbered over these), else mech_rtols.
    function setup_grid_rtols(setup) result(rtols)
        class(trust_setup), intent(in) :: setup
        real(wp), allocatable :: rtols(:)
        if (allocated(setup%rtols)) then
            rtols = setup%rtols
        else
            rtols = mech_rtols
        end if
    end function setup_grid_rtols

    !> The options of a cell: the defaults (with the option.KEY=VALUE arguments) but rtol = atol = R.
    function setup_cell_options(setup, rtol) result(opts)
        class(trust_setup), intent(in) :: setup
        real(wp), intent(in) :: rtol
        type(solver_options) :: opts
        opts = setup%overrides
        opts%rtol = rtol
        opts%atol = rtol
    end function setup_cell_options

    !> The generator of the seeded grids: seed S, its first 16 draws dropped (a small seed's
    !! first draws are small: let the bits mix).
    function setup_seeded_generator(setup) result(gen)
        class(trust_setup), intent(in) :: setup
        type(xorshift64) :: gen
        integer(int64) :: bits
        integer :: i
        gen = new_xorshift64(setup%grid_seed)
        do i = 1, 16
            bits = gen%next_bits()
        end do
    end function setup_seeded_generator

    !> The tag of this process's child files: k and K of part=k/K ('1of2').
    function setup_child_tag(setup) result(tag)
        class(trust_setup), intent(in) :: setup
        character(len=:), allocatable :: tag
        tag = itext(setup%filter%part)//'of'//itext(setup%filter%parts)
    end function setup_child_tag

    !> plus or minus 10^u, u uniform in [lo, hi], the sign drawn first.
    real(wp) function signed_log_uniform(gen, lo, hi) result(x)
        type(xorshift64), intent(inout) :: gen
        real(wp), intent(in) :: lo, hi
        real(wp) :: sgn
        sgn = merge(1.0_wp, -1.0_wp, gen%next_uniform() < 0.5_wp)
        x = sgn*10.0_wp**gen%next_between(lo, hi)
    end function signed_log_uniform

end module trust_grid
