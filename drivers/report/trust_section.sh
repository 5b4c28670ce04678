#!/bin/sh
# Issue 19's section of doc/performance.md ("Trust grids"), in markdown on stdout, from the raw
# outputs in RAW (tools/benchmark.sh's build/benchmark): RAW/trust/ (drivers/report/trust_grids.sh's
# family tables, summaries.txt, baseline.txt and PNGs), RAW/error_estimate.txt
# (drivers/report/error_estimate.sh), RAW/cost_of_trust.txt (drivers/report/cost_of_trust.sh) and
# RAW/bench.txt (drivers/bench). The grids' heat maps are copied to FIGS/trust_*.png. The
# baseline (the library before issue 19) is drivers/report/trust_baseline.txt and
# drivers/report/cost_baseline.txt, measured at 29c5eaf with the same drivers.
#
# Usage: trust_section.sh RAW FIGS > section.md
set -eu
raw=${1:?usage: trust_section.sh RAW FIGS}
figs=${2:?usage: trust_section.sh RAW FIGS}
here=$(dirname "$0")
grids=$raw/trust
mkdir -p "$figs"
for f in crank_err crank_class chain_err chain_class chain_long_err chain_long_class fourbar_err fourbar_class \
    linear_err linear_class; do
    [ -f "$grids/$f.png" ] && cp "$grids/$f.png" "$figs/trust_$f.png"
done
verdict() { if [ "$1" = 1 ]; then echo met; else echo '**not met**'; fi; }
# field FILE FAMILY KEY: a count of the family's summary line
field() { awk -v fam="$2" -v k="$3" '$1 == "summary" && $2 == "family=" fam {
    for (i = 3; i <= NF; i++) { split($i, kv, "="); if (kv[1] == k) v = kv[2] } } END { print v + 0 }' "$1"; }
fams="crank chain chain_long fourbar linear"

# --- the classes per family, now and at the baseline
silent_all=0
fa_over=0
rows=""
for fam in $fams; do
    n=$(field "$grids/summaries.txt" "$fam" cells)
    [ "$n" -gt 0 ] || continue
    line="| $fam | $n"
    for k in ok warned silent false_alarm failed undecided no_reference; do
        line="$line | $(field "$grids/summaries.txt" "$fam" $k) ($(field "$here/trust_baseline.txt" "$fam" $k))"
    done
    s=$(field "$grids/summaries.txt" "$fam" silent)
    fa=$(field "$grids/summaries.txt" "$fam" false_alarm)
    pct=$(awk -v a="$fa" -v n="$n" 'BEGIN { printf "%.1f", 100 * a / n }')
    silent_all=$((silent_all + s))
    fa_over=$(awk -v p="$pct" -v o="$fa_over" 'BEGIN { print (p + 0 > 1) ? o + 1 : o }')
    rows="$rows$line | $pct% |
"
done
fa_list=$(for fam in $fams; do
    n=$(field "$grids/summaries.txt" "$fam" cells)
    [ "$n" -gt 0 ] || continue
    awk -v f="$fam" -v a="$(field "$grids/summaries.txt" "$fam" false_alarm)" -v n="$n" \
        'BEGIN { printf "%s %s of %s (%.1f%%); ", f, a, n, 100 * a / n }'
done)
silent_list=$(for fam in $fams; do
    n=$(field "$grids/summaries.txt" "$fam" cells)
    [ "$n" -gt 0 ] || continue
    printf '%s %s, ' "$fam" "$(field "$grids/summaries.txt" "$fam" silent)"
done)

# --- tolerance proportionality: the crank's defaults rows of the bench (1e-3 ... 1e-10, least
# squares of log err on log rtol); the chain's plain cells per N (err in error weights times R:
# the absolute error's slope is 1 + that of the weights)
crank_slope=$(awk -F'"' '$2 == "defaults" && $1 ~ /^crank3 / { split($3, a, " "); r = a[1] + 0; e = a[2] + 0
        k = -log(r) / log(10); if (e > 0 && a[7] != "failed" && a[7] != "off_branch" && k >= 2.99 && k <= 10.01 && k == int(k + 0.5)) {
        x = log(r); y = log(e); n++; sx += x; sy += y; sxx += x * x; sxy += x * y } }
    END { if (n > 2) printf "%.2f", (n * sxy - sx * sy) / (n * sxx - sx * sx); else print "?" }' "$raw/bench.txt")
chain_slopes=$(awk '$1 ~ /^[0-9]+$/ && $3 == "plain" && $9 > 0 && ($8 == "ok" || $8 == "warned" || $8 == "silent") {
        n = $4 + 0; x = log($6); y = log($9 * $6); c[n]++; sx[n] += x; sy[n] += y; sxx[n] += x * x; sxy[n] += x * y }
    END { for (n in c) if (c[n] > 2) printf "%d %.2f\n", n, (c[n] * sxy[n] - sx[n] * sy[n]) / (c[n] * sxx[n] - sx[n] * sx[n]) }' \
    "$grids/chain.txt" | sort -n)
chain_min=$(echo "$chain_slopes" | awk 'NR == 1 || $2 < m { m = $2 } END { print (NR ? m : "?") }')
chain_text=$(echo "$chain_slopes" | awk '{ printf "%sN = %d: %s", (NR > 1 ? ", " : ""), $1, $2 }')
v_prop=$(awk -v a="$crank_slope" -v b="$chain_min" 'BEGIN { print (a != "?" && b != "?" && a + 0 >= 0.8 && b + 0 >= 0.8) ? 1 : 0 }')
# integrator=ida on the crank: the best error of the bench's 'defaults integrator=ida' rows
ida_best=$(awk -F'"' '$2 == "defaults integrator=ida" && $1 ~ /^crank3 / { split($3, a, " ")
        if (a[7] != "failed" && a[7] != "off_branch" && (b == "" || a[2] + 0 < b + 0)) { b = a[2]; r = a[1]; s = a[7] } }
    END { if (b == "") print "? - -"; else print b, r, s }' "$raw/bench.txt")
set -- $ida_best
ida_err=$1 ida_rtol=$2 ida_status=$3
v_ida=$(awk -v e="$ida_err" 'BEGIN { print (e != "?" && e + 0 <= 1e-9) ? 1 : 0 }')

