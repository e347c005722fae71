#!/usr/bin/env bash
# t_proto: the editor's server on a free port: token, previews from the descriptors,
# saves equal to the command line's output, confinement, bad requests and bursts.
. "$(dirname "$0")/../lib.sh"
top=${TEXTURA_TOP:-.}
mkdir -p "$T/work"
start_proto "$T/work" --defs "$top/patterns/primitives.tp"
url=$proto_url
proto_up "t_proto prints a 127.0.0.1 URL with a token" || exit 0
PYTHONPATH="$(dirname "$0")" python3 - "$url" "$T/work" "$T" <<'PY'
import http.client, json, os, subprocess, sys, threading, time, urllib.parse as up
from protoclient import Proto, say
url, work, tmp = sys.argv[1:4]
token, host, port, get = Proto(url).parts()

s, b = get("/", tok=False)
say(s == 403, "a request without the token gets 403", s)
s, b = get("/", [("token", "0" * 32)], tok=False)
say(s == 403, "a wrong token gets 403", s)
s, b = get("/")
say(s == 200 and b"<html" in b, "the page is served with the token", s)
s, b = get("/api/primitives")
j = json.loads(b)
names = {p["name"]: p for p in j["primitives"]}
freq = [r for r in names["noise"]["params"] if r["name"] == "frequency"]
say(freq and freq[0]["max"] == 1e6 and freq[0]["default"] == "8",
    "primitives and parameter rows come from the descriptors", freq)
say("marble" in names and names["marble"]["composed"] == 1 and
    any(r["name"] == "veins" for r in names["marble"]["params"]), "composed primitives are offered")

base = [("prim", "noise"), ("seed", "3")]
s1, a = get("/api/preview", base + [("p", "frequency:4")])
s2, b2 = get("/api/preview", base + [("p", "frequency:9")])
say(s1 == 200 and a[:8] == b"\x89PNG\r\n\x1a\n", "a preview is a PNG", s1)
say(s2 == 200 and a != b2, "moving the frequency changes the preview")
s, b = get("/api/preview", [("prim", "marble"), ("p", "veins:2"), ("step", "palette:marble")])
say(s == 200 and b[:4] == b"\x89PNG", "a composed primitive previews through t_expr --defs", (s, b[:80]))
s, pal = get("/api/preview", base + [("p", "frequency:4"), ("step", "palette:marble")])
say(s == 200 and pal != a, "a palette step changes the preview", s)
times = []
for _ in range(9):
    t0 = time.time(); get("/api/preview", [("prim", "noise"), ("p", "frequency:6")]); times.append(time.time() - t0)
times.sort()
say(times[4] < 0.5, "a 256x256 preview comes back quickly (median %.0f ms)" % (1000 * times[4]))

# save, then the command line in a shell gives the same bytes
q = base + [("p", "frequency:5"), ("step", "filter:median:2"), ("step", "palette:marble"),
            ("step", "blur:1.5"), ("step", "filter:emboss:2"), ("size", "200")]
for bad in ["filter:frob:1", "filter:median", "filter:smooth:2"]:
    s, b = get("/api/preview", base + [("step", bad)])
    say(s == 400, "a bad filter step is refused: " + bad, (s, b[:80]))
s, b = get("/api/save", q + [("kind", "map"), ("name", "saved.png")])
say(s == 200 and os.path.exists(os.path.join(work, "saved.png")), "a map is saved in the working folder", b)
s, cmd = get("/api/cmdline", q + [("map", "shell.png")])
r = subprocess.run(["sh", "-c", cmd.decode()], cwd=work, capture_output=True)
same = r.returncode == 0 and open(os.path.join(work, "saved.png"), "rb").read() == \
    open(os.path.join(work, "shell.png"), "rb").read()
say(same, "the command line run in a shell gives the saved map byte for byte", cmd.decode() + r.stderr.decode())
s, b = get("/api/save", q + [("kind", "cmdline"), ("name", "make.sh"), ("map", "again.png")])
r = subprocess.run(["sh", "make.sh"], cwd=work, capture_output=True)
say(s == 200 and r.returncode == 0 and open(os.path.join(work, "again.png"), "rb").read() ==
    open(os.path.join(work, "saved.png"), "rb").read(), "the saved command line file makes the same map", b)
s, b = get("/api/save", [("kind", "palette"), ("name", "two.pal"),
                        ("text", "space oklab\n0 #203060\n1 #f0e0b0\n")])
