#!/usr/bin/env python3
"""tests/tools/cdp.py - drive headless chromium through the DevTools protocol: the editor tests.

usage: cdp.py CHROMIUM URL WORKDIR SHOTS SCENARIO
Starts CHROMIUM headless on URL (a t_proto page with its token) and drives the page as a user
does, through the DevTools protocol (a WebSocket client written here with the standard library
only), one SCENARIO (a test file each, to keep each under its time budget):
  basic     picks t_noise, moves the frequency slider, adds a palette step, saves the map and
            checks that the page's command line, run in a shell, gives it byte for byte
  prims     picks every primitive of the registry with its defaults: a preview, no error
  values    every palette as a step, exact typed values, defaults kept, the modes' rows,
            an error that clears the preview and names the parameter
  project   saves a project (readable JSON), refuses to replace it unless confirmed, reloads
            the page and loads it back to the same state and the same preview
Screenshots of the states are written into the folder SHOTS and checked by their pixels (a
PNG decoder is here too).  Prints "ok - ..." / "not ok - ..." lines; exits 3 (with the reason
on stderr) when chromium cannot start at all.
"""
import base64, hashlib, json, os, shutil, socket, struct, subprocess, sys, tempfile, time, zlib
import urllib.request


class WebSocket:
    def __init__(self, url):
        assert url.startswith("ws://")
        hostport, path = url[5:].split("/", 1)
        host, port = hostport.split(":")
        self.s = socket.create_connection((host, int(port)), timeout=60)
        key = base64.b64encode(os.urandom(16)).decode()
        self.s.sendall(("GET /%s HTTP/1.1\r\nHost: %s\r\nUpgrade: websocket\r\nConnection: Upgrade\r\n"
                        "Sec-WebSocket-Key: %s\r\nSec-WebSocket-Version: 13\r\n\r\n" % (path, hostport, key)).encode())
        head = b""
        while b"\r\n\r\n" not in head:
            chunk = self.s.recv(4096)
            if not chunk:
                raise OSError("websocket handshake failed")
            head += chunk
        if b" 101 " not in head.split(b"\r\n")[0]:
            raise OSError("websocket handshake refused: %r" % head[:100])
        self.buf = head.split(b"\r\n\r\n", 1)[1]

    def send(self, text):
        data, mask = text.encode(), os.urandom(4)
        n = len(data)
        hdr = bytes([0x81]) + (bytes([0x80 | n]) if n < 126 else
                               bytes([0x80 | 126]) + struct.pack(">H", n) if n < 65536 else
                               bytes([0x80 | 127]) + struct.pack(">Q", n))
        self.s.sendall(hdr + mask + bytes(b ^ mask[i % 4] for i, b in enumerate(data)))

    def _read(self, n):
        while len(self.buf) < n:
            chunk = self.s.recv(1 << 16)
            if not chunk:
                raise OSError("websocket closed")
            self.buf += chunk
        out, self.buf = self.buf[:n], self.buf[n:]
        return out

    def recv(self):
        msg = b""
        while True:
            b0, b1 = self._read(2)
            n = b1 & 0x7F
            if n == 126:
                n = struct.unpack(">H", self._read(2))[0]
            elif n == 127:
                n = struct.unpack(">Q", self._read(8))[0]
            data = self._read(n)
            op = b0 & 0x0F
            if op in (1, 2, 0):
                msg += data
                if b0 & 0x80:
                    return msg.decode()
            elif op == 8:
                raise OSError("websocket closed by chromium")


class Page:
    def __init__(self, ws_url):
        self.ws, self.id = WebSocket(ws_url), 0

    def call(self, method, **params):
        self.id += 1
        self.ws.send(json.dumps({"id": self.id, "method": method, "params": params}))
        while True:
            m = json.loads(self.ws.recv())
            if m.get("id") == self.id:
                if "error" in m:
                    raise RuntimeError("%s: %s" % (method, m["error"]))
                return m["result"]

    def js(self, expr):
        r = self.call("Runtime.evaluate", expression=expr, awaitPromise=True, returnByValue=True)
        if "exceptionDetails" in r:
            raise RuntimeError(r["exceptionDetails"].get("exception", {}).get("description", str(r)))
        return r["result"].get("value")

    def preview_other_than(self, h, seconds=90):
        """The preview's hash once it differs from h, or h after the timeout: a render
        asked for before the change (slow under ASan) may land first."""
        end = time.time() + seconds
        while time.time() < end:
            v = self.js(PREVIEW)
            if v != h:
                return v
            time.sleep(0.1)
        return h

    def until(self, expr, seconds=30):
        end = time.time() + seconds
        while time.time() < end:
            v = self.js(expr)
            if v:
                return v
            time.sleep(0.1)
        raise RuntimeError("timed out waiting for " + expr)


