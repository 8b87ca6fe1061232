"""The grades written into the lecturer's own Canvas gradebook and Moodle grading worksheet
(whittaker_teach.grading.exports), checked against hand-written samples of each platform's
documented format (tests/fixtures/lms/README.md says which documentation) and against each
importer's rules as its own code states them, re-stated here in Python:

- Canvas, ``app/models/gradebook_importer.rb`` (``process_header``): row 0 is the header,
  ``Student`` then ``ID`` then ``Section`` or ``SIS User ID, SIS Login ID, Section``; the
  trailing read-only score columns are dropped; each remaining column is an assignment by
  ``Assignment.title_and_id`` (``Title (id)``), a column without a known id creating a new
  assignment; a row beginning ``Points Possible`` is the points row; a student is found by ID.
- Moodle, ``mod/assign/feedback/offline/importgradeslib.php`` (``init``, ``next``) and
  ``locallib.php`` (``process_import_grades``): the columns ``Identifier``, ``Grade`` and
  ``Last modified (grade)`` must exist (else the whole file is refused); the participant is
  ``Identifier`` without ``Participant ``; a row is skipped when its grade is unchanged,
  empty or negative, above the assignment's maximum, or when the grade in Moodle was
  modified more than 60 s after ``strtotime(Last modified (grade))``; feedback columns are
  matched by the feedback plugin's name (``Feedback comments``) and set when they differ.

Nothing here ran against a real Canvas or Moodle.
"""
import csv
import io
import re
import shutil
from datetime import datetime
from pathlib import Path

import pytest

from whittaker_teach.grading import exports
from whittaker_teach.grading.rows import Row

FIXTURES = Path(__file__).resolve().parents[1] / "fixtures" / "lms"
CANVAS_ASSIGNMENTS = {4321: ("Kepler orbit", 10.0), 4400: ("Essay 1", 20.0)}


# ---------------------------------------------------------------- the importers, restated
def canvas_import(text, known=CANVAS_ASSIGNMENTS):
    """{assignment id: {user id: score}} as Canvas's importer reads ``text``; raises where it
    would refuse, and on a column it would make a new assignment of."""
    rows = list(csv.reader(io.StringIO(text.lstrip("\ufeff"))))
    header = rows[0]
    if len(header) < 3 or not re.search("Student", header[0]) or not re.search("ID",
                                                                               header[1]):
        raise ValueError("Couldn't find header row")
    student_columns = 3
    if not re.search("Section", header[2]):
        if not (re.search("Section", header[4]) and re.search(r"SIS\s+User\s+ID", header[2])
                and re.search(r"SIS\s+Login\s+ID", header[3])):
            raise ValueError("Couldn't find header row")
        student_columns += 2
    cols = header[student_columns:]
    while cols and re.search("Current Score|Current Points|Final Score|Final Points|"
                             "Final Grade|Unposted", cols[-1]):
        cols.pop()
    ids = []
    for name_and_id in cols:
        m = re.match(r"\A(.*)\s\((\d+)\)\Z", name_and_id, re.S)
        if not m or int(m.group(2)) not in known:
            raise ValueError(f"a new assignment would be made: {name_and_id!r}")
        ids.append(int(m.group(2)))
    out = {i: {} for i in ids}
    for row in rows[1:]:
        if re.search("Points Possible", row[0]):
            continue
        for k, aid in enumerate(ids):
            value = row[student_columns + k]
            if value != "":
                out[aid][row[1]] = float(value)
    return out


def _strtotime(text):
    try:
        return datetime.strptime(text, "%A, %d %B %Y, %I:%M %p").timestamp()
    except ValueError:
        return 0                     # PHP's strtotime("-") is false: 0 in the comparison


def moodle_import(text, db, maximum=100.0, ignoremodified=False):
    """Apply the worksheet ``text`` to ``db`` ({participant: {"grade", "timemodified",
    "feedback"}}) as Moodle's importer does; (grades updated, feedback updated)."""
    rows = list(csv.reader(io.StringIO(text.lstrip("\ufeff"))))
    columns = rows[0]
    try:
        idindex, gradeindex = columns.index("Identifier"), columns.index("Grade")
        modifiedindex = columns.index("Last modified (grade)")
    except ValueError:
        raise ValueError("invalidgradeimport") from None
    fbindex = columns.index("Feedback comments") if "Feedback comments" in columns else None
    grades = feedback = 0
    for record in rows[1:]:
        uid = record[idindex][len("Participant "):]
        if uid not in db:
            continue
        user = db[uid]
        grade = record[gradeindex].replace(",", ".")        # unformat_float
        grade = float(grade) if grade.strip() else None
        modified = _strtotime(record[modifiedindex])
        stale = user["timemodified"] is not None and user["timemodified"] > modified + 60
        if user["grade"] is not None and user["grade"] == grade:
            pass
        elif grade is None or grade < 0:
            pass
        elif not ignoremodified and stale:
            pass
        elif grade > maximum:
            pass
        else:
            user["grade"] = grade
            grades += 1
        if (ignoremodified or not stale) and fbindex is not None and fbindex:
            if record[fbindex] != (user["feedback"] or ""):
                user["feedback"] = record[fbindex]
                feedback += 1
    return grades, feedback


