#!/bin/sh
# include/regdae.h must define every status code of src/regdae_status.f90 and
# every option and pattern code of the Fortran modules with the same value
# (REGDAE_<NAME> for regdae_<name>, REGDAE_METHOD_DIRECT for method_direct, ...),
# and no status code the Fortran side does not have; and every warning has an
# IDID of its own in the DASSL door (src/regdae_dassl.f90, doc/api.md's IDID table).
# Usage: check_header.sh SOURCE_DIR
src=${1:?usage: check_header.sh SOURCE_DIR}
header=$src/include/regdae.h
tmp=$(mktemp) || exit 1
trap 'rm -f "$tmp"' EXIT

# "NAME VALUE" for the Fortran constants, upper-cased with the REGDAE_ prefix.
{
    sed -n 's/^ *integer, parameter, public :: regdae_\([a-z_0-9]*\) = \(-\{0,1\}[0-9]*\).*/\1 \2/p' \
        "$src/src/regdae_status.f90"
    sed -n 's/^ *integer, parameter, public :: \(\(method\|formulation\|linear_solver\|lsq\|exclusion\|integrator\|excluded\)_[a-z_0-9]*\) = \([0-9]*\).*/\1 \3/p' \
        "$src/src/regdae_options.f90" "$src/src/regdae_damped_lsq.f90"
    sed -n 's/^ *integer, parameter, public :: \(pattern_[a-z_]*\) = \([0-9]*\).*/\1 \2/p' "$src/src/regdae_c_api.f90"
} | awk '{ print "REGDAE_" toupper($1), $2 }' >"$tmp"

failed=0
passed=0
while read -r name value; do
    if grep -q "^#define $name $value\( .*\)\{0,1\}\$" "$header"; then
        passed=$((passed + 1))
    else
        echo "include/regdae.h: expected \"#define $name $value\""
        failed=$((failed + 1))
    fi
done <"$tmp"
# Status codes in the header that the Fortran side does not have.
for name in $(sed -n 's/^#define \(REGDAE_\(SUCCESS\|WARN_[A-Z_]*\|ERR_[A-Z_]*\)\) .*/\1/p' "$header"); do
    if grep -q "^$name " "$tmp"; then
        passed=$((passed + 1))
    else
        echo "include/regdae.h: $name is not a status code of src/regdae_status.f90"
        failed=$((failed + 1))
    fi
done
# Every warning (a positive status) has a door of its own in DREGDAE: a case of
# src/regdae_dassl.f90 that gives it its IDID, and a row of doc/api.md's IDID table
# that names it.
idid_table=$(sed -n '/^| IDID | meaning |$/,/^$/p' "$src/doc/api.md")
for name in $(sed -n 's/^ *integer, parameter, public :: \(regdae_[a-z_0-9]*\) = [1-9][0-9]*.*/\1/p' \
    "$src/src/regdae_status.f90"); do
    if grep -q "^ *case ($name)" "$src/src/regdae_dassl.f90"; then
        passed=$((passed + 1))
    else
        echo "src/regdae_dassl.f90: the warning $name has no IDID of its own (no \"case ($name)\" in close_call)"
        failed=$((failed + 1))
    fi
    if printf '%s\n' "$idid_table" | grep -q "\`$name\`"; then
        passed=$((passed + 1))
    else
        echo "doc/api.md: the IDID table (section 8) has no row naming the warning \`$name\`"
        failed=$((failed + 1))
    fi
done
echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
