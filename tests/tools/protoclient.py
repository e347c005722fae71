"""tests/tools/protoclient.py - a client of t_proto for the tests (proto.sh,
proto_security.sh): the printed URL's parts, say() for a TAP line, get() for a reply.
get() paces itself as the editor's page does: a 429 (the rate limit: BURST 60, RATE 40 a
second) is asked again a little later, up to 10 s, unless pace=False (the limit's own tests):
a test of many quick requests otherwise hit the limit as the tools grew faster."""
import http.client
import time
import urllib.parse as up


def say(ok, name, why=""):
    print(("ok - " if ok else "not ok - ") + name + ("" if ok else ": " + str(why)[:300]), flush=True)


class Proto:
    def __init__(self, url):
        u = up.urlsplit(url)
        self.token = up.parse_qs(u.query)["token"][0]
        self.host, self.port = u.hostname, u.port

    def parts(self):
        return self.token, self.host, self.port, self.get

    def get(self, path, params=None, tok=True, headers=None, source=None, timeout=60, pace=True):
        """(status, body) of GET path?token=...&params; source: the client's address."""
        for _ in range(200 if pace else 0):
            s, body = self.ask(path, params, tok, headers, source, timeout)
            if s != 429:
                return s, body
            time.sleep(0.05)
        return self.ask(path, params, tok, headers, source, timeout)

    def ask(self, path, params, tok, headers, source, timeout):
        q = ([("token", self.token)] if tok else []) + list(params or [])
        c = http.client.HTTPConnection(self.host, self.port, timeout=timeout,
                                       source_address=(source, 0) if source else None)
        c.request("GET", path + "?" + up.urlencode(q), headers=headers or {})
        r = c.getresponse()
        body = r.read()
        c.close()
        return r.status, body
