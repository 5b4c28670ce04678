#!/bin/sh
# Two programs that solve the same problem with the same options through two
# interfaces (the Fortran 2008 API and the C or FORTRAN 77 one) must both succeed
# and print the same output, digit for digit: the same table and the same step
# count show that the interface passed the same problem and options on.
# Usage: check_same_output.sh PROGRAM_A PROGRAM_B
a=${1:?usage: check_same_output.sh PROGRAM_A PROGRAM_B}
b=${2:?usage: check_same_output.sh PROGRAM_A PROGRAM_B}
out_a=$(mktemp) || exit 1
out_b=$(mktemp) || exit 1
trap 'rm -f "$out_a" "$out_b"' EXIT
"$a" >"$out_a" || { echo "$a failed (exit status $?):"; cat "$out_a"; echo "0 passed, 1 failed"; exit 1; }
"$b" >"$out_b" || { echo "$b failed (exit status $?):"; cat "$out_b"; echo "0 passed, 1 failed"; exit 1; }
if cmp -s "$out_a" "$out_b"; then
    cat "$out_a"
    echo "1 passed, 0 failed"
else
    echo "the outputs of $a and $b differ:"
    diff "$out_a" "$out_b" | head -20
    echo "0 passed, 1 failed"
    exit 1
fi
