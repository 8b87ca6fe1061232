"""Automatic feedback for the exercises of the course.

>>> from whittaker_teach.exercises import check
>>> check("sledge-L-star", None, part="L_star").message[:16]
'not answered yet'
>>> check("sledge-L-star", "sqrt(2*h - k^2*theta^2)*sqrt(m*sec(theta)^2 + J*theta'^2)",
...       part="L_star").ok
True
>>> f = check("sledge-L-star", "-sqrt(2*h - k^2*theta^2)*sqrt(m*sec(theta)^2 + J*theta'^2)",
...           part="L_star")
>>> f.ok, f.message[:58]
(False, 'The sign is wrong (your answer is -1 times the right one):')

``check(exercise_id, answer, part=None)`` returns a
:class:`~whittaker_teach.exercises.feedback.Feedback` (``.ok``,
``.message``; it displays as a coloured box in a notebook).  It accepts any
form of the right answer (a SymPy expression, the library's own result such
as ``red.L_star``, or a string such as ``"sqrt(2*h)*..."``; ``theta(x)`` or
``theta``, ``Derivative(theta(x), x)`` or ``thetaprime`` or ``theta'``), and
never raises: a wrong answer gets a hint that names the kind of difference
(a wrong sign, a missing factor, a wrong power, a symbol it should not
contain), an unreadable one a message saying what was expected.  A number
may be of any common kind (Python, ``fractions``, SymPy, numpy, mpmath).
Every check is bounded (:mod:`.limits`): it answers within 2 s whatever it
is given, if need be with "this answer is too expensive to check; simplify
it".

The expected answers are data, not code: ``make exercises`` runs each
exercise's solution (``exercises/src/<id>.py``) and stores the answers in
``whittaker_teach/exercises/data/<id>.json``; :func:`answers_path` says where an
exercise's data is, :func:`load` gives the exercise (its parts, their
``points``, and ``solvers``: whether a graded notebook may use the
library's solvers).  A string is read as the object it prints: ``str(expr)``
of any SymPy answer, the name of an exception class, ``repr`` of a number
get the same verdict as the objects.
"""

from __future__ import annotations

from .feedback import Feedback
from .limits import TooExpensive

__all__ = ["check", "exercises", "parts", "load", "answers_path", "answers_dirs", "Feedback"]


def _catalog():
    from .catalog import EXERCISES
    return EXERCISES


def load(exercise_id):
    """The exercise (``.title``, ``.solvers``, ``.parts`` = {name: Part with ``.points``})."""
    from .catalog import load as _load
    return _load(exercise_id)


def answers_path(exercise_id):
    """The file holding ``exercise_id``'s expected answers (a Path), or None."""
    from .answers import answers_path as _path
    return _path(exercise_id)


def answers_dirs():
    """Every folder where answer data is looked for (keep them out of a graded kernel)."""
    from .answers import answers_dirs as _dirs
    return _dirs()


def exercises():
    """The ids of the exercises that have automatic checks."""
    return list(_catalog())


def parts(exercise_id):
    """{part name: what it asks} for one exercise."""
    ex = _catalog()[exercise_id]
    return {name: p.what for name, p in ex.parts.items()}


def check(exercise_id, answer, part=None, graded=False):
    """Check ``answer`` to ``part`` of exercise ``exercise_id``: a :class:`Feedback`.

    ``part`` may be omitted when the exercise has a single part.  Never
    raises; ``None`` (the placeholder of the student notebooks) gives "not
    answered yet".  A typed answer (a string) is read back before the verdict.
    ``graded=True`` (the grader's checks): hints name the kind of mistake only,
    with no quantity that reveals the right answer.
    """
    import os
    if os.environ.get("WHITTAKER_TEACH_COLLECT"):
        # `make exercises` runs the solution: its answers become the expected ones
        from .authoring import record_expected
        record_expected(exercise_id, part, answer)
        return Feedback(True, "recorded as the expected answer", str(exercise_id)[:40], part)
    if os.environ.get("WHITTAKER_TEACH_CHECK_LOG"):
        # graded: record the answer only; the grader checks it in its own process
        feedback = Feedback(False, "recorded for grading", str(exercise_id)[:40],
                            part if isinstance(part, str) else None,
                            "unanswered" if answer is None or answer is Ellipsis else "invalid")
        _record(feedback, answer)
        return feedback
    try:
        feedback = _check(exercise_id, answer, part, graded)
    except (Exception, TooExpensive) as exc:  # noqa: BLE001 - a checker must answer
        where = (exercise_id[:40] if isinstance(exercise_id, str) else "",
                 part[:40] if isinstance(part, str) else None)
        if isinstance(exc, TooExpensive):
            feedback = Feedback(False, "This answer is too expensive to check; simplify it.",
                                *where, "invalid")
        else:
            feedback = Feedback(False, "The checker could not check this answer "
                                f"({type(exc).__name__}); please report it", *where, "invalid")
    return feedback


def _record(feedback, answer):
    """Append the answer to the file WHITTAKER_TEACH_CHECK_LOG (set by ``grade``)."""
    import os
    path = os.environ.get("WHITTAKER_TEACH_CHECK_LOG")
    if not path:
        return
    from .grade import record_line
    try:
        with open(path, "a", encoding="utf-8") as out:
            out.write(record_line(feedback, answer) + "\n")
    except OSError:
        pass


def _check(exercise_id, answer, part, graded=False):
    from .specs import check_part
    cat = _catalog()
    if not isinstance(exercise_id, str) or exercise_id not in cat:
        return Feedback(False, f"There is no exercise {str(exercise_id)[:40]!r} (no answer data "
                        f"for it: run `make exercises`); the exercises are {', '.join(cat)}",
                        "", None, "invalid")
    ex = cat[exercise_id]
    names = list(ex.parts)
    if part is None:
        if len(names) != 1:
            return Feedback(False, f"This exercise has several parts ({', '.join(names)}): "
                            "say which one, e.g. check(..., part='" + names[0] + "')",
                            exercise_id, None, "invalid")
        part = names[0]
    if not isinstance(part, str) or part not in ex.parts:
        return Feedback(False, f"There is no part {str(part)[:40]!r} in {exercise_id}; its parts "
                        f"are {', '.join(names)}", exercise_id, None, "invalid")
    if ex.withheld:
        from .specs import read_back
        return read_back(ex, ex.parts[part], answer)
    return check_part(ex, ex.parts[part], answer, graded=graded)
