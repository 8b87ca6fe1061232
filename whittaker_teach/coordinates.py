"""The notation shared by the model and its reduction: time, coordinate names, signs.

>>> from sympy.physics.mechanics import dynamicsymbols
>>> x = dynamicsymbols("x", positive=True)
>>> name(x), sign_assumptions(x)
('x', {'positive': True})
"""

from sympy.physics.mechanics import dynamicsymbols

__all__ = ["T", "name", "sign_assumptions"]

#: The time variable of ``dynamicsymbols``.
T = dynamicsymbols._t


def name(c):
    """The name of a coordinate ``x(t)``: ``'x'``."""
    return c.func.__name__


def sign_assumptions(c):
    """The sign assumptions of a coordinate, to give its symbol or reduced function."""
    return {k: True for k in ("positive", "negative") if getattr(c, "is_" + k)}
