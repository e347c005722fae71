#!/usr/bin/env python3
"""tests/tools/gallery_page.py - the gallery's page in headless chromium.

usage: gallery_page.py CHROMIUM DIR SHOT
Serves DIR (patterns/gallery.sh's output) on 127.0.0.1, opens index.html in CHROMIUM
through the DevTools protocol (cdp.py's client) and checks what a visitor sees: every
picture loads; no caption overflows its figure or breaks inside a word that fits its
width; no two figures overlap; each thumbnail differs by its pixels from every input shown
beside it (drawn on a canvas at 32x32); a picture links to itself at full size.  Writes a
screenshot to SHOT.  Prints "ok - ..." / "not ok - ..." lines; exits 3 (the reason on
stderr) when chromium cannot start.
"""
import base64, functools, http.server, os, sys, threading

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cdp import Chromium, say  # noqa: E402

CHECKS = r"""(async () => {
  await Promise.all([...document.images].map(i => i.complete ? 0 :
      new Promise(r => { i.onload = i.onerror = r; })));
  const broken = [...document.images].filter(i => !i.naturalWidth).map(i => i.getAttribute('src'));
  const caps = [...document.querySelectorAll('figcaption')];
  const overflow = caps.filter(c => c.scrollWidth > c.clientWidth + 1).map(c => c.textContent);
  const ctx = document.createElement('canvas').getContext('2d');
  const midword = [];
  for (const c of caps) {
    ctx.font = getComputedStyle(c).font;
    const line = parseFloat(getComputedStyle(c).fontSize) * 1.6;
    for (const node of c.childNodes) {
      if (node.nodeType == 1) { /* a word in an element: taller than a line if broken */
        const word = node.textContent;
        if (ctx.measureText(word).width <= c.clientWidth && node.getBoundingClientRect().height > line)
          midword.push(word);
        continue;
      }
      const re = /\S+/g; let m;
      while ((m = re.exec(node.textContent))) {
        if (ctx.measureText(m[0]).width > c.clientWidth) continue; /* too long for any line */
        const r = document.createRange(); r.setStart(node, m.index); r.setEnd(node, m.index + m[0].length);
        const tops = new Set([...r.getClientRects()].map(q => Math.round(q.top)));
        if (tops.size > 1) midword.push(m[0]);
      }
    }
  }
  const figs = [...document.querySelectorAll('figure')];
  const rects = figs.map(f => f.getBoundingClientRect());
  let overlaps = 0;
  for (let i = 0; i < rects.length; i++)
    for (let j = i + 1; j < rects.length; j++) {
      const a = rects[i], b = rects[j];
      if (a.left < b.right - 1 && b.left < a.right - 1 && a.top < b.bottom - 1 && b.top < a.bottom - 1) overlaps++;
    }
  const px = img => { const c = document.createElement('canvas'); c.width = c.height = 32;
    const x = c.getContext('2d'); x.drawImage(img, 0, 0, 32, 32); return x.getImageData(0, 0, 32, 32).data; };
  const same = [], flat = [];
  let pairs = 0, links = 0;
  for (const f of figs) {
    const pic = f.querySelector('img.pic');
    if (!pic) continue;
    const identity = f.querySelector('figcaption').textContent.startsWith('t_palette greys ');
    const a = px(pic);
    let lo = 255, hi = 0;
    for (let k = 0; k < a.length; k++) if (k % 4 != 3) { lo = Math.min(lo, a[k]); hi = Math.max(hi, a[k]); }
    if (hi - lo < 8) flat.push(pic.getAttribute('src'));
    if (pic.parentElement.tagName == 'A' && pic.parentElement.getAttribute('href') == pic.getAttribute('src')) links++;
    for (const i of f.querySelectorAll('.in img')) {
      const b = px(i); let d = 0;
      for (let k = 0; k < a.length; k++) if (k % 4 != 3) d += Math.abs(a[k] - b[k]);
      d /= 32 * 32 * 3 * 255; pairs++;
      if (d < 0.01 && !identity) same.push(pic.getAttribute('src') + '~' + i.getAttribute('src') + ' ' + d.toFixed(4));
    }
  }
  return {n: figs.length, pics: document.querySelectorAll('img.pic').length, broken, overflow,
          midword, overlaps, same, flat, pairs, links};
})()"""


def main():
    chromium, folder, shot = sys.argv[1:4]
    handler = functools.partial(http.server.SimpleHTTPRequestHandler, directory=folder)
    handler.log_message = lambda *a: None
    server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), handler)
    threading.Thread(target=server.serve_forever, daemon=True).start()
    url = "http://127.0.0.1:%d/index.html" % server.server_address[1]
    try:
        with Chromium(chromium, url) as page:
            checks(page, shot)
    finally:
        server.shutdown()


def checks(page, shot):
    page.until("document.readyState == 'complete' && document.querySelectorAll('figure').length > 0")
    r = page.js(CHECKS)
    say(r["pics"] > 100 and not r["broken"], "chromium shows the %d pictures, none broken" % r["pics"],
        r["broken"][:5])
    say(r["links"] == r["pics"], "a click on each picture opens it at full size (%d links)" % r["links"])
    say(not r["overflow"], "no caption overflows its figure", r["overflow"][:3])
    say(not r["midword"], "no caption breaks inside a word", r["midword"][:5])
    say(r["overlaps"] == 0, "no two figures overlap", r["overlaps"])
    say(not r["flat"], "no thumbnail is flat", r["flat"][:5])
    say(r["pairs"] > 40 and not r["same"],
        "each of %d thumbnails with inputs differs from them by its pixels" % r["pairs"], r["same"][:5])
    png = base64.b64decode(page.call("Page.captureScreenshot", format="png")["data"])
    os.makedirs(os.path.dirname(os.path.abspath(shot)), exist_ok=True)
    open(shot, "wb").write(png)
    say(png[:8] == b"\x89PNG\r\n\x1a\n" and len(png) > 20000, "a screenshot of the page is kept: " + shot,
        len(png))


if __name__ == "__main__":
    main()
