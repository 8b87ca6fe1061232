"""The course book's shape, read from its sources (issue 23): every chapter opens with an
overview and closes its main text with a summary; every chapter exercise names its level;
every one of Mei's 46 equation numbers has exactly one target in the chapters, and the
page "The paper's equations" links each; every figure of a system has alt text and a
caption, and its drawing script reproduces it."""

from __future__ import annotations

import json
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from whittaker_teach.labels import PAPER_NUMBERS

ROOT = Path(__file__).resolve().parents[2]
BOOK = ROOT / "book"
CHAPTERS = sorted(p for p in BOOK.glob("[0-9][0-9]-*.ipynb") if p.name[:2] != "01")
LEVELS = ("Warm-up", "Standard", "Challenge")


def _markdown(path: Path) -> str:
    if path.suffix == ".md":
        return path.read_text(encoding="utf-8")
    nb = json.loads(path.read_text(encoding="utf-8"))
    return "\n\n".join("".join(c["source"]) for c in nb["cells"] if c["cell_type"] == "markdown")


def _pages():
    return sorted(BOOK.glob("*.ipynb")) + sorted(BOOK.glob("*.md"))


def test_there_are_chapters():
    assert len(CHAPTERS) >= 7, [p.name for p in CHAPTERS]


@pytest.mark.parametrize("chapter", CHAPTERS, ids=lambda p: p.stem)
def test_chapter_opens_with_an_overview_and_ends_with_a_summary(chapter):
    heads = re.findall(r"(?m)^(#{1,3}) (.+)$", _markdown(chapter))
    names = [h[1].strip() for h in heads if h[0] == "##"]
    assert names and names[0] == "Overview", f"{chapter.name}: first section is {names[:1]}"
    assert "Summary" in names, f"{chapter.name} has no '## Summary'"
    if "Exercises" in names:
        assert names.index("Summary") < names.index("Exercises")


@pytest.mark.parametrize("chapter", CHAPTERS, ids=lambda p: p.stem)
def test_every_exercise_names_its_level(chapter):
    titles = re.findall(r"(?m)^:{3,}\{exercise\}\s*(.*)$|^`{3,}\{exercise\}\s*(.*)$",
                        _markdown(chapter))
    titles = [a or b for a, b in titles]
    assert titles, f"{chapter.name} has no exercises"
    for t in titles:
        assert t.strip().startswith(LEVELS), f"{chapter.name}: exercise '{t}' names no level"


def _targets():
    found = {}
    for page in _pages():
        for label in re.findall(r"(?m)^\((eq-\d-\d+)\)=\s*$", _markdown(page)):
            found.setdefault(label, []).append(page.name)
    return found


def test_each_paper_number_has_exactly_one_target():
    found = _targets()
    want = {"eq-" + n.replace(".", "-") for n in PAPER_NUMBERS}
    missing = sorted(want - set(found))
    twice = {k: v for k, v in found.items() if len(v) > 1}
    assert not missing, f"no target for {missing}"
    assert not twice, f"targets placed twice: {twice}"


def test_the_paper_equations_page_links_all_46_in_order():
    page = BOOK / "paper-equations.md"
    assert page.is_file()
    refs = re.findall(r"\{ref\}`\((\d\.\d+)\) <(eq-\d-\d+)>`", page.read_text(encoding="utf-8"))
    assert [n for n, _ in refs] == list(PAPER_NUMBERS)
    assert all(t == "eq-" + n.replace(".", "-") for n, t in refs)


def _figures():
    for page in _pages():
        text = _markdown(page)
        for m in re.finditer(r"(?ms)^(`{3,}|:{3,})\{figure\}\s*(\S+)\s*\n(.*?)^\1\s*$", text):
            yield page.name, m.group(2), m.group(3)


def test_every_figure_has_alt_text_and_a_caption():
    figs = list(_figures())
    assert len(figs) >= 5, figs
    for page, src, body in figs:
        opts = dict(re.findall(r"(?m)^:(\w+):\s*(.*)$", body))
        assert len(opts.get("alt", "").split()) >= 5, f"{page}: {src} has no real alt text"
        caption = re.sub(r"(?m)^:\w+:.*$", "", body).strip()
        assert caption, f"{page}: {src} has no caption"
        assert (BOOK / src).is_file(), f"{page}: {src} does not exist"


def test_every_plot_drawn_by_a_cell_has_alt_text():
    """A code cell whose stored output is an image carries its alt text in the cell's
    metadata (``mystnb: image: alt:``), so the page's <img> has one: found at the source,
    before the browser test of the built page."""
    missing = []
    for nb_path in sorted(BOOK.glob("*.ipynb")):
        for i, cell in enumerate(json.loads(nb_path.read_text(encoding="utf-8"))["cells"]):
            images = [o for o in cell.get("outputs", [])
                      if {"image/svg+xml", "image/png"} & set(o.get("data", {}))]
            alt = cell.get("metadata", {}).get("mystnb", {}).get("image", {}).get("alt", "")
            if images and len(alt.split()) < 5:
                missing.append(f"{nb_path.name} cell {i}")
    assert not missing, missing


SCRIPTS = sorted((BOOK / "figures" / "systems").glob("[!_]*.py"))   # _draw.py is shared


@pytest.mark.parametrize("script", SCRIPTS, ids=lambda p: p.stem)
def test_figure_script_reproduces_its_svg(script, tmp_path):
    """Each drawing script writes <name>.svg next to itself: run a copy elsewhere and
    compare (the stored SVG is what the script draws now, byte for byte)."""
    copy = tmp_path / script.name
    shutil.copy(script, copy)
    shutil.copy(script.parent / "_draw.py", tmp_path / "_draw.py")   # the shared helpers
    subprocess.run([sys.executable, str(copy)], check=True, cwd=tmp_path, capture_output=True,
                   env={"PATH": "/usr/bin:/bin", "MPLBACKEND": "svg", "PYTHONHASHSEED": "0",
                        "HOME": str(tmp_path)})
    made = sorted(p.name for p in tmp_path.glob("*.svg"))
    assert made, f"{script.name} wrote no SVG next to itself"
    for name in made:
        stored = script.parent / name
        assert stored.is_file(), f"{name} is not stored beside {script.name}"
        assert (tmp_path / name).read_bytes() == stored.read_bytes(), (
            f"{name} is out of date: run `python {script.relative_to(ROOT)}`")
        assert b"<dc:date>" not in stored.read_bytes()