class Chromium:
    """Headless chromium on url, its page driven through the DevTools protocol: `with
    Chromium(path, url) as page:`; exits 3, saying why, when chromium cannot start."""

    def __init__(self, chromium, url, size="1100,900"):
        self.profile = tempfile.mkdtemp(prefix="textura-chromium.")
        self.proc = subprocess.Popen([chromium, "--headless=new", "--no-sandbox", "--disable-gpu",
                                      "--no-first-run", "--disable-extensions",
                                      "--remote-debugging-port=0", "--user-data-dir=" + self.profile,
                                      "--window-size=" + size, url],
                                     stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)

    def __enter__(self):
        port_file = os.path.join(self.profile, "DevToolsActivePort")
        for _ in range(300):
            if (os.path.exists(port_file) and open(port_file).read().count("\n") >= 1) or \
                    self.proc.poll() is not None:
                break
            time.sleep(0.1)
        if not os.path.exists(port_file):
            sys.stderr.write("chromium did not start: %s\n" %
                             self.proc.stderr.read1(400).decode(errors="replace")
                             if self.proc.poll() is not None else
                             "chromium did not open its DevTools port\n")
            self.__exit__()
            sys.exit(3)
        port = int(open(port_file).read().split()[0])
        targets = json.load(urllib.request.urlopen("http://127.0.0.1:%d/json/list" % port, timeout=10))
        page = Page(next(t for t in targets if t["type"] == "page")["webSocketDebuggerUrl"])
        page.call("Runtime.enable")
        return page

    def __exit__(self, *exc):
        self.proc.kill()
        self.proc.wait()
        shutil.rmtree(self.profile, ignore_errors=True)


def say(ok, name, why=""):
    print(("ok - " if ok else "not ok - ") + name + ("" if ok else ": " + str(why)[:300]), flush=True)


# the bytes of the preview image, as a hash, from inside the page
PREVIEW = """(async () => { const b = await (await fetch(document.getElementById('preview').src)).arrayBuffer();
  const h = await crypto.subtle.digest('SHA-256', b);
  return Array.from(new Uint8Array(h)).map(x => x.toString(16).padStart(2, '0')).join(''); })()"""
VERSION = "Number(document.getElementById('preview').dataset.version || 0)"



