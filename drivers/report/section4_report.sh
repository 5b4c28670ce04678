#!/bin/sh
# Section-4 part of the report: order 3, redundant constraints, singular mass matrix.
# Markdown on stdout, raw outputs in OUTDIR/section4/.
# Usage: section4_report.sh BINDIR OUTDIR
set -eu
bin=${1:?usage: section4_report.sh BINDIR OUTDIR}
out=${2:?usage: section4_report.sh BINDIR OUTDIR}
mkdir -p "$out/section4"
run() { name=$1; drv=$2; shift 2; "$bin/$drv" "$@" >"$out/section4/$name.out" 2>"$out/section4/$name.err" || true; }
field() { tail -n 1 "$out/section4/$1.out" | tr ' ' '\n' | sed -n "s/^$2=//p"; }
cell() { v=$(field "$1" "$2"); [ "$(field "$1" status)" = ok ] || v="$v (failed at t = $(field "$1" t_end))"; echo "$v"; }

cat <<'TXT'
## Order 3 (index 4): x''' = (1 - cos t) - t y, 0 = t (x - 1 - sin t), t in [-1, 1]

Trust region with the Taylor weights 3!/(k! h^(3-k)) of (4.16); exact x = 1 + sin t, y = 1/t,
singular at t = 0. `max_err` (max |x - x*| over 201 outputs) against eps and rtol = atol
(taylor_h = 1e-2), then against taylor_h (eps = 1e-9, rtol = atol = 1e-8):

| eps \ rtol = atol | 1e-5 | 1e-8 | 1e-10 |
|---|---|---|---|
TXT
for e in 1e-6 1e-9 1e-12; do
    for tol in 1e-5 1e-8 1e-10; do run o3_${e}_$tol order3 eps=$e rtol=$tol atol=$tol; done
    printf '| %s | %s | %s | %s |\n' "$e" "$(cell o3_${e}_1e-5 max_err)" "$(cell o3_${e}_1e-8 max_err)" \
        "$(cell o3_${e}_1e-10 max_err)"
done
echo
echo '| taylor_h | max_err | steps |'
echo '|---|---|---|'
for h in 1e-1 3e-2 1e-2 3e-3; do
    run o3h_$h order3 eps=1e-9 rtol=1e-8 atol=1e-8 taylor_h=$h
    printf '| %s | %s | %s |\n' "$h" "$(cell o3h_$h max_err)" "$(field o3h_$h steps)"
done
echo

cat <<'TXT'
## Redundant constraints kept: the slider crank with its constraint given twice

Trust region, index 3, t in [0, 10]; `max_err` against the reduced ODE, `max_diff_single` against
the same run of the single-constraint model.

| formulation | eps | lsq | status | t_end | max_err | max_diff_single | steps | jac_evals | conv_fails |
|---|---|---|---|---|---|---|---|---|---|
TXT
for f in eliminated multiplier; do
    for e in 1e-6 1e-12; do
        for l in normal stacked; do
            run red_${f}_${e}_$l redundant formulation=$f eps=$e lsq=$l
            n=red_${f}_${e}_$l
            printf '| %s | %s | %s | %s | %s | %s | %s | %s | %s | %s |\n' "$f" "$e" "$l" "$(field $n status)" \
                "$(field $n t_end)" "$(field $n max_err)" "$(field $n max_diff_single)" "$(field $n steps)" \
                "$(field $n jac_evals)" "$(field $n conv_fails)"
        done
    done
done
echo

cat <<'TXT'
## Singular mass matrix: a pendulum on a massless carrier, through (4.11)

M = diag(1, 1, 0); `max_err` against the hand-eliminated model (the pendulum), t in [0, 5].

| run | status | max_err | max_abs_g | steps |
|---|---|---|---|---|
TXT
for a in "mass_damping=1e-8" "mass_damping=1e-4" "mass_damping=1e-12" "mass_damping=1e-8 rtol=1e-8 atol=1e-8" \
    "mass_damping=1e-8 rtol=1e-10 atol=1e-10 eps=1e-12" "mass_damping=0" "carrier=follower"; do
    n=sm_$(echo "$a" | tr ' =' '__')
    # shellcheck disable=SC2086
    run "$n" singular_mass $a
    printf '| %s | %s | %s | %s | %s |\n' "$a" "$(field "$n" status)" "$(field "$n" max_err)" "$(field "$n" max_abs_g)" \
        "$(field "$n" steps)"
done
echo
