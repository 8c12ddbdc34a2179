#!/usr/bin/env python3
"""Load every page of the built book in headless Chromium and check its layout.

    python3 scripts/check_book.py [BOOK_OUT] [--captions warn|fail] [--width 1280]
    python3 scripts/check_book.py --self-test

Each page (BOOK_OUT/**/*.html, default book/book; the rustdoc pages under api/,
print.html, index.html, toc.html and 404.html are left out) is opened at the given window
width with mdBook's default theme, and the page fails on:

- a display equation wider than its column (.katex-display: scrollWidth > clientWidth),
- an equation tag "(n)" overlapping its equation,
- a table wider than the text column,
- an image that does not load,
- a KaTeX error (.katex-error),
- a console error or an uncaught exception,
- a request leaving the book: a file:// URL outside BOOK_OUT, or any other host.

It also counts figures (<img>) and tables without a visible numbered caption:
a paragraph right after the image, or right before or after the table (past its
"Download" line), whose text starts with "Fig. N" / "Figure N" or "Table N" (N a
number, optionally preceded by the chapter's code of up to three capitals, as in
"Fig. H2" or "Table NI1", and optionally followed by a letter), or a
<figcaption>/<caption>. With --captions fail a
missing caption fails the page; by default it is only reported.

--self-test builds the fixture book tests/fixtures/book-check (a too-wide
equation, a too-wide tagged equation and a too-wide table, beside narrow ones
that must pass, and a page with a picture from another host, a missing picture
and a console error) and succeeds only if exactly those faults are reported
(tests/fixtures/book-check/expected.json).

Chromium is driven over the DevTools protocol with the `websocket-client`
package; both are installed by .ci/run (see README, "Checks").
"""

from __future__ import annotations

import argparse
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
import urllib.parse
import urllib.request
from dataclasses import dataclass, field
from pathlib import Path

import websocket  # websocket-client

ROOT = Path(__file__).resolve().parent.parent
# print.html repeats every chapter, index.html the first one; toc.html is the
# sidebar for readers without JavaScript; 404.html is only served by a server.
SKIP = {"print.html", "index.html", "toc.html", "404.html"}
CHROMIUM_FLAGS = [
    "--headless=new",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--no-first-run",
    "--no-default-browser-check",
    "--hide-scrollbars",
    "--remote-debugging-port=0",
]

