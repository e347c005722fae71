# install.sh - make install gives a usable library: headers compile as C and C++,
# a program links through pkg-config, and installed tools find their data.
#
# The tree was built for the default prefix (the suite runs after `make`);
# installing it elsewhere is a separate step, as distributions do, and the
# installed tools and library must find their bridges and data there.
. "$(dirname "$0")/../lib.sh"
top=$TEXTURA_TOP
b=$(basename "$TEXTURA_BUILD")
unset TEXTURA_OIIO_BRIDGE TEXTURA_PALETTES TEXTURA_MATERIALS
if ! make -s -C "$top" install BUILD="$b" PREFIX="$T/p" >"$T/log" 2>&1; then
    notok "make install into a fresh prefix" "$(tail -3 "$T/log")"
    exit 0
fi
ok "make install into a fresh prefix"
for f in bin/t_noise lib/libtex.a lib/libtex.so.0 lib/textura/textura-oiio.so lib/textura/textura-png.so \
    lib/textura/textura-jpeg.so lib/textura/textura-tiff.so share/textura/patterns/materials.txt \
    include/textura/textura.h lib/pkgconfig/textura.pc share/man/man1/t_noise.1 share/man/man5/textura.5; do
    [ -e "$T/p/$f" ] && ok "installs $f" || notok "installs $f"
done
cat >"$T/prog.c" <<'C'
#include <textura/textura.h>
#include <stdio.h>
int main(void)
{
    struct tex_field *f = tex_field_new(tex_primitive_find("noise"));
    tex_map *m;
    if (!f || tex_field_init(f, 16, 16) < 0 || !(m = tex_field_sample(f)))
        return 1;
    printf("%d %d\n", m->w, m->nc);
    tex_map_free(m);
    tex_field_free(f);
    return 0;
}
C
export PKG_CONFIG_PATH="$T/p/lib/pkgconfig"
san=() # a sanitizer build installs an instrumented library: link the program alike
nm "$T/p/lib/libtex.a" 2>/dev/null | grep -q __asan_ && san=(-fsanitize=address,undefined)
# and with the compiler the library was built with (its OpenMP runtime)
cc=$(sed -n 's/^CC = //p' "$TEXTURA_BUILD/config.mk" 2>/dev/null)
if ${cc:-cc} "${san[@]}" -o "$T/prog" "$T/prog.c" $(pkg-config --cflags textura) -I"$T/p/include" \
    "$T/p/lib/libtex.a" $(pkg-config --static --libs-only-l textura | sed 's/-ltex//') -fopenmp 2>"$T/cc"; then
    [ "$("$T/prog")" = "16 1" ] && ok "a program links libtex through pkg-config and samples a primitive" \
        || notok "the linked program samples a primitive"
else
    notok "a program compiles against the installed headers" "$(head -3 "$T/cc")"
fi
printf '#include <textura/textura.h>\nint main(void) { return tex_primitive_find("noise") == nullptr; }\n' >"$T/prog.cc"
check "the public headers compile as C++" c++ -fsyntax-only -I"$T/p/include" -I/usr/include/OpenEXR "$T/prog.cc"
check "installed tools find the OpenImageIO bridge" "$T/p/bin/t_noise" -s 8 -o "$T/x.bmp"
check "installed tools find the shipped palettes" bash -c "'$T/p/bin/t_noise' -s 8 | TEXTURA_PALETTES= '$T/p/bin/t_palette' fire | '$T/p/bin/t_info' >/dev/null"

# libtex.so exports exactly what the installed headers declare (base/api.h), every
# installed header is read by textura.h, and textura.h's overview names each of them.
# exports LIB: the symbols a shared library defines for programs
exports() { nm -D --defined-only "$1" | awk '{ print $3 }' | sort; }
# decls INCLUDE: what the headers under INCLUDE/textura declare, then the headers read
decls() { python3 "$top/tests/house/api_decls.py" "$1"; }
if ! command -v clang >/dev/null; then
    skip "libtex.so exports what the installed headers declare" "no clang (make deps installs it)"
