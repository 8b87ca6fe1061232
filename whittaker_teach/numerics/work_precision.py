"""Speed against error: a work-precision study of the full, reduced and exact models.

``python -m whittaker_teach bench numerics [--quick] [--json FILE] [--plot FILE] [--quiet]``

The sledge (m = J = k = C = 1, so omega = 1) at two amplitudes, a small one
and one near pi/2, over 20 periods from theta = a cos(phi), phi = 0.3.  For
each model and each method and tolerance: the largest error against the exact
solution, over the integrator's own steps, in theta, x and y and in the energy
(relative), the median wall time of several runs, and the number of
right-hand-side evaluations.

* ``full``: the Chaplygin equations (1.4) and the constraint, in t;
* ``reduced``: the generalized Whittaker equation (1.26) in x, with t(x) and
  y(x) by quadrature alongside (its energy is exact by construction);
* ``DLA``: the fixed-step discrete Lagrange-d'Alembert integrator (setting:
  steps per period);
* ``exact``: the closed form, evaluated on 1000 points.

Every right-hand side is built (code generation) before the clock starts.
``--quick`` runs a smaller study (5 periods, three tolerances, one run each).

>>> res = study(quick=True, progress=False, amplitudes=(0.3,), methods=("DOP853",),
...             rtols=(1e-6,), dla_steps=(), periods=1)
>>> sorted({r["model"] for r in res["runs"]})
['exact', 'full', 'reduced']
"""

from __future__ import annotations

import json
import math
import statistics
import sys
import time

import numpy as np

from ..errors import ModelError

__all__ = ["study", "cheapest", "table", "summary", "plot", "main", "AMPLITUDES", "METHODS",
           "RTOLS", "TARGETS"]

AMPLITUDES = (0.3, 1.5)
METHODS = ("RK45", "DOP853", "Radau", "LSODA")
RTOLS = tuple(10.0 ** -k for k in range(3, 14))
DLA_STEPS = (16, 32, 64, 128, 256, 512)
TARGETS = (1e-6, 1e-9, 1e-12)
PARAMS = {"m": 1.0, "J": 1.0, "k": 1.0}
PHI, C = 0.3, 1.0
#: A (model, method) stops going to tighter tolerances after a run this long (seconds).
BUDGET = 20.0

QUICK = {"periods": 5, "rtols": (1e-4, 1e-7, 1e-10), "dla_steps": (32, 128), "repeat": 1}


def _errors(ex, t, q):
    e = ex(np.asarray(t))
    return {f"err_{k}": float(np.max(np.abs(np.asarray(q[k]) - e[k]))) for k in
            ("theta", "x", "y")}


def _timed(fn, repeat):
    """(result of the first run, median seconds); a run over 2 s is not repeated."""
    t0 = time.perf_counter()
    out = fn()
    secs = [time.perf_counter() - t0]
    if secs[0] < 2.0:
        for _ in range(repeat - 1):
            t0 = time.perf_counter()
            fn()
            secs.append(time.perf_counter() - t0)
    return out, statistics.median(secs)


def _record(amplitude, model, method, setting, errs, energy, seconds, nfev, njev, points):
    r = {"amplitude": amplitude, "model": model, "method": method, "setting": setting,
         **errs, "err_energy": energy, "seconds": seconds, "nfev": int(nfev),
         "njev": int(njev), "points": int(points)}
    r["error"] = max(errs.values())
    return r


def _exact_error(ex, T, n=4):
    """The closed form against mpmath quadrature at 30 digits at n instants."""
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


def exact_cost(ex, T, repeat=7):
    """(seconds per scalar evaluation, seconds for 1000 points vectorised)."""
    n = 2000
    ts = [T * (i + 0.5) / n for i in range(n)]

    def scalar():
        for t in ts:
            ex(t)
    _, s1 = _timed(scalar, repeat)
    grid = np.linspace(0, T, 1000)
    _, s2 = _timed(lambda: ex(grid), repeat)
    return s1 / n, s2


def _tasks(amplitudes, methods, rtols, dla_steps):
    tasks = []
    for a in amplitudes:
        for model in ("full", "reduced"):
            for m in methods:
                tasks += [(a, model, m, r) for r in rtols]
        tasks += [(a, "DLA", "DLA", n) for n in dla_steps]
        tasks.append((a, "exact", "closed form", None))
    return tasks