# Measures one loaded page; returns a JSON-able object (see Page.absorb).
MEASURE_JS = r"""
(() => {
  // "Fig. 3", "Fig. H2", "Fig. NI1b", "Table PS4": an optional chapter code
  // (one to three capitals) before the number, as the book numbers them.
  const FIG = /^\s*(Fig\.|Figure)\s*[A-Z]{0,3}\d+[a-z]?\b/;
  const TAB = /^\s*Table\s+[A-Z]{0,3}\d+[a-z]?\b/;
  const main = document.querySelector('main') || document.body;
  const col = main.getBoundingClientRect();
  const short = (s) => s.trim().replace(/\s+/g, ' ').slice(0, 90);
  const tex = (el) => {
    const a = el.querySelector('annotation');
    return short(a ? a.textContent : el.textContent);
  };
  const visible = (el) => {
    if (!el) return false;
    const r = el.getBoundingClientRect();
    const s = getComputedStyle(el);
    return r.width > 0 && r.height > 0 && s.visibility !== 'hidden' && s.display !== 'none';
  };
  const out = {displays: 0, tags: [], wideEquations: [], tagOverlaps: [], tables: 0,
               wideTables: [], images: 0, brokenImages: [], katexErrors: [],
               uncaptionedFigures: [], uncaptionedTables: [], column: Math.round(col.width)};

  for (const d of document.querySelectorAll('.katex-display')) {
    out.displays++;
    const html = d.querySelector('.katex-html');
    const r = (html || d).getBoundingClientRect();
    if (d.scrollWidth > d.clientWidth + 1 || r.right > col.right + 1) {
      out.wideEquations.push({tex: tex(d), width: d.scrollWidth, column: d.clientWidth});
    }
    const tag = d.querySelector('.tag');
    if (tag) out.tags.push(short(tag.textContent));
    if (tag && html) {
      const t = tag.getBoundingClientRect();
      let overlap = 0;
      for (const b of html.querySelectorAll(':scope > .base')) {
        const br = b.getBoundingClientRect();
        if (br.left < t.right && br.bottom > t.top && br.top < t.bottom) {
          overlap = Math.max(overlap, Math.min(br.right, t.right) - t.left);
        }
      }
      if (overlap > 0.5) {
        out.tagOverlaps.push({tex: tex(d), tag: short(tag.textContent), overlap: Math.round(overlap)});
      }
    }
  }
  for (const e of document.querySelectorAll('.katex-error')) {
    out.katexErrors.push(short(e.getAttribute('title') || e.textContent));
  }

  // mdBook 0.5 shows each image twice (the picture and its click-to-zoom
  // copy inside .img-wrapper): both must load, the figure counts once.
  for (const img of main.querySelectorAll('img')) {
    const src = img.getAttribute('src');
    if (!img.complete || img.naturalWidth === 0) out.brokenImages.push(src);
    if (img.closest('.img-wrapper')) continue;
    out.images++;
    const unit = img.closest('label.checkbox-label') || img;
    const fig = img.closest('figure');
    const fc = fig && fig.querySelector('figcaption');
    let inline = false;
    for (let n = unit.nextSibling; n; n = n.nextSibling) {
      const text = n.textContent || '';
      if (FIG.test(text) && (n.nodeType !== 1 || visible(n))) { inline = true; break; }
      if (text.trim() !== '') break;
    }
    const block = unit.closest('p, li, figure, div') || unit;
    const next = block.nextElementSibling;
    const ok = (fc && visible(fc) && FIG.test(fc.textContent)) || inline
      || (next && visible(next) && FIG.test(next.textContent));
    if (!ok) out.uncaptionedFigures.push(src);
  }
  for (const t of main.querySelectorAll('table')) {
    out.tables++;
    const wrap = t.closest('.table-wrapper') || t;
    const host = wrap.parentElement;
    if (t.offsetWidth > host.clientWidth + 1 || t.getBoundingClientRect().right > col.right + 1) {
      const head = t.querySelector('tr');
      out.wideTables.push({head: short(head ? head.textContent : ''), width: t.offsetWidth,
                           column: host.clientWidth});
    }
    const cap = t.querySelector('caption');
    // the "Download: name.csv" line after a generated table is not its caption
    const skip = (e) => (e && e.classList.contains('download') ? e.nextElementSibling : e);
    const prev = wrap.previousElementSibling, next = skip(wrap.nextElementSibling);
    const ok = (cap && visible(cap) && TAB.test(cap.textContent))
      || (prev && visible(prev) && TAB.test(prev.textContent))
      || (next && visible(next) && TAB.test(next.textContent));
    if (!ok) {
      const head = t.querySelector('tr');
      out.uncaptionedTables.push(short(head ? head.textContent : ''));
    }
  }
  return out;
})()
"""


class Cdp:
    """A minimal DevTools-protocol client for one page target."""

    def __init__(self, ws_url: str):
        self.ws = websocket.create_connection(ws_url, timeout=60, suppress_origin=True)
        self.next_id = 0
        self.events: list[dict] = []

    def call(self, method: str, **params):
        self.next_id += 1
        mid = self.next_id
        self.ws.send(json.dumps({"id": mid, "method": method, "params": params}))
        while True:
            msg = json.loads(self.ws.recv())
            if msg.get("id") == mid:
                if "error" in msg:
                    raise RuntimeError(f"{method}: {msg['error']}")
                return msg.get("result", {})
            if "method" in msg:
                self.events.append(msg)

    def wait_event(self, method: str, timeout: float) -> bool:
        deadline = time.monotonic() + timeout
        if any(e["method"] == method for e in self.events):
            return True
        while time.monotonic() < deadline:
            self.ws.settimeout(max(0.05, deadline - time.monotonic()))
            try:
                msg = json.loads(self.ws.recv())
            except websocket.WebSocketTimeoutException:
                break
            if "method" in msg:
                self.events.append(msg)
                if msg["method"] == method:
                    return True
        return False

    def drain(self, seconds: float):
        self.wait_event("<never>", seconds)

    def close(self):
        self.ws.close()