subprocess.run(["t_noise", "-s", "16", "-o", os.path.join(tmp, "n.exr")], check=True)
r = subprocess.run(["t_palette", os.path.join(work, "two.pal"), os.path.join(tmp, "n.exr"),
                    "-o", os.path.join(tmp, "p.exr")], capture_output=True)
say(s == 200 and r.returncode == 0, "a palette from the editor is saved and t_palette reads it", b)
s, b = get("/api/preview", base + [("step", "palette:two.pal")])
say(s == 200 and b[:4] == b"\x89PNG", "a saved palette serves as a pipeline step", (s, b[:80]))
# the palettes are a list (they were one string, split wrong by the page), each a step
pals = j["palettes"]
say(isinstance(pals, list) and "marble" in pals and all(" " not in n and "," not in n for n in pals),
    "the palettes are a list of names", pals)
bad = [n for n in pals if get("/api/preview", base + [("step", "palette:" + n)])[0] != 200]
say(isinstance(pals, list) and len(pals) >= 10 and not bad, "every palette listed works as a step", bad)
s, b = get("/api/primitives")
say("two.pal" in json.loads(b)["palettes"], "a palette saved in the folder is listed")
rows = {r["name"]: r for r in names["fractal"]["params"]}
say(rows.get("ridge_gain", {}).get("kinds") == 2 and rows.get("mode", {}).get("kinds") == 0 and
    rows.get("octaves", {}).get("kinds") == 7, "each row gives the modes it applies to (kinds)",
    [(k, r.get("kinds")) for k, r in rows.items()][:6])
# saving over a file: refused (409) unless the request says overwrite=1
pal = os.path.join(work, "two.pal")
before = open(pal).read()
s, b = get("/api/save", [("kind", "palette"), ("name", "two.pal"), ("text", "space rgb\n0 #000000\n1 #ffffff\n")])
say(s == 409 and open(pal).read() == before, "saving over a file is refused (409) and leaves it", (s, b))
s, b = get("/api/save", [("kind", "palette"), ("name", "two.pal"), ("overwrite", "1"),
                         ("text", "space oklab\n0 #102040\n1 #f0e0b0\n")])
say(s == 200 and "#102040" in open(pal).read(), "overwrite=1 replaces it", (s, b))
# the standard scene: bump with a strength, a Ks view that shows the map
from cdp import png_pixels
def grey(png):
    w, h, ch, rows = png_pixels(png)
    return [sum(r[x * ch:x * ch + 3]) / 3 for r in rows for x in range(w)]
def diff(a, b):
    return sum(abs(x - y) for x, y in zip(grey(a), grey(b))) / len(grey(a))
s1, soft = get("/api/scene", base + [("apply", "bump"), ("strength", "0.05")])
s2, hard = get("/api/scene", base + [("apply", "bump"), ("strength", "2")])
say(s1 == 200 and s2 == 200 and soft != hard, "the bump's strength is a control", (s1, s2))
s, b = get("/api/scene", base + [("apply", "bump"), ("strength", "5000")])
say(s == 400 and b"strength must be -1000..1000" in b, "a bump strength out of range is refused", (s, b))
s, b = get("/api/scene", base + [("apply", "Kr")])
s2, b2 = get("/api/scene", base + [("apply", "Kt")])
say(s == 200 and b[:4] == b"\x89PNG" and s2 == 400 and b"Kd, Ks, Kr or bump" in b2,
    "the scene's application functions are Kd, Ks, Kr and bump", (s, s2, b2[:80]))
s1, a = get("/api/scene", [("prim", "noise"), ("p", "frequency:3"), ("apply", "Ks")])
s2, c = get("/api/scene", [("prim", "noise"), ("p", "frequency:12"), ("apply", "Ks")])
d = diff(a, c) if s1 == s2 == 200 else 0
say(d > 2, "the Ks view shows the map: two maps differ by %.1f grey levels a pixel" % d, (s1, s2))
proj = json.dumps({"format": "t_proto project 1", "name": "m.png", "size": 200,
                   "primitive": "noise", "params": dict(p.split(":") for k, p in q if k == "p")})
