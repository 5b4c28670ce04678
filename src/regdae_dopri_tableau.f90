!> The Dormand-Prince 5(4) tableau (Dormand & Prince 1980): nodes c, stage
!! weights a, 5th-order weights b, e = b - b_hat for the embedded error estimate,
!! and the weights d of the 4th-order continuous extension (Shampine 1986, as in
!! Hairer, Norsett & Wanner, Solving ODEs I, section II.6): with theta in [0, 1],
!! dy = y1 - y0, p = h k1 - dy, q = dy - h k7 - p, r = h sum_i d_i k_i,
!! $$ y(t_0 + \theta h) = y_0 + \theta (dy + (1-\theta)(p + \theta (q + (1-\theta) r))). $$
!! Shared by `integrator=dopri5` and the benchmark's oracle.
module regdae_dopri_tableau
    use regdae_kinds, only: wp
    implicit none
    public
    private :: wp   ! the tableau only

    real(wp), parameter :: c2 = 1.0_wp/5, c3 = 3.0_wp/10, c4 = 4.0_wp/5, c5 = 8.0_wp/9
    real(wp), parameter :: a21 = 1.0_wp/5
    real(wp), parameter :: a31 = 3.0_wp/40, a32 = 9.0_wp/40
    real(wp), parameter :: a41 = 44.0_wp/45, a42 = -56.0_wp/15, a43 = 32.0_wp/9
    real(wp), parameter :: a51 = 19372.0_wp/6561, a52 = -25360.0_wp/2187, a53 = 64448.0_wp/6561, &
                           a54 = -212.0_wp/729
    real(wp), parameter :: a61 = 9017.0_wp/3168, a62 = -355.0_wp/33, a63 = 46732.0_wp/5247, a64 = 49.0_wp/176, &
                           a65 = -5103.0_wp/18656
    real(wp), parameter :: b1 = 35.0_wp/384, b3 = 500.0_wp/1113, b4 = 125.0_wp/192, b5 = -2187.0_wp/6784, &
                           b6 = 11.0_wp/84
    real(wp), parameter :: e1 = 71.0_wp/57600, e3 = -71.0_wp/16695, e4 = 71.0_wp/1920, e5 = -17253.0_wp/339200, &
                           e6 = 22.0_wp/525, e7 = -1.0_wp/40
    real(wp), parameter :: d1 = -12715105075.0_wp/11282082432.0_wp, d3 = 87487479700.0_wp/32700410799.0_wp, &
                           d4 = -10690763975.0_wp/1880347072.0_wp, d5 = 701980252875.0_wp/199316789632.0_wp, &
                           d6 = -1453857185.0_wp/822651844.0_wp, d7 = 69997945.0_wp/29380423.0_wp

end module regdae_dopri_tableau
