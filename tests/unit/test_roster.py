"""Which student handed in which notebook (whittaker_teach.grading.roster), and `grade` on
layouts where the identities are hostile: names that contain a classmate's number, two
uploads of one student, a notebook of another exercise, Moodle's folders, nothing found,
file names that are not UTF-8.

The file-name formats are the LMSs' own, as their code writes them: Canvas,
``lib/content_zipper.rb`` (``get_filename``: ``<sortable name>[_LATE]_<user id>``, then
``_<file id>_<file name>``; the name lower-cased, ``_<digits>_`` collapsed, anything but
letters, digits and ``_`` dropped); Moodle, ``mod/assign/classes/local/downloader.php``
(``<full name with _ as spaces>_<unique id>_assignsubmission_file_<file>``, or in folders
``<...>_assignsubmission_file/<file>``).
"""
import argparse
import csv
import os
from pathlib import Path

import nbformat
import pytest

from whittaker_teach.grading import roster as rs
from whittaker_teach.grading import run

FIXTURES = Path(__file__).resolve().parents[1] / "fixtures" / "lms"

ROSTER = rs.Roster.from_rows([("111111", "Vic Tim"), ("222222", "Eve_111111"),
                              ("12345", "Smith, John"), ("777", "Jane Doe"),
                              ("123456", "Zoë Ça"), ("s1234", "Plain Student")])


def _who(*parts):
    m = rs.identify(parts, ROSTER)
    return m.status, (m.student.id if m.student else None), m.rule


# ---------------------------------------------------------------- file names
def test_canvas_names():
    assert _who("smithjohn_12345_67890_kepler.ipynb") == ("matched", "12345",
                                                          "Canvas file name")
    assert _who("smithjohn_LATE_12345_67890_kepler.ipynb")[:2] == ("matched", "12345")
    assert _who("doejane_777_1_my_file_name_2.ipynb")[:2] == ("matched", "777")
    # the name must be the roster's: the id alone is not enough
    assert _who("doejane_12345_67890_kepler.ipynb")[:2] == ("unknown", None)
    assert _who("nobody_999_1_x.ipynb")[:2] == ("unknown", None)
    assert _who("anon_x7Yq2_123_kepler.ipynb")[:2] == ("unknown", None)


def test_a_name_that_contains_a_classmates_number_is_never_read_as_the_classmate():
    # Canvas: display name "Eve_111111" -> "eve_111111", then Eve's own id 222222
    assert _who("eve_111111_222222_555_kepler.ipynb")[:2] == ("matched", "222222")
    # the student's own file name imitating a classmate's prefix changes nothing
    assert _who("eve_111111_222222_555_victim_111111_9_x.ipynb")[:2] == ("matched", "222222")
    # Moodle: "Eve_111111" is written "Eve 111111"
    assert _who("Eve 111111_222222_assignsubmission_file_kepler.ipynb")[:2] == \
        ("matched", "222222")
    # a file name of the student's own after Moodle's prefix names no one else
    assert _who("Eve 111111_222222_assignsubmission_file_Vic Tim_111111_"
                "assignsubmission_file_x.ipynb")[:2] == ("matched", "222222")


def test_moodle_names_and_folders():
    assert _who("Jane Doe_777_assignsubmission_file_kepler.ipynb") == \
        ("matched", "777", "Moodle file name")
    assert _who("Participant_777_assignsubmission_file_kepler.ipynb")[:2] == \
        ("matched", "777")                                  # blind marking: no name
    assert _who("Jane Doe_777_assignsubmission_file", "kepler.ipynb") == \
        ("matched", "777", "Moodle folder")
    assert _who("Jane Doe_777_assignsubmission_file", "sub", "k.ipynb")[:2] == \
        ("matched", "777")
    # inside a Moodle folder the folder decides: the file name is the student's own
    assert _who("Jane Doe_777_assignsubmission_file",
                "Vic Tim_111111_assignsubmission_file_x.ipynb")[:2] == ("matched", "777")
    assert _who("Jane Doe_777_assignsubmission_file", "111111.ipynb")[:2] == \
        ("matched", "777")
    assert _who("Vic Tim_777_assignsubmission_file", "k.ipynb")[:2] == ("unknown", None)
    assert _who("some wrapper", "Jane Doe_777_assignsubmission_file", "k.ipynb")[:2] == \
        ("matched", "777")


