#!/bin/sh
# Downstream builds against an installed regdae (ctest label install).
#
#   check_downstream.sh install BUILD_DIR PREFIX
#       cmake --install BUILD_DIR into a fresh PREFIX.
#   check_downstream.sh cmake|pkg-config static|shared PREFIX SOURCE
#       Build the program SOURCE (.f90: gfortran, .c: cc; FC and CC override) against PREFIX:
#       cmake       the project in this directory: find_package(regdae), then regdae::regdae
#                   (static) or regdae::regdae_shared;
#       pkg-config  one compiler command line: `pkg-config --cflags --libs regdae` and an rpath
#                   (shared), or -static and `pkg-config --cflags --static --libs regdae`
#                   (everything static, so Libs.private must be complete).
#       Then check with ldd how it is linked to regdae, and run it: SOURCE checks its answer.
set -eu
here=$(cd "$(dirname "$0")" && pwd)
if [ "${1:-}" = install ]; then
    build=${2:?}; prefix=${3:?}
    rm -rf "$prefix"
    cmake --install "$build" --prefix "$prefix" >/dev/null
    echo "installed in $prefix"
    exit 0
fi
tool=${1:?}; linkage=${2:?}; prefix=$(cd "${3:?}" && pwd)
source=$(cd "$(dirname "${4:?}")" && pwd)/$(basename "$4")
case $source in
*.f90) compiler=${FC:-gfortran}; own_libs="" ;;
*.c) compiler=${CC:-cc}; own_libs=-lm ;;   # the C example's own fmax, sqrt
*) echo "check_downstream.sh: unknown language: $source" >&2; exit 2 ;;
esac
case $linkage in
static) target=regdae::regdae; static_flag=-static ;;
shared) target=regdae::regdae_shared; static_flag="" ;;
*) echo "check_downstream.sh: linkage is static or shared, not $linkage" >&2; exit 2 ;;
esac
# The installed shared library (lib/ or a lib/<multiarch>/ directory).
soname=""
for f in "$prefix"/lib/libregdae.so.0 "$prefix"/lib/*/libregdae.so.0; do
    if [ -e "$f" ]; then soname=$f; break; fi
done
[ -n "$soname" ] || { echo "FAIL: no libregdae.so.0 in $prefix/lib"; exit 1; }
libdir=$(dirname "$soname")
library=$(readlink -f "$soname")
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

case $tool in
cmake)
    cmake -S "$here" -B "$tmp" -DCMAKE_PREFIX_PATH="$prefix" -DREGDAE_CONSUMER_SOURCE="$source" \
        -DREGDAE_CONSUMER_TARGET="$target" >/dev/null
    cmake --build "$tmp" >/dev/null
    ;;
pkg-config)
    command -v pkg-config >/dev/null || { echo "pkg-config not found (apt-get install pkg-config)" >&2; exit 1; }
    export PKG_CONFIG_PATH="$libdir/pkgconfig"
    if [ "$linkage" = static ]; then
        flags=$(pkg-config --cflags --static --libs regdae)
    else
        flags="$(pkg-config --cflags --libs regdae) $own_libs -Wl,-rpath,$(pkg-config --variable=libdir regdae)"
    fi
    echo "$compiler $static_flag $source $flags"
    # shellcheck disable=SC2086
    (cd "$tmp" && "$compiler" $static_flag "$source" $flags -o consumer)
    ;;
*) echo "check_downstream.sh: tool is cmake or pkg-config, not $tool" >&2; exit 2 ;;
esac

# The libregdae.so.0 the program loads (ldd), if any.
linked=$(ldd "$tmp/consumer" 2>/dev/null | sed -n 's/^[[:space:]]*libregdae\.so\.0 => \([^ ]*\).*/\1/p')
if [ "$linkage" = shared ] && [ "$(readlink -f "${linked:-/nonexistent}")" != "$library" ]; then
    echo "FAIL: not linked to $library (ldd: '$linked')"; exit 1
elif [ "$linkage" = static ] && [ -n "$linked" ]; then
    echo "FAIL: the static build loads $linked"; exit 1
fi
if [ -n "$linked" ]; then echo "loads $linked"; fi
if (cd "$tmp" && ./consumer >out); then
    tail -n 1 "$tmp/out"; echo "1 passed, 0 failed"
else
    cat "$tmp/out"; echo "0 passed, 1 failed"; exit 1
fi
