"""Check every link of a built site (default: site/): each relative href/src (or one from the site's
root, /...) must name a file that exists and, with a #fragment, an element id in it.  Links in the
executed tutorials are checked too (MkDocs itself does not check them: write them as ``page.html``).  Links to other hosts are listed, not fetched
(the build machine may be offline).  Exit 1 with the broken links listed, else 0.

    python scripts/check-links.py [SITE_DIR]
"""
from __future__ import annotations

import sys
from html.parser import HTMLParser
from pathlib import Path
from urllib.parse import unquote, urlsplit


class Page(HTMLParser):
    """The links (href, src) and element ids of one HTML page."""

    def __init__(self):
        super().__init__()
        self.links: list[str] = []
        self.ids: set[str] = set()

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if a.get("id"):
            self.ids.add(a["id"])
        if tag == "a" and a.get("name"):
            self.ids.add(a["name"])
        for key in ("href", "src"):
            if a.get(key) and not (tag == "link" and a.get("rel") in ("preconnect", "dns-prefetch")):
                self.links.append(a[key])


def parse(path: Path) -> Page:
    page = Page()
    page.feed(path.read_text(encoding="utf-8", errors="replace"))
    return page


def broken_links(site: Path) -> tuple[list[str], set[str]]:
    """(broken links as 'page: link (why)', external hosts linked)."""
    pages = {p: parse(p) for p in site.rglob("*.html")}
    broken, external = [], set()
    for path, page in pages.items():
        for link in page.links:
            url = urlsplit(link)
            if url.scheme in ("http", "https", "mailto", "data", "javascript") or link.startswith("//"):
                if url.netloc:
                    external.add(url.netloc)
                continue
            if not url.path:
                target = path
            elif url.path.startswith("/"):                 # from the site's root (the 404 page)
                target = (site / unquote(url.path).lstrip("/")).resolve()
            else:
                target = (path.parent / unquote(url.path)).resolve()
            if target.is_dir():
                target = target / "index.html"
            where = f"{path.relative_to(site)}: {link}"
            if not target.exists():
                broken.append(f"{where} (no such file)")
                continue
            if url.fragment and target.suffix == ".html":
                ids = (pages.get(target) or parse(target)).ids
                if unquote(url.fragment) not in ids:
                    broken.append(f"{where} (no element with id '{url.fragment}')")
    return broken, external


def main(argv: list[str]) -> int:
    site = Path(argv[1] if len(argv) > 1 else "site").resolve()
    if not (site / "index.html").exists():
        print(f"check-links: {site} holds no index.html; build the site first (bash scripts/build-docs.sh)")
        return 2
    broken, external = broken_links(site)
    n = len(list(site.rglob("*.html")))
    for b in broken:
        print(f"check-links: broken: {b}")
    print(f"check-links: {n} pages, {len(broken)} broken links; links to other hosts (not fetched): "
          + (", ".join(sorted(external)) or "none"))
    return 1 if broken else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
