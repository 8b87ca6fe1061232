"""Speed against error: a work-precision study of the full, reduced and exact models.

``python -m whittaker_teach bench numerics [--quick] [--json FILE] [--csv FILE]
[--plot FILE] [--quiet]``

The sledge (m = J = k = C = 1, so omega = 1) at two amplitudes, a small one
and one near pi/2, over 10 periods from theta = a cos(phi), phi = 0.3.

**The run set is fixed.**  Every (model, method) runs down a ladder of
tolerances ``rtol`` = 1e-3, 1e-5, 1e-7, 1e-9, 1e-10, ..., 1e-13 and 2.3e-14
(the smallest the package accepts), with ``atol`` = :data:`ATOL` (tiny: the error control is
relative in every component).  A (model, method) stops going tighter after a
run that needed more than :data:`NFEV_BUDGET` right-hand-side evaluations, once
it has reached the tightest target of :data:`TARGETS`; a ladder over the budget
that has not reached it goes on until it does, or until a run needs more than
:data:`NFEV_CAP` evaluations, and the summary then says "not reached within
budget" (a budget cut never makes a looser run stand in for a tighter one).
Budgets in evaluations, the same on every machine, never in seconds.

Below that, the method ``DOP853-tight`` (DOP853 with rtol allowed below
scipy's floor of 100 machine epsilons, :class:`.ivp.TightDOP853`) continues the
ladders of the full, full (1.4) and reduced models with :data:`TIGHT_RTOLS`
(1e-14 down to 5e-16), within its own budget of :data:`TIGHT_NFEV_BUDGET`
evaluations: it shows where the error floor of each model lies
when the tolerance no longer sets it (``tight=False`` leaves it out; the
quick study does).

**The error** of a run is measured at its own steps against the exact
solution, per component and relative to the component's scale: theta against
the amplitude a, x and y against their largest exact values over the run, t
(recovered by the reduced model) against the length of the run.  ``error`` is
the largest of the four: the error of the state at the same time.

**The path error** ``err_path`` is the distance of the run's points from the
exact path in the same scaled coordinates (x, theta, y, t): each point is
compared with the nearest point of the exact motion instead of the exact state
at the run's own time.  An error along the path (a clock running slightly fast
or slow) counts once, in t, where the state error counts it in every component:
the reduced model integrates in x and recovers t(x) by quadrature, so a clock
error dt shifts its theta by thetadot dt and its y by ydot dt as well.  Both
floors are reported (:func:`floors`).

**The cost** is the number of right-hand-side evaluations (machine
independent) and the median wall time of :data:`REPEAT` runs, the repeats
interleaved: the whole run set is timed once, then again, and so on, so that
a burst of load on the machine spreads over all runs instead of hitting one.
The package / hand-written ratio for each target is measured apart: the cheapest
run (by evaluations) of the package's full model and of the hand-written version of
the same equations that reach the target are timed again, alternately,
:data:`RATIO_REPEAT` times each, and the ratio is that of their medians (a run
of a few milliseconds varies by 10-20 % from one timing to the next: three
repeats are enough to rank runs, not to compare two of them).

Models:

* ``full``: the default formulation (``"auto"``: the multiplier form for the
  sledge, regular at cos(theta) = 0), in t;
* ``full (1.4)``: the paper's Chaplygin form (1.4), a labelled alternative;
* ``reduced``: the generalized Whittaker equation (1.26) in x, with t(x) and
  y(x) by quadrature alongside;
* ``DLA``: the fixed-step discrete Lagrange-d'Alembert integrator (setting:
  steps per period);
* ``numpy+scipy``: the same equations as ``full``, hand-written with NumPy and
  passed to ``scipy.integrate.solve_ivp`` with the package's stepper for the
  explicit methods (the yardstick for the overhead of the package's right-hand
  sides);
* ``exact``: the closed form, evaluated on 1000 points: the cost limit.

Every right-hand side is generated before the clock starts.

>>> res = study(quick=True, amplitudes=(0.3,), methods=("DOP853",), rtols=(1e-6,),
...             dla_steps=(), periods=1, repeat=1, alternatives=False)
>>> sorted({r["model"] for r in res["runs"]})
['exact', 'full', 'numpy+scipy', 'reduced']
"""

from __future__ import annotations

import csv
import io
import json
import math
import statistics
import sys
import time

import numpy as np

from ..errors import ModelError

