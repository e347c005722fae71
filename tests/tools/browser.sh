#!/usr/bin/env bash
# The editor in a real browser: headless chromium driven through the DevTools protocol
# (tests/tools/cdp.py) against t_proto on a free port.  The screenshot is kept as an artefact in
# BUILD/artefacts/t_proto.png.  Skipped, saying why, only when chromium cannot run.
. "$(dirname "$0")/../lib.sh"
top=${TEXTURA_TOP:-.}
chromium=$(command -v chromium || command -v chromium-browser || true)
if [ -z "$chromium" ]; then
    skip "the editor in a browser" "chromium is not installed (make deps installs it)"
    exit 0
fi
mkdir -p "$T/work"
start_proto "$T/work" --defs "$top/patterns/primitives.tp"
url=$proto_url
shot=${TEXTURA_BUILD:-build}/artefacts/t_proto.png
timeout 400 python3 "$top/tests/tools/cdp.py" "$chromium" "$url" "$T/work" "$shot" 2>"$T/cdp.err"
status=$?
if [ $status = 3 ]; then
    skip "the editor in a browser" "$(head -c 200 "$T/cdp.err")"
elif [ $status != 0 ]; then
    notok "the browser test ran to its end" "exit $status: $(tail -c 300 "$T/cdp.err" | tr "\n" " ")"
fi
