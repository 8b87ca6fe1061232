"""Checks of what a user hands over: coordinates, expressions, their values.

Shared by the system models (:class:`~whittaker_teach.system.ChaplyginSystem` and
:class:`~whittaker_teach.forms.NonholonomicSystem`), so that both refuse bad input
with the same :class:`~whittaker_teach.errors.ModelError` naming the condition.

>>> import sympy as sp
>>> from sympy.physics.mechanics import dynamicsymbols
>>> x, y = dynamicsymbols("x y")
>>> check_coordinates([x, y])
[x(t), y(t)]
>>> check_values(sp.Symbol("m")*sp.oo, "the Lagrangian L")
Traceback (most recent call last):
...
whittaker_teach.errors.ModelError: the Lagrangian L contains an infinity (oo, -oo or zoo): L and the constraints must be finite real expressions (1.1)
>>> readable(x.diff())
"x'"
"""

from __future__ import annotations

import sympy as sp
from sympy.core.function import AppliedUndef

from .coordinates import T, name
from .dag import instances, max_depth
from .errors import ModelError, ModelTypeError

__all__ = ["MAX_DEPTH", "check_coordinates", "check_values", "readable", "require_expr",
           "subexpressions"]


#: Deepest nesting of an input expression: differentiating it twice (1.4) must stay
#: well inside Python's recursion limit.
MAX_DEPTH = 30


def subexpressions(expr):
    """The distinct subexpressions of ``expr`` (one walk: ``dag.instances``)."""
    return set(instances(expr, sp.Basic))


def check_values(expr, what):
    """Refuse what the derivation cannot treat as a real function of the coordinates:
    infinities, NaN, complex coefficients, too deep a nesting."""
    nodes = subexpressions(expr)
    if sp.nan in nodes:
        raise ModelError(f"{what} contains nan (not a number): L and the constraints must be "
                         "finite real expressions (1.1)")
    if any(x in nodes for x in (sp.oo, -sp.oo, sp.zoo)):
        raise ModelError(f"{what} contains an infinity (oo, -oo or zoo): L and the constraints must "
                         "be finite real expressions (1.1)")
    if sp.I in nodes:
        raise ModelError(f"{what} contains the imaginary unit I: complex coefficients are not "
                         "allowed, L and the constraints must be real (1.1), (1.11)")
    if max_depth(expr, MAX_DEPTH) > MAX_DEPTH:
        raise ModelError(f"{what} is nested more than {MAX_DEPTH} levels deep: too deep to "
                         "differentiate (1.4) reliably; write it with fewer nested functions")


def require_expr(value, what):
    if isinstance(value, bool) or not isinstance(value, (sp.Basic, int, float)):
        raise ModelTypeError(
            f"{what} must be a SymPy expression, got {type(value).__name__} {value!r:.60}")
    value = sp.sympify(value)
    if not isinstance(value, sp.Expr):
        raise ModelTypeError(f"{what} must be a SymPy expression (not an equation or a "
                             f"relation), got {type(value).__name__}: {value}")
    return value


def check_coordinates(coordinates):
    if isinstance(coordinates, (sp.Basic, str)) or not hasattr(coordinates, "__iter__"):
        raise ModelTypeError("coordinates must be a list of dynamicsymbols such as "
                             f"[x, theta, y], got {type(coordinates).__name__}")
    coords = list(coordinates)
    if not coords:
        raise ModelError("coordinates is empty: a system needs at least one coordinate q_s (1.1)")
    for c in coords:
        if not (isinstance(c, AppliedUndef) and len(c.args) == 1
                and isinstance(c.args[0], sp.Symbol) and c.args[0].name == T.name):
            raise ModelTypeError(
                f"coordinate {c!r} is not a function of time: make coordinates with "
                "sympy.physics.mechanics.dynamicsymbols, e.g. x, y = dynamicsymbols('x y')")
    times = {c.args[0] for c in coords}
    if len(times) > 1:
        raise ModelTypeError("the coordinates are functions of different time symbols "
                             f"{sorted(map(repr, times))} (one declared real=True?): use one "
                             "time symbol for all of them")
    names = [name(c) for c in coords]
    dup = sorted({n for n in names if names.count(n) > 1})
    if dup:
        raise ModelError(f"duplicate coordinates: {', '.join(dup)} appear more than once "
                         "in the list of coordinates q_s (1.1)")
    return coords



def readable(expr) -> str:
    """``expr`` on one line for an error message, as sympy.physics.mechanics prints it:
    x for x(t), x' for its time derivative (``vsprint``)."""
    from sympy.physics.vector.printing import vsprint
    return vsprint(expr)