def study(quick=False, progress=True, amplitudes=AMPLITUDES, methods=METHODS, rtols=None,
          dla_steps=None, periods=None, repeat=None):
    """Run the study; a dict {"meta": ..., "runs": [record, ...], "exact_cost": ...}."""
    import whittaker_teach as wt
    cfg = QUICK if quick else {"periods": 20, "rtols": RTOLS, "dla_steps": DLA_STEPS,
                               "repeat": 3}
    periods = cfg["periods"] if periods is None else periods
    rtols = cfg["rtols"] if rtols is None else rtols
    dla_steps = cfg["dla_steps"] if dla_steps is None else dla_steps
    repeat = cfg["repeat"] if repeat is None else repeat
    S = wt.examples.sledge()
    red = S.reduce("x", +1)
    tasks = _tasks(amplitudes, methods, rtols, dla_steps)
    bar = _progress(len(tasks), progress)
    runs, over, costs = [], set(), {}
    for a, model, method, setting in tasks:
        ex = wt.examples.sledge_exact(PARAMS, a=a, phi=PHI, C=C)
        T = periods * ex.period
        bar.set_description(f"a={a:g} {model:7s} {method:6s} {setting if setting else ''}")
        if (a, model, method) in over:
            bar.update()
            continue
        try:
            rec = _run(S, red, ex, T, a, model, method, setting, repeat)
        except ModelError as err:           # e.g. a loose run wandering into a turning point
            runs.append({"amplitude": a, "model": model, "method": method,
                         "setting": setting, "failed": f"{type(err).__name__}: {err}"})
            bar.update()
            continue
        if model == "exact":
            costs[a] = {"scalar": rec.pop("scalar"), "grid1000": rec["seconds"]}
        runs.append(rec)
        if rec["seconds"] > BUDGET:
            over.add((a, model, method))
        bar.update()
    bar.close()
    return {"meta": _meta(periods, repeat, amplitudes), "runs": runs,
            "exact_cost": {str(a): c for a, c in costs.items()}}


def _run(S, red, ex, T, a, model, method, setting, repeat):
    if model == "full":
        q0, qd0 = ex.initial()
        S.simulate(q0, qd0, (0, T / 50), PARAMS, method=method, formulation="chaplygin")
        tr, secs = _timed(lambda: S.simulate(q0, qd0, (0, T), PARAMS, method=method,
                                             rtol=setting, dense=False,
                                             formulation="chaplygin"), repeat)
        dE = float(np.max(np.abs(tr.energy - ex.h)) / ex.h)
        return _record(a, model, method, setting, _errors(ex, tr.t, tr.q), dE, secs,
                       tr.nfev, tr.njev, len(tr.t))
    if model == "reduced":
        q0, qp0, h = ex.reduced_initial()
        x_end = ex(T)["x"]
        red.simulate(q0, qp0, h, (q0["x"], q0["x"] + 0.1), PARAMS, method=method)
        p, secs = _timed(lambda: red.simulate(q0, qp0, h, (q0["x"], x_end), PARAMS,
                                              method=method, rtol=setting, dense=False),
                         repeat)
        return _record(a, model, method, setting, _errors(ex, p.t, p.q), None, secs,
                       p.nfev, p.njev, len(p.t))
    if model == "DLA":
        q0, qd0 = ex.initial()
        dt = ex.period / setting
        S.simulate(q0, qd0, (0, dt), PARAMS, method="DLA", dt=dt)
        tr, secs = _timed(lambda: S.simulate(q0, qd0, (0, T), PARAMS, method="DLA", dt=dt,
                                             dense=False), repeat)
        dE = float(np.max(np.abs(tr.energy - ex.h)) / ex.h)
        return _record(a, model, method, setting, _errors(ex, tr.t, tr.q), dE, secs,
                       tr.nfev, tr.njev, len(tr.t))
    err = _exact_error(ex, T)
    per_point, grid = exact_cost(ex, T, max(repeat, 3))
    g = ex(np.linspace(0, T, 1000))
    E = 0.5 * (g["xdot"] ** 2 + g["ydot"] ** 2) + 0.5 * g["thetadot"] ** 2 + 0.5 * g["theta"] ** 2
    rec = _record(a, model, method, None, {"err_theta": 0.0, "err_x": err, "err_y": err},
                  float(np.max(np.abs(E - ex.h)) / ex.h), grid, 0, 0, 1000)
    rec["scalar"] = per_point
    return rec


