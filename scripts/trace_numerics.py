#!/usr/bin/env python
"""Count the calls that cross from one module of the package to another during one call
of ``simulate`` (full model, reduced model, DLA), cold (code generated) and warm (cached).

    PYTHONPATH=$PWD python scripts/trace_numerics.py [-v]

A transition is a direct call from one module of whittaker_teach to another (imports
and the right-hand sides that scipy calls back are not transitions: their caller is
scipy; nor are calls into ``numerics.portable``, the arithmetic that stands in for numpy's
``dot`` and ``linalg.solve`` inside a step, a leaf used as numpy is).  ``-v`` lists them.  The architecture note of the developers' guide: one entry per
model, the code generation behind it, the input checked once up front.
"""
from __future__ import annotations

import os
import sys

import whittaker_teach as wt

PKG = os.path.dirname(wt.__file__)
#: arithmetic helpers used like a library (numpy's stand-ins): not an architectural crossing
LEAVES = ("numerics.portable",)


def _module(code):
    f = code.co_filename
    if not f.startswith(PKG):
        return None
    return os.path.relpath(f, PKG)[:-3].replace(os.sep, ".")


def transitions(fn):
    """[(caller module, callee module, callee function)] for one call of fn()."""
    seq = []

    def prof(frame, event, arg):
        if event != "call":
            return
        m = _module(frame.f_code)
        name = frame.f_code.co_name
        if m is None or name in ("<module>", "__getattr__") or frame.f_back is None:
            return
        caller = _module(frame.f_back.f_code)
        if caller is not None and caller != m and m not in LEAVES:
            seq.append((caller, m, name))
    sys.setprofile(prof)
    try:
        fn()
    finally:
        sys.setprofile(None)
    return seq


def cases():
    S = wt.examples.sledge()
    red = S.reduce("x", +1)
    P = {"m": 1, "J": 1, "k": 1}
    ex = wt.examples.sledge_exact(P, a=0.5, C=1.0)
    q0, qd0 = ex.initial()
    rq0, qp0, h = ex.reduced_initial()
    return [
        ("full model, S.simulate", lambda: S.simulate(q0, qd0, (0, 10), P)),
        ("reduced model, red.simulate", lambda: red.simulate(rq0, qp0, h, (0, 5), P)),
        ("DLA, S.simulate(method='DLA')",
         lambda: S.simulate(q0, qd0, (0, 10), P, method="DLA", dt=0.1)),
    ]


def main(argv):
    verbose = "-v" in argv
    for name, fn in cases():
        for label in ("cold", "warm"):
            seq = transitions(fn)
            print(f"{name:32s} {label}: {len(seq):3d} cross-module calls")
            if verbose:
                for a, b, f in seq:
                    print(f"      {a} -> {b}.{f}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
