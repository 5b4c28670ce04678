!> Problems whose routines are not Fortran 2008 type-bound procedures: C
!! functions (the C interface, `regdae_c_api`) or FORTRAN 77 EXTERNAL subroutines
!! (DREGDAE, `regdae_dassl`).
!!
!! Each door describes its routines by an extension of `foreign_routines`, which
!! evaluates routine `which` (f, B, g, G, ...) at (t, x) or (t, x, v) into a flat
!! array (matrices in column-major order, as Fortran stores them). The three
!! problem types below are the Fortran API's `dae_problem`, `second_order_problem`
!! and `mechanical_problem` with every binding forwarded to those routines; an
!! optional routine that the door does not have (g_t, the curvature, the invariant,
!! the values of a declared pattern) falls back on the Fortran API's default.
!!
!! The solver copies its problem; the copy points at the same `foreign_routines`
!! object (and structure), so a door may update it between calls (FORTRAN 77: the
!! RPAR and IPAR arrays of the current call). The problems themselves have no
!! allocatable components: gfortran 12 does not free those of an extended type
!! when the solver's polymorphic copies go (valgrind sees the leak).
module regdae_foreign_problems
    use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
    use regdae_kinds, only: wp
    use regdae_problem, only: dae_problem, constraint_dt_difference
    use regdae_second_order_problem, only: second_order_problem, curvature_difference, &
                                           second_order_constraint_dt_difference
    use regdae_mechanical_problem, only: mechanical_problem, mechanical_structure, default_mass_values, &
                                         default_constraint_jacobian_values
    use regdae_sparsity, only: sparsity_pattern
    implicit none
    private

    integer, parameter, public :: routine_f = 1            !! f: f(x, t) (first order), f(x, v, t) (second order)
    integer, parameter, public :: routine_b = 2            !! B, n x m: B(x, t) or B(x, v, t)
    integer, parameter, public :: routine_g = 3            !! g(x, t), length m
    integer, parameter, public :: routine_gx = 4           !! G = g_x(x, t), m x n
    integer, parameter, public :: routine_gt = 5           !! g_t(x, t), length m (optional)
    integer, parameter, public :: routine_curvature = 6    !! g_xx(v, v) + 2 g_xt v + g_tt, length m (optional)
    integer, parameter, public :: routine_invariant = 7    !! I(x, v, t), one value (optional)
    integer, parameter, public :: routine_mass = 8         !! M(q, t), n x n
    integer, parameter, public :: routine_forces = 9       !! f(q, q', t), length n
    integer, parameter, public :: routine_mass_values = 10 !! the entries of M in pattern order (optional)
    integer, parameter, public :: routine_gx_values = 11   !! the entries of G in pattern order (optional)
    integer, parameter, public :: n_routines = 11          !! the number of routine codes

    !> The routines of a problem, as one door (C or FORTRAN 77) holds them.
    type, abstract, public :: foreign_routines
        !> The last routine that reported failure, in the door's words (for messages).
        character(len=:), allocatable :: failure
        !> Every component of x (q) must stay >= 0 (FORTRAN 77: INFO(10) = 1).
        logical :: nonnegative = .false.
    contains
        !> Whether routine `which` was given.
        procedure(has_routine), deferred :: has
        !> Evaluate routine `which` at (t, x), or (t, x, v) when v is present.
        procedure(evaluate_routine), deferred :: evaluate
        !> From on = .true. to .false.: routine `which` (f or the forces) near (t, x, v)
        !! from the user's Jacobian of it there, if the door has one (`linearize_rhs`
        !! of the problems); default: nothing.
        procedure :: linearize => no_linearization
    end type foreign_routines

    abstract interface
        logical function has_routine(self, which)
            import :: foreign_routines
            class(foreign_routines), intent(in) :: self
            integer, intent(in) :: which    !! a routine code
        end function has_routine

        subroutine evaluate_routine(self, which, t, x, val, stat, v)
            import :: foreign_routines, wp
            class(foreign_routines), intent(inout) :: self
            integer, intent(in) :: which          !! a routine code
            real(wp), intent(in) :: t             !! time
            real(wp), intent(in) :: x(*)          !! position (state), length n
            real(wp), intent(out) :: val(*)       !! the value; matrices column by column
            integer, intent(inout) :: stat        !! 0 on entry; > 0 recoverable, < 0 fatal failure
            real(wp), intent(in), optional :: v(*)   !! velocity, length n (second-order routines)
        end subroutine evaluate_routine
    end interface

    !> An index-2 problem x' = f(x, t) - B(x, t) y, 0 = g(x, t) with foreign routines.
    type, extends(dae_problem), public :: foreign_first_order
        class(foreign_routines), pointer :: routines => null()   !! f, B, g, G and optionally g_t
    contains
        procedure :: rhs => first_f
        procedure :: matrix_b => first_b
        procedure :: constraint => first_g
        procedure :: constraint_jacobian => first_gx
        procedure :: constraint_dt => first_gt
        procedure :: linearize_rhs => first_linearize
        procedure :: nonnegative => first_nonnegative
    end type foreign_first_order

    !> A second-order problem x'' = f(x, x', t) - B(x, x', t) y, 0 = g(x, t) with foreign routines.
    type, extends(second_order_problem), public :: foreign_second_order
        class(foreign_routines), pointer :: routines => null()   !! f, B, g, G; optionally g_t, curvature, invariant
    contains
        procedure :: rhs => second_f
        procedure :: matrix_b => second_b
        procedure :: constraint => second_g
        procedure :: constraint_jacobian => second_gx
        procedure :: constraint_dt => second_gt
        procedure :: constraint_curvature => second_curvature
        procedure :: invariant => second_invariant
    end type foreign_second_order

    !> A mechanical system M(q) q'' = f(q, q', t) + G^T lambda, 0 = g(q, t) with foreign
    !! routines, optionally with a declared structure.
    type, extends(mechanical_problem), public :: foreign_mechanical
        class(foreign_routines), pointer :: routines => null()   !! M, forces, g, G; optionally g_t, curvature,
                                                                  !! invariant and the values of M and G
        type(mechanical_structure), pointer :: declared => null() !! the patterns (null: dense); a pointer, so
                                                                  !! that copies of the problem share them
    contains
        procedure :: mass_matrix => mechanical_mass
        procedure :: forces => mechanical_forces
        procedure :: constraint => mechanical_g
        procedure :: constraint_jacobian => mechanical_gx
        procedure :: constraint_dt => mechanical_gt
        procedure :: constraint_curvature => mechanical_curvature
        procedure :: invariant => mechanical_invariant
        procedure :: structure => mechanical_structure_declared
        procedure :: mass_values => mechanical_mass_values
        procedure :: constraint_jacobian_values => mechanical_gx_values
        procedure :: linearize_rhs => mechanical_linearize
        procedure :: nonnegative => mechanical_nonnegative
    end type foreign_mechanical

    public :: routine_name

contains

    !> The name of a routine code, as the C interface's arguments have it (the
    !! FORTRAN 77 door upper-cases it), padded with blanks (a fixed-length result:
    !! doc/methods.md, "No global state").
    pure function routine_name(which) result(name)
        integer, intent(in) :: which   !! a routine code
        character(len=11) :: name
        character(len=11), parameter :: names(n_routines) = [character(len=11) :: 'f', 'b', 'g', 'gx', 'gt', &
            'curvature', 'invariant', 'mass', 'forces', 'mass_values', 'gx_values']
        name = '?'
        if (which >= 1 .and. which <= n_routines) name = names(which)
    end function routine_name

    ! --- first order -----------------------------------------------------------------

    subroutine first_f(self, t, x, v, stat)
        class(foreign_first_order), intent(inout) :: self
        real(wp), intent(in) :: t, x(:)
        real(wp), intent(out) :: v(:)
        integer, intent(inout) :: stat
        call self%routines%evaluate(routine_f, t, x, v, stat)
    end subroutine first_f

    subroutine no_linearization(self, which, t, x, on, stat, v)
        class(foreign_routines), intent(inout) :: self
        integer, intent(in) :: which           !! routine_f or routine_forces
        real(wp), intent(in) :: t, x(:)        !! the point of the Jacobian
        logical, intent(in) :: on              !! .true.: linearize there; .false.: evaluate again
        integer, intent(inout) :: stat         !! 0 on entry; > 0 recoverable, < 0 fatal failure
        real(wp), intent(in), optional :: v(:) !! the velocity (routine_forces)
    end subroutine no_linearization

    subroutine first_linearize(self, t, x, on, stat)
        class(foreign_first_order), intent(inout) :: self
        real(wp), intent(in) :: t, x(:)
        logical, intent(in) :: on
        integer, intent(inout) :: stat
        call self%routines%linearize(routine_f, t, x, on, stat)
    end subroutine first_linearize

    function first_nonnegative(self) result(mask)
        class(foreign_first_order), intent(in) :: self
        logical :: mask(self%n)
        mask = self%routines%nonnegative
    end function first_nonnegative

    subroutine first_b(self, t, x, a, stat)
        class(foreign_first_order), intent(inout) :: self
        real(wp), intent(in) :: t, x(:)
        real(wp), intent(out) :: a(:, :)
        integer, intent(inout) :: stat
        call self%routines%evaluate(routine_b, t, x, a, stat)
    end subroutine first_b

    subroutine first_g(self, t, x, v, stat)
        class(foreign_first_order), intent(inout) :: self
        real(wp), intent(in) :: t, x(:)
        real(wp), intent(out) :: v(:)
        integer, intent(inout) :: stat
        call self%routines%evaluate(routine_g, t, x, v, stat)
    end subroutine first_g

    subroutine first_gx(self, t, x, a, stat)
        class(foreign_first_order), intent(inout) :: self
        real(wp), intent(in) :: t, x(:)
        real(wp), intent(out) :: a(:, :)
        integer, intent(inout) :: stat
        call self%routines%evaluate(routine_gx, t, x, a, stat)
    end subroutine first_gx

    subroutine first_gt(self, t, x, v, stat)
        class(foreign_first_order), intent(inout) :: self
        real(wp), intent(in) :: t, x(:)
        real(wp), intent(out) :: v(:)
        integer, intent(inout) :: stat
        if (self%routines%has(routine_gt)) then
            call self%routines%evaluate(routine_gt, t, x, v, stat)
        else
            call constraint_dt_difference(self, t, x, v, stat)
        end if
    end subroutine first_gt

    ! --- second order ----------------------------------------------------------------

    subroutine second_f(self, t, x, v, val, stat)
        class(foreign_second_order), intent(inout) :: self
        real(wp), intent(in) :: t, x(:), v(:)
        real(wp), intent(out) :: val(:)
        integer, intent(inout) :: stat
        call self%routines%evaluate(routine_f, t, x, val, stat, v)
    end subroutine second_f

    subroutine second_b(self, t, x, v, a, stat)
        class(foreign_second_order), intent(inout) :: self
        real(wp), intent(in) :: t, x(:), v(:)
        real(wp), intent(out) :: a(:, :)
        integer, intent(inout) :: stat
        real(wp) :: b(size(a, 1), size(a, 2))   ! index 2 passes a section of a larger matrix: evaluate contiguously
        call self%routines%evaluate(routine_b, t, x, b, stat, v)
        a = b
    end subroutine second_b

    subroutine second_g(self, t, x, val, stat)
        class(foreign_second_order), intent(inout) :: self
        real(wp), intent(in) :: t, x(:)
        real(wp), intent(out) :: val(:)
        integer, intent(inout) :: stat
        call self%routines%evaluate(routine_g, t, x, val, stat)
    end subroutine second_g

    subroutine second_gx(self, t, x, a, stat)
        class(foreign_second_order), intent(inout) :: self
        real(wp), intent(in) :: t, x(:)
        real(wp), intent(out) :: a(:, :)
        integer, intent(inout) :: stat
        call self%routines%evaluate(routine_gx, t, x, a, stat)
    end subroutine second_gx

    subroutine second_gt(self, t, x, val, stat)
        class(foreign_second_order), intent(inout) :: self
        real(wp), intent(in) :: t, x(:)
        real(wp), intent(out) :: val(:)
        integer, intent(inout) :: stat
        call position_dt(self, self%routines, t, x, val, stat)
    end subroutine second_gt

    subroutine second_curvature(self, t, x, v, val, stat)
        class(foreign_second_order), intent(inout) :: self
        real(wp), intent(in) :: t, x(:), v(:)
        real(wp), intent(out) :: val(:)
        integer, intent(inout) :: stat
        call curvature(self, self%routines, t, x, v, val, stat)
    end subroutine second_curvature

    subroutine second_invariant(self, t, x, v, val, stat)
        class(foreign_second_order), intent(inout) :: self
        real(wp), intent(in) :: t, x(:), v(:)
        real(wp), intent(out) :: val
        integer, intent(inout) :: stat
        call invariant(self%routines, t, x, v, val, stat)
    end subroutine second_invariant

    ! --- mechanical ------------------------------------------------------------------

    subroutine mechanical_mass(self, t, q, mass, stat)
        class(foreign_mechanical), intent(inout) :: self
        real(wp), intent(in) :: t, q(:)
        real(wp), intent(out) :: mass(:, :)
        integer, intent(inout) :: stat
        call self%routines%evaluate(routine_mass, t, q, mass, stat)
    end subroutine mechanical_mass

    subroutine mechanical_forces(self, t, q, qd, f, stat)
        class(foreign_mechanical), intent(inout) :: self
        real(wp), intent(in) :: t, q(:), qd(:)
        real(wp), intent(out) :: f(:)
        integer, intent(inout) :: stat
        call self%routines%evaluate(routine_forces, t, q, f, stat, qd)
    end subroutine mechanical_forces

    subroutine mechanical_linearize(self, t, x, v, on, stat)
        class(foreign_mechanical), intent(inout) :: self
        real(wp), intent(in) :: t, x(:), v(:)
        logical, intent(in) :: on
        integer, intent(inout) :: stat
        call self%routines%linearize(routine_forces, t, x, on, stat, v)
    end subroutine mechanical_linearize

    function mechanical_nonnegative(self) result(mask)
        class(foreign_mechanical), intent(in) :: self
        logical :: mask(self%n)
        mask = self%routines%nonnegative
    end function mechanical_nonnegative

    subroutine mechanical_g(self, t, x, val, stat)
        class(foreign_mechanical), intent(inout) :: self
        real(wp), intent(in) :: t, x(:)
        real(wp), intent(out) :: val(:)
        integer, intent(inout) :: stat
        call self%routines%evaluate(routine_g, t, x, val, stat)
    end subroutine mechanical_g

    subroutine mechanical_gx(self, t, x, a, stat)
        class(foreign_mechanical), intent(inout) :: self
        real(wp), intent(in) :: t, x(:)
        real(wp), intent(out) :: a(:, :)
        integer, intent(inout) :: stat
        call self%routines%evaluate(routine_gx, t, x, a, stat)
    end subroutine mechanical_gx

    subroutine mechanical_gt(self, t, x, val, stat)
        class(foreign_mechanical), intent(inout) :: self
        real(wp), intent(in) :: t, x(:)
        real(wp), intent(out) :: val(:)
        integer, intent(inout) :: stat
        call position_dt(self, self%routines, t, x, val, stat)
    end subroutine mechanical_gt

    subroutine mechanical_curvature(self, t, x, v, val, stat)
        class(foreign_mechanical), intent(inout) :: self
        real(wp), intent(in) :: t, x(:), v(:)
        real(wp), intent(out) :: val(:)
        integer, intent(inout) :: stat
        call curvature(self, self%routines, t, x, v, val, stat)
    end subroutine mechanical_curvature

    subroutine mechanical_invariant(self, t, x, v, val, stat)
        class(foreign_mechanical), intent(inout) :: self
        real(wp), intent(in) :: t, x(:), v(:)
        real(wp), intent(out) :: val
        integer, intent(inout) :: stat
        call invariant(self%routines, t, x, v, val, stat)
    end subroutine mechanical_invariant

    function mechanical_structure_declared(self) result(st)
        class(foreign_mechanical), intent(in) :: self
        type(mechanical_structure) :: st
        if (associated(self%declared)) st = self%declared
    end function mechanical_structure_declared

    subroutine mechanical_mass_values(self, t, q, pattern, vals, stat)
        class(foreign_mechanical), intent(inout) :: self
        real(wp), intent(in) :: t, q(:)
        type(sparsity_pattern), intent(in) :: pattern
        real(wp), intent(out) :: vals(:)
        integer, intent(inout) :: stat
        if (self%routines%has(routine_mass_values)) then
            call self%routines%evaluate(routine_mass_values, t, q, vals, stat)
        else
            call default_mass_values(self, t, q, pattern, vals, stat)
        end if
    end subroutine mechanical_mass_values

    subroutine mechanical_gx_values(self, t, q, pattern, vals, stat)
        class(foreign_mechanical), intent(inout) :: self
        real(wp), intent(in) :: t, q(:)
        type(sparsity_pattern), intent(in) :: pattern
        real(wp), intent(out) :: vals(:)
        integer, intent(inout) :: stat
        if (self%routines%has(routine_gx_values)) then
            call self%routines%evaluate(routine_gx_values, t, q, vals, stat)
        else
            call default_constraint_jacobian_values(self, t, q, pattern, vals, stat)
        end if
    end subroutine mechanical_gx_values

    ! --- shared by the second-order and mechanical problems ---------------------------

    ! g_t from the routine, or the central difference quotient.
    subroutine position_dt(problem, routines, t, x, val, stat)
        class(second_order_problem), intent(inout) :: problem
        class(foreign_routines), intent(inout) :: routines
        real(wp), intent(in) :: t, x(:)
        real(wp), intent(out) :: val(:)
        integer, intent(inout) :: stat
        if (routines%has(routine_gt)) then
            call routines%evaluate(routine_gt, t, x, val, stat)
        else
            call second_order_constraint_dt_difference(problem, t, x, val, stat)
        end if
    end subroutine position_dt

    ! The curvature term from the routine, or the difference quotient of G v + g_t.
    subroutine curvature(problem, routines, t, x, v, val, stat)
        class(second_order_problem), intent(inout) :: problem
        class(foreign_routines), intent(inout) :: routines
        real(wp), intent(in) :: t, x(:), v(:)
        real(wp), intent(out) :: val(:)
        integer, intent(inout) :: stat
        if (routines%has(routine_curvature)) then
            call routines%evaluate(routine_curvature, t, x, val, stat, v)
        else
            call curvature_difference(problem, t, x, v, val, stat)
        end if
    end subroutine curvature

    ! The invariant from the routine, or NaN (none).
    subroutine invariant(routines, t, x, v, val, stat)
        class(foreign_routines), intent(inout) :: routines
        real(wp), intent(in) :: t, x(:), v(:)
        real(wp), intent(out) :: val
        integer, intent(inout) :: stat
        real(wp) :: box(1)
        box(1) = ieee_value(1.0_wp, ieee_quiet_nan)
        if (routines%has(routine_invariant)) call routines%evaluate(routine_invariant, t, x, box, stat, v)
        val = box(1)
    end subroutine invariant

end module regdae_foreign_problems
