"""A lecturer writes a new exercise in one file, with no edit of the package (issue 25).

In a temporary copy: sledge-L-star's source is copied to a new id and its spring
changed from k^2 theta^2/2 to k^2 (1 - cos theta); the exercise builder
(scripts/make_exercises.py) runs its solution and stores the answers; the new
exercise then accepts its own right answers, rejects the old system's, and
``grade`` gives its solution notebook full marks.
"""
import csv
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import nbformat
import pytest

import whittaker_teach
from whittaker_teach.exercises import answers_path, check, load

ROOT = Path(__file__).resolve().parents[2]
NEW = "sledge-cos-spring"


def _new_source():
    text = (ROOT / "exercises" / "src" / "sledge-L-star.py").read_text(encoding="utf-8")
    edits = [
        ("- k**2*theta**2/2)", "- k**2*(1 - sp.cos(theta)))"),                 # (3.3)
        ("U = -\\tfrac12 k^2\\theta^2", "U = -k^2(1 - \\cos\\theta)"),
        ("- \\tfrac12 k^2\\theta^2\n", "- k^2(1 - \\cos\\theta)\n"),
        ('"conditions": ["2*h - k^2*theta^2"]', '"conditions": ["h - k^2*(1 - cos(theta))"]'),
        ('"title": "The sledge\'s reduced Lagrangian"',
         '"title": "A sledge with a cosine spring"'),
    ]
    for old, new in edits:
        assert old in text, old
        text = text.replace(old, new)
    # the forms written for the hints are the old system's: a lecturer removes them
    text = re.sub(r'\n *"form": "[^"]*",', "", text)
    # the solution's comparison with the library's sledge (the old system) goes too
    text = re.sub(r"# %% \[markdown\] solution\n# The library derives.*?(?=# %%\ncheck)", "",
                  text, flags=re.S)
    return text.replace('"sledge-L-star"', f'"{NEW}"')


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("course")
    (tmp / "scripts").mkdir()
    for name in ("make_exercises.py", "execute_notebooks.py"):
        shutil.copy2(ROOT / "scripts" / name, tmp / "scripts" / name)
    (tmp / "exercises" / "src").mkdir(parents=True)
    (tmp / "exercises" / "src" / f"{NEW}.py").write_text(_new_source(), encoding="utf-8")
    proc = subprocess.run([sys.executable, str(tmp / "scripts" / "make_exercises.py")],
                          cwd=tmp, capture_output=True, text=True, timeout=600,
                          env={**os.environ, "PYTHONHASHSEED": "0"})
    assert proc.returncode == 0, proc.stdout + proc.stderr
    return tmp


@pytest.fixture
def answers(built, monkeypatch):
    monkeypatch.setenv("WHITTAKER_TEACH_ANSWERS", str(built / "exercises" / "answers"))
    return built


def test_the_builder_writes_data_not_code(built):
    data = built / "exercises" / "answers" / f"{NEW}.json"
    assert data.exists()
    for nb in (built / "exercises" / f"{NEW}.ipynb",
               built / "exercises" / "solutions" / f"{NEW}.ipynb"):
        assert nb.exists()
    # nothing was written into the package
    pkg = Path(whittaker_teach.__file__).parent
    assert not any(NEW in p.name for p in pkg.rglob("*"))
    # the builder says the copy is up to date now
    proc = subprocess.run([sys.executable, str(built / "scripts" / "make_exercises.py"),
                           "--check"], cwd=built, capture_output=True, text=True, timeout=120)
    assert proc.returncode == 0, proc.stdout


def test_without_its_data_the_exercise_does_not_exist(built):
    f = check(NEW, "1", part="L_star")
    assert not f.ok and "There is no exercise" in f.message


def test_the_new_exercise_accepts_its_right_answers(answers):
    assert answers_path(NEW).parent == answers / "exercises" / "answers"
    ex = load(NEW)
    assert ex.title == "A sledge with a cosine spring" and not ex.solvers
    assert {p: v.points for p, v in ex.parts.items()} == {"Omega": 1, "xdot": 1, "L_star": 2}
    right = {
        "Omega": ["xdot^2*(m*(1 + tan(theta)^2) + J*theta'^2)/2 - k^2*(1 - cos(theta))",
                  "ẋ²·(m·sec²θ + J·θ′²)/2 − k²·(1 − cos θ)"],
        "xdot": ["sqrt(2*h - 2*k^2*(1 - cos(theta)))/sqrt(m*sec(theta)^2 + J*theta'^2)",
                 "√(2·(h − k²·(1 − cos θ)))/√(m·sec²θ + J·θ′²)"],
        "L_star": ["sqrt(2*h - 2*k^2*(1 - cos(theta)))*sqrt(m*sec(theta)^2 + J*theta'^2)",
                   "sqrt(2*(h - k^2 + k^2*cos(theta))*(m/cos(theta)^2 + J*thetaprime^2))"],
    }
    for part, texts in right.items():
        for text in texts:
            f = check(NEW, text, part=part)
            assert f.ok, (part, text, f.message)


def test_the_new_exercise_rejects_the_old_systems_answers(answers):
    old = load("sledge-L-star")
    for part in ("Omega", "xdot", "L_star"):
        expected = old.parts[part].expected
        assert check("sledge-L-star", expected, part=part).ok
        for answer in (expected, str(expected)):
            f = check(NEW, answer, part=part)
            assert not f.ok and f.status == "wrong", (part, f.message)


# grades in the sandbox (uids 61000 + slot): in the grading tests' worker, so that their
# check for processes left running does not see this test's
@pytest.mark.xdist_group("sandbox")
def test_the_solution_notebook_checks_right_and_grade_gives_full_marks(answers, tmp_path):
    sol = answers / "exercises" / "solutions" / f"{NEW}.ipynb"
    nb = nbformat.read(sol, as_version=4)
    outs = [o["data"]["text/plain"] for c in nb.cells if c.cell_type == "code"
            and c.source.startswith("check(") for o in c.outputs
            if o.output_type == "execute_result"]
    assert len(outs) == 3 and all("Correct" in o for o in outs), outs
    from whittaker_teach.grading import run as grading
    sub = tmp_path / "submissions"
    sub.mkdir()
    shutil.copy2(sol, sub / "student.ipynb")
    out = tmp_path / "grades.csv"
    try:
        rows, line = grading.grade([str(sub / "student.ipynb")], str(out), jobs=1, quiet=True)
    except grading.SandboxUnavailable:          # the answers are what is tested here
        rows, line = grading.grade([str(sub / "student.ipynb")], str(out), jobs=1, quiet=True,
                                   unsafe=True)
    table = list(csv.DictReader(open(out, encoding="utf-8")))
    parts = {r["part"]: r for r in table if r["part"]}
    assert set(parts) == {"Omega", "xdot", "L_star"}, table
    assert all(r["ok"] == "True" for r in parts.values()), table
    assert sum(float(r["points"]) for r in parts.values()) == 4 == \
        sum(float(r["max_points"]) for r in parts.values())
    assert "1 submissions: 3 parts right, 0 parts wrong" in line or "3 parts right" in line


def test_every_existing_exercise_still_accepts_its_solution():
    from whittaker_teach.exercises import exercises
    for ex in exercises():
        for name, p in load(ex).parts.items():
            answer = p.answer_key if p.is_choice else p.expected
            assert check(ex, answer, part=name).ok, (ex, name)
