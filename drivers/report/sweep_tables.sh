#!/bin/sh
# Tables for drivers/sweep (issue 13), written to stdout.
#   sweep_tables.sh crank_map [N_TH] [N_W]   the slider crank at index 3, all options at their
#       defaults, from th1 = (i - 1/2) pi / N_TH (i = 1..N_TH, th2 = pi - th1) with speed
#       w1 = -10 + 20 (j - 1/2) / N_W rad/s (j = 1..N_W), t in [0, 10]: N_TH N_W rows
#       (default 100 x 100 = 10^4), row id (i - 1) N_W + j
#   sweep_tables.sh stability [PROBLEM]   the cells of drivers/stability's tuned grid (problem=ex51,
#       crank2, crank3; default all three, in stability's order: rtol, eps, gamma, problem) with
#       its options: rtol = atol, max_steps=20000, integrator=ida, singular_threshold=0.05,
#       drift_tol=1e-2, work_tol=0; Example 5.1 with 201 outputs (steps end at them), the crank
#       t in [0, 10] with 501 outputs (stop_at_output=no, as stability), gamma1 = gamma, gamma0 = gamma^2/2, invariant_tol=1.
#       The sweep gives each cell's status and errors, not stability's classes (those need its
#       bounds and the rerun without checks), nor its 200000-step budget per crank run.
set -eu
case ${1:-} in
crank_map)
    awk -v nt="${2:-100}" -v nw="${3:-100}" 'BEGIN {
        pi = atan2(0, -1)
        print "# the slider crank map: th1 (i - 1/2) pi / " nt ", w1 -10 + 20 (j - 1/2) / " nw
        for (i = 1; i <= nt; i++) for (j = 1; j <= nw; j++)
            printf "crank3 th1=%.17g w1=%.17g\n", (i - 0.5) * pi / nt, -10 + 20 * (j - 0.5) / nw }'
    ;;
stability)
    which=${2:-all}
    awk -v which="$which" 'BEGIN {
        split("1e1 1e2 1e3 1e4 1e5 1e6 1e7 1e8", gammas, " ")
        split("1e-2 1e-4 1e-6 1e-8 1e-10 1e-12 1e-14 0", epss, " ")
        split("1e-3 1e-5 1e-7 1e-10", rtols, " ")
        tuned = "max_steps=20000 integrator=ida singular_threshold=0.05 drift_tol=1e-2 work_tol=0"
        print "# drivers/stability tuned grid through sweep (" which ")"
        for (r = 1; r <= 4; r++) for (e = 1; e <= 8; e++) for (g = 1; g <= 8; g++) {
            tol = "rtol=" rtols[r] " atol=" rtols[r] " eps=" epss[e]
            if (which == "all" || which == "ex51")
                print "ex51 gamma=" gammas[g], tol, tuned
            for (k = 2; k <= 3; k++) if (which == "all" || which == "crank" k)
                print "crank" k " gamma=" gammas[g] " gamma1=" gammas[g] " gamma0=" (gammas[g] ^ 2) / 2, tol, tuned,
                    "tf=10 nout=500 invariant_tol=1 stop_at_output=no"
        } }'
    ;;
*)
    echo "usage: sweep_tables.sh crank_map [N_TH] [N_W] | stability [ex51|crank2|crank3]" >&2
    exit 2
    ;;
esac
