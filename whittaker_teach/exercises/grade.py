"""Moved: the grader is :mod:`whittaker_teach.grading` (``grading.run``), apart from checking.

What stays here is :func:`record_line`, the check-log line that
:func:`whittaker_teach.exercises.check` writes while a notebook is graded
without the sandbox (it needs only the recorder).  Any other name
(``grade``, ``main``, ``points``, ...) is looked up in
:mod:`whittaker_teach.grading.run` when first asked for, with a
DeprecationWarning: this module imports nothing of the grader, so checking
never depends on grading (no import circle; tests/unit/test_import_graph.py).
"""

from __future__ import annotations

__all__ = ["record_line"]


def record_line(feedback, answer):
    """The check-log line for an answer given to ``check`` (see :mod:`.recorder`)."""
    from .recorder import record_line as line
    return line(feedback.exercise, feedback.part,
                None if feedback.status == "unanswered" else answer)


def __getattr__(name):
    if name.startswith("__"):
        raise AttributeError(name)
    import importlib
    import warnings
    run = importlib.import_module("whittaker_teach.grading.run")
    if not hasattr(run, name):
        raise AttributeError(name)
    warnings.warn("whittaker_teach.exercises.grade moved to whittaker_teach.grading.run",
                  DeprecationWarning, stacklevel=2)
    return getattr(run, name)
