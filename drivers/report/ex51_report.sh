#!/bin/sh
# Example 5.1 section of the reproduction report: runs the ex51 driver for the
# paper's figures 5.1-5.4, the eps sweep, and writes Markdown to stdout and the
# figures (gnuplot PNG, if gnuplot is installed) and raw outputs into OUTDIR.
# Usage: ex51_report.sh path/to/ex51 OUTDIR
set -eu
ex51=${1:?usage: ex51_report.sh path/to/ex51 OUTDIR}
out=${2:?usage: ex51_report.sh path/to/ex51 OUTDIR}
mkdir -p "$out/ex51"

# run NAME ARGS...: keep the whole output; never stop the report on a failed run.
run() {
    name=$1; shift
    "$ex51" "$@" >"$out/ex51/$name.out" 2>"$out/ex51/$name.err" || true
}
field() { tail -n 1 "$out/ex51/$1.out" | tr ' ' '\n' | sed -n "s/^$2=//p"; }
row() {   # row NAME LABEL: one Markdown table row from a run's summary line
    printf '| %s | %s | %s | %s | %s | %s | %s | %s | %s | %s |\n' "$2" "$(field "$1" status)" \
        "$(field "$1" t_end)" "$(field "$1" max_err_x)" "$(field "$1" steps)" "$(field "$1" res_evals)" \
        "$(field "$1" jac_evals)" "$(field "$1" err_test_fails)" "$(field "$1" conv_fails)" "$(field "$1" seconds)"
}
header='| run | status | t_end | max_err_x | steps | res_evals | jac_evals | err_test_fails | conv_fails | seconds |
|---|---|---|---|---|---|---|---|---|---|'

cat <<'TXT'
## Example 5.1: x' = 2 + t y, 0 = t x - t(t+1), t in [-1, 1]

Exact solution x = t + 1, y = -1/t (orientation `paper`, B = -t) or y = 1/t (orientation `psd`,
B = t = G^T). The constraint Jacobian G = t vanishes at t = 0. rtol = atol = 1e-5, 201 output
times including t = 0, steps ending at every output time (`stop_at_output=yes`), unless stated.

### The paper's runs (Figures 5.1-5.4)

TXT
echo "$header"
for form in multiplier eliminated; do
    run fig51_$form method=baumgarte gamma=1e3 formulation=$form
    run fig52_$form method=direct gamma=1e3 eps=1e-6 formulation=$form
    run fig53_$form method=trust_region gamma=1e3 eps=1e-6 formulation=$form
    run fig54_$form method=trust_region gamma=1e3 eps=1e-9 formulation=$form
    row fig51_$form "Fig. 5.1 baumgarte gamma=1e3, $form"
    row fig52_$form "Fig. 5.2 direct eps=1e-6, $form"
    row fig53_$form "Fig. 5.3 trust_region eps=1e-6, $form"
    row fig54_$form "Fig. 5.4 trust_region eps=1e-9, $form"
done
run fig52_paper method=direct gamma=1e3 eps=1e-6 orientation=paper
row fig52_paper "direct eps=1e-6, orientation=paper (B = -t)"
echo
echo "Messages of the failed runs:"
echo
for f in "$out"/ex51/fig5*.out; do
    msg=$(grep -m1 '^# error:' "$f" | sed 's/^# error: //' || true)
    [ -n "$msg" ] && printf -- '- `%s`: %s\n' "$(basename "$f" .out)" "$msg"
done
echo

cat <<'TXT'
### Formulations and error-test exclusion (trust region, eps = 1e-6)

`multiplier`: IDA integrates (x, y), y left out of the error test by `exclusion`;
`eliminated` (the default): y is solved inside the residual and IDA integrates x alone.

TXT
echo "$header"
for x in suppress weights off; do
    run excl_$x method=trust_region eps=1e-6 formulation=multiplier exclusion=$x
    row excl_$x "multiplier, exclusion=$x"
done
run excl_elim method=trust_region eps=1e-6 formulation=eliminated
row excl_elim "eliminated"
echo

cat <<'TXT'
### Stepping over the singularity

Without `stop_at_output` IDA chooses its steps freely. With y out of the error test and x = t + 1
linear, it takes a few large steps over [-1, 1] and may never evaluate the residual near t = 0,
so the regularization error is never seen: the small errors below are an artifact.

TXT
echo "$header"
for m in trust_region direct; do
    run skip_$m method=$m eps=1e-6 stop_at_output=no
    row skip_$m "$m eps=1e-6, stop_at_output=no"