__all__ = ["study", "cheapest", "floors", "table", "summary", "summary_rows", "plot", "main",
           "to_csv", "handwritten_full", "AMPLITUDES", "METHODS", "RTOLS", "TARGETS", "ATOL",
           "NFEV_BUDGET", "NFEV_CAP", "TIGHT_NFEV_BUDGET", "MODELS", "TIGHT", "TIGHT_RTOLS"]

AMPLITUDES = (0.3, 1.5)
METHODS = ("RK45", "DOP853", "Radau", "LSODA")
#: the hand-written yardstick and the alternative formulation run these only (the
#: cheapest methods of the full model)
SHORT_METHODS = ("DOP853", "LSODA")
RTOLS = (1e-3, 1e-5, 1e-7, 1e-9, 1e-10, 1e-11, 1e-12, 1e-13, 2.3e-14)
#: DOP853 below scipy's rtol floor (:class:`.ivp.TightDOP853`), and its ladder
TIGHT = "DOP853-tight"
#: timings of each side of a package / hand-written comparison (alternately)
RATIO_REPEAT = 15
TIGHT_RTOLS = (1e-14, 5e-15, 2e-15, 1e-15, 5e-16)
#: the models whose ladders DOP853-tight continues
TIGHT_MODELS = ("full", "full (1.4)", "reduced")
#: atol for every run: tiny, so that the error control is relative in every component
ATOL = 1e-20
DLA_STEPS = (16, 32, 64, 128, 256, 512)
TARGETS = (1e-6, 1e-9, 1e-12)
PARAMS = {"m": 1.0, "J": 1.0, "k": 1.0}
PHI, C = 0.3, 1.0
#: A (model, method) stops going to tighter tolerances after a run with more evaluations,
#: once it has reached the tightest target
NFEV_BUDGET = 30_000
#: ... and after a run with more evaluations than this, whatever it reached
NFEV_CAP = 120_000
#: the budget of the DOP853-tight ladders, whose purpose is the floor: near pi/2 the
#: reduced model needs about 47 000 evaluations at rtol 1e-14 and 130 000 at 5e-16
TIGHT_NFEV_BUDGET = 150_000
REPEAT = 3
PERIODS = 10
MODELS = ("full", "full (1.4)", "reduced", "DLA", "numpy+scipy", "exact")

#: ``--quick``: 5 periods, four tolerances, no Radau (the slowest), 3 interleaved repeats
QUICK = {"periods": 5, "rtols": (1e-4, 1e-7, 1e-10, 1e-13), "dla_steps": (32, 128),
         "repeat": 3, "methods": ("RK45", "DOP853", "LSODA"), "tight": False}


# ----------------------------------------------------------------- the errors
def _t_of_x(ex, x, t_guess):
    """The exact time at which the sledge is at x (x monotone: a < pi/2), by Newton."""
    t = np.array(t_guess, dtype=float)
    for _ in range(6):
        e = ex(t)
        t = t - (e["x"] - x) / e["xdot"]
    return t


def _errors(ex, T, t, q, x_scale, y_scale, reduced=False):
    """Per-component relative errors at the run's points."""
    t = np.asarray(t)
    e = ex(t)
    out = {"err_theta": float(np.max(np.abs(np.asarray(q["theta"]) - e["theta"]))) / ex.a,
           "err_x": float(np.max(np.abs(np.asarray(q["x"]) - e["x"]))) / x_scale,
           "err_y": float(np.max(np.abs(np.asarray(q["y"]) - e["y"]))) / y_scale,
           "err_t": 0.0}
    if reduced:
        tx = _t_of_x(ex, np.asarray(q["x"]), t)
        out["err_t"] = float(np.max(np.abs(t - tx))) / T
    return out


def _path_error(ex, T, t, q, x_scale, y_scale):
    """The largest distance of the run's points (x, theta, y, t), scaled as the errors
    are, from the exact path: the nearest exact point of each, by three Gauss-Newton
    steps along the path from the exact point at the run's own time.

    >>> import whittaker_teach as wt
    >>> ex = wt.examples.sledge_exact(PARAMS, a=0.3, phi=PHI, C=C)
    >>> t = np.linspace(0, 5, 6); g = ex(t + 1e-6)      # the right path, a late clock
    >>> 0.9 < _path_error(ex, 5.0, t, g, 5.0, 1.0) / (1e-6 / 5.0) <= 1.0     # at most dt / T
    True
    """
    t = np.asarray(t, dtype=float)
    point = np.array([q["x"], q["theta"], q["y"], t], dtype=float).T
    scale = np.array([x_scale, ex.a, y_scale, T])
    s = t.copy()
    for _ in range(3):
        e = ex(s)
        r = (point - np.array([e["x"], e["theta"], e["y"], s]).T) / scale
        d = np.array([e["xdot"], e["thetadot"], e["ydot"], np.ones_like(s)]).T / scale
        s = s + (r * d).sum(axis=1) / (d * d).sum(axis=1)
    e = ex(s)
    r = (point - np.array([e["x"], e["theta"], e["y"], s]).T) / scale
    return float(np.sqrt((r * r).sum(axis=1)).max())


