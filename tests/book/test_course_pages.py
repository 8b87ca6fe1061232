"""The built course pages (``make site``) as a reader meets them (issue 23): every image
has alt text; the page "The paper's equations" links each of Mei's 46 numbers to an
anchor that exists on the page it points to; the [1.26a] caption names
dL/dqdot_(eps+beta); the book's own labels never look like Mei's numbers."""

from __future__ import annotations

import os
import re
from html.parser import HTMLParser
from pathlib import Path
from urllib.parse import urlsplit

import pytest

from whittaker_teach.labels import PAPER_NUMBERS

SITE = Path(__file__).resolve().parents[2] / "_build" / "html"


@pytest.fixture(scope="module")
def pages():
    if not (SITE / "index.html").exists():
        if os.environ.get("WT_REQUIRE_SITE"):
            pytest.fail("the site is not built: run `make site` first")
        pytest.skip("the site is not built (make site)")
    return {p.relative_to(SITE).as_posix(): p.read_text(encoding="utf-8")
            for p in SITE.rglob("*.html") if p.relative_to(SITE).parts[0] not in ("lite", "_static")}


class _Scan(HTMLParser):
    def __init__(self):
        super().__init__()
        self.ids, self.imgs, self.links = set(), [], []

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if "id" in a:
            self.ids.add(a["id"])
        if tag == "img":
            self.imgs.append(a)
        if tag == "a" and a.get("href"):
            self.links.append(a["href"])


def _scan(html):
    s = _Scan()
    s.feed(html)
    return s


def test_every_image_has_alt_text(pages):
    bare = [(rel, img.get("src")) for rel, html in pages.items()
            for img in _scan(html).imgs
            if len((img.get("alt") or "").split()) < 3 and "logo" not in (img.get("class") or "")]
    assert not bare, f"images without alt text: {bare[:10]}"


def test_paper_equations_page_links_every_number_to_an_existing_anchor(pages):
    rel = "book/paper-equations.html"
    assert rel in pages
    links = _scan(pages[rel]).links
    ids = {}
    for n in PAPER_NUMBERS:
        anchor = "eq-" + n.replace(".", "-")
        hits = [h for h in links if urlsplit(h).fragment == anchor]
        assert hits, f"({n}) is not linked"
        target = urlsplit(hits[0])
        page = (Path(rel).parent / target.path).as_posix() if target.path else rel
        page = os.path.normpath(page)
        assert page in pages, f"({n}) links to a missing page {page}"
        ids.setdefault(page, _scan(pages[page]).ids)
        assert anchor in ids[page], f"({n}) links to {page}#{anchor}, which has no such id"


def test_1_26a_caption_names_dL_dqdot_dependent(pages):
    html = pages["book/04-generalized-whittaker.html"]
    caps = re.findall(r'<div class="wt-step"><strong>.{0,80}?\[1\.26a\].*?</div>', html, re.S)
    assert caps, "chapter 4 prints no [1.26a] step"
    for cap in caps:
        assert r"\partial L/\partial\dot q_{\varepsilon+\beta}" in cap
        assert r"\partial\tilde L/\partial\dot q_{\varepsilon+\beta}" not in cap


def test_own_labels_are_never_tagged_as_paper_numbers(pages):
    for rel, html in pages.items():
        for tag in re.findall(r"\\tag\{([^}]*)\}", html):
            assert tag in PAPER_NUMBERS, f"{rel}: \\tag{{{tag}}} looks like one of Mei's numbers"