# ---------------------------------------------------------------- Canvas
def test_canvas_gradebook_filled_in(tmp_path):
    src = tmp_path / "gradebook.csv"
    shutil.copy(FIXTURES / "canvas-gradebook.csv", src)
    before = src.read_bytes()
    column, written, missing = exports.fill_canvas(src, tmp_path / "out.csv",
                                                   {"777": (3, 4), "222222": (4, 4),
                                                    "424242": (1, 4)}, "kepler-orbit",
                                                   "Kepler orbit")
    assert src.read_bytes() == before                          # the download is untouched
    assert column == "Kepler orbit (4321)" and sorted(written) == ["222222", "777"]
    assert missing == ["424242"]
    out = (tmp_path / "out.csv").read_bytes()
    assert out.startswith(b"\xef\xbb\xbf") and b"\r\n" in out    # BOM and CRLF kept
    old = list(csv.reader(io.StringIO(before.decode("utf-8-sig"))))
    new = list(csv.reader(io.StringIO(out.decode("utf-8-sig"))))
    assert len(new) == len(old) and new[0] == old[0] and new[1] == old[1]  # Points Possible
    changed = {(i, j) for i, (a, b) in enumerate(zip(old, new)) for j in range(len(a))
               if a[j] != b[j]}
    assert changed == {(3, 5), (5, 5)}                         # only the graded cells
    imported = canvas_import(out.decode("utf-8-sig"))
    assert imported[4321] == {"777": 7.5, "222222": 10.0}      # 3/4 and 4/4 of 10 points
    assert imported[4400]["12345"] == 15.0                     # other columns as they were


def test_canvas_column_must_be_an_existing_assignment(tmp_path):
    src = FIXTURES / "canvas-gradebook.csv"
    with pytest.raises(exports.ExportError, match="no assignment column"):
        exports.fill_canvas(src, tmp_path / "o.csv", {}, "nielsen-form", "Nielsen's form")
    with pytest.raises(exports.ExportError, match="no column"):
        exports.fill_canvas(src, tmp_path / "o.csv", {}, "x", column="Kepler (whittaker)")
    with pytest.raises(exports.ExportError, match="not an assignment column"):
        exports.fill_canvas(src, tmp_path / "o.csv", {}, "x", column="Current Points")
    col, written, _ = exports.fill_canvas(src, tmp_path / "o.csv", {"777": (1, 2)}, "x",
                                          column="Essay 1 (4400)")
    assert col == "Essay 1 (4400)" and canvas_import(
        (tmp_path / "o.csv").read_text(encoding="utf-8-sig"))[4400]["777"] == 10.0
    with pytest.raises(exports.ExportError, match="not a Canvas gradebook"):
        exports.fill_canvas(FIXTURES / "moodle-worksheet.csv", tmp_path / "o.csv", {}, "x")


def test_the_old_export_would_not_import():
    """What the issue found: a column '<exercise> (whittaker-teach)' makes a new assignment."""
    text = "Student,ID,SIS User ID,SIS Login ID,Section,kepler-orbit (whittaker-teach)\n" \
        "x,777,,,,3\n"
    with pytest.raises(ValueError, match="new assignment"):
        canvas_import(text)


# ---------------------------------------------------------------- Moodle
def _db():
    t = datetime(2024, 5, 15, 9, 0).timestamp()
    return {"123456": {"grade": None, "timemodified": None, "feedback": None},
            "111111": {"grade": 50.0, "timemodified": t, "feedback": "<p>Seen in class.</p>"},
            "222222": {"grade": None, "timemodified": None, "feedback": None},
            "333333": {"grade": None, "timemodified": None, "feedback": None}}


