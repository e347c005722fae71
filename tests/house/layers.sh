# layers.sh - libtex's folders are layers, and includes point only down them.
#
# base <- io <- prim <- ops <- lang <- render <- cli: a file may include headers
# of its own layer or of a layer before it.  A .c file names the layer
# ("base/map.h", found through -Ilibtex); a header includes relative to itself
# ("map.h", "../base/map.h"), so that the installed tree needs no -I.  A layer's
# x86/ folder (its CPU-specific kernels) belongs to the layer: its headers say
# "../noise.h" for the layer's own, "../../base/simd.h" for a layer below, and a
# layer's header names its kernels' as "x86/noise_x86.h".
. "$(dirname "$0")/../lib.sh"
top=${TEXTURA_TOP:-$(cd "$(dirname "$0")/../.." && pwd)}
layers=(base io prim ops lang render cli)

# check_tree DIR: print one line per include that points up or is not "layer/name.h".
check_tree() {
    local dir=$1 i f inc l rank
    declare -A rank_of
    for i in "${!layers[@]}"; do rank_of[${layers[$i]}]=$i; done
    for f in "$dir"/*/*.[ch] "$dir"/*/*.cpp "$dir"/*/*.def "$dir"/*/x86/*.[ch]; do
        [ -e "$f" ] || continue
        local sub=
        l=$(basename "$(dirname "$f")")
        [ "$l" = x86 ] && { sub=x86; l=$(basename "$(dirname "$(dirname "$f")")"); }
        rank=${rank_of[$l]:-}
        [ -n "$rank" ] || { echo "$f: folder $l is not a layer"; continue; }
        while IFS= read -r inc; do
            local il
            case $sub:$f:$inc in
            x86:*.h:../../*/*) il=${inc#../../}; il=${il%%/*} ;;
            x86:*.h:../*/*) il=- ;;
            x86:*.h:../*) il=$l ;;
            :*.h:../*/*) il=${inc#../}; il=${il%%/*} ;;
            :*.h:x86/*) il=$l ;; # the layer's own kernels
            *.h:*/*) il=- ;; # a header's "layer/x.h" would not resolve once installed
            *.h:* | *.def:*) il=$l ;;
            *:*/*) il=${inc%%/*} ;;
            *) il=- ;;
            esac
            if [ -z "${rank_of[$il]:-}" ]; then
                echo "$f: #include \"$inc\" names no layer"
            elif [ "${rank_of[$il]}" -gt "$rank" ]; then
                echo "$f: #include \"$inc\" points up ($l includes $il)"
            fi
        done < <(sed -n 's/^[[:space:]]*#[[:space:]]*include[[:space:]]*"\([^"]*\)".*/\1/p' "$f")
    done
}

bad=$(check_tree "$top/libtex")
[ -z "$bad" ] && ok "every libtex include points down the layers" || notok "libtex includes point down" "$bad"

n=$(ls -d "$top"/libtex/*/ | wc -l)
[ "$n" = ${#layers[@]} ] && ok "libtex has exactly the ${#layers[@]} layer folders" || notok "libtex layer folders" "$n folders"
ls "$top"/libtex/*.[ch] 2>/dev/null | grep -qv '/textura.h$' \
    && notok "only textura.h stands above the layers" "$(ls "$top"/libtex/*.[ch])" \
    || ok "only textura.h stands above the layers"

# The check must catch an upward include: a copy of the tree with one planted.
cp -R "$top/libtex" "$T/libtex"
printf '#include "render/scene.h"\n' >>"$T/libtex/base/map.c"
printf '#include "noise.h"\n' >>"$T/libtex/ops/remap.c"
printf '#include "../lang/script.h"\n' >>"$T/libtex/ops/filter.h"
mkdir -p "$T/libtex/prim/x86"
printf '#include "../../render/scene.h"\n#include "../noise.h"\n#include "../../base/simd.h"\n' \
    >"$T/libtex/prim/x86/planted.h"
printf '#include "prim/noise.h"\n#include "ops/palette.h"\n' >"$T/libtex/prim/x86/planted.c"
bad=$(check_tree "$T/libtex")
grep -q 'base/map.c: #include "render/scene.h" points up' <<<"$bad" \
    && grep -q 'ops/remap.c: #include "noise.h" names no layer' <<<"$bad" \
    && grep -q 'ops/filter.h: #include "../lang/script.h" points up' <<<"$bad" \
    && grep -q 'prim/x86/planted.h: #include "../../render/scene.h" points up' <<<"$bad" \
    && grep -q 'prim/x86/planted.c: #include "ops/palette.h" points up' <<<"$bad" \
    && [ "$(wc -l <<<"$bad")" = 5 ] \
    && ok "the layer check finds planted upward includes and a bare one" \
    || notok "the layer check finds planted includes" "$bad"
