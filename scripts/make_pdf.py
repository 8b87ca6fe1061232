#!/usr/bin/env python
"""The printable edition: the whole built site as ONE PDF (``make pdf``).

    python scripts/make_pdf.py [--site _build/html] [--out _build/pdf/whittaker-teach.pdf]

Reads the pages of the built site (``make site``) in the order of ``_toc.yml``,
joins their article bodies into one print document (ids prefixed by page, links
between pages turned into links inside the document), moves every exercise
solution into an appendix at the end, and prints it with headless Chromium
(Playwright ``page.pdf`` on ``/usr/bin/chromium`` or ``$CHROMIUM``), after
MathJax has typeset it. The print style (``book/_ext/wt_static/wt-print.css``)
opens every fold, wraps code and text outputs, and scales every display
equation that is wider than the page down until it fits, so that each one is
printed whole with its paper number; figures stay SVG (vector) in the PDF.

The PDF is also copied into the site (``<site>/whittaker-teach.pdf``), which
links to it from its front page. Nothing is fetched from the network.
"""
from __future__ import annotations

import argparse
import functools
import http.server
import os
import re
import shutil
import sys
import threading
import time
from pathlib import Path
from urllib.parse import urljoin, urlsplit

ROOT = Path(__file__).resolve().parents[1]
PDF_NAME = "whittaker-teach.pdf"
CHROMIUM = os.environ.get("CHROMIUM") or shutil.which("chromium") or "/usr/bin/chromium"
BOOK_PATH = "__print__/book.html"
PRINT_CSS = ROOT / "book" / "_ext" / "wt_static" / "wt-print.css"  # served from memory, never written into the site


def toc_pages(toc_file: Path) -> list[tuple[str, str]]:
    """(part caption, page) in reading order, from the Jupyter Book _toc.yml."""
    import yaml

    toc = yaml.safe_load(toc_file.read_text(encoding="utf-8"))
    pages = [("", toc["root"])]
    for part in toc.get("parts", []):
        for chapter in part.get("chapters", []):
            pages.append((part.get("caption", ""), chapter["file"]))
    return pages


def _slug(page: str) -> str:
    return re.sub(r"[^A-Za-z0-9]+", "-", page).strip("-")


def build_document(site: Path, pages: list[tuple[str, str]]) -> str:
    """One HTML document from the article bodies of the site's pages."""
    from bs4 import BeautifulSoup

    first = BeautifulSoup((site / f"{pages[1][1]}.html").read_text("utf-8"), "html.parser")
    page_url = {page: f"/{page}.html" for _, page in pages}
    slug_of = {f"/{page}.html": _slug(page) for _, page in pages}

    def absolute(url: str, base: str) -> str:
        return urlsplit(urljoin(f"http://site{base}", url))._replace(scheme="", netloc="").geturl()

    # the head: the site's style sheets and MathJax (its configuration first)
    head = ['<meta charset="utf-8">', "<title>Whittaker equations for non-holonomic systems</title>"]
    base0 = page_url[pages[1][1]]
    for link in first.find_all("link", rel="stylesheet"):
        head.append(f'<link rel="stylesheet" href="{absolute(link["href"], base0)}">')
    head.append(f"<style>{PRINT_CSS.read_text('utf-8')}</style>")
    for script in first.find_all("script"):
        src = script.get("src") or ""
        if "mathjax" in src:
            head.append(f'<script defer src="{absolute(src, base0)}"></script>')
        elif not src and "MathJax" in script.text:
            head.append(f"<script>{script.text}</script>")

    body = ['<div class="wt-title-page"><h1 class="wt-book-title">Whittaker equations for '
            "non-holonomic systems</h1><p class=\"wt-book-subtitle\">A course on Mei Fengxiang "
            "(1983), <em>Extension of the Whittaker equations to non-holonomic mechanical "
            "systems</em>, with the whittaker-teach library</p>"
            '<p class="wt-book-note">The printed edition of the course website. Exercise '
            "solutions are collected in the appendix.</p></div>",
            '<nav class="wt-contents"><h2>Contents</h2><ol>']
    chapters = []
    solutions = []
    current_part = None
    for part, page in pages:
        path = site / f"{page}.html"
        soup = BeautifulSoup(path.read_text("utf-8"), "html.parser")
        article = soup.find("article", class_="bd-article") or soup.find("main")
        if article is None:
            raise SystemExit(f"make_pdf: no article in {path}")
        base = page_url[page]
        slug = _slug(page)
        for tag in article.find_all(True):
            if tag.get("id"):
                tag["id"] = f"{slug}--{tag['id']}"
            for attr in ("src", "href"):
                url = tag.get(attr)
                if not url or url.startswith(("data:", "mailto:", "javascript:")):
                    continue
                target = urlsplit(urljoin(f"http://site{base}", url))
                if target.netloc != "site":
                    continue  # an external link stays as it is
                if attr == "href" and target.path in slug_of:
                    anchor = f"{slug_of[target.path]}--{target.fragment}" if target.fragment else slug_of[target.path]
                    tag[attr] = f"#{anchor}"
                elif attr == "href" and target.path.endswith(".html"):
                    tag[attr] = f"#{slug}"  # a generated page (index, search): not printed
                else:
                    tag[attr] = absolute(url, base)
        for sel in ("a.headerlink", "div.toggle-details__summary", "script"):
            for t in article.select(sel):
                t.decompose()
        # exercise solutions: to the appendix, in reading order
        heading = article.find(["h1"])
        title = heading.get_text(" ", strip=True).replace("#", "").strip() if heading else page
        title = re.sub(r"\s+", " ", title)
        found = article.select("div.solution")
        if found:
            block = [f'<section class="wt-solutions-of" id="{slug}--solutions"><h2>{title}</h2>']
            for sol in found:
                sol["class"] = [c for c in sol.get("class", []) if c not in ("dropdown", "toggle", "toggle-hidden")]
                block.append(str(sol.extract()))
            block.append("</section>")
            solutions.append("".join(block))
        if part != current_part and part:
            body_part = f'<h1 class="wt-part-title">{part}</h1>'
            chapters.append(f'<section class="wt-part">{body_part}</section>')
            body.append(f'<li class="wt-toc-part">{part}</li>')
            current_part = part
        body.append(f'<li><a href="#{slug}">{title}</a></li>')
        chapters.append(f'<section class="wt-page" id="{slug}" data-page="{page}">{article.decode_contents()}</section>')
    body.append('<li class="wt-toc-part"><a href="#wt-solutions">Appendix: solutions to the exercises</a></li>')
    body.append("</ol></nav>")
    body.extend(chapters)
    body.append('<section class="wt-page wt-appendix" id="wt-solutions"><h1>Appendix: solutions to the '
                "exercises</h1>" + "".join(solutions) + "</section>")
    return ("<!DOCTYPE html><html lang=\"en\" data-theme=\"light\" data-mode=\"light\"><head>"
            + "\n".join(head) + '</head><body class="wt-print">' + "\n".join(body) + "</body></html>")