def _scales(ex, T):
    g = ex(np.linspace(0, T, 4001))
    return float(np.max(np.abs(g["x"]))), float(np.max(np.abs(g["y"])))


# ----------------------------------------------------------------- the yardstick
def handwritten_full(k=1.0, J=1.0):
    """The sledge's multiplier form written by hand with NumPy, for ``solve_ivp``:
    state (x, theta, y, xdot, thetadot, ydot); the multiplier of the cleared
    constraint ydot cos(theta) - xdot sin(theta) = 0 is lambda/m = thetadot
    (xdot cos(theta) + ydot sin(theta)).

    >>> f = handwritten_full()
    >>> [round(float(v), 4) for v in f(0.0, np.array([0, 0.5, 0, 1, 0.2, 0.5]))][3:]
    [-0.1071, -0.5, 0.1961]
    """
    w2 = k * k / J

    def f(t, u):
        x, th, y, xd, thd, yd = u
        s, c = np.sin(th), np.cos(th)
        lam = thd * (xd * c + yd * s)
        return np.array([xd, thd, yd, -lam * s, -w2 * th, lam * c])
    return f


# ----------------------------------------------------------------- one run
class _Case:
    """One amplitude: the exact motion, the starting states, the scales."""

    def __init__(self, S, red, a, periods):
        import whittaker_teach as wt
        self.S, self.red, self.a = S, red, a
        self.ex = wt.examples.sledge_exact(PARAMS, a=a, phi=PHI, C=C)
        self.T = periods * self.ex.period
        self.q0, self.qd0 = self.ex.initial()
        self.rq0, self.qp0, self.h = self.ex.reduced_initial()
        self.x_end = self.ex(self.T)["x"]
        self.x_scale, self.y_scale = _scales(self.ex, self.T)
        s = self.ex(0.0)
        self.u0 = np.array([s["x"], s["theta"], s["y"], s["xdot"], s["thetadot"], s["ydot"]])
        self.hand = handwritten_full()

    def runner(self, model, method, setting):
        """A function doing the run, returning (t, q dict, nfev, njev, energy error)."""
        S, P = self.S, PARAMS
        if model in ("full", "full (1.4)"):
            form = "auto" if model == "full" else "chaplygin"

            def go():
                tr = S.simulate(self.q0, self.qd0, (0, self.T), P, method=method,
                                rtol=setting, atol=ATOL, dense=False, formulation=form)
                return tr.t, tr.q, tr.nfev, tr.njev, tr.energy_error
            S.simulate(self.q0, self.qd0, (0, self.T / 50), P, method=method, formulation=form)
            return go
        if model == "reduced":
            def go():
                p = self.red.simulate(self.rq0, self.qp0, self.h, (self.rq0["x"], self.x_end),
                                      P, method=method, rtol=setting, atol=ATOL, dense=False)
                return p.t, p.q, p.nfev, p.njev, None
            self.red.simulate(self.rq0, self.qp0, self.h, (self.rq0["x"], self.rq0["x"] + 0.1),
                              P, method=method)
            return go
        if model == "DLA":
            dt = self.ex.period / setting

            def go():
                tr = S.simulate(self.q0, self.qd0, (0, self.T), P, method="DLA", dt=dt,
                                dense=False)
                return tr.t, tr.q, tr.nfev, tr.njev, tr.energy_error
            S.simulate(self.q0, self.qd0, (0, dt), P, method="DLA", dt=dt)
            return go
        if model == "numpy+scipy":
            from scipy.integrate import solve_ivp

            from .portable import PORTABLE
            # the package's stepper for the explicit methods (scipy's, with portable sums:
            # see numerics.portable), so that the comparison is of the right-hand sides
            stepper = PORTABLE.get(method, method)

            def go():
                sol = solve_ivp(self.hand, (0, self.T), self.u0, method=stepper, rtol=setting,
                                atol=ATOL)
                if sol.status != 0:
                    raise ModelError(f"solve_ivp failed: {sol.message}")
                q = {"x": sol.y[0], "theta": sol.y[1], "y": sol.y[2]}
                return sol.t, q, sol.nfev, sol.njev, None
            return go
        grid = np.linspace(0, self.T, 1000)

        def go():
            g = self.ex(grid)
            return grid, g, 0, 0, None
        return go

    def judge(self, model, out):
        t, q, nfev, njev, dE = out
        errs = _errors(self.ex, self.T, t, q, self.x_scale, self.y_scale,
                       reduced=model == "reduced")
        path = _path_error(self.ex, self.T, t, q, self.x_scale, self.y_scale)
        return {**errs, "err_energy": dE, "nfev": int(nfev), "njev": int(njev),
                "points": int(len(t)), "error": max(errs.values()), "err_path": path}


