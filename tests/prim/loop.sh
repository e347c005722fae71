#!/bin/bash
# loop.sh - looping animation of the noise family (--frames N --frame K): 4D noise on a circle
. "${TEXTURA_TOP:-.}/tests/lib.sh"
top=${TEXTURA_TOP:-.}

# Frame K of N is the point at angle 2 pi K/N: frame 2K of 2N is the same map, bit for bit,
# and frame N (angle 2 pi) is frame 0 again.
for t in "t_noise" "t_turbulence" "t_fractal --mode fbm" "t_fractal --mode ridged"; do
    $t -s 48 --frames 10 --frame 3 -o "$T/a.exr"
    $t -s 48 --frames 20 --frame 6 -o "$T/b.exr"
    same "$t: frame 3 of 10 == frame 6 of 20" "$T/a.exr" "$T/b.exr"
done

# Frame N == frame 0: the loop closes.  The step from the last frame back to the first is
# like every other step (mean change per pixel), and the frames do move.
N=12
for k in $(seq 0 $((N - 1))); do t_noise -s 64 --frames $N --frame $k -o "$T/f$k.exr"; done
steps=()
for k in $(seq 0 $((N - 1))); do
    t_op sub "$T/f$k.exr" "$T/f$(((k + 1) % N)).exr" | t_op abs - -o "$T/d.exr"
    steps+=("$(info_json "$T/d.exr" stats 0 mean)")
done
r=$(python3 -c '
import sys
s = [float(x) for x in sys.argv[1:]]
inner, wrap = s[:-1], s[-1]
ok = min(s) > 1e-3 and max(s) < 1.5 * min(s) and min(inner) <= wrap <= max(inner) * 1.2
print("ok" if ok else "steps %s" % s)' "${steps[@]}")
[ "$r" = ok ] && ok "the last frame leads back to frame 0 as smoothly as any step" ||
    notok "the loop closes smoothly" "$r"
t_noise -s 64 --frames $N --frame 0 -o "$T/g0.exr"
t_noise -s 64 --frames 5 --frame 0 -o "$T/h0.exr"
same "frame 0 is the same for any N (angle 0 = angle 2 pi)" "$T/g0.exr" "$T/h0.exr"
t_noise -s 64 --frames 4 --frame 1 --window 10,10,30,20 -o "$T/w.exr"
check "frames are windowed too" t_info "$T/w.exr"

# The recipe writes its frames; ffmpeg, when installed, a GIF and a video.
if (cd "$T" && frames=4 "$top/patterns/loop.sh" -o "$T/loop" -s 32 >"$T/out" 2>"$T/err"); then
    n=$(ls "$T"/loop_*.png 2>/dev/null | wc -l)
    [ "$n" = 4 ] && ok "patterns/loop.sh writes its frames" || notok "loop.sh frames" "$n files"
    if command -v ffmpeg >/dev/null; then
        [ -s "$T/loop.gif" ] && ok "patterns/loop.sh encodes a GIF" || notok "loop.sh GIF"
    else
        grep -q "ffmpeg not installed" "$T/out" && skip "patterns/loop.sh encodes a GIF" "ffmpeg is not installed (said so)" ||
            notok "loop.sh without ffmpeg says so"
    fi
else
    notok "patterns/loop.sh runs" "$(head -c 300 "$T/err")"
fi

check_fails "--frame K >= N" 2 t_noise -s 32 --frames 8 --frame 8 -o "$T/bad.exr"
check_fails "--frame without --frames" 2 t_turbulence -s 32 --frame 2 -o "$T/bad.exr"
check_fails "--frames on a fractal not made of noise" 2 t_fractal --mode julia -s 32 \
    --frames 4 -o "$T/bad.exr"
[ -e "$T/bad.exr" ] && notok "no output after a bad frame" || ok "no output after a bad frame"
