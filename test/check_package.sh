#!/bin/sh
# The Debian package (ctest label package): cpack -G DEB from BUILD_DIR into a scratch
# directory, then its name, control fields, files, the soname and regdae.pc's prefix.
# Usage: check_package.sh SOURCE_DIR BUILD_DIR VERSION LIBDIR INCLUDEDIR
#   (LIBDIR, INCLUDEDIR: the install directories relative to the prefix, /usr in the package)
# Prints one line per check and 'N passed, N failed'; exits 1 on a failure.
src=${1:?}; build=${2:?}; version=${3:?}; libdir=usr/${4:?}; includedir=usr/${5:?}
tmp=$(mktemp -d) || exit 1
trap 'rm -rf "$tmp"' EXIT INT TERM
. "$(dirname "$0")/check_lib.sh"

deb=regdae_${version}_$(dpkg --print-architecture).deb
cpack -G DEB --config "$build/CPackConfig.cmake" -B "$tmp" >"$tmp/cpack.log" 2>&1
check "cpack -G DEB writes $deb" $?
[ -f "$tmp/$deb" ] || { cat "$tmp/cpack.log"; finish; exit 1; }
echo "  $deb: $(wc -c <"$tmp/$deb") bytes"

for field in Package:regdae Version:$version; do
    [ "$(dpkg-deb -f "$tmp/$deb" "${field%%:*}")" = "${field#*:}" ]
    check "control: $field" $?
done
[ -n "$(dpkg-deb -f "$tmp/$deb" Maintainer)" ]
check "control: a maintainer" $?
depends=$(dpkg-deb -f "$tmp/$deb" Depends)
for p in libsundials-dev libsundials-fortran-dev liblapack-dev gfortran; do
    echo "$depends" | tr ',' '\n' | grep -q "^ *$p\( \|$\)"
    check "control: depends on $p" $?
done

dpkg-deb -x "$tmp/$deb" "$tmp/root"
files="$libdir/libregdae.a $libdir/libregdae.so.$version $includedir/regdae/regdae.mod
       $libdir/pkgconfig/regdae.pc $libdir/cmake/regdae/regdaeConfig.cmake"
[ -f "$src/include/regdae.h" ] && files="$files $includedir/regdae.h"
for f in $files; do
    [ -f "$tmp/root/$f" ]
    check "file /$f" $?
done
[ "$(readlink "$tmp/root/$libdir/libregdae.so")" = libregdae.so.0 ] &&
    [ "$(readlink "$tmp/root/$libdir/libregdae.so.0")" = "libregdae.so.$version" ]
check "symlinks libregdae.so -> libregdae.so.0 -> libregdae.so.$version" $?
objdump -p "$tmp/root/$libdir/libregdae.so.$version" | grep -q 'SONAME  *libregdae\.so\.0$'
check "soname libregdae.so.0" $?
grep -qx 'prefix=/usr' "$tmp/root/$libdir/pkgconfig/regdae.pc"
check "regdae.pc: prefix=/usr" $?
empty=$(cd "$tmp/root" && find . -type d -empty)
[ -z "$empty" ]
check "no empty directory${empty:+ (}$(echo $empty)${empty:+)}" $?
# the sizes the README gives (measured, not checked: they change with every module)
echo "  $deb: $(du -k --apparent-size "$tmp/$deb" | cut -f1) KiB; Installed-Size $(dpkg-deb -f "$tmp/$deb" \
    Installed-Size) KiB; the files $(du -sk --apparent-size "$tmp/root" | cut -f1) KiB"
finish
