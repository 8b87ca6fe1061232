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
from .ivp import ARITHMETIC, roots_within_steps, solve
from .results import CoordDict, Trajectory

__all__ = ["simulate"]


def _first_pole(fm, sol, p):
    """(t, text) of the first zero of a pole factor of (1.4) along ``sol``, looking inside
    every step (a pole crossed twice within one step shows no sign change at its ends)."""
    best = None
    for text, fn in fm.poles_np:
        def g(t, Y, fn=fn):
            return fn(*Y, *p)
        hit = roots_within_steps(sol, g, first=True)
        if hit and (best is None or abs(hit[0] - sol.t[0]) < abs(best[0] - sol.t[0])):
            best = (hit[0], text)
    return best


def _pole_error(system, where, text):
    return ModelError(
        f"the Chaplygin form (1.4) of the {system.name} reaches a pole, {text} = 0, at "
        f"t = {where:.10g}: the constraints solved for the dependent velocities are singular "
        "there; use formulation='multiplier' (the default 'auto' does), which is regular")


def simulate(system, q0, qdot0, t_span, params, method="DOP853", rtol=1e-9, atol=None, *,
             formulation="auto", dt=None, t_eval=None, dense=None, max_energy_error=1e-2):
    """Integrate the full model in t; see :meth:`ChaplyginSystem.simulate`.

    The input is checked once (:func:`.validate.time_input`), then the compiled
    model (:func:`.codegen.time_model`, cached) gives the initial state and the
    right-hand side, and :func:`.ivp.solve` integrates.  ``dense``
    (interpolation by ``traj(t)``) defaults to True without ``t_eval`` and to
    False with it: a long run then keeps only the points asked for.  ``dt`` and
    ``max_energy_error`` belong to ``method="DLA"`` (see
    :func:`~whittaker_teach.numerics.integrators.simulate_dla`)."""
    try:
        inp = validate.time_input(system, q0, qdot0, t_span, params, method, rtol, atol,
                                  formulation, dt, t_eval, dense, max_energy_error)
        if inp.method == "DLA":
            from .integrators import simulate_dla
            return simulate_dla(system, inp)
        return _simulate(system, inp)
    except ARITHMETIC as err:
        raise ModelError(f"{system.name}, time model: the arithmetic failed ({err}); the "
                         "initial state or the parameters are out of the range of floating "
                         "point (too large or too small)") from None


def _simulate(system, inp):
    fm = codegen.time_model(system, inp.formulation)
    y0 = fm.initial_state(inp.q, inp.v, inp.p)
    p = inp.p
    poles = fm.formulation == "chaplygin" and fm.poles_np
    what = f"{system.name}, time model"
    try:
        sol = solve(fm.rhs, fm.jac, inp.span, y0, p, inp.method, inp.rtol, inp.atol,
                    dense=inp.dense or bool(poles), t_eval=inp.t_eval, what=what)
    except ModelError as err:
        if poles and getattr(err, "sol", None) is not None:
            hit = _first_pole(fm, err.sol, p)
            if hit:
                raise _pole_error(system, hit[0], hit[1]) from None
        raise
    if poles:
        hit = _first_pole(fm, sol, p)
        if hit:
            raise _pole_error(system, hit[0], hit[1])
    return _trajectory(system, fm, sol, p, inp.method, fm.formulation, inp.dense)


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
