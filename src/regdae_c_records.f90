!> The C interface's records: `regdae_options` and `regdae_stats` of
!! `include/regdae.h`, field for field `solver_options` and `solver_stats`
!! (logicals as int, 0 or 1; counters as int64_t).
module regdae_c_records
    use, intrinsic :: iso_c_binding, only: c_int, c_double, c_int64_t
    use regdae_options, only: solver_options
    use regdae_solver_stats, only: solver_stats
    implicit none
    private

    !> `regdae_options` (include/regdae.h): the options, as `solver_options`.
    type, bind(C), public :: c_options
        integer(c_int) :: method              !! REGDAE_METHOD_*
        integer(c_int) :: formulation         !! REGDAE_FORMULATION_*
        integer(c_int) :: lsq                 !! REGDAE_LSQ_*
        integer(c_int) :: exclusion           !! REGDAE_EXCLUSION_*
        real(c_double) :: gamma               !! REGDAE_AUTO or the value
        real(c_double) :: eps
        real(c_double) :: rtol
        real(c_double) :: atol
        integer(c_int) :: stop_at_output      !! 0 or 1
        integer(c_int) :: max_steps
        real(c_double) :: h_init
        real(c_double) :: h_max
        real(c_double) :: ic_tol
        integer(c_int) :: index
        real(c_double) :: gamma0
        real(c_double) :: gamma1
        integer(c_int) :: curvature           !! 0 or 1
        integer(c_int) :: excluded            !! REGDAE_EXCLUDED_*
        real(c_double) :: singular_threshold
        real(c_double) :: jump_tol
        real(c_double) :: drift_tol
        real(c_double) :: work_tol
        real(c_double) :: invariant_tol
        real(c_double) :: taylor_h
        real(c_double) :: mass_damping
        integer(c_int) :: integrator          !! REGDAE_INTEGRATOR_*
        integer(c_int) :: linear_solver       !! REGDAE_LINEAR_SOLVER_*
        integer(c_int) :: check_jacobians     !! 0 or 1
        real(c_double) :: resolution_tol
        real(c_double) :: atol_v              !! REGDAE_AUTO (atol) or the value
        integer(c_int) :: pass_check          !! 0 or 1
        real(c_double) :: pass_tol
        integer(c_int) :: error_estimate      !! 0 or 1
        integer(c_int) :: max_order           !! IDA's largest BDF order, 1 ... 5
    end type c_options

    !> `regdae_stats` (include/regdae.h): the statistics, as `solver_stats`.
    type, bind(C), public :: c_stats
        integer(c_int64_t) :: steps
        integer(c_int64_t) :: res_evals
        integer(c_int64_t) :: jac_res_evals
        integer(c_int64_t) :: jac_evals
        integer(c_int64_t) :: lin_setups
        integer(c_int64_t) :: nonlin_iters
        integer(c_int64_t) :: err_test_fails
        integer(c_int64_t) :: conv_fails
        real(c_double) :: t
        real(c_double) :: h_last
        integer(c_int) :: singular_passes
        real(c_double) :: sigma_min
        real(c_double) :: velocity_jump
        real(c_double) :: max_drift
        real(c_double) :: invariant_change
        integer(c_int) :: switches
        real(c_double) :: work_defect
        integer(c_int) :: unresolved_passes
        real(c_double) :: resolution_ratio
        integer(c_int) :: pass_checks
        integer(c_int) :: passes_resolved
        integer(c_int) :: passes_unresolved
        real(c_double) :: pass_error
        integer(c_int64_t) :: companion_steps
        real(c_double) :: error_estimate
        integer(c_int) :: weight_changes
        integer(c_int) :: eps_changes
        integer(c_int) :: roots_found
    end type c_stats

    public :: to_c_options, to_c_stats

contains

    !> The options as the C record.
    pure function to_c_options(opts) result(c)
        type(solver_options), intent(in) :: opts
        type(c_options) :: c
        c = c_options(method=opts%method, formulation=opts%formulation, lsq=opts%lsq, exclusion=opts%exclusion, &
                      gamma=opts%gamma, eps=opts%eps, rtol=opts%rtol, atol=opts%atol, &
                      stop_at_output=merge(1, 0, opts%stop_at_output), max_steps=opts%max_steps, &
                      h_init=opts%h_init, h_max=opts%h_max, ic_tol=opts%ic_tol, index=opts%index, &
                      gamma0=opts%gamma0, gamma1=opts%gamma1, curvature=merge(1, 0, opts%curvature), &
                      excluded=opts%excluded, singular_threshold=opts%singular_threshold, jump_tol=opts%jump_tol, &
                      drift_tol=opts%drift_tol, work_tol=opts%work_tol, invariant_tol=opts%invariant_tol, &
                      taylor_h=opts%taylor_h, mass_damping=opts%mass_damping, integrator=opts%integrator, &
                      linear_solver=opts%linear_solver, check_jacobians=merge(1, 0, opts%check_jacobians), &
                      resolution_tol=opts%resolution_tol, atol_v=opts%atol_v, &
                      pass_check=merge(1, 0, opts%pass_check), pass_tol=opts%pass_tol, &
                      error_estimate=merge(1, 0, opts%error_estimate), max_order=opts%max_order)
    end function to_c_options

    !> The statistics as the C record.
    pure function to_c_stats(st) result(c)
        type(solver_stats), intent(in) :: st
        type(c_stats) :: c
        c = c_stats(steps=st%steps, res_evals=st%res_evals, jac_res_evals=st%jac_res_evals, jac_evals=st%jac_evals, &
                    lin_setups=st%lin_setups, nonlin_iters=st%nonlin_iters, err_test_fails=st%err_test_fails, &
                    conv_fails=st%conv_fails, t=st%t, h_last=st%h_last, singular_passes=st%singular_passes, &
                    sigma_min=st%sigma_min, velocity_jump=st%velocity_jump, max_drift=st%max_drift, &
                    invariant_change=st%invariant_change, switches=st%switches, work_defect=st%work_defect, &
                    unresolved_passes=st%unresolved_passes, resolution_ratio=st%resolution_ratio, &
                    pass_checks=st%pass_checks, passes_resolved=st%passes_resolved, &
                    passes_unresolved=st%passes_unresolved, pass_error=st%pass_error, &
                    companion_steps=st%companion_steps, error_estimate=st%error_estimate, &
                    weight_changes=st%weight_changes, eps_changes=st%eps_changes, &
                    roots_found=st%roots_found)
    end function to_c_stats

end module regdae_c_records
