#!/bin/sh
# The size rule of the sources (a file over ~800 lines is split by concept) and the
# front's one advance over the integrator interface (issue 21): fails when any
# src/*.f90, drivers/*.f90 or drivers/*/*.f90 (the drivers' problems, common
# modules and drivers/trust/) has more than 800 lines, or when solver_advance in
# src/regdae_solver_front.f90 (with its internal procedures, comments left out)
# names an integrator: dopri5, IDA or Radau by name or option code, the core's
# slots (core%active, %stiff, %nonstiff) or a type test (select type / type is).
# Usage: check_file_sizes.sh SOURCE_DIR
src=${1:?usage: check_file_sizes.sh SOURCE_DIR}
limit=800
status=0
for f in "$src"/src/*.f90 "$src"/drivers/*.f90 "$src"/drivers/*/*.f90; do
    [ -f "$f" ] || continue   # a pattern that matched nothing
    lines=$(wc -l < "$f")
    if [ "$lines" -gt "$limit" ]; then
        echo "FAIL ${f#"$src"/}: $lines lines (at most $limit: split it by concept)"
        status=1
    fi
done
front=$src/src/regdae_solver_front.f90
body=$(sed -n '/^ *subroutine solver_advance(/,/^ *end subroutine solver_advance/p' "$front" | sed 's/!.*//')
if [ -z "$body" ]; then
    echo "FAIL solver_advance not found in $front"
    status=1
fi
named=$(printf '%s\n' "$body" |
    grep -inE 'dopri|(^|[^a-z0-9_])ida([^a-z0-9_]|$)|radau|integrator_(auto|ida|dopri5|radau)|core%active|%(non)?stiff([^a-z0-9_]|$)|select +type|type +is')
if [ -n "$named" ]; then
    echo "FAIL solver_advance names an integrator (write it over the interface of regdae_integrator):"
    printf '%s\n' "$named"
    status=1
fi
[ "$status" -eq 0 ] && echo "ok: every src/*.f90, drivers/*.f90 and drivers/*/*.f90 at most $limit lines; solver_advance names no integrator"
exit $status
