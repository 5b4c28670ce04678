#!/bin/sh
# The tests: install missing packages; build with plain make and run its
# self-checks; build with CMake and run-time checks in build-test/ and run ctest.
# Usage: tools/test.sh
set -eu
cd "$(dirname "$0")/.."
sh tools/install-deps.sh
jobs=$(nproc 2>/dev/null || echo 2)
echo "== Makefile.legacy: build and self-checks"
make -s -f Makefile.legacy -j "$jobs" BUILD=build-test/legacy >/dev/null
make -s -f Makefile.legacy check BUILD=build-test/legacy
echo "== CMake (Debug, -fcheck=all): build and ctest"
cmake -S . -B build-test -DCMAKE_BUILD_TYPE=Debug -DREGDAE_RUNTIME_CHECKS=ON >/dev/null
cmake --build build-test -j "$jobs" >/dev/null
cd build-test && ctest --output-on-failure -j "$jobs"