def _exact_error(ex, T, n=4):
    """The closed form against mpmath quadrature at 30 digits at n instants (absolute)."""
    import mpmath as mp
    worst = 0.0
    with mp.workdps(30):
        a, phi, w = mp.mpf(ex.a), mp.mpf(ex.phi), mp.mpf(ex.omega)
        for t in np.linspace(T / n, T, n):
            pts = mp.linspace(0, mp.mpf(t), 2 * int(t * ex.omega / math.pi) + 3)
            x = mp.quad(lambda s: ex.C * mp.cos(a * mp.cos(w * s + phi)), pts)
            y = mp.quad(lambda s: ex.C * mp.sin(a * mp.cos(w * s + phi)), pts)
            got = ex(float(t))
            worst = max(worst, abs(got["x"] - float(x)), abs(got["y"] - float(y)))
    return worst


def exact_errors(rec, abs_error, x_scale, y_scale):
    """The exact solution's errors: its largest absolute error in x and y against a
    30-digit mpmath quadrature (:func:`_exact_error`), relative to their scales."""
    rec["err_x_abs"] = abs_error
    rec["err_x"], rec["err_y"] = abs_error / x_scale, abs_error / y_scale
    rec["error"] = max(rec["err_theta"], rec["err_x"], rec["err_y"], rec["err_t"])
    rec["err_path"] = rec["error"]          # the closed form's clock is exact


# ----------------------------------------------------------------- the run set
def _ladder(amplitudes, methods, rtols, dla_steps, alternatives, tight=False):
    """[(a, model, method, [settings])]: every (model, method) with its ladder."""
    out = []
    for a in amplitudes:
        for m in methods:
            out.append((a, "full", m, list(rtols)))
        if tight:
            out.append((a, "full", TIGHT, list(TIGHT_RTOLS)))
        if alternatives:
            for m in SHORT_METHODS:
                if m in methods:
                    out.append((a, "full (1.4)", m, list(rtols)))
            if tight:
                out.append((a, "full (1.4)", TIGHT, list(TIGHT_RTOLS)))
        for m in methods:
            out.append((a, "reduced", m, list(rtols)))
        if tight:
            out.append((a, "reduced", TIGHT, list(TIGHT_RTOLS)))
        for m in methods:
            if m in SHORT_METHODS:
                out.append((a, "numpy+scipy", m, list(rtols)))
        if dla_steps:
            out.append((a, "DLA", "DLA", list(dla_steps)))
        out.append((a, "exact", "closed form", [None]))
    return out


