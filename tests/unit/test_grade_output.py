"""What the grader writes for a lecturer: CSV cells, feedback page names, the gradebook exports."""
import csv

from whittaker_teach.grading import exports
from whittaker_teach.grading.roster import Student
from whittaker_teach.grading.rows import Row, cell, summary
from whittaker_teach.grading.run import page_name


def test_cells_a_spreadsheet_never_reads_as_formulas():
    for text in ("=1+1", "+1", "-dash.ipynb", "@SUM(A1)", "\tx", "\rx"):
        assert cell(text) == "'" + text
    for text in ("ok", "x=1", "", "1.5", "'quoted"):
        assert cell(text) == text


def test_every_submission_gets_its_own_feedback_page():
    names = ["honest_3.ipynb", "honest~3.ipynb", "honest 3.ipynb", "Honest_3.ipynb",
             "-dash.ipynb", ".hidden.ipynb", "a/b.ipynb", "θ.ipynb", "x\ny.ipynb", "=1+1.ipynb"]
    pages = [page_name(n) for n in names]
    assert len({p.lower() for p in pages}) == len(names)
    assert page_name("honest_3.ipynb") == "honest_3.ipynb.html"
    for p in pages:
        assert p.endswith(".html") and "/" not in p and not p.startswith((".", "-"))
        assert all(c.isascii() and (c.isalnum() or c in "-_.") for c in p)


def _rows(name, oks, points=(1, 2, 1)):
    parts = ["a", "b", "c"]
    return [Row(name, "ex", p, ok, "m", pts if ok else 0, pts)
            for p, ok, pts in zip(parts, oks, points)]


def test_the_gradebook_export(tmp_path):
    per = [_rows("smithjohn_12345_67890_ex.ipynb", [True, True, False]),
           _rows("Jane Doe_777_assignsubmission_file_ex.ipynb", [True, False, False]),
           _rows("=evil.ipynb", [False, False, False])
           + [Row("=evil.ipynb", "ex", "", False, "failure", 0, 0)]]
    exports.write_gradebook(tmp_path / "g.csv", per,
                            [Student("12345", "Smith, John"), Student("777", "Jane Doe"), None])
    g = list(csv.DictReader(open(tmp_path / "g.csv", encoding="utf-8")))
    assert [r["total"] for r in g] == ["3", "1", "0"] and g[0]["max_points"] == "4"
    assert g[0]["student"] == "12345" and g[1]["student"] == "777" and g[2]["student"] == ""
    assert g[1]["name"] == "Jane Doe"
    assert g[2]["submission"] == "'=evil.ipynb" and g[0]["ex:b"] == "2"
    assert summary([r for rows in per for r in rows], 3) == \
        "3 submissions: 3 parts right, 6 parts wrong, 1 failure"


def test_recorder_writes_an_exception_class_as_its_name():
    """A choice part answered with the class itself (check(..., wt.ChartError)) is recorded
    as its name, which check() reads back with the same verdict."""
    import whittaker_teach as wt
    from whittaker_teach.exercises.recorder import _answer_text
    assert _answer_text(wt.ChartError) == "ChartError"
    assert _answer_text(ValueError) == "ValueError"
    assert _answer_text(int) is None
