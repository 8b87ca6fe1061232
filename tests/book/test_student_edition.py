"""The student edition (`make student`, scripts/student_edition.py): no graded answer
anywhere in what it publishes, practice exercises unchanged (issue 37, item 1).

Needs the built edition in _build/student (skipped without it, failed with
WT_REQUIRE_STUDENT=1, as `make test` sets)."""
import json
import os
import subprocess
import zipfile
from pathlib import Path

import pytest
import sympy as sp

from whittaker_teach.exercises.answers import DATA_DIR, from_srepr, read_data

ROOT = Path(__file__).resolve().parents[2]
OUT = ROOT / "_build" / "student"
HTML = OUT / "html"
PDF = OUT / "pdf" / "whittaker-teach.pdf"
TEXT_SUFFIXES = {".html", ".htm", ".js", ".mjs", ".json", ".ipynb", ".txt", ".md", ".svg",
                 ".css", ".py", ".xml", ".csv", ".map"}
MAX_SCANNED = 8 * 2**20          # Pyodide's runtime (tens of MB of wasm/zip) holds no answers


@pytest.fixture(scope="module")
def site():
    if not (HTML / "index.html").is_file():
        if os.environ.get("WT_REQUIRE_STUDENT"):
            pytest.fail("no student edition in _build/student/html: run `make student`")
        pytest.skip("no student edition built (make student)")
    return HTML


@pytest.fixture(scope="module")
def graded(site):
    return json.loads((site / "graded.json").read_text())["graded"]


def answer_forms(exercise_id):
    """Every printed form of every expected answer of an exercise: srepr, str, LaTeX
    (and a float's repr); a choice's answer key and its message."""
    data = read_data(DATA_DIR / f"{exercise_id}.json")
    out = set()
    for p in data["parts"]:
        if p.get("expected"):
            e = from_srepr(p["expected"])
            out |= {p["expected"], str(e), sp.sstr(e), sp.latex(e)}
            if e.is_Float:
                out.add(repr(float(e)))
        if p.get("success"):
            out.add(p["success"])
        for _, message in (p.get("choices") or {}).values():
            if message:
                out.add(message)
    return {f for f in out if len(f) >= 6}


def published_texts(site):
    """{name: text} of every published file: text files, the members of every wheel
    of whittaker_teach, and the PDF's text."""
    texts = {}
    for p in site.rglob("*"):
        if not p.is_file():
            continue
        name = str(p.relative_to(site))
        if p.suffix == ".whl" and p.name.startswith("whittaker_teach"):
            with zipfile.ZipFile(p) as z:
                for m in z.namelist():
                    texts[f"{name}!{m}"] = z.read(m).decode("utf-8", "replace")
        elif p.suffix in TEXT_SUFFIXES and p.stat().st_size <= MAX_SCANNED:
            texts[name] = p.read_text(encoding="utf-8", errors="replace")
    if PDF.is_file():
        texts["pdf"] = subprocess.run(["pdftotext", "-layout", str(PDF), "-"],
                                      capture_output=True, text=True, check=True).stdout
    return texts


def test_no_graded_answer_is_published_anywhere(site, graded):
    texts = published_texts(site)
    assert any(k.endswith(".whl!whittaker_teach/exercises/data/nielsen-form.json")
               or "exercises/data/" in k for k in texts), "the lite wheel was not scanned"
    leaks = []
    for ex in graded:
        for form in answer_forms(ex):
            for name, text in texts.items():
                if form in text:
                    leaks.append((ex, form[:60], name))
    assert not leaks, leaks[:10]


def test_the_scan_finds_answers_where_they_are(site, graded):
    """The same search finds every graded exercise's answers in the instructor's
    data (so an empty result above is not a search that cannot find anything)."""
    for ex in graded:
        text = (DATA_DIR / f"{ex}.json").read_text(encoding="utf-8")
        assert sum(form in text for form in answer_forms(ex)) >= 1, ex


def test_graded_exercises_are_statements_only(site, graded):
    assert graded
    for ex in graded:
        assert not (site / "exercises" / "solutions" / f"{ex}.html").exists()
        assert (site / "exercises" / f"{ex}.html").is_file()
        assert (site / "lite" / "files" / "exercises" / f"{ex}.ipynb").is_file()
    (whl,) = (site / "lite").rglob("whittaker_teach-*.whl")
    with zipfile.ZipFile(whl) as z:
        for ex in graded:
            data = json.loads(z.read(f"whittaker_teach/exercises/data/{ex}.json"))
            assert data["withheld"] is True
            assert all(set(p) <= {"name", "what", "points", "why_not", "choices"}
                       for p in data["parts"])
        practice = json.loads(z.read("whittaker_teach/exercises/data/sledge-L-star.json"))
        assert "withheld" not in practice and all(p.get("expected") for p in practice["parts"])


def test_practice_exercises_keep_their_solution_pages(site, graded):
    solutions = {p.stem for p in (site / "exercises" / "solutions").glob("*.html")}
    every = {p.stem for p in DATA_DIR.glob("*.json")}
    assert solutions == every - set(graded)


def test_no_link_points_at_a_withheld_solution(site, graded):
    for p in site.rglob("*.html"):
        text = p.read_text(encoding="utf-8", errors="replace")
        for ex in graded:
            assert f"solutions/{ex}" not in text, (p, ex)
