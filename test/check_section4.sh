#!/bin/sh
# Driver-level checks of section 4 and the rates: order3, redundant, singular_mass, rates.
# Usage: check_section4.sh BINDIR
bin=${1:?usage: check_section4.sh BINDIR}
tmp=$(mktemp -d) || exit 1
trap 'rm -rf "$tmp"' EXIT INT TERM
. "$(dirname "$0")/check_lib.sh"

# Order 3 (index 4) through t = 0: error against x = 1 + sin t. The paper's form uses only G,
# so its error has a floor O(h^2) in taylor_h (measured 4.5e-5 at h = 1e-2, 4.2e-4 at 3e-2).
driver=$bin/order3
run o3 eps=1e-9 rtol=1e-8 atol=1e-8
[ "$(field o3 status)" = ok ] && le 1 "$(field o3 t_end)" && le "$(field o3 max_err)" 1e-4
check "order3: through t = 0, max_err=$(field o3 max_err) <= 1e-4" $?
run o3h eps=1e-9 rtol=1e-8 atol=1e-8 taylor_h=3e-2
awk -v a="$(field o3h max_err)" -v b="$(field o3 max_err)" 'BEGIN { r = a / b; exit !(r > 6 && r < 13) }'
check "order3: error floor ~ h^2 (ratio $(field o3h max_err) / $(field o3 max_err) for h 3e-2 / 1e-2 in [6, 13])" $?

# Redundant constraints kept: eliminated formulation (the default), against the reduced ODE.
driver=$bin/redundant
run red6 eps=1e-6
[ "$(rc red6)" = 0 ] && [ "$(field red6 status)" = ok ] && le "$(field red6 max_err)" 1e-3 && \
    le "$(field red6 max_diff_single)" 1e-3
check "redundant eps=1e-6: max_err=$(field red6 max_err) <= 1e-3, max_diff_single=$(field red6 max_diff_single) <= 1e-3" $?
run red12 eps=1e-12
[ "$(rc red12)" = 0 ] && le "$(field red12 max_err)" 1e-4
check "redundant eps=1e-12: max_err=$(field red12 max_err) <= 1e-4" $?

# Singular mass matrix through (4.11): fixed carrier against the pendulum; mu = 0 refused;
# a massless coordinate that must accelerate is flagged.
driver=$bin/singular_mass
run sm rtol=1e-10 atol=1e-10 eps=1e-12
[ "$(rc sm)" = 0 ] && le "$(field sm max_err)" 1e-6
check "singular_mass: max_err=$(field sm max_err) <= 1e-6 against the hand-eliminated model" $?
run sm0 mass_damping=0
[ "$(rc sm0)" = 1 ] && grep -q 'mass matrix' "$tmp/sm0.out"
check "singular_mass mass_damping=0: refused, M not positive definite" $?
run smf carrier=follower
[ "$(rc smf)" = 1 ] && [ "$(field smf status)" = failed ] && grep -q '^# warning:' "$tmp/smf.out"
check "singular_mass carrier=follower: flagged as outside (4.11)" $?

# Rates: Example 5.1 at gamma = 1e3. Most runs warn that the pass at t = 0 is not resolved to
# rtol (the pass check): status=warning, with a '# warning:' line per warned run; no run fails.
driver=$bin/rates
run rates problem=EX51 gamma=1e3
p=$(grep '^fit problem=EX51 method=direct gamma=1.0000E+03 region=inside' "$tmp/rates.out" | sed 's/.* p=\([^ ]*\).*/\1/')
[ "$(rc rates)" = 0 ] && usable rates && [ "$(field rates failed_runs)" = 0 ] && le 0.3 "$p" && le "$p" 0.42
check "rates EX51 (3.2): inside order p=$p in [0.30, 0.42]" $?
finish
