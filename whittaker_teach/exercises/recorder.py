"""``check`` as a graded kernel sees it: the answer is recorded, never checked there.

Inside the grading sandbox this module is the whole of
``whittaker_teach.exercises`` (the grader binds it there as
``exercises/__init__.py``): no expected answers, no checker, nothing but a
function that appends the answer, as text, to the submission's check log
(the pipe ``WHITTAKER_TEACH_CHECK_FD`` that the grader reads, else the
file named by ``WHITTAKER_TEACH_CHECK_LOG``).  The grader reads that
log after the notebook has run and checks every answer itself, outside the
sandbox, with :func:`whittaker_teach.exercises.check`.

Each record is one JSON line with a fixed set of keys: ``exercise``,
``part``, ``kind`` (``"answer"``, ``"unanswered"``, ``"unrecordable"`` or
``"solver"``), ``answer`` (the text, or None) and ``what`` (for an
unrecordable answer, one word from :data:`KINDS`; for ``"solver"``, the
module asked for).  Nothing else in it is ever shown to anyone: the grader
writes its own messages.

>>> import json
>>> json.loads(record_line("kepler-orbit", "h", 0.5))["answer"]
'0.5'
>>> json.loads(record_line("kepler-orbit", "h", [1, 2]))["what"]
'list'
>>> json.loads(record_line("kepler-orbit", "h", None))["kind"]
'unanswered'
"""

from __future__ import annotations

import json
import os
import sys

__all__ = ["check", "record_line", "record_event", "KINDS", "MAX_ANSWER_CHARS"]

MAX_ANSWER_CHARS = 50_000
#: what an answer that cannot be recorded as text was (the grader's messages name these)
KINDS = ("list", "tuple", "dict", "set", "bool", "complex", "function", "too-large", "other")


def _answer_text(answer):
    """The answer as text the grader's parser reads back (None if it cannot be)."""
    if isinstance(answer, str):
        return answer[:MAX_ANSWER_CHARS]
    if isinstance(answer, type) and issubclass(answer, BaseException):
        return answer.__name__          # a choice part answered with an exception class
    kind = type(answer).__module__.split(".")[0]
    if kind == "numpy" and getattr(answer, "ndim", None) == 0:
        answer = answer.item()
    if kind == "mpmath":
        import mpmath
        return mpmath.nstr(answer, 30) if isinstance(answer, mpmath.mpf) else None
    if isinstance(answer, bool) or answer is None:
        return None
    if isinstance(answer, (int, float)):
        text = repr(answer)
        return text if len(text) < 100 else None
    if "sympy" in sys.modules and kind == "sympy":
        import sympy as sp
        if isinstance(answer, sp.Basic):
            if sum(1 for _ in zip(range(5001), sp.preorder_traversal(answer))) > 5000:
                return None
            text = sp.sstr(answer)
            return text if len(text) <= MAX_ANSWER_CHARS else None
    import numbers
    from fractions import Fraction
    if isinstance(answer, Fraction):
        return f"Rational({answer.numerator}, {answer.denominator})"
    if isinstance(answer, numbers.Number) and not isinstance(answer, complex):  # Decimal
        text = str(answer)
        return text if len(text) < 100 else None
    return None


def _kind(answer):
    for name, types in (("bool", bool), ("list", list), ("tuple", tuple), ("dict", dict),
                        ("set", (set, frozenset)), ("complex", complex)):
        if isinstance(answer, types):
            return name
    if callable(answer):
        return "function"
    if isinstance(answer, (int, float, str)) or type(answer).__module__.startswith("sympy"):
        return "too-large"
    return "other"


def record_line(exercise, part, answer):
    """The JSON line recorded for one ``check(exercise, answer, part=part)``."""
    rec = {"exercise": str(exercise)[:40], "part": part[:40] if isinstance(part, str) else None,
           "kind": "answer", "answer": None, "what": ""}
    if answer is None or answer is Ellipsis:
        rec["kind"] = "unanswered"
    else:
        try:
            rec["answer"] = _answer_text(answer)
        except BaseException:  # noqa: BLE001 - a student's object may raise anything
            rec["answer"] = None
        if rec["answer"] is None:
            rec["kind"], rec["what"] = "unrecordable", _kind(answer)
    return json.dumps(rec)


def _append(line):
    fd = os.environ.get("WHITTAKER_TEACH_CHECK_FD", "")
    if fd.isdigit():                  # the grader's pipe (a pipe of another user: not reopened)
        data = memoryview((line + "\n").encode("utf-8"))
        try:
            while data:
                data = data[os.write(int(fd), data):]
        except OSError:
            pass
        return
    path = os.environ.get("WHITTAKER_TEACH_CHECK_LOG")
    if not path:
        return
    try:
        with open(path, "a", encoding="utf-8") as out:
            out.write(line + "\n")
    except OSError:
        pass


def record_event(kind, what):
    """Record something the grader reports in its own words (``"solver"``: a refused import)."""
    _append(json.dumps({"exercise": "", "part": None, "kind": str(kind)[:20], "answer": None,
                        "what": str(what)[:80]}))


class Recorded:
    """What ``check`` returns while a notebook is graded."""

    ok = False
    status = "recorded"
    message = "recorded for grading (the grader checks it after the notebook has run)"

    def __init__(self, exercise, part):
        self.exercise, self.part = exercise, part

    def __repr__(self):
        return f"{self.part or 'answer'}: {self.message}"

    def _repr_html_(self):
        import html
        return (f'<div style="border-left:4px solid #616161;padding:.3em .6em">'
                f"{html.escape(repr(self))}</div>")


def check(exercise_id, answer, part=None):
    """Record ``answer`` for the grader; see the module docstring."""
    _append(record_line(exercise_id, part, answer))
    return Recorded(str(exercise_id)[:40], part if isinstance(part, str) else None)
