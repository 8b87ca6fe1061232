#!/usr/bin/env python
"""What sets the error floor of the full model: truncation or round-off?  (a benchmark
that prints; about 20 s)

    PYTHONPATH=$PWD python scripts/error_floor.py

The sledge of chapter 7 (a = 0.3, phi = 0.3, m = J = k = C = 1, 10 periods), the
largest error relative to each component's scale against the closed form.  For
each formulation, DOP853 runs at scipy's smallest rtol (2.3e-14) and below it
("DOP853-tight"); then the steps of each run are replayed with the same
Runge-Kutta tableau three ways: in double precision (the run's arithmetic: the
package's stepper, ``numerics.portable``, sums the stages in the same order), in
double precision with the state update summed with Kahan's compensation, and in
x87 long double (64-bit mantissa, eps 1.1e-19).  At the same steps the
truncation error is the same in all three: what long double removes is
round-off, what the compensated update removes is the round-off of the update.
"""
from __future__ import annotations

import sys

import numpy as np
from scipy.integrate import solve_ivp
from scipy.integrate._ivp import dop853_coefficients as dc

import whittaker_teach as wt
from whittaker_teach.numerics.ivp import TightDOP853
from whittaker_teach.numerics.portable import PortableDOP853, combine
from whittaker_teach.numerics.work_precision import _scales

P = {"m": 1.0, "J": 1.0, "k": 1.0}


def rhs(form, dtype):
    """The sledge's right-hand side (k = J = 1) in the given float type."""
    def multiplier(t, u):
        x, th, y, xd, thd, yd = u
        s, c = np.sin(th), np.cos(th)
        lam = thd * (xd * c + yd * s)
        return np.array([xd, thd, yd, -lam * s, -th, lam * c], dtype=dtype)

    def chaplygin(t, u):                      # (1.4): ydot = xdot tan(theta)
        x, th, y, xd, thd = u
        yd = xd * np.tan(th)
        return np.array([xd, thd, yd, -thd * yd, -th], dtype=dtype)
    return multiplier if form == "multiplier" else chaplygin


def replay(form, ts, u0, dtype, kahan=False):
    """The DOP853 steps ts taken again in ``dtype`` (optionally a compensated update)."""
    f = rhs(form, dtype)
    A, B, C = (np.asarray(M, dtype=dtype) for M in (dc.A[:12, :12], dc.B, dc.C[:12]))
    y = np.asarray(u0, dtype=dtype)
    comp = np.zeros_like(y)
    out = [y.copy()]
    K = np.empty((12, len(y)), dtype=dtype)
    tt = np.asarray(ts, dtype=dtype)
    for n in range(len(ts) - 1):
        t, h = tt[n], tt[n + 1] - tt[n]
        K[0] = f(t, y)
        for s in range(1, 12):
            K[s] = f(t + C[s] * h, y + combine(K[:s], A[s, :s]) * h)   # the run's order
        inc = h * combine(K, B)
        if kahan:
            z = inc - comp
            new = y + z
            comp = (new - y) - z
            y = new
        else:
            y = y + inc
        out.append(y.copy())
    return np.array(out, dtype=float).T


def main():
    a = 0.3
    ex = wt.examples.sledge_exact(P, a=a, phi=0.3, C=1.0)
    T = 10 * ex.period
    xs, ys = _scales(ex, T)
    s = ex(0.0)
    full = np.array([s["x"], s["theta"], s["y"], s["xdot"], s["thetadot"], s["ydot"]])

    def err(t, Y):
        e = ex(np.asarray(t, dtype=float))
        return (np.max(np.abs(Y[1] - e["theta"])) / a, np.max(np.abs(Y[0] - e["x"])) / xs,
                np.max(np.abs(Y[2] - e["y"])) / ys)
    print(f"sledge, a = {a}, 10 periods; errors (theta, x, y) relative to each scale;\n"
          f"100 machine epsilons = {100 * np.finfo(float).eps:.1e}; long double here has "
          f"eps {np.finfo(np.longdouble).eps:.1e}\n(on a machine where it is 2.2e-16, the "
          f"long double rows say nothing)\n")
    for form in ("chaplygin", "multiplier"):
        u0 = full if form == "multiplier" else full[:5]
        print(f"{form} form")
        for method, rtol in (("DOP853", 2.3e-14), ("DOP853-tight", 2e-15),
                             ("DOP853-tight", 1e-15)):
            sol = solve_ivp(rhs(form, float), (0, T), u0, rtol=rtol, atol=1e-20,
                            method=TightDOP853 if method != "DOP853" else PortableDOP853)
            print(f"  {method:12s} rtol {rtol:.1e}: {len(sol.t) - 1} steps, nfev {sol.nfev}")
            for label, dtype, kahan in (("double", np.float64, False),
                                        ("double, Kahan update", np.float64, True),
                                        ("long double", np.longdouble, False)):
                e = err(sol.t, replay(form, sol.t, u0, dtype, kahan))
                print(f"    {label:22s} theta {e[0]:.1e}  x {e[1]:.1e}  y {e[2]:.1e}"
                      f"   largest {max(e):.1e}")
        print()
    return 0


if __name__ == "__main__":
    sys.exit(main())
