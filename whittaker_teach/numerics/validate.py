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
from dataclasses import dataclass

from ..errors import ModelError, ModelTypeError

__all__ = ["ROUNDOFF", "SCIPY_METHODS", "FIXED_STEP_METHODS", "coordinate_of", "initial_values",
           "parameter_values", "check_method", "check_tolerances", "check_span", "check_t_eval",
           "real", "MAX_T_EVAL", "MIN_RTOL", "MIN_RTOL_TIGHT", "FORMULATIONS", "TimeInput", "time_input", "state_input",
           "ReducedInput", "reduced_input"]

#: A radicand within ROUNDOFF * (its scale) below zero is round-off of zero: it is
#: clipped to 0 (a turning point); further below, the state is off the energy surface.
ROUNDOFF = 64 * 2.220446049250313e-16

SCIPY_METHODS = ("RK45", "RK23", "DOP853", "Radau", "BDF", "LSODA", "DOP853-tight")
#: The smallest rtol of scipy's methods (about 100 machine epsilons) and of
#: "DOP853-tight" (DOP853 allowed below scipy's floor, :class:`.ivp.TightDOP853`).
MIN_RTOL, MIN_RTOL_TIGHT = 2.3e-14, 4.5e-16
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
                     f"{', '.join(SCIPY_METHODS[:-1])}, 'DOP853-tight' (DOP853 with rtol "
                     "allowed below scipy's floor) or 'DLA' (the fixed-step discrete "
                     "Lagrange-d'Alembert integrator)")


def check_tolerances(rtol, atol, method=None):
    """(rtol, atol) as floats; atol=None means atol = rtol."""
    rtol = real(rtol, "rtol")
    if method == "DOP853-tight":
        if not MIN_RTOL_TIGHT <= rtol < 1:
            raise ModelError(f"rtol = {rtol:g} is outside [{MIN_RTOL_TIGHT:g}, 1) for "
                             "DOP853-tight: below 2 machine epsilons no step is accepted")
    elif not MIN_RTOL <= rtol < 1:
        raise ModelError(f"rtol = {rtol:g} is outside [2.3e-14, 1): below about 100 machine "
                         "epsilons scipy's error estimate is near round-off (method "
                         "'DOP853-tight' allows rtol down to 4.5e-16)")
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


# ----------------------------------------------------------------- one check per entry
FORMULATIONS = ("auto", "chaplygin", "multiplier")


@dataclass
class TimeInput:
    """The checked input of the full model (:func:`time_input`): ``q`` and ``v`` are
    {coordinate: float} (every coordinate; the independent velocities), ``p`` the
    parameter values in ``system.parameters`` order."""

    q: dict
    v: dict
    p: list
    span: tuple
    method: str
    rtol: float | None
    atol: float | None
    formulation: str
    t_eval: object
    dense: bool
    dt: float | None
    max_energy_error: float | None


def state_input(system, q0, qdot0, params):
    """(q, v, p): the coordinates, the independent velocities and the parameters, checked."""
    S = system
    q = initial_values(S, q0, "q0", S.coordinates)
    v = initial_values(
        S, qdot0, "qdot0", S.independent_coordinates, forbidden=S.dependent_coordinates,
        why_forbidden="is a dependent coordinate: its velocity follows from the constraint "
                      "(1.3); give the velocities of the independent coordinates only")
    return q, v, parameter_values(S, params)


