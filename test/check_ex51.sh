#!/bin/sh
# Driver-level checks of ex51 (the acceptance points of Example 5.1).
# Usage: check_ex51.sh path/to/ex51
# Prints one line per check and 'N passed, N failed'; exits 1 on a failure.
ex51=${1:?usage: check_ex51.sh path/to/ex51}
tmp=$(mktemp -d) || exit 1
trap 'rm -rf "$tmp"' EXIT INT TERM
driver=$ex51
. "$(dirname "$0")/check_lib.sh"

# 1. Trust region reaches t = 1 at eps = 1e-6 and 1e-9; the error at 1e-9 is <= 1e-2 and smaller.
run tr6 method=trust_region eps=1e-6
run tr9 method=trust_region eps=1e-9
for n in tr6 tr9; do
    [ "$(rc $n)" = 0 ] && [ "$(field $n status)" = ok ] && le 1 "$(field $n t_end)"
    check "trust_region $n reaches t = 1 (max_err_x=$(field $n max_err_x))" $?
done
le "$(field tr9 max_err_x)" 1e-2
check "trust_region eps=1e-9: max_err_x <= 1e-2" $?
lt "$(field tr9 max_err_x)" "$(field tr6 max_err_x)"
check "trust_region: max_err_x(eps=1e-9) < max_err_x(eps=1e-6)" $?

# 2. Output shape: nout+1 rows of 5 numbers, '#' lines, the summary last.
rows=$(grep -v '^#' "$tmp/tr6.out" | grep -vc '^summary')
cols=$(grep -v '^#' "$tmp/tr6.out" | grep -v '^summary' | awk '{ print NF }' | sort -u)
[ "$rows" = 201 ] && [ "$cols" = 5 ] && tail -n 1 "$tmp/tr6.out" | grep -q '^summary method=trust_region status=ok t_end='
check "table of 201 rows x 5 columns, summary line last" $?
for key in method status t_end max_err_x steps res_evals jac_evals err_test_fails conv_fails seconds; do
    [ -n "$(field tr6 $key)" ] || { bad "summary field $key"; continue; }
done

# 3. Direct: passes with B = t (GB = t^2 >= 0); refuses B = -t with a clear message. Passing may
#    end in status=warning (the pass check could not resolve the pass at t = 0 to the tolerance).
run dpsd method=direct orientation=psd
[ "$(rc dpsd)" = 0 ] && usable dpsd && le 1 "$(field dpsd t_end)"
check "direct, orientation=psd reaches t = 1 (status=$(field dpsd status))" $?
run dpaper method=direct orientation=paper
[ "$(rc dpaper)" != 0 ] && [ "$(field dpaper status)" = failed ] && grep -q '^# error:.*positive semidefinite' "$tmp/dpaper.out"
check "direct, orientation=paper stops: GB not positive semidefinite, non-zero exit" $?

# 4. Baumgarte: whatever happens at t = 0 is reported truthfully (a warning, e.g. the multiplier
#    undefined at t = 0, is a run that goes on: exit 0, and a '# warning:' line).
for form in multiplier eliminated; do
    run bg_$form method=baumgarte formulation=$form
    st=$(field bg_$form status); r=$(rc bg_$form); te=$(field bg_$form t_end)
    if [ "$st" = ok ] || [ "$st" = warning ]; then
        [ "$r" = 0 ] && usable bg_$form && le 1 "$te" && le "$(field bg_$form max_err_x)" 1e-3
    else
        [ "$st" = failed ] && [ "$r" != 0 ] && lt "$te" 1 && grep -q '^# error:' "$tmp/bg_$form.out"
    fi
    check "baumgarte $form: status=$st t_end=$te reported consistently" $?
done

# 5. Both formulations and both least-squares solvers agree to 10 rtol (1e-4), under one integrator
#    (IDA) and the paper's gamma = 100 and eps = 1e-6 (the bound was measured with them).
for form in multiplier eliminated; do
    for lsq in normal stacked; do
        run "agree_${form}_$lsq" formulation=$form lsq=$lsq integrator=ida gamma=100 eps=1e-6
        grep -v '^#' "$tmp/agree_${form}_$lsq.out" | grep -v '^summary' | awk '{ print $2 }' >"$tmp/x_${form}_$lsq"
    done
done
maxdiff=$(paste "$tmp"/x_multiplier_normal "$tmp"/x_multiplier_stacked "$tmp"/x_eliminated_normal \
    "$tmp"/x_eliminated_stacked | awk '{ for (i = 2; i <= 4; i++) { d = $i - $1; if (d < 0) d = -d; if (d > m) m = d } }
    END { printf "%.3e", m + 0 }')
le "$maxdiff" 1e-4 && [ "$(wc -l <"$tmp/x_eliminated_stacked")" = 201 ]
check "formulations x least-squares solvers: max |x difference| = $maxdiff <= 1e-4" $?

# 6. Bad arguments and inconsistent initial values.
run unknown epsilon=1e-6
[ "$(rc unknown)" = 2 ] && grep -q epsilon "$tmp/unknown.err"
check "unknown key: exit 2, message names it" $?
run badvalue method=newton
[ "$(rc badvalue)" = 2 ] && grep -q newton "$tmp/badvalue.err"
check "bad value: exit 2, message names it" $?
run negeps eps=-1
[ "$(rc negeps)" = 2 ] && grep -q eps "$tmp/negeps.err"
check "eps < 0: exit 2, message names eps" $?
run zerogamma gamma=0
[ "$(rc zerogamma)" = 2 ] && grep -q gamma "$tmp/zerogamma.err"
check "gamma = 0: exit 2, message names gamma" $?
run nan eps=nan
[ "$(rc nan)" = 2 ]
check "eps = nan: exit 2" $?
run noeq trust_region
[ "$(rc noeq)" = 2 ] && grep -q 'key=value' "$tmp/noeq.err"
check "argument without '=': exit 2" $?
run inconsistent x0=0.5
[ "$(rc inconsistent)" = 1 ] && [ "$(field inconsistent status)" = failed ] && grep -q 'inconsistent' "$tmp/inconsistent.out"
check "inconsistent x0: status=failed, exit 1" $?

finish
