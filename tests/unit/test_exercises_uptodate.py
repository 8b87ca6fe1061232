"""The exercise notebooks are generated from exercises/src/<id>.py by
`make exercises` (scripts/make_exercises.py); this test fails when a stored
notebook is out of date with its source, and checks what the stored outputs
say: every student check "not answered yet", every solution check correct.
"""
import importlib.util
from pathlib import Path

import nbformat
import pytest

ROOT = Path(__file__).resolve().parents[2]
spec = importlib.util.spec_from_file_location("make_exercises",
                                              ROOT / "scripts" / "make_exercises.py")
make_exercises = importlib.util.module_from_spec(spec)
spec.loader.exec_module(make_exercises)

SOURCES = make_exercises.sources()
REQUIRED = ["projectile-path", "kepler-orbit", "omega-and-energy", "identity-1-19",
            "constraint-star", "sledge-L-star", "sledge-reduced-equation", "nielsen-form",
            "chaplygin-sleigh", "turning-point", "work-precision"]


def test_the_required_exercises_exist():
    assert set(REQUIRED) <= set(SOURCES)


@pytest.mark.parametrize("ex_id", sorted(SOURCES))
def test_generated_notebooks_are_up_to_date(ex_id, tmp_path):
    student, solution = make_exercises.build(ex_id, SOURCES[ex_id].read_text(encoding="utf-8"))
    for generated, stored_path in zip((student, solution), make_exercises.targets(ex_id)):
        assert stored_path.exists(), f"{stored_path} is missing: run `make exercises`"
        stored = nbformat.read(stored_path, as_version=4)
        assert make_exercises.cell_signature(stored) == make_exercises.cell_signature(
            generated), f"{stored_path} is out of date with its source: run `make exercises`"
        # written to a temporary folder and read back, it is the same notebook
        tmp = tmp_path / stored_path.name
        tmp.write_text(nbformat.writes(generated) + "\n", encoding="utf-8")
        assert make_exercises.cell_signature(nbformat.read(tmp, as_version=4)) == \
            make_exercises.cell_signature(stored)
        for cell in stored.cells:
            if cell.cell_type == "code" and cell.source.strip():
                assert cell.execution_count is not None, f"{stored_path}: not executed"
                assert all(o.output_type != "error" for o in cell.outputs)


def _check_outputs(nb):
    out = []
    for cell in nb.cells:
        if cell.cell_type == "code" and cell.source.lstrip().startswith("check("):
            (o,) = [o for o in cell.outputs if o.output_type == "execute_result"]
            out.append(o["data"]["text/plain"])
    return out


@pytest.mark.parametrize("ex_id", sorted(SOURCES))
def test_stored_checks_say_what_they_should(ex_id):
    student_path, solution_path = make_exercises.targets(ex_id)
    student = nbformat.read(student_path, as_version=4)
    solution = nbformat.read(solution_path, as_version=4)
    s_checks, o_checks = _check_outputs(student), _check_outputs(solution)
    assert s_checks and len(s_checks) == len(o_checks)
    assert all("not answered yet" in t for t in s_checks), s_checks
    assert all("ok=True" in t and "Correct." in t for t in o_checks), o_checks
    # the notebook states the exercise, opens with setup() and ends with a check
    code = [c for c in student.cells if c.cell_type == "code"]
    assert code[0].source.startswith("from whittaker_teach.notebook import setup; setup()")
    assert code[-1].source.lstrip().startswith("check(")
    text = "\n".join(c.source for c in student.cells if c.cell_type == "markdown")
    # the grader finds the exercise, and the student reads how to hand it in
    assert student.metadata["whittaker_teach"] == {"exercise": ex_id}
    assert "Handing in" in text and "Download" in text and ".ipynb" in text
    assert "python -m whittaker_teach grade" in text
    assert "Assumptions" in text and any(s in text for s in ("(1.", "(2.", "(3."))
    # no solution leaks into the student notebook
    student_code = "\n".join(c.source for c in code)
    assert "BEGIN SOLUTION" not in student_code and "PLACEHOLDER" not in student_code
    assert "None  # your answer here" in student_code
    # timings only in cells tagged nbval-ignore-output
    for nb in (student, solution):
        for c in nb.cells:
            if "nbval-ignore-output" in c.metadata.get("tags", []):
                assert c.cell_type == "code"


