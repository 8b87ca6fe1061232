"""The table of the course's named equations (book/paper-equations.md) says what the
library's steps say: each form's row gives the label and the title of the step the
library prints under it (a title changed in the library, or a row edited by hand,
fails here), and every link target exists in a chapter."""
import json
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
PAGE = ROOT / "book" / "paper-equations.md"
ROW = re.compile(r"^\| \{ref\}`[^<`]+<(?P<target>[\w-]+)>` \| \[(?P<label>\w+)\] \| (?P<text>.*) \|$")


def _section():
    text = PAGE.read_text(encoding="utf-8")
    return text[text.index("(course-named-equations)="):]


def _form_rows():
    return [m.groupdict() for m in map(ROW.match, _section().splitlines()) if m]


def _steps():
    from whittaker_teach.forms import (BoltzmannHamel, GibbsAppell, Kane, Maggi, Nielsen,
                                       RouthVoss, Tzenoff, Voronets, examples)
    sleigh = examples.sleigh()
    out = {}
    for form in (RouthVoss, Voronets, Maggi, BoltzmannHamel, GibbsAppell, Kane, Nielsen,
                 Tzenoff):
        for step in form(sleigh).steps:
            out[step.label] = step.title
    return out


def test_every_form_row_is_the_librarys_step():
    rows = _form_rows()
    assert {r["label"] for r in rows} >= {"RV", "Vor", "Mag", "BH", "GA", "Kane", "Ni", "Tz"}
    steps = _steps()
    for r in rows:
        title = steps[r["label"]]
        assert r["text"] == title[0].upper() + title[1:], r["label"]


@pytest.mark.parametrize("target", sorted(set(re.findall(r"<(course-[\w-]+)>", _section()))))
def test_every_link_target_is_in_a_chapter(target):
    found = []
    for nb in (ROOT / "book").glob("*.ipynb"):
        cells = json.loads(nb.read_text(encoding="utf-8"))["cells"]
        if any(f"({target})=" in "".join(c["source"]) for c in cells if c["cell_type"] == "markdown"):
            found.append(nb.name)
    assert len(found) == 1, (target, found)
