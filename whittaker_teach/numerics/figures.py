"""Regenerate the stored results the book shows: ``python -m whittaker_teach.numerics.figures``.

Writes into ``book/figures/numerics/`` (or ``--out DIR``):

=============================  ===============================================
``work_precision.json/.csv``   the full work-precision study (``bench numerics``)
``work_precision.svg``         its figure: error against evaluations (nfev), the
                               chapter's cost (``--only work_precision_plot``
                               redraws it from the stored json, without the study)
``long_run.json/.svg``         hard case 6: 10^4 periods of the sledge, 10^3 of the sleigh
``stiff.json``                 hard case 5: k^2/J = 1e4 and 1e6, every method
``hard_cases.json``            the outcome of every hard case at full size
``method_choice.json``         what ``simulate(..., tol=)`` chose on the integrated
                               scenes of chapters 7-8 and the fast sleigh, against
                               the cheapest run of each scipy method at equal error
                               (evaluations and timings, printed as they are taken)
=============================  ===============================================

The SVG files are deterministic (no date, fixed hash salt); the timings in
them are those of the run that made them.  ``--only NAME[,NAME]`` remakes some.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import time

__all__ = ["main", "plot_long_run", "PARTS"]

PARTS = ("work_precision", "work_precision_plot", "long_run", "stiff", "hard_cases",
         "method_choice")
#: what a bare run remakes (the plot is part of ``work_precision``)
DEFAULT_PARTS = ("work_precision", "long_run", "stiff", "hard_cases", "method_choice")


def _dump(obj, path):
    with open(path, "w") as f:
        json.dump(obj, f, indent=1, sort_keys=True, default=float)
        f.write("\n")
    print(f"wrote {path}", flush=True)


def _svg(fig, path):
    fig.savefig(path, metadata={"Date": None})
    print(f"wrote {path}", flush=True)


def plot_long_run(data, path=None):
    """Relative energy error against time, one panel per system (text >= 9 pt at page
    width, the legend below the panels)."""
    import matplotlib
    if path is not None and "matplotlib.pyplot" not in sys.modules:
        matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    matplotlib.rcParams["svg.hashsalt"] = "whittaker-teach"
    order = sorted(data, key=lambda s: s != "sledge")            # the sledge first
    with plt.rc_context({"font.size": 10}):          # >= 9 pt at the page's width (~7 in)
        fig, axes = plt.subplots(1, len(data), figsize=(3.75 * len(data), 4.6), squeeze=False)
        for ax, (system, block) in zip(axes[0], ((s, data[s]) for s in order)):
            for i, r in enumerate(block["runs"]):
                label = (f"DLA, {r['setting']} steps/period" if r["method"] == "DLA"
                         else f"{r['method']}, rtol {r['setting']:.0e}")
                e = [max(v, 1e-17) for v in r["energy_error"]]
                ax.loglog(r["t"], e, color="k" if r["method"] == "DLA" else f"C{i}", lw=1.4,
                          label=label)
            ax.set_title(f"{system.replace('_', ' ')}: {block['periods']} "
                         + ("periods" if system == "sledge" else "× 2π"))
            ax.set_xlabel("t [1/ω]")
            ax.grid(True, color="0.92")
        axes[0][0].set_ylabel("|E(t) − h| / h")
        handles, labels = axes[0][0].get_legend_handles_labels()
        fig.legend(handles, labels, loc="lower center", ncol=2, fontsize=10, frameon=False)
        fig.tight_layout(rect=(0, 0.17, 1, 1))
    if path is not None:
        _svg(fig, path)
    return fig


def _work_precision(out):
    from . import work_precision as wp
    res = wp.study(quick=False, progress=True)
    _dump(res, os.path.join(out, "work_precision.json"))
    with open(os.path.join(out, "work_precision.csv"), "w") as f:
        f.write(wp.to_csv(res))
    print(f"wrote {os.path.join(out, 'work_precision.csv')}", flush=True)
    print(wp.table(res))
    print(wp.summary(res))
    _svg(wp.plot(res), os.path.join(out, "work_precision.svg"))


def _work_precision_plot(out):
    from . import work_precision as wp
    with open(os.path.join(out, "work_precision.json")) as f:
        res = json.load(f)
    _svg(wp.plot(res), os.path.join(out, "work_precision.svg"))


def _long_run(out):
    from . import hard_cases as hc
    data = {}
    for system, periods in (("sledge", 10_000), ("offset_sleigh", 1000)):
        t0 = time.perf_counter()
        data[system] = {"periods": periods, "runs": hc.long_run(periods, system)}
        print(f"long run, {system}: {time.perf_counter() - t0:.0f} s", flush=True)
        for r in data[system]["runs"]:
            print(f"  {r['method']:7s} {r['setting']:<8g} energy final {r['energy_final']:.2e} "
                  f"max {r['energy_max']:.2e} position {r['position_error']:.2e} "
                  + (f"phase {r['phase_error']:.2e} " if "phase_error" in r else "")
                  + f"nfev {r['nfev']} {r['seconds']:.1f} s", flush=True)
    _dump(data, os.path.join(out, "long_run.json"))
    _svg(plot_long_run(data), os.path.join(out, "long_run.svg"))


def _stiff(out):
    from . import hard_cases as hc
    data = {}
    for system in ("sledge", "offset_sleigh"):
        for ratio in (1e4, 1e6):
            t0 = time.perf_counter()
            data[f"{system} {ratio:.0e}"] = hc.stiff(ratio, system=system, repeat=3)
            print(f"stiff {system} {ratio:.0e}: {time.perf_counter() - t0:.0f} s", flush=True)
            for m, v in data[f"{system} {ratio:.0e}"].items():
                print(f"  {m:7s} {v}", flush=True)
    _dump(data, os.path.join(out, "stiff.json"))


def _hard_cases(out):
    from . import hard_cases as hc
    res = []
    for case in (1, 2, 3, 4, 7):
        for system in ("sledge", "offset_sleigh"):
            r = hc.run(case, system, quick=False)
            print(r, flush=True)
            res.append({"case": r.case, "system": r.system, "title": r.title, "ok": r.ok,
                        "expected": r.expected, "outcome": r.outcome, "error": r.error,
                        "tolerance": r.tolerance})
    _dump(res, os.path.join(out, "hard_cases.json"))


def _method_choice(out):
    from . import hard_cases as hc
    data = []
    for name, system, q0, qd0, T, P, tol in hc.choice_scenes():
        t0 = time.perf_counter()
        r = hc.choice_costs(system, q0, qd0, T, P, tol, repeat=3)
        best = r["methods"][r["cheapest"]]
        print(f"{name} ({time.perf_counter() - t0:.0f} s): tol={tol:g} chose {r['method']} "
              f"rtol {r['rtol']:.0e}, {r['nfev']} evaluations ({r['nfev_all']} with its "
              f"check), {1e3 * r['seconds']:.1f} ms, error {r['error']:.1e}; cheapest "
              f"{r['cheapest']} {best['nfev']}: run x{r['nfev'] / best['nfev']:.2f}, call "
              f"x{r['nfev_all'] / best['nfev']:.2f}", flush=True)
        for m, v in r["methods"].items():
            print(f"  {m:7s} " + ("not reached" if v is None else
                                  f"rtol {v['rtol']:.0e} nfev {v['nfev']:6d} error "
                                  f"{v['error']:.1e} {1e3 * v['seconds']:8.1f} ms"), flush=True)
        data.append({"scene": name, "system": system, "T": T, "params": P, **r})
    _dump(data, os.path.join(out, "method_choice.json"))


def main(argv=None):
    ap = argparse.ArgumentParser(prog="python -m whittaker_teach.numerics.figures",
                                 description="regenerate the book's stored numerics results")
    ap.add_argument("--out", default=os.path.join("book", "figures", "numerics"))
    ap.add_argument("--only", default=",".join(DEFAULT_PARTS),
                    help=f"comma-separated subset of {', '.join(PARTS)}")
    args = ap.parse_args(argv)
    os.makedirs(args.out, exist_ok=True)
    for part in args.only.split(","):
        if part not in PARTS:
            ap.error(f"unknown part {part!r}")
        t0 = time.perf_counter()
        globals()[f"_{part}"](args.out)
        print(f"{part}: {time.perf_counter() - t0:.0f} s\n", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
