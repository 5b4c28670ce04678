#!/bin/sh
# No global mutable state (doc/methods.md, "No global state"): the library's objects
# hold no writable static variable, so two solvers run side by side in two threads.
# Fails on any symbol nm lists in a data or bss section (classes b, B, d, D) that is
# none of the read-only-in-use ones: the type-bound tables and default initializers
# gfortran makes for derived types (__vtab_, __def_init_), its constant tables (A.N,
# jumptable.N: array constructors of strings, SELECT CASE on strings), and the
# protected C texts of regdae_c_api. In particular `slen.N`: the static length gfortran
# 12 gives each call site of a function whose result is character(len=:), allocatable.
# Usage: check_no_static.sh NM LIBRARY [checked]   (the static library, e.g. libregdae.a;
# checked: a build with gfortran's -fcheck=all, whose run-time flags is_recursive.N and
# print_warning.N are allowed: such a build is single-threaded by design, its threads tests skip)
nm=${1:?usage: check_no_static.sh NM LIBRARY}
lib=${2:?usage: check_no_static.sh NM LIBRARY}
symbols=$("$nm" -A "$lib") || { echo "FAIL $nm -A $lib"; exit 1; }
allowed='(__[a-z0-9_]+_MOD___(vtab|def_init)_[A-Za-z0-9_]+|A\.[0-9]+(\.[0-9]+)?|jumptable\.[0-9]+(\.[0-9]+)?'
allowed="$allowed|__regdae_c_api_MOD_c_(status_texts|unknown_status|version|null_handle)"
[ "${3:-}" = checked ] && allowed="$allowed|is_recursive\\.[0-9]+(\\.[0-9]+)?|print_warning\\.[0-9]+(\\.[0-9]+)?"
allowed="$allowed)"
found=$(printf '%s\n' "$symbols" | awk '$(NF-1) ~ /^[bBdD]$/ { print $1, $NF }' | grep -vE " $allowed\$")
if [ -n "$found" ]; then
    echo "FAIL writable static variables in $lib (object: symbol):"
    printf '%s\n' "$found" | sed 's/^/  /'
    if printf '%s\n' "$found" | grep -q ' slen\.'; then
        echo "slen.N: a function with a character(len=:), allocatable result; gfortran keeps that length in"
        echo "a static per call site, which threads share. Give the result an automatic length (a pure"
        echo "function of the arguments) or make it a subroutine with an allocatable intent(out) argument."
    fi
    echo "The rule: no writable static in src/ (doc/methods.md, \"No global state\")."
    exit 1
fi
count=$(printf '%s\n' "$symbols" | awk '$(NF-1) ~ /^[bBdD]$/' | wc -l)
echo "ok: no writable static variable in $lib ($count read-only-in-use data symbols)"
