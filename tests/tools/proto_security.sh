#!/usr/bin/env bash
# t_proto's defences (issue 60, item 6): values quoted for the shell in the command lines it
# shows and saves, no newline into a scene, files only from inside the working folder and
# within the input limit, Host and Origin checked, the rate limit per client and for
# requests with the token only, bodies and query parameters bounded, slow clients dropped
# and never starving new ones, a folder path of any length, the temporary folder removed on
# a signal, and messages that name the limits.
. "$(dirname "$0")/../lib.sh"
mkdir -p "$T/work" "$T/tmp"
export TEXTURA_MAX_INPUT=1M
TMPDIR=$T/tmp start_proto "$T/work"
url=$proto_url
proto_up "t_proto starts" || exit 0
PYTHONPATH="$(dirname "$0")" python3 - "$url" "$T/work" "$T" <<'PY'
import http.client, os, shlex, socket, subprocess, sys, threading, time, urllib.parse as up
from protoclient import Proto, say
url, work, tmp = sys.argv[1:4]
token, host, port, get = Proto(url).parts()

# shell quoting: a quote in a value cannot end the word in the command line shown or saved
evil = "#fff'; touch PWNED; echo '"
q = [("prim", "weave"), ("p", "warp_colours:" + evil)]
s, cmd = get("/api/cmdline", q + [("map", "w.png")])
words = shlex.split(cmd.decode()) if s == 200 else []
say(s == 200 and "--warp-colours=" + evil in words,
    "a quote in a value stays inside its word of the command line", (s, cmd))
subprocess.run(["sh", "-c", cmd.decode()], cwd=work, capture_output=True)
say(not os.path.exists(os.path.join(work, "PWNED")), "the command line shown runs nothing else")
s, b = get("/api/save", q + [("kind", "cmdline"), ("name", "run.sh"), ("map", "w.png")])
subprocess.run(["sh", "run.sh"], cwd=work, capture_output=True)
say(s == 200 and not os.path.exists(os.path.join(work, "PWNED")), "a saved run.sh runs nothing else", b)

# a newline in a value would end the scene's comment line
nl = 'euclid\ntexture evil file "/etc/shadow"'
s, b = get("/api/save", [("prim", "bubble"), ("p", "metric:" + nl), ("kind", "scene"),
                         ("name", "t.scene")])
text = open(os.path.join(work, "t.scene")).read() if os.path.exists(os.path.join(work, "t.scene")) else ""
say(s == 400 and b"control character" in b and "texture evil" not in text,
    "a newline in a value is refused, and no scene statement is written", (s, b, text))

# files a parameter names: inside the folder, plain, within the input limit
open(os.path.join(tmp, "outside.pts"), "w").write("0.5 0.5\n")
open(os.path.join(work, "in.pts"), "w").write("0.25 0.25\n0.75 0.5\n")
os.symlink("/etc/passwd", os.path.join(work, "link.pts"))
os.mkfifo(os.path.join(work, "fifo.pts"))
with open(os.path.join(work, "big.pts"), "w") as f:
    f.write("0.5 0.5\n" * 200000)
for name, v, want in [("an absolute path outside", "/etc/passwd", b"not a file inside"),
                      ("a path through ..", "../outside.pts", b"not a file inside"),
                      ("a symlink out of the folder", "link.pts", b"not a file inside"),
                      ("a device", "/dev/zero", b"not a file inside"),
                      ("a fifo in the folder", "fifo.pts", b"not a plain file"),
                      ("a file over the input limit", "big.pts", b"over the input limit")]:
    t0 = time.time()
    s, b = get("/api/preview", [("prim", "bubble"), ("p", "points:" + v)])
    say(400 <= s < 500 and want in b and b"root:" not in b and time.time() - t0 < 5,
        "a points file refused: " + name, (s, b[:120]))
s, b = get("/api/preview", [("prim", "bubble"), ("p", "points:in.pts")])
say(s == 200 and b[:4] == b"\x89PNG", "a points file inside the folder is read", (s, b[:120]))

# slow runs do not hold other requests: four /dev/zero requests, then another
res = []
ts = [threading.Thread(target=lambda: res.append(get("/api/preview", [("prim", "bubble"),
                                                    ("p", "points:/dev/zero")])[0])) for _ in range(4)]
