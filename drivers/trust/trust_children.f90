!> The reference runs of drivers/trust that run in child processes of the driver under
!! coreutils' `timeout` (neither has a wall budget of its own): the plain IDA peer on a chain
!! (`peer_job=...`) and Dormand-Prince on a reduced ODE (`oracle_job=...`); the parent's side
!! (peer_run, oracle_run) and the child's (peer_job, oracle_job), the results through a file.
module trust_children
    use, intrinsic :: iso_fortran_env, only: int64
    use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
    use regdae, only: wp
    use slider_crank_problem, only: slider_crank_reduced
    use fourbar_problem, only: fourbar_reduced
    use chain_peer, only: run_chain_peer
    use dopri5, only: dopri5_integrate
    use driver_support, only: die_usage, read_number, read_count
    use trust_grid, only: crank_gravity, chain_gravity, fourbar_r, fourbar_g
    use trust_text, only: itext, num_exact
    implicit none
    private
    public :: peer_run, oracle_run, peer_job, oracle_job, output_times, peer_good, finite_outputs, oracle_text

    character(len=*), parameter :: prog = 'trust'
    !> The status of a child process (the peer, Dormand-Prince) that `timeout` stopped, or that failed.
    integer, parameter, public :: child_timed_out = -9124, child_failed = -9125
    !> Wall-clock limit (s) of a Dormand-Prince run (a normal one takes milliseconds).
    integer, parameter, public :: oracle_timeout = 10
    !> Wall-clock limits (s) of a peer run: a reference, a reference-method run.
    integer, parameter, public :: peer_ref_timeout = 600, peer_method_timeout = 120

