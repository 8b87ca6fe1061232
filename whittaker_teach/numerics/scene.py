"""Motions within a requested error: ``simulate(..., tol=...)`` and ``scene(...)``.

``system.simulate(q0, qdot0, t_span, params, tol=1e-9)`` and
``reduction.simulate(q0, qp0, h, span, params, tol=1e-9)`` ask for a motion
within a relative error ``tol`` (relative to each coordinate's largest value
over the run) and leave the choice of the model and the method to what the
work-precision study (:mod:`.work_precision`, chapter 7) shows.  The
candidates are tried cheapest first:

1. **the exact solution** where one exists (the built-in sledge: the closed
   form (3.15) through Bessel functions; error about 1e-15, a fraction of a
   millisecond for 1000 points, no code generated);
2. **an integration**: for a system, the full model in t (formulation
   ``"auto"``); for a reduction, the reduced model (1.26) in q_eps, since a
   path in q_eps is what was asked (the sledge study of chapter 7 finds the
   full model 1.4-3.3 times cheaper in evaluations down to 1e-12).  The method:
   DOP853, the cheapest by evaluations at every target but one *in the sledge
   study* (an oscillation with no decaying mode), unless the scene is **stiff**
   (:func:`stiffness`): the Jacobian of the right-hand side at the start has a
   mode decaying so fast that DOP853, held by its stability interval
   (h * rate <= 6.39), would spend at least ``STIFF_FLOOR`` evaluations on
   stability alone.  Then LSODA, a switching method (Adams while the motion
   is not stiff, BDF with the Jacobian when it is), runs first, and is kept if
   all its runs together cost fewer evaluations than DOP853's stability floor;
   otherwise DOP853 runs too and the cheaper of the two chosen runs is kept.
   atol tiny, rtol = tol / 10 to start.  The error is *estimated*, not assumed:
   the run is repeated at rtol / 10 and the difference is the estimate; if it
   exceeds ``tol`` the tolerance is tightened, down to scipy's smallest, 2.3e-14
   (the tighter run of a failed pair is the looser of the next: each rtol is run
   once).  Of the accepted pair a full-model integration returns the *tighter*
   run: the estimate is that of the looser run, and the tighter one is normally
   more accurate still, for no extra work (the reduced model still returns the
   looser run, whose error the estimate is).  Its cost is the whole call: both
   runs of every rung tried and the stiffness test (``choice.nfev_all``; each
   evaluation counted once).

If no candidate reaches ``tol``, a ModelError gives the best error available.
The result is the usual :class:`~.results.Trajectory` or :class:`~.results.Path`
with ``choice`` set (a :class:`~.results.Choice`); ``result.explain()`` says
which model and method were picked and why.  ``model="exact"``,
``"full"`` or ``"reduced"`` restricts the choice to one model (a figure that
shows the reduced equation asks for it).

>>> import whittaker_teach as wt
>>> S = wt.examples.sledge()
>>> P = {"m": 1, "J": 1, "k": 1}
>>> tr = S.simulate({"x": 0, "theta": 0.3, "y": 0}, {"x": 1, "theta": 0}, (0, 20), P,
...                 tol=1e-6)
>>> tr.choice.model, tr.method, round(tr(20.0)["theta"], 6)
('exact', 'closed form', 0.122425)
>>> print(tr.explain())
exact model, closed form: estimated relative error 1.0e-15 <= tol 1e-06
why: the closed form (3.15) exists for the sledge: cheaper than any
  integration (no right-hand side evaluated) and exact to rounding

``scene(system, ...)`` is the same choice returned as a :class:`Scene` (given a
reduction, it integrates the reduction's system in time, the cheaper model).
"""

from __future__ import annotations

import math
import textwrap
from dataclasses import dataclass, field
from functools import lru_cache

import numpy as np

from ..errors import ModelError
from . import validate
from .results import Choice, CoordDict, Path, Trajectory

__all__ = ["scene", "Scene", "simulate_within", "stiffness", "Stiffness", "dop853_stability",
           "FLOOR", "MIN_RTOL", "ATOL", "EXACT_ERROR", "STIFF_FLOOR", "STIFF_METHOD"]