def study(quick=False, progress=True, amplitudes=AMPLITUDES, methods=None, rtols=None,
          dla_steps=None, periods=None, repeat=None, alternatives=True, tight=None):
    """Run the study: {"meta": ..., "runs": [record, ...], "exact_cost": ...}.

    First pass: every run of the fixed set once (errors, evaluations; the
    evaluation budget cuts a ladder); then ``repeat`` timing passes over the
    same runs in the same order; each run's ``seconds`` is the median."""
    import whittaker_teach as wt
    cfg = QUICK if quick else {"periods": PERIODS, "rtols": RTOLS, "dla_steps": DLA_STEPS,
                               "repeat": REPEAT, "methods": METHODS, "tight": True}
    tight = cfg.get("tight", False) if tight is None else tight
    methods = cfg["methods"] if methods is None else methods
    periods = cfg["periods"] if periods is None else periods
    rtols = cfg["rtols"] if rtols is None else rtols
    dla_steps = cfg["dla_steps"] if dla_steps is None else dla_steps
    repeat = cfg["repeat"] if repeat is None else repeat
    S = wt.examples.sledge()
    red = S.reduce("x", +1)
    cases = {a: _Case(S, red, a, periods) for a in amplitudes}
    ladder = _ladder(amplitudes, methods, rtols, dla_steps, alternatives, tight)
    bar = _progress(sum(len(s) for *_, s in ladder) * (1 + repeat), progress)
    runs, fns = [], []
    for a, model, method, settings in ladder:
        case = cases[a]
        for setting in settings:
            bar.set_description(f"a={a:g} {model} {method} {setting or ''}")
            rec = {"amplitude": a, "model": model, "method": method, "setting": setting}
            try:
                fn = case.runner(model, method, setting)
                rec.update(case.judge(model, fn()))
            except ModelError as err:   # e.g. a loose run wandering into a turning point
                rec["failed"] = f"{type(err).__name__}: {err}"
                runs.append(rec)
                bar.update(1 + repeat)
                continue
            rec["times"] = []
            runs.append(rec)
            fns.append((rec, fn))
            bar.update()
            if _ladder_ends(rec, method):
                bar.update((1 + repeat) * (len(settings) - settings.index(setting) - 1))
                break
    for _ in range(repeat):                 # interleaved: pass after pass over the set
        for rec, fn in fns:
            t0 = time.perf_counter()
            fn()
            rec["times"].append(time.perf_counter() - t0)
            bar.update()
    bar.close()
    costs = {}
    for rec in runs:
        if "failed" in rec:
            continue
        rec["seconds"] = statistics.median(rec["times"]) if rec["times"] else float("nan")
        if rec["model"] == "exact":
            case = cases[rec["amplitude"]]
            exact_errors(rec, _exact_error(case.ex, case.T), case.x_scale, case.y_scale)
            costs[str(rec["amplitude"])] = {"grid1000": rec["seconds"]}
    meta = _meta(periods, repeat, amplitudes, rtols)
    meta["tight_rtols"] = list(TIGHT_RTOLS) if tight else []
    results = {"meta": meta, "runs": runs, "exact_cost": costs}
    meta["ratio_repeat"] = RATIO_REPEAT if repeat > 1 else repeat
    results["ratios"] = (_paired_ratios(results, {id(rec): fn for rec, fn in fns},
                                        meta["ratio_repeat"]) if repeat > 0 else {})
    return results


def _ladder_ends(rec, method):
    """Whether a ladder stops after this run: over its budget and at the tightest
    target (DOP853-tight, whose purpose is the floor: over its own budget), or
    over :data:`NFEV_CAP` whatever it reached."""
    if method == TIGHT:
        return rec["nfev"] > TIGHT_NFEV_BUDGET
    return rec["nfev"] > NFEV_CAP or (rec["nfev"] > NFEV_BUDGET
                                      and rec["error"] <= min(TARGETS))


def _paired_ratios(results, fn_of, repeat):
    """{amplitude: {target: {"package", "hand", "ratio", "runs"}}}: the package's full
    model (the same equations as the hand-written version) and the hand-written
    version, each in its cheapest run reaching the target by evaluations (the
    study's own choice, the same on every machine), timed again alternately
    ``repeat`` times each; the medians and their ratio."""
    best = cheapest(results)
    out = {}
    for a, per in best.items():
        out[str(a)] = {}
        for tgt, row in per.items():
            pk, hw = row.get("full"), row.get("numpy+scipy")
            if tgt == "floor" or not pk or not hw:
                continue
            fp, fh = fn_of[id(pk)], fn_of[id(hw)]
            tp, th = [], []
            for _ in range(repeat):
                t0 = time.perf_counter()
                fp()
                tp.append(time.perf_counter() - t0)
                t0 = time.perf_counter()
                fh()
                th.append(time.perf_counter() - t0)
            mp_, mh = statistics.median(tp), statistics.median(th)
            out[str(a)][f"{tgt:.0e}"] = {
                "package": mp_, "hand": mh, "ratio": mp_ / mh,
                "runs": [[pk["model"], pk["method"], pk["setting"]],
                         [hw["model"], hw["method"], hw["setting"]]]}
    return out


class _NoBar:
    def set_description(self, *_):
        pass

    def update(self, *_):
        pass

    def close(self):
        pass


class _LogBar(_NoBar):
    """Progress as a line every 10%, for a log file."""

    def __init__(self, total):
        self.total, self.n, self.next = total, 0, 0.1

    def update(self, k=1):
        self.n += k
        if self.n >= self.next * self.total:
            print(f"  {self.n}/{self.total} runs", file=sys.stderr, flush=True)
            self.next += 0.1


def _progress(total, enabled):
    if not enabled:
        return _NoBar()
    if not sys.stderr.isatty():
        return _LogBar(total)
    try:
        from tqdm import tqdm
    except ImportError:
        return _NoBar()
    return tqdm(total=total, unit="run", file=sys.stderr, leave=False)


