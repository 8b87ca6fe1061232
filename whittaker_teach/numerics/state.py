"""The starting state of each model, from what the user gives: checked, then compiled.

Every entry point (:func:`~whittaker_teach.numerics.time_model.simulate`,
:func:`~whittaker_teach.numerics.integrators.simulate_dla`,
:func:`~whittaker_teach.numerics.reduced_model.simulate`) starts here, so that
the input checks (:mod:`.validate`) and the generated code (:mod:`.codegen`)
are reached from one place.  Imports only those two: no import circles.

>>> import whittaker_teach as wt
>>> S = wt.examples.sledge()
>>> choose_formulation(S)
'multiplier'
>>> y0, p, fm = initial_state(S, {"x": 0, "theta": 0.5, "y": 0}, {"x": 1, "theta": 0},
...                           {"m": 1, "J": 1, "k": 1}, "multiplier")
>>> fm.state, [round(float(v), 6) for v in y0]
(['x', 'theta', 'y', 'xdot', 'thetadot', 'ydot'], [0.0, 0.5, 0.0, 1.0, 0.0, 0.546302])
"""

from __future__ import annotations

import numpy as np

from ..errors import ModelError
from . import codegen, validate

__all__ = ["choose_formulation", "initial_state", "check_poles", "POLE_TOL"]

#: An initial state where a denominator of the constraints is smaller than this
#: is refused (the dependent velocities would be round-off divided by round-off).
POLE_TOL = 1e-12


def choose_formulation(system, formulation="auto"):
    """``formulation``, with ``"auto"`` resolved (see the module docstring)."""
    if formulation != "auto":
        if formulation not in ("chaplygin", "multiplier"):
            raise ModelError(f"unknown formulation {formulation!r}: use 'auto', "
                             "'chaplygin' (1.4) or 'multiplier' (Lagrange-d'Alembert)")
        if formulation == "multiplier":
            codegen.constraint_rows(system)          # linear constraints, or ModelError
        return formulation
    cache = codegen.cache_of(system)
    if "auto" not in cache:
        S = system
        q = [S.q[c] for c in S.coordinates]
        choice = "chaplygin"
        if codegen.pole_factors(list(S._phi.values()), q):
            try:
                codegen.constraint_rows(S)
                choice = "multiplier"
            except ModelError:
                pass
        cache["auto"] = choice
    return cache["auto"]


def initial_state(system, q0, qdot0, params, formulation):
    """The state vector of ``formulation`` from ``q0`` (all coordinates) and ``qdot0``
    (the independent ones); also the parameter list and the model."""
    S = system
    deps = S.dependent_coordinates
    q = validate.initial_values(S, q0, "q0", S.coordinates)
    v = validate.initial_values(
        S, qdot0, "qdot0", S.independent_coordinates, forbidden=deps,
        why_forbidden="is a dependent coordinate: its velocity follows from the constraint "
                      "(1.3); give the velocities of the independent coordinates only")
    p = validate.parameter_values(S, params)
    fm = codegen.time_model(S, formulation)
    qv = [q[c] for c in S.coordinates]
    vs = [v[c] for c in S.independent_coordinates]
    check_poles(S, qv, p)
    with np.errstate(all="ignore"):
        allv = [float(w) for w in fm.from_independent(*qv, *vs, *p)]
    if not all(np.isfinite(allv)):
        bad = [c.func.__name__ for c, w in zip(S.coordinates, allv) if not np.isfinite(w)]
        raise ModelError(f"the constraint for {', '.join(bad)}dot cannot be evaluated at the "
                         "initial state (a pole of the constraint, 1.3): start elsewhere")
    y0 = qv + (vs if formulation == "chaplygin" else allv)
    return np.array(y0), p, fm


def check_poles(system, qv, p):
    """ModelError if the coordinates ``qv`` are (nearly) at a pole of the constraints."""
    for text, fn in codegen.constraint_poles(system):
        if abs(fn(*qv, *p)) < POLE_TOL:
            raise ModelError(f"the initial state is (nearly) at a pole of the constraints "
                             f"(1.3), {text} = {fn(*qv, *p):.1e}: the independent velocities "
                             "do not determine the dependent ones there; start elsewhere")