contains

    !> The chain (with `slider`, every even joint on y = 0) by the peer at rtol = atol = `rtol`,
    !! outputs at 0 and `times` (output_times), in a child process of this program stopped after
    !! `timeout` seconds (status child_timed_out).
    subroutine peer_run(tag, links, slider, rtol, times, q, stat, steps, seconds, message, timeout, v)
        character(len=*), intent(in) :: tag   !! the process's tag of its child files (trust_setup%child_tag)
        integer, intent(in) :: links, timeout
        logical, intent(in) :: slider
        real(wp), intent(in) :: rtol, times(:)
        real(wp), intent(out) :: q(:, :)
        real(wp), intent(out), optional :: v(:, :)   !! the velocities, as q
        integer, intent(out) :: stat, steps
        real(wp), intent(out) :: seconds
        character(len=:), allocatable, intent(out) :: message
        character(len=:), allocatable :: file
        integer :: unit, ios, nmsg
        q = ieee_value(1.0_wp, ieee_quiet_nan)
        if (present(v)) v = ieee_value(1.0_wp, ieee_quiet_nan)
        steps = 0
        seconds = 0.0_wp
        call run_child('peer_job='//itext(links)//','//trim(merge('slider', 'plain ', slider))//','// &
                       num_exact(rtol)//','//itext(size(times))//','// &
                       num_exact(times(size(times))), timeout, 'the peer', tag, file, unit, stat, message)
        if (stat /= 0) return
        read (unit, iostat=ios) stat, steps, seconds, nmsg
        if (ios == 0) then
            deallocate (message)
            allocate (character(len=nmsg) :: message)
            read (unit, iostat=ios) message, q
            if (ios == 0 .and. present(v)) read (unit, iostat=ios) v
        end if
        close (unit, status='delete')
        if (ios /= 0) then
            stat = child_failed
            message = 'the peer''s result could not be read'
        end if
    end subroutine peer_run

    !> The reference method: Dormand-Prince (drivers/common/dopri5.f90) at rtol = atol = `rtol` on
    !! the reduced ODE of `system` ('crank' or 'fourbar') from (th1, w1) to `times` (output_times),
    !! in a child process stopped after `timeout` seconds: dopri5_integrate has no step limit,
    !! and an error estimate that becomes NaN (a solution that blew up) makes it loop for ever.
    subroutine oracle_run(tag, system, th1, w1, rtol, times, states, stat, message, timeout)
        character(len=*), intent(in) :: tag   !! the process's tag of its child files (trust_setup%child_tag)
        character(len=*), intent(in) :: system
        real(wp), intent(in) :: th1, w1, rtol, times(:)
        real(wp), intent(out) :: states(:, :)
        integer, intent(out) :: stat
        character(len=:), allocatable, intent(out) :: message
        integer, intent(in) :: timeout
        character(len=:), allocatable :: file
        integer :: unit, ios
        states = ieee_value(1.0_wp, ieee_quiet_nan)
        call run_child('oracle_job='//system//','//num_exact(th1)//','//num_exact(w1)//','//num_exact(rtol)//','// &
                       itext(size(times))//','//num_exact(times(size(times))), timeout, 'Dormand-Prince', tag, file, unit, &
                       stat, message)
        if (stat /= 0) return
        read (unit, iostat=ios) states
        close (unit, status='delete')
        if (ios /= 0) then
            stat = child_failed
            message = 'the Dormand-Prince result could not be read'
        end if
    end subroutine oracle_run

    !> The child process: peer_job=N,plain|slider,rtol,nout,tf,file runs the chain (slider: every
    !! even joint on y = 0) by the peer at rtol = atol on the outputs 0 and output_times(tf, nout)
    !! and writes the result.
    subroutine peer_job(spec)
        character(len=*), intent(in) :: spec
        character(len=len(spec)) :: fields(6)
        character(len=:), allocatable :: message
        real(wp) :: rtol, tf, seconds
        real(wp), allocatable :: q(:, :), v(:, :)
        integer :: links, nout, stat, steps, res_evals, jac_evals, unit, count
        call split_fields(spec, fields, count)
        if (count /= 6 .or. all(trim(fields(2)) /= ['plain ', 'slider'])) &
            call die_usage(prog, 'peer_job=N,plain|slider,rtol,nout,tf,file')
        call read_count(prog, 'peer_job N', trim(fields(1)), links, 1, 1000000)
        call read_number(prog, 'peer_job rtol', trim(fields(3)), rtol)
        call read_count(prog, 'peer_job nout', trim(fields(4)), nout, 1, 1000000)
        call read_number(prog, 'peer_job tf', trim(fields(5)), tf)
        allocate (q(2*links, nout + 1), v(2*links, nout + 1))
        call run_chain_peer(links, trim(fields(2)) == 'slider', rtol, rtol, [0.0_wp, output_times(tf, nout)], q, &
                            steps, res_evals, jac_evals, seconds, stat, message, v_out=v)
        open (newunit=unit, file=trim(fields(6)), access='stream', form='unformatted', status='replace', action='write')
        write (unit) stat, steps, seconds, len(message), message, q, v
        close (unit)
    end subroutine peer_job

    !> The child process: oracle_job=crank|chain2|fourbar,th1,w1,rtol,nout,tf,file runs Dormand-Prince on
    !! the reduced ODE from (th1, w1) to output_times(tf, nout) and writes the states (2, nout).
    subroutine oracle_job(spec)
        character(len=*), intent(in) :: spec
        character(len=len(spec)) :: fields(7)
        type(slider_crank_reduced) :: crank
        type(fourbar_reduced) :: bar
        real(wp) :: th1, w1, rtol, tf
        real(wp), allocatable :: states(:, :)
        integer :: nout, steps, evals, unit, count
        call split_fields(spec, fields, count)
        if (count /= 7) call die_usage(prog, 'oracle_job=crank|chain2|fourbar,th1,w1,rtol,nout,tf,file')
        call read_number(prog, 'oracle_job th1', trim(fields(2)), th1)
        call read_number(prog, 'oracle_job w1', trim(fields(3)), w1)
        call read_number(prog, 'oracle_job rtol', trim(fields(4)), rtol)
        call read_count(prog, 'oracle_job nout', trim(fields(5)), nout, 1, 1000000)
        call read_number(prog, 'oracle_job tf', trim(fields(6)), tf)
        allocate (states(2, nout))
        select case (trim(fields(1)))
        case ('crank', 'chain2')   ! chain2: the slider crank as the chain of 2 links with the slider
            crank%gravity = merge(chain_gravity, crank_gravity, trim(fields(1)) == 'chain2')
            call dopri5_integrate(crank, 0.0_wp, [th1, w1], output_times(tf, nout), states, rtol, rtol, steps, evals)
        case ('fourbar')
            bar%crank = fourbar_r
            bar%gravity = fourbar_g
            call dopri5_integrate(bar, 0.0_wp, [th1, w1], output_times(tf, nout), states, rtol, rtol, steps, evals)
        case default
            call die_usage(prog, 'oracle_job: crank or fourbar')
        end select
        open (newunit=unit, file=trim(fields(7)), access='stream', form='unformatted', status='replace', action='write')
        write (unit) states
        close (unit)
    end subroutine oracle_job

    !> The nout outputs tf k / nout, k = 1 ... nout (the parent's and the child processes' alike).
    pure function output_times(tf, nout) result(times)
        real(wp), intent(in) :: tf
        integer, intent(in) :: nout
        real(wp) :: times(nout)
        integer :: k
        times = [(tf*real(k, wp)/real(nout, wp), k=1, nout)]
    end function output_times

    !> The outputs of a peer run before its first NaN.
    integer function peer_good(q) result(good)
        real(wp), intent(in) :: q(:, :)
        good = 0
        do while (good < size(q, 2))
            if (any(q(:, good + 1) /= q(:, good + 1))) exit
            good = good + 1
        end do
    end function peer_good

    !> The outputs before the first one with a component that is NaN or infinite.
    pure integer function finite_outputs(states) result(good)
        real(wp), intent(in) :: states(:, :)
        good = 0
        do while (good < size(states, 2))
            if (.not. all(abs(states(:, good + 1)) <= huge(1.0_wp))) exit
            good = good + 1
        end do
    end function finite_outputs

    !> The reference method's column: ok, timeout, failed, or diverged (a NaN or Inf output).
    function oracle_text(stat, states) result(text)
        integer, intent(in) :: stat
        real(wp), intent(in) :: states(:, :)
        character(len=:), allocatable :: text
        if (stat == child_timed_out) then
            text = 'timeout'
        else if (stat /= 0) then
            text = 'failed'
        else if (finite_outputs(states) < size(states, 2)) then
            text = 'diverged'
        else
            text = 'ok'
        end if
    end function oracle_text

    ! Run this program as `exe job,FILE` under coreutils' timeout; on success (stat = 0) FILE is
    ! open for reading on `unit` (stream access), otherwise stat = child_timed_out or child_failed.
    subroutine run_child(job, timeout, what, tag, file, unit, stat, message)
        character(len=*), intent(in) :: job, what, tag
        integer, intent(in) :: timeout
        character(len=:), allocatable, intent(out) :: file, message
        integer, intent(out) :: unit, stat
        character(len=:), allocatable :: exe, tmp
        integer :: length, exit_stat, cmd_stat, ios
        integer(int64) :: tick
        stat = 0
        unit = -1
        message = ''
        call get_command_argument(0, length=length)
        allocate (character(len=length) :: exe)
        call get_command_argument(0, exe)
        call get_environment_variable('TMPDIR', length=length)
        if (length > 0) then
            allocate (character(len=length) :: tmp)
            call get_environment_variable('TMPDIR', tmp)
        else
            tmp = '/tmp'
        end if
        call system_clock(tick)
        file = tmp//'/trust_child_'//tag//'_'// &
               itext(int(modulo(tick, 1000000000_int64)))
        call execute_command_line('timeout '//itext(timeout)//' '//exe//' '//job//','//file//' >/dev/null 2>&1', &
                                  exitstat=exit_stat, cmdstat=cmd_stat)
        if (cmd_stat /= 0) then
            stat = child_failed
            message = 'could not start the child process for '//what
        else if (exit_stat == 124) then
            stat = child_timed_out
            message = what//' ran longer than '//itext(timeout)//' s (stopped by timeout)'
            call remove_file(file)
        else
            open (newunit=unit, file=file, access='stream', form='unformatted', status='old', action='read', &
                  iostat=ios)
            if (ios /= 0) then
                stat = child_failed
                message = 'the child process for '//what//' wrote no result (exit status '//itext(exit_stat)//')'
            end if
        end if
    end subroutine run_child

    ! The comma-separated fields of `text` into fields(1:min(count, size(fields))).
    subroutine split_fields(text, fields, count)
        character(len=*), intent(in) :: text
        character(len=*), intent(out) :: fields(:)
        integer, intent(out) :: count
        integer :: a, b
        fields = ''
        count = 0
        a = 1
        do
            count = count + 1
            b = index(text(a:), ',')
            if (count <= size(fields)) then
                if (b == 0) then
                    fields(count) = text(a:)
                else
                    fields(count) = text(a:a + b - 2)
                end if
            end if
            if (b == 0) exit
            a = a + b
        end do
    end subroutine split_fields

    ! Delete `file` if it exists.
    subroutine remove_file(file)
        character(len=*), intent(in) :: file
        integer :: unit, ios
        open (newunit=unit, file=file, status='old', iostat=ios)
        if (ios == 0) close (unit, status='delete')
    end subroutine remove_file

end module trust_children