def test_plain_ids_and_names_in_any_order():
    assert _who("s1234.ipynb") == ("matched", "s1234", "file = roster id")
    assert _who("s1234", "anything.ipynb") == ("matched", "s1234", "folder = roster id")
    assert _who("johnsmith_12345_1_x.ipynb")[:2] == ("matched", "12345")
    assert _who("kepler.ipynb")[:2] == ("unknown", None)


def test_file_names_that_are_not_utf8():
    # Zoë Ça's name as CP437 bytes (a zip without the UTF-8 flag), and as Latin-1
    for enc in ("cp437", "latin-1"):
        raw = "Zoë Ça".encode(enc) + b"_123456_assignsubmission_file_k.ipynb"
        name = os.fsdecode(raw)
        status, sid, _ = _who(name)
        assert (status, sid) == ("matched", "123456"), enc
        assert rs.shown(name).encode("utf-8")          # always writable
    raw = b"\xff\xfe_999_assignsubmission_file_k.ipynb"
    assert _who(os.fsdecode(raw))[:2] == ("unknown", None)


def test_two_uploads_of_one_student_are_duplicates(tmp_path):
    for name in ("Jane Doe_777_assignsubmission_file_a.ipynb",
                 "Jane Doe_777_assignsubmission_file_b.ipynb",
                 "Vic Tim_111111_assignsubmission_file_k.ipynb",
                 "Vic Tim_111111_assignsubmission_file_notes.pdf"):
        (tmp_path / name).write_text("{}", encoding="utf-8")
    notebooks, skipped = rs.assign([tmp_path], ROSTER)
    status = {m.name: m.status for m in notebooks}
    assert status == {"Jane Doe_777_assignsubmission_file_a.ipynb": "duplicate",
                      "Jane Doe_777_assignsubmission_file_b.ipynb": "duplicate",
                      "Vic Tim_111111_assignsubmission_file_k.ipynb": "matched"}
    assert [m.status for m in skipped] == ["ignored"]          # the pdf


def test_symlinks_are_not_followed(tmp_path):
    sub = tmp_path / "subs"
    sub.mkdir()
    (tmp_path / "secret").mkdir()
    (tmp_path / "secret" / "s1234.ipynb").write_text("{}", encoding="utf-8")
    os.symlink(tmp_path / "secret", sub / "s1234")
    notebooks, skipped = rs.assign([sub], ROSTER)
    assert notebooks == [] and skipped[0].reason.startswith("a symbolic link")


def test_rosters_from_canvas_moodle_and_plain_csv(tmp_path):
    canvas = rs.Roster.read(FIXTURES / "canvas-gradebook.csv")
    assert canvas.kind == "canvas" and canvas.students["12345"].name == "Smith, John"
    assert "" not in canvas.students and len(canvas.students) == 5   # no Points Possible
    moodle = rs.Roster.read(FIXTURES / "moodle-worksheet.csv")
    assert moodle.kind == "moodle" and moodle.students["222222"].name == "Eve 111111"
    plain = tmp_path / "r.csv"
    plain.write_text("id,name\ns1,Ann\ns2,Bob\n", encoding="utf-8")
    assert rs.Roster.read(plain).students["s2"].name == "Bob"
    plain.write_text("id,name\ns1,Ann\ns1,Bob\n", encoding="utf-8")
    with pytest.raises(rs.RosterError, match="twice"):
        rs.Roster.read(plain)
    plain.write_text("a,b\n1,2\n", encoding="utf-8")
    with pytest.raises(rs.RosterError, match="not a roster"):
        rs.Roster.read(plain)


# ---------------------------------------------------------------- another exercise
def _nb(path, exercise, meta=True):
    nb = nbformat.v4.new_notebook()
    if meta:
        nb.metadata["whittaker_teach"] = {"exercise": exercise}
    nb.cells = [nbformat.v4.new_code_cell("from whittaker_teach.exercises import check"),
                nbformat.v4.new_code_cell(f"check({exercise!r}, None, part='x')")]
    nbformat.write(nb, path)


def test_a_notebook_of_another_exercise_is_refused(tmp_path):
    _nb(tmp_path / "other.ipynb", "identity-1-19")
    _nb(tmp_path / "bare.ipynb", "identity-1-19", meta=False)
    _nb(tmp_path / "mine.ipynb", "kepler-orbit")
    for name in ("other.ipynb", "bare.ipynb"):
        _, ex, raw, rows = run.prepare(tmp_path / name, name, "kepler-orbit")
        assert ex is None and rows[0].message.startswith(run.OTHER_EXERCISE)
        assert "'identity-1-19'" in rows[0].message and rows[0].exercise == "kepler-orbit"
    _, ex, raw, rows = run.prepare(tmp_path / "mine.ipynb", "mine.ipynb", "kepler-orbit")
    assert ex == "kepler-orbit" and rows is None


