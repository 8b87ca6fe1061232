"""The grades, written where a lecturer needs them: a gradebook CSV, and the LMS's own files.

- :func:`write_gradebook` (``--gradebook FILE``): one row per submission,
  ``student,name,submission,exercise,<exercise>:<part>...,total,max_points``;
- :func:`fill_canvas` (``--canvas GRADEBOOK.csv``): the lecturer's own
  export of the Canvas gradebook (*Grades ▸ Export ▸ Export Entire
  Gradebook*), written back with the assignment's column filled in;
- :func:`fill_moodle` (``--moodle WORKSHEET.csv``): the lecturer's own
  Moodle *offline grading worksheet* (Assignment ▸ View all submissions ▸
  *Download grading worksheet*), written back with ``Grade`` and
  ``Feedback comments`` filled in.

Both LMS files are only ever read, and written to a new file
(``--canvas-out``, ``--moodle-out``; by default ``<name>-graded.csv`` beside
them): every row and column of the download is kept as it was (its BOM, its
line ends), and only the cells of students graded in this run change.

**Canvas** (its importer, ``app/models/gradebook_importer.rb``, finds the
header by ``Student``, ``ID`` then ``SIS User ID``, ``SIS Login ID``,
``Section`` or ``Section`` alone; takes a row beginning ``Points Possible``
as the points row; matches a column to an assignment by the id in
``Title (id)``, and a column without a known id makes a new assignment;
ignores the read-only score columns): the column is the one
``--canvas-column`` names, else the only ``Title (id)`` column whose title
is the exercise's id or title; the value written is the points scaled to
that column's Points Possible (``3 of 4`` points in a 10-point assignment:
``7.5``), rounded to 2 decimals; where the Points Possible cell is not a
number, the points themselves.

**Moodle** (its importer, ``mod/assign/feedback/offline/importgradeslib.php``
and ``locallib.php``, needs the columns ``Identifier``, ``Grade`` and
``Last modified (grade)`` or refuses the whole file; reads ``Participant
<n>``; skips a row whose grade is unchanged, empty, negative, above the
assignment's maximum, or whose grade was changed in Moodle more than 60 s
after the worksheet's ``Last modified (grade)``): ``Grade`` is the points
scaled to the worksheet's ``Maximum Grade`` and written with its decimals
and decimal separator; ``Last modified (grade)`` is kept exactly as
downloaded (changing it would defeat Moodle's check against grades changed
since the download; ``-`` means no grade yet, which Moodle accepts);
``Feedback comments`` gets a paragraph appended (the part count and the
points), or replaced with ``overwrite_feedback``.  A worksheet of an
assignment graded with a scale (no ``Maximum Grade``) is refused.

>>> fmt(7.5, 2, "."), fmt(3.0, 2, ","), fmt(2.3333333, 2, ",")
('7.50', '3,00', '2,33')
"""

from __future__ import annotations

import csv
import html
import io
import re
from pathlib import Path

from .rows import cell, num, totals

__all__ = ["write_gradebook", "fill_canvas", "fill_moodle", "ExportError", "default_out",
           "feedback_text", "fmt"]

_TITLE_AND_ID = re.compile(r"^(?P<title>.*)\s\((?P<id>\d+)\)$", re.S)


class ExportError(ValueError):
    """An LMS file that cannot be filled in; the message says why."""


def fmt(value, decimals, sep):
    """``value`` with ``decimals`` decimals and the decimal separator ``sep``."""
    text = f"{value:.{decimals}f}"
    return text.replace(".", sep) if sep != "." else text


def default_out(path):
    """``grades.csv`` -> ``grades-graded.csv`` (beside it)."""
    p = Path(path)
    return str(p.with_name(p.stem + "-graded" + (p.suffix or ".csv")))


def _norm(text):
    return "".join(c for c in str(text).casefold() if c.isalnum())


# ---------------------------------------------------------------- our own gradebook
def write_gradebook(path, per_submission, students=None):
    """One row per submission: its student (when a roster said who), points of every part,
    total, maximum."""
    students = students or [None] * len(per_submission)
    table = [totals(rows) for rows in per_submission]
    columns = []
    for _, ex, got, _, _ in table:
        for part in got:
            if f"{ex}:{part}" not in columns:
                columns.append(f"{ex}:{part}")
    lines = []
    for (name, ex, got, total, most), student in zip(table, students):
        values = []
        for c in columns:
            cex, part = c.split(":", 1)
            values.append(num(got[part]) if cex == ex and part in got else "")
        lines.append([student.id if student else "", student.name if student else "", name,
                      ex, *values, num(total), num(most)])
    with open(path, "w", newline="", encoding="utf-8") as f:
        w = csv.writer(f)
        w.writerow([cell(h) for h in ["student", "name", "submission", "exercise", *columns,
                                      "total", "max_points"]])
        for line in lines:
            w.writerow([cell(v) for v in line])


def feedback_text(rows):
    """The sentence a student's LMS feedback gets: parts right and points, nothing more."""
    name, ex, got, total, most = totals(rows)
    right = sum(1 for r in rows if r.part and r.ok)
    return (f"{ex}: {right} of {len(got)} parts right, {num(total)} of {num(most)} points "
            "(graded by whittaker-teach).")


# ---------------------------------------------------------------- reading and writing LMS files
def _read(path):
    """(rows, has a BOM, line terminator) of a CSV as downloaded."""
    try:
        raw = Path(path).read_bytes()
    except OSError as exc:
        raise ExportError(f"cannot read {path} ({type(exc).__name__}): download it from "
                          "the LMS first") from exc
    bom = raw.startswith(b"\xef\xbb\xbf")
    try:
        text = raw.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        raise ExportError(f"{path} is not UTF-8 text (download the CSV again)") from exc
    end = "\r\n" if "\r\n" in text else "\n"
    rows = list(csv.reader(io.StringIO(text, newline="")))
    if not rows:
        raise ExportError(f"{path} is empty")
    return rows, bom, end


