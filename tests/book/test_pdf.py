"""The printable edition (``make pdf`` -> ``_build/pdf/whittaker-teach.pdf``).

Read with poppler's ``pdftotext`` (Debian ``poppler-utils``):

* every one of the paper's 46 equation numbers (1.1)-(1.27), (2.1)-(2.4),
  (3.1)-(3.15) is printed;
* every chapter of ``_toc.yml`` and the appendix of solutions are in it;
* no word lies outside the page's text area (``pdftotext -bbox``): nothing is
  cut at the right edge or runs off the sheet;
* the figures are vector graphics (no raster image in the PDF: ``pdfimages``).

Without the PDF the module is skipped, unless ``WT_REQUIRE_PDF=1`` (set by
``make test``) makes that a failure; a missing ``pdftotext`` is then a failure
saying what to install.
"""
from __future__ import annotations

import html
import os
import re
import shutil
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
PDF = Path(os.environ.get("WT_PDF", ROOT / "_build" / "pdf" / "whittaker-teach.pdf"))
REQUIRED = os.environ.get("WT_REQUIRE_PDF") == "1"
LABELS = ([f"1.{i}" for i in range(1, 28)] + [f"2.{i}" for i in range(1, 5)]
          + [f"3.{i}" for i in range(1, 16)])
# the page margins of scripts/make_pdf.py (16 mm left and right), in points
SIDE_MARGIN_PT = 16 / 25.4 * 72
TOL_PT = 1.0
# MathJax builds a tall bracket from glyph pieces (U+239B-U+23AF), and a wide
# under- or overbrace from pieces of its TeX font's private-use area (U+E150-U+E154),
# that it scales and clips to the bracket's height or the brace's width; pdftotext
# reports the unclipped glyph box, thousands of points tall or wide, so these pieces
# are not "words"
STRETCHY_PIECES = re.compile("^[\u239b-\u23af\ue150-\ue154]+$")
# a stretched vertical bar (\Big|, an evaluation bar) is one glyph scaled the same way:
# skipped only when its box is that of a scaled glyph (taller than a page's text line)
STRETCHY_BARS = re.compile("^[|\u2223\u2225\u2016]+$")


def _stretched(w, y0, y1):
    return bool(STRETCHY_PIECES.match(w) or (STRETCHY_BARS.match(w) and y1 - y0 > 100))


def _need(tool: str) -> str:
    path = shutil.which(tool)
    if path is None:
        msg = f"{tool} not found: apt-get install poppler-utils (make sysdeps does it as root)"
        if REQUIRED:
            pytest.fail(msg)
        pytest.skip(msg)
    return path


@pytest.fixture(scope="module")
def pdf() -> Path:
    if not PDF.is_file():
        msg = f"no PDF at {PDF}: run `make pdf`"
        if REQUIRED:
            pytest.fail(msg)
        pytest.skip(msg)
    return PDF


@pytest.fixture(scope="module")
def text(pdf) -> str:
    out = subprocess.run([_need("pdftotext"), "-enc", "UTF-8", str(pdf), "-"],
                         check=True, capture_output=True, text=True).stdout
    return re.sub(r"[ \t]+", " ", out)


@pytest.fixture(scope="module")
def words(pdf) -> list[tuple[int, float, float, float, float, float, str]]:
    """(page, page width, xMin, yMin, xMax, yMax, word) of every word."""
    out = subprocess.run([_need("pdftotext"), "-bbox", str(pdf), "-"],
                         check=True, capture_output=True, text=True).stdout
    found = []
    page, width = 0, 0.0
    for line in out.splitlines():
        m = re.match(r'\s*<page width="([\d.]+)" height="([\d.]+)">', line)
        if m:
            page += 1
            width, height = float(m.group(1)), float(m.group(2))
            continue
        m = re.match(r'\s*<word xMin="([-\d.]+)" yMin="([-\d.]+)" xMax="([-\d.]+)" '
                     r'yMax="([-\d.]+)">(.*)</word>', line)
        if m:
            x0, y0, x1, y1 = map(float, m.groups()[:4])
            found.append((page, width, height, x0, y0, x1, y1, html.unescape(m.group(5))))
    return found