[t.start() for t in ts]
t0 = time.time(); s, b = get("/api/primitives"); dt = time.time() - t0
[t.join() for t in ts]
say(s == 200 and dt < 2 and res == [400] * 4, "four /dev/zero requests hold nothing (%.2f s)" % dt, (s, res))

# Host and Origin
s, b = get("/api/primitives", headers={"Host": "evil.example:%d" % port})
say(s == 403 and b"Host" in b, "another Host is refused (DNS rebinding)", (s, b))
s, b = get("/api/primitives", headers={"Host": "localhost:%d" % port})
say(s == 200, "localhost:PORT is a Host of its own", (s, b[:80]))
s, b = get("/api/primitives", headers={"Origin": "http://evil.example"})
say(s == 403 and b"Origin" in b, "another site's Origin is refused", (s, b))
s, b = get("/api/primitives", headers={"Origin": "http://127.0.0.1:%d" % port})
say(s == 200, "its own Origin is served", s)

# the rate limit: requests without the token do not use it up; each client has its own
for _ in range(80):
    get("/api/primitives", tok=False)
s, b = get("/api/primitives")
say(s == 200, "80 requests without the token leave the page's requests served", (s, b[:80]))
# a burst from another client, eight requests at a time until one gets 429 (at most 20 s): its
# bucket (BURST 60, refilled by RATE 40 a second) serves no more than 60 + 40 a second of the
# burst, however slow the machine, and the page's client is still served
codes, lock, t0 = {}, threading.Lock(), time.time()
def burst():
    while time.time() - t0 < 20 and not codes.get(429):
        s, b = get("/api/primitives", source="127.0.0.2", pace=False)
        with lock:
            codes[s] = codes.get(s, 0) + 1
ts = [threading.Thread(target=burst) for _ in range(8)]
[t.start() for t in ts]
[t.join() for t in ts]
dt = time.time() - t0
s, b = get("/api/primitives")
say(codes.get(429, 0) > 0 and 0 < codes.get(200, 0) <= 60 + 40 * dt + 1 and s == 200,
    "a burst from one client is limited to its bucket, and leaves another served", (codes, dt, s))

# bodies and query parameters
c = socket.create_connection((host, port), timeout=10)
c.sendall(("POST /api/preview?token=%s HTTP/1.1\r\nHost: 127.0.0.1:%d\r\n"
           "Transfer-Encoding: chunked\r\n\r\n" % (token, port)).encode())
got = b""
try:
    for _ in range(16):
        c.sendall(b"10000\r\n" + b"x" * 65536 + b"\r\n")
except OSError:
    pass
try:
    while True:
        chunk = c.recv(4096)
        if not chunk:
            break
        got += chunk
except OSError:
    pass
c.close()
say(got.startswith(b"HTTP/1.1 413"), "a 1 MB chunked body gets 413", got[:60])
t0 = time.time()
try:
    s, b = get("/api/preview", [("prim", "noise")] + [("x%d" % i, "1") for i in range(1000)], timeout=10)
except Exception as e:
    s, b = str(e), b""
say(s == 400 and b"query parameters" in b and time.time() - t0 < 3,
    "1000 query parameters get 400 at once (%.2f s)" % (time.time() - t0), (s, b))

# slow clients: 150 connections (more than any connection limit) sending a byte a second; new
# ones are served, the slow dropped
slow = []
for _ in range(150):
    try:
        k = socket.create_connection((host, port), timeout=10)
        k.sendall(b"G")
        slow.append(k)
    except OSError:
        pass
stop = time.time() + 8
def trickle():
    while time.time() < stop:
        for k in slow:
            try:
                k.sendall(b"E")
            except OSError:
                pass
        time.sleep(1)
tt = threading.Thread(target=trickle); tt.start()
time.sleep(1)
t0 = time.time()
try:
    s, b = get("/api/primitives", timeout=5)
except Exception as e:
    s = str(e)
say(s == 200 and time.time() - t0 < 2, "150 trickling clients leave a new one served (%.2f s)"
    % (time.time() - t0), s)
tt.join()
closed = 0
for k in slow:
    try:
        k.settimeout(0.5)
        closed += k.recv(100) == b""
    except OSError:
        closed += 1
    k.close()
