"""The answer data: read back safely, found where the book, the repository and the
in-browser site keep it (issue 25)."""
import importlib.util
from pathlib import Path

import pytest
import sympy as sp

from whittaker_teach.exercises import answers_dirs, answers_path, exercises
from whittaker_teach.exercises.answers import from_srepr, read_data
from whittaker_teach.exercises.authoring import SpecError, read_spec

ROOT = Path(__file__).resolve().parents[2]


@pytest.mark.parametrize("text", [
    "__import__('os').system('echo hacked')", "Symbol('x').__class__", "eval('1')",
    "Function('f')(Symbol('x'))", "Symbol('x', evaluate=False)", "Integer(10**100)",
    "Float(1.5)", "lambda: 1", "Add(*[Symbol('x')])", "[Symbol('x')]",
    "Symbol(Symbol('x'))", "Integer(" + "1" * 70 + ")",
])
def test_the_reader_builds_only_sympy_arithmetic(text):
    with pytest.raises((ValueError, SyntaxError)):
        from_srepr(text)


def test_every_stored_answer_reads_back_to_what_srepr_printed():
    for ex in exercises():
        data = read_data(answers_path(ex))
        for p in data["parts"]:
            if p.get("expected"):
                e = from_srepr(p["expected"])
                assert sp.srepr(e) == p["expected"], (ex, p["name"])


def test_data_is_package_data_found_only_in_the_package_or_the_named_folder(tmp_path,
                                                                            monkeypatch):
    import whittaker_teach
    pkg = Path(whittaker_teach.__file__).parent
    for ex in exercises():
        assert answers_path(ex).parent == pkg / "exercises" / "data"
    # a file planted in the current folder (or its parent) is never read
    for d in (tmp_path / "answers", tmp_path / "work" / "answers"):
        d.mkdir(parents=True, exist_ok=True)
        (d / "sledge-L-star.json").write_text("{}", encoding="utf-8")
    (tmp_path / "work" / "sledge-L-star.json").write_text("{}", encoding="utf-8")
    monkeypatch.chdir(tmp_path / "work")
    monkeypatch.delenv("WHITTAKER_TEACH_ANSWERS", raising=False)
    assert answers_dirs() == [pkg / "exercises" / "data"]
    assert answers_path("sledge-L-star").parent == pkg / "exercises" / "data"
    # the lecturer's folder, named by the variable, is searched first
    monkeypatch.setenv("WHITTAKER_TEACH_ANSWERS", str(tmp_path / "answers"))
    assert answers_path("sledge-L-star") == tmp_path / "answers" / "sledge-L-star.json"


def test_pyproject_declares_the_data_as_package_data():
    text = (ROOT / "pyproject.toml").read_text(encoding="utf-8")
    assert '"whittaker_teach.exercises" = ["data/*.json"]' in text


def test_the_spec_cell_is_read_not_run():
    with pytest.raises(SpecError, match="only literals"):
        read_spec("EXERCISE = {'title': __import__('os').getcwd(), 'symbols': '', 'parts': {}}")
    with pytest.raises(SpecError, match="one assignment"):
        read_spec("import os\nEXERCISE = {}")
    with pytest.raises(SpecError, match="points"):
        read_spec("EXERCISE = {'title': 't', 'symbols': 'x', "
                  "'parts': {'a': {'what': 'w', 'points': -1}}}")
    with pytest.raises(SpecError, match="not in 'symbols'"):
        read_spec("EXERCISE = {'title': 't', 'symbols': 'x', 'domain': {'y': 'unit'}, "
                  "'parts': {'a': {'what': 'w'}}}")


def test_the_in_browser_site_ships_no_loose_answer_files(tmp_path):
    """The lite site's wheel carries the data (tests/integration/test_wheel.py); no
    copy lies beside the notebooks, where a student edition could not withhold it."""
    spec = importlib.util.spec_from_file_location("build_lite", ROOT / "scripts" / "build_lite.py")
    build_lite = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(build_lite)
    files = tmp_path / "files"
    build_lite.write_notebooks(files)
    for ex in exercises():
        assert (files / "exercises" / f"{ex}.ipynb").exists()
    assert not list(files.rglob("*.json"))


def test_withheld_data_reads_answers_back_without_a_verdict(tmp_path, monkeypatch):
    """The student edition of a graded exercise: the statement only; check() echoes the
    answer as read and gives no verdict, for a right and a wrong answer alike."""
    import json as _json
    from whittaker_teach.exercises.answers import withheld
    full = read_data(answers_path("kepler-orbit"))
    data = withheld(full)
    text = _json.dumps(data)
    for p in full["parts"]:
        assert p["expected"] not in text and p["success"] not in text
    (tmp_path / "kepler-orbit.json").write_text(text, encoding="utf-8")
    monkeypatch.setenv("WHITTAKER_TEACH_ANSWERS", str(tmp_path))
    from whittaker_teach.exercises import check
    right = "sqrt(m)*sqrt(2*h + 2*m*mu/r)*sqrt(r^2 + rprime^2)"
    for answer in (right, "sqrt(m)*sqrt(2*h)*sqrt(r^2 + rprime^2)"):
        f = check("kepler-orbit", answer, part="L_star")
        assert not f.ok and f.status == "graded", f.message
        assert f.message.startswith("Read as ") and "sqrt(m)" in f.message and "graded" in f.message
    assert check("kepler-orbit", None, part="h").status == "unanswered"
    assert check("kepler-orbit", "2 3", part="h").status == "invalid"


def test_a_wrong_entry_equal_to_the_answer_is_refused():
    """Review C, gap 7: a ``wrong`` entry that equals the right answer on the domain
    would tell a student with the right answer that it is wrong; the build refuses it
    (for an expression and for a number), and accepts a really wrong one."""
    from whittaker_teach.exercises.authoring import make_data

    def spec(wrong, answer_kind="expr"):
        part = {"what": "w", "points": 1, "wrong": [[wrong, "a hint"]]}
        return {"title": "t", "symbols": "x+ a+", "parts": {"p": part}}

    rec = [{"exercise": "demo", "part": "p", "text": "x*(a + 1)"}]
    with pytest.raises(SpecError, match="equals the right answer"):
        make_data("demo", spec("a*x + x"), rec)
    assert make_data("demo", spec("a*x"), rec)["parts"][0]["wrong"]
    num = [{"exercise": "demo", "part": "p", "text": "950"}]
    with pytest.raises(SpecError, match="equals the right answer"):
        make_data("demo", spec("950.0000000001"), num)
    assert make_data("demo", spec("1157"), num)["parts"][0]["wrong"]