def time_input(system, q0, qdot0, t_span, params, method, rtol, atol, formulation, dt,
               t_eval, dense, max_energy_error):
    """Every check of a call of the full model, once, before any code is generated.

    >>> import whittaker_teach as wt
    >>> S = wt.examples.sledge()
    >>> inp = time_input(S, {"x": 0, "theta": 0.5, "y": 0}, {"x": 1, "theta": 0}, (0, 1),
    ...                  {"m": 1, "J": 1, "k": 1}, "DOP853", 1e-9, None, "auto", None, None,
    ...                  None, 1e-2)
    >>> inp.span, inp.rtol, inp.atol, inp.dense
    ((0.0, 1.0), 1e-09, 1e-09, True)
    """
    method = check_method(method)
    span = check_span(t_span, "t_span")
    if formulation not in FORMULATIONS:
        raise ModelError(f"unknown formulation {formulation!r}: use 'auto', "
                         "'chaplygin' (1.4) or 'multiplier' (Lagrange-d'Alembert)")
    t_eval = check_t_eval(t_eval, span)
    if dense is None:
        dense = t_eval is None
    if method in FIXED_STEP_METHODS:
        if dt is None:
            raise ModelError("method 'DLA' is a fixed-step integrator: pass its step dt")
        if t_eval is not None:
            raise ModelError("t_eval is not available with the fixed-step method 'DLA': it "
                             "returns its steps; interpolate with traj(t)")
        dt = real(dt, "dt")
        if not dt > 0:
            raise ModelError(f"dt = {dt} must be positive")
    elif dt is not None:
        raise ModelError(f"dt is the step of the fixed-step method 'DLA'; {method} chooses "
                         "its own steps (set rtol and atol)")
    else:
        rtol, atol = check_tolerances(rtol, atol, method)
    q, v, p = state_input(system, q0, qdot0, params)
    return TimeInput(q, v, p, span, method, rtol, atol, formulation, t_eval, bool(dense), dt,
                     max_energy_error)


@dataclass
class ReducedInput:
    """The checked input of the reduced model (:func:`reduced_input`)."""

    q: dict
    qp: dict
    h: float
    span: tuple
    p: list
    method: str
    rtol: float
    atol: float
    on_turning_point: str
    tau: float
    t0: float
    max_bridge_time: float | None


def reduced_input(red, q0, qp0, h, span, params, method, rtol, atol, on_turning_point,
                  turning_tol, t0, max_bridge_time=None):
    """Every check of a call of the reduced model, once, before any code is generated."""
    S, eps = red.system, red._eps
    e = eps.func.__name__
    if method in FIXED_STEP_METHODS:
        raise ModelError("'DLA' integrates the full model in time; the reduced model takes "
                         "a scipy method (DOP853, RK45, Radau, LSODA, ...)")
    method = check_method(method)
    rtol, atol = check_tolerances(rtol, atol, method)
    if on_turning_point not in ("raise", "switch"):
        raise ModelError(f"on_turning_point must be 'raise' or 'switch', got "
                         f"{on_turning_point!r}")
    q = initial_values(S, q0, "q0", S.coordinates)
    qp = initial_values(
        S, qp0, "qp0", red._nus, forbidden=[eps] + S.dependent_coordinates,
        why_forbidden=f"has no slope here: qp0 holds dq_nu/d{e} for the coordinates "
                      f"{', '.join(c.func.__name__ for c in red._nus)} only (q_eps = {e}; "
                      "the dependent coordinates follow from the constraints, 1.23)")
    h = real(h, "h")
    a, b = check_span(span, "span")
    if abs(a - q[eps]) > 1e-12 * max(1.0, abs(a)):
        raise ModelError(f"span starts at {e} = {a} but q0[{e}] = {q[eps]}")
    if (b - a) * red.direction < 0:
        raise ModelError(f"span ({a}, {b}) runs against the direction {red.direction:+d} of "
                         f"the reduction (the sign of qdot_{e}); use "
                         f"system.reduce('{e}', direction={-red.direction})")
    p = parameter_values(S, params)
    tau = real(turning_tol, "turning_tol")
    if not 0 < tau < 0.25:
        raise ModelError(f"turning_tol = {tau} must lie in (0, 0.25)")
    if max_bridge_time is not None:
        max_bridge_time = real(max_bridge_time, "max_bridge_time")
    return ReducedInput(q, qp, h, (a, b), p, method, rtol, atol, on_turning_point, tau,
                        real(t0, "t0"), max_bridge_time)
