#!/usr/bin/env bash
# t_proto's node graphs (/api/graph): every node kind of the catalog previews with its
# defaults; the shell export gives the preview's bytes (fan-out, constants, an inner node,
# the 3D scene through the t_apply export); t_compose's export runs; bad graphs get 400
# naming the node; exports and projects are saved without overwriting.
. "$(dirname "$0")/../lib.sh"
top=${TEXTURA_TOP:-.}
mkdir -p "$T/work"
start_proto "$T/work" --defs "$top/patterns/primitives.tp"
proto_up "t_proto prints a 127.0.0.1 URL with a token" || exit 0
PYTHONPATH="$(dirname "$0")" python3 - "$proto_url" "$T/work" <<'PY'
import json, os, subprocess, sys
from protoclient import Proto, say
url, work = sys.argv[1:3]
token, host, port, get = Proto(url).parts()

def graph(q, **extra):
    """(status, body) of /api/graph for the graph q (a dict)"""
    return get("/api/graph", [("graph", json.dumps(q))] + list(extra.items()))

def sh(cmd, **kw):
    return subprocess.run(cmd, cwd=work, capture_output=True, **kw)

def spread(png):
    """the largest channel's standard deviation of a PNG, by t_info"""
    path = os.path.join(work, "spread.png")
    open(path, "wb").write(png)
    r = sh(["t_info", "--json", "spread.png"])
    return max(c["stddev"] for c in json.loads(r.stdout)["stats"]) if r.returncode == 0 else -1

s, b = get("/api/primitives")
cat = json.loads(b)
kinds = {k["name"]: k for k in cat["kinds"]}
say(sorted(kinds) == sorted(["op", "palette", "filter", "remap", "xform", "warp", "cascade", "tile"]),
    "the catalog lists every operator kind", sorted(kinds))
rows = lambda k: {r["name"]: r for r in kinds[k]["params"]}
say(rows("op")["op"]["operand"] == 1 and "mix" in rows("op")["op"]["choices"] and
    rows("op")["threshold"]["default"] == "0.5" and rows("filter")["sigma"]["min"] == 0.01,
    "operator rows come from the tools' --help-json, with their defaults and ranges", rows("op"))
say("from" not in rows("palette") and "list" not in rows("palette") and "size" not in rows("tile"),
    "rows that make no map from the inputs, or that t_proto sets, are not offered")
say(kinds["warp"]["slots"] == ["map", "by"] and kinds["cascade"]["needs"] == 2,
    "each kind names its input slots", kinds["warp"]["slots"])

# every node kind with its defaults: a primitive alone, an operator fed by noise
noise = {"id": "n", "kind": "noise", "params": {"seed": 5}}
blank = []
for p in cat["primitives"]:
    s, b = graph({"nodes": [{"id": "x", "kind": p["name"]}], "output": "x"}, size="64")
    if s != 200 or spread(b) <= 0:
        blank.append((p["name"], s, b[:100]))
say(not blank, "every primitive (%d) previews with its defaults, not blank" % len(cat["primitives"]), blank)
feeds = {"cascade": [({"id": "i", "kind": "brick", "params": {"ids": 1}}, "ids"), (noise, "1")],
         "warp": [({"id": "w", "kind": "wood"}, "map"), (noise, "by")]}
unlike = []

def same_as_export(q, png, name):
    """the shell export of q at 64, run here, writes png"""
    s, script = graph(q, size="64", what="sh", map="k.png")
    open(os.path.join(work, "k.sh"), "wb").write(script)
    r = sh(["sh", "k.sh"])
    if s != 200 or r.returncode or open(os.path.join(work, "k.png"), "rb").read() != png:
        unlike.append((name, s, r.stderr[:100]))
for k in kinds:
    src = feeds.get(k, [(noise, s) for s in kinds[k]["slots"][:kinds[k]["needs"]]])
    nodes = {n["id"]: n for n, _ in src}
    q = {"nodes": list(nodes.values()) + [{"id": "k", "kind": k}],
         "edges": [{"from": n["id"], "to": "k", "slot": sl} for n, sl in src], "output": "k"}
    s, b = graph(q, size="64")
    if s != 200 or spread(b) <= 0:
        blank.append((k, s, b[:100]))
    same_as_export(q, b, k)