# Run in the page before printing: open folds, fit wide equations to the page.
PREPARE_JS = """async () => {
    await MathJax.startup.promise;
    document.querySelectorAll('details:not(.wt-report)').forEach(d => { d.open = true; });
    document.querySelectorAll('.toggle-hidden').forEach(e => e.classList.remove('toggle-hidden'));
    await document.fonts.ready;
    let scaled = 0, smallest = 1;
    for (const box of document.querySelectorAll('div.math')) {
        const c = box.querySelector('mjx-container');
        if (!c) continue;
        const room = box.clientWidth;
        const need = box.scrollWidth;
        if (need > room + 1) {
            const f = room / need;
            c.style.zoom = f.toFixed(4);
            scaled++; smallest = Math.min(smallest, f);
        }
    }
    for (const c of document.querySelectorAll('span.math > mjx-container')) {
        const line = c.closest('p, li, td, dd, div') || document.body;
        const w = c.getBoundingClientRect().width, room = line.clientWidth - 4;
        if (w > room) c.style.zoom = (room / w).toFixed(4);
    }
    return {scaled, smallest, displays: document.querySelectorAll('div.math').length};
}"""


def print_pdf(site: Path, html: str, out: Path) -> dict:
    from playwright.sync_api import sync_playwright

    if not Path(CHROMIUM).is_file():
        raise SystemExit(f"make_pdf: Chromium not found at {CHROMIUM}: apt-get install chromium "
                         "(make sysdeps), or set CHROMIUM=/path/to/chromium")
    handler = functools.partial(_Quiet, directory=str(site))
    server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), handler)
    threading.Thread(target=server.serve_forever, daemon=True).start()
    base = f"http://127.0.0.1:{server.server_address[1]}/"
    errors: list[str] = []
    try:
        with sync_playwright() as pw:
            browser = pw.chromium.launch(executable_path=CHROMIUM, headless=True,
                                         args=["--no-sandbox", "--disable-gpu", "--headless"])
            # A4 text width (210 mm - 2 x 16 mm) at 96 px/in is about 673 px
            page = browser.new_page(viewport={"width": 673, "height": 1000})
            page.on("pageerror", lambda e: errors.append(str(e)))

            def route(r):
                host = urlsplit(r.request.url).hostname
                if r.request.url == base + BOOK_PATH:
                    r.fulfill(body=html, content_type="text/html; charset=utf-8")
                elif host == "127.0.0.1" or urlsplit(r.request.url).scheme in ("data", "blob"):
                    r.continue_()
                else:
                    r.abort()

            page.route("**/*", route)
            page.goto(base + BOOK_PATH, wait_until="load", timeout=240_000)
            page.emulate_media(media="print")
            stats = page.evaluate(PREPARE_JS)
            out.parent.mkdir(parents=True, exist_ok=True)
            page.pdf(path=str(out), format="A4", print_background=True,
                     margin={"top": "18mm", "bottom": "18mm", "left": "16mm", "right": "16mm"},
                     display_header_footer=True,
                     header_template="<span></span>",
                     footer_template='<div style="font-size:8px;width:100%;text-align:center;">'
                                     '<span class="pageNumber"></span> / <span class="totalPages"></span></div>')
            browser.close()
    finally:
        server.shutdown()
        server.server_close()
    if errors:
        raise SystemExit(f"make_pdf: JavaScript errors in the print document: {errors}")
    return stats


class _Quiet(http.server.SimpleHTTPRequestHandler):
    def log_message(self, format, *args):  # noqa: A002
        pass


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--site", default=str(ROOT / "_build" / "html"))
    ap.add_argument("--out", default=str(ROOT / "_build" / "pdf" / PDF_NAME))
    ap.add_argument("--toc", default=str(ROOT / "_toc.yml"))
    args = ap.parse_args(argv)
    site, out = Path(args.site), Path(args.out)
    if not (site / "index.html").is_file():
        raise SystemExit(f"make_pdf: no built site at {site}: run `make site` first")
    t0 = time.monotonic()
    html = build_document(site, toc_pages(Path(args.toc)))
    stats = print_pdf(site, html, out)
    shutil.copyfile(out, site / PDF_NAME)
    print(f"make_pdf: {out} ({out.stat().st_size // 1024} KiB) in {time.monotonic() - t0:.0f} s; "
          f"{stats['displays']} display equations, {stats['scaled']} scaled to the page width "
          f"(smallest factor {stats['smallest']:.2f}); copied to {site / PDF_NAME}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