say(closed == len(slow), "a client trickling a byte a second is dropped within its time (%d of %d)"
    % (closed, len(slow)))

# the steps' limit is the one the message gives
steps = [("step", "invert")] * 8
s, b = get("/api/preview", [("prim", "noise")] + steps)
say(s == 200, "8 steps are taken", (s, b[:80]))
s, b = get("/api/preview", [("prim", "noise")] + steps + [("step", "invert")])
say(s == 400 and b"too many steps (at most 8)" in b, "a 9th step is refused, the message saying 8", (s, b))
PY

# a working folder whose path is longer than any fixed buffer of a word
long=$T/$(printf 'folder-of-a-long-name-%02d/' $(seq 1 9))
mkdir -p "$long"
kill "$proto_pid" 2>/dev/null
wait "$proto_pid" 2>/dev/null
start_proto "$long"
proto_up "t_proto serves a working folder of $(printf %s "$long" | wc -c) characters" &&
PYTHONPATH="$(dirname "$0")" python3 - "$proto_url" "$long" <<'PY'
import sys
from protoclient import Proto, say
url, work = sys.argv[1:3]
token, host, port, get = Proto(url).parts()
s1, b1 = get("/api/save", [("kind", "palette"), ("name", "two.pal"), ("text", "space rgb\n0 #000000\n1 #ff8000\n")])
s2, b2 = get("/api/preview", [("prim", "noise"), ("step", "palette:two.pal")])
s3, b3 = get("/api/scene", [("prim", "noise")])
say(s1 == 200 and s2 == 200 and b2[:4] == b"\x89PNG" and s3 == 200,
    "in a working folder of %d characters, a saved palette and the scene work" % len(work),
    [(s1, b1[:80]), (s2, b2[:120]), (s3, b3[:80])])
PY
kill "$proto_pid" 2>/dev/null
wait "$proto_pid" 2>/dev/null

# the port: busy gives a message naming it and the range, status 1
t_proto -C "$T/work" -p 0 >"$T/a.url" 2>/dev/null &
a=$!
for _ in $(seq 50); do grep -q token= "$T/a.url" && break; sleep 0.1; done
busy=$(sed -n 's/.*127\.0\.0\.1:\([0-9]*\)\/.*/\1/p' "$T/a.url")
t_proto -C "$T/work" -p "$busy" >/dev/null 2>"$T/busy.err"
st=$?
if [ $st = 1 ] && grep -q "127.0.0.1:$busy" "$T/busy.err" && grep -q "0\.\.65535" "$T/busy.err"; then
    ok "a busy port is named with -p's range (status 1)"
else
    notok "a busy port is named with -p's range (status 1)" "status $st: $(cat "$T/busy.err")"
fi
kill $a 2>/dev/null
wait $a 2>/dev/null

# the temporary folder goes with it on SIGTERM, SIGINT and SIGHUP
for sig in TERM INT HUP; do
    rm -rf "$T/tmp"/t_proto.* "$T/s.url"
    TMPDIR=$T/tmp t_proto -C "$T/work" -p 0 >"$T/s.url" 2>"$T/s.err" &
    pid=$!
    for _ in $(seq 50); do grep -q token= "$T/s.url" && break; sleep 0.1; done
    u=$(sed -n 's/.* on \(http:[^ ]*\)$/\1/p' "$T/s.url")
    python3 -c "import urllib.request,sys; urllib.request.urlopen(sys.argv[1].replace('/?', '/api/scene?') + '&prim=noise').read()" "$u" 2>/dev/null
    made=$(ls -d "$T/tmp"/t_proto.* 2>/dev/null | wc -l)
    kill -s $sig $pid
    wait $pid 2>/dev/null
    st=$?
    left=$(ls -d "$T/tmp"/t_proto.* 2>/dev/null | wc -l)
    # status 0 and nothing said: a sanitizer build's leak report would be here
    if [ "$made" = 1 ] && [ "$left" = 0 ] && [ $st = 0 ] && [ ! -s "$T/s.err" ]; then
        ok "the temporary folder is removed on SIG$sig, and t_proto ends cleanly"
    else
        notok "the temporary folder is removed on SIG$sig, and t_proto ends cleanly" \
            "made $made, left $left, status $st: $(head -c 300 "$T/s.err")"
    fi
done
