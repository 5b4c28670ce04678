!> regdae: regularization of higher-index DAEs with rank-deficient or singular
!! constraints (Petzold, Ren & Maly, SIAM J. Sci. Comput. 18(3), 1997) on
!! SUNDIALS IDA.
!!
!! `use regdae` gives the whole public API: the working precision `wp`, the
!! problem type to extend, the options, the solver and the status codes.
module regdae
    use regdae_kinds, only: wp
    use regdae_format, only: format_real, format_int
    use regdae_status
    use regdae_problem, only: dae_problem, first_order_dt_difference => constraint_dt_difference
    use regdae_second_order_problem, only: second_order_problem, velocity_constraint, curvature_difference, &
                                           second_order_constraint_dt_difference
    use regdae_mechanical_problem, only: mechanical_problem, mechanical_structure
    ! the default mass_values and constraint_jacobian_values, callable from an override
    use regdae_mechanical_problem, only: default_mass_values, default_constraint_jacobian_values
    use regdae_sparsity, only: sparsity_pattern, dense_pattern, empty_pattern, diagonal_pattern, band_pattern, &
                               pattern_from_entries, pattern_union
    use regdae_linear_problem, only: linear_dae_problem
    use regdae_higher_order_problem, only: higher_order_problem, taylor_weights
    use regdae_options
    use regdae_parse, only: parse_real, parse_integer
    use regdae_c_strings, only: c_string
    use regdae_damped_lsq, only: damped_lsq_workspace, damped_lsq_solve, shifted_spd_solve, square_solve
    use regdae_solver_trust, only: regdae_solver, solver_stats
    use regdae_events, only: event_functions
    implicit none
    private

    !> g_t by a central difference in t, the default `constraint_dt` of a
    !! `dae_problem` and of a `second_order_problem` (and so of a
    !! `mechanical_problem`), callable from an override of it:
    !! `call constraint_dt_difference(self, t, x, val, stat)`.
    interface constraint_dt_difference
        procedure :: first_order_dt_difference, second_order_constraint_dt_difference
    end interface constraint_dt_difference

    public :: wp, format_real, format_int, dae_problem, constraint_dt_difference, regdae_solver, solver_stats
    public :: event_functions
    public :: second_order_problem, velocity_constraint, curvature_difference, mechanical_problem, &
              higher_order_problem, taylor_weights
    public :: linear_dae_problem
    public :: parse_real, parse_integer, c_string
    public :: mechanical_structure, sparsity_pattern, dense_pattern, empty_pattern, diagonal_pattern, band_pattern, &
              pattern_from_entries, pattern_union
    public :: damped_lsq_workspace, damped_lsq_solve, shifted_spd_solve, square_solve
    public :: default_mass_values, default_constraint_jacobian_values
    ! regdae_status
    public :: regdae_success, regdae_warn_multiplier_undefined, regdae_warn_unresolved, regdae_err_bad_input, &
              regdae_err_inconsistent_ic, &
              regdae_err_user_callback, &
              regdae_err_not_psd, regdae_err_singular, regdae_err_lapack, regdae_err_sundials, &
              regdae_err_integration, regdae_err_not_initialized, regdae_err_nonfinite, regdae_err_mass_matrix, &
              regdae_err_branch, regdae_err_drift, regdae_err_invariant, regdae_err_structure, regdae_err_jacobian, &
              regdae_err_work, regdae_err_memory, regdae_root_found, &
              status_message
    ! regdae_options
    public :: solver_options, set_option, validate_options, method_name, formulation_name, lsq_name, &
              exclusion_name, method_baumgarte, method_trust_region, method_direct, formulation_multiplier, &
              formulation_eliminated, lsq_auto, lsq_normal, lsq_stacked, lsq_checked, exclusion_suppress, exclusion_weights, &
              exclusion_off, excluded_y, excluded_vy, excluded_name, integrator_ida, integrator_dopri5, integrator_auto, &
              integrator_radau, integrator_name, &
              formulation_auto, formulation_augmented, augmented_min_n, linear_solver_auto, linear_solver_dense, &
              linear_solver_band, linear_solver_sparse, linear_solver_name, option_auto, resolved_work_tol, option_text
end module regdae
