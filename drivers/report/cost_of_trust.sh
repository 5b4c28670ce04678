#!/bin/sh
# The cost of trust on the slider crank (paper case, every option at its default but rtol = atol):
# the instructions of the solve (valgrind's callgrind, inclusive of the solver's init and advances:
# exact and repeatable, unlike the machine's timings) and the theta error, from ex52 with 1000
# outputs, interpolated (stop_at_output=no, as the bench times them), at rtol 1e-4 ... 1e-8: the
# defaults, the defaults with pass_check=no and with error_estimate=yes; with a second BIN_DIR of
# an older build (the baseline) its defaults too.
# Rows: 'label rtol max_err_th steps instructions'.
#
# Usage: cost_of_trust.sh BIN_DIR [BASELINE_BIN_DIR]    (about 1 minute; needs valgrind)
set -eu
bin=${1:?usage: cost_of_trust.sh BIN_DIR [BASELINE_BIN_DIR]}
base=${2:-}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# instructions LABEL BIN RTOL [EXTRA]: one row
instructions() {
    label=$1 dir=$2 r=$3
    shift 3
    # the solve: the solver's init and advance (regdae_solver is the trust layer from issue 19 on,
    # the solver front before)
    if nm "$dir/ex52" | grep -q '__regdae_solver_trust_MOD_trust_advance$'; then
        toggles="--toggle-collect=__regdae_solver_trust_MOD_trust_init_second --toggle-collect=__regdae_solver_trust_MOD_trust_advance"
    else
        toggles="--toggle-collect=__regdae_solver_front_MOD_solver_init_second --toggle-collect=__regdae_solver_front_MOD_solver_advance"
    fi
    # shellcheck disable=SC2086
    valgrind --tool=callgrind --callgrind-out-file="$tmp/cg" $toggles "$dir/ex52" rtol="$r" atol="$r" nout=1000 \
        stop_at_output=no "$@" > "$tmp/out" 2> /dev/null || true
    ir=$(callgrind_annotate "$tmp/cg" 2> /dev/null | awk '/PROGRAM TOTALS/ { gsub(",", "", $1); print $1 }')
    s=$(grep '^summary' "$tmp/out" | tr ' ' '\n')
    err=$(echo "$s" | awk -F= '$1 == "max_err_th" { print $2 }')
    steps=$(echo "$s" | awk -F= '$1 == "steps" { print $2 }')
    printf '%-22s %s %s %s %s\n' "$label" "$r" "$err" "$steps" "$ir"
}
echo "# cost of trust: ex52 (slider crank, paper case) rtol = atol, nout=1000 stop_at_output=no"
echo "# label rtol max_err_th steps instructions(init + advances, callgrind)"
for r in 1e-4 1e-5 1e-6 1e-7 1e-8; do
    [ -z "$base" ] || instructions baseline "$base" $r
    instructions defaults "$bin" $r
    instructions pass_check=no "$bin" $r pass_check=no
    instructions error_estimate=yes "$bin" $r error_estimate=yes
done
