#!/bin/sh
# Issue 19's reproducers, each checked against a reference that does not come from regdae
# (drivers/trust: the slider crank's and the four-bar's reduced ODEs by CVODE at 1e-13, the
# linear DAEs' exact solutions, the chain's IDA peer or tight run): every one ends within its
# bound (class ok) or with a warning that says so (warned), never silent.
# Usage: check_trust.sh BIN_DIR
set -u
bindir=$1
driver=$bindir/trust
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
. "$(dirname "$0")/check_lib.sh"
# class CELL_ROW_FILE: the class column of the row(s)
class() { awk '$1 ~ /^[0-9]+$/ { print $8 }' "$1"; }
# the slider crank from the issue's starts (th1 w1 rtol): 156,057 steps and 9.1e-3 rad, 0.243 rad,
# a false alarm of the work check, eps = 2.5e-37 and 0.337 rad, 1.95e-2 rad before
n=0
for start in "2.0 1e-5 1e-6" "3.041592653589793 1e-4 1e-4" "1.0 1e-4 1e-3" "1e-8 2.5 1e-3" "1e-8 2.81 1e-6"; do
    set -- $start
    n=$((n + 1))
    run crank$n family=crank th1=$1 w1=$2 rtol=$3
    c=$(class "$tmp/crank$n.out")
    check "crank th1=$1 w1=$2 rtol=$3: $c" "$(case $c in ok|warned) echo 0 ;; *) echo 1 ;; esac)"
done
# the crank from a start of seed=2026 (drivers/trust, against the reduced ODE by CVODE; bound 10x
# Dormand-Prince on it at the same rtol): cell 566 (th1 = 0.966, w1 = 0.1, rtol 1e-4) was silent,
# 386 against 306, a 0.55 s explicit step beyond the constraint modes' stability after the restart
# at the first pass's end (doc/methods.md, "The stable step after a restart")
run seed2026_566 family=crank seed=2026 cell=566
c=$(class "$tmp/seed2026_566.out")
check "crank seed=2026 cell 566 (was silent): $c" "$(case $c in ok|warned) echo 0 ;; *) echo 1 ;; esac)"
# the work-energy check (issue 19 item 4), against the same references: the four-bar from
# th1 = pi - 7.4e-6, w1 = 1.05e-3 at R = 1e-3 (seed=2 cell 2) was stopped by the check's own
# quadrature over 0.3 s steps (kinetic energy change 14.62 against a work of 10.43, the solution
# conserving energy to 0.07%); the crank from th1 = 1.688, w1 = 0.1 at R = 1e-3 (seed=77 cell
# 1333) was silent (302 against 262) while the allowance grew with the quadrature's estimate
# (both as reported in the issue's round; at 2f1ddf0 both end ok already, the check's quadrature
# now refines such steps: doc/methods.md, "Work-energy balance")
run seed2_fourbar2 family=fourbar seed=2 cell=2
c=$(class "$tmp/seed2_fourbar2.out")
check "fourbar seed=2 cell 2 (was a false alarm): $c" "$(case $c in ok|warned) echo 0 ;; *) echo 1 ;; esac)"
run seed77_crank1333 family=crank seed=77 cell=1333
c=$(class "$tmp/seed77_crank1333.out")
check "crank seed=77 cell 1333 (was silent): $c" "$(case $c in ok|warned|failed) echo 0 ;; *) echo 1 ;; esac)"
# the work-energy balance of long explicit steps (doc/methods.md, "Work-energy balance"): the
# crank from the same start at R = 1e-3 gained 60% of its energy in one 0.26 s step (0.23 rad off,
# within the cell's loose bound of 262 weights): against the reduced ODE by CVODE in ex52, now at
# most 0.1 rad; the four-bar of seed=3 cell 5 (th1 = 2.038, w1 = -1.366, R = 1e-3) gained 0.49 in
# one 0.44 s step across the fold at pi and went over the top (3726 against a bound of 115, silent)
"$bindir/ex52" th1=1.688345 w1=0.1 rtol=1e-3 atol=1e-3 nout=200 stop_at_output=no >"$tmp/ex52_1333.out" 2>&1
e=$(awk '/^summary/ { for (i = 1; i <= NF; i++) if ($i ~ /^max_err_th=/) print substr($i, 12) }' "$tmp/ex52_1333.out")
st=$(awk '/^summary/ { for (i = 1; i <= NF; i++) if ($i ~ /^status=/) print substr($i, 8) }' "$tmp/ex52_1333.out")
check "ex52 th1=1.688345 w1=0.1 rtol=1e-3: status ${st:-none}, max_err_th ${e:-none} <= 0.1 (or a warning)" \
    "$(if [ "$st" = warning ]; then echo 0; elif [ "$st" = ok ] && le "${e:-1}" 0.1; then echo 0; else echo 1; fi)"
