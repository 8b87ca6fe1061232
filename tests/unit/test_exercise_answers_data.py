"""The answer data: read back safely, found where the book, the repository and the
in-browser site keep it (issue 25)."""
import importlib.util
import json
from pathlib import Path

import pytest
import sympy as sp

from whittaker_teach.exercises import answers_dirs, answers_path, exercises
from whittaker_teach.exercises.answers import from_srepr, read_data
from whittaker_teach.exercises.authoring import SpecError, exercise_from_data, read_spec
from whittaker_teach.exercises.specs import check_part

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


def test_data_lives_beside_the_sources_not_in_the_package():
    import whittaker_teach
    pkg = Path(whittaker_teach.__file__).parent
    for ex in exercises():
        path = answers_path(ex)
        assert path.parent == ROOT / "exercises" / "answers"
        assert pkg not in path.parents
    assert not list((pkg / "exercises").rglob("*.json"))


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


def test_the_in_browser_site_gets_the_data_next_to_the_exercise_notebooks(tmp_path,
                                                                          monkeypatch):
    spec = importlib.util.spec_from_file_location("build_lite", ROOT / "scripts" / "build_lite.py")
    build_lite = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(build_lite)
    files = tmp_path / "files"
    build_lite.write_notebooks(files)
    for ex in exercises():
        assert (files / "exercises" / f"{ex}.ipynb").exists()
        shipped = files / "exercises" / "answers" / f"{ex}.json"
        assert json.loads(shipped.read_text(encoding="utf-8")) == \
            json.loads(answers_path(ex).read_text(encoding="utf-8"))
    # the kernel runs in the notebook's folder: ./answers is searched
    monkeypatch.chdir(files / "exercises")
    assert Path.cwd() / "answers" in answers_dirs()
    ex = exercise_from_data(read_data(Path("answers") / "sledge-L-star.json"))
    f = check_part(ex, ex.parts["L_star"],
                   "sqrt(2*h - k^2*theta^2)*sqrt(m*sec(theta)^2 + J*theta'^2)")
    assert f.ok, f.message


def test_the_builder_stops_on_a_solution_that_does_not_fit_its_exercise_cell():
    from whittaker_teach.exercises.authoring import make_data
    spec = read_spec("EXERCISE = {'title': 't', 'symbols': 'x a+', 'parts': {"
                     "'f': {'what': 'f', 'form': 'a*x^2'}, "
                     "'c': {'what': 'c', 'choices': {'yes': [['y'], 'ok'], 'no': [[], 'no']}}}}")
    with pytest.raises(SpecError, match="never calls check"):
        make_data("t", spec, [{"exercise": "t", "part": "c", "text": "yes"}])
    with pytest.raises(SpecError, match="not one of its choices"):
        make_data("t", spec, [{"exercise": "t", "part": "f", "text": "a*x^2"},
                              {"exercise": "t", "part": "c", "text": "maybe"}])
    with pytest.raises(SpecError, match="is not equal to the solution's answer"):
        make_data("t", spec, [{"exercise": "t", "part": "f", "text": "a*x^3"},
                              {"exercise": "t", "part": "c", "text": "y"}])
    with pytest.raises(SpecError, match="not in EXERCISE\\['symbols'\\]"):
        make_data("t", spec, [{"exercise": "t", "part": "f", "text": "b*x^2"},
                              {"exercise": "t", "part": "c", "text": "y"}])
    data = make_data("t", spec, [{"exercise": "t", "part": "f", "text": "x^2*a"},
                                 {"exercise": "t", "part": "c", "text": "Y"}])
    ex = exercise_from_data(json.loads(json.dumps(data)))
    assert check_part(ex, ex.parts["f"], "a*x*x").ok and not check_part(ex, ex.parts["f"], "x^2").ok
    assert check_part(ex, ex.parts["c"], "yes").ok and not check_part(ex, ex.parts["c"], "no").ok
    assert ex.parts["f"].variables == (sp.Symbol("a", positive=True), sp.Symbol("x"))