elif decls "$T/p/include" >"$T/decls" 2>"$T/decls.err"; then
    sed -n 's/^D //p' "$T/decls" | sort >"$T/declared"
    exports "$T/p/lib/libtex.so.0" >"$T/exported"
    diff=$(comm -3 "$T/declared" "$T/exported" | head -20)
    [ -s "$T/declared" ] && [ -z "$diff" ] \
        && ok "libtex.so exports exactly the $(wc -l <"$T/declared") functions and variables the installed headers declare" \
        || notok "libtex.so's exports against the headers' declarations (left: declared only)" "$diff"
    (cd "$T/p/include/textura" && find . -type f | sed 's|^\./||' | sort) >"$T/installed"
    sed -n 's/^H //p' "$T/decls" | sort >"$T/read"
    missing=$(comm -23 "$T/installed" "$T/read" | grep -vx 'textura.h')
    [ -z "$missing" ] && ok "textura.h reads every installed header" \
        || notok "installed headers textura.h does not read" "$missing"
    unnamed=$(while read -r h; do
        grep -q "^ \*  *$(basename "$h" | sed 's/\./\\./g')\b\|[ (]$(basename "$h" | sed 's/\./\\./g')[ ,)]" \
            "$T/p/include/textura/textura.h" || echo "$h"; done < <(grep -vx 'textura.h' "$T/installed"))
    [ -z "$unnamed" ] && ok "textura.h's overview names every installed header" \
        || notok "headers textura.h's overview leaves out" "$unnamed"
    # the checks find a planted declaration and a planted header
    cp -R "$T/p/include" "$T/inc2"
    printf '#include "api.h"\nTEX_API_BEGIN\nint tex_planted(void);\nTEX_API_END\n' >>"$T/inc2/textura/base/rng.h"
    : >"$T/inc2/textura/base/planted.h"
    decls "$T/inc2" >"$T/decls2" 2>/dev/null
    sed -n 's/^D //p' "$T/decls2" | sort | comm -23 - "$T/exported" | grep -qx tex_planted \
        && ! sed -n 's/^H //p' "$T/decls2" | grep -qx base/planted.h \
        && ok "the export check finds a planted declaration and a header textura.h does not read" \
        || notok "the export check finds what is planted"
else
    notok "the installed headers' declarations" "$(head -3 "$T/decls.err")"
fi

# The renderer's public header is the only one of its own that is installed,
# and it is enough to render.
[ -e "$T/p/include/textura/render/render.h" ] && [ ! -e "$T/p/include/textura/render/scene.h" ] \
    && [ ! -e "$T/p/include/textura/lang/lex.h" ] \
    && ok "render.h is installed, the renderer's and languages' insides are not" \
    || notok "only the public render header is installed" "$(ls "$T/p/include/textura/render")"
cat >"$T/render.c" <<'C'
#include <textura/textura.h>
#include <stdio.h>
#include <string.h>
int main(void)
{
    const char *text = "camera { eye 0 0 -4 look 0 0 0 }\nlight point { position 0 3 -3 }\n"
                       "surface red { Kd 1 0 0 }\nsphere { radius 1 surface red }\n";
    struct tex_scene *s = tex_scene_parse(text, strlen(text), "inline.scene");
    tex_map *m;
    if (!s || tex_scene_set_size(s, 32, 24) < 0 || tex_scene_set_samples(s, 0) == 0 ||
        tex_scene_prepare(s) < 0 || !(m = tex_render(s, NULL, NULL)))
        return 1;
    const float *c = tex_map_px(m, 16, 12);
    printf("%d %d %d\n", m->w, m->h, c[0] > 0.1f && c[1] < 0.05f && c[2] < 0.05f);
    tex_map_free(m);
    tex_scene_free(s);
    return 0;
}
C
if ${cc:-cc} "${san[@]}" -o "$T/render" "$T/render.c" $(pkg-config --cflags textura) -I"$T/p/include" \
    "$T/p/lib/libtex.a" $(pkg-config --static --libs-only-l textura | sed 's/-ltex//') -fopenmp 2>"$T/cc"; then
    got=$("$T/render")
    [ "$got" = "32 24 1" ] && ok "a program renders a scene through render.h alone (a red sphere, 32x24)" \
        || notok "a program renders through render.h" "got '$got'"
else
    notok "a program compiles against render.h" "$(head -3 "$T/cc")"
fi

# libtex(3)'s whole program, compiled with pkg-config's flags alone (a
# sanitizer build's instrumented library needs the runtime linked too), run
# from a folder outside the source tree: it writes a PNG through the
# installed PNG bridge and renders a scene whose material comes from the
# installed database.
sed -n '/^\.\\" begin program/,/^\.\\" end program/p' "$top/man/man3/libtex.3" |
    sed -e '/^\./d' -e 's/\\e/\\/g' >"$T/synopsis.c"
