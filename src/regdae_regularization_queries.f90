!> What the monitor and the checks ask of a regularized model (`regdae_regularization`):
!! the position drift, the invariant, the position Jacobian, the free slope, sigma_min(GB)
!! (with a given G too), and for mechanical problems the kinetic energy and power.
submodule (regdae_regularization) regdae_regularization_queries
    use regdae_velocity_index2, only: velocity_index2_problem
    use regdae_work_energy, only: kinetic_energy_and_power
    implicit none

contains

    module procedure position_drift
        stat = 0
        drift = -1.0_wp
        if (self%order >= 2) then
            drift = maxval(abs(self%g), 1)
        else if (allocated(self%first)) then
            select type (p => self%first)
            type is (velocity_index2_problem)
                block
                    real(wp) :: g(self%m)
                    call p%second%constraint(t, z(1:p%second%n), g, stat)
                    if (stat == 0) drift = maxval(abs(g), 1)
                end block
            end select
        end if
        if (self%m == 0) drift = max(drift, 0.0_wp)
    end procedure position_drift

    module procedure invariant_value
        use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
        integer :: n
        stat = 0
        val = ieee_value(1.0_wp, ieee_quiet_nan)
        if (allocated(self%second)) then
            n = self%n
            call self%second%invariant(t, z(1:n), z(n + 1:2*n), val, stat)
        else if (allocated(self%higher)) then
            return
        else if (allocated(self%first)) then
            select type (p => self%first)
            type is (velocity_index2_problem)
                n = p%second%n
                call p%second%invariant(t, z(1:n), z(n + 1:2*n), val, stat)
            end select
        end if
    end procedure invariant_value

    module procedure position_jacobian
        stat = 0
        if (allocated(self%second)) then
            call self%second%constraint_jacobian(t, x, gx, stat)
        else if (allocated(self%higher)) then
            call self%higher%constraint_jacobian(t, x, gx, stat)
        else
            select type (p => self%first)
            type is (velocity_index2_problem)
                call p%second%constraint_jacobian(t, x, gx, stat)
            class default
                call p%constraint_jacobian(t, x, gx, stat)
            end select
        end if
    end procedure position_jacobian

    module procedure free_slope
        stat = 0
        if (allocated(self%second)) then
            call self%second%rhs(t, z(1:self%n), z(self%n + 1:2*self%n), f, stat)
        else if (allocated(self%higher)) then
            call self%higher%rhs(t, reshape(z(1:self%order*self%n), [self%n, self%order]), f, stat)
        else
            call self%first%rhs(t, z, f, stat)
        end if
    end procedure free_slope

    module procedure conditioning_with
        real(wp), allocatable :: b(:, :), gb(:, :)
        integer :: n
        stat = 0
        n = size(gx, 2)
        allocate (b(n, self%m), gb(self%m, self%m))
        if (allocated(self%second)) then
            call self%second%matrix_b_from_jacobian(t, z(1:n), z(n + 1:2*n), gx, b, stat)
        else if (allocated(self%higher)) then
            b = self%b
        else
            select type (p => self%first)
            type is (velocity_index2_problem)
                call p%second%matrix_b_from_jacobian(t, z(1:n), z(n + 1:2*n), gx, b, stat)
            class default
                b = self%b
            end select
        end if
        sigma = -1.0_wp
        if (stat /= 0) return
        gb = matmul(gx, b)
        sigma = self%lsq_ws%smallest_singular_value(gb)
    end procedure conditioning_with

    module procedure is_mechanical
        class(mechanical_problem), allocatable :: mold   ! unallocated: its declared type
        is_mechanical = .false.
        if (allocated(self%second)) then
            is_mechanical = extends_type_of(self%second, mold)
        else if (allocated(self%first)) then
            select type (p => self%first)
            type is (velocity_index2_problem)
                is_mechanical = extends_type_of(p%second, mold)
            end select
        end if
    end procedure is_mechanical

    module procedure mechanical
        problem => null()
        if (allocated(self%second)) then
            select type (p => self%second)
            class is (mechanical_problem)
                problem => p
            end select
        else if (allocated(self%first)) then
            select type (p => self%first)
            type is (velocity_index2_problem)
                select type (pp => p%second)
                class is (mechanical_problem)
                    problem => pp
                end select
            end select
        end if
    end procedure mechanical

    module procedure work_sample
        real(wp) :: y(self%m)
        class(mechanical_problem), pointer :: p
        kinetic = 0.0_wp
        power = 0.0_wp
        stat = -1
        if (.not. self%is_mechanical()) return
        call self%solve_multiplier(t, y, stat)
        if (stat /= 0) return
        p => self%mechanical()
        if (associated(p)) &
            call kinetic_energy_and_power(p, t, z(1:p%n), z(p%n + 1:2*p%n), y, kinetic, power, stat, sums=sums)
    end procedure work_sample

    module procedure sigma_min_gb
        sigma = self%lsq_ws%smallest_singular_value(self%gb)
    end procedure sigma_min_gb

end submodule regdae_regularization_queries
