!> Diagnostics sampled along the computed solution: sigma_min(GB) and the
!! singular intervals (runs of consecutive samples with sigma_min(GB) below a
!! threshold). A sample reads the regularized model's last evaluation, so it
!! costs nothing when that evaluation was made at a point of the solution anyway
!! (IDA: the output times; dopri5: the end of each accepted step).
module regdae_monitor
    use regdae_kinds, only: wp
    use regdae_regularization, only: regularized_dae
    implicit none
    private

    !> The sampled diagnostics of one solver.
    type, public :: solution_monitor
        real(wp) :: threshold = 0.05_wp          !! sigma_min(GB) below this marks a singular sample
        real(wp) :: sigma_last = huge(1.0_wp)    !! sigma_min(GB) at the last sample
        real(wp) :: sigma_min = huge(1.0_wp)     !! smallest sigma_min(GB) over the samples
        integer :: n_singular = 0                !! singular intervals so far
        logical :: in_singular = .false.         !! the last sample was singular
        real(wp), allocatable :: singular(:, :)  !! (2, n_singular): first and last sample time of each
    contains
        !> Forget all samples; set the threshold.
        procedure :: reset => monitor_reset
        !> Sample the model's last evaluation, made at time t on the solution.
        procedure :: sample => monitor_sample
        !> The singular intervals, (2, n_singular).
        procedure :: intervals => monitor_intervals
    end type solution_monitor

contains

    subroutine monitor_reset(self, threshold)
        class(solution_monitor), intent(inout) :: self
        real(wp), intent(in) :: threshold
        self%threshold = threshold
        self%sigma_last = huge(1.0_wp)
        self%sigma_min = huge(1.0_wp)
        self%n_singular = 0
        self%in_singular = .false.
        if (allocated(self%singular)) deallocate (self%singular)
    end subroutine monitor_reset

    subroutine monitor_sample(self, t, model)
        class(solution_monitor), intent(inout) :: self
        real(wp), intent(in) :: t
        type(regularized_dae), intent(inout) :: model
        real(wp), allocatable :: grown(:, :)
        self%sigma_last = model%sigma_min_gb()
        self%sigma_min = min(self%sigma_min, self%sigma_last)
        if (self%sigma_last < self%threshold) then
            if (.not. self%in_singular) then
                if (.not. allocated(self%singular)) allocate (self%singular(2, 8))
                if (self%n_singular == size(self%singular, 2)) then
                    allocate (grown(2, 2*size(self%singular, 2)))
                    grown(:, 1:self%n_singular) = self%singular
                    call move_alloc(grown, self%singular)
                end if
                self%n_singular = self%n_singular + 1
                self%singular(1, self%n_singular) = t
            end if
            self%singular(2, self%n_singular) = t
            self%in_singular = .true.
        else
            self%in_singular = .false.
        end if
    end subroutine monitor_sample

    function monitor_intervals(self) result(intervals)
        class(solution_monitor), intent(in) :: self
        real(wp), allocatable :: intervals(:, :)
        allocate (intervals(2, 0))
        if (self%n_singular > 0) intervals = self%singular(:, 1:self%n_singular)
    end function monitor_intervals

end module regdae_monitor