s, b = get("/api/save", [("kind", "project"), ("name", "p.tproj"), ("text", proj)])
s2, b2 = get("/api/load", [("name", "p.tproj")])
say(s == 200 and s2 == 200 and b2.decode() == proj, "a project is saved and loaded back", b)
s, b = get("/api/save", [("kind", "project"), ("name", "q.tproj"), ("text", up.urlencode(q))])
say(s == 400 and b"JSON" in b and not os.path.exists(os.path.join(work, "q.tproj")),
    "a project that is not JSON is refused", (s, b))
s, b = get("/api/save", q + [("kind", "scene"), ("name", "t.scene")])
text = open(os.path.join(work, "t.scene")).read() if s == 200 else ""
say(s == 200 and text.startswith("# t_noise") and "texture map file -" in text,
    "a scene's texture statement is saved", (s, b, text))
s, b = get("/api/scene", base + [("apply", "bump")])
say(s == 200 and b[:4] == b"\x89PNG", "the standard scene renders the map (bump)", s)

# confinement and bad requests: each a 4xx, the server alive after
os.symlink(os.path.join(tmp, "outside.png"), os.path.join(work, "evil.png"))
for name, params in [
        ("a path with ..", [("kind", "map"), ("name", "../up.png")]),
        ("an absolute path", [("kind", "map"), ("name", os.path.join(tmp, "abs.png"))]),
        ("a symlink out of the folder", [("kind", "map"), ("name", "evil.png")]),
        ("a project through ..", [("kind", "project"), ("name", "../p.tproj"), ("text", "x")]),
        ("a command line whose map is out of the folder",
         [("kind", "cmdline"), ("name", "out.sh"), ("map", "../out.png")]),
        ("a command line without a map", [("kind", "cmdline"), ("name", "out.sh")]),
        ("a kind it does not know", [("kind", "frob"), ("name", "x.txt")])]:
    s, b = get("/api/save", base + params)
    say(s == 400, "save refuses " + name, (s, b))
say(not os.path.exists(os.path.join(work, "out.sh")), "a refused command line leaves no file")
say(not os.path.exists(os.path.join(tmp, "outside.png")) and not os.path.exists(os.path.join(tmp, "up.png"))
    and not os.path.exists(os.path.join(tmp, "abs.png")), "nothing was written outside the working folder")
s, b = get("/api/load", [("name", "../url")])
say(s == 400, "load refuses a path out of the folder", s)
for name, params, want in [
        ("an out-of-range parameter", base + [("p", "frequency:-3")], b"--frequency must be 0..1000000"),
        ("a parameter the primitive lacks", base + [("p", "octaves:3")], b"noise has no parameter 'octaves'"),
        ("a malformed parameter", base + [("p", "frequency")], b"malformed parameter"),
        ("an unknown primitive", [("prim", "nosuch")], b"unknown primitive"),
        ("a size too large", base + [("size", "100000")], b"size must be 1..4096"),
        ("an unknown step", base + [("step", "rm:-rf")], b"unknown step"),
        ("a palette that is a path", base + [("step", "palette:/etc/passwd")], b"malformed step argument"),
        ("an option smuggled as a value", base + [("p", "frequency:4 -o x")], b"frequency")]:
    s, b = get("/api/preview", params)
    say(400 <= s < 500 and want in b, "a 4xx with the message for " + name, (s, b))
c = http.client.HTTPConnection(host, port, timeout=30)
c.putrequest("POST", "/api/preview?token=" + token)
c.putheader("Content-Length", str(100 << 20))
c.endheaders()
try:
    c.send(b"x" * 65536)
except OSError:
    pass
r = c.getresponse()
say(r.status == 413, "a 100 MB body is refused (413) without being read", r.status)
c.close()

codes = {}
def burst(n):
    for _ in range(n):
        try:
            s, _ = get("/api/primitives", pace=False)
        except Exception as e:
            s = "error"
        codes[s] = codes.get(s, 0) + 1
ts = [threading.Thread(target=burst, args=(125,)) for _ in range(8)]
[t.start() for t in ts]; [t.join() for t in ts]
say(codes.get(429, 0) > 0 and set(codes) <= {200, 429}, "1000 requests in a burst: 200 or 429, nothing else", codes)
# the limiter refills: poll for the first 200 rather than sleep its whole window
end = time.time() + 10
while True:
    s, b = get("/api/preview", base)
    if s == 200 or time.time() > end:
        break
    time.sleep(0.05)
say(s == 200, "the server keeps serving after all that", s)
PY
