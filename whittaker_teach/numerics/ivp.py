"""One call of scipy's ``solve_ivp`` with the library's conventions.

Compiled right-hand sides take plain float lists; here they become the
``fun(t, y)`` scipy wants.  A right-hand side that cannot be evaluated
(a pole hit exactly, a square root of a negative number) returns infinities,
which makes an explicit method reject the step; a run that still fails, or
that returns anything non-finite, raises a ModelError: never a silent NaN.

>>> def f(y, p): return [-p[0] * y[0]]
>>> sol = solve(f, None, (0.0, 1.0), [1.0], [2.0], "DOP853", 1e-10, 1e-10, what="decay")
>>> bool(abs(sol.y[0, -1] - 0.1353352832366127) < 1e-9)
True
"""

from __future__ import annotations

import warnings

import numpy as np
from scipy.integrate import solve_ivp

from ..errors import ModelError
from .portable import PORTABLE, PortableDOP853, combine

__all__ = ["solve", "as_fun", "roots_within_steps", "ARITHMETIC", "TightDOP853", "TIGHT"]

#: The method name of :class:`TightDOP853`.
TIGHT = "DOP853-tight"


class TightDOP853(PortableDOP853):
    """scipy's DOP853 with ``rtol`` below scipy's floor of 100 machine epsilons.

    scipy raises any rtol below 2.2e-14 to 2.2e-14; this subclass starts
    scipy's solver at that value (the first step is chosen with it) and then
    sets the requested rtol (down to 2 machine epsilons, checked by
    :func:`.validate.check_tolerances`).  Below 100 eps the error estimate
    is itself near round-off, so the run takes more steps than the error
    needs; what it buys is a smaller truncation error: on the sledge the
    paper's form (1.4) at rtol 1e-15 reaches a relative error of 4e-15 over
    10 periods, where rtol 2.3e-14 stops at 1e-13 (chapter 7).
    """

    def __init__(self, fun, t0, y0, t_bound, rtol=1e-3, atol=1e-6, **kw):
        floor = 100 * np.finfo(float).eps
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            super().__init__(fun, t0, y0, t_bound, rtol=max(rtol, floor), atol=atol, **kw)
        self.rtol = rtol

_BAD = (ZeroDivisionError, ValueError, OverflowError)
#: The raw arithmetic errors that must never reach a user (they become ModelErrors).
ARITHMETIC = (OverflowError, ZeroDivisionError, FloatingPointError)


def as_fun(rhs, p, n):
    """``fun(t, y)`` for scipy from a compiled ``rhs(y list, p list) -> list``."""
    raw = getattr(rhs, "raw", None)
    inf = np.full(n, np.inf)
    if raw is not None:
        def fun(t, y):
            try:
                return np.array(raw(*y.tolist(), *p))
            except _BAD:
                return inf
    else:
        def fun(t, y):
            try:
                return np.array(rhs(y.tolist(), p))
            except _BAD:
                return inf
    return fun


def as_jac(jac, p):
    """``jac(t, y)`` for the implicit methods from a compiled Jacobian."""
    raw = getattr(jac, "raw", None)

    def jf(t, y):
        try:
            return np.array(raw(*y.tolist(), *p) if raw else jac(y.tolist(), p), dtype=float)
        except _BAD:
            return np.full((len(y), len(y)), np.inf)
    return jf


IMPLICIT = ("Radau", "BDF", "LSODA")


def solve(rhs, jac, span, y0, p, method, rtol, atol, *, what, events=None, dense=False,
          t_eval=None, max_step=np.inf, fun=None, jac_fun=None):
    """Integrate; ModelError (naming ``what``) if scipy fails or returns non-finite values."""
    y0 = np.asarray(y0, dtype=float)
    fun = fun or as_fun(rhs, p, len(y0))
    kw = {}
    if method in IMPLICIT and (jac is not None or jac_fun is not None):
        kw["jac"] = jac_fun or as_jac(jac, p)
    with np.errstate(invalid="ignore", over="ignore", divide="ignore"):
        # an infinite trial value (rejected step) makes scipy's error estimate inf - inf
        # the explicit methods in their portable form (the same bits on every processor)
        cls = TightDOP853 if method == TIGHT else PORTABLE.get(method, method)
        sol = solve_ivp(fun, span, y0, method=cls, rtol=rtol, atol=atol, events=events,
                        dense_output=dense, t_eval=t_eval, max_step=max_step, **kw)
    if sol.status == -1:
        where = sol.t[-1] if len(sol.t) else span[0]
        err = ModelError(f"{what}: the integrator ({method}) failed at {where:.10g}: "
                         f"{sol.message}")
        err.sol = sol
        raise err
    if not np.all(np.isfinite(sol.y)):
        err = ModelError(f"{what}: the integrator ({method}) produced non-finite values; "
                         "the motion reached a singular point of the equations")
        err.sol = sol
        raise err
    return sol