#: The smallest relative error the study shows the full model reaching (10 periods).
FLOOR = 1e-13
#: The smallest rtol the package accepts (about 100 machine epsilons).
MIN_RTOL = 2.3e-14
#: atol of every chosen run: tiny, so that the error control is relative.
ATOL = 1e-20
#: The closed form's relative error (the study: 2.1e-15 to 2.4e-15 against 30 digits).
EXACT_ERROR = 1e-15
#: Output points of a closed-form trajectory or path when none are asked for.
POINTS = 1001
#: Evaluations that DOP853's stability limit alone must cost before a scene counts as stiff
#: (and LSODA is tried): below it, stability cannot dominate the cost of any run worth a switch.
STIFF_FLOOR = 1000
#: The method tried on a stiff scene: it switches between non-stiff (Adams) and stiff (BDF).
STIFF_METHOD = "LSODA"


# ----------------------------------------------------------------- the closed form
@lru_cache(maxsize=1)
def _sledge_parts():
    import whittaker_teach as wt
    ref = wt.examples.sledge()
    return ref._L, ref.constraints


def has_closed_form(system):
    """True for the built-in sledge (same Lagrangian and constraint as
    ``examples.sledge()``): its motion is known in closed form (3.15)."""
    if [c.func.__name__ for c in system.coordinates] != ["x", "theta", "y"]:
        return False
    L, cons = _sledge_parts()
    return system._L == L and system.constraints == cons


def _sledge_values(system, q0, params):
    """({name: value} of the coordinates, {name: value} of the parameters), checked."""
    q = validate.initial_values(system, q0, "q0", system.coordinates)
    p = dict(zip((s.name for s in system.parameters),
                 validate.parameter_values(system, params)))
    return {c.func.__name__: val for c, val in q.items()}, p


def _exact_from_time(system, q0, qdot0, params, t0):
    """The SledgeExact through the state (q0, qdot0) at t0, or None (cos theta = 0)."""
    from .exact import SledgeExact
    v = validate.initial_values(system, qdot0, "qdot0", system.independent_coordinates,
                                forbidden=system.dependent_coordinates,
                                why_forbidden="is a dependent coordinate: its velocity "
                                "follows from the constraint (1.3)")
    q, p = _sledge_values(system, q0, params)
    xd, thd = (v[c] for c in system.independent_coordinates)
    th = q["theta"]
    if abs(math.cos(th)) < 1e-8:
        return None
    w = p["k"] / math.sqrt(p["J"])
    return SledgeExact(p, a=math.hypot(th, thd / w), phi=math.atan2(-thd / w, th),
                       C=xd / math.cos(th), x0=q["x"], y0=q["y"], t0=t0)


def _exact_trajectory(system, ex, t_span, t_eval, dense):
    t = (np.linspace(t_span[0], t_span[1], POINTS) if t_eval is None
         else np.asarray(t_eval, dtype=float))
    g = ex(t)
    names = ["x", "theta", "y"]
    q = CoordDict((c, g[n]) for c, n in zip(system.coordinates, names))
    qdot = CoordDict((c, g[n + "dot"]) for c, n in zip(system.coordinates, names))
    E = ex.energy(g)

    def interp(tt):
        gg = ex(tt)
        return [gg[n] for n in names]
    return Trajectory(t, q, qdot, E, float(E[0]), 0, 0, "closed form", "exact (3.15)",
                      list(system.coordinates), interp if dense else None)


def _exact_from_reduced(red, q0, qp0, h, params, t0):
    """The SledgeExact through a reduced state of the sledge in x, or None (no closed form
    for this chart, or the motion reverses x: a >= pi/2)."""
    from .exact import SledgeExact
    S = red.system
    if red._eps.func.__name__ != "x":
        return None
    q, p = _sledge_values(S, q0, params)
    qp = validate.initial_values(S, qp0, "qp0", red._nus)
    thp = next(iter(qp.values()))
    th, h = q["theta"], validate.real(h, "h")
    c = math.cos(th)
    if abs(c) < 1e-8:
        return None
    R = 2 * h - p["k"] ** 2 * th ** 2
    D = p["m"] / c ** 2 + p["J"] * thp ** 2
    if not (R > 0 and D > 0):
        return None                       # the integration reports it (1.12), (1.13)
    xd = red.direction * math.sqrt(R / D)
    w = p["k"] / math.sqrt(p["J"])
    thd = xd * thp
    a = math.hypot(th, thd / w)
    if a >= math.pi / 2 - 1e-6:
        return None                       # x turns back: the reduction meets a turning point
    return SledgeExact(p, a=a, phi=math.atan2(-thd / w, th), C=xd / c, x0=q["x"],
                       y0=q["y"], t0=t0)


