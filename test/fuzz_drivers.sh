#!/bin/sh
# Fuzz the drivers' command lines: random key=value arguments from test/fuzz/corpus.txt
# (valid and invalid keys and values, NaN, Inf, overflows, huge counts, empty and malformed
# arguments). Every run must end with exit 0 (and a summary line), 1 (a summary line or a
# message on stderr) or 2 (a message on stderr): no signal, no hang, no sanitizer report.
# Usage: fuzz_drivers.sh BINDIR [SEED] [COUNT] [TIMEOUT]
#   ctest runs a fixed seed; a long run: sh test/fuzz_drivers.sh build/bin $(date +%s) 100000
# A failing run is printed with its arguments (tab-separated) so that it can be replayed.
bin=${1:?usage: fuzz_drivers.sh BINDIR [SEED] [COUNT] [TIMEOUT]}
seed=${2:-1}
count=${3:-300}
limit=${4:-120}
here=$(dirname "$0")
tmp=$(mktemp -d) || exit 1
trap 'rm -rf "$tmp"' EXIT INT TERM
. "$here/check_lib.sh"
ASAN_OPTIONS=${ASAN_OPTIONS:-exitcode=86:detect_leaks=1}
UBSAN_OPTIONS=${UBSAN_OPTIONS:-exitcode=87:print_stacktrace=1}
LSAN_OPTIONS=${LSAN_OPTIONS:-exitcode=88}
export ASAN_OPTIONS UBSAN_OPTIONS LSAN_OPTIONS

# One command line per output line, fields separated by tabs: program, then its arguments.
awk -v seed="$seed" -v count="$count" '
function pick(list, n) { return list[1 + int(rand() * n)] }
function token(t,    s, i) {
    if (t == "<empty>") return ""
    if (t == "<long>") { s = ""; for (i = 0; i < 500; i++) s = s "1234567890"; return s }
    if (t == "<huge>") { s = "1"; for (i = 0; i < 400; i++) s = s "0"; return s }
    return t
}
function knows(programs, p) { return programs == "*" ? (p in solver) : index("," programs ",", "," p ",") > 0 }
$1 == "program" { np++; prog[np] = $2; pre = ""; for (i = 3; i <= NF; i++) pre = pre "\t" $i; prefix[$2] = pre }
$1 == "key" { nk++; kprog[nk] = $2; kname[nk] = $3; kvals[nk] = ""; for (i = 4; i <= NF; i++) kvals[nk] = kvals[nk] " " $i }
$1 == "values" { for (i = 2; i <= NF; i++) pool[++nv] = $i }
END {
    split("ex51 ex52 pendulum order3 redundant singular_mass", s, " ")
    for (i in s) solver[s[i]] = 1
    srand(seed)
    for (c = 0; c < count; c++) {
        p = pick(prog, np)
        line = p prefix[p]
        nargs = int(rand() * 5)
        for (a = 0; a < nargs; a++) {
            r = rand()
            if (r < 0.06) { line = line "\t" pick(pool, nv); continue }          # no "="
            if (r < 0.08) { line = line "\t=" token(pick(pool, nv)); continue }  # no key
            # a key this driver knows (mostly), or any key
            do k = 1 + int(rand() * nk); while (!knows(kprog[k], p) && rand() < 0.9)
            nvals = split(kvals[k], vals, " ")
            v = (rand() < 0.6 && nvals > 0) ? pick(vals, nvals) : pick(pool, nv)
            line = line "\t" token(kname[k]) "=" token(v)
        }
        print line
    }
}' "$here/fuzz/corpus.txt" >"$tmp/cases"

tab=$(printf '\t')
n=0
exits0=0
exits1=0
exits2=0
set -f
while IFS= read -r line; do
    n=$((n + 1))
    IFS=$tab
    # shellcheck disable=SC2086
    set -- $line
    IFS=' '
    program=$1
    shift
    timeout "$limit" "$bin/$program" "$@" >"$tmp/out" 2>"$tmp/err"
    code=$?
    what="run $n: $program $*"
    if [ "$code" = 124 ]; then
        bad "$what: no end within $limit s"
    elif [ "$code" != 0 ] && [ "$code" != 1 ] && [ "$code" != 2 ]; then
        bad "$what: exit $code"
        tail -n 15 "$tmp/err"
    elif grep -q 'Sanitizer\|runtime error\|Fortran runtime error\|Program received signal' "$tmp/err"; then
        bad "$what: a run-time error report"
        grep -m 5 'Sanitizer\|runtime error\|Program received' "$tmp/err"
    elif [ "$code" = 0 ] && ! grep -q '^summary' "$tmp/out"; then
        bad "$what: exit 0 without a summary line"
    elif [ "$code" = 1 ] && ! { grep -q '^summary' "$tmp/out" || [ -s "$tmp/err" ]; }; then
        bad "$what: exit 1 with neither a summary line nor a message"
    elif [ "$code" = 2 ] && ! grep -q "^$program: " "$tmp/err"; then
        bad "$what: exit 2 without a message naming the program"
    else
        passed=$((passed + 1))
        eval "exits$code=\$((exits$code + 1))"
    fi
done <"$tmp/cases"
set +f
# Values are taken as given: a blank before or after one (an argument "rtol=1e-3 " in
# quotes) is refused with exit 2 and a message naming the key, in the solver's options,
# the drivers' own numbers and counts, and nout.
for arg in 'rtol=1e-3 ' 'rtol= 1e-3' 'tf=3 ' 'nout=10 ' 'method=direct ' 'max_order=2 '; do
    timeout "$limit" "$bin/ex52" "$arg" >"$tmp/out" 2>"$tmp/err"
    code=$?
    key=${arg%%=*}
    if [ "$code" = 2 ] && grep -q "^ex52: bad value \".*\" for $key: a blank before or after it" "$tmp/err"; then
        passed=$((passed + 1))
    else
        bad "ex52 \"$arg\": exit $code, expected 2 and the message on the blank"
        cat "$tmp/err"
    fi
done
echo "fuzz: seed $seed, $n command lines; exit 0: $exits0, exit 1: $exits1, exit 2: $exits2"
finish
