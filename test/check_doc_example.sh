#!/bin/sh
# The complete example in doc/api.md must be drivers/example_circle.f90, which
# ctest compiles and runs: the documentation cannot drift from working code.
# Usage: check_doc_example.sh SOURCE_DIR
src=${1:?usage: check_doc_example.sh SOURCE_DIR}
tmp=$(mktemp) || exit 1
trap 'rm -f "$tmp"' EXIT
awk '/<!-- begin example_circle.f90 -->/ { grab = 1; next }
     /<!-- end example_circle.f90 -->/ { grab = 0 }
     grab && !/^```/ { print }' "$src/doc/api.md" >"$tmp"
if cmp -s "$tmp" "$src/drivers/example_circle.f90"; then
    echo "1 passed, 0 failed"
else
    echo "doc/api.md's example differs from drivers/example_circle.f90:"
    diff "$tmp" "$src/drivers/example_circle.f90" | head -20
    echo "0 passed, 1 failed"
    exit 1
fi
