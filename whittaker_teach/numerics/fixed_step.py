"""Fixed-step explicit Runge-Kutta methods, for order and stability studies (chapter 15).

An adaptive integrator changes its step with the tolerance, so the slope of its
work-precision line is not its order (chapter 7).  With a *fixed* step ``dt`` the
global error of a method of order p behaves like ``C dt**p``: halving the step divides
it by about ``2**p``, and the **observed order** ``log2(e(dt) / e(dt/2))`` measures p.

Three classical methods, each a Butcher tableau (Hairer, Norsett & Wanner I, II.1):

=============  =====  ======  ===========================================
``"euler"``    order  1       one evaluation a step
``"midpoint"`` order  2       the explicit midpoint rule (two evaluations)
``"rk4"``      order  4       the classical Runge-Kutta method (four)
=============  =====  ======  ===========================================

:func:`integrate` takes ``steps`` equal steps, with plain numpy arithmetic in a fixed
order (no step-size control, no interpolation: the result at the end is the last step).
:func:`stability_interval` is the length beta of the real interval [-beta, 0] on which
the method's stability function R(z) has ``|R| <= 1``: a decaying mode of rate
``lam`` keeps a stable step below ``beta / lam``.  :func:`sledge_rhs` is the sledge in
the form (3.12)-(3.14), which (3.15) solves in closed form.

>>> import math
>>> f = lambda t, u: -u                      # u' = -u, u(0) = 1: u(1) = 1/e
>>> t, U, nfev = integrate(f, (0.0, 1.0), [1.0], 10, "rk4")
>>> bool(abs(U[-1, 0] - math.exp(-1)) < 1e-6), nfev
(True, 40)
>>> round(stability_interval("rk4"), 4), stability_interval("euler")
(2.7853, 2.0)
"""

from __future__ import annotations

import math

import numpy as np

from ..errors import ModelError

__all__ = ["TABLEAUS", "ORDERS", "integrate", "observed_order", "stability_function",
           "stability_interval", "sledge_rhs"]

#: (A, b, c) of each method: A strictly lower triangular (explicit)
TABLEAUS = {
    "euler": ([[0.0]], [1.0], [0.0]),
    "midpoint": ([[0.0, 0.0], [0.5, 0.0]], [0.0, 1.0], [0.0, 0.5]),
    "rk4": ([[0.0, 0.0, 0.0, 0.0], [0.5, 0.0, 0.0, 0.0], [0.0, 0.5, 0.0, 0.0],
             [0.0, 0.0, 1.0, 0.0]], [1 / 6, 1 / 3, 1 / 3, 1 / 6], [0.0, 0.5, 0.5, 1.0]),
}
#: the classical order of each method
ORDERS = {"euler": 1, "midpoint": 2, "rk4": 4}


def _tableau(method):
    if method not in TABLEAUS:
        raise ModelError(f"method = {method!r}: a fixed-step method is one of "
                         f"{', '.join(TABLEAUS)}")
    return TABLEAUS[method]


def integrate(f, t_span, y0, steps, method="rk4"):
    """``steps`` equal steps of ``method`` for y' = f(t, y) over ``t_span``: (t, Y, nfev),
    t the ``steps + 1`` times, Y[i] the state at t[i], nfev = stages * steps."""
    A, b, c = _tableau(method)
    if isinstance(steps, bool) or not isinstance(steps, (int, np.integer)) or steps < 1:
        raise ModelError(f"steps = {steps!r} must be a positive integer")
    t0, t1 = (float(v) for v in t_span)
    if not (math.isfinite(t0) and math.isfinite(t1)) or t1 == t0:
        raise ModelError(f"t_span = {t_span!r} must be two different finite times")
    y = np.array(y0, dtype=float)
    if y.ndim != 1 or not np.all(np.isfinite(y)):
        raise ModelError("y0 must be a flat list of finite numbers")
    dt = (t1 - t0) / steps
    s = len(b)
    t = t0 + dt * np.arange(steps + 1)
    t[-1] = t1
    Y = np.empty((steps + 1, len(y)))
    Y[0] = y
    for n in range(steps):
        K = []
        for i in range(s):
            yi = y.copy()
            for j in range(i):
                if A[i][j]:
                    yi = yi + dt * A[i][j] * K[j]
            K.append(np.asarray(f(t[n] + c[i] * dt, yi), dtype=float))
            if K[-1].shape != y.shape:
                raise ModelError(f"f(t, y) returned shape {K[-1].shape}; it must return one "
                                 f"number per component of y0, shape {y.shape}")
        for i in range(s):
            if b[i]:
                y = y + dt * b[i] * K[i]
        Y[n + 1] = y
    return t, Y, s * steps


