#!/bin/sh
# The residual a fold leaves (doc/methods.md, "The residual a fold leaves"): the chains with
# sliders on [0, 10] (drivers/trust family chain_long: err = the energy change and the constraint
# violation at the outputs in units of the reduced ODE's energy change (CVODE at 1e-13) plus R times
# the scales), where one pair's fold follows another's within the stabilization's memory. Before the
# projection before the next fold: N = 4 at R = 1e-8 2316 units (energy change 4.5e-4, the reduced
# ODE's 3.3e-10), N = 8 at R = 1e-6 4937 units (bound 515), at R = 1e-8 4.6e5 units (0.17).
# Usage: check_slider_passes.sh BIN_DIR
set -u
driver=$1/trust
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
. "$(dirname "$0")/check_lib.sh"
# column COLUMN NAME: a column of the cell's row (8: class, 9: err, 11: bound)
column() { awk -v c="$1" '$1 ~ /^[0-9]+$/ { print $c }' "$tmp/$2.out"; }
# cell R CELL: chain_long at R with N <= 8 (cell 5: the slider chain of 4 links, 6: of 8 links)
cell() { run "n$2_r$1" family=chain_long rtols="$1" max_links=8 cell="$2" tight_check=no; }
cell 1e-8 5
e=$(column 9 n5_r1e-8)
check "slider chain N = 4, R = 1e-8: $(column 8 n5_r1e-8), err ${e:-none} <= 100 units (2316 before)" \
    "$(le "${e:-1e300}" 100; echo $?)"
cell 1e-6 6
e=$(column 9 n6_r1e-6)
check "slider chain N = 8, R = 1e-6: $(column 8 n6_r1e-6), err ${e:-none} <= bound $(column 11 n6_r1e-6) (4937 before)" \
    "$(le "${e:-1e300}" "$(column 11 n6_r1e-6)"; echo $?)"
cell 1e-8 6
e=$(column 9 n6_r1e-8)
check "slider chain N = 8, R = 1e-8: $(column 8 n6_r1e-8), err ${e:-none} <= 1e4 units (4.6e5 before)" \
    "$(le "${e:-1e300}" 1e4; echo $?)"
finish
