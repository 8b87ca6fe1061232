"""Scenes that choose their model: ``scene(system, q0, qdot0, t_span, params, tol=...)``.

A scene asks for a motion within a relative error ``tol`` (relative to each
coordinate's scale over the run) and leaves the choice of the model and the
method to what the work-precision study (:mod:`.work_precision`, chapter 7)
shows:

1. **the exact solution** where one exists (the built-in sledge: the closed
   form (3.15) through Bessel functions; error about 1e-15, a fraction of a
   millisecond for 1000 points);
2. **the full model** otherwise, with DOP853 (the cheapest by evaluations at
   every target of the study but one, 1e-6 at a = 1.5, where LSODA is) at the
   tolerance the study shows reaching ``tol``: rtol = tol / 10 to start, atol
   tiny.  The reduced model is never the cheaper one in the study (1.4 to 3.3
   times the evaluations of the full model at equal error, the more the nearer
   pi/2), so a scene given a reduction integrates its system in time and says
   so.

The error of an integrated scene is *estimated*, not assumed: the run is
repeated at rtol / 10 at the same points and the difference is the estimate;
if it exceeds ``tol`` the tolerance is tightened (down to the package's
2.3e-14), and if no tolerance reaches ``tol`` a ModelError says so with the
best error available.

>>> import whittaker_teach as wt
>>> S = wt.examples.sledge()
>>> sc = scene(S, {"x": 0, "theta": 0.3, "y": 0}, {"x": 1, "theta": 0}, (0, 20),
...            {"m": 1, "J": 1, "k": 1}, tol=1e-6)
>>> sc.model, round(sc(20.0)["theta"], 6)
('exact', 0.122425)
>>> print(sc.why)
exact solution (3.15): a closed form exists for the sledge (error ~1e-15)
"""

from __future__ import annotations

import math
import textwrap
from dataclasses import dataclass, field

import numpy as np

from ..errors import ModelError
from . import validate

__all__ = ["scene", "Scene", "FLOOR"]

#: The smallest relative error the study shows the full model reaching (20 periods).
FLOOR = 1e-13
MIN_RTOL = 2.3e-14


@dataclass
class Scene:
    """A motion and the reason for its model: ``model`` ('exact' or 'full'),
    ``method``, ``rtol``, ``why`` (one or two sentences), ``error`` (the
    estimated relative error; ~1e-15 for the exact solution), ``t``, ``q``
    (arrays at the output times) and ``nfev``.  ``scene(t)`` evaluates it."""

    model: str
    method: str
    rtol: float | None
    why: str
    error: float
    t: object
    q: dict
    nfev: int
    _eval: object = field(default=None, repr=False)

    def __call__(self, t):
        return self._eval(t)

    def __str__(self):
        head = (f"scene: {self.model} model" + (f", {self.method} rtol {self.rtol:.0e}"
                                                 if self.rtol else "")
                + f"; error ~{self.error:.0e}; {self.nfev} evaluations")
        return "\n".join([head] + textwrap.wrap("why: " + self.why, 78))


def _is_sledge(S):
    return (S.name == "sledge" and [c.func.__name__ for c in S.coordinates] == ["x", "theta", "y"]
            and sorted(p.name for p in S.parameters) == ["J", "k", "m"])


def _exact_scene(S, q0, qdot0, t_span, params):
    from .exact import SledgeExact
    from .state import initial_state
    y0, p, _fm = initial_state(S, q0, qdot0, params, "chaplygin")
    J, k, m = p
    x, th, y, xd, thd = (float(v) for v in y0)
    if abs(math.cos(th)) < 1e-8:
        return None
    w = k / math.sqrt(J)
    a = math.hypot(th, thd / w)
    phi = math.atan2(-thd / w, th)
    C = xd / math.cos(th)
    ex = SledgeExact({"m": m, "J": J, "k": k}, a=a, phi=phi, C=C, x0=x, y0=y, t0=t_span[0])
    t = np.linspace(t_span[0], t_span[1], 1001)
    g = ex(t)
    q = {c: g[c] for c in ("x", "theta", "y")}
    return Scene("exact", "closed form", None, "exact solution (3.15): a closed form exists "
                 "for the sledge (error ~1e-15)", 1e-15, t, q, 0,
                 lambda tt: ex(tt))


def _rel_diff(q1, q2):
    worst = 0.0
    for c in q1:
        scale = max(float(np.max(np.abs(q1[c]))), 1e-300)
        worst = max(worst, float(np.max(np.abs(q1[c] - q2[c]))) / scale)
    return worst


def scene(system, q0, qdot0, t_span, params, tol=1e-6, *, points=1001):
    """The cheapest model and method the study shows reaching ``tol``; see the module."""
    from ..reduction import Reduction
    note = ""
    if isinstance(system, Reduction):
        note = (f"given the reduction in {system._eps.func.__name__}: the study finds the "
                "reduced model needs 1.4-3.3x the full model's evaluations, so the full model "
                "runs; ")
        system = system.system
    tol = validate.real(tol, "tol")
    if not 0 < tol < 1:
        raise ModelError(f"tol = {tol:g} must lie in (0, 1): a relative error")
    t_span = validate.check_span(t_span, "t_span")
    if _is_sledge(system):
        sc = _exact_scene(system, q0, qdot0, t_span, params)
        if sc is not None:
            sc.why = note + sc.why
            return sc
    t_eval = np.linspace(t_span[0], t_span[1], points)
    rtol = min(max(tol / 10, 10 * MIN_RTOL), 1e-3)
    best = None
    while True:
        tr = system.simulate(q0, qdot0, t_span, params, method="DOP853", rtol=rtol, atol=1e-20,
                             t_eval=t_eval, dense=True)
        ref = system.simulate(q0, qdot0, t_span, params, method="DOP853",
                              rtol=max(rtol / 10, MIN_RTOL), atol=1e-20, t_eval=t_eval,
                              dense=False)
        err = _rel_diff({c.func.__name__: tr.q[c] for c in system.coordinates},
                        {c.func.__name__: ref.q[c] for c in system.coordinates})
        best = err if best is None else min(best, err)
        if err <= tol:
            break
        if rtol <= 10 * MIN_RTOL * 1.0001:     # no tighter reference to check against
            raise ModelError(f"no model reaches the relative error {tol:g} for this "
                             f"{system.name}: the best available is about {best:.1e} (the "
                             f"full model, DOP853 at rtol {rtol:.1e}, against a run at "
                             f"rtol {MIN_RTOL:g}, the package's smallest); ask for "
                             f"tol >= {2 * best:.0e}")
        rtol = max(rtol / 10, 10 * MIN_RTOL)
    why = (note + f"no closed form for the {system.name}; the full model (formulation "
           f"{tr.formulation}) with DOP853 is the cheapest by evaluations at the study's "
           f"targets; rtol = {rtol:.0e} (estimated error {err:.0e} <= {tol:g}, against a "
           "run at rtol/10)")
    q = {c.func.__name__: tr.q[c] for c in system.coordinates}
    return Scene("full", "DOP853", rtol, why, err, tr.t, q, tr.nfev + ref.nfev, tr)