def _write(path, rows, bom, end):
    buf = io.StringIO(newline="")
    csv.writer(buf, lineterminator=end).writerows(rows)
    with open(path, "w", newline="", encoding="utf-8-sig" if bom else "utf-8") as f:
        f.write(buf.getvalue())


def _number(text, sep="."):
    try:
        return float(str(text).strip().replace(sep, ".")) if str(text).strip() else None
    except ValueError:
        return None


# ---------------------------------------------------------------- Canvas
def canvas_column(header, exercise, title=None, column=None):
    """The index of the assignment's column in a Canvas gradebook header."""
    assignments = [(i, h) for i, h in enumerate(header) if _TITLE_AND_ID.match(h.strip())]
    if column is not None:
        hits = [i for i, h in enumerate(header) if h.strip() == column.strip()]
        if len(hits) != 1:
            raise ExportError(f"the Canvas gradebook has no column {column!r}; its "
                              "assignments: " + "; ".join(h for _, h in assignments))
        if not _TITLE_AND_ID.match(header[hits[0]].strip()):
            raise ExportError(f"{column!r} is not an assignment column (Canvas's are "
                              "'Title (id)'; this one would make a new assignment)")
        return hits[0]
    wanted = {_norm(exercise)} | ({_norm(title)} if title else set())
    hits = [i for i, h in assignments
            if _norm(_TITLE_AND_ID.match(h.strip()).group("title")) in wanted]
    if len(hits) != 1:
        raise ExportError(
            ("no" if not hits else "more than one") + f" assignment column of the Canvas "
            f"gradebook is titled {exercise!r}" + (f" or {title!r}" if title else "") +
            "; name it with --canvas-column (one of: " +
            "; ".join(repr(h) for _, h in assignments) + ")")
    return hits[0]


def fill_canvas(src, dst, grades, exercise, title=None, column=None):
    """Write ``grades`` ({Canvas user id: (points, max points)}) into the assignment's column
    of the Canvas gradebook ``src``, as ``dst``.  (column header, ids written, ids not in
    the gradebook)."""
    rows, bom, end = _read(src)
    header = [h.lstrip("\ufeff") for h in rows[0]]
    if len(header) < 3 or not header[0].strip().startswith("Student") or \
            header[1].strip() != "ID":
        raise ExportError(f"{src} is not a Canvas gradebook export (its header begins "
                          "Student, ID, ...)")
    col = canvas_column(header, exercise, title, column)
    possible = None
    for row in rows[1:]:
        if row and row[0].strip().startswith("Points Possible") and len(row) > col:
            possible = _number(row[col])
    written, missing = [], set(grades)
    for row in rows[1:]:
        if len(row) < 2 or row[0].strip().startswith("Points Possible"):
            continue
        sid = row[1].strip()
        if sid not in grades:
            continue
        got, most = grades[sid]
        if not most:
            continue
        value = got / most * possible if possible and possible > 0 else got
        while len(row) <= col:
            row.append("")
        text = fmt(round(value, 2), 2, ".")
        text = text.rstrip("0").rstrip(".") if "." in text else text
        row[col] = text
        written.append(sid)
        missing.discard(sid)
    _write(dst, rows, bom, end)
    return header[col], written, sorted(missing)


# ---------------------------------------------------------------- Moodle
def fill_moodle(src, dst, grades, overwrite_feedback=False):
    """Write ``grades`` ({participant number: (points, max points, feedback)}) into the
    Moodle grading worksheet ``src``, as ``dst``.  (participants written, participants not
    in the worksheet)."""
    rows, bom, end = _read(src)
    header = [h.lstrip("\ufeff").strip() for h in rows[0]]
    need = ("Identifier", "Grade", "Last modified (grade)")
    lacking = [c for c in need if c not in header]
    if lacking:
        raise ExportError(f"{src} is not a Moodle grading worksheet: it lacks "
                          + ", ".join(lacking) + " (Moodle refuses a worksheet without "
                          "Identifier, Grade and Last modified (grade))")
    if "Maximum Grade" not in header:
        raise ExportError(f"{src} has no Maximum Grade column: the assignment is graded with "
                          "a scale, and points cannot be written into it")
    ident, grade, most_col = (header.index("Identifier"), header.index("Grade"),
                              header.index("Maximum Grade"))
    fb = header.index("Feedback comments") if "Feedback comments" in header else None
    written, missing = [], set(grades)
    for row in rows[1:]:
        if len(row) <= max(ident, grade, most_col):
            continue
        m = re.search(r"(\d+)\s*$", row[ident])
        if not m or m.group(1) not in grades:
            continue
        pid = m.group(1)
        got, most, text = grades[pid]
        top = row[most_col].strip()
        sep = "," if ("," in top and "." not in top) else "."
        decimals = len(top.split(sep, 1)[1]) if sep in top else 0
        maximum = _number(top, sep)
        if maximum is None or maximum <= 0 or not most:
            continue
        value = min(round(got / most * maximum, decimals), maximum)
        row[grade] = fmt(value, decimals, sep)
        if fb is not None and text:
            while len(row) <= fb:
                row.append("")
            para = f"<p>{html.escape(text)}</p>"
            old = row[fb]
            if overwrite_feedback or not old.strip():
                row[fb] = para
            elif para not in old:
                row[fb] = old + para
        written.append(pid)
        missing.discard(pid)
    _write(dst, rows, bom, end)
    return written, sorted(missing)
