"""What a check may cost: size limits on an answer, and a time budget on its checking.

Anything a student types is untrusted, so every check is bounded twice:

* before anything is evaluated, the answer is measured (:mod:`.parsing`
  refuses integers beyond ``MAX_DIGITS`` digits, derivatives of order above
  ``MAX_DERIVATIVE_ORDER``, Floats of more than ``MAX_FLOAT_DIGITS`` digits,
  powers beyond ``MAX_EXPONENT``, nesting deeper than ``MAX_DEPTH`` and
  expressions of more than ``MAX_NODES`` nodes); the numerical evaluation
  refuses intermediate values beyond ``1e300`` (:mod:`.compare`);
* the checking itself runs under :func:`time_budget`: on Linux, in the main
  thread, a ``SIGPROF`` timer interrupts it after ``seconds`` of this process's
  CPU time (not wall time: a loaded machine does not make a right answer "too
  expensive", so stored notebook outputs do not depend on the load) and
  :class:`TooExpensive` is raised.  Where no timer can be set (another
  thread, Pyodide) the size limits alone bound the work.

>>> with time_budget(1.0):
...     sum(range(10))
45
>>> try:
...     with time_budget(0.05):
...         while True:
...             pass
... except TooExpensive as exc:
...     print(exc)
this answer is too expensive to check; simplify it
"""

from __future__ import annotations

import contextlib
import threading

__all__ = ["TooExpensive", "time_budget", "CHECK_SECONDS", "MAX_LENGTH", "MAX_DIGITS",
           "MAX_FLOAT_DIGITS", "MAX_EXPONENT", "MAX_DERIVATIVE_ORDER", "MAX_DEPTH",
           "MAX_NODES", "MAX_MAGNITUDE"]

CHECK_SECONDS = 1.2          # the budget of one check (the promise is 2 s, on a busy machine)
MAX_LENGTH = 2000            # characters of a typed answer
MAX_DIGITS = 30              # digits of an integer in an answer
MAX_FLOAT_DIGITS = 50        # significant digits of a Float
MAX_EXPONENT = 1000          # |n| in x**n
MAX_DERIVATIVE_ORDER = 3
MAX_DEPTH = 60               # nesting of an expression
MAX_NODES = 5000             # nodes of an expression tree
MAX_MAGNITUDE = 1e300        # of any number, given or computed

TOO_EXPENSIVE = "this answer is too expensive to check; simplify it"


class TooExpensive(BaseException):
    """The check of an answer went over its size or time budget.

    A BaseException (like KeyboardInterrupt), so that no ``except Exception``
    on the way (in SymPy, or in a hint that gives up) swallows it.
    """

    def __init__(self, message=TOO_EXPENSIVE):
        super().__init__(message)


def _timer_available():
    try:
        import signal
    except ImportError:  # pragma: no cover - Pyodide
        return None
    if not hasattr(signal, "setitimer") or threading.current_thread() is not \
            threading.main_thread():
        return None
    return signal


@contextlib.contextmanager
def time_budget(seconds=CHECK_SECONDS):
    """Raise :class:`TooExpensive` in the body after ``seconds`` of CPU time (main thread,
    POSIX).

    Nested budgets keep the outer deadline (an inner one is a no-op).
    """
    signal = _timer_available()
    if signal is None:
        yield
        return
    try:
        remaining, _ = signal.getitimer(signal.ITIMER_PROF)
    except (OSError, ValueError, AttributeError):   # no timer here (Pyodide)
        remaining = None
    if remaining is None or remaining:   # no timer, or an outer budget runs: keep it
        yield
        return

    def expire(signum, frame):
        # again soon, in case some code on the way catches it and carries on
        signal.setitimer(signal.ITIMER_PROF, 0.1)
        raise TooExpensive()

    try:
        previous = signal.signal(signal.SIGPROF, expire)
        signal.setitimer(signal.ITIMER_PROF, seconds)
    except (OSError, ValueError, AttributeError):  # pragma: no cover - no timer after all
        yield
        return
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_PROF, 0)
        signal.signal(signal.SIGPROF, previous)
