#!/bin/sh
# Fast spins of the slider crank: regdae's error against the reference method's (Dormand-Prince on
# the reduced ODE at the same R), both in the trust grids' weighted norm against CVODE at 1e-13
# (`trust family=crank th1=A w1=W rtol=R`). Starts: 6 th1 uniform in (0.05, pi - 0.05) (awk's
# srand(8181)) times 8 speeds w1 = 2 * 15^(k/7), k = 0 ... 7 (2 ... 30 rad/s, log-spaced), times
# R = 1e-5 ... 1e-10: 288 cells. Rows 'th1 w1 R status class err err_ref steps', then the
# classes and, per R and over all cells, the distribution of the ratio err/err_ref (geometric
# mean, median, 90th percentile, largest).
#
# Usage: spin_grid.sh BIN_DIR [option.KEY=VALUE ...]    (about 30 s)
set -eu
bin=${1:?usage: spin_grid.sh BIN_DIR [option.KEY=VALUE ...]}
shift
rows=$(mktemp)
trap 'rm -f "$rows"' EXIT
awk 'BEGIN { srand(8181); pi = atan2(0, -1)
             for (i = 0; i < 6; i++) { th = 0.05 + (pi - 0.1) * rand()
                 for (k = 0; k < 8; k++) printf "%.6f %.6f\n", th, 2 * 15^(k / 7) } }' |
    while read -r th w; do
        for r in 1e-5 1e-6 1e-7 1e-8 1e-9 1e-10; do
            "$bin/trust" family=crank th1="$th" w1="$w" rtol="$r" "$@" |
                awk -v th="$th" -v w="$w" -v r="$r" '$2 == "crank" { print th, w, r, $7, $8, $9, $10, $13 }'
        done
    done > "$rows"
cat "$rows"
awk '{ print $0, $6 / $7 }' "$rows" | sort -k3,3g -k9,9g | awk '
    function report(label, n, lsum,    k) {
        printf "%-6s n=%d gmean=%.2f median=%.2f p90=%.2f max=%.2f\n", label, n, exp(lsum / n),
            v[int(n / 2) + 1], v[int(0.9 * n) + 1], v[n]
    }
    { cls[$5]++; ratio = $9; all[++na] = ratio; lall += log(ratio) }
    $3 != r && n > 0 { report(r, n, ls); n = 0; ls = 0 }
    { r = $3; v[++n] = ratio; ls += log(ratio) }
    END {
        report(r, n, ls)
        for (c in cls) printf "class %s %d\n", c, cls[c]
        # all cells: sort the ratios (insertion sort, 288 of them)
        for (i = 2; i <= na; i++) { x = all[i]; for (j = i - 1; j >= 1 && all[j] > x; j--) all[j + 1] = all[j]; all[j + 1] = x }
        for (i = 1; i <= na; i++) v[i] = all[i]
        report("all", na, lall)
    }'
