#!/bin/sh
# Tolerance proportionality on the chain (issue 19, "Targets"): the chains of N = 2 ... 64 links,
# plain and with sliders, t in [0, 1], at rtol = atol = 1e-3 ... 1e-10, each against its reduced
# ODE (drivers/trust, `reference=reduced`: chain_plain_recursive / chain_slider_recursive by CVODE
# at 1e-13). Per chain the least-squares slope of log10(err R) against log10(R), err the trust
# driver's weighted error max |q_i - qref_i| / (R |qref_i| + R) over the outputs: at N = 8 and 64,
# plain and slider, >= 0.8, and every cell ok or warned. Measured (commit of this test): slopes
# 1.09 ... 1.16 at N = 8 and 64; over N = 2 ... 64 the smallest 0.83 (slider N = 4, warned at 1e-9
# and 1e-10: 20 and 189 error weights).
# Usage: check_proportionality.sh BIN_DIR
set -u
bindir=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
. "$(dirname "$0")/check_lib.sh"
"$bindir/trust" family=chain rtols=1e-3,1e-4,1e-5,1e-6,1e-7,1e-8,1e-9,1e-10 max_links=64 reference=reduced \
    tight_check=no >"$tmp/grid.out" 2>&1
grep '^summary' "$tmp/grid.out"
awk '$1 ~ /^[0-9]+$/ { k = $3 " " $4 + 0; x = log($6) / log(10); y = log($9 * $6) / log(10)
        n[k]++; sx[k] += x; sy[k] += y; sxx[k] += x * x; sxy[k] += x * y
        if ($8 != "ok" && $8 != "warned") bad[k] = bad[k] " " $1 ":" $8 }
    END { for (k in n) printf "%s %d %.3f %s\n", k, n[k], (n[k] * sxy[k] - sx[k] * sy[k]) / (n[k] * sxx[k] - sx[k] ^ 2),
                               (k in bad) ? bad[k] : "-" }' "$tmp/grid.out" | sort -k1,1 -k2n >"$tmp/slopes"
cat "$tmp/slopes"
for k in "plain 8" "plain 64" "slider 8" "slider 64"; do
    set -- $k
    line=$(awk -v v=$1 -v n=$2 '$1 == v && $2 == n' "$tmp/slopes")
    set -- $line
    check "chain $1 N = $2: $3 cells, slope ${4:-none} >= 0.8, cells not ok or warned: ${5:-none}" \
        "$(if [ "${3:-0}" -eq 8 ] && le 0.8 "${4:-0}" && [ "${5:-x}" = - ]; then echo 0; else echo 1; fi)"
done
finish
