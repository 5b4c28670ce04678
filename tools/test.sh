#!/bin/sh
# The tests: install missing packages, build with run-time checks in
# build-test/, run ctest, then the plain-make build and its self-checks.
# Usage: tools/test.sh
set -eu
cd "$(dirname "$0")/.."
sh tools/install-deps.sh
jobs=$(nproc 2>/dev/null || echo 2)
cmake -S . -B build-test -DCMAKE_BUILD_TYPE=Debug -DREGDAE_RUNTIME_CHECKS=ON >/dev/null
cmake --build build-test -j "$jobs"
(cd build-test && ctest --output-on-failure -j "$jobs")
make -s -f Makefile.legacy -j "$jobs" BUILD=build-test/legacy >/dev/null
make -s -f Makefile.legacy check BUILD=build-test/legacy
