#!/bin/sh
# A complete program in doc/api.md must be the file that ctest compiles and
# runs: the documentation cannot drift from working code. The program stands
# between <!-- begin NAME --> and <!-- end NAME --> (NAME: the file's base name),
# inside a code fence.
# Usage: check_doc_example.sh SOURCE_DIR [FILE]   (FILE relative to SOURCE_DIR;
#        default drivers/example_circle.f90)
src=${1:?usage: check_doc_example.sh SOURCE_DIR [FILE]}
file=${2:-drivers/example_circle.f90}
name=$(basename "$file")
tmp=$(mktemp) || exit 1
trap 'rm -f "$tmp"' EXIT
awk -v begin="<!-- begin $name -->" -v end="<!-- end $name -->" '
     $0 == begin { grab = 1; next }
     $0 == end { grab = 0 }
     grab && !/^```/ { print }' "$src/doc/api.md" >"$tmp"
if [ -s "$tmp" ] && cmp -s "$tmp" "$src/$file"; then
    echo "1 passed, 0 failed"
else
    echo "doc/api.md's $name differs from $file (or is missing):"
    diff "$tmp" "$src/$file" | head -20
    echo "0 passed, 1 failed"
    exit 1
fi