def _t_of_x(ex, s):
    """The times at which the exact sledge is at x = s (x monotone: a < pi/2), by Newton."""
    s = np.asarray(s, dtype=float)
    t = ex.t0 + (s - ex.x0) / ex.drift
    for _ in range(60):
        g = ex(t)
        dt = (g["x"] - s) / g["xdot"]
        t = t - dt
        if np.all(np.abs(dt) <= 4e-16 * np.maximum(1.0, np.abs(t))):
            break
    return t


def _exact_path(red, ex, span, dense):
    S = red.system
    s = np.linspace(span[0], span[1], POINTS)
    t = _t_of_x(ex, s)
    g = ex(t)
    names = ["x", "theta", "y"]
    q = CoordDict((c, g[n] if n != "x" else s) for c, n in zip(S.coordinates, names))
    (nu,) = red._nus
    qp = CoordDict([(nu, g["thetadot"] / g["xdot"])])

    def interp(ss):
        ss = np.asarray(ss, dtype=float)
        tt = _t_of_x(ex, np.atleast_1d(ss))
        gg = ex(tt)
        out = CoordDict()
        for c, n in zip(S.coordinates, names):
            v = np.atleast_1d(ss) if n == "x" else gg[n]
            out[c] = float(v[0]) if ss.ndim == 0 else v
        out["t"] = float(tt[0]) if ss.ndim == 0 else tt
        return out
    return Path(s, t, q, qp, ex.h, 0, 0, "closed form", "x", red.direction,
                list(S.coordinates), _dense=interp if dense else None)


# ----------------------------------------------------------------- stiffness
@lru_cache(maxsize=1)
def dop853_stability():
    """(stages, beta): the evaluations per step of scipy's DOP853 and the length of the
    real interval [-beta, 0] on which its stability function R(z) = 1 + z b^T (I - zA)^-1 1
    (from scipy's own tableau) has |R| <= 1: a decaying mode of rate ``lam`` keeps the
    step below beta / lam, or the run blows up.

    >>> stages, beta = dop853_stability()
    >>> stages, round(beta, 2)
    (12, 6.39)
    """
    from scipy.integrate._ivp import dop853_coefficients as dc
    n = dc.N_STAGES
    A, b = np.asarray(dc.A[:n, :n], dtype=float), np.asarray(dc.B, dtype=float)

    def unstable(x):
        z = -x
        return abs(1 + z * b @ np.linalg.solve(np.eye(n) - z * A, np.ones(n))) > 1 + 1e-12
    xs = np.linspace(0.0, 20.0, 20001)
    bad = next(x for x in xs[1:] if unstable(x))
    lo, hi = bad - 1e-3, bad
    for _ in range(50):
        mid = 0.5 * (lo + hi)
        lo, hi = (lo, mid) if unstable(mid) else (mid, hi)
    return n, float(lo)


@dataclass
class Stiffness:
    """What :func:`stiffness` found at the start of a scene: ``rate`` (the fastest decay
    rate, max of -Re(lambda) over the Jacobian's eigenvalues, 0 if none decays),
    ``eigenvalues``, ``floor`` (the evaluations DOP853 must spend over the span to keep
    h * rate inside its stability interval, whatever the tolerance) and ``stiff``
    (floor >= STIFF_FLOOR)."""

    rate: float
    eigenvalues: object
    floor: float
    stiff: bool

    def __str__(self):
        return (f"fastest decay rate at the start {self.rate:.3g}; DOP853's stability floor "
                f"{self.floor:.0f} evaluations: {'stiff' if self.stiff else 'not stiff'}")