def observed_order(e_coarse, e_fine, ratio=2.0):
    """log(e_coarse / e_fine) / log(ratio): the order seen from two errors, at steps in
    the ratio ``ratio`` (2: dt and dt/2).

    >>> observed_order(1.6e-5, 1e-6)
    4.0
    """
    if not (e_coarse > 0 and e_fine > 0):
        raise ModelError("observed_order needs two positive errors (an error of 0 says "
                         "the method is exact here, or round-off has taken over)")
    if not (math.isfinite(e_coarse) and math.isfinite(e_fine)):
        raise ModelError("observed_order needs two finite errors (an infinite one says the "
                         "run blew up: the step is outside the stability interval)")
    if not (math.isfinite(ratio) and ratio > 0 and ratio != 1):
        raise ModelError(f"ratio = {ratio!r} must be a finite positive number other than 1 "
                         "(the ratio of the two steps)")
    return math.log(e_coarse / e_fine) / math.log(ratio)


def stability_function(method, z):
    """R(z) = 1 + z b^T (I - z A)^-1 1: the factor by which one step multiplies the
    solution of y' = lam y, z = lam dt."""
    A, b, _ = _tableau(method)
    A, b = np.asarray(A), np.asarray(b)
    n = len(b)
    return 1 + z * b @ np.linalg.solve(np.eye(n) - z * A, np.ones(n))


def stability_interval(method):
    """beta: |R(-x)| <= 1 for 0 <= x <= beta: the first x > 0 where |R| exceeds 1, found by
    a scan in steps of 0.01 (an unstable window narrower than that could be missed; the
    methods here have none) and bisection to 1e-13."""
    def unstable(x):
        return abs(stability_function(method, -x)) > 1 + 1e-14
    k = 1
    while not unstable(0.01 * k):
        k += 1
    lo, hi = 0.01 * (k - 1), 0.01 * k
    while hi - lo > 1e-13:
        mid = 0.5 * (lo + hi)
        lo, hi = (lo, mid) if unstable(mid) else (mid, hi)
    return round(lo, 12)


def sledge_rhs(params, C):
    """The sledge as (3.12)-(3.15) integrate it: the state u = (theta, thetadot, x, y),
    theta'' = -(k^2/J) theta (3.14), xdot = C cos theta (3.12), ydot = C sin theta (3.13),
    C the constant speed along the runner.  The closed form of the same motion is
    ``examples.sledge_exact``."""
    missing = [p for p in ("J", "k") if p not in params]
    if missing:
        raise ModelError(f"params lacks {', '.join(missing)}: the sledge needs J and k")
    J, k, C = float(params["J"]), float(params["k"]), float(C)
    if not (math.isfinite(J) and J > 0 and math.isfinite(k) and math.isfinite(C)):
        raise ModelError(f"J = {J}, k = {k}, C = {C}: J must be positive, all three finite")
    w2 = k ** 2 / J

    def f(t, u):
        th, thd = u[0], u[1]
        return np.array([thd, -w2 * th, C * math.cos(th), C * math.sin(th)])
    return f
