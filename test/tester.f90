!> The regdae test runner: `regdae_tester SUITE` runs one suite (ctest has an
!! entry per suite), `regdae_tester` runs all. Prints 'N passed, N failed'
!! and exits with status 1 if a test failed.
program regdae_tester
    use regdae_testing, only: test_case, run_suite
    use test_lsq, only: lsq_tests
    use test_residuals, only: residual_tests
    use test_solver, only: solver_tests
    use test_mechanics, only: mechanics_tests
    use test_theory, only: theory_tests
    use test_hardening, only: hardening_tests
    use test_fuzz, only: fuzz_tests
    use test_structure, only: structure_tests
    use test_defaults, only: defaults_tests
    use test_api, only: api_tests
    use test_radau, only: radau_tests
    use test_radau_solver, only: radau_solver_tests
    use test_events, only: events_tests
    use test_plain_dae, only: plain_dae_tests
    implicit none
    character(len=64) :: suite
    integer :: nfailed, ntotal
    logical :: all_suites, known

    suite = ''
    if (command_argument_count() >= 1) call get_command_argument(1, suite)
    all_suites = (suite == '')
    known = .false.
    nfailed = 0
    ntotal = 0
    call maybe_run('lsq', lsq_tests())
    call maybe_run('residuals', residual_tests())
    call maybe_run('solver', solver_tests())
    call maybe_run('mechanics', mechanics_tests())
    call maybe_run('theory', theory_tests())
    call maybe_run('hardening', hardening_tests())
    call maybe_run('fuzz', fuzz_tests())
    call maybe_run('structure', structure_tests())
    call maybe_run('defaults', defaults_tests())
    call maybe_run('api', api_tests())
    call maybe_run('radau', radau_tests())
    call maybe_run('radau_solver', radau_solver_tests())
    call maybe_run('events', events_tests())
    call maybe_run('plain_dae', plain_dae_tests())
    if (.not. known) then
        write (*, '(a)') 'regdae_tester: unknown suite "'//trim(suite)// &
            '" (lsq, residuals, solver, mechanics, theory, hardening, fuzz, structure, defaults, api, radau, ' // &
            'radau_solver, events, plain_dae)'
        stop 2
    end if
    write (*, '(i0,a,i0,a)') ntotal - nfailed, ' passed, ', nfailed, ' failed'
    if (nfailed > 0) stop 1

contains

    subroutine maybe_run(name, tests)
        character(len=*), intent(in) :: name
        type(test_case), intent(in) :: tests(:)
        if (.not. (all_suites .or. suite == name)) return
        known = .true.
        nfailed = nfailed + run_suite(name, tests)
        ntotal = ntotal + size(tests)
    end subroutine maybe_run

end program regdae_tester