run seed3_fourbar5 family=fourbar seed=3 cell=5
c=$(class "$tmp/seed3_fourbar5.out")
check "fourbar seed=3 cell 5 (was silent): $c" "$(case $c in ok|warned) echo 0 ;; *) echo 1 ;; esac)"
# a fast spin of the fixed grid (crank cell 91: th1 = 1e-6, w1 = 20, R = 1e-3) whose energy grows
# 1e5-fold: stopped by the work check at t = 0.90 before the step rule (status -117), now it runs on
# and fails at t = 8.29 (-108, step size too small); it must not end ok or silent (the balance
# carried across the pass checks warns on the way, at t = 1.60 in `ex52 th1=1e-6 w1=20 rtol=1e-3`:
# doc/methods.md, "Work-energy balance")
run crank91 family=crank cell=91
c=$(class "$tmp/crank91.out")
check "crank cell 91 (fast spin, energy 1e5-fold): $c" "$(case $c in ok|silent|'') echo 1 ;; *) echo 0 ;; esac)"
# the fast spin of issue 19 (th1 = 4.269101e-6, w1 = 20, R = 1e-3; an earlier commit ended it ok
# with an energy error of 1.9e4 against 990, 166 rad off the reduced ODE by CVODE): the energy the
# stretches between the pass checks leave grows like a drift, and the balance carried across the
# checks warns at the first output past t = 1.82 (energy 1168 against 990; doc/methods.md,
# "Work-energy balance"); before, status ok at every output until the failure at t = 9.39
"$bindir/ex52" th1=4.269101e-6 w1=20 rtol=1e-3 atol=1e-3 nout=50 tf=2.5 stop_at_output=no >"$tmp/ex52_spin.out" 2>&1
st=$(awk '/^summary/ { for (i = 1; i <= NF; i++) if ($i ~ /^status=/) print substr($i, 8) }' "$tmp/ex52_spin.out")
e=$(awk '/^summary/ { for (i = 1; i <= NF; i++) if ($i ~ /^max_err_th=/) print substr($i, 12) }' "$tmp/ex52_spin.out")
check "ex52 th1=4.269101e-6 w1=20 rtol=1e-3 to t = 2.5: status ${st:-none} (max_err_th ${e:-none}), a warning naming the carried balance or a failure" \
    "$(if [ "$st" = warning ] && grep -q '^# warning: .*carried across the pass checks' "$tmp/ex52_spin.out"; then echo 0
       elif [ "$st" = failed ]; then echo 0; else echo 1; fi)"
# issue 19 item 7: `ex52 integrator=ida` at rtol 1e-8 and 1e-10 ended 124x-680x the tolerance with
# status ok; the same start (th1 = pi/2 at rest) and options in the trust driver against the
# reduced ODE by CVODE, bound 10x Dormand-Prince's error on it at the same rtol, with
# stop_at_output yes (ex52's) and no (the library's default): ok or warned (measured: ok at 1e-8,
# 7.4 and 17.7 error weights against 30.4; warned at 1e-10, 8.7 and 8.8 against 19.6)
for r in 1e-8 1e-10; do
    for s in yes no; do
        run ida_${r}_${s} family=crank th1=1.5707963267948966 w1=0 rtol=$r option.integrator=ida option.stop_at_output=$s
        c=$(class "$tmp/ida_${r}_${s}.out")
        check "ex52's start, integrator=ida stop_at_output=$s rtol $r: $c" \
            "$(case $c in ok|warned) echo 0 ;; *) echo 1 ;; esac)"
    done
