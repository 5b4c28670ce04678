#!/bin/sh
# The tests: install missing packages; build with plain make, run its
# self-checks, install it and build a program against it with pkg-config;
# build with CMake and run-time checks in build-test/ and run ctest (unit
# suites, driver checks, fuzzing, valgrind memcheck, downstream builds from an
# installed tree, the Debian package); build with
# AddressSanitizer + UBSan in build-asan/ and run the unit suites and the
# driver runs there (ctest -L sanitize).
# Usage: tools/test.sh
set -eu
cd "$(dirname "$0")/.."
sh tools/install-deps.sh --tests
jobs=$(nproc 2>/dev/null || echo 2)
echo "== Makefile.legacy: build and self-checks"
make -s -f Makefile.legacy -j "$jobs" BUILD=build-test/legacy >/dev/null
make -s -f Makefile.legacy check BUILD=build-test/legacy
echo "== Makefile.legacy: install, and pkg-config builds against the installed tree"
rm -rf build-test/legacy/prefix
make -s -f Makefile.legacy install BUILD=build-test/legacy PREFIX="$PWD/build-test/legacy/prefix" >/dev/null
for linkage in static shared; do
    sh test/downstream/check_downstream.sh pkg-config $linkage build-test/legacy/prefix drivers/example_circle.f90
done
echo "== CMake (Debug, -fcheck=all): build and ctest"
cmake -S . -B build-test -DCMAKE_BUILD_TYPE=Debug -DREGDAE_RUNTIME_CHECKS=ON >/dev/null
cmake --build build-test -j "$jobs" >/dev/null
(cd build-test && ctest --output-on-failure -j "$jobs")
echo "== CMake (Debug, -fsanitize=address,undefined -fcheck=all): build and ctest -L sanitize -LE fuzz"
cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=Debug -DREGDAE_SANITIZE=ON >/dev/null
cmake --build build-asan -j "$jobs" >/dev/null
(cd build-asan && ctest --output-on-failure -j "$jobs" -L sanitize)
