"""scripts/student_edition.py: the staged sources of the student edition (the built
edition is searched for answers by tests/book/test_student_edition.py)."""
import importlib.util
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
spec = importlib.util.spec_from_file_location("student_edition",
                                              ROOT / "scripts" / "student_edition.py")
se = importlib.util.module_from_spec(spec)
spec.loader.exec_module(se)


def test_links_to_a_graded_solution_point_at_its_statement():
    text = ("{doc}`solutions/kepler-orbit`, ../exercises/solutions/kepler-orbit.ipynb, "
            "solutions/kepler-orbit-2, solutions/sledge-L-star")
    assert se.relinked(text, ["kepler-orbit"]) == (
        "{doc}`kepler-orbit`, ../exercises/kepler-orbit.ipynb, solutions/kepler-orbit-2, "
        "solutions/sledge-L-star")


def test_the_staged_sources_hold_no_graded_solution(tmp_path):
    graded = se.graded_ids()
    assert graded, "exercises/course.yml names no graded exercise"
    se.stage(tmp_path / "src", graded)
    src = tmp_path / "src"
    assert not (src / "exercises" / "src").exists()          # the one sources hold solutions
    toc = (src / "_toc.yml").read_text()
    for ex in graded:
        assert not (src / "exercises" / "solutions" / f"{ex}.ipynb").exists()
        assert f"exercises/{ex}\n" in toc and f"solutions/{ex}" not in toc
        for p in list(src.rglob("*.md")) + list(src.rglob("*.ipynb")):
            if "build" not in p.relative_to(src).parts[:1]:
                assert f"solutions/{ex}" not in p.read_text(encoding="utf-8"), p
    assert "(student edition)" in (src / "_config.yml").read_text()
    practice = {p.stem for p in (ROOT / "exercises" / "solutions").glob("*.ipynb")}
    kept = {p.stem for p in (src / "exercises" / "solutions").glob("*.ipynb")}
    assert kept == practice - set(graded)


def test_an_unknown_graded_id_is_refused(tmp_path):
    course = tmp_path / "course.yml"
    course.write_text("graded:\n  - no-such-exercise\n")
    with pytest.raises(SystemExit, match="no-such-exercise"):
        se.graded_ids(course)