# ---------------------------------------------------------------- the command
def _args(tmp_path, subs, **kw):
    base = dict(submissions=[str(s) for s in subs], out=str(tmp_path / "g.csv"),
                feedback=None, jobs=1, cell_timeout=5, timeout=5, memory=500, quiet=True,
                unsafe=True, gradebook=None)
    base.update(kw)
    return argparse.Namespace(**base)


def test_nothing_found_exits_non_zero(tmp_path, capsys):
    folder = tmp_path / "subs"
    (folder / "Jane Doe_777_assignsubmission_file").mkdir(parents=True)
    (folder / "Jane Doe_777_assignsubmission_file" / "onlinetext.html").write_text("x")
    roster = tmp_path / "roster.csv"
    roster.write_text("id,name\n777,Jane Doe\n", encoding="utf-8")
    # the Moodle folders layout, globbed as if the notebooks lay at the top
    pattern = str(folder / "*.ipynb")
    assert run.main(_args(tmp_path, [pattern])) == 2
    err = capsys.readouterr().err
    assert "found no notebook" in err and "not found" in err and "assignsubmission_file/" in err
    assert run.main(_args(tmp_path, [folder], exercise="kepler-orbit",
                          roster=str(roster))) == 2
    assert "found no notebook" in capsys.readouterr().err
    assert run.main(_args(tmp_path, [folder], roster=str(roster))) == 2
    assert "need --exercise" in capsys.readouterr().err


def test_identity_report_and_exit_status(tmp_path, monkeypatch, capsys):
    """Graded under one student, or listed and graded under no one (no notebook runs here:
    grade() is replaced by one that gives every part of a notebook 1 point)."""
    folder = tmp_path / "subs"
    folder.mkdir()
    for name in ("Jane Doe_777_assignsubmission_file_a.ipynb",
                 "Jane Doe_777_assignsubmission_file_b.ipynb",
                 "Vic Tim_111111_assignsubmission_file_k.ipynb",
                 "Eve 111111_222222_assignsubmission_file_k.ipynb",
                 "Nobody_424242_assignsubmission_file_k.ipynb"):
        (folder / name).write_text("{}", encoding="utf-8")
    raw = "Zoë Ça".encode("cp437") + b"_123456_assignsubmission_file_k.ipynb"
    with open(os.path.join(os.fsencode(folder), raw), "wb") as f:     # not UTF-8
        f.write(b"{}")
    roster = tmp_path / "roster.csv"
    roster.write_text("id,name\n777,Jane Doe\n111111,Vic Tim\n222222,Eve_111111\n"
                      "123456,Zoë Ça\n555,Absent Student\n", encoding="utf-8")
    graded = []

    def fake(paths, out, names=None, assignment=None, per_submission=None, **kw):
        graded.extend(names)
        per = [[run.Row(n, assignment, "x", True, "right", 1, 1)] for n in names]
        per_submission.extend(per)
        return [r for p in per for r in p], run.summary([r for p in per for r in p],
                                                        len(names))
    monkeypatch.setattr(run, "grade", fake)
    code = run.main(_args(tmp_path, [folder], exercise="kepler-orbit", roster=str(roster)))
    assert code == 1                                   # the report lists problems
    assert sorted(graded) == sorted([
        "Vic Tim_111111_assignsubmission_file_k.ipynb",
        "Eve 111111_222222_assignsubmission_file_k.ipynb",
        rs.shown(os.fsdecode(raw))])
    report = list(csv.DictReader(open(tmp_path / "g-identities.csv", encoding="utf-8")))
    by = {}
    for r in report:
        by.setdefault(r["status"], []).append(r)
    assert sorted(r["student_id"] for r in by["graded"]) == ["111111", "123456", "222222"]
    assert len(by["duplicate"]) == 2 and {r["student_id"] for r in by["duplicate"]} == {"777"}
    assert [r["submission"] for r in by["unknown"]] == [
        "Nobody_424242_assignsubmission_file_k.ipynb"]
    assert [r["student_id"] for r in by["no-submission"]] == ["555"]
    err = capsys.readouterr().err
    assert "duplicate" in err and "unknown" in err