def _meta(periods, repeat, amplitudes, rtols):
    import platform

    import scipy
    return {"system": "sledge", "params": PARAMS, "C": C, "phi": PHI, "periods": periods,
            "amplitudes": list(amplitudes), "repeat": repeat, "rtols": list(rtols),
            "atol": ATOL, "nfev_budget": NFEV_BUDGET, "nfev_cap": NFEV_CAP,
            "tight_nfev_budget": TIGHT_NFEV_BUDGET,
            "python": platform.python_version(), "numpy": np.__version__,
            "scipy": scipy.__version__, "machine": platform.machine(),
            "error": "max over the run's points of |theta - exact|/a, |x - exact|/max|x|, "
                     "|y - exact|/max|y|, |t - exact|/T"}


# ----------------------------------------------------------------- reading the results
def _done(results):
    """The runs that finished (a run may fail with a ModelError, recorded as such)."""
    return [r for r in results["runs"] if "failed" not in r]


def run_set(results):
    """The identity of every run, in order: (amplitude, model, method, setting)."""
    return [(r["amplitude"], r["model"], r["method"], r["setting"]) for r in results["runs"]]


def floors(results, measure="error"):
    """{amplitude: {model: the run with the smallest error}}; ``measure="err_path"``: the
    smallest distance from the exact path instead (see the module's docstring)."""
    out = {}
    for a in results["meta"]["amplitudes"]:
        out[a] = {}
        for model in MODELS:
            rs = [r for r in _done(results) if r["amplitude"] == a and r["model"] == model
                  and measure in r]
            out[a][model] = min(rs, key=lambda r: (r[measure], r["nfev"])) if rs else None
    return out


def cheapest(results, targets=TARGETS, by="nfev"):
    """{amplitude: {target: {model: record or None}}}: the cheapest run of each model whose
    error is within the target, by evaluations (``by="nfev"``, the same on every
    machine; ties go to the shorter time) or by ``"seconds"``.  The target
    ``"floor"`` holds each model's most accurate run."""
    out = {}
    fl = floors(results)
    key = ((lambda r: (r["nfev"], r["seconds"])) if by == "nfev"
           else (lambda r: (r["seconds"], r["nfev"])))
    for a in results["meta"]["amplitudes"]:
        per = {}
        for tgt in targets:
            row = {}
            for model in MODELS:
                ok = [r for r in _done(results) if r["amplitude"] == a
                      and r["model"] == model and r["error"] <= tgt]
                row[model] = min(ok, key=key) if ok else None
            per[tgt] = row
        per["floor"] = dict(fl[a])
        out[a] = per
    return out


def picks(results, targets=TARGETS):
    """The cheapest-by-evaluations picks as plain tuples (for comparing two runs)."""
    best = cheapest(results, targets)
    return {(a, str(t), m): (r["method"], r["setting"]) if r else None
            for a, per in best.items() for t, row in per.items() for m, r in row.items()}


def _setting(r):
    s = r["setting"]
    if s is None:
        return ""
    return f"{s}/period" if r["model"] == "DLA" else f"{s:.1e}" if s < 1e-13 else f"{s:.0e}"


def table(results):
    """Every run as a text table (86 columns), one block per amplitude: the errors of the
    state per component, the distance from the exact path, the cost."""
    lines = []
    head = (f"{'model':11s} {'method':12s} {'setting':>10s} {'theta':>6s} {'x':>6s} "
            f"{'y':>6s} {'t':>6s} {'path':>6s} {'nfev':>6s} {'ms':>7s}")
    for a in results["meta"]["amplitudes"]:
        lines += [f"amplitude a = {a:g} (errors relative to each component's scale)", head]
        for r in results["runs"]:
            if r["amplitude"] != a:
                continue
            meth = r["method"] if r["model"] != "exact" else "-"
            if "failed" in r:
                lines.append(f"{r['model']:11s} {meth:12s} {_setting(r):>10s}  failed: "
                             f"{r['failed'][:40]}")
                continue
            lines.append(f"{r['model']:11s} {meth:12s} {_setting(r):>10s} "
                         f"{r['err_theta']:6.0e} {r['err_x']:6.0e} {r['err_y']:6.0e} "
                         f"{r['err_t']:6.0e} {r.get('err_path', math.nan):6.0e} "
                         f"{r['nfev']:6d} {1e3 * r['seconds']:7.1f}")
        lines.append("")
    return "\n".join(lines)


