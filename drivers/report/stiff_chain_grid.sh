#!/bin/sh
# Issue 21 item 3's judge of integrator=auto on small stiff chains (drivers/chain.f90 with
# springs and dashpots under the joints), one cell per line: the defaults (or ARGS) against a
# reference run (integrator=ida, rtol = atol = 1e-11, eps = 1e-14) and against the plain IDA
# band peer (peer=yes) at the same rtol.
# Usage: stiff_chain_grid.sh BINDIR [SEED] [ARGS...]
#   without SEED (or SEED=0): the fixed grid, mass in {1e-3, 1e-2, 1e-1}, stiffness in
#   {1e3, 1e4, 1e5}, damping in {1, 10}, n_links in {2, 3, 4, 6, 8}, R in {1e-4, 1e-6, 1e-8}
#   (270 cells); with SEED: 90 cells, mass, stiffness and damping log-uniform over the same
#   ranges, n_links and R drawn from the same sets (awk's srand(SEED)).
# Rows: 'cell n_links mass stiffness damping R status err err_peer class steps switches engine_end'
# err: the largest distance of the free end from the reference's over the 101 outputs of
# [0, 1]; class ok / silent (status ok, err > 10 max(R, err_peer)) / warned / failed (the
# run failed or stopped early); then a line '# classes ok=.. silent=.. warned=.. failed=..'.
# CACHE=DIR (environment): the reference's and the peer's tables kept in DIR and read from it
# (they do not depend on the build's integrator=auto: for a before/after comparison).
set -eu
bin=${1:?usage: stiff_chain_grid.sh BINDIR [SEED] [ARGS...]}
seed=${2:-0}
[ $# -ge 2 ] && shift 2 || shift $#
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cache=${CACHE:-$work}
if [ "$seed" = 0 ]; then
    for m in 1e-3 1e-2 1e-1; do for k in 1e3 1e4 1e5; do for c in 1 10; do for n in 2 3 4 6 8; do
        for r in 1e-4 1e-6 1e-8; do echo "$n $m $k $c $r"; done
    done; done; done; done >"$work/cells"
else
    awk -v s="$seed" 'BEGIN { srand(s); split("2 3 4 6 8", ns, " "); split("1e-4 1e-6 1e-8", rs, " ")
        for (i = 1; i <= 90; i++) printf "%d %.3e %.3e %.3e %s\n", ns[1 + int(5 * rand())],
            10 ^ (-3 + 2 * rand()), 10 ^ (3 + 2 * rand()), 10 ^ rand(), rs[1 + int(3 * rand())] }' >"$work/cells"
fi
# xy FILE: the table's (x_end, y_end) rows of a chain run
xy() { awk '!/^#/ && !/^summary/ && NF >= 3 { print $2, $3 }' "$1"; }
# dist A B: the largest distance between two xy files of 101 rows (-1 otherwise)
dist() { awk 'FNR == 1 { f++ } f == 1 { x[FNR] = $1; y[FNR] = $2; n1 = FNR; next }
    { d = sqrt(($1 - x[FNR]) ^ 2 + ($2 - y[FNR]) ^ 2); if (d > e) e = d; n2 = FNR }
    END { printf "%.3e", (n1 == 101 && n2 == 101) ? e : -1 }' "$1" "$2"; }
field() { sed -n "s/.* $1=\([^ ]*\).*/\1/p" "$2"; }
i=0
ok=0; silent=0; warned=0; failed=0
while read -r n m k c r; do
    i=$((i + 1))
    prob="n_links=$n mass=$m stiffness=$k damping=$c tf=1 nout=100"
    ref="$cache/ref_${n}_${m}_${k}_$c.xy"
    peer="$cache/peer_${n}_${m}_${k}_${c}_$r.xy"
    # shellcheck disable=SC2086
    {
        if [ ! -s "$ref" ]; then
            "$bin/chain" $prob rtol=1e-11 atol=1e-11 eps=1e-14 integrator=ida >"$work/ref" 2>&1 </dev/null || true
            xy "$work/ref" >"$ref"
        fi
        if [ ! -s "$peer" ]; then
            "$bin/chain" $prob rtol="$r" atol="$r" peer=yes >"$work/peer" 2>&1 </dev/null || true
            xy "$work/peer" >"$peer"
        fi
        "$bin/chain" $prob rtol="$r" atol="$r" "$@" >"$work/run" 2>&1 </dev/null || true
    }
    xy "$work/run" >"$work/run.xy"
    err=$(dist "$ref" "$work/run.xy")
    errp=$(dist "$ref" "$peer")
    st=$(field status "$work/run"); st=${st:-failed}
    class=$(awk -v s="$st" -v e="$err" -v p="$errp" -v r="$r" 'BEGIN {
        if (s == "failed" || e < 0) print "failed"; else if (s == "warning") print "warned";
        else if (e > 10 * (p > r ? p : r)) print "silent"; else print "ok" }')
    eval "$class=\$(($class + 1))"
    echo "$i $n $m $k $c $r $st $err $errp $class $(field steps "$work/run") $(field switches "$work/run") $(field engine_end "$work/run")"
done <"$work/cells"
echo "# classes ok=$ok silent=$silent warned=$warned failed=$failed"