class _NoBar:
    def set_description(self, *_):
        pass

    def update(self, *_):
        pass

    def close(self):
        pass


def _progress(total, enabled):
    if not enabled or not sys.stderr.isatty():
        return _NoBar()
    try:
        from tqdm import tqdm
    except ImportError:
        return _NoBar()
    return tqdm(total=total, unit="run", file=sys.stderr, leave=False)


def _meta(periods, repeat, amplitudes):
    import platform

    import scipy
    return {"system": "sledge", "params": PARAMS, "C": C, "phi": PHI, "periods": periods,
            "amplitudes": list(amplitudes), "repeat": repeat, "python": platform.python_version(),
            "numpy": np.__version__, "scipy": scipy.__version__, "machine": platform.machine(),
            "error": "max over the steps of |theta - theta_exact|, |x - x_exact|, |y - y_exact|"}


# ----------------------------------------------------------------- reading the results
def _done(results):
    """The runs that finished (a run may fail with a ModelError, recorded as such)."""
    return [r for r in results["runs"] if "failed" not in r]


def cheapest(results, targets=TARGETS):
    """{amplitude: {target: {model: record or None, "ratio": reduced/full seconds}}}."""
    out = {}
    for a in results["meta"]["amplitudes"]:
        per = {}
        for tgt in targets:
            row = {}
            for model in ("full", "reduced", "DLA", "exact"):
                ok = [r for r in _done(results) if r["amplitude"] == a
                      and r["model"] == model and r["error"] <= tgt]
                row[model] = min(ok, key=lambda r: r["seconds"]) if ok else None
            f, r = row["full"], row["reduced"]
            row["ratio"] = r["seconds"] / f["seconds"] if f and r else None
            row["nfev_ratio"] = r["nfev"] / f["nfev"] if f and r else None
            per[tgt] = row
        out[a] = per
    return out


def _fmt_e(v):
    return "   exact " if v is None else f"{v:9.1e}"


def table(results):
    """Every run as a text table, one block per amplitude."""
    lines = []
    head = (f"{'model':8s} {'method':11s} {'setting':>8s} {'err theta':>9s} {'err x':>9s} "
            f"{'err y':>9s} {'err E':>9s} {'time ms':>9s} {'nfev':>8s}")
    for a in results["meta"]["amplitudes"]:
        lines += [f"amplitude a = {a:g}", head]
        for r in results["runs"]:
            if r["amplitude"] != a:
                continue
            s = r["setting"]
            setting = "" if s is None else (f"{s:.0e}" if r["model"] != "DLA" else f"{s}/T")
            if "failed" in r:
                lines.append(f"{r['model']:8s} {r['method']:11s} {setting:>8s}  failed: "
                             f"{r['failed'][:60]}")
                continue
            lines.append(f"{r['model']:8s} {r['method']:11s} {setting:>8s} "
                         f"{r['err_theta']:9.1e} {r['err_x']:9.1e} {r['err_y']:9.1e} "
                         f"{_fmt_e(r['err_energy'])} {1e3 * r['seconds']:9.2f} {r['nfev']:8d}")
        lines.append("")
    return "\n".join(lines)


def _how(r):
    if r is None:
        return "not reached"
    if r["model"] == "exact":
        return f"closed form, {1e3 * r['seconds']:.2f} ms / 1000 points"
    s = f"rtol {r['setting']:.0e}" if r["model"] != "DLA" else f"{r['setting']} steps/period"
    return f"{r['method']} {s}: {1e3 * r['seconds']:.2f} ms, nfev {r['nfev']}"