def summary_rows(results, targets=TARGETS):
    """The summary as rows: (a, target, model, method, setting, error, nfev, ms)."""
    best = cheapest(results, targets)
    rows = []
    for a, per in best.items():
        for tgt, row in per.items():
            for model in MODELS:
                r = row[model]
                rows.append((a, tgt, model, r["method"] if r else None,
                             _setting(r) if r else None, r["error"] if r else None,
                             r["nfev"] if r else None, 1e3 * r["seconds"] if r else None))
    return rows


def _cut(results, a, model):
    """Whether a ladder of this model at this amplitude was stopped by :data:`NFEV_CAP`
    before reaching the tightest target."""
    cap = results["meta"].get("nfev_cap", NFEV_CAP)
    return any(r["amplitude"] == a and r["model"] == model and r["method"] != TIGHT
               and r["nfev"] > cap and r["error"] > min(TARGETS) for r in _done(results))


def _ratio(results, a, tgt):
    """package / hand-written for a target, from the paired re-timing
    (:func:`_paired_ratios`), or None."""
    paired = results.get("ratios", {}).get(str(a), {}).get(f"{tgt:.0e}")
    return paired["ratio"] if paired else None


def summary(results, targets=TARGETS):
    """The cheapest run of every model for each target and the floor (80 columns)."""
    best = cheapest(results, targets)
    lines = []
    for a, per in best.items():
        lines.append(f"a = {a:g}: cheapest run (by evaluations) with error <= target")
        for tgt, row in per.items():
            name = "floor (smallest error reached)" if tgt == "floor" else f"error {tgt:.0e}"
            lines.append(f"  {name}")
            for model in MODELS:
                r = row[model]
                if r is None:
                    cut = " within budget" if _cut(results, a, model) else ""
                    lines.append(f"    {model:11s} not reached{cut}")
                    continue
                meth = "" if model == "exact" else f"{r['method']} {_setting(r)}"
                lines.append(f"    {model:11s} {meth:20s} err {r['error']:7.1e}  nfev "
                             f"{r['nfev']:6d}  {1e3 * r['seconds']:8.2f} ms")
            ratio = _ratio(results, a, tgt) if tgt != "floor" else None
            if ratio is not None:
                n = results["meta"]["ratio_repeat"]
                lines.append(f"    package / numpy+scipy (full model, timed {n} times "
                             f"alternately): {ratio:.2f}")
        path = floors(results, "err_path")[a]
        if any(path.values()):
            lines.append("  floor by distance from the exact path (a clock error counted once)")
            for model in MODELS:
                r = path[model]
                if r is not None:
                    meth = "" if model == "exact" else f"{r['method']} {_setting(r)}"
                    lines.append(f"    {model:11s} {meth:20s} path {r['err_path']:7.1e}  "
                                 f"(state {r['error']:7.1e})")
        lines.append("")
    return "\n".join(lines)


def to_csv(results):
    """Every run as CSV text (one row per run, the failed ones included)."""
    cols = ["amplitude", "model", "method", "setting", "error", "err_theta", "err_x", "err_y",
            "err_t", "err_path", "err_energy", "nfev", "njev", "points", "seconds", "failed"]
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(cols)
    for r in results["runs"]:
        w.writerow(["" if r.get(c) is None else r.get(c) for c in cols])
    return buf.getvalue()


# ----------------------------------------------------------------- the figure
STYLE = {"full": ("-", "o"), "full (1.4)": ((0, (1, 1)), "D"), "reduced": ("--", "s"),
         "DLA": (":", "^"), "numpy+scipy": ((0, (5, 2, 1, 2)), "x"), "exact": ("", "*")}
LABEL = {"full": "full model (default form), in t", "full (1.4)": "full model, paper's (1.4)",
         "reduced": "reduced (1.26), in x", "DLA": "DLA (fixed step)",
         "numpy+scipy": "hand-written numpy + scipy", "exact": "exact (1000 points): the limit"}


