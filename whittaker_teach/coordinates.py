"""The notation shared by the model and its reduction: time, coordinate names, signs.

>>> x = dynamicsymbols("x", positive=True)
>>> name(x), sign_assumptions(x)
('x', {'positive': True})

:func:`dynamicsymbols` makes the same objects as
``sympy.physics.mechanics.dynamicsymbols`` (the same ``t``, the same undefined
functions, so the two mix freely) without importing ``sympy.physics``, whose
``units`` package alone costs about 0.2 s at import (more in a browser):

>>> from sympy.physics.mechanics import dynamicsymbols as me_dynamicsymbols
>>> dynamicsymbols("x theta") == me_dynamicsymbols("x theta"), T == me_dynamicsymbols._t
(True, True)
"""

from sympy import Function, Symbol, symbols

__all__ = ["T", "dynamicsymbols", "name", "sign_assumptions"]

#: The time variable of ``sympy.physics.mechanics.dynamicsymbols``.
T = Symbol("t")


def dynamicsymbols(names, **assumptions):
    """``names`` as functions of :data:`T` (a list for several names), as
    ``sympy.physics.mechanics.dynamicsymbols`` makes them."""
    made = symbols(names, cls=Function, **assumptions)
    return [f(T) for f in made] if isinstance(made, (list, tuple)) else made(T)


dynamicsymbols._t = T


def name(c):
    """The name of a coordinate ``x(t)``: ``'x'``."""
    return c.func.__name__


def sign_assumptions(c):
    """The sign assumptions of a coordinate, to give its symbol or reduced function."""
    return {k: True for k in ("positive", "negative") if getattr(c, "is_" + k)}
