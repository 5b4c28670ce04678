#!/bin/sh
# Install the build tree into a scratch prefix, build drivers/example_circle.f90
# in a separate project with find_package(regdae), and run it.
# Usage: check_install.sh SOURCE_DIR BUILD_DIR
set -eu
src=${1:?}; build=${2:?}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cmake --install "$build" --prefix "$tmp/prefix" >/dev/null
cmake -S "$src/test/consumer" -B "$tmp/consumer" -DCMAKE_PREFIX_PATH="$tmp/prefix" \
    -DREGDAE_EXAMPLE_SOURCE="$src/drivers/example_circle.f90" >/dev/null
cmake --build "$tmp/consumer" >/dev/null
if "$tmp/consumer/consumer" >/dev/null; then echo "1 passed, 0 failed"; else echo "0 passed, 1 failed"; exit 1; fi