def png_pixels(data):
    """(width, height, channels, rows of bytes) of an 8-bit, non-interlaced PNG."""
    assert data[:8] == b"\x89PNG\r\n\x1a\n", "not a PNG"
    pos, idat, w = 8, b"", 0
    while pos < len(data):
        n, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        if kind == b"IHDR":
            w, h, depth, ctype, _, _, lace = struct.unpack(">IIBBBBB", body)
            assert depth == 8 and lace == 0, "PNG of depth %d, interlace %d" % (depth, lace)
            ch = {0: 1, 2: 3, 4: 2, 6: 4}[ctype]
        elif kind == b"IDAT":
            idat += body
        pos += 12 + n
    raw, rows, prev, stride = zlib.decompress(idat), [], bytearray(w * ch), w * ch
    for y in range(h):
        f, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for x in range(stride):
            a = line[x - ch] if x >= ch else 0
            b, c = prev[x], prev[x - ch] if x >= ch else 0
            if f == 1: line[x] = (line[x] + a) & 255
            elif f == 2: line[x] = (line[x] + b) & 255
            elif f == 3: line[x] = (line[x] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c; pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[x] = (line[x] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(bytes(line)); prev = line
    return w, h, ch, rows


def region_stats(png, box):
    """Distinct colours and the mean and spread of the grey level in box (x, y, w, h)."""
    w, h, ch, rows = png_pixels(png)
    x0, y0, bw, bh = [int(round(v)) for v in box]
    colours, s, s2, n = set(), 0.0, 0.0, 0
    for y in range(max(y0 + 2, 0), min(y0 + bh - 2, h)):
        for x in range(max(x0 + 2, 0), min(x0 + bw - 2, w)):
            px = rows[y][x * ch:x * ch + min(ch, 3)]
            colours.add(px)
            g = sum(px) / len(px)
            s += g; s2 += g * g; n += 1
    mean = s / max(n, 1)
    return {"colours": len(colours), "mean": mean, "spread": max(s2 / max(n, 1) - mean * mean, 0) ** 0.5}


class Editor:
    """The t_proto page in chromium, with the actions a user takes."""

    def __init__(self, page, shots):
        self.page, self.shots, self.n = page, shots, 0

    def js(self, expr):
        return self.page.js(expr)

    def version(self):
        return self.js(VERSION)

    def settled(self, before, seconds=60):
        """Wait for the preview after an edit: a new version or an error, and no redraw pending."""
        end = time.time() + seconds
        while time.time() < end:
            st = self.js("[document.getElementById('preview').dataset.state, %s]" % VERSION)
            if st[0] == "error" or (st[0] == "ok" and st[1] > before):
                time.sleep(0.15)  # a redraw asked for just after may still come
                st2 = self.js("[document.getElementById('preview').dataset.state, %s]" % VERSION)
                if st2 == st:
                    return st[0]
            time.sleep(0.05)
        return "timeout"

    def set(self, selector, value, event="input"):
        return self.js("(() => { const e = document.querySelector(%s); e.value = %s;"
                       " e.dispatchEvent(new Event(%s)); return e.value; })()"
                       % (json.dumps(selector), json.dumps(value), json.dumps(event)))

    def palette_step(self, palette):
        """Add a palette step, then choose PALETTE in it, each edit's preview waited for."""
        v = self.version()
        self.js("(() => { document.getElementById('stepkind').value = 'palette';"
                " document.getElementById('addstep').click(); })()")
        self.settled(v)
        v = self.version()
        self.set("#steps .steparg", palette, "change")
        return self.settled(v)

    def pick(self, name):
        v = self.version()
        self.set("#prim", name, "change")
        return self.settled(v)

    def shot(self, label):
        """A screenshot of the preview as the page shows it, kept in SHOTS; its box is then the
        whole image (decoding a whole page in Python would cost seconds)."""
        x, y, w, h = self.js("(() => { const r = document.getElementById('preview').getBoundingClientRect();"
                             " return [r.x + scrollX, r.y + scrollY, r.width, r.height]; })()")  # the clip's are the page's
        png = base64.b64decode(self.page.call("Page.captureScreenshot", format="png", clip={
            "x": x, "y": y, "width": w, "height": h, "scale": 1})["data"])
        self.n += 1
        open(os.path.join(self.shots, "%02d-%s.png" % (self.n, label)), "wb").write(png)
        return png, (0, 0, w, h)

    def page_shot(self, label):
        png = base64.b64decode(self.page.call("Page.captureScreenshot", format="png")["data"])
        self.n += 1
        open(os.path.join(self.shots, "%02d-%s.png" % (self.n, label)), "wb").write(png)
        return png

    def preview_stats(self, label):
        png, box = self.shot(label)
        return region_stats(png, box)

    def cmd(self):
        return self.js("document.getElementById('cmd').textContent")

    def msg(self):
        return self.js("document.getElementById('msg').textContent")


def basic(page, work, shots):
    page.js("(() => { const s = document.getElementById('prim'); s.value = 'noise';"
            " s.dispatchEvent(new Event('change')); })()")
    page.until("document.querySelector('#params [data-name=frequency]') && %s > 0" % VERSION)
    time.sleep(0.3)
    v0 = page.until(VERSION)
    h0 = page.js(PREVIEW)
    kind = page.js("document.querySelector('#params [data-row=frequency] .slider').type")
    say(kind == "range", "the frequency has a slider, from the descriptor's row", kind)
    page.js("(() => { const e = document.querySelector('#params [data-row=frequency] .slider');"
            " e.value = 23; e.dispatchEvent(new Event('input')); })()")
    page.until("%s > %d" % (VERSION, v0))
    h1 = page.preview_other_than(h0)
    f = page.js("document.querySelector('#params [data-name=frequency]').value")
    say(h0 != h1 and f == "23", "moving the frequency slider changes the field and the preview", (h0, h1, f))
    v1 = page.js(VERSION)
    page.js("(() => { document.getElementById('stepkind').value = 'palette';"
            " document.getElementById('addstep').click(); })()")
    page.until("%s > %d" % (VERSION, v1))
    h2 = page.preview_other_than(h1)
    n = page.js("document.querySelectorAll('#steps .step').length")
    say(n == 1 and h2 != h1, "adding a palette step shows in the pipeline and the preview", (n, h1, h2))
    page.js("(() => { const n = document.getElementById('name'); n.value = 'browser.png';"
            " const s = document.getElementById('size'); s.value = 160;"
            " document.getElementById('seed').dispatchEvent(new Event('input')); })()")
    time.sleep(0.5)
    page.until("document.getElementById('cmd').textContent.includes('browser.png')")
    page.js("document.querySelector('button[data-kind=map]').click()")
    page.until("document.getElementById('status').textContent.includes('saved browser.png')")
    cmd = page.js("document.getElementById('cmd').textContent")
    saved = os.path.join(work, "browser.png")
    r = subprocess.run(["sh", "-c", cmd.replace("> browser.png", "> shell.png")], cwd=work,
                       capture_output=True)
    same = r.returncode == 0 and open(saved, "rb").read() == open(os.path.join(work, "shell.png"), "rb").read()
    say(same, "the saved map equals the page's command line output byte for byte",
        cmd + " " + r.stderr.decode(errors="replace"))
    page.until("document.getElementById('scene').src")
    time.sleep(0.5)
    png = base64.b64decode(page.call("Page.captureScreenshot", format="png")["data"])
    open(os.path.join(shots, "t_proto.png"), "wb").write(png)
    say(png[:8] == b"\x89PNG\r\n\x1a\n", "a screenshot of the page is kept: " + shots)


def prims(page, work, shots):
    ed = Editor(page, shots)
    names = page.js("prims.map(p => p.name)")
    say(len(names) > 20, "the registry's primitives are offered (%d)" % len(names), names)
    bad = []
    for name in names:
        st = ed.pick(name)
        stats = ed.preview_stats(name)
        cmd, msg = ed.cmd(), ed.msg()
        # its defaults: nothing but the size and the seed on the command line's first stage
        first = cmd.split(" | ")[0].split()
        extra = [w for w in first[1:] if not w.startswith(("-s", "-S", "--format")) and
                 w not in ("--defs", name, ">", "map.png") and not w.endswith(".tp")]
        if st != "ok" or msg or stats["colours"] < 2 or extra:
            bad.append((name, st, msg[:80], stats, extra))
    say(not bad, "every primitive previews with its defaults, non-blank and with no error (%d)"
        % len(names), bad)
    ed.page_shot("page")


def values(page, work, shots):
    ed = Editor(page, shots)
    ed.pick("noise")
    cmd = ed.cmd()
    say("--slice" not in cmd and "--loop-radius" not in cmd and "--frequency" not in cmd,
        "noise's defaults are kept: nothing sent but what differs", cmd)
    field = page.js("(() => { const e = document.querySelector('#params [data-name=loop_radius]');"
                    " return [e.value, e.step, document.querySelector('#params [data-name=slice]').value]; })()")
    say(field == ["0.25", "any", "0"], "defaults are shown as the descriptor has them", field)
    v = ed.version()
    ed.set("#params [data-name=frequency]", "7.3")
    ed.settled(v)
    page.until("document.getElementById('cmd').textContent.includes('--frequency')")
    say("--frequency=7.3 " in ed.cmd() + " ", "a typed value is sent exactly", ed.cmd())
    for name, want, absent in [("colorvar", None, "--frequency"), ("wood", None, "--rings"),
                               ("marble", None, "--octaves"), ("cracked", None, "--count")]:
        if name not in page.js("prims.map(p => p.name)"):
            continue
        st = ed.pick(name)
        stats = ed.preview_stats(name)
        say(st == "ok" and absent not in ed.cmd() and stats["spread"] > 1,
            "%s with its defaults: its values untouched, the preview not black" % name, (st, ed.cmd(), stats))
    ed.pick("turbulence")
    v = ed.version()
    page.js("(() => { const t = document.getElementById('tile'); t.checked = true;"
            " t.dispatchEvent(new Event('input')); })()")
    st = ed.settled(v)
    say(st == "ok" and not ed.msg(), "tile on turbulence works with the default lacunarity", (st, ed.msg()))
    page.js("(() => { const t = document.getElementById('tile'); t.checked = false;"
            " t.dispatchEvent(new Event('input')); })()")
    ed.pick("fractal")
    step = page.js("document.querySelector('#params [data-name=octaves]').step")
    shown = page.js("getComputedStyle(document.querySelector('#params [data-row=ridge_gain]')).display")
    say(step == "1" and shown == "none", "whole-number rows step by 1; rows of another mode are hidden", (step, shown))
    v = ed.version()
    ed.set("#params [data-name=mode]", "ridged", "change")
    ed.settled(v)
    shown = page.js("getComputedStyle(document.querySelector('#params [data-row=ridge_gain]')).display")
    v = ed.version()
    ed.set("#params [data-name=ridge_gain]", "3")
    st = ed.settled(v)
    page.until("document.getElementById('cmd').textContent.includes('--ridge-gain')")
    say(shown != "none" and st == "ok" and "--ridge-gain=3" in ed.cmd() and "--mode=ridged" in ed.cmd(),
        "ridged shows and sends its ridge gain", (shown, st, ed.cmd()))
    v = ed.version()
    ed.set("#params [data-name=mode]", "fbm", "change")
    st = ed.settled(v)
    say(st == "ok" and "--ridge-gain" not in ed.cmd(), "back to fbm, the ridge gain is not sent", (st, ed.cmd()))
    # an error: the preview cleared, the parameter named and marked
    ed.pick("noise")
    good = ed.preview_stats("noise-before-error")
    v = ed.version()
    ed.set("#params [data-name=frequency]", "-3")
    st = ed.settled(v)
    msg = ed.msg()
    marked = page.js("document.querySelector('#params [data-row=frequency] .row').classList.contains('bad')")
    stats = ed.preview_stats("error")
    say(st == "error" and "--frequency" in msg and marked and ed.cmd() == "" and stats["colours"] == 1
        and good["colours"] > 1, "an error clears the preview and names and marks the parameter",
        (st, msg, marked, stats, good))
    v = ed.version()
    ed.set("#params [data-name=frequency]", "8")
    ed.settled(v)
    # every palette, as a step
    pals = page.js("palettes")
    page.js("(() => { document.getElementById('stepkind').value = 'palette';"
            " document.getElementById('addstep').click(); })()")
    bad, seen = [], {}
    for name in pals:
        v = ed.version()
        ed.set("#steps .steparg", name, "change")
        st = ed.settled(v)
        stats = ed.preview_stats("palette-" + name)
        h = page.js(PREVIEW)
        seen[h] = name
        if st != "ok" or ed.msg() or stats["colours"] < 2:
            bad.append((name, st, ed.msg()[:80], stats))
    say(len(pals) >= 10 and not bad and len(seen) == len(pals),
        "every palette works as a step, each its own preview (%d)" % len(pals), (bad, len(seen)))
    ed.page_shot("page")


def project(page, work, shots):
    ed = Editor(page, shots)
    ed.pick("wood")
    v = ed.version()
    ed.set("#params [data-name=rings]", "5.5")
    ed.settled(v)
    # three stops: the two there, recoloured, and one added between them
    page.js("(() => { document.getElementById('addstop').click();"
            " const c = document.querySelectorAll('#stops .stopcolour'), p = document.querySelectorAll('#stops .stoppos');"
            " const set = (e, v) => { e.value = v; e.dispatchEvent(new Event('input')); };"
            " set(c[0], '#102030'); set(p[1], '0.3'); set(c[1], '#40a060'); set(c[2], '#e0c040');"
            " document.getElementById('space').value = 'rgb'; document.getElementById('palname').value = 'leaf.pal';"
            " document.getElementById('savepal').click(); })()")
    page.until("document.getElementById('status').textContent.includes('saved leaf.pal')")
    page.until("palettes.includes('leaf.pal')")
    lines = [l for l in open(os.path.join(work, "leaf.pal")).read().splitlines() if not l.startswith("#")]
    say(lines == ["space rgb", "0 #102030", "0.3 #40a060", "1 #e0c040"],
        "the palette editor saves any number of stops", lines)
    ed.palette_step("leaf.pal")
    ed.set("#size", "300")
    before = page.js(PREVIEW)
    png_before, box = ed.shot("project-before")
    page.js("document.getElementById('projname').value = 'leaf.tproj'")
    page.js("document.querySelector('button[data-kind=project]').click()")
    page.until("document.getElementById('status').textContent.includes('saved leaf.tproj')")
    path = os.path.join(work, "leaf.tproj")
    try:
        j = json.load(open(path))
    except Exception as e:
        j = {"error": str(e)}
    say(j.get("primitive") == "wood" and j.get("params") == {"rings": "5.5"} and j.get("size") == 300
        and j.get("steps") == [{"kind": "palette", "args": ["leaf.pal"]}] and "leaf.pal" in j.get("palettes", {})
        and j.get("palette_editor", {}).get("stops") == [[0, "#102030"], [0.3, "#40a060"], [1, "#e0c040"]],
        "a project is readable JSON: primitive, parameters, steps, palettes, size, name", j)
    text0 = open(path).read()
    page.js("window.asked = 0; window.confirm = () => { window.asked++; return false; }")
    ed.set("#params [data-name=rings]", "6")
    page.js("document.querySelector('button[data-kind=project]').click()")
    page.until("window.asked > 0 && document.getElementById('status').textContent.includes('not saved')")
    say(open(path).read() == text0, "saving over a project asks, and a no leaves it as it was")
    page.js("window.confirm = () => { window.asked++; return true; }")
    page.js("document.querySelector('button[data-kind=project]').click()")
    page.until("window.asked > 1 && document.getElementById('status').textContent.includes('saved leaf.tproj')")
    say(json.load(open(path)).get("params") == {"rings": "6"}, "a yes replaces it")
    page.js("window.confirm = () => true; document.querySelector('#params [data-name=rings]').value = '5.5';"
            "document.getElementById('status').textContent = '';"
            "document.querySelector('button[data-kind=project]').click()")
    page.until("document.getElementById('status').textContent.includes('saved leaf.tproj')")
    # reload the page, then load the project
    page.call("Page.reload")
    time.sleep(0.5)
    page.until("typeof prims !== 'undefined' && prims.length > 10 && %s > 0" % VERSION)
    v = ed.version()
    page.js("document.getElementById('projname').value = 'leaf.tproj'; document.getElementById('load').click()")
    page.until("document.getElementById('status').textContent.includes('loaded leaf.tproj')")
    ed.settled(v)
    time.sleep(1.0)  # the redraws after loading are done: the message must still be there
    state = page.js("""({prim: document.getElementById('prim').value,
        rings: document.querySelector('#params [data-name=rings]').value,
        steps: steps.map(s => s.kind + ':' + s.args.join(':')),
        listed: Array.from(document.querySelectorAll('#steps .steparg option')).map(o => o.value).includes('leaf.pal'),
        chosen: document.querySelector('#steps .steparg').value,
        stops: Array.from(document.querySelectorAll('#stops .stop')).map(d =>
            d.querySelector('.stoppos').value + ' ' + d.querySelector('.stopcolour').value),
        space: document.getElementById('space').value, size: document.getElementById('size').value,
        status: document.getElementById('status').textContent})""")
    say(state == {"prim": "wood", "rings": "5.5", "steps": ["palette:leaf.pal"], "listed": True,
                  "chosen": "leaf.pal", "stops": ["0 #102030", "0.3 #40a060", "1 #e0c040"], "space": "rgb", "size": "300",
                  "status": "loaded leaf.tproj"},
        "a project loads back to the same state after a reload, and the message stays", state)
    after = page.js(PREVIEW)
    png_after, box2 = ed.shot("project-after")
    a, b = region_stats(png_before, box), region_stats(png_after, box2)
    say(after == before and abs(a["mean"] - b["mean"]) < 0.5 and a["colours"] == b["colours"],
        "the loaded project previews the same bytes and pixels", (a, b))
    ed.page_shot("page")


def graph(page, work, shots):
    """A graph with fan-out built by clicking, its shell export run, its inner node and 3D
    previews, saved in a project and loaded back after a reload."""
    ed = Editor(page, shots)
    # the single-primitive editor's state as nodes: the same preview, byte for byte
    ed.pick("wood")
    v = ed.version()
    ed.set("#params [data-name=rings]", "5.5")
    ed.settled(v)
    ed.palette_step("marble")
    h_steps = page.js(PREVIEW)
    v = ed.version()
    page.js("document.getElementById('tograph').click()")
    st = ed.settled(v)
    g = ed.js("graphJSON()")
    h_nodes = page.preview_other_than("", 30)
    say(st == "ok" and h_nodes == h_steps and [n["kind"] for n in g["nodes"]] == ["wood", "palette"]
        and g["nodes"][0]["params"] == {"rings": "5.5"} and g["output"] == g["nodes"][1]["id"],
        "the primitive and its steps become a chain of nodes with the same preview", (st, g))
    v = ed.version()
    page.js("document.getElementById('cleargraph').click()")
    ed.settled(v)
    kinds = page.js("Array.from(document.querySelectorAll('#nodekind option')).map(o => o.value)")
    say(all(k in kinds for k in ["op", "palette", "filter", "remap", "xform", "warp", "cascade", "tile",
                                 "noise", "marble"]),
        "the node menu offers every operator kind and every primitive, composed ones too", kinds)

    def add(kind):
        v = ed.version()
        ed.js("(() => { const s = document.getElementById('nodekind'); s.value = %s;"
              " document.getElementById('addnode').click(); })()" % json.dumps(kind))
        ed.settled(v)
        return ed.js("graph.nodes[graph.nodes.length - 1].id")

    def in_node(node, selector, value, event="change"):
        v = ed.version()
        ed.set('#nodes .node[data-id="%s"] %s' % (node, selector), value, event)
        return ed.settled(v)

    n = add("noise")
    in_node(n, "[data-name=frequency]", "5", "input")
    p = add("palette")   # fed by the node before it
    in_node(p, "[data-name=palette]", "marble")
    f = add("filter")
    in_node(f, "select.slot[data-slot=in]", n)
    in_node(f, "[data-name=op]", "emboss")
    m = add("op")
    in_node(m, "[data-name=op]", "mix")
    in_node(m, "select.slot[data-slot=a]", p)
    in_node(m, "select.slot[data-slot=b]", f)
    st = in_node(m, "select.slot[data-slot=w]", n)
    v = ed.version()
    ed.js("document.querySelector('#nodes .node[data-id=\"%s\"] input.out').click()" % m)
    ed.js("document.querySelector('#nodes .node[data-id=\"%s\"] button.show').click()" % m)
    st = ed.settled(v)
    g = ed.js("graphJSON()")
    edges = sorted((e["from"], e["to"], e["slot"]) for e in g["edges"])
    say(st == "ok" and g["output"] == m and edges == sorted([(n, p, "in"), (n, f, "in"), (p, m, "a"), (f, m, "b"),
                                                             (n, m, "w")]),
        "a graph with fan-out is built by clicking: the noise feeds three nodes", (st, ed.msg(), g))
    stats = ed.preview_stats("graph-output")
    say(stats["colours"] > 50 and stats["spread"] > 5, "the output's preview is a textured map", stats)
    h_out = ed.js(PREVIEW)
    # the last node scrolled into view: the previews stay in view, the same pixels
    ed.js("document.querySelector('#nodes .node:last-child').scrollIntoView()")
    time.sleep(0.3)
    top, bottom, high, scrolled = ed.js("(() => { const r = document.getElementById('preview')"
                                        ".getBoundingClientRect(); return [r.top, r.bottom, innerHeight, scrollY]; })()")
    there = ed.preview_stats("graph-scrolled")
    ed.page_shot("graph-scrolled-page")
    say(scrolled > 0 and 0 <= top and bottom <= high and abs(there["mean"] - stats["mean"]) < 0.5
        and there["colours"] == stats["colours"], "the previews stay in view while the graph panel scrolls",
        (top, bottom, high, scrolled, stats, there))
    ed.js("window.scrollTo(0, 0)")
    # export at the preview's size, run it in a shell: the same bytes
    ed.js("document.getElementById('size').value = 256; document.getElementById('name').value = 'fan.png';")
    ed.js("document.getElementById('status').textContent = '';"
          " document.querySelector('button[data-export=sh]').click()")
    page.until("document.getElementById('status').textContent.includes('saved fan.sh')")
    r = subprocess.run(["sh", "fan.sh"], cwd=work, capture_output=True)
    got = hashlib.sha256(open(os.path.join(work, "fan.png"), "rb").read()).hexdigest() if r.returncode == 0 else ""
    script = open(os.path.join(work, "fan.sh")).read()
    say(got == h_out and script.count("t_noise") == 1 and "-o %s.exr" % n in script,
        "the exported shell script, run in a shell, gives the preview's bytes (the fan-out made once)",
        (r.stderr[:200], script))
    for form, name, want in [("compose", "fan.tc", "no t_compose equivalent"), ("apply", "fan.scene", "saved fan.scene")]:
        ed.js("document.getElementById('status').textContent = '';"
              " document.querySelector('button[data-export=%s]').click()" % form)
        text = page.until("document.getElementById('status').textContent")
        say(want in text, "export %s: %s" % (form, want), text)
    # an inner node previewed; the 3D preview follows it
    sv = ed.js("Number(document.getElementById('scene').dataset.version || 0)")
    v = ed.version()
    ed.js("document.querySelector('#nodes .node[data-id=\"%s\"] button.show').click()" % p)
    st = ed.settled(v)
    h_p = ed.js(PREVIEW)
    stats_p = ed.preview_stats("graph-palette-node")
    page.until("Number(document.getElementById('scene').dataset.version || 0) > %d" % sv, 60)
    say(st == "ok" and h_p != h_out and stats_p["colours"] > 50 and "t_palette marble" in ed.cmd()
        and "t_op" not in ed.cmd(), "any node previews, and the command line is its own", (st, ed.cmd()))
    v = ed.version()
    ed.set("#apply", "bump", "input")
    sv = ed.js("Number(document.getElementById('scene').dataset.version || 0)")
    page.until("Number(document.getElementById('scene').dataset.version || 0) > %d" % sv, 60)
    x, y, w, h = ed.js("(() => { const r = document.getElementById('scene').getBoundingClientRect();"
                       " return [r.x, r.y, r.width, r.height]; })()")
    scene = base64.b64decode(page.call("Page.captureScreenshot", format="png", clip={
        "x": x, "y": y, "width": w, "height": h, "scale": 1})["data"])
    ed.n += 1
    open(os.path.join(shots, "%02d-graph-scene-bump.png" % ed.n), "wb").write(scene)
    sst = region_stats(scene, (0, 0, w, h))
    say(sst["colours"] > 50 and sst["spread"] > 5, "the 3D preview shows the node in the standard scene", sst)
    ed.js("document.getElementById('apply').value = 'Kd'")
    # an error names the node and marks it (a node upstream of the one previewed)
    v = ed.version()
    ed.js("document.querySelector('#nodes .node[data-id=\"%s\"] button.show').click()" % m)
    ed.settled(v)
    in_node(f, "[data-name=sigma]", "0", "input")
    try:  # a redraw asked for before (the bump view's) may settle first
        page.until("document.getElementById('preview').dataset.state === 'error'", 60)
    except RuntimeError:
        pass
    st = ed.js("document.getElementById('preview').dataset.state")
    bad = ed.js("document.querySelector('#nodes .node[data-id=\"%s\"]').classList.contains('bad')" % f)
    say(st == "error" and ("node '%s'" % f) in ed.msg() and bad, "an error names and marks its node", (st, ed.msg()))
    in_node(f, "[data-name=sigma]", "1", "input")
    # a palette of the editor's used by a node: the project carries its text
    page.js("(() => { const c = document.querySelectorAll('#stops .stopcolour');"
            " c[0].value = '#301000'; c[0].dispatchEvent(new Event('input'));"
            " document.getElementById('palname').value = 'graphpal.pal';"
            " document.getElementById('savepal').click(); })()")
    try:
        page.until("palettes.includes('graphpal.pal') && !!document.querySelector("
                   "'#nodes .node[data-id=\"%s\"] [data-name=palette] option[value=\"graphpal.pal\"]')" % p)
    except RuntimeError:
        say(False, "a palette saved in the editor is offered to the palette node",
            page.js("[document.getElementById('status').textContent, palettes]"))
    st = in_node(p, "[data-name=palette]", "graphpal.pal")
    h_out = page.preview_other_than(h_out)
    ed.js("window.confirm = () => true; document.getElementById('projname').value = 'fan.tproj';"
          " document.getElementById('status').textContent = '';"
          " document.querySelector('button[data-kind=project]').click()")
    page.until("document.getElementById('status').textContent.includes('saved fan.tproj')")
    j = json.load(open(os.path.join(work, "fan.tproj")))
    say(j.get("graph", {}).get("output") == m and len(j["graph"]["nodes"]) == 4 and len(j["graph"]["edges"]) == 5
        and j["graph"]["nodes"][0]["params"] == {"frequency": "5"} and "graphpal.pal" in j.get("palettes", {}),
        "the project holds the graph, readable, and the text of the palette a node uses", j.get("graph"))
    before = ed.js("JSON.stringify(graphJSON())")
    png_before, box = ed.shot("graph-before-reload")
    page.call("Page.reload")
    time.sleep(0.5)
    page.until("typeof prims !== 'undefined' && prims.length > 10 && %s > 0" % VERSION)
    v = ed.version()
    page.js("document.getElementById('projname').value = 'fan.tproj'; document.getElementById('load').click()")
    page.until("document.getElementById('status').textContent.includes('loaded fan.tproj')")
    ed.settled(v)
    time.sleep(0.5)
    after = ed.js("JSON.stringify(graphJSON())")
    cards = ed.js("document.querySelectorAll('#nodes .node').length")
    h_after = ed.js(PREVIEW)
    png_after, box2 = ed.shot("graph-after-reload")
    a, b = region_stats(png_before, box), region_stats(png_after, box2)
    say(after == before and cards == 4 and h_after == h_out and abs(a["mean"] - b["mean"]) < 0.5,
        "a project loads back the same graph after a reload, and previews the same bytes and pixels",
        (before, after, cards, a, b))
    ed.page_shot("page")


def main():
    chromium, url, work, shots, scenario = sys.argv[1:6]
    os.makedirs(shots, exist_ok=True)
    with Chromium(chromium, url) as page:
        page.call("Page.enable")
        page.until("document.querySelectorAll('#prim option').length > 10")
        page.until("%s > 0" % VERSION)
        say(True, "chromium loads the editor and its primitives")
        {"basic": basic, "prims": prims, "values": values, "project": project,
         "graph": graph}[scenario](page, work, shots)


if __name__ == "__main__":
    main()