def stiffness(system, q0, qdot0, t_span, params):
    """The stiffness test of ``simulate(..., tol=...)``: the eigenvalues of the Jacobian
    of the full model's right-hand side (multiplier or (1.4) form, as ``"auto"``) at the
    initial state, by central differences, and what they cost an explicit method.

    A mode with eigenvalue lambda, Re(lambda) < 0, must be kept stable: DOP853's step
    stays below beta / |Re lambda| (beta = 6.39, :func:`dop853_stability`) even after
    the mode has died out, so the span costs at least 12 rate T / beta evaluations.
    A fast *oscillation* (lambda = +-i omega) gives rate 0: it must be followed step by
    step for accuracy anyway, and is not stiffness.  Only the start is examined: a scene
    that becomes stiff later is not detected (LSODA's own switch would be)."""
    from . import codegen
    from .ivp import as_fun
    t_span = validate.check_span(t_span, "t_span")
    fm = codegen.time_model(system, "auto")
    inp = validate.time_input(system, q0, qdot0, t_span, params, "DOP853", 1e-9, None,
                              "auto", None, None, None, 1e-2)
    y0 = np.asarray(fm.initial_state(inp.q, inp.v, inp.p), dtype=float)
    f = as_fun(fm.rhs, inp.p, len(y0))
    cols = []
    for i in range(len(y0)):
        d = 1e-6 * max(1.0, abs(y0[i]))
        up, down = y0.copy(), y0.copy()
        up[i] += d
        down[i] -= d
        cols.append((f(t_span[0], up) - f(t_span[0], down)) / (2 * d))
    jac = np.array(cols).T
    if not np.all(np.isfinite(jac)):
        return Stiffness(0.0, np.array([]), 0.0, False)
    lam = np.linalg.eigvals(jac)
    rate = max(0.0, float(np.max(-lam.real)))
    stages, beta = dop853_stability()
    floor = stages * rate * abs(t_span[1] - t_span[0]) / beta
    return Stiffness(rate, lam, float(floor), bool(floor >= STIFF_FLOOR))


#: the methods whose ``nfev`` leaves out the evaluations of their difference-quotient
#: Jacobians (scipy's ``num_jac`` calls the right-hand side past the counter); LSODA's
#: ``nfev`` (ODEPACK's NFE) already includes them, and DOP853 forms no Jacobian
JAC_UNCOUNTED = ("Radau", "BDF")


def _cost(res, n, method="DOP853"):
    """Evaluations of one run: nfev, plus n for each Jacobian where scipy leaves the
    difference quotient of n columns out of nfev (:data:`JAC_UNCOUNTED`), so that each
    evaluation of the right-hand side is counted once."""
    extra = n * getattr(res, "njev", 0) if method in JAC_UNCOUNTED else 0
    return res.nfev + extra


# ----------------------------------------------------------------- integrations
def _rel_diff(q1, q2):
    """max over the coordinates of |q1 - q2| / (the coordinate's largest value, at least
    1e-8 of the largest coordinate)."""
    big = max(float(np.max(np.abs(v))) for v in q1.values())
    worst = 0.0
    for c in q1:
        scale = max(float(np.max(np.abs(q1[c]))), 1e-8 * big, 1e-300)
        worst = max(worst, float(np.max(np.abs(np.asarray(q1[c]) - np.asarray(q2[c]))))
                    / scale)
    return worst


def _ladder(tol):
    """rtol = tol/10, then ten times tighter each time, down to 10 MIN_RTOL (whose check
    is a run at MIN_RTOL)."""
    r = min(max(tol / 10, 10 * MIN_RTOL), 1e-3)
    out = [r]
    while r > 10 * MIN_RTOL * 1.0001:
        r = max(r / 10, 10 * MIN_RTOL)
        out.append(r)
    return out


def _integrate(run, compare, tol, model, tried, method="DOP853", n=0, keep_tighter=False):
    """Climb the ladder: the first pair of runs, at rtol r and r/10, whose difference (the
    estimated error of the run at r) is within tol.  Returns (result, its rtol, the
    estimate, (evaluations of the other run of the pair, of every run made)), or (None,
    rtol, best estimate, None) if no rung reaches tol.

    ``run(rtol, check)`` makes one run (``check`` is True for the tighter run of a pair).
    The runs are cached by rtol alone, so the tighter run of a failed rung is the looser
    run of the next one, not made again: every run at a given rtol must be the same run.
    ``keep_tighter``: return the tighter run of the accepted pair (its error is normally
    smaller still than the estimate, which is that of the looser run) instead of the
    looser one; the work is the same, the result more accurate."""
    cache = {}

    def at(r, check):
        if r not in cache:
            cache[r] = run(r, check)
        return cache[r]
    best = None
    for r in _ladder(tol):
        r_ref = max(r / 10, MIN_RTOL)
        res, ref = at(r, False), at(r_ref, True)
        err = compare(res, ref)
        tried.append((model, method, r, err, _cost(res, n, method)))
        if best is None or err < best[2]:
            best = (res, r, err)
        if err <= tol:
            total = sum(_cost(v, n, method) for v in cache.values())
            if keep_tighter:
                return ref, r_ref, err, (_cost(res, n, method), total)
            return res, r, err, (_cost(ref, n, method), total)
    return None, best[1], best[2], None


