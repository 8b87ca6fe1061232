"""The grader's rows: one per part of a submission, and the CSV cells they are written as.

>>> row = Row("alice.ipynb", "kepler-orbit", "h", False, "not answered")
>>> row.csv()
['alice.ipynb', 'kepler-orbit', 'h', 'False', '0', '1', 'not answered']
>>> cell("=HYPERLINK(\\"http://x\\")"), cell("-dash.ipynb"), cell("ok")
('\\'=HYPERLINK("http://x")', "'-dash.ipynb", 'ok')
"""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["Row", "cell", "num", "summary", "totals", "HEADER"]

HEADER = ["submission", "exercise", "part", "ok", "points", "max_points", "message"]


@dataclass
class Row:
    """One line of the grades: a part of a submission, or (part "") why it could not run."""

    submission: str
    exercise: str
    part: str
    ok: bool
    message: str
    points: float = 0
    max_points: float = 1

    def csv(self):
        return [cell(v) for v in (self.submission, self.exercise, self.part, str(bool(self.ok)),
                                  num(self.points), num(self.max_points) if self.part else "",
                                  self.message)]


def num(x):
    """A number as the CSV shows it: 3, 2.5 (never 3.0)."""
    return f"{x:g}" if isinstance(x, float) else str(x)


def cell(text):
    """A CSV cell a spreadsheet never reads as a formula (OWASP: a leading quote)."""
    text = str(text)
    return "'" + text if text[:1] in ("=", "+", "-", "@", "\t", "\r") else text


def totals(rows):
    """(submission, exercise, {part: points}, total, max_points) of one submission's rows."""
    parts = [r for r in rows if r.part]
    name = rows[0].submission if rows else ""
    exercise = rows[0].exercise if rows else ""
    got = {r.part: r.points for r in parts}
    return name, exercise, got, sum(got.values()), sum(r.max_points for r in parts)


def summary(rows, n):
    """'30 submissions: 41 parts right, 49 parts wrong, 6 failures'."""
    right = sum(1 for r in rows if r.part and r.ok)
    wrong = sum(1 for r in rows if r.part and not r.ok)
    failures = len({r.submission for r in rows if not r.part})
    return (f"{n} submission{'s' if n != 1 else ''}: {right} part{'s' if right != 1 else ''} "
            f"right, {wrong} part{'s' if wrong != 1 else ''} wrong, {failures} "
            f"failure{'s' if failures != 1 else ''}")