for op in rows("op")["op"]["choices"].split("|"):
    n = 1 if op in ("abs", "invert", "threshold") else 3 if op == "mix" else 2
    q = {"nodes": [noise, {"id": "m", "kind": "wood"}, {"id": "k", "kind": "op", "params": {"op": op}}],
         "edges": [{"from": f, "to": "k", "slot": sl} for f, sl in zip("nmn", "abw")][:n], "output": "k"}
    s, b = graph(q, size="64")
    if s != 200:
        blank.append(("op " + op, s, b[:100]))
    same_as_export(q, b, "op " + op)
say(not blank, "every operator kind and every operation previews with its defaults", blank)
say(not unlike, "for each, the shell export writes the preview's bytes", unlike)

# the shell export gives the preview's bytes
fan = {"nodes": [{"id": "n", "kind": "noise", "params": {"frequency": 4, "seed": 3}},
                 {"id": "s", "kind": "wood"},
                 {"id": "w", "kind": "warp", "params": {"displacement": "0.2"}},
                 {"id": "p", "kind": "palette", "params": {"palette": "marble"}},
                 {"id": "f", "kind": "filter", "params": {"op": "emboss", "strength": 2}},
                 {"id": "m", "kind": "op", "params": {"op": "mix"}}],
       "edges": [{"from": "s", "to": "w", "slot": "map"}, {"from": "n", "to": "w", "slot": "by"},
                 {"from": "w", "to": "p", "slot": "in"}, {"from": "p", "to": "m", "slot": "a"},
                 {"from": "n", "to": "f", "slot": "in"}, {"from": "f", "to": "m", "slot": "b"},
                 {"from": "n", "to": "m", "slot": "w"}], "output": "m"}
diamond = {"nodes": [{"id": "a", "kind": "marble", "params": {"veins": 2}},
                     {"id": "b", "kind": "filter", "params": {"op": "blur", "sigma": 3}},
                     {"id": "c", "kind": "remap", "params": {"gamma": "2.2", "invert": True}},
                     {"id": "d", "kind": "op", "params": {"op": "max"}},
                     {"id": "e", "kind": "op", "params": {"op": "mul", "b": "0.5"}},
                     {"id": "t", "kind": "tile", "params": {"nu": 3, "mirror": 1}}],
           "edges": [{"from": "a", "to": "b", "slot": "in"}, {"from": "a", "to": "c", "slot": "in"},
                     {"from": "b", "to": "d", "slot": "a"}, {"from": "c", "to": "d", "slot": "b"},
                     {"from": "d", "to": "e", "slot": "a"}, {"from": "e", "to": "t", "slot": "1"}],
           "output": "t"}
cells = {"nodes": [{"id": "ids", "kind": "brick", "params": {"ids": 1, "seed": 2}},
                   {"id": "g", "kind": "noise", "params": {"seed": 9}},
                   {"id": "h", "kind": "palette", "params": {"palette": "brick"}},
                   {"id": "k", "kind": "cascade"}, {"id": "x", "kind": "xform", "params": {"rotate": 30}}],
         "edges": [{"from": "ids", "to": "k", "slot": "ids"}, {"from": "g", "to": "k", "slot": "1"},
                   {"from": "g", "to": "h", "slot": "in"}, {"from": "h", "to": "k", "slot": "2"},
                   {"from": "k", "to": "x", "slot": "in"}], "output": "x"}
for name, q, node, size in [("fan-out", fan, None, "128"), ("a diamond and a constant", diamond, None, "96"),
                            ("a cascade", cells, None, "100"), ("an inner node", fan, "w", "80")]:
    extra = {"size": size, **({"node": node} if node else {})}
    s1, prev = graph(q, **extra)
    s2, script = graph(q, what="sh", map="out.png", **extra)
    open(os.path.join(work, "g.sh"), "wb").write(script)
    for f in os.listdir(work):
        if f.endswith(".exr") or f == "out.png":
            os.unlink(os.path.join(work, f))
    r = sh(["sh", "g.sh"])
    got = open(os.path.join(work, "out.png"), "rb").read() if r.returncode == 0 else b""
    say(s1 == s2 == 200 and prev[:4] == b"\x89PNG" and got == prev,
        "the shell export of %s gives the preview's bytes" % name,
        (s1, s2, prev[:80], script.decode()[:600], r.stderr[:200]))
