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

import numpy as np
from scipy.integrate import solve_ivp

from ..errors import ModelError

__all__ = ["solve", "as_fun"]

_BAD = (ZeroDivisionError, ValueError, OverflowError)


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
        sol = solve_ivp(fun, span, y0, method=method, rtol=rtol, atol=atol, events=events,
                        dense_output=dense, t_eval=t_eval, max_step=max_step, **kw)
    if sol.status == -1:
        where = sol.t[-1] if len(sol.t) else span[0]
        raise ModelError(f"{what}: the integrator ({method}) failed at {where:.10g}: "
                         f"{sol.message}")
    if not np.all(np.isfinite(sol.y)):
        raise ModelError(f"{what}: the integrator ({method}) produced non-finite values; "
                         "the motion reached a singular point of the equations")
    return sol
