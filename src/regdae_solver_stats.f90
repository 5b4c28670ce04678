!> The statistics a solver reports: its integrator's counters, in IDA's terms,
!! and the singularity diagnostics of the monitor.
module regdae_solver_stats
    use, intrinsic :: iso_fortran_env, only: int64
    use regdae_kinds, only: wp
    implicit none
    private

    !> Integration statistics, in IDA's terms, and the singularity diagnostics.
    type, public :: solver_stats
        integer(int64) :: steps = 0            !! steps taken
        integer(int64) :: res_evals = 0        !! all residual evaluations (IDA's + Jacobian's)
        integer(int64) :: jac_res_evals = 0    !! residual evaluations in difference-quotient Jacobians
        integer(int64) :: jac_evals = 0        !! Jacobian evaluations
        integer(int64) :: lin_setups = 0       !! linear solver setups (factorizations)
        integer(int64) :: nonlin_iters = 0     !! Newton iterations
        integer(int64) :: err_test_fails = 0   !! local error test failures
        integer(int64) :: conv_fails = 0       !! nonlinear convergence failures
        real(wp) :: t = 0.0_wp                 !! time reached
        real(wp) :: h_last = 0.0_wp            !! last step size used
        integer :: singular_passes = 0         !! runs of consecutive samples with sigma_min(GB) < singular_threshold
                                               !! (samples: the output times with IDA, the accepted steps with dopri5)
        real(wp) :: sigma_min = huge(1.0_wp)   !! smallest sigma_min(GB) over the samples
        real(wp) :: velocity_jump = 0.0_wp     !! largest relative velocity jump across a singular interval
        real(wp) :: max_drift = 0.0_wp         !! largest max |g(x, t)| over the samples (order >= 2)
        real(wp) :: invariant_change = 0.0_wp  !! largest |I - I(t0)| of the problem's invariant (invariant_tol > 0)
        integer :: switches = 0                !! integrator=auto: switches between dopri5 and the implicit integrator (IDA or Radau)
        real(wp) :: work_defect = 0.0_wp       !! mechanical problems: largest |T - T(t0) - W| relative to the energy
                                               !! scale of the motion (the work-energy check, work_tol)
        integer :: unresolved_passes = 0       !! singular passes approached with an x error, implied by the
                                               !! constraint residual, above resolution_tol times the tolerance
        real(wp) :: resolution_ratio = 0.0_wp  !! largest such implied error over the tolerance (rtol |x| + atol)
        integer :: pass_checks = 0             !! singular passes re-integrated at tighter tolerances (pass_check)
        integer :: passes_resolved = 0         !! of those, passes where the solution disagreed with rtol/10 and
                                               !! a tighter pair agreed
        integer :: passes_unresolved = 0       !! of those, passes where no two levels agreed (a warning each)
        real(wp) :: pass_error = 0.0_wp        !! largest difference between the solution and the first tighter
                                               !! level over a pass, in error weights (rtol |z| + atol)
        integer(int64) :: companion_steps = 0  !! steps of the companions (pass checks and the error estimate)
        real(wp) :: error_estimate = -1.0_wp   !! error_estimate=yes: the estimated error of x at the last output,
                                               !! max_i |e_i| / (rtol |x_i| + atol_i); -1: no estimate
        integer :: weight_changes = 0          !! automatic Baumgarte weights changed along the run
        integer :: eps_changes = 0             !! automatic eps changed along the run
        integer :: roots_found = 0             !! roots of the event functions reported (set_events)
    end type solver_stats

end module regdae_solver_stats