# --- the cost of trust: instructions of the defaults against the baseline's at the same rtol,
# and at matched accuracy (the baseline's instructions at the defaults' error, log-log
# interpolated between its rtols)
cost_rows=$(awk 'FNR == 1 { f++ } /^#/ { next }
    f == 1 && $1 == "baseline" { br[++nb] = $2; be[nb] = $3; bi[nb] = $5 }
    f == 2 && $1 == "defaults" { dr[++nd] = $2; de[nd] = $3; di[nd] = $5 }
    f == 2 && $1 == "pass_check=no" { pn[$2] = $5 }
    f == 2 && $1 == "error_estimate=yes" { ee[$2] = $5 }
    END { for (j = 1; j <= nd; j++) { same = "-"; matched = "-"
            for (k = 1; k <= nb; k++) if (br[k] == dr[j]) same = di[j] / bi[k]
            for (k = 1; k < nb; k++) { e1 = be[k]; e2 = be[k + 1]
                if ((de[j] <= e1 && de[j] >= e2) || (de[j] >= e1 && de[j] <= e2)) {
                    w = (e1 == e2) ? 0 : log(de[j] / e1) / log(e2 / e1)
                    matched = di[j] / exp(log(bi[k]) + w * log(bi[k + 1] / bi[k])) } }
            printf "%s %s %s %s %s %s %s %s\n", dr[j], de[j], di[j], same, matched, pn[dr[j]], ee[dr[j]], (di[j] > 0) ? ee[dr[j]] / di[j] : 0 } }' \
    "$here/cost_baseline.txt" "$raw/cost_of_trust.txt")
cost_max=$(echo "$cost_rows" | awk '{ r = ($5 != "-") ? $5 : $4; if (r != "-" && r + 0 > m) m = r } END { printf "%.2f", m }')
cost_range=$(echo "$cost_rows" | awk '{ r = ($5 != "-") ? $5 : $4; printf "%s%s: %.2f", (NR > 1 ? ", " : ""), $1, r }')
v_cost=$(awk -v m="$cost_max" 'BEGIN { print (m + 0 <= 1.2) ? 1 : 0 }')
est_summary=$(grep '^summary' "$raw/error_estimate.txt" || echo "summary runs=0")
est_get() { echo "$est_summary" | tr ' ' '\n' | awk -F= -v k="$1" '$1 == k { print $2 }'; }
est_ratio=$(echo "$cost_rows" | awk '{ if ($8 > m) m = $8; if (n == 0 || $8 < l) l = $8; n++ } END { printf "%.1f-%.1f", l, m }')

v_silent=$([ "$silent_all" = 0 ] && echo 1 || echo 0)
v_fa=$([ "$fa_over" = 0 ] && echo 1 || echo 0)
run_line=$(head -n 1 "$grids/summaries.txt" | sed 's/^# //')

# --- the long chains' reference methods, from chain_long.txt (rows, their '#   ' notes, the
# '# [part 1] reference' lines): cell 1 (plain N = 2), 49 (slider N = 2) and 67 (slider N = 16)
# at R = 1e-3; the slider cells of N > 2 whose peer failed; the sliders' units from the reduced
# ODE against regdae's tight run; the sliders without a reference.
long=$grids/chain_long.txt
long_cell() { # long_cell CELL: "err err_ref bound class dE dE_unit dE_ref", "? ..." if absent
    awk -v c="$1" '$1 == c && $2 == "chain_long" { found = 1; e = $9; r = $10; b = $11; k = $8; d = $15; u = $16; next }
        found && /^#   reference method: dE=/ { split($4, a, "="); dr = a[2]; found = 0 }
        /^ *[0-9]+ / { found = 0 }
        END { if (e == "") print "? ? ? ? ? ? ?"; else print e, r, b, k, d, u, (dr == "" ? "?" : dr) }' "$long" 2>/dev/null ||
        echo "? ? ? ? ? ? ?"
}
sci() { awk -v x="$1" 'BEGIN { if (x == "?") print "?"; else printf "%.3g", x }'; }
set -- $(long_cell 1); c1_err=$(sci "$1") c1_ref=$(sci "$2")
set -- $(long_cell 49); c49_err=$(sci "$1") c49_ref=$(sci "$2")
set -- $(long_cell 67); c67_err=$(sci "$1") c67_ref=$(sci "$2") c67_bound=$(sci "$3") c67_class=$4
c67_de=$(sci "$5") c67_unit=$(sci "$6") c67_deref=$(sci "$7")
# slider cells of N > 2 judged against the peer, and those where it failed (N/R at t): before
# the first output (t < 0.1: at the start, err_ref = 0) or later
slider_peer=$(awk '$1 ~ /^[0-9]+$/ && $3 == "slider" && $4 + 0 > 2 && NF >= 19 && $19 != "none" { n++ } END { print n + 0 }' "$long" 2>/dev/null || echo 0)
peer_failures() { # peer_failures early|late
    awk -v which="$1" '$1 ~ /^[0-9]+$/ { cur = ""
            if ($3 == "slider" && $4 + 0 > 2 && NF >= 19 && $19 != "0" && $19 != "none") cur = sprintf("N = %d at R = %s", $4, $6)
            next }
        cur != "" && /^#   reference method failed: .*at t = / { t = $0; sub(/.*at t = /, "", t); sub(/ .*/, "", t)
            if ((which == "early") == (t + 0 < 0.1)) printf "%s%s (t = %.2g)", (n++ ? ", " : ""), cur, t; cur = "" }' "$long" 2>/dev/null || true
}
fail_early=$(peer_failures early)
fail_late=$(peer_failures late)
count_list() { echo "$1" | awk -F'), ' 'NF { print NF; next } { print 0 }'; }
n_early=$(count_list "$fail_early")
n_late=$(count_list "$fail_late")
# folds passed at the tight runs' outputs, per N, and the slider sizes without a reference (why)
long_folds=$(awk '/^# \[part 1\] reference chain_long slider N=/ && /folds passed/ { n = $7; sub(/N=/, "", n); sub(/:/, "", n)
        f = $NF; sub(/.*=/, "", f); printf "%sN = %s: %s", (k++ ? ", " : ""), n, f }' "$long" 2>/dev/null || true)
# CVODE's cpu on the reduced ODE of the plain chain of 256 links on [0, 10]
long_cpu=$(awk '/^# \[part 1\] reference chain_long plain N=256:/ && /reduced ODE \(CVODE\)/ { c = $0; sub(/.*status=0 \(/, "", c)
        sub(/ s cpu.*/, "", c); printf "%.2g", c }' "$long" 2>/dev/null || true)
# the slider cells of N >= 128 above their bounds: "N = n at R = r (err e, bound b, class)"
long_over=$(awk '$1 ~ /^[0-9]+$/ && $2 == "chain_long" && $3 == "slider" && $4 + 0 >= 128 && $9 + 0 > $11 + 0 {
        printf "%sN = %d at R = %s (err %.2g, bound %.2g, %s)", (k++ ? ", " : ""), $4, $6, $9, $11, $8 }' "$long" 2>/dev/null || true)
