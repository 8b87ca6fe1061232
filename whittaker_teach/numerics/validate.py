"""Checks of the numerical input: every mistake becomes a ModelError naming it.

>>> import whittaker_teach as wt
>>> S = wt.examples.sledge()
>>> parameter_values(S, {"m": 1, "J": 2, "k": 3})
[2.0, 3.0, 1.0]
>>> parameter_values(S, {"m": 1, "J": 2})
Traceback (most recent call last):
...
whittaker_teach.errors.ModelError: params: no value for the parameter k (the sledge needs J, k, m)
"""

from __future__ import annotations

import math
import numbers

from ..errors import ModelError, ModelTypeError

__all__ = ["ROUNDOFF", "SCIPY_METHODS", "FIXED_STEP_METHODS", "coordinate_of", "initial_values",
           "parameter_values", "check_method", "check_tolerances", "check_span", "check_t_eval",
           "real", "MAX_T_EVAL"]

#: A radicand within ROUNDOFF * (its scale) below zero is round-off of zero: it is
#: clipped to 0 (a turning point); further below, the state is off the energy surface.
ROUNDOFF = 64 * 2.220446049250313e-16

SCIPY_METHODS = ("RK45", "RK23", "DOP853", "Radau", "BDF", "LSODA")
FIXED_STEP_METHODS = ("DLA",)
IMPLICIT = ("Radau", "BDF", "LSODA")


def _name_of(key):
    import sympy as sp
    from sympy.core.function import AppliedUndef
    if isinstance(key, str):
        return key
    if isinstance(key, AppliedUndef):
        return key.func.__name__
    if isinstance(key, sp.Symbol):
        return key.name
    return None


def coordinate_of(system, key, what):
    """The coordinate (a dynamicsymbol of ``system``) that ``key`` names.

    A key may be the dynamicsymbol x(t), its name "x", the reduced function
    x(s) of a Reduction, or (for velocities) x(t).diff(t).
    """
    import sympy as sp
    if isinstance(key, sp.Derivative):
        key = key.expr
    name = _name_of(key)
    for c in system.coordinates:
        if c.func.__name__ == name:
            return c
    names = ", ".join(c.func.__name__ for c in system.coordinates)
    raise ModelError(f"{what}: {key!r} is not a coordinate of the {system.name} "
                     f"(its coordinates are {names})")


def real(value, what):
    """``value`` as a finite float, or ModelError naming ``what``."""
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        try:
            import sympy as sp
            if isinstance(value, sp.Basic) and value.is_number and value.is_real:
                value = float(value)
            else:
                raise TypeError
        except TypeError:
            raise ModelTypeError(f"{what} must be a real number, got "
                                 f"{type(value).__name__} {value!r:.40}") from None
    value = float(value)
    if not math.isfinite(value):
        raise ModelError(f"{what} must be finite, got {value}")
    return value


def initial_values(system, values, what, required, forbidden=(), why_forbidden=""):
    """{coordinate: float} for exactly the coordinates ``required``."""
    if not isinstance(values, dict):
        raise ModelTypeError(f"{what} must be a dict {{coordinate: value}}, got "
                             f"{type(values).__name__}")
    out = {}
    for key, val in values.items():
        c = coordinate_of(system, key, what)
        n = c.func.__name__
        if c in forbidden:
            raise ModelError(f"{what}: {n} {why_forbidden}")
        if c not in required:
            raise ModelError(f"{what}: {n} is not expected here (expected "
                             f"{', '.join(r.func.__name__ for r in required)})")
        if c in out:
            raise ModelError(f"{what}: {n} is given twice")
        out[c] = real(val, f"{what}[{n}]")
    for c in required:
        if c not in out:
            raise ModelError(f"{what}: no initial value for the coordinate {c.func.__name__}")
    return out


def parameter_values(system, params):
    """The parameter values in the order of ``system.parameters`` (floats)."""
    if params is None:
        params = {}
    if not isinstance(params, dict):
        raise ModelTypeError(f"params must be a dict {{parameter: value}}, got "
                             f"{type(params).__name__}")
    by_name = {p.name: p for p in system.parameters}
    got = {}
    for key, val in params.items():
        name = _name_of(key)
        if name not in by_name:
            need = ", ".join(by_name) or "none"
            raise ModelError(f"params: {key!r} is not a parameter of the {system.name} "
                             f"(its parameters are {need})")
        p = by_name[name]
        x = real(val, f"params[{name}]")
        if p.is_positive and x <= 0:
            raise ModelError(f"params[{name}] = {x}: {name} is declared positive")
        got[name] = x
    for name in by_name:
        if name not in got:
            raise ModelError(f"params: no value for the parameter {name} (the "
                             f"{system.name} needs {', '.join(by_name)})")
    return [got[p.name] for p in system.parameters]


def check_method(method):
    """``method`` if it is known; ModelError listing the known ones."""
    if method in SCIPY_METHODS or method in FIXED_STEP_METHODS:
        return method
    raise ModelError(f"unknown method {method!r}: use one of scipy's "
                     f"{', '.join(SCIPY_METHODS)}, or 'DLA' (the fixed-step discrete "
                     "Lagrange-d'Alembert integrator)")


def check_tolerances(rtol, atol):
    """(rtol, atol) as floats; atol=None means atol = rtol."""
    rtol = real(rtol, "rtol")
    if not 2.3e-14 <= rtol < 1:
        raise ModelError(f"rtol = {rtol:g} is outside [2.3e-14, 1): below about 100 machine "
                         "epsilons the error estimate is round-off")
    atol = rtol if atol is None else real(atol, "atol")
    if atol <= 0:
        raise ModelError(f"atol = {atol:g} must be positive")
    return rtol, atol


def check_span(span, what):
    """A pair (start, end) of distinct finite floats."""
    try:
        a, b = span
    except (TypeError, ValueError):
        raise ModelTypeError(f"{what} must be a pair (start, end), got {span!r:.60}") from None
    a, b = real(a, f"{what}[0]"), real(b, f"{what}[1]")
    if a == b:
        raise ModelError(f"{what} = ({a}, {b}) is empty")
    return a, b


#: The most output points a run keeps (``t_eval``); a longer list is refused.
MAX_T_EVAL = 10**7


def check_t_eval(t_eval, span):
    """``t_eval`` as a sorted float array inside ``span`` (None stays None)."""
    if t_eval is None:
        return None
    import numpy as np
    try:
        t = np.asarray(t_eval, dtype=float).ravel()
    except (TypeError, ValueError):
        raise ModelTypeError("t_eval must be a sequence of times") from None
    if not 0 < t.size <= MAX_T_EVAL:
        raise ModelError(f"t_eval has {t.size} points: give between 1 and {MAX_T_EVAL}")
    if not np.all(np.isfinite(t)):
        raise ModelError("t_eval contains a non-finite time")
    a, b = span
    lo, hi = min(a, b), max(a, b)
    if t.min() < lo or t.max() > hi:
        raise ModelError(f"t_eval must lie within t_span = ({a}, {b})")
    d = np.diff(t)
    if not (np.all(d > 0) if b > a else np.all(d < 0)):
        raise ModelError("t_eval must be strictly increasing (decreasing for a backward "
                         "span), without repeated times")
    return t