class Chromium:
    def __init__(self, binary: str, width: int):
        self.profile = tempfile.mkdtemp(prefix="book-check-profile-")
        args = [binary, *CHROMIUM_FLAGS, f"--user-data-dir={self.profile}",
                f"--window-size={width},1000", "about:blank"]
        self.proc = subprocess.Popen(args, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        port_file = Path(self.profile) / "DevToolsActivePort"
        deadline = time.monotonic() + 30
        while not (port_file.exists() and port_file.read_text().strip()):
            if self.proc.poll() is not None or time.monotonic() > deadline:
                self.close()
                sys.exit(f"error: {binary} did not start (DevToolsActivePort missing)")
            time.sleep(0.1)
        port = port_file.read_text().split()[0]
        with urllib.request.urlopen(f"http://127.0.0.1:{port}/json/list") as r:
            targets = json.load(r)
        page = next(t for t in targets if t["type"] == "page")
        self.cdp = Cdp(page["webSocketDebuggerUrl"])

    def close(self):
        try:
            if hasattr(self, "cdp"):
                self.cdp.close()
        finally:
            self.proc.terminate()
            try:
                self.proc.wait(timeout=10)
            except subprocess.TimeoutExpired:
                self.proc.kill()
            shutil.rmtree(self.profile, ignore_errors=True)


@dataclass
class Page:
    name: str
    measure: dict = field(default_factory=dict)
    console: list[str] = field(default_factory=list)
    outside: list[str] = field(default_factory=list)
    failed: list[str] = field(default_factory=list)
    requests: int = 0
    extra: list[tuple[str, str]] = field(default_factory=list)
    tolerated: dict[str, int] = field(default_factory=dict)

    def failures(self, captions_fail: bool) -> list[tuple[str, str]]:
        m = self.measure
        out = []
        out += [("equation-overflow", f"{e['width']} px in {e['column']} px: {e['tex']}")
                for e in m["wideEquations"]]
        out += [("tag-overlap", f"tag {e['tag']} overlaps by {e['overlap']} px: {e['tex']}")
                for e in m["tagOverlaps"]]
        out += [("table-overflow", f"{e['width']} px in {e['column']} px: {e['head']}")
                for e in m["wideTables"]]
        out += [("broken-image", s) for s in m["brokenImages"]]
        out += [("katex-error", s) for s in m["katexErrors"]]
        out += [("console-error", s) for s in self.console]
        out += [("outside-request", s) for s in self.outside]
        out += [("failed-request", s) for s in self.failed]
        out += self.extra
        if captions_fail:
            out += [("missing-caption", f"figure {s}") for s in m["uncaptionedFigures"]]
            out += [("missing-caption", f"table {s}") for s in m["uncaptionedTables"]]
        return out

    def unexpected(self, captions_fail: bool) -> list[tuple[str, str]]:
        """The failures beyond those the baseline tolerates."""
        left = dict(self.tolerated)
        out = []
        for kind, what in self.failures(captions_fail):
            if left.get(kind, 0) > 0:
                left[kind] -= 1
            else:
                out.append((kind, what))
        return out


def inside(url: str, root: Path) -> bool:
    parsed = urllib.parse.urlparse(url)
    if parsed.scheme in ("data", "blob", "about"):
        return True
    if parsed.scheme != "file":
        return False
    target = Path(urllib.parse.unquote(parsed.path)).resolve()
    return target == root or root in target.parents


def check_page(cdp: Cdp, html: Path, root: Path, width: int) -> Page:
    page = Page(str(html.relative_to(root)))
    cdp.events.clear()
    cdp.call("Page.navigate", url=html.as_uri())
    if not cdp.wait_event("Page.loadEventFired", 60):
        page.console.append("page did not finish loading in 60 s")
    # Let fonts (KaTeX's) settle before measuring.
    cdp.call("Runtime.evaluate", expression="document.fonts.ready.then(() => 1)",
             awaitPromise=True, returnByValue=True)
    cdp.drain(0.2)
    res = cdp.call("Runtime.evaluate", expression=MEASURE_JS, returnByValue=True)
    if "exceptionDetails" in res:
        raise RuntimeError(f"{page.name}: measuring failed: {res['exceptionDetails']}")
    page.measure = res["result"]["value"]
    for e in cdp.events:
        m, p = e["method"], e.get("params", {})
        if m == "Network.requestWillBeSent":
            page.requests += 1
            if not inside(p["request"]["url"], root):
                page.outside.append(p["request"]["url"])
        elif m == "Network.loadingFailed" and not p.get("blockedReason"):
            page.failed.append(f"{p.get('errorText')} ({p.get('type')})")
        elif m == "Runtime.consoleAPICalled" and p.get("type") in ("error", "assert"):
            args = " ".join(str(a.get("value", a.get("description", ""))) for a in p.get("args", []))
            page.console.append(f"console.{p['type']}: {args}")
        elif m == "Runtime.exceptionThrown":
            d = p["exceptionDetails"]
            page.console.append(f"exception: {d.get('exception', {}).get('description', d.get('text'))}")
        elif m == "Log.entryAdded" and p["entry"]["level"] == "error":
            entry = p["entry"]
            page.console.append(f"{entry.get('source')}: {entry.get('text')} {entry.get('url', '')}".strip())
    return page


def pages_of(root: Path) -> list[Path]:
    """The chapters in reading order (the sidebar's, toc.html), then any others."""
    found = sorted(p for p in root.rglob("*.html")
                   if p.name not in SKIP and "api" not in p.relative_to(root).parts[:1])
    toc = root / "toc.html"
    order = []
    if toc.exists():
        for href in re.findall(r'<a href="([^"#]+\.html)"', toc.read_text()):
            p = (root / urllib.parse.unquote(href)).resolve()
            if p in found and p not in order:
                order.append(p)
    return order + [p for p in found if p not in order]


def tag_number(tag: str) -> tuple[int, str] | None:
    m = re.fullmatch(r"\((\d+)([a-z]?)\)", tag.strip())
    return (int(m.group(1)), m.group(2)) if m else None


def order_failures(results: list[Page]) -> None:
    """Numbered equations must appear in their numbered order through the book."""
    last, last_where = None, None
    for p in results:
        for tag in p.measure["tags"]:
            n = tag_number(tag)
            if n is None:
                continue
            if last is not None and n <= last:
                p.extra.append(("equation-order", f"{tag} comes after ({last[0]}{last[1]}) of {last_where}"))
            last, last_where = n, p.name


def apply_baseline(results: list[Page], baseline: dict, captions_fail: bool) -> list[str]:
    """Tolerate the known failures listed in `baseline` ({page: {kind: count}}).

    A page may fail by at most the listed count of each kind; more, or a kind
    not listed, is a failure. Returns the entries that are now better than
    listed, so that the baseline can be tightened.
    """
    stale = []
    for p in results:
        allowed = baseline.get(p.name, {})
        counts: dict[str, int] = {}
        for kind, _ in p.failures(captions_fail):
            counts[kind] = counts.get(kind, 0) + 1
        for kind, n in allowed.items():
            if counts.get(kind, 0) < n:
                stale.append(f"{p.name}: {kind} listed {n}, found {counts.get(kind, 0)}")
        p.tolerated = {k: min(n, allowed.get(k, 0)) for k, n in counts.items()}
    return stale


def run(root: Path, width: int, captions: str, chromium: str, json_out: str | None,
        baseline: dict | None = None) -> dict:
    root = root.resolve()
    pages = pages_of(root)
    if not pages:
        sys.exit(f"error: no pages in {root}: build the book first")
    browser = Chromium(chromium, width)
    results = []
    try:
        cdp = browser.cdp
        for domain in ("Page", "Runtime", "Log", "Network"):
            cdp.call(f"{domain}.enable")
        cdp.call("Emulation.setDeviceMetricsOverride", width=width, height=1000,
                 deviceScaleFactor=1, mobile=False)
        # Nothing may leave the machine; the attempt is still reported.
        cdp.call("Network.setBlockedURLs", urls=["http://*", "https://*", "ws://*", "wss://*"])
        for html in pages:
            results.append(check_page(cdp, html, root, width))
    finally:
        browser.close()

    captions_fail = captions == "fail"
    order_failures(results)
    stale = apply_baseline(results, baseline or {}, captions_fail)
    print(f"Browser check of {root} at {width} px ({len(results)} pages, reading order)")
    print(f"{'page':<24}{'col':>5}{'eqs':>5}{'wide':>5}{'tag':>5}{'tabs':>5}{'wide':>5}"
          f"{'imgs':>5}{'bad':>4}{'cons':>5}{'out':>4}{'reqs':>5}  uncaptioned fig/tab")
    totals = {"pages": len(results), "failures": {}, "uncaptioned_figures": 0,
              "uncaptioned_tables": 0, "figures": 0, "tables": 0, "equations": 0,
              "failing_pages": 0, "known": 0}
    report = []
    for p in results:
        m = p.measure
        fails = p.failures(captions_fail)
        new = p.unexpected(captions_fail)
        totals["failing_pages"] += bool(new)
        totals["known"] += len(fails) - len(new)
        for kind, _ in fails:
            totals["failures"][kind] = totals["failures"].get(kind, 0) + 1
        totals["uncaptioned_figures"] += len(m["uncaptionedFigures"])
        totals["uncaptioned_tables"] += len(m["uncaptionedTables"])
        totals["figures"] += m["images"]
        totals["tables"] += m["tables"]
        totals["equations"] += m["displays"]
        verdict = "  FAIL" if new else ("  known" if fails else "")
        print(f"{p.name:<24}{m['column']:>5}{m['displays']:>5}{len(m['wideEquations']):>5}"
              f"{len(m['tagOverlaps']):>5}{m['tables']:>5}{len(m['wideTables']):>5}"
              f"{m['images']:>5}{len(m['brokenImages']):>4}{len(p.console):>5}{len(p.outside):>4}"
              f"{p.requests:>5}  {len(m['uncaptionedFigures'])}/{m['images']} "
              f"{len(m['uncaptionedTables'])}/{m['tables']}{verdict}")
        report.append({"page": p.name, "requests": p.requests, **m, "console": p.console,
                       "outside": p.outside, "failed": p.failed,
                       "failures": [{"kind": k, "what": w} for k, w in fails]})
    for p in results:
        fails = p.failures(captions_fail)
        new = set(p.unexpected(captions_fail))
        if fails:
            print(f"\n{p.name}:")
            for kind, what in fails:
                print(f"  {'FAIL ' if (kind, what) in new else 'known'} {kind}: {what}")
    if not captions_fail and (totals["uncaptioned_figures"] or totals["uncaptioned_tables"]):
        print("\nwithout a visible numbered caption (reported only; --captions fail makes them errors):")
        for r in report:
            for s in r["uncaptionedFigures"]:
                print(f"  {r['page']}: figure {s}")
            for s in r["uncaptionedTables"]:
                print(f"  {r['page']}: table [{s}]")
    if stale:
        print("\nthe baseline lists more failures than found; tighten it:")
        for line in stale:
            print(f"  {line}")
    print(f"\n{len(results)} pages, {totals['equations']} display equations, {totals['tables']} tables, "
          f"{totals['figures']} figures; failures: {totals['failures'] or 'none'} "
          f"({totals['known']} tolerated by the baseline); missing captions: "
          f"{totals['uncaptioned_figures']} figures, {totals['uncaptioned_tables']} tables")
    if json_out:
        Path(json_out).write_text(json.dumps({"totals": totals, "pages": report}, indent=1))
    return totals


def self_test(width: int, chromium: str) -> int:
    """Build the fixture book and require exactly its deliberate failures."""
    fixture = ROOT / "tests" / "fixtures" / "book-check"
    expected = json.loads((fixture / "expected.json").read_text())
    with tempfile.TemporaryDirectory(prefix="book-check-") as tmp:
        book = Path(tmp) / "book"
        shutil.copytree(fixture, book)
        shutil.copytree(ROOT / "book" / "src" / "katex", book / "src" / "katex")
        shutil.copytree(ROOT / "book" / "theme", book / "theme")
        toml = (book / "book.toml").read_text()
        tool = ROOT / "book" / "tools" / "mdbook-iga.mjs"
        (book / "book.toml").write_text(toml.replace("../../../book/tools/mdbook-iga.mjs", str(tool)))
        subprocess.run(["mdbook", "build", str(book)], check=True)
        totals = run(book / "out", width, "warn", chromium, None)
    got = totals["failures"]
    exact, at_least = expected["exact"], expected["at_least"]
    problems = [f"{k}: expected {n}, got {got.get(k, 0)}" for k, n in exact.items() if got.get(k, 0) != n]
    problems += [f"{k}: expected at least {n}, got {got.get(k, 0)}"
                 for k, n in at_least.items() if got.get(k, 0) < n]
    problems += [f"{k}: not expected, got {n}" for k, n in got.items()
                 if k not in exact and k not in at_least]
    print(f"\nself-test: expected exactly {exact} and at least {at_least}; got {got}")
    if problems:
        print("self-test FAILED: the check does not report the fixture's deliberate faults:")
        for p in problems:
            print(f"  {p}")
        return 1
    print("self-test passed: the check fails on the too-wide equations, tag and table, the "
          "request leaving the book, the broken images and the console error, and on nothing else")
    return 0


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("book", nargs="?", default=str(ROOT / "book" / "book"),
                    help="the built book (default: book/book)")
    ap.add_argument("--width", type=int, default=1280)
    ap.add_argument("--captions", choices=["warn", "fail"], default="warn")
    ap.add_argument("--chromium", default=os.environ.get("CHROMIUM", "chromium"))
    ap.add_argument("--json", help="write the per-page report as JSON to this file")
    ap.add_argument("--baseline", help="JSON {page: {kind: count}} of known failures to tolerate")
    ap.add_argument("--self-test", action="store_true")
    a = ap.parse_args()
    if shutil.which(a.chromium) is None:
        sys.exit(f"error: {a.chromium} not found: apt-get install -y chromium (see README, Checks)")
    if a.self_test:
        return self_test(a.width, a.chromium)
    baseline = json.loads(Path(a.baseline).read_text()) if a.baseline else None
    if baseline is not None:
        baseline.pop("_comment", None)
    totals = run(Path(a.book), a.width, a.captions, a.chromium, a.json, baseline)
    return 1 if totals["failing_pages"] else 0


if __name__ == "__main__":
    sys.exit(main())
