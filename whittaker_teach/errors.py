"""Errors raised by whittaker_teach.

Every error that bad input can cause is a :class:`ModelError` (a
``ValueError``), and its message names the violated condition and the
equation of Mei (1983) it belongs to.  Nothing here imports SymPy.
"""

__all__ = ["ModelError", "ModelTypeError", "ChartError"]


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