def _no_model(tol, what, model, rtol, err, method="DOP853"):
    where = f"the {model}, {method} at rtol {rtol:.1e}, against a run at rtol {MIN_RTOL:g}"
    return ModelError(f"no model reaches the relative error {tol:g} for this {what}: the "
                      f"best available is about {err:.1e} ({where}, scipy's smallest); ask "
                      f"for tol >= {2 * err:.0e}")


def _exact_reaches(tol):
    if tol < EXACT_ERROR:
        raise ModelError(f"no model reaches the relative error {tol:g}: the best available "
                         f"is the closed form (3.15), about {EXACT_ERROR:.0e} (rounding)")


def _check_request(tol, model, allowed, method, rtol, atol):
    tol = validate.real(tol, "tol")
    if not 0 < tol < 1:
        raise ModelError(f"tol = {tol:g} must lie in (0, 1): a relative error")
    if model is not None and model not in allowed:
        raise ModelError(f"model = {model!r}: with tol, choose among {', '.join(allowed)} "
                         "(or None: the cheapest that reaches tol)")
    if method not in (None, "DOP853") or rtol not in (None, 1e-9) or atol is not None:
        raise ModelError("pass either tol (the model, the method and rtol are then chosen "
                         "to reach it) or method/rtol/atol, not both")
    return tol


def simulate_within(obj, *args, tol, model=None, method=None, rtol=None, atol=None,
                    **options):
    """``system.simulate(q0, qdot0, t_span, params, tol=...)`` or
    ``reduction.simulate(q0, qp0, h, span, params, tol=...)``: see the module."""
    from ..reduction import Reduction
    if isinstance(obj, Reduction):
        return _reduced_within(obj, *args, tol=tol, model=model, method=method, rtol=rtol,
                               atol=atol, **options)
    return _full_within(obj, *args, tol=tol, model=model, method=method, rtol=rtol,
                        atol=atol, **options)


