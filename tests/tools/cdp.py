#!/usr/bin/env python3
"""tests/tools/cdp.py - drive headless chromium through the DevTools protocol: the editor test.

usage: cdp.py CHROMIUM URL WORKDIR SHOT
Starts CHROMIUM headless on URL (a t_proto page with its token), and through the DevTools
protocol (a WebSocket client written here with the standard library only): picks t_noise,
moves the frequency slider and checks that the preview changed; adds a palette step; saves
the map and checks that the page's command line, run in a shell, gives it byte for byte;
writes a screenshot of the page to SHOT.  Prints "ok - ..." / "not ok - ..." lines; exits 3
(with the reason on stderr) when chromium cannot start at all.
"""
import base64, hashlib, json, os, shutil, socket, struct, subprocess, sys, tempfile, time
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

    def until(self, expr, seconds=90):
        end = time.time() + seconds
        while time.time() < end:
            v = self.js(expr)
            if v:
                return v
            time.sleep(0.1)
        raise RuntimeError("timed out waiting for " + expr)


def say(ok, name, why=""):
    print(("ok - " if ok else "not ok - ") + name + ("" if ok else ": " + str(why)[:300]), flush=True)


# the bytes of the preview image, as a hash, from inside the page
PREVIEW = """(async () => { const b = await (await fetch(document.getElementById('preview').src)).arrayBuffer();
  const h = await crypto.subtle.digest('SHA-256', b);
  return Array.from(new Uint8Array(h)).map(x => x.toString(16).padStart(2, '0')).join(''); })()"""
VERSION = "Number(document.getElementById('preview').dataset.version || 0)"


def main():
    chromium, url, work, shot = sys.argv[1:5]
    profile = tempfile.mkdtemp(prefix="textura-chromium.")
    proc = subprocess.Popen([chromium, "--headless=new", "--no-sandbox", "--disable-gpu",
                             "--no-first-run", "--disable-extensions", "--remote-debugging-port=0",
                             "--user-data-dir=" + profile, "--window-size=1100,760", url],
                            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    try:
        port_file = os.path.join(profile, "DevToolsActivePort")
        for _ in range(300):
            if os.path.exists(port_file) and open(port_file).read().count("\n") >= 1:
                break
            if proc.poll() is not None:
                break
            time.sleep(0.1)
        else:
            pass
        if not os.path.exists(port_file):
            sys.stderr.write("chromium did not start: %s\n" % proc.stderr.read1(400).decode(errors="replace")
                             if proc.poll() is not None else "chromium did not open its DevTools port\n")
            sys.exit(3)
        port = int(open(port_file).read().split()[0])
        targets = json.load(urllib.request.urlopen("http://127.0.0.1:%d/json/list" % port, timeout=10))
        page = Page(next(t for t in targets if t["type"] == "page")["webSocketDebuggerUrl"])
        page.call("Runtime.enable")
        page.until("document.querySelectorAll('#prim option').length > 10")
        say(True, "chromium loads the editor and its primitives")
        page.js("(() => { const s = document.getElementById('prim'); s.value = 'noise';"
                " s.dispatchEvent(new Event('change')); })()")
        page.until("document.querySelector('#params [data-name=frequency]') && %s > 0" % VERSION)
        v0 = page.js(VERSION)
        time.sleep(0.3)
        v0 = page.until(VERSION)
        h0 = page.js(PREVIEW)
        kind = page.js("document.querySelector('#params [data-name=frequency]').type")
        say(kind == "range", "the frequency is a slider, from the descriptor's row", kind)
        page.js("(() => { const e = document.querySelector('#params [data-name=frequency]');"
                " e.value = 23; e.dispatchEvent(new Event('input')); })()")
        page.until("%s > %d" % (VERSION, v0))
        h1 = page.preview_other_than(h0)
        say(h0 != h1, "moving the frequency slider changes the preview", (h0, h1))
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
        page.until("document.getElementById('msg').textContent.includes('saved browser.png')")
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
        os.makedirs(os.path.dirname(os.path.abspath(shot)), exist_ok=True)
        open(shot, "wb").write(png)
        say(png[:8] == b"\x89PNG\r\n\x1a\n", "a screenshot of the page is kept: " + shot)
    finally:
        proc.kill()
        proc.wait()
        shutil.rmtree(profile, ignore_errors=True)


if __name__ == "__main__":
    main()