done
# the order-3 problem with taylor_h = 1e-5 (drivers/order3, exact x = 1 + sin t): status ok with
# max_err = 10.8 at t = 0 after 608,734 steps (the Taylor weights' layer, doc/methods.md): now a
# warning that names the layer, or an error within 100 rtol
order3=$bindir/order3
"$order3" taylor_h=1e-5 >"$tmp/order3.out" 2>&1
st=$(awk '/^summary/ { for (i = 1; i <= NF; i++) if ($i ~ /^status=/) print substr($i, 8) }' "$tmp/order3.out")
err=$(awk '/^summary/ { for (i = 1; i <= NF; i++) if ($i ~ /^max_err=/) print substr($i, 9) }' "$tmp/order3.out")
check "order3 taylor_h=1e-5: status ${st:-none}, max_err ${err:-none} (warning naming the layer, or <= 1e-3)" \
    "$(if [ "$st" = warning ] && grep -q '^# warning: .*the layer of the Taylor weights' "$tmp/order3.out"; then echo 0
       elif [ "$st" = ok ] && le "${err:-1}" 1e-3; then echo 0; else echo 1; fi)"
# the four-bar through its folds: the cells that were silent before (index 2, position errors up
# to 6e-2 with status ok), and the family
run fourbar family=fourbar
for cell in 64 73 75 83 100 102; do
    c=$(awk -v c=$cell '$1 == c { print $8 }' "$tmp/fourbar.out")
    check "fourbar cell $cell (was silent): $c" "$(case $c in silent) echo 1 ;; '') echo 1 ;; *) echo 0 ;; esac)"
done
grep '^summary' "$tmp/fourbar.out"
# issue 19 item 5 against the one-coordinate ODE by CVODE: every index-2 cell (55 ... 108), and at
# index 3 the swing from rest 0.02 rad from a fold (fold+0.02) and the motion that turns back
# 6e-5 rad before one (turn6e-5), both stopped by the velocity-jump check before although right
# (6e-9 with jump_tol=0): ok or warned, never silent, false_alarm or failed
notok=$(awk '$1 ~ /^[0-9]+$/ && ($3 ~ /\/i2$/ || $3 ~ /^(fold\+0\.02|turn6e-5)\/i3$/) && $8 != "ok" && $8 != "warned" \
    { printf "%s%s:%s", sep, $1, $8; sep = " " }' "$tmp/fourbar.out")
n2=$(awk '$1 ~ /^[0-9]+$/ && ($3 ~ /\/i2$/ || $3 ~ /^(fold\+0\.02|turn6e-5)\/i3$/)' "$tmp/fourbar.out" | wc -l)
check "fourbar index 2 and the index-3 slow swing and turn-back: $n2 cells ok or warned (else: ${notok:-none})" \
    "$(if [ -z "$notok" ] && [ "$n2" -eq 66 ]; then echo 0; else echo 1; fi)"
# the four-bar at index 2 from seeded starts (issue 19): the run left the parallelogram branch at
# t ~ 3 with status ok at every output after a warning at t = 0.65 (error 1.05e8; the driver counts a
# later fold's error beyond the bound and 100x all errors before it as silent); index 3 from the same start
for sc in "77 107" "6 104" "77 53"; do
    set -- $sc
    run fourbar_s$1_$2 family=fourbar seed=$1 cell=$2
    c=$(class "$tmp/fourbar_s$1_$2.out")
    check "fourbar seed=$1 cell $2: $c" "$(case $c in ok|warned) echo 0 ;; *) echo 1 ;; esac)"
done
# the linear DAE S2 with its singular point inside one Dormand-Prince step (outputs inside it from
# the step's continuous extension, 10.9 and 22.2 error weights against a bound of 10, status ok)
for sc in "2026 97" "77 74"; do
    set -- $sc
    run linear_s$1_$2 family=linear seed=$1 cell=$2
    c=$(class "$tmp/linear_s$1_$2.out")
    check "linear seed=$1 cell $2: $c" "$(case $c in ok|warned) echo 0 ;; *) echo 1 ;; esac)"
done
# the linear index-2 DAEs with GB ~ t^2 and t^4 under the three methods: none silent (x1(0) was
# 885.5 off with status ok through the direct method at rtol 1e-8)
run linear family=linear
check "linear DAEs: 0 silent" "$(grep -q '^summary family=linear .* silent=0 ' "$tmp/linear.out"; echo $?)"
grep '^summary' "$tmp/linear.out"
# the chain with sliders, N = 16 at rtol 1e-6 (the augmented formulation's passes, 14x-2e4x
# the tolerance before), and the plain chain of 512 links at 1e-5 (silent before; judged against
# its reduced ODE with O(N) slopes, no longer undecided)
run chain16 family=chain cell=94
check "chain with sliders N = 16, rtol 1e-6: $(class "$tmp/chain16.out")" \
    "$(class "$tmp/chain16.out" | grep -qx -e ok -e warned; echo $?)"