def _full_within(S, q0, qdot0, t_span, params, *, tol, model, method, rtol, atol,
                 t_eval=None, dense=None, **options):
    tol = _check_request(tol, model, ("exact", "full"), method, rtol, atol)
    if options:
        raise ModelError(f"with tol, the options {', '.join(sorted(options))} are chosen by "
                         "the package (it picks the model, the method and the formulation)")
    t_span = validate.check_span(t_span, "t_span")
    t_eval = validate.check_t_eval(t_eval, t_span)
    if dense is None:
        dense = t_eval is None
    tried = []
    if model in (None, "exact") and has_closed_form(S):
        ex = _exact_from_time(S, q0, qdot0, params, t_span[0])
        if ex is not None:
            _exact_reaches(tol)
            tr = _exact_trajectory(S, ex, t_span, t_eval, dense)
            tr.choice = Choice("exact", "closed form", None, tol, EXACT_ERROR,
                               "the closed form (3.15) exists for the sledge: cheaper than "
                               "any integration (no right-hand side evaluated) and exact to "
                               "rounding")
            return tr
    if model == "exact":
        raise ModelError(f"model='exact': the {S.name} has no closed form in the package "
                         "(only the built-in sledge has one)")
    grid = t_eval if t_eval is not None else np.linspace(t_span[0], t_span[1], POINTS)

    def runner(method):
        def run(r, check):            # the same run whichever of a pair it is: either may be kept
            d = dense if t_eval is not None else True
            return S.simulate(q0, qdot0, t_span, params, method=method, rtol=r, atol=ATOL,
                              t_eval=t_eval, dense=d)
        return run

    def compare(a, b):
        if t_eval is not None:
            return _rel_diff(a.q, b.q)
        return _rel_diff(a(grid), b(grid))
    st = stiffness(S, q0, qdot0, t_span, params)
    n = len(st.eigenvalues) or 2 * len(S.coordinates)              # the state's size
    stages, beta = dop853_stability()
    found = {}
    if st.stiff:
        found[STIFF_METHOD] = _integrate(runner(STIFF_METHOD), compare, tol, "full", tried,
                                         STIFF_METHOD, n, keep_tighter=True)
    lsoda = found.get(STIFF_METHOD)
    if lsoda is None or lsoda[0] is None or lsoda[3][1] > st.floor:
        found["DOP853"] = _integrate(runner("DOP853"), compare, tol, "full", tried,
                                     keep_tighter=True)
    reached = {m: v for m, v in found.items() if v[0] is not None}
    if not reached:
        method, (_, r, err, _) = min(found.items(), key=lambda kv: kv[1][2])
        raise _no_model(tol, S.name, "full model", r, err, method)
    method = min(reached, key=lambda m: (_cost(reached[m][0], n, m), m))
    tr, r, err, counts = reached[method]
    everything = sum(v[3][1] for v in reached.values()) + 2 * n      # + the stiffness test
    closed = ("model='full' was asked; " if model == "full" else
              "" if not has_closed_form(S) else
              "the closed form does not apply here (cos theta = 0 at the start); ")
    lead = (f"{closed or f'no closed form for the {S.name}; '}the full model in t "
            f"({tr.formulation} form)")
    stab = (f"the Jacobian at the start has a mode decaying at rate {st.rate:.3g}, so DOP853, "
            f"whose step must keep h * rate within its stability interval ({beta:.2f}), would "
            f"spend at least {st.floor:.0f} evaluations on stability alone, whatever the "
            f"tolerance (stiff)")
    if method == STIFF_METHOD:
        dop = found.get("DOP853")
        how = (f": {stab}; so {STIFF_METHOD} runs, a switching method: Adams steps while "
               f"the motion is not stiff, BDF steps with the Jacobian while it is (its "
               f"difference-quotient Jacobians are in its count)" + ("" if dop is None else
                                  f", cheaper than DOP853 ({_cost(dop[0], n)} evaluations)"
                                  if dop[0] is not None else ", DOP853 not reaching tol"))
    elif st.stiff:
        cost = ("not reaching tol" if lsoda[0] is None
                else f"{_cost(lsoda[0], n, STIFF_METHOD)} evaluations")
        how = (f": {stab}; but {STIFF_METHOD} cost more ({cost} for its chosen run), so "
               f"DOP853, the cheapest by evaluations in the sledge study")
    else:
        how = (f" with DOP853, the cheapest integration by evaluations in the sledge study "
               f"(chapter 7); not stiff: the fastest decay rate at the start, {st.rate:.2g}, "
               f"costs DOP853's stability at most {st.floor:.0f} evaluations over the span "
               f"(below {STIFF_FLOOR})")
    tr.choice = Choice("full", method, r, tol, err, (
        f"{lead}{how}; rtol {10 * r:.1e} is the loosest whose run differs from the one at "
        f"rtol/10 by no more than tol (the estimated error of the looser run); the run "
        f"returned is the tighter one, at rtol {r:.1e}, more accurate still for the same "
        f"work ({everything} evaluations in all, with the {2 * n} of the stiffness test)"),
        tried, counts[0], st, everything)
    if not dense and t_eval is None:
        tr._dense = None
    return tr


#: the options of Reduction.simulate that a run with tol passes on
REDUCED_OPTIONS = ("on_turning_point", "turning_tol", "t0", "max_switches", "max_bridge_time")


