#!/usr/bin/env bash
# Every option a tool's --help lists appears in its man page's SYNOPSIS, by its short
# letter or its long name; the synopsis is made from the option rows (--help-synopsis,
# refreshed by make man), so a new row cannot be left out of it.
. "$(dirname "$0")/../lib.sh"
top=${TEXTURA_TOP:-.}
n=0
for bin in "$TEXTURA_BUILD"/bin/t_*; do
    tool=$(basename "$bin")
    page=$top/man/man1/$tool.1
    [ -f "$page" ] || { notok "$tool has a man page"; continue; }
    # the options of --help ("-x, --long" or "--long"), then the SYNOPSIS's words
    missing=$({ "$bin" --help | sed -En 's/^  (-([A-Za-z0-9]),|   ) --([a-z0-9-]+).*/opt \2 \3/p'
        awk '/^\.Sh SYNOPSIS/ { p = 1; next } /^\.Sh / { p = 0 } p' "$page"; } | awk '
        $1 == "opt" { if (NF == 2) { $3 = $2; $2 = "" } if ($3 != "help" && $3 != "version") want[$3] = $2; next }
        { for (i = 1; i < NF; i++) if ($i == "Fl") have[$(i + 1)] = 1 }
        END { for (o in want) if (!have["-" o] && !(want[o] != "" && have[want[o]])) printf " --%s", o }')
    [ -z "$missing" ] && ok "$tool(1): every option of --help in the SYNOPSIS" ||
        notok "$tool(1): every option of --help in the SYNOPSIS" "missing$missing"
    n=$((n + 1))
done
[ "$n" -ge 40 ] && ok "every tool was checked ($n)" || notok "every tool was checked" "$n"
# the rendered pages read as prose: no "default .." where a default ends in a full stop,
# no stray tab or accent standing for a symbol
bad=$(for p in "${TEXTURA_TOP:-.}"/man/man1/*.1 "${TEXTURA_TOP:-.}"/man/man5/*.5; do
    mandoc -Tutf8 "$p" 2>/dev/null | col -bx | grep -n 'default \.\.\|´' | sed "s|^|$(basename "$p"):|"
done)
[ -z "$bad" ] && ok "no page renders 'default ..' or an accent for a prime" || notok "rendered pages" "$bad"