grep -q 'int main' "$T/synopsis.c" || notok "libtex(3) holds the example program"
mkdir -p "$T/away"
cat >"$T/away/gold.scene" <<'SCENE'
camera { eye 0 0 -4 look 0 0 0 }
light point { position 0 3 -3 }
surface gilt { Kd 0.85 0.65 0.25 Ks 0.7 n 60 model cook-torrance material gold facets beckmann 0.1 specular 1 }
sphere { radius 1 surface gilt }
SCENE
if ${cc:-cc} "${san[@]}" -o "$T/away/prog" "$T/synopsis.c" $(pkg-config --cflags --libs textura) 2>"$T/cc"; then
    ok "libtex(3)'s program compiles with pkg-config --cflags --libs textura alone"
    if (cd "$T/away" && ./prog gold.scene >"$T/prog.out" 2>&1); then
        ok "the program runs from the prefix without LD_LIBRARY_PATH, writes a PNG and renders material gold"
        got=$(cd "$T/away" && "$T/p/bin/t_info" noise.png | head -1)
        [ "$got" = "noise.png: 256x256, 1 channel" ] && ok "its PNG reads back" || notok "its PNG reads back" "$got"
        "$T/p/bin/t_info" "$T/away/scene.png" >"$T/si" 2>&1 && grep -q '64x48, 3 channels' "$T/si" &&
            awk '$1 == "R" { r = $7 } $1 == "B" { b = $7 } END { exit !(r > b) }' "$T/si" &&
            ok "the gold sphere renders warmer than blue" || notok "the rendered scene" "$(head -3 "$T/si")"
    else
        notok "the program runs from the prefix" "$(head -3 "$T/prog.out")"
    fi
else
    notok "libtex(3)'s program compiles with pkg-config alone" "$(head -3 "$T/cc")"
fi
cflags=$(pkg-config --cflags textura)
[[ " $cflags " == *" -I$T/p/include "* ]] && ok "pkg-config --cflags gives PREFIX/include" \
    || notok "pkg-config --cflags gives PREFIX/include" "$cflags"

# Installed tools, run from a folder outside the source tree.
check "an installed tool writes a PNG from outside the source tree" \
    bash -c "cd '$T/away' && '$T/p/bin/t_noise' -s 32 -o n.png && '$T/p/bin/t_info' n.png >/dev/null"
check "an installed t_apply renders material gold from outside the source tree" \
    bash -c "cd '$T/away' && '$T/p/bin/t_apply' -s 32x24 -o g.png gold.scene"

# Staged with DESTDIR, then moved: the tree finds its parts where it lands.
if make -s -C "$top" install BUILD="$b" PREFIX=/opt/textura-test DESTDIR="$T/stage" >"$T/log" 2>&1 &&
    mv "$T/stage/opt/textura-test" "$T/moved"; then
    check "a DESTDIR-staged, moved tree writes PNG, TIFF and JPEG" bash -c "cd '$T/away' &&
        '$T/moved/bin/t_noise' -s 16 -o s.png && '$T/moved/bin/t_convert' s.png -o s.tif &&
        '$T/moved/bin/t_convert' s.tif -o s.jpg"
    check "a DESTDIR-staged, moved tree finds its palettes" \
        bash -c "'$T/moved/bin/t_noise' -s 8 | '$T/moved/bin/t_palette' fire | '$T/moved/bin/t_info' >/dev/null"
    grep -q "^prefix=/opt/textura-test$" "$T/moved/lib/pkgconfig/textura.pc" \
        && ok "a DESTDIR install's textura.pc names the final prefix" || notok "the DESTDIR textura.pc" "$(head -2 "$T/moved/lib/pkgconfig/textura.pc")"
else
    notok "make install DESTDIR=" "$(tail -3 "$T/log")"
fi

if make -s -C "$top" uninstall BUILD="$b" PREFIX="$T/p" >"$T/log" 2>&1; then
    left=$(find "$T/p" ! -type d | head -3)
    [ -z "$left" ] && ok "make uninstall removes every installed file" || notok "make uninstall leaves files" "$left"
else
    notok "make uninstall" "$(tail -3 "$T/log")"
fi
