#!/usr/bin/env python3
"""Opens refract's HTML report in headless Chromium and fails on a broken link, a missing
image or a console error; keeps a screenshot of the experiment's page.

    report_in_browser.py --refract EXE --work DIR [--screenshot FILE]

Builds a small report first: the gem-cuts experiment in quick mode into DIR/out, then
`refract report DIR/out`. Before that it opens a page with one broken link, one missing
image and one console error, and fails unless it finds exactly those three (so the check
cannot pass by finding nothing). Every page of the report reachable from index.html is
opened; every link into the report must name an existing file (and an existing id for a
#fragment), every image must load, and no page may log an error or throw.

Talks to Chromium through the DevTools protocol over a pipe (--remote-debugging-pipe:
JSON messages ending in NUL on descriptors 3 and 4); the Python standard library only.
Exit 77 (a skip for CTest) when no Chromium is installed.
"""
import argparse
import base64
import fcntl
import json
import os
import select
import shutil
import subprocess
import sys
import time
import urllib.parse

SKIP = 77
TIMEOUT_S = 20.0  # per page load


def find_chromium():
    for name in ("chromium", "chromium-browser", "google-chrome"):
        path = shutil.which(name)
        if path:
            return path
    return None


class Browser:
    def __init__(self, exe, profile):
        p2c_r, p2c_w = os.pipe()
        c2p_r, c2p_w = os.pipe()

        def child_fds():  # descriptors 3 (commands in) and 4 (replies out) for Chromium
            a = fcntl.fcntl(p2c_r, fcntl.F_DUPFD, 10)
            b = fcntl.fcntl(c2p_w, fcntl.F_DUPFD, 10)
            os.dup2(a, 3)
            os.dup2(b, 4)

        args = [exe, "--headless", "--remote-debugging-pipe", "--no-sandbox", "--disable-gpu",
                "--no-first-run", "--no-default-browser-check", "--disable-extensions", "--mute-audio",
                "--hide-scrollbars", "--window-size=1280,900", "--user-data-dir=" + profile,
                "--disable-background-networking", "--disable-component-update", "--disable-sync",
                "--disable-default-apps", "--password-store=basic", "--disable-features=Translate,MediaRouter",
                "about:blank"]
        self.proc = subprocess.Popen(args, preexec_fn=child_fds, close_fds=False, stdin=subprocess.DEVNULL,
                                     stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        os.close(p2c_r)
        os.close(c2p_w)
        self.w, self.r = p2c_w, c2p_r
        self.buf = b""
        self.next_id = 0
        self.events = []
        self.session = None

    def _read_message(self, deadline):
        while b"\0" not in self.buf:
            left = deadline - time.monotonic()
            if left <= 0:
                raise TimeoutError("no reply from Chromium")
            ready, _, _ = select.select([self.r], [], [], left)
            if ready:
                chunk = os.read(self.r, 1 << 16)
                if not chunk:
                    raise RuntimeError("Chromium closed the DevTools pipe")
                self.buf += chunk
        msg, self.buf = self.buf.split(b"\0", 1)
        return json.loads(msg)

    def call(self, method, params=None, session=True, timeout=TIMEOUT_S):
        self.next_id += 1
        msg = {"id": self.next_id, "method": method, "params": params or {}}
        if session and self.session:
            msg["sessionId"] = self.session
        os.write(self.w, json.dumps(msg).encode() + b"\0")
        deadline = time.monotonic() + timeout
        while True:
            m = self._read_message(deadline)
            if m.get("id") == self.next_id:
                if "error" in m:
                    raise RuntimeError(method + ": " + json.dumps(m["error"]))
                return m.get("result", {})
            self.events.append(m)

    def wait_event(self, method, timeout=TIMEOUT_S):
        deadline = time.monotonic() + timeout
        for k, m in enumerate(self.events):
            if m.get("method") == method:
                del self.events[k]
                return m
        while True:
            m = self._read_message(deadline)
            if m.get("method") == method:
                return m
            self.events.append(m)

    def open_page(self):
        target = self.call("Target.createTarget", {"url": "about:blank"}, session=False)["targetId"]
        self.session = self.call("Target.attachToTarget", {"targetId": target, "flatten": True},
                                 session=False)["sessionId"]
        for domain in ("Page", "Runtime", "Log", "Network"):
            self.call(domain + ".enable")

    def close(self):
        try:
            self.call("Browser.close", session=False, timeout=5)
        except Exception:
            pass
        try:
            self.proc.wait(timeout=5)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            self.proc.wait()


PAGE_FACTS = """JSON.stringify({
  links: Array.from(document.querySelectorAll('a[href]'), a => a.href),
  images: Array.from(document.images, i => ({src: i.currentSrc || i.src, ok: i.complete && i.naturalWidth > 0})),
  ids: Array.from(document.querySelectorAll('[id]'), e => e.id)
})"""


def visit(browser, url):
    """Loads URL; returns (facts, problems seen while loading)."""
    browser.events.clear()
    browser.call("Page.navigate", {"url": url})
    browser.wait_event("Page.loadEventFired")
    facts = json.loads(browser.call("Runtime.evaluate", {"expression": PAGE_FACTS, "returnByValue": True})
                       ["result"]["value"])
    problems = []
    for m in browser.events:
        p, method = m.get("params", {}), m.get("method")
        if method == "Runtime.consoleAPICalled" and p.get("type") in ("error", "assert"):
            text = " ".join(str(a.get("value", a.get("description", ""))) for a in p.get("args", []))
            problems.append("console error: " + text)
        elif method == "Runtime.exceptionThrown":
            problems.append("exception: " + p.get("exceptionDetails", {}).get("text", ""))
        elif method == "Log.entryAdded" and p.get("entry", {}).get("level") == "error":
            problems.append("browser error: " + p["entry"].get("text", "") + " " + p["entry"].get("url", ""))
    for img in facts["images"]:
        if not img["ok"]:
            problems.append("missing image: " + img["src"])
    return facts, problems


def file_of(url):
    parts = urllib.parse.urlsplit(url)
    return urllib.parse.unquote(parts.path), parts.fragment


def check_site(browser, index):
    """Opens index.html and every page of the report it reaches; returns the problems."""
    root = os.path.dirname(os.path.abspath(index))
    queue, seen, problems, ids = [os.path.abspath(index)], set(), [], {}
    fragments = []  # (page, fragment, from)
    while queue:
        page = queue.pop(0)
        if page in seen:
            continue
        seen.add(page)
        facts, found = visit(browser, "file://" + urllib.parse.quote(page))
        problems += [os.path.relpath(page, root) + ": " + p for p in found]
        ids[page] = set(facts["ids"])
        for link in facts["links"]:
            if not link.startswith("file://"):
                problems.append(os.path.relpath(page, root) + ": a link out of the report: " + link)
                continue
            path, fragment = file_of(link)
            if not os.path.exists(path):
                problems.append(os.path.relpath(page, root) + ": broken link: " + link)
                continue
            if fragment:
                fragments.append((path, fragment, page))
            if path.endswith(".html") and os.path.commonpath([root, path]) == root:
                queue.append(path)
    for path, fragment, page in fragments:
        if path in ids and fragment not in ids[path]:
            problems.append(os.path.relpath(page, root) + ": no id '" + fragment + "' in " + os.path.relpath(path, root))
    return problems, len(seen)


def self_check(browser, work):
    """The checker finds a broken link, a missing image and a console error."""
    bad = os.path.join(work, "broken")
    os.makedirs(bad, exist_ok=True)
    with open(os.path.join(bad, "index.html"), "w") as f:
        f.write('<!DOCTYPE html><html><head><meta charset="utf-8"><title>t</title></head><body>'
                '<a href="missing.html">x</a><img src="missing.png" alt="x">'
                '<script>console.error("deliberate")</script></body></html>\n')
    problems, _ = check_site(browser, os.path.join(bad, "index.html"))
    want = ["broken link", "missing image", "console error: deliberate"]
    missed = [w for w in want if not any(w in p for p in problems)]
    if missed:
        print("report_in_browser: the checker missed " + ", ".join(missed) + " on a broken page; it found: "
              + "; ".join(problems), file=sys.stderr)
        return False
    return True


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--refract", required=True)
    ap.add_argument("--work", required=True)
    ap.add_argument("--screenshot")
    a = ap.parse_args()
    exe = find_chromium()
    if not exe:
        print("report_in_browser: no chromium on PATH (Debian: apt-get install chromium): skipped")
        return SKIP
    work = os.path.abspath(a.work)
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    out = os.path.join(work, "out")
    t0 = time.monotonic()
    for cmd in ([a.refract, "experiment", "gem-cuts", "--quick", "--threads", "2", "-o",
                 os.path.join(out, "gem-cuts")], [a.refract, "report", out]):
        r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        if r.returncode != 0:
            print("report_in_browser: " + " ".join(cmd) + " failed:\n" + r.stdout, file=sys.stderr)
            return 1
    t1 = time.monotonic()
    browser = Browser(exe, os.path.join(work, "profile"))
    try:
        browser.open_page()
        if not self_check(browser, work):
            return 1
        problems, pages = check_site(browser, os.path.join(out, "index.html"))
        visit(browser, "file://" + urllib.parse.quote(os.path.join(out, "gem-cuts.html")))
        shot = a.screenshot or os.path.join(work, "report.png")
        png = browser.call("Page.captureScreenshot", {"format": "png"})["data"]
        with open(shot, "wb") as f:
            f.write(base64.b64decode(png))
    finally:
        browser.close()
    t2 = time.monotonic()
    for p in problems:
        print("report_in_browser: " + p, file=sys.stderr)
    print("report_in_browser: %d page(s) opened, %d problem(s); screenshot %s; report %.1f s, browser %.1f s"
          % (pages, len(problems), shot, t1 - t0, t2 - t1))
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
