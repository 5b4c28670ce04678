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
#   sweep_tables.sh bench [crank|ex51|all]   drivers/bench's regdae rows (problem=crank, ex51; default
#       all), one row each, in bench's order: for rtol = atol = 1e-3 ... 1e-10 9 of its configurations
#       of the slider crank (crank3, crank2; its options: gamma=1e6 gamma1=2e3 gamma0=2e6
#       integrator=ida, or dopri5 with gamma1=20 gamma0=200, or 'defaults' = rtol and atol alone;
#       stop_at_output=no as bench; 1001 outputs on [0, 10], the rows' default) and its 6 of
#       Example 5.1 (every method and formulation, eps=1e-12; 201 outputs, steps end at each, the
#       default), then bench's extra crank rows: the half-decades 10^-3.5 ... 10^-9.5 of
#       'dopri5 gamma1=20' and 'defaults', and 1e-11, 1e-12 of those and 'trust_region eps=1e-12'
#       (crank 92 rows, ex51 48; all 140). Not here: bench's oracles and IDA peers (not regdae),
#       its other problems (order3, redundant, singular_mass, linear_*: not sweep problems), and
#       issue 19's 'defaults pass_check=no', 'defaults error_estimate=yes' and 'defaults
#       integrator=ida' rows (the cost of the pass check and of the estimate, IDA's reach).
#       The crank rows at index 3 have curvature_source=analytic (bench's g_xx(v, v); ex52 and a
#       row without the key use the solver's difference quotient). The crank rows and ex51's
#       eliminated rows give bench's error, steps and evaluations in every printed digit, but
#       (1) ex51's outputs are -1 + 2k/200 here, bench's -1 + 0.01k (23 of 201 an ulp apart):
#       with steps ending there the multiplier formulation takes another path (baumgarte
#       multiplier even fails or not); (2) a failed crank run's max_err_th stops at its last
#       good output (bench also counts the failed advance's). Timing: a row's seconds is one
#       run's solve with the multiplier at every output, bench's the median of repetitions.
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
bench)
    which=${2:-all}
    case $which in crank | ex51 | all) ;; *)
        echo "sweep_tables.sh bench: bad problem \"$which\" (crank, ex51, all)" >&2
        exit 2
        ;;
    esac
    awk -v which="$which" 'BEGIN {
        ida = "gamma=1e6 gamma1=2e3 gamma0=2e6 integrator=ida"
        rk = "method=trust_region eps=1e-14 gamma=1e6 gamma1=20 gamma0=200 integrator=dopri5"
        n = 0   # bench crank configurations: config[i] its name, opts[i] the row options
        config[++n] = "defaults"; opts[n] = ""
        config[++n] = "trust_region eps=1e-12"; opts[n] = "method=trust_region eps=1e-12 " ida
        config[++n] = "trust_region eps=1e-6"; opts[n] = "method=trust_region eps=1e-6 " ida
        config[++n] = "trust_region eps=1e-12 excluded=vy"; opts[n] = "method=trust_region eps=1e-12 excluded=vy " ida
        config[++n] = "baumgarte"; opts[n] = "method=baumgarte eps=1e-12 " ida
        config[++n] = "direct eps=1e-12"; opts[n] = "method=direct eps=1e-12 " ida
        config[++n] = "trust_region eps=1e-12 multiplier"; opts[n] = "method=trust_region eps=1e-12 formulation=multiplier " ida
        config[++n] = "trust_region eps=1e-14 dopri5 gamma1=20"; opts[n] = rk
        config[++n] = "trust_region gamma=1e6 eps=1e-12"; opts[n] = "method=trust_region eps=1e-12 " ida
        split("trust_region direct baumgarte", methods, " ")
        split("eliminated multiplier", forms, " ")
        crank = (which == "all" || which == "crank")
        ex51 = (which == "all" || which == "ex51")
        print "# drivers/bench problem=" which " through sweep: its regdae rows, one row each, in its order. For rtol = atol = 1e-3..1e-10:"
        if (crank) {
            line = "#   crank3"
            for (i = 1; i < n; i++) line = line " \"" config[i] "\"" (i < n - 1 ? "," : ";")
            print line " crank2 \"" config[n] "\""
        }
        if (ex51) print "#   ex51 \"METHOD FORMULATION eps=1e-12\", METHOD trust_region, direct, baumgarte, FORMULATION eliminated, multiplier"
        if (crank) print "# then crank3 \"" config[8] "\" and \"defaults\" at 10^-3.5..10^-9.5; these and \"" config[2] "\" at 1e-11, 1e-12."
        print "# Not here: the oracles (dopri5, CVODE, IDA on the reduced ODE) and the IDA peers (not regdae), order3, " \
            "redundant, singular_mass, linear_* (not sweep problems)."
        print "# Not bench\047s numbers everywhere (see the header of drivers/report/sweep_tables.sh):" \
            (ex51 ? " the ex51 outputs -1 + 2k/200 are an ulp from bench\047s -1 + 0.01k at 23 times (the multiplier rows differ);" : "") \
            " seconds is one run\047s solve, not a median of repetitions with setup."
        for (k = 3; k <= 10; k++) {
            tol = "rtol=1e-" k " atol=1e-" k
            if (crank) for (i = 1; i <= n; i++)
                print (i == n ? "crank2" : "crank3 curvature_source=analytic"), opts[i], tol, "stop_at_output=no"
            if (ex51) for (m = 1; m <= 3; m++) for (f = 1; f <= 2; f++)
                print "ex51 method=" methods[m], "formulation=" forms[f], "eps=1e-12", tol
        }
        if (!crank) exit
        for (k = 7; k <= 19; k += 2) {
            tol = sprintf("rtol=%.17g atol=%.17g", 10 ^ (-k / 2), 10 ^ (-k / 2))
            print "crank3 curvature_source=analytic", rk, tol, "stop_at_output=no"
            print "crank3 curvature_source=analytic", tol, "stop_at_output=no"
        }
        for (k = 11; k <= 12; k++) {
            tol = "rtol=1e-" k " atol=1e-" k
            print "crank3 curvature_source=analytic", rk, tol, "stop_at_output=no"
            print "crank3 curvature_source=analytic", opts[2], tol, "stop_at_output=no"
            print "crank3 curvature_source=analytic", tol, "stop_at_output=no"
        } }' | sed 's/  */ /g'
    ;;
*)
    echo "usage: sweep_tables.sh crank_map [N_TH] [N_W] | stability [ex51|crank2|crank3] | bench [crank|ex51|all]" >&2
    exit 2
    ;;
esac
