!> A small test harness: named test cases grouped in suites, checks that
!! record failures with a message, and a summary line 'N passed, N failed'.
module regdae_testing
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
    use regdae, only: wp
    implicit none
    private

    !> Collects the failed checks of one test case.
    type, public :: checker
        integer :: failures = 0
    contains
        !> Record a failure unless `condition` holds.
        procedure :: true => check_true
        !> |actual - expected| <= tol (both finite).
        procedure :: close => check_close
        !> |actual - expected| <= rel |expected| elementwise (both finite).
        procedure :: close_rel => check_close_rel
        !> Two integers are equal.
        procedure :: equal => check_equal
    end type checker

    abstract interface
        subroutine test_procedure(chk)
            import :: checker
            type(checker), intent(inout) :: chk
        end subroutine test_procedure
    end interface

    !> A named test.
    type, public :: test_case
        character(len=64) :: name = ''   ! fixed length: arrays of tests need no deep copies
        procedure(test_procedure), pointer, nopass :: run => null()
    end type test_case

    public :: test_procedure, new_test, run_suite

contains

    function new_test(name, run) result(tc)
        character(len=*), intent(in) :: name
        procedure(test_procedure) :: run
        type(test_case) :: tc
        tc%name = name
        tc%run => run
    end function new_test

    !> Run all tests of a suite; returns the number of failed tests.
    function run_suite(suite_name, tests) result(nfailed)
        character(len=*), intent(in) :: suite_name
        type(test_case), intent(in) :: tests(:)
        integer :: nfailed, i
        type(checker) :: chk
        nfailed = 0
        do i = 1, size(tests)
            chk%failures = 0
            call tests(i)%run(chk)
            if (chk%failures == 0) then
                write (*, '(a)') '  PASS '//suite_name//'/'//trim(tests(i)%name)
            else
                write (*, '(a)') '  FAIL '//suite_name//'/'//trim(tests(i)%name)
                nfailed = nfailed + 1
            end if
        end do
    end function run_suite

    subroutine check_true(self, condition, what)
        class(checker), intent(inout) :: self
        logical, intent(in) :: condition
        character(len=*), intent(in) :: what
        if (.not. condition) then
            self%failures = self%failures + 1
            write (*, '(a)') '    check failed: '//what
        end if
    end subroutine check_true

    subroutine check_equal(self, actual, expected, what)
        class(checker), intent(inout) :: self
        integer, intent(in) :: actual, expected
        character(len=*), intent(in) :: what
        if (actual /= expected) then
            self%failures = self%failures + 1
            write (*, '(a,i0,a,i0)') '    check failed: '//what//': got ', actual, ', expected ', expected
        end if
    end subroutine check_equal

    subroutine check_close(self, actual, expected, tol, what)
        class(checker), intent(inout) :: self
        real(wp), intent(in) :: actual, expected, tol
        character(len=*), intent(in) :: what
        if (.not. (ieee_is_finite(actual) .and. abs(actual - expected) <= tol)) then
            self%failures = self%failures + 1
            write (*, '(a,es23.15,a,es23.15,a,es9.2,a,es9.2)') '    check failed: '//what//': got ', actual, &
                ', expected ', expected, ', |diff| ', abs(actual - expected), ' > tol ', tol
        end if
    end subroutine check_close

    subroutine check_close_rel(self, actual, expected, rel, what)
        class(checker), intent(inout) :: self
        real(wp), intent(in) :: actual(:), expected(:), rel
        character(len=*), intent(in) :: what
        real(wp) :: err
        err = maxval(abs(actual - expected))/maxval(abs(expected))
        if (.not. (all(ieee_is_finite(actual)) .and. err <= rel)) then
            self%failures = self%failures + 1
            write (*, '(a,es9.2,a,es9.2)') '    check failed: '//what//': relative error ', err, ' > ', rel
        end if
    end subroutine check_close_rel

end module regdae_testing
