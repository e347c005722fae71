# recipe.sh - what every recipe in patterns/ shares; source it first.
#
#   recipe=NAME; . recipe.sh reads the recipe's arguments, the same in every recipe:
#                                   -o PREFIX  (default NAME: files NAME_*.png and .exr)
#                                   -s N|WxH   (map size in pixels, default $size or 512;
#                                               a render is W wide, its shape its own)
#                                   -S N       (added to every seed the recipe uses;
#                                               default 0, the pictures as documented)
#                                   -h         (this help: the recipe's header)
# and sets $here (the recipe's folder: the source tree's patterns/ or the installed
# share/textura/patterns), $out, $size, $W and $H (its sides), $S and $tmp (removed at
# exit); a caller that sets fixed_seeds refuses -S.  The tools beside the recipe come first on PATH: the source tree's build/bin,
# or the installed prefix's bin; PATH's own otherwise.
#   write MAP NAME           MAP as $out_NAME.png and $out_NAME.exr
#   scene TEXT               the scene text with @TMP@ standing for $tmp, into $tmp/s.scene
set -eu
here=$(cd "$(dirname "$0")" && pwd)
for bin in "$here/../build/bin" "$here/../../../bin"; do
    if [ -x "$bin/t_noise" ]; then PATH=$(cd "$bin" && pwd):$PATH; break; fi
done
export PATH
out=$recipe
size=${size:-512} # a caller may set another default
S=0
usage="usage: $0 [-o PREFIX] [-s N|WxH] [-S SEED] [-h]"
while getopts o:s:S:h opt; do
    case $opt in
    o) out=$OPTARG ;;
    s) size=$OPTARG ;;
    S) [ -z "${fixed_seeds:-}" ] || { echo "$0: takes no -S: its pictures are the documented ones" >&2; exit 2; }
       S=$OPTARG ;;
    h) sed -n '2,/^set /p' "$0" | sed '$d' | sed 's/^# \{0,1\}//'; echo "$usage"; exit 0 ;;
    *) echo "$usage" >&2; exit 2 ;;
    esac
done
shift $((OPTIND - 1))
[ $# = 0 ] || { echo "$0: unexpected operand '$1' ($usage)" >&2; exit 2; }
case $size in *x*) W=${size%%x*} H=${size#*x} ;; *) W=$size H=$size ;; esac
case $W$H in '' | *[!0-9]*) echo "$0: -s must be N or WxH in pixels (got '$size')" >&2; exit 2 ;; esac
[ "$W" -ge 1 ] && [ "$H" -ge 1 ] || { echo "$0: -s must be N or WxH in pixels (got '$size')" >&2; exit 2; }
case $S in '' | *[!0-9]*) echo "$0: -S must be a whole number 0..1000000 (got '$S')" >&2; exit 2 ;; esac
[ "$S" -le 1000000 ] || { echo "$0: -S must be a whole number 0..1000000 (got '$S')" >&2; exit 2; }
tmp=$(mktemp -d "${TMPDIR:-/tmp}/${recipe##*/}.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
write() {
    t_convert -o "${out}_$2.exr" "$1"
    t_convert -o "${out}_$2.png" "$1"
    echo "wrote ${out}_$2.png and .exr"
}
scene() {
    printf '%s\n' "$1" | sed "s|@TMP@|$tmp|g" >"$tmp/s.scene"
}
