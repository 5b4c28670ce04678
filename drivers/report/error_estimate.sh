#!/bin/sh
# The error estimate (error_estimate=yes) against the true error on the slider crank: ex52 from
# the paper's start and from 11 starts drawn here (awk's generator, seed 19: th1 uniform in
# (0, pi), w1 = 0 or log-uniform in [1e-3, 10] rad/s; not the trust grids' starts), at rtol = atol
# = 1e-4, 1e-6, 1e-8, 100 outputs on [0, 10]; the true error against ex52's reference (the reduced
# ODE by CVODE at 1e-13). Per row: the counts of ex52's summary (est_bounds: est >= true/10;
# est_within10: true/10 <= est <= 10 true), and the solve's seconds and steps with the estimate
# and without it (the same run with error_estimate=no).
#
# Usage: error_estimate.sh BIN_DIR > table.txt     (about 30 s)
set -eu
bin=${1:?usage: error_estimate.sh BIN_DIR}
field() { tr ' ' '\n' | awk -F= -v k="$1" '$1 == k { print $2 }'; }
echo "# regdae error estimate on the slider crank: ex52 error_estimate=yes against the reference"
echo "# th1 w1 rtol status max_err_th outputs bounds within10 ratio_min ratio_max seconds_est seconds_plain steps companion_steps"
starts=$(awk 'BEGIN { srand(19); pi = atan2(0, -1); printf "%.17g 0\n", pi / 2
    for (i = 1; i <= 11; i++) { th = pi * (0.02 + 0.96 * rand()); u = rand()
        w = (i % 4 == 0) ? 0 : exp(log(1e-3) + u * (log(10) - log(1e-3))); printf "%.17g %.6g\n", th, w } }')
echo "$starts" | while read -r th w; do
    for r in 1e-4 1e-6 1e-8; do
        s=$("$bin/ex52" th1="$th" w1="$w" rtol=$r atol=$r nout=100 error_estimate=yes 2>/dev/null | grep '^summary' || true)
        p=$("$bin/ex52" th1="$th" w1="$w" rtol=$r atol=$r nout=100 2>/dev/null | grep '^summary' || true)
        [ -n "$s" ] || { echo "$th $w $r no_summary"; continue; }
        printf '%.6f %s %s %s %s %s %s %s %s %s %s %s %s %s\n' "$th" "$w" "$r" \
            "$(echo "$s" | field status)" "$(echo "$s" | field max_err_th)" "$(echo "$s" | field est_outputs)" \
            "$(echo "$s" | field est_bounds)" "$(echo "$s" | field est_within10)" "$(echo "$s" | field est_ratio_min)" \
            "$(echo "$s" | field est_ratio_max)" "$(echo "$s" | field seconds)" "$(echo "$p" | field seconds)" \
            "$(echo "$s" | field steps)" "$(echo "$s" | field companion_steps)"
    done
done | tee /dev/stderr | awk '{ print } $6 ~ /^[0-9]+$/ { n += $6; b += $7; w += $8; se += $11; sp += $12
        if ($8 < $6) miss++ }
    END { printf "summary runs=%d outputs=%d bounds=%d within10=%d runs_not_all_within=%d cost_ratio=%.2f\n", NR, n, b, w, miss, se / sp }' 2>/dev/null
