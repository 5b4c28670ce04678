# Helpers for the driver checks (sourced, POSIX sh). Each check script sets
# `driver` and `tmp`, calls `run NAME ARGS...`, reads summary fields with
# `field NAME KEY`, and records results with `check DESCRIPTION STATUS`.
passed=0
failed=0
ok()   { passed=$((passed + 1)); echo "  PASS $1"; }
bad()  { failed=$((failed + 1)); echo "  FAIL $1"; }
check() { if [ "$2" = 0 ]; then ok "$1"; else bad "$1"; fi; }   # check NAME STATUS
# run NAME ARGS...: output in $tmp/NAME.out, stderr in $tmp/NAME.err, exit code in $tmp/NAME.rc
run() {
    name=$1; shift
    "$driver" "$@" >"$tmp/$name.out" 2>"$tmp/$name.err"
    echo $? >"$tmp/$name.rc"
}
field() { tail -n 1 "$tmp/$1.out" | tr ' ' '\n' | sed -n "s/^$2=//p"; }   # field NAME KEY
rc() { cat "$tmp/$1.rc"; }
# usable NAME: status ok, or warning (x valid, the tolerance maybe not met) with its '# warning:' line
usable() { case $(field "$1" status) in ok) true ;; warning) grep -q '^# warning:' "$tmp/$1.out" ;; *) false ;; esac; }
le() { awk -v a="$1" -v b="$2" 'BEGIN { exit !(a + 0 <= b + 0) }'; }   # le A B: A <= B
lt() { awk -v a="$1" -v b="$2" 'BEGIN { exit !(a + 0 < b + 0) }'; }    # lt A B: A < B
finish() { echo "$passed passed, $failed failed"; [ "$failed" = 0 ]; }