s, script = graph(fan, what="sh", size="64")
lines = [l for l in script.decode().splitlines() if not l.startswith("#")]
say(sum(l.count("t_noise") for l in lines) == 1 and any(l.endswith("--compression=none -o n.exr") for l in lines) and
    sum(l.count(" n.exr") for l in lines) == 4,  # written once, read by w, f and m "a map feeding several nodes is made once, into a named file",
    script.decode()[:600])

# a map is kept for the next request: an edit reruns only what is downstream of it
import glob
def kept():
    return {f: os.stat(f).st_mtime_ns for f in glob.glob(os.path.join(os.environ.get("TMPDIR", "/tmp"),
                                                                      "t_proto.*", "g.*.exr"))}
before = kept()
s1, a = graph(fan, size="48")
k1 = {f: t for f, t in kept().items() if f not in before}
fan2 = json.loads(json.dumps(fan))
fan2["nodes"][5]["params"]["op"] = "add"
fan2["edges"] = [e for e in fan2["edges"] if e["slot"] != "w"]
s2, b = graph(fan2, size="48")
k2 = {f: t for f, t in kept().items() if f not in before}
fan3 = json.loads(json.dumps(fan))
fan3["nodes"][0]["params"]["frequency"] = 5
s3, c = graph(fan3, size="48")
k3 = {f: t for f, t in kept().items() if f not in before}
# a preview keeps every node's map but the output's (n, s, w, p, f); the noise's edit remakes
# those below it (n, w, p, f), the wood's is reused
say(s1 == s2 == s3 == 200 and len(k1) == 5 and set(k2) == set(k1) and len(k3) == 9 and
    set(k1) <= set(k3) and a != b and a != c,
    "every node's map is kept: editing the output reuses them all, editing the noise remakes those below it",
    (s1, s2, s3, len(k1), len(k2), len(k3)))
# a palette saved again under its name is not taken from a kept map
pal = lambda c: "space rgb\n0 #000000\n1 %s\n" % c
s, b = get("/api/save", [("kind", "palette"), ("name", "mine.pal"), ("text", pal("#ff0000"))])
pg = {"nodes": [{"id": "n", "kind": "noise"}, {"id": "p", "kind": "palette", "params": {"palette": "mine.pal"}},
                {"id": "m", "kind": "op", "params": {"op": "max"}}],
      "edges": [{"from": "n", "to": "p", "slot": "in"}, {"from": "p", "to": "m", "slot": "a"},
                {"from": "p", "to": "m", "slot": "b"}], "output": "m"}
s1, red = graph(pg, size="32")
s, b = get("/api/save", [("kind", "palette"), ("name", "mine.pal"), ("text", pal("#00ff00")), ("overwrite", "1")])
s2, green = graph(pg, size="32")
say(s1 == s2 == 200 and red != green, "a palette saved again changes the graph's preview", (s1, s2, s, b))

# the 3D preview, and the t_apply export of it: the same scene, the same bytes
s1, scene = graph(fan, what="scene", apply="bump", strength="0.5", size="64")
s2, text = graph(fan, what="apply", apply="bump", strength="0.5", size="64", map="fan.exr")
s3, script = graph(fan, what="sh", size="64", map="fan.exr")
open(os.path.join(work, "fan.sh"), "wb").write(script)
open(os.path.join(work, "fan.scene"), "wb").write(text)
r = sh(["sh", "-c", "sh fan.sh && t_apply fan.scene -q --format=png > fan.png"])
got = open(os.path.join(work, "fan.png"), "rb").read() if r.returncode == 0 else b""
say(s1 == s2 == s3 == 200 and b"bump = 0.5" in text and b'file "fan.exr"' in text and got == scene,
    "the 3D preview is the t_apply export's scene over the shell export's map, byte for byte",
    (s1, s2, s3, text[:300], r.stderr[:200]))
s, other = graph(fan, what="scene", apply="Kd", size="64")
say(s == 200 and other != scene and spread(other) > 0, "the application function changes the 3D preview")

