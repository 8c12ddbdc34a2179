#!/usr/bin/env python3
"""Check every link of the built book, its API pages included.

    python3 scripts/check_links.py [BOOK_OUT]        (default: book/book)

For every HTML file under BOOK_OUT, every href= and src= must resolve:
a relative URL to an existing file inside BOOK_OUT, and its #fragment (if any)
to an id or name in that file. The book's own pages may not link outside
BOOK_OUT at all: no http(s) link, no file outside the folder.

The rustdoc pages under api/ are checked the same way, with two allowances
that rustdoc itself makes: links into the Rust standard library's documentation
and of the dependencies (https://doc.rust-lang.org/, https://docs.rs/: links a
reader may follow, never requests the page makes), and the line-range fragments of its source pages (#12-30), which its
JavaScript resolves. The chapters' links into api/ (made by the book
preprocessor's api: links) are checked like any other link, anchor included.

Needs only the Python standard library.
"""

from __future__ import annotations

import html
import re
import sys
import urllib.parse
from pathlib import Path

ATTR = re.compile(r"""\s(href|src)\s*=\s*("([^"]*)"|'([^']*)')""", re.I)
ID = re.compile(r"""\s(?:id|name)\s*=\s*("([^"]*)"|'([^']*)')""", re.I)
# Text that is not markup: code shown in <pre>/<code> may contain href="…" literally,
# and scripts build URLs from strings.
SKIP_BLOCKS = re.compile(r"<(script|style)\b[^>]*>.*?</\1>", re.I | re.S)
COMMENT = re.compile(r"<!--.*?-->", re.S)
# rustdoc links the standard library's and the dependencies' own documentation.
API_EXTERNAL = ("https://doc.rust-lang.org/", "https://docs.rs/")
# mdBook writes 404.html for web servers: it resolves links against the site root.
SKIP_FILES = {"404.html"}


def ids_of(path: Path, cache: dict[Path, set[str]]) -> set[str]:
    if path not in cache:
        text = path.read_text(encoding="utf-8", errors="replace")
        cache[path] = {html.unescape(m.group(2) or m.group(3) or "") for m in ID.finditer(text)}
    return cache[path]


def links_of(text: str):
    text = COMMENT.sub("", SKIP_BLOCKS.sub(lambda m: m.group(0)[: m.group(0).find(">") + 1], text))
    for m in ATTR.finditer(text):
        yield html.unescape(m.group(3) if m.group(3) is not None else m.group(4))


def check(root: Path) -> int:
    root = root.resolve()
    files = sorted(p for p in root.rglob("*.html") if p.name not in SKIP_FILES)
    if not files:
        print(f"error: no HTML in {root}: build the book first", file=sys.stderr)
        return 2
    ids: dict[Path, set[str]] = {}
    errors: list[str] = []
    counts = {"book pages": 0, "api pages": 0, "links": 0, "api links from chapters": 0,
              "std/docs.rs links from api pages": 0}
    for page in files:
        rel = page.relative_to(root)
        in_api = rel.parts[0] == "api"
        counts["api pages" if in_api else "book pages"] += 1
        text = page.read_text(encoding="utf-8", errors="replace")
        for url in links_of(text):
            counts["links"] += 1
            parsed = urllib.parse.urlsplit(url)
            where = f"{rel}: {url}"
            if parsed.scheme or url.startswith("//"):
                if parsed.scheme in ("data", "javascript"):
                    continue
                if in_api and url.startswith(API_EXTERNAL):
                    counts["std/docs.rs links from api pages"] += 1
                    continue
                errors.append(f"{where}: leaves the book")
                continue
            if parsed.path:
                target = (page.parent / urllib.parse.unquote(parsed.path)).resolve()
            else:
                target = page
            if target != root and root not in target.parents:
                errors.append(f"{where}: leaves the book folder")
                continue
            if target.is_dir():
                target = target / "index.html"
            if not target.is_file():
                errors.append(f"{where}: no such file")
                continue
            if not in_api and target.is_relative_to(root / "api"):
                counts["api links from chapters"] += 1
            frag = parsed.fragment
            if not frag or target.suffix != ".html":
                continue
            if in_api and re.fullmatch(r"\d+(-\d+)?", frag):
                continue  # a line range on a rustdoc source page
            # rustdoc writes some ids percent-encoded (impl-Clone-for-Load%3CB%3E).
            known = ids_of(target, ids)
            if frag not in known and urllib.parse.unquote(frag) not in known:
                errors.append(f"{where}: no anchor #{frag} in {target.relative_to(root)}")
    for e in errors:
        print(f"error: {e}")
    summary = ", ".join(f"{v} {k}" for k, v in counts.items())
    print(f"link check of {root}: {summary}; {len(errors)} broken")
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(check(Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).resolve().parent.parent / "book" / "book"))