@pytest.mark.parametrize("label", LABELS)
def test_equation_number_printed(text, label):
    assert f"({label})" in text, f"equation ({label}) is not in the PDF"


def _chapter_titles() -> list[str]:
    titles = []
    for nb in sorted((ROOT / "book").glob("0*.ipynb")):
        import json

        first = "".join(json.loads(nb.read_text("utf-8"))["cells"][0]["source"])
        m = re.search(r"^# (.+)$", first, re.M)
        if m:
            titles.append(m.group(1).strip())
    return titles


def _plain(s: str) -> str:
    """A title as pdftotext prints it, roughly: no maths markup, one space."""
    s = re.sub(r"\$[^$]*\$", " ", s)
    return re.sub(r"\s+", " ", s).strip()


def test_every_chapter_and_the_appendix(text):
    flat = re.sub(r"\s+", " ", text)
    titles = _chapter_titles()
    assert len(titles) >= 8, titles
    missing = []
    for title in titles:
        # the words of the title before any maths, e.g. "The generalized Whittaker equations"
        head = _plain(title).split(" ( ")[0]
        head = " ".join(head.split()[:4])
        if head not in flat:
            missing.append(title)
    assert not missing, f"chapters not in the PDF: {missing}"
    assert "Appendix: solutions to the exercises" in flat
    # the appendix holds the solutions: after its heading come "Solution to" blocks
    appendix = flat.rsplit("Appendix: solutions to the exercises", 1)[1]
    assert appendix.count("Solution to") >= 20, appendix.count("Solution to")


def test_no_text_outside_the_text_area(words):
    outside = [
        f"page {p}: {w!r} at x {x0:.0f}..{x1:.0f} of {width:.0f} pt"
        for p, width, height, x0, y0, x1, y1, w in words
        if not _stretched(w, y0, y1) and (x0 < SIDE_MARGIN_PT - TOL_PT or x1 > width - SIDE_MARGIN_PT + TOL_PT
        or y0 < -TOL_PT or y1 > height + TOL_PT)
    ]
    assert words, "pdftotext found no words"
    assert not outside, f"{len(outside)} words outside the text area:\n  " + "\n  ".join(outside[:20])


def test_figures_are_vector_graphics(pdf):
    tool = _need("pdfimages")
    listing = subprocess.run([tool, "-list", str(pdf)], check=True, capture_output=True,
                             text=True).stdout.splitlines()[2:]
    # the figures are SVG and the print style draws no shadows (which Chromium
    # would rasterise): a raster image here is a figure that is not vector
    assert not listing, "raster images in the PDF:\n" + "\n".join(listing[:10])


# ---------------------------------------------------------------- Chinese (issue 23)
CJK = re.compile(r"[\u3400-\u4dbf\u4e00-\u9fff]+")


def test_pdf_embeds_a_cjk_font(pdf):
    out = subprocess.run([_need("pdffonts"), str(pdf)], check=True, capture_output=True,
                         text=True).stdout
    cjk = [line for line in out.splitlines() if re.search(r"WenQuanYi|CJK|SourceHan", line)]
    assert cjk, f"no CJK font in the PDF (apt-get install fonts-wqy-zenhei):\n{out}"
    assert all(" yes " in line for line in cjk), f"a CJK font is not embedded:\n{out}"


def test_pdf_prints_the_glossarys_chinese(text):
    glossary = (ROOT / "book" / "glossary.md").read_text(encoding="utf-8")
    terms = sorted(set(CJK.findall(glossary)))
    assert len(terms) >= 20
    flat = re.sub(r"\s+", "", text)
    missing = [t for t in terms if t not in flat]
    assert not missing, f"Chinese terms of the glossary missing from the PDF text: {missing}"