# ----------------------------------------------------------------- zeros inside steps
#: Samples per step for :func:`roots_within_steps` (Chebyshev points of the first kind).
NODES = 16


def _cheb_matrix(n=NODES):
    j = np.arange(n)
    x = np.cos(np.pi * (j + 0.5) / n)                       # nodes on [-1, 1]
    T = np.cos(np.outer(np.arange(n), np.pi * (j + 0.5) / n))   # T_k(x_j)
    return x, T


_X, _T = _cheb_matrix()


def roots_within_steps(sol, g, first=False):
    """Every zero of ``g(t, Y)`` along a dense solution, including pairs of zeros that
    fall inside one step (a sign change that the values at the step ends do not show).

    ``g`` takes the times (1-d array) and the states (n x len(t)) and returns an
    array.  On each step g is sampled at NODES Chebyshev points of the
    interpolant and fitted by a Chebyshev series; the series' critical points
    split the step into pieces on which g is monotone (to the fit's accuracy);
    a piece whose ends differ in sign holds one zero, located by Brent's
    method on g itself.  Returns the sorted times; ``first``: at most one.

    >>> from scipy.integrate import solve_ivp
    >>> s = solve_ivp(lambda t, y: [1.0], (0, 2), [0.0], dense_output=True, max_step=10)
    >>> g = lambda t, Y: (Y[0] - 1) ** 2 - 1e-8       # zeros 1 -+ 1e-4, one step
    >>> [round(r, 6) for r in roots_within_steps(s, g)]
    [0.9999, 1.0001]
    """
    from numpy.polynomial import chebyshev as C
    from scipy.optimize import brentq
    ts = np.asarray(sol.t if hasattr(sol, "t") and not hasattr(sol, "ts") else sol.ts)
    dense = sol.sol if hasattr(sol, "sol") else sol
    if dense is None or len(ts) < 2:
        return []
    lo, hi = np.minimum(ts[:-1], ts[1:]), np.maximum(ts[:-1], ts[1:])
    mid, half = (lo + hi) / 2, (hi - lo) / 2
    tt = (mid[:, None] + half[:, None] * _X[None, :])
    with np.errstate(all="ignore"):
        vals = np.asarray(g(tt.ravel(), dense(tt.ravel())), dtype=float).reshape(tt.shape)
        coef = np.array([combine(vals.T, row) for row in _T]).T * (2.0 / NODES)
    coef[:, 0] /= 2
    tail = np.sum(np.abs(coef[:, 1:]), axis=1)
    maybe = ~(np.abs(coef[:, 0]) > 1.01 * tail) | ~np.isfinite(tail)
    back = bool(ts[-1] < ts[0])
    order = np.arange(len(lo))[::-1] if back else np.arange(len(lo))
    found = []

    def gs(t):
        return float(np.asarray(g(np.array([t]), dense(np.array([t]))), dtype=float)[0])
    for i in order:
        if not maybe[i]:
            continue
        a, b = lo[i], hi[i]
        cuts = [-1.0, 1.0]
        if np.all(np.isfinite(coef[i])):
            crit = C.chebroots(C.chebder(coef[i]))
            cuts += [float(r.real) for r in np.atleast_1d(crit)
                     if abs(r.imag) < 1e-9 and -1 < r.real < 1]
        pts = sorted((mid[i] + half[i] * np.array(cuts)).tolist(), reverse=back)
        vs = [gs(t) for t in pts]
        for (t0, v0), (t1, v1) in zip(zip(pts, vs), zip(pts[1:], vs[1:])):
            if v0 == 0:
                r = t0
            elif v0 * v1 < 0:
                r = brentq(gs, t0, t1, xtol=1e-15 * max(1.0, abs(t0)), rtol=1e-15)
            else:
                continue
            if not found or abs(r - found[-1]) > 1e-14 * max(1.0, abs(r)):
                found.append(r)
        if vs and vs[-1] == 0 and (not found or found[-1] != pts[-1]):
            found.append(pts[-1])
        if first and found:
            return found[:1]
    found = sorted(set(found), reverse=back)
    return found
