#!/bin/sh
# Example 5.2 (slider crank) and pendulum sections of the report: Markdown on
# stdout, raw outputs in OUTDIR/ex52/.
# Usage: ex52_report.sh BINDIR OUTDIR
set -eu
bin=${1:?usage: ex52_report.sh BINDIR OUTDIR}
out=${2:?usage: ex52_report.sh BINDIR OUTDIR}
mkdir -p "$out/ex52"
run() {   # run NAME DRIVER ARGS...
    name=$1; drv=$2; shift 2
    "$bin/$drv" "$@" >"$out/ex52/$name.out" 2>"$out/ex52/$name.err" || true
}
field() { tail -n 1 "$out/ex52/$1.out" | tr ' ' '\n' | sed -n "s/^$2=//p"; }
row52() {   # row52 NAME LABEL
    printf '| %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s |\n' "$2" "$(field "$1" status)" \
        "$(field "$1" max_err_th)" "$(field "$1" max_abs_g3)" "$(field "$1" max_energy_err)" \
        "$(field "$1" max_branch_dev)" "$(field "$1" singular_passes)" "$(field "$1" steps)" \
        "$(field "$1" res_evals)" "$(field "$1" jac_evals)" "$(field "$1" seconds)"
}
h52='| run | status | max_err_th | max_abs_g3 | max_energy_err | max_branch_dev | singular_passes | steps | res_evals | jac_evals | seconds |
|---|---|---|---|---|---|---|---|---|---|---|'

cat <<'TXT'
## Example 5.2: the slider crank

From th1 = th2 = pi/2 at rest, t in [0, 10], 1001 outputs, steps ending at each; six passes
through the singular configuration (0, pi). Errors against the reduced one-degree-of-freedom ODE
integrated by CVODE at 1e-13. Trust region, index 3, gamma0 = 2e6, gamma1 = 2e3 unless stated.

### What leaves the error test (index 3, eps = 1e-6, rtol = atol = 1e-5)

TXT
echo "$h52"
for e in y vy; do
    for c in no yes; do
        run excl_${e}_$c ex52 excluded=$e curvature=$c
        row52 excl_${e}_$c "excluded=$e curvature=$c"
    done
done
echo

cat <<'TXT'
### The regularization error is controllable (index 3, excluded=y)

TXT
echo "$h52"
for e in 1e-6 1e-9 1e-12; do
    for tol in 1e-5 1e-8 1e-10; do
        run grid_${e}_$tol ex52 eps=$e rtol=$tol atol=$tol
        row52 grid_${e}_$tol "eps=$e rtol=atol=$tol"
    done
done
echo

cat <<'TXT'
### Index 2 (velocity constraint 5.4)

TXT
echo "$h52"
for g in 1e3 1e6; do
    for m in trust_region direct baumgarte; do
        run i2_${m}_$g ex52 index=2 method=$m gamma=$g eps=1e-6 rtol=1e-6 atol=1e-6
        row52 i2_${m}_$g "index=2 $m gamma=$g rtol=1e-6"
    done
done
echo
cat <<'TXT'
### Index 3 under other step strategies (the paper's form: excluded=vy, curvature=no, eps = 1e-6)

TXT
echo "$h52"
for m in baumgarte direct; do
    for v in "stop_at_output=no" "stop_at_output=no nout=100" "stop_at_output=no nout=10" "formulation=multiplier" \
        "formulation=multiplier stop_at_output=no"; do
        name=strat_${m}_$(echo "$v" | tr ' =' '__')
        # shellcheck disable=SC2086
        run "$name" ex52 method=$m index=3 excluded=vy curvature=no eps=1e-6 $v
        row52 "$name" "$m $v"
    done
done
echo
echo "Singular intervals of the default run (\`ex52\`):"
echo
run default ex52
grep '^#   t in\|^# singular passes' "$out/ex52/default.out" | sed 's/^# */    /'
echo

cat <<'TXT'
## The pendulum: the curvature term

Cartesian pendulum from phi = pi/2 at rest, t in [0, 10], against the angle ODE by CVODE.
`max_err_pos` for the curvature-corrected form (`curvature=yes`, eps = 1e-12) and the paper's form
(`curvature=no`) at two gamma0 (gamma1 = sqrt(2 gamma0), i.e. 2/h with gamma0 = 2/h^2).

| rtol = atol | curvature=yes | curvature=no, gamma0 = 2e6 | curvature=no, gamma0 = 2e7 |
|---|---|---|---|
TXT
for tol in 1e-6 1e-7 1e-8 1e-9 1e-10 1e-11 1e-12; do
    run pend_yes_$tol pendulum curvature=yes eps=1e-12 rtol=$tol atol=$tol
    run pend_no6_$tol pendulum curvature=no rtol=$tol atol=$tol
    run pend_no7_$tol pendulum curvature=no gamma0=2e7 gamma1=6325 rtol=$tol atol=$tol
    cell() { v=$(field "$1" max_err_pos); [ "$(field "$1" status)" = ok ] || v="$v (failed)"; echo "$v"; }
    printf '| %s | %s | %s | %s |\n' "$tol" "$(cell pend_yes_$tol)" "$(cell pend_no6_$tol)" "$(cell pend_no7_$tol)"
done
echo
