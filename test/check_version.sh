#!/bin/sh
# The version three places give must be CMakeLists.txt's project(VERSION): the macros
# REGDAE_VERSION_MAJOR/MINOR/PATCH of include/regdae.h, and the constants and the text
# of regdae_version() in src/regdae_c_api.f90 (capi_tester's suite `version` holds the
# library's run-time answer against the macros).
# Usage: check_version.sh SOURCE_DIR PROJECT_VERSION
src=${1:?usage: check_version.sh SOURCE_DIR PROJECT_VERSION}
version=${2:?usage: check_version.sh SOURCE_DIR PROJECT_VERSION}
header=$src/include/regdae.h
fortran=$src/src/regdae_c_api.f90
failed=0
passed=0
ok() {
    if [ "$1" = "$2" ]; then
        passed=$((passed + 1))
    else
        echo "$3: $1, CMakeLists.txt's project(VERSION): $2"
        failed=$((failed + 1))
    fi
}
major=${version%%.*}
rest=${version#*.}
minor=${rest%%.*}
patch=${rest#*.}
for part in MAJOR MINOR PATCH; do
    case $part in
    MAJOR) want=$major ;;
    MINOR) want=$minor ;;
    PATCH) want=$patch ;;
    esac
    got=$(sed -n "s/^#define REGDAE_VERSION_$part \([0-9]*\)\$/\1/p" "$header")
    ok "$got" "$want" "include/regdae.h: REGDAE_VERSION_$part"
    lower=$(echo "$part" | tr 'A-Z' 'a-z')
    got=$(sed -n "s/.*integer, parameter, public :: regdae_version_major.* regdae_version_$lower = \([0-9]*\).*/\1/p;
                  s/.*integer, parameter, public :: regdae_version_$lower = \([0-9]*\).*/\1/p" "$fortran" | head -n 1)
    ok "$got" "$want" "src/regdae_c_api.f90: regdae_version_$lower"
done
got=$(sed -n "s/.* :: c_version = '\([0-9.]*\)'\/\/c_null_char.*/\1/p" "$fortran")
ok "$got" "$version" "src/regdae_c_api.f90: the text of regdae_version()"
echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