def summary(results, targets=TARGETS):
    """The cheapest way to each target error with each model, and reduced / full."""
    best = cheapest(results, targets)
    lines = []
    for a, per in best.items():
        lines.append(f"amplitude a = {a:g}: cheapest run with error <= target")
        for tgt, row in per.items():
            lines.append(f"  error {tgt:.0e}")
            for model in ("full", "reduced", "DLA", "exact"):
                lines.append(f"    {model:8s} {_how(row[model])}")
            if row["ratio"] is not None:
                lines.append(f"    reduced / full: time {row['ratio']:.2f}, nfev "
                             f"{row['nfev_ratio']:.2f}")
        c = results["exact_cost"].get(str(a))
        if c:
            lines.append(f"  one exact evaluation: {1e6 * c['scalar']:.2f} us (scalar), "
                         f"{1e3 * c['grid1000']:.3f} ms for 1000 points")
        lines.append("")
    return "\n".join(lines)


# ----------------------------------------------------------------- the figure
STYLE = {"full": ("-", "o"), "reduced": ("--", "s"), "DLA": (":", "^"), "exact": ("", "*")}


def plot(results, path=None, targets=TARGETS):
    """Log-log error against wall time, one panel per amplitude.  Saved (deterministic SVG
    or PNG) if ``path`` is given; returns the figure."""
    import matplotlib
    if path is not None and "matplotlib.pyplot" not in sys.modules:
        matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    matplotlib.rcParams["svg.hashsalt"] = "whittaker-teach"
    amps = results["meta"]["amplitudes"]
    fig, axes = plt.subplots(1, len(amps), figsize=(5.2 * len(amps), 4.4), squeeze=False,
                             sharey=True)
    colors = {m: f"C{i}" for i, m in enumerate(METHODS)}
    for ax, a in zip(axes[0], amps):
        for r_model in ("full", "reduced", "DLA", "exact"):
            for m in sorted({r["method"] for r in _done(results) if r["model"] == r_model}):
                rs = [r for r in _done(results) if r["amplitude"] == a
                      and r["model"] == r_model and r["method"] == m]
                if not rs:
                    continue
                ls, mk = STYLE[r_model]
                ax.loglog([r["seconds"] for r in rs], [max(r["error"], 1e-17) for r in rs],
                          ls=ls, marker=mk, color=colors.get(m, "k"),
                          ms=5 if r_model != "exact" else 12)
        for tgt in targets:
            ax.axhline(tgt, color="0.55", lw=0.8, ls=(0, (4, 4)), zorder=1)
        ax.set_title(f"a = {a:g} ({results['meta']['periods']} periods)")
        ax.set_xlabel("wall time per run [s] (median)")
        ax.grid(True, which="major", color="0.92")
    axes[0][0].set_ylabel("max error in theta, x, y")
    from matplotlib.lines import Line2D
    handles = [Line2D([], [], color=colors[m], lw=2, label=m) for m in METHODS]
    handles += [Line2D([], [], color="0.3", ls=STYLE[k][0] or "none", marker=STYLE[k][1],
                       ms=5 if k != "exact" else 10,
                       label={"full": "full model (1.4), in t", "reduced": "reduced (1.26), in x",
                              "DLA": "DLA (fixed step)", "exact": "exact (1000 points)"}[k])
                for k in STYLE]
    axes[0][0].legend(handles=handles, fontsize=7.5, loc="center left", framealpha=0.95)
    fig.tight_layout()
    if path is not None:
        fig.savefig(path, metadata={"Date": None} if str(path).endswith(".svg") else None)
    return fig


# ----------------------------------------------------------------- command line
def main(args):
    """``python -m whittaker_teach bench numerics``."""
    res = study(quick=args.quick, progress=not args.quiet)
    print(f"work-precision study: sledge, {res['meta']['periods']} periods, phi = {PHI}, "
          f"C = {C}, m = J = k = 1; error = {res['meta']['error']}; times are medians of "
          f"{res['meta']['repeat']} run(s)\n")
    print(table(res))
    print(summary(res))
    if args.json:
        with open(args.json, "w") as f:
            json.dump(res, f, indent=1, sort_keys=True)
            f.write("\n")
        print(f"wrote {args.json}")
    if args.plot:
        plot(res, args.plot)
        print(f"wrote {args.plot}")
    return 0
