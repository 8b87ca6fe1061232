"""The full model: the Chaplygin equations (1.4) and the constraints, integrated in t.

:func:`simulate` is what :meth:`ChaplyginSystem.simulate` calls.

>>> import whittaker_teach as wt
>>> S = wt.examples.sledge()
>>> traj = S.simulate({"x": 0, "theta": 0.5, "y": 0}, {"x": 1, "theta": 0}, (0, 10),
...                   {"m": 1, "J": 1, "k": 1})
>>> traj.formulation, traj.energy_error < 1e-8
('multiplier', True)
>>> round(traj(10.0)["theta"], 6)      # theta = 0.5 cos t: (3.15)
-0.419536

Formulations (``formulation=``):

``"chaplygin"``
    the state (q_s, qdot_sigma); the accelerations solved from (1.4), the
    dependent coordinates from the constraints (1.3).  This is the paper's
    model.  Where a constraint or (1.4) has a pole (the sledge's
    ydot = xdot tan(theta) at cos(theta) = 0) it is singular: reaching a pole
    raises a ModelError that says where.
``"multiplier"``
    the Lagrange-d'Alembert equations with one multiplier per constraint,
    written as A(q) qdot = 0 after multiplying each constraint by its
    denominator (the sledge: ydot cos(theta) - xdot sin(theta) = 0).  The
    state is (q_s, qdot_s); no pole, so it runs through theta = pi/2.  It
    needs constraints linear in the velocities.
``"auto"`` (default)
    ``"multiplier"`` when the constraints are linear and have a pole,
    otherwise ``"chaplygin"``.
"""

from __future__ import annotations

import numpy as np

from ..errors import ModelError
from . import codegen, validate
from .ivp import solve
from .results import CoordDict, Trajectory

__all__ = ["simulate", "choose_formulation", "initial_state", "POLE_TOL"]

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


def _pole_events(fm, p):
    events = []
    for text, fn in fm.poles:
        def ev(t, y, fn=fn):
            return fn(y.tolist(), p)
        ev.terminal = True
        ev.text = text
        events.append(ev)
    return events


def simulate(system, q0, qdot0, t_span, params, method="DOP853", rtol=1e-9, atol=None, *,
             formulation="auto", dt=None, t_eval=None, dense=True, max_energy_error=1e-2):
    """Integrate the full model in t; see :meth:`ChaplyginSystem.simulate`.

    ``dt`` and ``max_energy_error`` belong to ``method="DLA"`` (see
    :func:`~whittaker_teach.numerics.integrators.simulate_dla`)."""
    method = validate.check_method(method)
    t_span = validate.check_span(t_span, "t_span")
    formulation = choose_formulation(system, formulation)
    if method == "DLA":
        from .integrators import simulate_dla
        if dt is None:
            raise ModelError("method 'DLA' is a fixed-step integrator: pass its step dt")
        if t_eval is not None:
            raise ModelError("t_eval is not available with the fixed-step method 'DLA': it "
                             "returns its steps; interpolate with traj(t)")
        return simulate_dla(system, q0, qdot0, t_span, params, validate.real(dt, "dt"),
                            dense=dense, max_energy_error=max_energy_error)
    if dt is not None:
        raise ModelError(f"dt is the step of the fixed-step method 'DLA'; {method} chooses "
                         "its own steps (set rtol and atol)")
    rtol, atol = validate.check_tolerances(rtol, atol)
    y0, p, fm = initial_state(system, q0, qdot0, params, formulation)
    events = _pole_events(fm, p) if formulation == "chaplygin" else None
    for ev in events or ():
        if ev(t_span[0], y0) == 0:
            raise ModelError(f"the Chaplygin form (1.4) has a pole at the initial state "
                             f"({ev.text} = 0); use formulation='multiplier'")
    sol = solve(fm.rhs, fm.jac, t_span, y0, p, method, rtol, atol, events=events,
                dense=dense, t_eval=t_eval, what=f"{system.name}, time model")
    if sol.status == 1:
        hit = next(i for i, te in enumerate(sol.t_events) if len(te))
        raise ModelError(
            f"the Chaplygin form (1.4) of the {system.name} reaches a pole, "
            f"{events[hit].text} = 0, at t = {sol.t_events[hit][0]:.10g}: the constraints "
            "solved for the dependent velocities are singular there; use "
            "formulation='multiplier' (the default 'auto' does), which is regular")
    return _trajectory(system, fm, sol, p, method, formulation, dense)


def _trajectory(system, fm, sol, p, method, formulation, dense):
    S, n = system, fm.n
    Y = sol.y
    with np.errstate(all="ignore"):
        vel = fm.velocities(*Y, *p)
        E = np.broadcast_to(np.asarray(fm.energy(*Y, *p), dtype=float), sol.t.shape)
    q = CoordDict((c, Y[i]) for i, c in enumerate(S.coordinates))
    qdot = CoordDict((c, np.broadcast_to(np.asarray(vel[i], dtype=float), sol.t.shape))
                     for i, c in enumerate(S.coordinates))
    if not (np.all(np.isfinite(E)) and all(np.all(np.isfinite(v)) for v in qdot.values())):
        raise ModelError(f"{S.name}: the velocities or the energy are not finite along the "
                         f"computed motion ({formulation} form at a pole?)")
    dense_fn = None
    if dense and sol.sol is not None:
        solution = sol.sol

        def dense_fn(t):
            return solution(t)[:n]
    return Trajectory(sol.t, q, qdot, np.array(E), float(E[0]), int(sol.nfev),
                      int(sol.njev), method, formulation, list(S.coordinates), dense_fn)
