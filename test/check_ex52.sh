#!/bin/sh
# Driver-level checks of ex52, the slider crank (acceptance points of Example 5.2).
# Usage: check_ex52.sh path/to/ex52
driver=${1:?usage: check_ex52.sh path/to/ex52}
tmp=$(mktemp -d) || exit 1
trap 'rm -rf "$tmp"' EXIT INT TERM
. "$(dirname "$0")/check_lib.sh"

# 1. Index 3, the paper's parameters: all six singular passes on the physical branch.
run tr3 method=trust_region index=3 gamma0=2e6 gamma1=2e3 eps=1e-6 rtol=1e-5 atol=1e-5
[ "$(rc tr3)" = 0 ] && [ "$(field tr3 status)" = ok ] && le 10 "$(field tr3 t_end)" && [ "$(field tr3 singular_passes)" = 6 ]
check "trust_region index 3: ok at t = 10 with 6 singular passes" $?
le "$(field tr3 max_branch_dev)" 1e-3 && le "$(field tr3 max_err_th)" 1e-2
check "trust_region index 3: max_branch_dev=$(field tr3 max_branch_dev) <= 1e-3, max_err_th=$(field tr3 max_err_th) <= 1e-2" $?
rows=$(grep -v '^#' "$tmp/tr3.out" | grep -vc '^summary')
cols=$(grep -v '^#' "$tmp/tr3.out" | grep -v '^summary' | awk '{ print NF }' | sort -u)
[ "$rows" = 1001 ] && [ "$cols" = 8 ]
check "table of 1001 rows x 8 columns" $?
for key in method index status t_end max_err_th max_abs_g3 max_energy_err max_branch_dev singular_passes steps \
    res_evals jac_evals err_test_fails conv_fails seconds; do
    [ -n "$(field tr3 $key)" ] || bad "summary field $key"
done

# 2. The regularization error is controllable: eps = 1e-12, rtol = atol = 1e-10.
run tight method=trust_region index=3 eps=1e-12 rtol=1e-10 atol=1e-10
[ "$(field tight status)" = ok ] && le "$(field tight max_err_th)" 1e-6
check "eps=1e-12, tol=1e-10: max_err_th=$(field tight max_err_th) <= 1e-6" $?

# 3. Index 2 trust region, gamma = 1e6 (Fig. 5.11): on the physical branch.
run tr2 method=trust_region index=2 gamma=1e6 rtol=1e-6 atol=1e-6 eps=1e-6
[ "$(rc tr2)" = 0 ] && [ "$(field tr2 status)" = ok ] && le 10 "$(field tr2 t_end)" && le "$(field tr2 max_branch_dev)" 1e-2
check "trust_region index 2 gamma=1e6: ok, max_branch_dev=$(field tr2 max_branch_dev) <= 1e-2" $?

# 4. Direct and Baumgarte, index 2: never a good-looking run off the physical branch.
for m in direct baumgarte; do
    for g in 1e3 1e6; do
        run "${m}_$g" method=$m index=2 gamma=$g eps=1e-6
        st=$(field "${m}_$g" status); dev=$(field "${m}_$g" max_branch_dev)
        if [ "$st" = ok ]; then
            [ "$(rc "${m}_$g")" = 0 ] && le "$dev" 0.1
        else
            [ "$(rc "${m}_$g")" != 0 ] && grep -q '^# \(error\|warning\):' "$tmp/${m}_$g.out"
        fi
        check "$m index 2 gamma=$g: status=$st max_branch_dev=$dev reported consistently" $?
    done
done

# 5. The explicit integrator on the eliminated regularized system (moderate gamma: not stiff).
run rk method=trust_region index=3 integrator=dopri5 gamma0=200 gamma1=20 eps=1e-12 rtol=1e-8 atol=1e-8
[ "$(rc rk)" = 0 ] && [ "$(field rk singular_passes)" = 6 ] && le "$(field rk max_err_th)" 1e-6 && \
    le "$(field rk max_branch_dev)" 1e-3
check "integrator=dopri5 gamma1=20: max_err_th=$(field rk max_err_th) <= 1e-6, 6 passes" $?
run rkbad integrator=dopri5 formulation=multiplier
[ "$(rc rkbad)" = 2 ] && grep -q 'dopri5 needs formulation=eliminated' "$tmp/rkbad.err"
check "integrator=dopri5 with the multiplier formulation: refused" $?

# 6. Bad arguments.
run badindex index=4
[ "$(rc badindex)" = 2 ] && grep -q index "$tmp/badindex.err"
check "index=4: exit 2, message names index" $?
run badth th1=abc
[ "$(rc badth)" = 2 ] && grep -q th1 "$tmp/badth.err"
check "th1=abc: exit 2, message names th1" $?
finish