small_warned=$(awk '$1 ~ /^[0-9]+$/ && $3 == "slider" && $4 + 0 >= 16 && ($6 == "1.0E-07" || $6 == "1.0E-08") { n++; w += ($8 == "warned") }
    END { printf "%d of the %d", w, n }' "$long" 2>/dev/null || echo "? of the ?")
# the slider chains whose units come from the reduced ODE: "N = n (dE d; regdae's tight run: status s, dE d)"
long_reduced=$(awk '/^# \[part 1\] reference chain_long slider N=/ && /source=reduced/ { n = $7; sub(/N=/, "", n); sub(/:/, "", n)
        d = $0; sub(/.*tight run: dE=/, "", d); sub(/ .*/, "", d)
        st = "?"; dr = "?"; t = "?"
        if ($0 ~ /vs regdae 1e-11 \(status=/) { st = $0; sub(/.*vs regdae 1e-11 \(status=/, "", st); sub(/ .*/, "", st)
            t = $0; sub(/.*vs regdae 1e-11 \(status=[^ ]* at t = /, "", t); sub(/,.*/, "", t)
            dr = $0; sub(/.*vs regdae 1e-11 \(status=[^)]*\) dE=/, "", dr); sub(/ .*/, "", dr) }
        printf "%sN = %s: %.2g (regdae %s at t = %.3g%s)", (k++ ? "; " : ""), n, d, st, t, (dr == "?" ? "" : sprintf(", %.2g", dr)) }' \
    "$long" 2>/dev/null || true)
long_noref=$(awk '/^# \[part 1\] reference chain_long slider N=/ && /no reference/ { n = $7; sub(/N=/, "", n); sub(/:/, "", n)
        st = $0; sub(/.*status=/, "", st); sub(/ .*/, "", st); t = $0; sub(/.* at t = /, "", t); sub(/ .*/, "", t)
        printf "%sN = %s (status %s at t = %.3g)", (k++ ? ", " : ""), n, st, t }' "$long" 2>/dev/null || true)
# --- the chains with sliders on [0, 1], from chain.txt: their classes; the cells of N > 2 judged
# against the peer and those where it failed (N/R at t, or why it gave no result)
short=$grids/chain.txt
short_classes=$(awk '$1 ~ /^[0-9]+$/ && $3 == "slider" { n++; c[$8]++ }
    END { split("ok warned silent false_alarm failed undecided no_reference", k, " ")
          for (i = 1; i <= 7; i++) if (c[k[i]]) printf "%s%d %s", (m++ ? ", " : ""), c[k[i]], k[i]
          if (!n) printf "?" }' "$short" 2>/dev/null || echo "?")
short_peer=$(awk '$1 ~ /^[0-9]+$/ && $3 == "slider" && $4 + 0 > 2 && NF >= 17 && $17 != "none" { n++ } END { print n + 0 }' "$short" 2>/dev/null || echo 0)
short_fail=$(awk '$1 ~ /^[0-9]+$/ { cur = ""
            if ($3 == "slider" && $4 + 0 > 2 && NF >= 17 && $17 != "0" && $17 != "none") cur = sprintf("N = %d at R = %s", $4, $6)
            next }
        cur != "" && /^#   reference method \(peer\) failed: / { t = $0
            if (t ~ /at t = /) { sub(/.*at t = /, "", t); sub(/ .*/, "", t); t = sprintf("t = %.2g", t) }
            else if (t ~ /ran longer than/) { sub(/.*ran longer than /, "", t); sub(/ s .*/, "", t); t = "no result in " t " s" }
            else t = "no result"
            printf "%s%s (%s)", (n++ ? ", " : ""), cur, t; cur = "" }' "$short" 2>/dev/null || true)
n_short_fail=$(count_list "$short_fail")
# the chains' references on [0, 1] ('# [part 1] reference chain ...' lines): CVODE's cpu on the
# reduced ODE at N = 4096 ("plain a, slider b"), the sizes whose reference is regdae's tight run,
# and regdae's tight run against the reduced ODE (norm at 1e-8) on the sizes it was the reference
# of before the O(N) slopes (plain N >= 512, slider N >= 128): "plain a ... b, slider c ... d"
short_refs=$(grep '^# \[part 1\] reference chain plain\|^# \[part 1\] reference chain slider' "$short" 2>/dev/null || true)
short_cpu=$(echo "$short_refs" | awk '$7 == "N=4096:" && /reduced ODE \(CVODE\)/ { c = $0; sub(/.*status=0 \(/, "", c); sub(/ s cpu.*/, "", c)
        printf "%s%s %.2g", (k++ ? ", " : ""), $6, c }' || true)
short_regdae=$(echo "$short_refs" | awk '/source=regdae/ { n = $7; sub(/N=/, "", n); sub(/:/, "", n)
        printf "%s%s N = %s", (k++ ? ", " : ""), $6, n }' || true)
short_cross=$(echo "$short_refs" | awk '/source=reduced/ && /outputs it reached: norm\(1e-8\)=/ { n = $7; sub(/N=/, "", n); sub(/:/, "", n)
        if (n + 0 < ($6 == "plain" ? 512 : 128)) next
        x = $0; sub(/.*outputs it reached: norm\(1e-8\)=/, "", x); sub(/ .*/, "", x); x += 0
        if (!($6 in lo) || x < lo[$6]) lo[$6] = x; if (x > hi[$6]) hi[$6] = x }
    END { split("plain slider", vs, " "); for (i = 1; i <= 2; i++) if (vs[i] in lo)
              printf "%s%s %.2g ... %.2g", (k++ ? ", " : ""), vs[i], lo[vs[i]], hi[vs[i]]
          if (!k) printf "?" }' || echo "?")

cat <<TXT
## Trust grids: is a status ok right?

Issue 19's grids, built for it and not used to choose any rule (starts drawn at random and
log-spaced, speeds from 0 to 20 rad/s, sizes to 4096 links), every option at its default but
rtol = atol = R, each cell against a reference that does not come from regdae (\`drivers/trust.f90\`,
run by \`sh drivers/report/trust_grids.sh build\`, ${run_line}). A cell's error is the largest
\|x_i - xref_i\| / (R \|xref_i\| + R) over its outputs; its bound 10 max(1, err_ref), err_ref the
same error of a reference method at the same R (Dormand-Prince on the reduced ODE for the crank
and the four-bar, the plain IDA peer for the plain chain and for the chains of 4 ... 4096 links
with sliders (the peer on the same constraints, the sliders' too), Dormand-Prince on the slider
crank's reduced ODE for the chain of 2 links with the slider, on [0, 1] and [0, 10] alike, none
for the linear DAEs). Classes: **ok** (status ok, error within the bound), **warned** (a warning status,
x returned), **silent** (status ok, error above the bound; also a warned run whose outputs after
its last warning jump above the bound, by 100x every error before, past a fold of the reference
other than the warned pass's: a later silent departure), **false alarm** (a check stopped a run
that ends within the bound with the checks off), **failed** (stopped, and without the checks not
within the bound either), **undecided** (the reference's own check too coarse to judge).

Issue 19's targets, from this run:

| target | measured | |
|---|---|---|
| 0 silent cells on every grid | ${silent_list%, } | $(verdict "$v_silent") |
| false alarms at most 1% of the cells | ${fa_list%; } | $(verdict "$v_fa") |
| tolerance proportionality: log-log slope of the error against rtol >= 0.8 on the slider crank (1e-3 ... 1e-10) and the chain | crank ${crank_slope} (bench, \`defaults\`); chain at least ${chain_min} over R = 1e-3 ... 1e-8 (${chain_text}); over R = 1e-3 ... 1e-10 at N = 2 ... 64 at least 0.83 (slider N = 4; N = 8 and 64: 1.09-1.16, ctest \`driver.trust_proportionality\`, by hand: below) | $(verdict "$v_prop") |
| \`integrator=ida\` reaches 1e-9 on the slider crank | ${ida_err} at rtol ${ida_rtol} (status ${ida_status}; bench row \`defaults integrator=ida\`) | $(verdict "$v_ida") |
| the cost of trust: the defaults on the slider crank (paper case) within 1.2x of the baseline's cost at matched accuracy | at most ${cost_max}x in instructions (${cost_range}; table below) | $(verdict "$v_cost") |
| the error estimate's cost stated, and how often it bounds the true error within a factor 10 | $(est_get within10) of $(est_get outputs) outputs within a factor 10, $(est_get bounds) at least a tenth of the true error; ${est_ratio}x the instructions of the defaults (table below) | stated |

Cells per class on this run, and in brackets on the baseline (the library before this issue, at
29c5eaf, the same grids: \`drivers/report/trust_baseline.txt\`; chain_long's baseline was judged
without the reference methods, against the units alone):

| grid | cells | ok | warned | silent | false alarm | failed | undecided | no reference | false alarms of the cells |
|---|---|---|---|---|---|---|---|---|---|
${rows}
![slider crank: error over the bound](figures/trust_crank_err.png)

![slider crank: classes](figures/trust_crank_class.png)

The slider crank: 25 starts th1 in [1e-8, pi - 1e-8] (log-spaced towards both ends, random in
between, the fold pi/2 among them) times 13 speeds w1 in {0, 1e-6 ... 1e-2, 0.1, 0.5, 1, 2, 5,
10, 20} times R = 1e-3 ... 1e-8, t in [0, 10], 200 outputs; reference the reduced ODE by CVODE at
1e-13.

![four-bar: error over the bound](figures/trust_fourbar_err.png)

![four-bar: classes](figures/trust_fourbar_class.png)

The parallelogram four-bar (G loses rank at every fold) at index 3 and 2: slow swings from 0.02 rad
of a fold, a turn 6e-5 rad before one, the unstable top, random starts; reference its
one-coordinate ODE.

![linear DAEs: error over the bound](figures/trust_linear_err.png)

![linear DAEs: classes](figures/trust_linear_class.png)

The linear index-2 DAEs with GB ~ t^2 (S1) and t^4 (S2) under the three methods, exact solutions.

![chain on \[0, 1\]: error over the bound](figures/trust_chain_err.png)

![chain on \[0, 1\]: classes](figures/trust_chain_class.png)

![chain on \[0, 10\]: error over the bound](figures/trust_chain_long_err.png)

![chain on \[0, 10\]: classes](figures/trust_chain_long_class.png)

The chain of N = 2 ... 4096 unit links, plain and with sliders, on [0, 1] and [0, 10] (chaotic
there: the long grid judges the checks, the energy change and the constraint violation, in units of
the tight run's own plus R times the scales, err = max(dE/dE_unit, viol/viol_unit)). On [0, 1]
the chains with sliders of 2 ... 4096 links are compared with their reduced ODE in the N/2 crank
angles (below; CVODE at 1e-13, checked at 1e-12, regdae's tight run a cross-check on the reference
line); the plain chains with the peer at 1e-11 (checked at 1e-10) where both succeed (N = 2 ...
32), else with their reduced ODE in the N link angles (N = 64 ... 4096). Both reduced ODEs are
integrated with their O(N) slopes (\`chain_slider_recursive\`, \`chain_plain_recursive\` in
\`drivers/problems/chain_problem.f90\`: articulated-body recursions, equal in the unit tests to
the dense forms \`chain_slider_reduced\`, \`chain_plain_reduced\` within 1e-12 of the largest
acceleration; CVODE at 1e-13 takes ${short_cpu} s cpu at N = 4096); regdae's own tight run
(formulation=augmented, rtol = atol = 1e-11, eps = 1e-16, checked against 1e-10 with eps = 1e-14)
would be the reference only where the reduced ODE failed: ${short_regdae:-nowhere on this run}.
That tight run was the reference of the plain chains of 512 ... 4096 links and the slider chains
of 128 ... 4096 links up to fe0352f (17 cells undecided there, its check too coarse); against the
reduced ODE it is ${short_cross} error weights off at R = 1e-8 (the reference lines). The
chains with sliders are judged against the long chains' reference methods at R: the peer on the same constraints for N = 4 ... 4096,
Dormand-Prince on the slider crank's reduced ODE for N = 2, err_ref over the outputs the method
reached. Their cells: ${short_classes}. Of the ${short_peer} cells of N > 2 the peer failed in
${n_short_fail}${short_fail:+ (${short_fail})}; err_ref counts the outputs before the failure (where it
failed before the first output, none: err_ref = 0 and the bound 10, as without a reference method).

The cells that miss (silent, false alarm, undecided; the row's columns, then for a false alarm
the run with the checks off), from \`trust_grids.sh\`'s \`baseline.txt\`:

\`\`\`
$(awk '/^# (silent|false_alarm|undecided) cells/ { show = 1; print; next } /^# (warned|no_reference) cells/ { show = 0 } show && NF' "$grids/baseline.txt" | cut -c1-200)
\`\`\`

Of the crank's silent cells, the four left spin fast (w1 = 10, 20) at R = 1e-8: the
error is 15-26 times the reference method's over 16 revolutions (1.3-2.6x the bound), the same on
the baseline, and it is the regular integration's (no pass is unresolved; Dormand-Prince on the
four-coordinate regularized system against Dormand-Prince on the one-coordinate reduced ODE);
\`error_estimate=yes\` sees it (ratio estimate/true 0.87-1.8 at \`ex52 th1=3.141493 w1=10 rtol=1e-8
atol=1e-8 nout=100 error_estimate=yes\`). At the neighbouring R the same starts are 0.3-1.3x the
reference method's error: the reference's phase error changes sign near R = 1e-8, so its error
there is 10-40x below its level on either side (the stop-25 diagnosis; the judge is the issue's
and is not changed). Measured step by step on these four cells (doc/methods.md, "The answer"):
Dormand-Prince on the reduced ODE with its pass regions integrated exactly has 69.3 / 52.4 / 48.8 /
49.4 weights (regdae 71.6 / 84.2 / 46.7 / 64.2): the method's own error on the regular part of each
half turn, which the reference method cancels to 2% by its 20% longer steps just after each pass;
regdae re-integrates that stretch at rtol/10 and so keeps the error of a more accurate run. The two near-singular starts that were silent before (w1 = 2 from th1 =
3.7e-3 and 1e-2, at R = 1e-7 and 1e-6: the automatic weights too stiff there, and IDA's BDF
error 5-10x the reference's) are ok since \`integrator=auto\` hands a small stiff second-order
problem to Radau IIA instead of IDA (issue 21): errors 0.63 and 0.76 against bounds of 21 and 29.
The four-bar's top (the unstable equilibrium at rest), silent before at R = 1e-3 (cells 9 and 63:
14.3 and 32.4 weights), stays at the top since a start at rest in an equilibrium keeps every
explicit step within the constraint modes' stable step (doc/methods.md, "The stable step after a
restart"): the damped least squares' bias eps/sigma^2 (4.8e-6 in th2, normal to the constraints)
had been grown by a 0.625 s step at h |s| = 7.8 to th2 ~ 1e-4, which fed the unstable mode
(exp(sqrt(g/r) t), 6e6 over the 5 s) through the tilted constraint force; now 3.4e-5 and 1.4e-3
weights, the reference method keeping the top exactly (its right-hand side vanishes there).
rand4/i3 at R = 1e-3, silent before (a 0.34 s explicit step straight
over the fold at th1 = -2 pi, no pass seen), is ok since a step longer than the motion's time
scale has its quarter points probed for a singular pass (\`regdae_explicit_rk\`,
\`sample_step_end\`): error 3.29 against a bound of 38.6 (was 42.9).
**A crank grid on starts no rule was chosen on** (\`build/bin/trust family=crank seed=2026\`: the
same speeds and R, the 4 near-singular th1 drawn log-uniform in [1e-8, 1e-1] and the 16 others
uniform from seed 2026; run by hand, 3 minutes; not part of \`trust_grids.sh\`). At 253ffff: 1950
cells, ok 1863, warned 68, silent 8, false alarm 4 (0.2%), failed 6, undecided 1. With the stable
step after a restart (doc/methods.md; at 1643bba): ok 1866, warned 68, silent 9,
false alarm 3 (0.15%), failed 2, undecided 2; on the starts of seed=31 (no rule was tuned there)
silent 12 and false alarms 6 before and after (failed 8 -> 4, warned 132 both), on the standard
crank grid (\`trust_grids.sh build crank\`) silent 4 before and after (the same four cells), false
alarms 7 -> 6 (5 fast spins at R = 1e-3 no longer stopped, 4 others now stopped, two of them
failures before), failed 7 -> 4. Cell 566 (th1 = 0.97, w1 = 0.1, R = 1e-4: 386 against 306), where
after the first pass the explicit integrator grew its steps from the companion's state to 0.55 s
(h |s| = 6.5 on the constraint modes) near the turning point and the energy went 1.4% off, is 3.3;
cell 1170 (a fast spin at R = 1e-8) is ok. Silent: five fast spins at R = 1e-8 (w1 = 10, 20: 49-68
against bounds of 17-59, the pattern above), cells 732 (th1 = 1.24, w1 = 1e-4, R = 1e-5: 15.6
against 14.7) and 800 (th1 = 1.38, w1 = 0.1, R = 1e-4: 34.5 against 27.1; 18.4 before), where the
reference method is 5x better than at the neighbouring speeds; cell 1784 (th1 = 3.119, w1 = 1e-5,
R = 1e-8: 676 against 354), a slow start near the crank's unstable singular configuration whose
error moves between 14 and 800 with any change of the steps (the reference's own check is 2.2
units; 93 with stop_at_output=yes, 36 with integrator=radau); cells 1873 and 1874 (th1 = pi - 3.5e-6
at rest or w1 = 1e-6, R = 1e-3: 6.2e3 against 4.8e3 and 5.0e3): the start lies inside the eps layer
of the solution and of every pass-check level (sigma_min(GB)^2 ~ 1e-22 against eps >= 1e-12 sigma_reg^2),
so the levels agree on the regularized motion, which leaves the singular configuration on the
other branch (th2 = th1 - pi, 3.1 rad off); with eps = 1e-24 the run keeps the branch but is still
9 rad off, the departure from the unstable configuration being timed by a perturbation far below
the tolerance (the reference method's own error is 480-500 units). Tried and not kept (each run on
the three grids): a cap on every step at 2.8/|s| with the capped steps counted for the stiffness
test (seed=2026 silent 8 -> 7 and false alarms 4 -> 0, 1873/1874 within their bounds; but the
standard grid's silent 4 -> 9: slow starts inside the layer handed to Radau, whose large steps
damp the unstable motion, lost the pass check's warning), the cap without the count (seed=31
silent 12 -> 14, warned 132 -> 276), and a growth of at most 1.2x per step beyond 2.8/|s|
(seed=2026 silent 8 -> 11, false alarms 4 -> 7).
With the pass check's two rules (doc/methods.md: a solution 1000 pass_tol off its level restarts
from it inside the pass; outputs interpolated in a step that a later check finds off warn; at
the commit after 3f11404): ok 1859, warned 76, silent 8, false alarm 3 (0.15%), failed 2,
undecided 2 (1873 warned; 7 cells within their bounds warned too: 14, 15, 32, 1654, 1878, 1891,
1904); the standard crank grid (\`trust_grids.sh build crank\`, both with the driver of that
commit) ok 1729 -> 1711, warned 207 -> 225, silent 4 -> 4 (the same four), false alarms 6 -> 6
(0.3%), failed 4 -> 4: 18 cells within their bounds now warned, mostly slow starts at the
singular configuration (err 0.4-8.8 at th1 = 1e-8 ... 1e-4) and w1 = 1e-2 at th1 near pi.
The long chains are judged against a reference method at the same R that does not come from
regdae: the plain IDA peer (stabilized index 2, \`drivers/common/chain_peer.f90\`) on the plain chain
and on the chains of 4 ... 256 links with sliders (the same constraints, the sliders' y_2k = 0
too), Dormand-Prince on the slider crank's reduced ODE for 2 links with the slider. The slider
chains pass singular configurations: a pair of links folds (G loses rank) where joint 2k crosses
joint 2k-2 on the line (the folds seen at the tight runs' 100 outputs, a lower bound: ${long_folds:-?});
plain IDA goes through a fold where none of its steps lands close to it and stops with a failed
corrector where one does. Of the ${slider_peer} slider cells of N > 2 the peer failed in ${n_late} in mid-run${fail_late:+ (${fail_late})},
and their err_ref counts the outputs before the failure, as for the plain chain (at d355198, by
hand: each of the six failures of that run at a fold, sigma_min(G) of the peer's state falling
linearly to 1e-5 ... 3e-4 in the last 0.005 s before it); in ${n_early} before its first output${fail_early:+ (${fail_early})}:
at the start of the long chains at loose R, as on the plain chains of 64 ... 256 links at R = 1e-3,
err_ref = 0 there and the bound 10, as without a reference method. The reference methods'
energy drift over 10 s of chaotic motion is of the same order as regdae's (at R = 1e-3, N = 2: the
peer's ${c1_ref} units on the plain chain and Dormand-Prince's ${c49_ref} on the slider crank,
regdae's ${c1_err} and ${c49_err}): judged without them, against the units alone (issue 19's first
run of this grid), 22 cells were silent, 16 plain and 6 with sliders. The slider chain of 16 links
at R = 1e-3, silent against the units alone, is ${c67_class} against the peer: its energy changes by
${c67_de} against a unit of ${c67_unit} (${c67_err} units), the peer's by ${c67_deref} (${c67_ref}
units: the bound ${c67_bound}). The units of every chain come from its reduced ODE, not from
regdae: the slider chain in its N/2 crank angles on the branch where each rod mirrors its crank (the
start's), regular through the folds, the plain chain in its N link angles (Lagrange's equations);
their dense forms (\`chain_slider_reduced\`, \`chain_plain_reduced\` in
\`drivers/problems/chain_problem.f90\`) are tested against the full equations, the O(N) forms
integrated (\`chain_slider_recursive\`, \`chain_plain_recursive\`) against the dense ones; by CVODE
at 1e-13 (${long_cpu:-?} s cpu for the plain chain of 256 links, whose dense form took over 90 s), its
scales checked at 1e-12; regdae's tight run (1e-11, eps = 1e-16) is a cross-check. The slider chains'
energy change, and in brackets the tight regdae run's status, the time it reached and its energy
change: ${long_reduced:-?}. Until the reduced ODE the slider chains of 4 and 8 links were not
judged: their tight regdae run, then the source of the units, is stopped by its drift check (-113
at t = 9.16 and 8.24), and the peer at 1e-11 is no substitute (it stops at a fold: N = 4 at t =
3.66, N = 8 at t = 1.63, by hand). Not judged for want of a reference: ${long_noref:-none}. Up
to fe0352f the units of the slider chains of 128 and 256 links and of the plain chain of 256 links
came from regdae's tight run, whose own energy change (slider 2.1e-4 and 1.3e-3, plain 5.4e-6;
the reduced ODE's 1.7e-10 ... 1.2e-8) was in the units: at small R regdae's energy change there
was about its tight run's, err about 1 and the bound 10 (slider N = 128 at R = 1e-8 0.85, N = 256
at R = 1e-7, 1e-8 3.3 and 11). With the reduced ODE's units no cell changed class (70 ok, 26
warned, as with fe0352f's drivers), and the warned slider cells of 128 and 256 links above their
bounds show how far regdae's energy drifts there: ${long_over:-none}. ${small_warned} cells of N >= 16 at R = 1e-7, 1e-8 end with a warning. Against R E_scale alone (the energy part,
the tight term left out; at d355198, by hand) no slider cell with status ok is above its bound
either: the cells above it (N = 16 ... 256 at R = 1e-5 ... 1e-8, up to 1.1e4 against 40) are all
warned.

**Fast spins against the reference method** (issue 19's last silent cells; at 63bcca4, the library of 8e737d6, by hand,
\`sh drivers/report/spin_grid.sh build/bin\`: 6 th1 uniform in (0.05, pi - 0.05) times w1 = 2 ... 30
rad/s log-spaced (8) times R = 1e-5 ... 1e-10, 288 cells, the trust grids' weighted error against
CVODE at 1e-13; \`trust family=crank th1=A w1=W rtol=R\` runs one cell at any R). regdae's explicit
path is not systematically less accurate than Dormand-Prince on the reduced ODE at the same R: the
ratio err/err_ref has a geometric mean of 0.83 (median 0.89, 90th percentile 2.3, largest 36), per
R 0.50, 0.89, 1.14, 2.56, 0.33, 0.75 (R = 1e-5 ... 1e-10); the 4 silent cells and every ratio
above 3.0 are at R = 1e-8. There the reference is lucky: both methods' global (phase) errors
change sign as R falls, Dormand-Prince on the reduced ODE near R = 7e-9 ... 1e-8, regdae near 3e-9
... 5e-9. At 13 R from 1e-7 to 1e-9 (th1 = 1.573, w1 = 20.4; th1 = 0.169, w1 = 13.8; th1 = 3.141493,
w1 = 10) the reference has 97-162 error weights at 1e-7, 2.0-20 at 6.8e-9 ... 1e-8 and 89-194 at
1e-9, regdae 106-194, 32-131 and 3.4-49: smooth in R but for its own zero, and 0.02-1.5 times the
reference (mostly below 0.5) from 3.2e-9 down. Every silent cell at R = 1e-8 of the crank grids at 8e737d6 (fixed 4; seeds
31, 4242, 77, 9090, 6161, 7171: 10, 6, 4, 5, 8, 5 of 10, 6, 5, 5, 9, 7 silent; 42 cells, 39 of them
at w1 >= 5, the others w1 = 0.5 and 1e-5 from th1 = 2.01 ... 2.69) has an err_ref of 1.5-8.4 weights, 10-60
times below the reference's own error at the neighbouring R. Nothing in the regularization moves
regdae's error (th1 = 1.573, w1 = 20.4 and th1 = 0.169, w1 = 13.8 at R = 1e-7 and 1e-8: eps = 1e-12
... 1e-16, gamma1 = 20 or 500, pass_check=no, stop_at_output=yes all within a factor 1.8 of the
defaults' 56-194 weights; eps = 1e-18 takes 8x the steps); the velocities w1, w2 have the largest
weighted local error in 94% of the accepted steps (th1 = 1.573, w1 = 20.4, R = 1e-8), and regdae
takes 3-13% more steps than Dormand-Prince on the reduced ODE (1069-2419 at R = 1e-7, 1e-8) with
about as many rejections (21% of the tries against 24-27%: the error constant grows fast on the
approach to each dead point). Radau (\`integrator=radau\`) is 340-2900x more accurate there at
3.8-5.1x the steps. **Tried and not kept**: the explicit steps' local tolerance at rtol/2 (every level
of the pass checks and the error estimate's companion alike). The spin grid's ratio falls to a
geometric mean of 0.38 (largest 12.9, 1 silent cell: th1 = 0.170, w1 = 13.8, R = 1e-8, 44 against
34); classes ok/warned/silent/false alarm/failed before -> after: fixed crank 1713/226/4/1/6 ->
1729/218/0/0/3 (the four cells 2.1-9.1 weights; 1897's false alarm and the w1 = 20 failures 91,
1729, 1885 at R = 1e-3 ok); seed 31 1788/149/10/0/3 -> 1796/146/5/0/3, of which 5 NEW silent
(th1 = 2.689 at w1 = 0 ... 1e-3, R = 1e-8: 19-34 against bounds of 14.7-18.3, 5.6-14.2 before: the
same lucky reference, err_ref 1.47; regdae's own error at that start moves between 3 and 160 weights
from R = 3e-8 to 5e-9 either way); seed 4242 1863/80/6/0/1 -> 1870/79/1/0/0 (cell 1559, err_ref 1.8:
38 against 18; at a margin of 3 still 23); seed 77 1868/75/5/0/2 -> 1875/73/0/0/2; seed 9090
1784/158/5/0/3 -> 1789/154/2/0/5 (the two new failures are the wall budget, 30 s, of two w1 = 20
runs at R = 1e-8 that took 11-18 s before, under a load of 12 on this 2-core machine: 2.6 s of CPU);
seed 6161 (new) 1776/160/9/0/4 -> 1789/154/2/0/5 (one NEW silent cell, 932: th1 = 1.386, w1 = 1,
R = 1e-8, 6.1 -> 123 against 21.4, but 1.4 with pass_check=no and 1.8 with stop_at_output=yes: the
pass checks' restart or outputs, not the integration; 2.9 at 8e737d6 with pass_check=no; one more
wall-budget failure); seed 7171 (new) 1843/93/7/1/6 -> 1859/87/0/0/4; fourbar 106/0/2/0/0 ->
107/0/1/0/0 (cell 9 ok); linear 8/32/0/0/8 -> 7/34/0/0/7 (cell 22 ok -> warned, 41 failed -> warned). Its cost (\`sh drivers/report/cost_of_trust.sh\`, paper case, rtol 1e-4 ... 1e-8): 16.1M,
15.6M, 16.5M, 20.5M, 32.0M instructions against 14.9M, 14.2M, 15.5M, 18.9M, 29.2M (1.06-1.10x at
the same rtol), errors 5.0e-4, 3.4e-5, 3.2e-6, 2.5e-7, 2.5e-8 against 1.1e-3, 9.3e-5, 5.1e-6,
5.1e-7, 6.5e-8, so at matched accuracy 1.71, 1.45, 1.33, 1.27, 1.54 times the baseline against 1.65,
1.38, 1.32, 1.27, 1.56 today (a margin of 3: 1.90, 1.51, 1.32, 1.15, 1.56). Not kept because it
moves the cells the judge's lucky reference picks rather than removing them (new silent cells on
seed 31), and it changes verdicts the tests pin: \`unit.defaults\` (the explicit run that went off
the branch without checks at rtol 1e-4 stays on it), \`unit.api\` (acceleration_on_request: a pass
warning), \`unit.radau_solver\` (the 33-link chain is no longer handed to IDA), \`example.ex51_f77\`
(an unresolved pass, levels 3.5 weights apart against pass_tol 3), \`driver.trust_reproducers\`.
A cell-wise bound that a method of the reference's own order and tolerance meets needs a judge
that does not take the reference's zero crossings as its error level (e.g. the largest err_ref
over the neighbouring R), which is the issue's to decide.

**Seeded grids of the four-bar, the linear DAEs and another crank seed** (run by hand at e50c07a,
seconds each but the crank's 1.5 minutes; not part of \`trust_grids.sh\`). \`build/bin/trust
family=fourbar seed=S\`: 3 slow swings near a fold (th1 = 0 or pi +- 10^u, u in [-6, -1], w1 =
+-10^u, u in [-6, 0]) and 6 starts in the fixed grid's ranges, index 3 and 2, the same R. Seeds 2026
and 77: 108 cells each, ok 106, warned 2, nothing silent, no false alarm, none failed (seed 2026 at
ce09c47 and after: ok 107, warned 1); but seed 77's
cell 107 (rand5/i2, th1 = 4.607, w1 = -4.47, R = 1e-8, err 1.0e8) was "warned" only by an unresolved
pass at t = 0.65 whose error is 1e-7: the run was caught at the fold th1 = 2 pi (1.2e6 error weights
from the pass check's level 1 at t = 1.85, sigma_min(GB) below the threshold to t = 5, so the pass
never ended) while its outputs came from a companion, which runs without checks and left the
parallelogram branch at t = 3.0 with status 0 at every output (seed 6's cell 104 the same). The
driver now counts such a run silent (after the last warning, status-0 outputs past a later fold of
the reference than the warned pass's with an error beyond the bound and 100x every error before
that fold; on the library before ce09c47 seed 77: ok 106, warned 1, silent 1; seed 6: ok 103,
warned 4, silent 1; the fixed grids and crank seed=2026 unchanged), and the pass
check restarts a solution more than 1000 pass_tol from level 1 from the level at once
(doc/methods.md): cell 107 13.8 against 87, cell 104 9.2 against 81, both warned by their first
pass; the index-3 cell 53 10.2 either way. Seeds 1-8 (864 cells): ok 853, warned
7, silent 1, false alarm 2, failed 1 (wall budget: slow1/i3 at R = 1e-8, 100,565 steps). The silent
cell (seed 3, cell 5: rand2/i3, th1 = 2.038, w1 = -1.366, R = 1e-3, 3726 against 115) swings to 0.25
below the unstable top in energy; 27 explicit steps gain 0.5 over the fold at pi (1.3% of the energy
scale, under work_tol), so the motion goes over the top and rotates (4.2e-3 with stop_at_output=yes,
3.0 with Radau; the error estimate sees it, 60 weights at t = 3.5). A false alarm (seed 2, cell 2:
th1 = pi - 7.4e-6, w1 = 1.05e-3, R = 1e-3, 0.34 with the checks off): the work-energy check at t =
4.06 finds a defect of 13.6% of the energy scale while the energy changed by 0.07%: its quadrature
of the forces' power over 0.3 s explicit steps is what is off. \`build/bin/trust family=linear
seed=S\` (S1 and S2 with the singular point t* uniform in (-0.9, 0.9), C scaled by 10^u, u in [-2,
2], t* among the outputs; 144 cells): seed 2026, ok 15, warned 97, silent 1, failed 31 (Baumgarte,
stopped at t*); seed 77, ok 20, warned 96, silent 1, failed 27 (after ce09c47: seed 2026 ok 13,
warned 100, silent 0, failed 31; seed 77 ok 17, warned 100, silent 0, failed 27). Both silent cells are S2 under
trust_region (seed 2026 cell 97: t* = -0.639, c = 0.255, R = 1e-3, 10.9 against 10; seed 77 cell 74:
t* = -0.833, c = 0.377, R = 1e-4, 22.2): one Dormand-Prince step spans t*; the outputs inside it are
its interpolant (seed 2026: the step's end 0.66 off, the outputs up to 11), and the pass check
compared levels 0 and 1 at those outputs, which agreed (2.5 error weights
apart at t = -0.62) while both were about 11 off; at the step's end levels 1 and 2 are 8.5 apart.
A pass whose later check finds the answer above a level whose x was returned at its earlier
outputs now warns, naming them (doc/methods.md): both cells warned; on the fixed linear grid 2
cells within their bounds (err 1.05 and 2.0) warn too (ok 10 -> 8). With stop_at_output=yes, IDA
or Radau the pass check warns (levels 4-5 weights apart); \`error_estimate=yes\` estimates 10.6 and
12.7 there. \`build/bin/trust family=crank
seed=77\`: 1950 cells, ok 1872, warned 64, silent 5, false alarm 5, failed 4. Four silent cells are
fast spins at R = 1e-8 (w1 = 10, 20: 59-84 against 32-84, the pattern above; Radau 0.14-0.23); cell
1333 (th1 = 1.688, w1 = 0.1, R = 1e-3: 302 against 262; \`ex52 th1=1.688345 w1=0.1 rtol=1e-3
atol=1e-3 nout=200 stop_at_output=no\`: 0.50 rad): 78 explicit steps (55 rejected) gain 60% of the
energy before the first pass, and the work check lets it through because its allowance adds the
quadrature's own error estimate, large at such steps (work_defect 0.145; work_tol=0.01 does not stop
it either); the cell with stop_at_output=yes 6.3e-3, with Radau 1.1; ex52 with h_max=0.05 3.8e-5
rad. The five false alarms are the work-energy check at R = 1e-3 on spinning starts (w1 = 1-20):
with the checks off the runs are 125-329 weights off (Radau 8-20), inside bounds of 1950-66500 set
by Dormand-Prince's own error at 1e-3: false by the judge, true by the tolerance.

**The step rule for unresolved energy balances** (doc/methods.md; at 7690905, merged in cb0fdb9): a
long explicit step whose work-energy balance the monitor cannot resolve (its defect plus the
quadrature's estimate above 3x the energy the tolerance leaves open) is taken again at half the
length, at most 3 times. Four-bar seed 3 cell 5: silent 3726 -> ok 4.9; crank seed 77 cell 1333: 158
-> 15.1 weights (ex52 as above 0.226 -> 0.031 rad). Classes ok / warned / silent / false alarm /
failed, before (399f6f9) -> after, each grid run by the helper that wrote the rule: fixed crank
1711/225/4/6/4 -> 1713/226/4/1/6; crank seed=31 1779/149/10/8/4 -> 1788/149/10/0/3; crank seed=4242
1862/79/6/1/2 -> 1863/80/6/0/1; crank seed=77 1865/74/5/4/2 -> 1868/75/5/0/2; on seeds no rule was
chosen on, crank seed=9090 1781/158/5/2/4 -> 1784/158/5/0/3 and four-bar seeds 21-24 and 31 unchanged
(108 cells each, all ok but one false alarm on seed 22). Three fast spins at R = 1e-3 (fixed crank
cells 91, 1729, 1807: w1 = 20 near th1 = 0 and pi) were stopped by the work check at t = 0.76-1.36
before and now fail with -108 (step size too small) at t = 6.9-8.3: their energy grows in small
steps between the pass checks, each of which starts the balance again from its verified state
(+1476 summed over 37 stretches to t = 3.7, each below its own allowance); the same class was not
held before either (crank seed 9090's spins at w1 = 20 failed -108 late at 399f6f9, and \`ex52
th1=4.269101e-6 w1=20 rtol=1e-3 atol=1e-3 nout=200 stop_at_output=no\` ended ok there with an
energy error of 1.9e4 against T(0) ~ 1000). A balance carried across the pass checks was tried and
does not fire either (defect 1105 against an allowance of 4330 at t = 2.88: the tolerance's term is
large near the passes): open. **Tried and not kept**: one iterated-Tikhonov step in the multiplier's
damped least squares (the same Cholesky factor; the regular modes' bias eps/sigma^2 -> (eps/sigma^2)^2,
off in and near the layer): the four-bar's top cells 9 and 63 14.3 / 32.4 -> 0.20 / 0.13 and the
fixed four-bar grid 0 silent, but the fixed crank grid silent 4 -> 6 and crank seed=4242 silent 6 ->
8 with 3 more false alarms (refined everywhere: crank silent 4 -> 14): the damping's bias on the
approach to a pass holds back the growth of integration errors.

**The cost of trust** (\`sh drivers/report/cost_of_trust.sh build/bin\`: instructions of the solve,
\`init\` and the advances, counted by callgrind, exact and repeatable where this machine's timings
move by up to 50% between processes; ex52 from the paper's start, 1000 interpolated outputs on
[0, 10]; the baseline's rows, from the library at 29c5eaf, in \`drivers/report/cost_baseline.txt\`).
"matched" is the baseline's instructions at the error of the defaults (log-log interpolated
between its rtols):

| rtol | error (defaults) | instructions (defaults) | / baseline at the same rtol | / baseline at matched accuracy | pass_check=no | error_estimate=yes | estimate / defaults |
|---|---|---|---|---|---|---|---|
$(echo "$cost_rows" | awk '{ printf "| %s | %s | %s | %s | %s | %s | %s | %.1f |\n", $1, $2, $3, ($4 == "-") ? "-" : sprintf("%.2f", $4), ($5 == "-") ? "-" : sprintf("%.2f", $5), $6, $7, $8 }')

Where it goes: the passes' companions (at rtol/10 from each pass's checkpoint to its end) and,
from rtol 1e-7 down where consecutive levels share the eps floor, the eps probes, each a
companion too (the second only where it can change the verdict); \`pass_check=no\` leaves the automatic rules' share (the landing and the probing of
the approach), 1.0-1.3x the baseline.

**The error estimate** against the true error (\`sh drivers/report/error_estimate.sh build/bin\`;
ex52 from the paper's start and 11 random starts, rtol 1e-4, 1e-6, 1e-8, 100 outputs): $(est_get outputs) outputs
in $(est_get runs) runs, the estimate within a factor 10 of the true error at $(est_get within10), at least a tenth of
it at $(est_get bounds); $(est_get runs_not_all_within) runs have outputs outside. Per rtol:

| rtol | outputs | est >= true/10 | within 10x | smallest est/true | largest est/true | seconds with / without |
|---|---|---|---|---|---|---|
$(awk '$1 !~ /^#/ && $1 != "summary" && $6 ~ /^[0-9]+$/ { r = $3; n[r] += $6; b[r] += $7; w[r] += $8
        if (!(r in lo) || $9 + 0 < lo[r]) lo[r] = $9 + 0; if ($10 + 0 > hi[r]) hi[r] = $10 + 0; se[r] += $11; sp[r] += $12 }
    END { for (r in n) printf "| %s | %d | %d | %d | %.3f | %.2f | %.2f |\n", r, n[r], b[r], w[r], lo[r], hi[r], se[r] / sp[r] }' \
    "$raw/error_estimate.txt" | sort -t '|' -k2 -g -r)

**Tight tolerances: the drift limit and tolerance proportionality** (issue 19 items 4 and 7; by
hand at 9f2e8c6 on the library of 93f48b7, drivers/trust's \`rtols=\`, \`max_links=\` and
\`reference=reduced\`). \`trust family=chain rtols=1e-9,1e-10 max_links=64\` (N = 2 ... 64, plain and
with sliders, [0, 1], against the peer or the reduced ODE): 24 cells, 22 ok, 2 warned (slider
N = 4); \`family=chain_long\` (the same on [0, 10], energy change and violation against the reduced
ODE's): 24 cells, 14 ok, 8 warned, 2 failed, 0 silent, 0 false alarms. The two failures are the
drift limit at 1e-10 on the slider chains of 4 and 8 links (\`chain n_links=4 slider=yes tf=10
rtol=1e-10 atol=1e-10\`: max \\|g\\| 7.7e-8 against drift_tol 7.07e-8 at t = 9.17, after four
unresolved-pass warnings); with the checks off they end with a warning and an energy change of
4.5e-4 (1.96e5 units, bound 1162; the reduced ODE's 3.3e-10, the peer's at 1e-10 2.7e-7) and
0.17 (4.2e7 units, bound 751): not false alarms. regdae's own tight run (augmented, 1e-11,
eps = 1e-16), taken as the reference in the issue, is as far off (energy 4.3e-4, stopped by the
same limit at t = 9.16). The drift of the slider chains on [0, 10] is 1.0e-7 ... 4.5e-7 at rtol
1e-9 and 1e-10 alike (the singular passes', not the step's; max_drift/drift_tol 0.013 ... 2.6 over
N = 4 ... 64), of the plain chains and on [0, 1] at most 1.6e-2 of the limit. On seed 7474 at
1e-9 and 1e-10: \`trust family=fourbar seed=7474 rtols=1e-9,1e-10\` 36 cells, 30 ok, 6 warned;
\`family=crank seed=7474 rtols=1e-9,1e-10 part=1/4\` 162 cells, 89 ok, 73 warned; no silent cell,
no false alarm, no failure. The drift rule was left as it is.
Tolerance proportionality on the chain against the reduced ODE (\`trust family=chain
rtols=1e-3,1e-4,1e-5,1e-6,1e-7,1e-8,1e-9,1e-10 max_links=64 reference=reduced tight_check=no\`,
ctest \`driver.trust_proportionality\`): the least-squares slope of log(err R) against log(R) over
the 8 tolerances is 1.16 (plain N = 8), 1.10 (plain 64), 1.11 (slider 8), 1.09 (slider 64);
over N = 2 ... 64 it is 1.06 ... 1.16 but for the slider chain of 4 links, 0.83 (20 and 189 error
weights at 1e-9 and 1e-10, both warned); 94 of the 96 cells ok, 2 warned.

TXT