def test_every_solution_notebook_is_in_the_toc():
    yaml = pytest.importorskip("yaml")
    toc = yaml.safe_load((ROOT / "_toc.yml").read_text(encoding="utf-8"))
    part = [p for p in toc["parts"] if p.get("caption") == "Exercises"]
    assert part and part[0].get("numbered") is False
    files = [c["file"] for c in part[0]["chapters"] if c["file"] != "exercises/index"]
    listed = {f.split("/")[-1] for f in files}
    assert all(f.startswith("exercises/solutions/") for f in files)
    assert set(REQUIRED) <= listed <= set(SOURCES)


def test_parser_rejects_malformed_sources():
    bad = ["text before a marker\n# %%\nx = 1\n",
           "# %% [markdown] statement\n# s\n# %%\n### BEGIN SOLUTION\nx = 1\n",
           "# %% [markdown] statement\n# s\n# %%\n### BEGIN SOLUTION\nx = 1\n### END SOLUTION\n",
           "# %% [markdown] statement\n# s\n# %% bogus\nx = 1\n",
           "# %%\nx = 1\n"]
    for text in bad:
        with pytest.raises(make_exercises.SourceError):
            make_exercises.build("demo", text)


def test_placeholders_replace_solutions():
    src = ("# %% [markdown] statement\n# Do it.\n# %%\nimport math\n### BEGIN SOLUTION\n"
           "a = math.pi\n### END SOLUTION\n### PLACEHOLDER: a = None  # your answer here\n"
           "a\n# %% solution\nprint(a)\n# %% [markdown] solution\n# Because.\n"
           "# %%\ncheck('demo', a)\n")
    student, solution = make_exercises.build("demo", src)
    assert [c.source for c in student.cells] == [
        "Do it.", "import math\na = None  # your answer here\na", "check('demo', a)",
        make_exercises.HAND_IN.format(ex_id="demo")]
    assert student.metadata["whittaker_teach"] == {"exercise": "demo"}
    sources = [c.source for c in solution.cells]
    assert sources[0].startswith(":::{exercise}\n:label: ex-demo")
    assert sources[1].startswith("```{solution-start} ex-demo\n:class: dropdown")
    assert sources[2:5] == ["import math\na = math.pi\na", "print(a)", "Because."]
    assert sources[5].startswith("```{solution-end}")
    assert sources[6] == "check('demo', a)"


@pytest.mark.parametrize("ex_id", sorted(SOURCES))
def test_answer_data_is_up_to_date(ex_id):
    """exercises/answers/<id>.json was made from the current source (its sha256)."""
    import json
    text = SOURCES[ex_id].read_text(encoding="utf-8")
    make_exercises.spec_of(ex_id, text)
    path = make_exercises.answers_target(ex_id)
    assert path.exists(), f"{path} is missing: run `make exercises`"
    assert not make_exercises.answers_stale(ex_id, text), \
        f"{path} is out of date with its source: run `make exercises`"
    data = json.loads(path.read_text(encoding="utf-8"))
    assert data["id"] == ex_id and {p["name"] for p in data["parts"]} == \
        set(make_exercises.spec_of(ex_id, text)["parts"])


@pytest.mark.parametrize("ex_id", sorted(SOURCES))
def test_no_exercise_needs_a_private_function(ex_id):
    """A student uses only the public library: no obj._name, no `from ... import _name`."""
    import ast
    text = SOURCES[ex_id].read_text(encoding="utf-8")
    code = "\n".join(c["source"] for c in make_exercises.parse_source(text, ex_id)
                     if c["type"] == "code")
    code = "\n".join(line for line in code.splitlines() if not line.lstrip().startswith("###"))
    for node in ast.walk(ast.parse(code)):
        if isinstance(node, ast.Attribute):
            assert not (node.attr.startswith("_") and not node.attr.startswith("__")), \
                f"{ex_id}: uses .{node.attr}"
        if isinstance(node, ast.ImportFrom):
            assert not any(a.name.startswith("_") for a in node.names), ex_id
            assert not any(part.startswith("_") for part in (node.module or "").split(".")), \
                f"{ex_id}: imports from {node.module}"


def test_every_exercise_has_a_level_and_a_time_in_the_index():
    """Review C, gap 5: each exercise notebook is listed in exercises/index.md with its
    level (Warm-up, Standard or Challenge) and the time a student should plan for."""
    import re
    index = (ROOT / "exercises" / "index.md").read_text(encoding="utf-8")
    rows = dict(re.findall(r"^\| \[.*?\]\(solutions/([\w-]+)\) \| ([^|]*) \|", index, re.M))
    assert set(rows) == set(SOURCES)
    for ex_id, cell in rows.items():
        assert re.fullmatch(r"(Warm-up|Standard|Challenge), \d+ min", cell.strip()), (ex_id, cell)