done
run skip_baumgarte_multiplier method=baumgarte formulation=multiplier stop_at_output=no
row skip_baumgarte_multiplier "baumgarte multiplier, stop_at_output=no"

echo

cat <<'TXT'
### max_err_x against eps (gamma = 1e3, orientation psd, lsq=auto)

`rate` is the local slope log(err_k / err_{k-1}) / log(eps_k / eps_{k-1}) of the eliminated
runs. `predicted` is the error at t = 0 of the regularized solution from its closed-form layer
analysis (doc/ex51.md): trust region 1.311 eps^(1/4), direct sqrt(eps) ln(2 / (gamma sqrt(eps)));
both assume a layer narrower than 1/gamma: the direct estimate is left out where
gamma sqrt(eps) >= 0.5, and the trust-region one overestimates while eps^(1/4) >= 1/gamma = 1e-3.

TXT
for tol in 1e-5 1e-10; do
    echo "rtol = atol = $tol:"
    echo
    echo '| eps | trust_region multiplier | trust_region eliminated | rate | predicted | direct multiplier | direct eliminated | rate | predicted |'
    echo '|---|---|---|---|---|---|---|---|---|'
    prev_tr=""; prev_d=""; prev_e=""
    for k in 4 5 6 7 8 9 10 11 12; do
        e="1e-$k"
        for m in trust_region direct; do
            for form in multiplier eliminated; do
                run sweep_${tol}_${m}_${form}_$k method=$m eps=$e formulation=$form rtol=$tol atol=$tol
            done
        done
        cell() {   # cell METHOD FORM: max_err_x, marked when the run failed
            v=$(field "sweep_${tol}_$1_$2_$k" max_err_x)
            [ "$(field "sweep_${tol}_$1_$2_$k" status)" = ok ] || v="$v (failed)"
            echo "$v"
        }
        tr_e=$(field "sweep_${tol}_trust_region_eliminated_$k" max_err_x)
        d_e=$(field "sweep_${tol}_direct_eliminated_$k" max_err_x)
        rates=$(awk -v a="$prev_tr" -v b="$tr_e" -v c="$prev_d" -v d="$d_e" -v e0="$prev_e" -v e1="$e" 'BEGIN {
            if (a == "") { print "- -"; exit }
            printf "%.2f %.2f", log(b / a) / log(e1 / e0), log(d / c) / log(e1 / e0) }')
        pred=$(awk -v e="$e" -v g=1e3 'BEGIN { s = sqrt(e)
            if (g * s < 0.5) printf "%.2e %.2e", 1.311 * e^0.25, s * log(2 / (g * s))
            else printf "%.2e -", 1.311 * e^0.25 }')
        printf '| %s | %s | %s | %s | %s | %s | %s | %s | %s |\n' "$e" "$(cell trust_region multiplier)" \
            "$(cell trust_region eliminated)" "${rates% *}" "${pred% *}" "$(cell direct multiplier)" \
            "$(cell direct eliminated)" "${rates#* }" "${pred#* }"
        prev_tr=$tr_e; prev_d=$d_e; prev_e=$e
    done
    echo
done

# Figures: x - x_exact and y against t for the paper's four runs (multiplier formulation).
if command -v gnuplot >/dev/null 2>&1; then
    for fig in fig51 fig52 fig53 fig54; do
        f="$out/ex51/${fig}_multiplier.out"
        title=$(sed -n 's/^# method=\([a-z_]*\).*/\1/p' "$f" | head -n 1)
        params=$(sed -n 's/^# \(gamma=[^ ]*\) \(eps=[^ ]*\).*/\1 \2/p' "$f" | head -n 1)
        gnuplot <<GP
set terminal png noenhanced size 900,360
set output '$out/ex51/$fig.png'
set multiplot layout 1,2 title "Example 5.1 as in the paper's Fig. 5.${fig#fig5}: $title, $params"
set xlabel 't'
set ylabel 'x - x_exact'
set grid
plot '$f' using 1:(\$2-\$4) with linespoints pt 7 ps 0.4 notitle
set ylabel 'y'
set yrange [-60:60]
plot '$f' using 1:3 with linespoints pt 7 ps 0.4 title 'regularized', '' using 1:5 with lines title 'exact'
unset multiplot
GP
    done
    echo "### Figures"
    echo
    for fig in fig51 fig52 fig53 fig54; do
        echo "![Example 5.1, as Fig. 5.${fig#fig5} of the paper](ex51/$fig.png)"
        echo
    done
fi