def test_moodle_worksheet_filled_in_and_imported(tmp_path):
    src = FIXTURES / "moodle-worksheet.csv"
    before = src.read_text(encoding="utf-8")
    grades = {"123456": (3, 4, "kepler-orbit: 2 of 3 parts right, 3 of 4 points."),
              "111111": (4, 4, "kepler-orbit: 3 of 3 parts right, 4 of 4 points."),
              "999999": (1, 4, "x")}
    written, missing = exports.fill_moodle(src, tmp_path / "w.csv", grades)
    assert sorted(written) == ["111111", "123456"] and missing == ["999999"]
    old = list(csv.reader(io.StringIO(before)))
    new = list(csv.reader(io.StringIO((tmp_path / "w.csv").read_text(encoding="utf-8"))))
    assert new[0] == old[0] and len(new) == len(old)           # every column kept
    head = new[0]
    g, fb, lm = head.index("Grade"), head.index("Feedback comments"), \
        head.index("Last modified (grade)")
    assert new[1][g] == "75.00" and new[2][g] == "100.00"       # scaled to Maximum Grade
    assert [r[lm] for r in new] == [r[lm] for r in old]        # kept as downloaded
    assert new[2][fb] == "<p>Seen in class.</p><p>kepler-orbit: 3 of 3 parts right, 4 of " \
        "4 points.</p>"                                        # appended
    assert new[3] == old[3] and new[4] == old[4]               # not graded: untouched
    db = _db()
    assert moodle_import((tmp_path / "w.csv").read_text(encoding="utf-8"), db) == (2, 2)
    assert db["123456"]["grade"] == 75.0 and db["111111"]["grade"] == 100.0
    # again, on the same worksheet: nothing more changes
    assert moodle_import((tmp_path / "w.csv").read_text(encoding="utf-8"), db) == (0, 0)


def test_moodle_keeps_its_check_against_grades_changed_since_the_download(tmp_path):
    exports.fill_moodle(FIXTURES / "moodle-worksheet.csv", tmp_path / "w.csv",
                        {"111111": (1, 4, "late")})
    db = _db()
    db["111111"]["timemodified"] = datetime(2024, 5, 16, 9, 0).timestamp()   # a TA, later
    assert moodle_import((tmp_path / "w.csv").read_text(encoding="utf-8"), db) == (0, 0)
    assert db["111111"]["grade"] == 50.0


def test_moodle_feedback_overwritten_when_asked_and_never_doubled(tmp_path):
    src = FIXTURES / "moodle-worksheet.csv"
    exports.fill_moodle(src, tmp_path / "a.csv", {"111111": (4, 4, "all right")},
                        overwrite_feedback=True)
    rows = list(csv.DictReader(open(tmp_path / "a.csv", encoding="utf-8")))
    assert rows[1]["Feedback comments"] == "<p>all right</p>"
    exports.fill_moodle(src, tmp_path / "b.csv", {"111111": (4, 4, "a <b> & c")})
    exports.fill_moodle(tmp_path / "b.csv", tmp_path / "c.csv", {"111111": (4, 4,
                                                                            "a <b> & c")})
    rows = list(csv.DictReader(open(tmp_path / "c.csv", encoding="utf-8")))
    assert rows[1]["Feedback comments"] == "<p>Seen in class.</p><p>a &lt;b&gt; &amp; c</p>"


def test_moodle_decimal_comma_integer_maximum_and_refusals(tmp_path):
    src = tmp_path / "de.csv"
    src.write_text('Identifier,"Full name",Grade,"Maximum Grade","Last modified (grade)"\n'
                   '"Teilnehmer/in 5",A,,"20,00",-\n"Participant 6",B,,10,-\n',
                   encoding="utf-8")
    exports.fill_moodle(src, tmp_path / "o.csv", {"5": (2, 3, ""), "6": (2, 3, "")})
    rows = list(csv.reader(open(tmp_path / "o.csv", encoding="utf-8")))
    assert rows[1][2] == "13,33" and rows[2][2] == "7"
    src.write_text("Identifier,Full name,Grade,Maximum Grade\nParticipant 1,A,,10\n",
                   encoding="utf-8")
    with pytest.raises(exports.ExportError, match="Last modified"):
        exports.fill_moodle(src, tmp_path / "o.csv", {})
    with pytest.raises(ValueError, match="invalidgradeimport"):    # as Moodle would
        moodle_import(src.read_text(encoding="utf-8"), {})
    src.write_text("Identifier,Full name,Grade,Scale,Last modified (grade)\n", encoding="utf-8")
    with pytest.raises(exports.ExportError, match="scale"):
        exports.fill_moodle(src, tmp_path / "o.csv", {})


def test_feedback_text_names_parts_and_points_only():
    rows = [Row("s", "kepler-orbit", "a", True, "right", 1, 1),
            Row("s", "kepler-orbit", "b", False, "the answer is 42", 0, 2)]
    text = exports.feedback_text(rows)
    assert text == "kepler-orbit: 1 of 2 parts right, 1 of 3 points (graded by " \
        "whittaker-teach)." and "42" not in text
