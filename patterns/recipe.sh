# recipe.sh - what every recipe in patterns/ shares; source it first.
#
#   recipe=NAME; . recipe.sh reads the recipe's arguments:
#                                   -o PREFIX  (default NAME: files NAME_*.png and .exr)
#                                   -s N       (map side in pixels, default $size or 512)
#                                   -h         (this help: the recipe's header)
# and sets $here (the recipe's folder: the source tree's patterns/ or the installed
# share/textura/patterns), $out, $size and $tmp (removed at exit).  The tools must be
# on PATH (build/bin, or the installed bin).
#   write MAP NAME           MAP as $out_NAME.png and $out_NAME.exr
#   scene TEXT               the scene text with @TMP@ standing for $tmp, into $tmp/s.scene
set -eu
here=$(cd "$(dirname "$0")" && pwd)
out=$recipe
size=${size:-512} # a caller may set another default
while getopts o:s:h opt; do
    case $opt in
    o) out=$OPTARG ;;
    s) size=$OPTARG ;;
    h) sed -n '2,/^set /p' "$0" | sed '$d' | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "usage: $0 [-o PREFIX] [-s N]" >&2; exit 2 ;;
    esac
done
case $size in '' | *[!0-9]*) echo "$0: -s must be a number of pixels (got '$size')" >&2; exit 2 ;; esac
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
