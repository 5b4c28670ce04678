!> A small deterministic pseudo-random generator for the drivers' grids:
!! Marsaglia's 64-bit xorshift (G. Marsaglia, "Xorshift RNGs", J. Stat. Softw.
!! 8(14), 2003) with the shift triple (13, 7, 17),
!! $$ x \leftarrow x \oplus (x \ll 13),\quad x \leftarrow x \oplus (x \gg 7),\quad
!!    x \leftarrow x \oplus (x \ll 17), $$
!! on a 64-bit integer used as a bit pattern (`ishft` is a logical shift, so no
!! signed overflow occurs). The intrinsic `random_number` is not used: its sequence
!! depends on the compiler and its version, and the grids must be the same everywhere.
module xorshift_random
    use, intrinsic :: iso_fortran_env, only: int64
    use regdae, only: wp
    implicit none
    private

    !> The generator's state (never zero). The default seed is Marsaglia's example.
    type, public :: xorshift64
        integer(int64) :: state = 88172645463325252_int64   !! the 64 bits of the state
    contains
        !> The next 64-bit pattern.
        procedure :: next_bits => xorshift_next_bits
        !> The next number uniform in the open interval (0, 1): the top 52 bits plus one half, over 2^52
        !! (exact in double precision, never 0 or 1).
        procedure :: next_uniform => xorshift_next_uniform
        !> The next number uniform in the open interval (a, b).
        procedure :: next_between => xorshift_next_between
    end type xorshift64

    public :: new_xorshift64

contains

    !> A generator started from `seed` (a zero seed is replaced by the default one).
    function new_xorshift64(seed) result(gen)
        integer(int64), intent(in) :: seed   !! the initial state
        type(xorshift64) :: gen
        if (seed /= 0_int64) gen%state = seed
    end function new_xorshift64

    function xorshift_next_bits(self) result(bits)
        class(xorshift64), intent(inout) :: self
        integer(int64) :: bits
        bits = self%state
        bits = ieor(bits, ishft(bits, 13))
        bits = ieor(bits, ishft(bits, -7))
        bits = ieor(bits, ishft(bits, 17))
        self%state = bits
    end function xorshift_next_bits

    function xorshift_next_uniform(self) result(u)
        class(xorshift64), intent(inout) :: self
        real(wp) :: u
        integer(int64) :: top
        top = ishft(self%next_bits(), -12)   ! 0 <= top < 2^52: top + 1/2 is exact
        u = (real(top, wp) + 0.5_wp)/4503599627370496.0_wp
    end function xorshift_next_uniform

    function xorshift_next_between(self, a, b) result(x)
        class(xorshift64), intent(inout) :: self
        real(wp), intent(in) :: a, b   !! the interval's ends, a < b
        real(wp) :: x
        x = a + (b - a)*self%next_uniform()
    end function xorshift_next_between

end module xorshift_random
