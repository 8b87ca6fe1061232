"""The gradebook of a graded class: points per submission, and exports a course platform imports.

From the rows of :func:`.grade.grade` (one list per submission):

- :func:`write_gradebook` (``--gradebook FILE``): one row per submission,
  ``student,submission,exercise,<exercise>:<part>...,total,max_points``;
- :func:`write_canvas` (``--canvas FILE``): Canvas's gradebook import,
  ``Student,ID,SIS User ID,SIS Login ID,Section,<assignment>``; ``ID`` is the
  Canvas user id that Canvas's "Download Submissions" puts in each file name
  (``name_12345_67890_file.ipynb``, ``name_LATE_12345_...``), the assignment
  column is named ``<exercise> (whittaker-teach)`` and holds the total;
- :func:`write_moodle` (``--moodle FILE``): Moodle's assignment "offline
  grading worksheet" (Assignment, *Upload grading worksheet*),
  ``Identifier,Full name,Grade,Maximum Grade,Feedback comments``;
  ``Identifier`` is ``Participant N`` with the participant number Moodle's
  "Download all submissions" puts in each file name
  (``Full Name_123456_assignsubmission_file_...``).

Where a file name carries no such number, the student column holds the
file's name without ``.ipynb`` (to be matched by hand).  Every cell goes
through :func:`.grade.cell` (no formula injection).

>>> canvas_id("smithjohn_12345_67890_sledge.ipynb"), canvas_id("smithjohn_LATE_12_34_a.ipynb")
('12345', '12')
>>> moodle_participant("John Smith_123456_assignsubmission_file_sledge.ipynb")
'123456'
"""

from __future__ import annotations

import csv
import re

__all__ = ["write_exports", "write_gradebook", "write_canvas", "write_moodle", "canvas_id",
           "moodle_participant", "totals"]


def canvas_id(name):
    """The Canvas user id in a file name from Canvas's "Download Submissions", or None."""
    m = re.match(r"^[^_/]+_(?:LATE_)?(\d+)_\d+_", name.rsplit("/", 1)[-1])
    return m.group(1) if m else None


def moodle_participant(name):
    """The participant number in a file name from Moodle's "Download all submissions"."""
    m = re.search(r"_(\d+)_assignsubmission_", name)
    return m.group(1) if m else None


def _stem(name):
    name = name.rsplit("/", 1)[-1]
    return name[:-6] if name.endswith(".ipynb") else name


def totals(rows):
    """(submission, exercise, {part: points}, total, max_points) of one submission's rows."""
    parts = [r for r in rows if r.part]
    name = rows[0].submission if rows else ""
    exercise = rows[0].exercise if rows else ""
    got = {r.part: r.points for r in parts}
    return name, exercise, got, sum(got.values()), sum(r.max_points for r in parts)


def _num(x):
    return f"{x:g}" if isinstance(x, float) else str(x)


def _write(path, header, lines):
    from .grade import cell
    with open(path, "w", newline="", encoding="utf-8") as f:
        w = csv.writer(f)
        w.writerow([cell(h) for h in header])
        for line in lines:
            w.writerow([cell(v) for v in line])


def write_gradebook(path, per_submission):
    """One row per submission: points of every part, total, maximum."""
    table = [totals(rows) for rows in per_submission]
    columns = []
    for _, ex, got, _, _ in table:
        for part in got:
            if f"{ex}:{part}" not in columns:
                columns.append(f"{ex}:{part}")
    lines = []
    for name, ex, got, total, most in table:
        student = canvas_id(name) or moodle_participant(name) or _stem(name)
        lines.append([student, name, ex] + [_num(got[c.split(":", 1)[1]])
                                            if c.split(":", 1)[0] == ex and
                                            c.split(":", 1)[1] in got else ""
                                            for c in columns] + [_num(total), _num(most)])
    _write(path, ["student", "submission", "exercise", *columns, "total", "max_points"], lines)


def write_canvas(path, per_submission):
    """Canvas's gradebook import: the total of each submission in one assignment column."""
    table = [totals(rows) for rows in per_submission]
    exercises = sorted({ex for _, ex, _, _, _ in table if ex}) or ["exercise"]
    column = (exercises[0] if len(exercises) == 1 else "exercises") + " (whittaker-teach)"
    lines = [[_stem(name), canvas_id(name) or "", "", "", "", _num(total)]
             for name, _, _, total, _ in table]
    _write(path, ["Student", "ID", "SIS User ID", "SIS Login ID", "Section", column], lines)


def write_moodle(path, per_submission):
    """Moodle's offline grading worksheet: Identifier, Full name, Grade, Maximum Grade."""
    lines = []
    for rows in per_submission:
        name, ex, got, total, most = totals(rows)
        pid = moodle_participant(name)
        full = name.split("_", 1)[0] if pid else _stem(name)
        lines.append([f"Participant {pid}" if pid else _stem(name), full, _num(total),
                      _num(most), f"{sum(1 for r in rows if r.part and r.ok)} of "
                      f"{len(got)} parts right"])
    _write(path, ["Identifier", "Full name", "Grade", "Maximum Grade", "Feedback comments"],
           lines)


def write_exports(per_submission, gradebook=None, canvas=None, moodle=None):
    """Write the exports asked for (each a path or None)."""
    for path, fn in ((gradebook, write_gradebook), (canvas, write_canvas),
                     (moodle, write_moodle)):
        if path:
            fn(path, per_submission)