def _reduced_within(red, q0, qp0, h, span, params, *, tol, model, method, rtol, atol,
                    dense=True, **options):
    tol = _check_request(tol, model, ("exact", "reduced"), method, rtol, atol)
    bad = sorted(set(options) - set(REDUCED_OPTIONS))
    if bad:
        raise ModelError(f"unknown option(s) {', '.join(bad)} of the reduced model (it takes "
                         f"{', '.join(REDUCED_OPTIONS)}, dense)")
    S = red.system
    span = validate.check_span(span, "span")
    tried = []
    if model in (None, "exact") and has_closed_form(S):
        ex = _exact_from_reduced(red, q0, qp0, h, params, options.get("t0", 0.0))
        if ex is not None:
            q = validate.initial_values(S, q0, "q0", S.coordinates)
            if abs(span[0] - q[red._eps]) > 1e-12 * max(1.0, abs(span[0])):
                raise ModelError(f"span starts at x = {span[0]} but q0[x] = {q[red._eps]}")
            if (span[1] - span[0]) * red.direction < 0:
                raise ModelError(f"span {span} runs against the direction "
                                 f"{red.direction:+d} of the reduction")
            _exact_reaches(tol)
            path = _exact_path(red, ex, span, dense)
            path.choice = Choice("exact", "closed form", None, tol, EXACT_ERROR,
                                 "the closed form (3.15) exists for the sledge; along x it "
                                 "is evaluated at t(x), found by Newton's method on x(t) "
                                 "(x is monotone: amplitude below pi/2)")
            return path
    if model == "exact":
        raise ModelError(f"model='exact': no closed form for this reduction of the "
                         f"{S.name} (only the sledge in x with amplitude below pi/2)")
    grid = np.linspace(span[0], span[1], POINTS)

    def run(r, check):
        return red.simulate(q0, qp0, h, span, params, method="DOP853", rtol=r, atol=ATOL,
                            dense=True, **options)

    def compare(a, b):
        if a._dense is not None and b._dense is not None:
            pa, pb = a(grid), b(grid)
            keys = [c for c in S.coordinates] + ["t"]
            return _rel_diff({k: pa[k] for k in keys}, {k: pb[k] for k in keys})
        return _rel_diff({c: a.q[c][-1:] for c in S.coordinates} | {"t": a.t[-1:]},
                         {c: b.q[c][-1:] for c in S.coordinates} | {"t": b.t[-1:]})
    path, r, err, counts = _integrate(run, compare, tol, "reduced", tried)
    if path is None:
        raise _no_model(tol, f"reduction of the {S.name}", "reduced model", r, err)
    e = red._eps.func.__name__
    closed = ("the closed form does not apply here (the amplitude reaches pi/2, or q_eps "
              "is not x); " if has_closed_form(S) else "")
    lead = (f"model='reduced' was asked: the reduced model (1.26) runs in {e}"
            if model == "reduced" else
            f"{closed}a path in {e} is asked, so the reduced model (1.26) runs (the sledge "
            "study finds the full model in t 1.4-3.3 times cheaper by evaluations down to "
            "1e-12: system.simulate(..., tol=...) for a motion in t)")
    path.choice = Choice("reduced", "DOP853", r, tol, err, (
        f"{lead}; DOP853 (the cheapest in the sledge study; the reduced model is not "
        f"tested for stiffness), rtol "
        f"{r:.1e}, the loosest whose estimated error (against a run at rtol/10"
        f"{'' if path._dense is not None else ', compared at the end point'}) is within "
        f"tol ({counts[1]} evaluations in all)"), tried, counts[0], None, counts[1])
    if not dense:
        path._dense = None
    return path


# ----------------------------------------------------------------- scene
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


def scene(system, q0, qdot0, t_span, params, tol=1e-6, *, points=1001):
    """The cheapest model and method the study shows reaching ``tol``, as a :class:`Scene`
    at ``points`` equally spaced times; see the module."""
    from ..reduction import Reduction
    note = ""
    if isinstance(system, Reduction):
        note = (f"given the reduction in {system._eps.func.__name__}: the sledge study finds "
                "the reduced model needs 1.4-3.3x the full model's evaluations, so the full "
                "model runs; ")
        system = system.system
    t_span = validate.check_span(t_span, "t_span")
    t_eval = np.linspace(t_span[0], t_span[1], points)
    tr = simulate_within(system, q0, qdot0, t_span, params, tol=tol, t_eval=t_eval, dense=True)
    c = tr.choice
    q = {k.func.__name__: tr.q[k] for k in system.coordinates}
    if c.model == "exact":
        return Scene("exact", "closed form", None, note + "exact solution (3.15): a closed "
                     "form exists for the sledge (error ~1e-15)", EXACT_ERROR, tr.t, q, 0,
                     lambda tt: _named(tr(tt)))
    nfev = tr.nfev + c.check_nfev
    return Scene("full", c.method, c.rtol, note + c.why, c.error, tr.t, q, nfev,
                 lambda tt: _named(tr(tt)))


def _named(d):
    return {(k if isinstance(k, str) else k.func.__name__): v for k, v in d.items()}
