#!/usr/bin/env bash
# tests/fuzz/libs.sh BUILD - libpng and OpenEXR's core from Debian's source packages
# (apt-get source libpng1.6 openexr: the versions the system's -dev packages install),
# compiled with the fuzzer's coverage and sanitizers into BUILD/libpng-fuzz.a and
# BUILD/libOpenEXRCore-fuzz.a, so that fuzz_png and fuzz_stream cover the decoders and
# not only the bridges; the fuzz Makefile links them in place of -lpng16 and
# -lOpenEXRCore when they are there (make fuzz-libs, then make fuzz).  Needs deb-src
# lines in apt's sources (Types: deb-src beside Types: deb) and dpkg-dev; says what is
# missing and exits 1 without them.  $FUZZ_CC and $FUZZ_CFLAGS: the compiler and flags
# (the Makefile's, sanitizers and -fsanitize=fuzzer-no-link included).
set -eu
build=${1:?usage: libs.sh BUILD}
cc=${FUZZ_CC:-clang}
flags=${FUZZ_CFLAGS:--g -O1 -fsanitize=address,undefined,fuzzer-no-link}
src=$build/src
mkdir -p "$src"
if ! ls -d "$src"/libpng1.6-*/ "$src"/openexr-*/ >/dev/null 2>&1; then
    (cd "$src" && apt-get source libpng1.6 openexr) || {
        echo "libs.sh: apt-get source libpng1.6 openexr failed: add deb-src lines to apt's" \
             "sources and install dpkg-dev; the fuzz targets link the system's libraries" >&2
        exit 1
    }
fi
png=$(ls -d "$src"/libpng1.6-*/ | head -1) exr=$(ls -d "$src"/openexr-*/ | head -1)
# one LIB DIR CFLAGS FILE...: compile the files into BUILD/LIB
one() {
    local lib=$1 dir=$2 cf=$3 obj=$build/obj-$1
    shift 3
    mkdir -p "$obj"
    for f in "$@"; do
        $cc $flags $cf -w -c -o "$obj/$(basename "${f%.c}").o" "$dir/$f" &
        [ "$(jobs -r | wc -l)" -lt "$(nproc)" ] || wait -n
    done
    wait
    rm -f "$build/$lib"
    ar rcs "$build/$lib" "$obj"/*.o
    echo "libs.sh: $build/$lib from $(basename "$dir") ($# files)"
}
# libpng: its configuration as shipped (scripts/pnglibconf.h.prebuilt), the C filters
cp "$png/scripts/pnglibconf.h.prebuilt" "$png/pnglibconf.h"
one libpng-fuzz.a "$png" "-I$png" png.c pngerror.c pngget.c pngmem.c pngpread.c pngread.c \
    pngrio.c pngrtran.c pngrutil.c pngset.c pngtrans.c pngwio.c pngwrite.c pngwtran.c pngwutil.c
core=$exr/src/lib/OpenEXRCore
one libOpenEXRCore-fuzz.a "$core" "-I$core -I/usr/include/OpenEXR -I/usr/include/Imath" \
    $(cd "$core" && ls *.c)
