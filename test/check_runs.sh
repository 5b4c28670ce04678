#!/bin/sh
# Run a list of driver command lines (test/runs/*.txt: 'EXPECTED_EXIT PROGRAM ARGS...'
# per line, optionally followed by ' ~ TEXT', a text the output or the message must
# contain) and check that each ends with its expected exit status, with a summary line
# on stdout or a message on stderr, and that no sanitizer or valgrind report appears.
# Usage: check_runs.sh BINDIR LIST [WRAPPER...]   (WRAPPER: e.g. valgrind and its options)
bin=${1:?usage: check_runs.sh BINDIR LIST [WRAPPER...]}
list=${2:?usage: check_runs.sh BINDIR LIST [WRAPPER...]}
shift 2
tmp=$(mktemp -d) || exit 1
trap 'rm -rf "$tmp"' EXIT INT TERM
. "$(dirname "$0")/check_lib.sh"
# Sanitizer reports abort the run with their own exit codes (not 0, 1 or 2).
ASAN_OPTIONS=${ASAN_OPTIONS:-exitcode=86:detect_leaks=1:abort_on_error=0}
UBSAN_OPTIONS=${UBSAN_OPTIONS:-exitcode=87:print_stacktrace=1}
LSAN_OPTIONS=${LSAN_OPTIONS:-exitcode=88}
export ASAN_OPTIONS UBSAN_OPTIONS LSAN_OPTIONS
n=0
while read -r expected program args; do
    case $expected in '#'* | '') continue ;; esac
    n=$((n + 1))
    pattern=""
    case $args in *' ~ '*) pattern=${args#* ~ }; args=${args%% ~ *} ;; esac
    # shellcheck disable=SC2086
    "$@" "$bin/$program" $args >"$tmp/out" 2>"$tmp/err"
    code=$?
    if [ "$code" != "$expected" ]; then
        bad "$program $args: exit $code, expected $expected"
        tail -n 20 "$tmp/err"
    elif grep -q 'Sanitizer\|runtime error\|ERROR SUMMARY: [1-9]\|definitely lost: [1-9]' "$tmp/err"; then
        bad "$program $args: a sanitizer or valgrind report"
        grep -m 5 'Sanitizer\|runtime error\|ERROR SUMMARY\|lost:' "$tmp/err"
    elif ! { grep -q '^summary' "$tmp/out" || [ "$program" = example_circle ] || [ -s "$tmp/err" ]; }; then
        bad "$program $args: neither a summary line nor a message on stderr"
    elif [ -n "$pattern" ] && ! cat "$tmp/out" "$tmp/err" | grep -qF -- "$pattern"; then
        bad "$program $args: the output does not say \"$pattern\""
        grep -h '^# error\|^[a-z0-9_]*: ' "$tmp/out" "$tmp/err" | head -n 3
    else
        ok "$program $args (exit $code)"
    fi
done <"$list"
[ "$n" -gt 0 ] || bad "no runs in $list"
finish
