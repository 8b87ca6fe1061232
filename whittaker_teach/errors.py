"""Errors raised by whittaker_teach.

Every error that bad input can cause is a :class:`ModelError` (a
``ValueError``), and its message names the violated condition and the
equation of Mei (1983) it belongs to.  Nothing here imports SymPy.
"""

__all__ = ["ModelError", "ModelTypeError", "ChartError", "guarded"]

import functools
import traceback


class ModelError(ValueError):
    """A system or a request that the paper's derivation cannot accept.

    >>> raise ModelError("L depends on the dependent coordinate y (Chaplygin condition, 1.3)")
    Traceback (most recent call last):
    ...
    whittaker_teach.errors.ModelError: L depends on the dependent coordinate y (Chaplygin condition, 1.3)
    """


class ModelTypeError(ModelError, TypeError):
    """An argument of the wrong type (also a ``TypeError``)."""


class ChartError(ModelError):
    """The chosen independent coordinate q_eps stops being usable.

    Raised when qdot_eps vanishes along a motion (a turning point), so that
    the change of variable (1.5) q'_nu = qdot_nu / qdot_eps breaks down.
    """


_FOREIGN = ("sympy", "mpmath", "numpy", "scipy")


def _raised_in_library(err):
    """True when ``err`` was raised inside SymPy, mpmath, numpy or scipy."""
    frames = traceback.extract_tb(err.__traceback__)
    return bool(frames) and any(f"{sep}{name}{sep}" in frames[-1].filename
                                for name in _FOREIGN for sep in "/\\")


def guarded(what):
    """Decorate a public method so that no raw exception of SymPy, mpmath, numpy or
    scipy reaches the user: it becomes a :class:`ModelError` naming ``what`` failed
    (the original is chained as ``__cause__``).  A RecursionError, wherever it
    arises, means an expression nested too deeply.

    >>> @guarded("the demo")
    ... def f():
    ...     import sympy
    ...     return sympy.Symbol(1)
    >>> f()
    Traceback (most recent call last):
    ...
    whittaker_teach.errors.ModelError: the demo failed inside the symbolic library (TypeError: name should be a string, not <class 'int'>); the input is outside what the derivation supports
    """
    def deco(fn):
        @functools.wraps(fn)
        def wrapper(*args, **kwargs):
            try:
                return fn(*args, **kwargs)
            except ModelError:
                raise
            except RecursionError as err:
                raise ModelError(f"{what}: an expression is nested too deeply to differentiate "
                                 "or evaluate (Python's recursion limit was reached)") from err
            except Exception as err:
                if not _raised_in_library(err):
                    raise
                raise ModelError(f"{what} failed inside the symbolic library "
                                 f"({type(err).__name__}: {err}); the input is outside what "
                                 "the derivation supports") from err
        return wrapper
    return deco