# t_compose: what it can say runs; what it cannot is named
simple = {"nodes": [{"id": "a", "kind": "noise", "params": {"frequency": 6, "seed": 2}},
                    {"id": "b", "kind": "filter", "params": {"op": "emboss", "strength": 2}},
                    {"id": "c", "kind": "op", "params": {"op": "over"}},
                    {"id": "d", "kind": "warp", "params": {"displacement": 0.3}},
                    {"id": "e", "kind": "wood"}, {"id": "f", "kind": "op", "params": {"op": "mix"}}],
          "edges": [{"from": "a", "to": "b", "slot": "in"}, {"from": "b", "to": "c", "slot": "a"},
                    {"from": "a", "to": "c", "slot": "b"}, {"from": "c", "to": "d", "slot": "map"},
                    {"from": "a", "to": "d", "slot": "by"}, {"from": "d", "to": "f", "slot": "a"},
                    {"from": "e", "to": "f", "slot": "b"}, {"from": "a", "to": "f", "slot": "w"}],
          "output": "f"}
s, tc = graph(simple, what="compose", size="64")
s2, prev = graph(simple, size="64")
open(os.path.join(work, "g.tc"), "wb").write(tc)
r = sh(["sh", "-c", "t_compose g.tc --format=png > tc.png"])
got = open(os.path.join(work, "tc.png"), "rb").read() if r.returncode == 0 else b""
say(s == s2 == 200 and b"d = warp c by a amount 0.3;" in tc and b"e = wood(seed = 1)" in tc and got == prev,
    "the t_compose export gives the preview's bytes where t_compose says the graph (the tools' seed written)",
    (s, tc.decode(), r.stderr[:300]))
s, b = graph(fan, what="compose", size="64")
say(s == 400 and b"node 'p' (palette marble) has no t_compose equivalent" in b,
    "a node with no t_compose equivalent is named", (s, b))

# bad graphs: 400 naming the node
def bad(name, q, want, status=400):
    s, b = graph(q) if not isinstance(q, str) else get("/api/graph", [("graph", q)])
    say(s == status and want.encode() in b, name, (s, b[:200]))
bad("a cycle is refused, naming a node in it",
    {"nodes": [{"id": "a", "kind": "remap"}, {"id": "b", "kind": "remap"}],
     "edges": [{"from": "a", "to": "b", "slot": "in"}, {"from": "b", "to": "a", "slot": "in"}], "output": "b"},
    "the graph has a cycle through node 'a'")
s, b = graph({"nodes": [{"id": "c", "kind": "remap"}, {"id": "a", "kind": "remap"}, {"id": "b", "kind": "remap"}],
               "edges": [{"from": "a", "to": "c", "slot": "in"}, {"from": "a", "to": "b", "slot": "in"},
                         {"from": "b", "to": "a", "slot": "in"}], "output": "c"})
say(s == 400 and b in (b"the graph has a cycle through node 'a'", b"the graph has a cycle through node 'b'"),
    "a cycle is named by a node on it, not by one it feeds", (s, b))
bad("a dangling input is refused, naming the node and the slot",
    {"nodes": [noise, {"id": "o", "kind": "op"}], "edges": [{"from": "n", "to": "o", "slot": "a"}], "output": "o"},
    "node 'o' (op): input 'b' is not connected")
bad("an unknown kind is refused, naming the node",
    {"nodes": [{"id": "z", "kind": "frobnicate"}]}, "node 'z': unknown kind 'frobnicate'")
bad("more than 32 nodes are refused",
    {"nodes": [{"id": "n%d" % i, "kind": "noise"} for i in range(33)], "output": "n0"},
    "too many nodes (33; at most 32)")
bad("a parameter out of its range names the node and the option",
    {"nodes": [noise, {"id": "f", "kind": "filter", "params": {"sigma": 0}}],
     "edges": [{"from": "n", "to": "f", "slot": "in"}], "output": "f"}, "node 'f' (filter): --sigma must be")
bad("a primitive's parameter is checked by its row",
    {"nodes": [{"id": "q", "kind": "noise", "params": {"frequency": 2e7}}]}, "node 'q' (noise): --frequency must be")
bad("an input on a primitive is refused",
    {"nodes": [noise, {"id": "q", "kind": "wood"}], "edges": [{"from": "n", "to": "q", "slot": "in"}], "output": "q"},
    "node 'q' (wood) takes no input")