run chain512 family=chain cell=51
check "plain chain N = 512, rtol 1e-5: $(class "$tmp/chain512.out")" \
    "$(class "$tmp/chain512.out" | grep -qx -e ok -e warned; echo $?)"
# issue 19 item 3 at its parameters: the plain chain of 512 and 1024 links at rtol = atol = 1e-6
# on [0, 1] (cells 52, 58), against the reduced ODE in the link angles (chain_plain_recursive,
# CVODE at 1e-13; the peer fails at 1e-11 there): ok or warned
for sc in "52 512" "58 1024"; do
    set -- $sc
    run chain_$2 family=chain cell=$1 tight_check=no
    check "plain chain N = $2, rtol 1e-6, t in [0, 1]: $(class "$tmp/chain_$2.out")" \
        "$(class "$tmp/chain_$2.out" | grep -qx -e ok -e warned; echo $?)"
done
# issue 19 item 4 on [0, 10]: the chain with sliders at N = 16 (a false branch alarm over a
# 2-second singular interval before) and N = 64 (the run left the branch), rtol 1e-6 (chain_long
# cells 70, 82; judged on the energy change and the violation against the reduced ODE's): not
# silent, not a false alarm
for sc in "70 16" "82 64"; do
    set -- $sc
    run chain_long_$2 family=chain_long cell=$1 tight_check=no
    c=$(class "$tmp/chain_long_$2.out")
    check "chain with sliders N = $2, rtol 1e-6, t in [0, 10]: $c" \
        "$(case $c in ok|warned|failed) echo 0 ;; *) echo 1 ;; esac)"
done
# issue 19 item 4, "at rtol 1e-10 the automatic drift limit stops correct runs": `chain n_links=4
# slider=yes tf=10 rtol=1e-10` is stopped by drift_tol at t = 9.17 (max |g| 7.7e-8 against 7.07e-8);
# with the checks off it ends with a warning and an energy change of 4.5e-4 against the reduced
# ODE's 3.3e-10 (1.9e5 units against a bound of 1.1e3; the peer's at 1e-10 2.7e-7): not a false
# alarm. The cell (chain_long slider N = 4 at R = 1e-10) must not be silent or a false alarm, and a
# failure must name drift_tol
run chain_long_drift family=chain_long rtols=1e-10 cell=10 tight_check=no
c=$(class "$tmp/chain_long_drift.out")
check "chain with sliders N = 4, rtol 1e-10, t in [0, 10]: $c" \
    "$(case $c in ok|warned) echo 0 ;; failed) grep -q '^#   message: .*drift_tol' "$tmp/chain_long_drift.out"; echo $? ;;
       *) echo 1 ;; esac)"
# eps and the regular modes of a large chain (issue 19, item 3): `chain n_links=1024 tf=1 nout=10
# rtol=1e-6` resolved eps = 4e-12 against sigma_min(GB)^2 = 5.5e-12 and changed the energy (which
# the exact motion conserves: no reference needed) by 0.33; the integration's own energy error at
# this rtol is 3.1e-3 (measured), 8e-4 at rtol 1e-10 with eps = 1e-14: the bound 1e-2 is 3x the
# former and 30x below the damped run's
"$bindir/chain" n_links=1024 tf=1 nout=10 rtol=1e-6 atol=1e-6 >"$tmp/chain1024.out" 2>&1
de=$(awk '/^summary/ { for (i = 1; i <= NF; i++) if ($i ~ /^energy_change=/) print substr($i, 15) }' "$tmp/chain1024.out")
st=$(awk '/^summary/ { for (i = 1; i <= NF; i++) if ($i ~ /^status=/) print substr($i, 8) }' "$tmp/chain1024.out")
check "chain n_links=1024 rtol 1e-6: status $st, energy change ${de:-none} <= 1e-2" \
    "$(awk -v d="${de:-x}" -v s="${st:-x}" 'BEGIN { exit !((s == "ok" || s == "warning") && d != "x" && d + 0 <= 1e-2) }'; echo $?)"
finish
