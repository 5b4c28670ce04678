#!/bin/sh
# Install the Debian packages regdae needs, if any is missing (Open MPI: drivers/sweep on MPI;
# without it CMake builds the serial sweep).
# Usage: tools/install-deps.sh [--figures] [--tests]
#   --figures adds gnuplot-nox (the report's figures); --tests adds valgrind (memcheck tests)
#   and pkg-config (builds against the installed regdae.pc)
set -eu
packages="gfortran cmake make liblapack-dev libsundials-dev libsundials-fortran-dev libopenmpi-dev openmpi-bin"
for arg in "$@"; do
    case $arg in
    --figures) packages="$packages gnuplot-nox" ;;
    --tests) packages="$packages valgrind pkg-config" ;;
    *) echo "usage: tools/install-deps.sh [--figures] [--tests]" >&2; exit 2 ;;
    esac
done

missing=""
for p in $packages; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' || missing="$missing $p"
done
[ -z "$missing" ] && exit 0

echo "regdae: installing missing Debian packages:$missing"
if [ "$(id -u)" = 0 ]; then
    sudo=""
elif command -v sudo >/dev/null 2>&1; then
    sudo="sudo"
else
    echo "regdae: missing packages:$missing; run this script as root or install them" >&2
    exit 1
fi
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
# shellcheck disable=SC2086
$sudo apt-get install -y -qq --no-install-recommends $missing >/dev/null