bad("an unknown slot is refused",
    {"nodes": [noise, {"id": "q", "kind": "remap"}], "edges": [{"from": "n", "to": "q", "slot": "x"}], "output": "q"},
    "node 'q' (remap) has no input 'x'")
bad("an unknown palette is refused",
    {"nodes": [noise, {"id": "q", "kind": "palette", "params": {"palette": "nope"}}],
     "edges": [{"from": "n", "to": "q", "slot": "in"}], "output": "q"}, "node 'q' (palette): unknown palette 'nope'")
bad("a control character in a value is refused",
    {"nodes": [noise, {"id": "q", "kind": "remap", "params": {"levels": "0,1\n"}}],
     "edges": [{"from": "n", "to": "q", "slot": "in"}], "output": "q"}, "control character")
bad("an operation that takes one input refuses a second",
    {"nodes": [noise, {"id": "q", "kind": "op", "params": {"op": "abs"}}],
     "edges": [{"from": "n", "to": "q", "slot": "a"}, {"from": "n", "to": "q", "slot": "b"}], "output": "q"},
    "abs takes 1 input")
bad("a constant input that is not a number or a colour is refused",
    {"nodes": [noise, {"id": "q", "kind": "op", "params": {"b": "0.5;x"}}],
     "edges": [{"from": "n", "to": "q", "slot": "a"}], "output": "q"},
    "node 'q' (op): input 'b' is a node's map or a constant such as 0.5 or 1,0,0")
bad("text that is not JSON is refused with where", '{"nodes": [', "the graph is not JSON: expected a value at byte 11")
bad("a runtime error names the node", {"nodes": [{"id": "s", "kind": "stripe"},
    {"id": "p", "kind": "palette"}], "edges": [{"from": "s", "to": "p", "slot": "in"}], "output": "p"},
    "node 'p' (palette): t_palette: error:", 500)

# the same gate as every request: the token, the Host
s, b = get("/api/graph", [("graph", json.dumps(fan))], tok=False)
s2, b2 = get("/api/graph", [("graph", json.dumps(fan))], headers={"Host": "evil.example:%d" % port})
say(s == 403 and s2 == 403, "a graph request without the token, or for another host, gets 403", (s, s2))

# exports and projects are saved, never over a file without asking
q = [("graph", json.dumps(fan)), ("size", "64")]
s1, b1 = get("/api/save", q + [("kind", "graph"), ("form", "sh"), ("name", "fan2.sh"), ("map", "f.png")])
s2, b2 = get("/api/save", q + [("kind", "graph"), ("form", "sh"), ("name", "fan2.sh"), ("map", "f.png")])
s3, b3 = get("/api/save", q + [("kind", "graph"), ("form", "sh"), ("name", "fan2.sh"), ("map", "f.png"),
                               ("overwrite", "1")])
say(s1 == 200 and s2 == 409 and s3 == 200 and open(os.path.join(work, "fan2.sh")).read().startswith("#!/bin/sh"),
    "a graph's script is saved, 409 over an existing file, replaced with overwrite=1", (s1, s2, s3))
s, b = get("/api/save", q + [("kind", "graph"), ("form", "apply"), ("name", "fan2.scene")])
say(s == 200 and "texture m file" in open(os.path.join(work, "fan2.scene")).read(), "the scene export is saved", b)
proj = json.dumps({"format": "t_proto project 2", "name": "fan", "size": 64, "graph": fan,
                   "palettes": {}}, indent=2)
s1, b1 = get("/api/save", [("kind", "project"), ("name", "fan.tproj"), ("text", proj)])
s2, b2 = get("/api/load", [("name", "fan.tproj")])
say(s1 == 200 and s2 == 200 and json.loads(b2)["graph"] == fan, "a project with a graph loads back the same graph",
    (s1, b1))
cyc = json.loads(proj)
cyc["graph"]["edges"].append({"from": "m", "to": "s", "slot": "in"})
s, b = get("/api/save", [("kind", "project"), ("name", "cyc.tproj"), ("text", json.dumps(cyc))])
say(s == 400 and b"node 's' (wood) takes no input" in b, "a project whose graph is bad is not saved", (s, b))
PY