def plot(results, path=None, targets=TARGETS, cost="nfev"):
    """Log-log relative error against the cost of each run, one panel per amplitude; the
    cheapest run of each model for each target and the floor, by evaluations, is ringed.
    ``cost="nfev"`` (the default): the horizontal axis is the chapter's cost, the
    right-hand-side evaluations (the exact solution, with none, is left off the axis);
    ``cost="seconds"``: the median wall time per run, with the exact solution as a
    dashed vertical line (a figure of time, to be named as such).  Saved (deterministic
    SVG) if ``path`` is given; returns the figure."""
    if cost not in ("nfev", "seconds"):
        raise ValueError(f"cost = {cost!r}: 'nfev' or 'seconds'")

    def x(r):
        return r["nfev"] if cost == "nfev" else 1e3 * r["seconds"]
    import matplotlib
    if path is not None and "matplotlib.pyplot" not in sys.modules:
        matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.lines import Line2D
    matplotlib.rcParams["svg.hashsalt"] = "whittaker-teach"
    amps = results["meta"]["amplitudes"]
    best = cheapest(results, targets)
    # 7.5 in wide with 10 pt text: at least 9 pt when shown at the page's width (~7 in)
    with plt.rc_context({"font.size": 10}):
        fig, axes = plt.subplots(1, len(amps), figsize=(3.75 * len(amps), 5.6), squeeze=False,
                                 sharey=True)
        colors = {m: f"C{i}" for i, m in enumerate(METHODS + (TIGHT,))}
        for ax, a in zip(axes[0], amps):
            done = [r for r in _done(results) if r["amplitude"] == a]
            for model in MODELS:
                if cost == "nfev" and model == "exact":
                    continue                     # no evaluations: nothing to plot on a log axis
                for m in sorted({r["method"] for r in done if r["model"] == model}):
                    rs = [r for r in done if r["model"] == model and r["method"] == m]
                    ls, mk = STYLE[model]
                    ax.loglog([x(r) for r in rs],
                              [max(r["error"], 1e-17) for r in rs], ls=ls, marker=mk,
                              color=colors.get(m, "k"), ms=5 if model != "exact" else 13,
                              lw=1.2, alpha=0.85)
            ringed = {id(r): r for row in best[a].values() for mod, r in row.items()
                      if r is not None and mod != "exact"}
            ax.plot([x(r) for r in ringed.values()],
                    [max(r["error"], 1e-17) for r in ringed.values()], "o", ms=12, mfc="none",
                    mec="k", mew=1.2, zorder=5)
            ex = [r for r in done if r["model"] == "exact"]
            if ex and cost == "seconds":
                ax.axvline(1e3 * ex[0]["seconds"], color="k", lw=0.8, ls="--", zorder=1)
            for tgt in targets:
                ax.axhline(tgt, color="0.45", lw=0.9, ls=(0, (4, 4)), zorder=2)
            ax.set_ylim(1e-16, None)
            ax.set_title(f"a = {a:g}, {results['meta']['periods']} periods")
            ax.set_xlabel("right-hand-side evaluations per run (nfev)" if cost == "nfev"
                          else "wall time per run [ms]")
            ax.grid(True, which="major", color="0.92", zorder=0)
            ax.set_axisbelow(True)
        axes[0][0].set_ylabel("largest relative error (θ, x, y, t)")
        shown = {r["method"] for r in _done(results)}
        handles = [Line2D([], [], color=colors[m], lw=2, label=m) for m in METHODS + (TIGHT,)
                   if m in shown]
        handles += [Line2D([], [], color="0.3", ls=STYLE[k][0] or "none", marker=STYLE[k][1],
                           ms=5 if k != "exact" else 10, label=LABEL[k]) for k in MODELS
                    if cost == "seconds" or k != "exact"]
        handles.append(Line2D([], [], ls="none", marker="o", ms=11, mfc="none", mec="k",
                              label="cheapest run per target (by evaluations)"))
        fig.legend(handles=handles, loc="lower center", ncol=2, fontsize=10, frameon=False)
        fig.tight_layout(rect=(0, 0.27, 1, 1))
    if path is not None:
        fig.savefig(path, metadata={"Date": None} if str(path).endswith(".svg") else None)
    return fig


# ----------------------------------------------------------------- command line
def main(args):
    """``python -m whittaker_teach bench numerics``."""
    res = study(quick=args.quick, progress=not args.quiet)
    m = res["meta"]
    print(f"work-precision study: sledge, {m['periods']} periods, phi = {PHI}, C = {C},\n"
          f"m = J = k = 1; atol = {ATOL:g}; evaluation budget {NFEV_BUDGET} per run once "
          f"a ladder reaches {min(TARGETS):.0e},\n{NFEV_CAP} before ({TIGHT_NFEV_BUDGET} "
          f"for {TIGHT});\n"
          f"times are medians of {m['repeat']} interleaved runs\n"
          f"error = {m['error']}\n")
    print(table(res))
    print(summary(res))
    if args.json:
        with open(args.json, "w") as f:
            json.dump(res, f, indent=1, sort_keys=True)
            f.write("\n")
        print(f"wrote {args.json}")
    if getattr(args, "csv", None):
        with open(args.csv, "w") as f:
            f.write(to_csv(res))
        print(f"wrote {args.csv}")
    if args.plot:
        plot(res, args.plot)
        print(f"wrote {args.plot}")
    return 0
