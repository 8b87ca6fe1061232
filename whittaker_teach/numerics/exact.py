r"""The sledge in closed form: (3.12)-(3.15) integrated with the Jacobi-Anger expansion.

theta = a cos(psi), psi = omega t + phi, omega = k/sqrt(J) (3.15); the speed C
is constant, xdot = C cos(theta), ydot = C sin(theta) (3.12), (3.13).  With

    cos(a cos psi) = J_0(a) + 2 sum_{n>=1} (-1)^n J_{2n}(a) cos(2n psi)
    sin(a cos psi) = 2 sum_{n>=0} (-1)^n J_{2n+1}(a) cos((2n+1) psi)

the quadratures are sums of sines:

    x = x0 + C J_0(a) t + (2C/omega) sum_{n>=1} (-1)^n J_{2n}(a) [sin 2n psi]/(2n)
    y = y0 + (2C/omega) sum_{n>=0} (-1)^n J_{2n+1}(a) [sin (2n+1) psi]/(2n+1)

([f] is f(psi) - f(phi)).  The mean drift along x is C J_0(a); the series are
cut where |J_n(a)| < 1e-18 (the Bessel functions decay like (a/2)^n/n!), so
the sums are exact to rounding, about 1e-15.  No square root appears (theta
dot is -a omega sin psi), so round-off near the turning points cannot make a
NaN (hard case 7).

>>> ex = SledgeExact({"m": 1, "J": 1, "k": 1}, a=0.5, phi=0.0, C=1.0)
>>> s = ex(0.0)
>>> s["theta"], s["x"], s["y"], s["thetadot"]
(0.5, 0.0, 0.0, -0.0)
>>> round(ex.drift, 12)      # C J_0(a)
0.938469807241
>>> round(ex(2 * 3.141592653589793)["x"] / (2 * 3.141592653589793), 12)   # one period
0.938469807241
"""

from __future__ import annotations

import math

import numpy as np
from scipy.special import jv

from ..errors import ModelError
from .ivp import ARITHMETIC
from .portable import combine
from .validate import ROUNDOFF, real

__all__ = ["SledgeExact", "sledge_exact", "terms_needed", "MAX_TERMS"]

#: Terms with |J_n(a)| below this are dropped.
CUT = 1e-18
#: The most Bessel terms the closed form will use; a larger amplitude is refused (each
#: evaluation costs one sine per term, and the coefficients one array of that length).
MAX_TERMS = 20_000


def _top(a):
    """An upper bound of the terms needed: J_n(a) < 1e-18 beyond a + 10 a^(1/3) + 40."""
    return abs(a) + 10 * abs(a) ** (1 / 3) + 40


def terms_needed(a):
    """The number n of Bessel functions J_0..J_{n-1}(a) the series need.

    >>> terms_needed(0.5), terms_needed(1.5)
    (14, 18)
    >>> terms_needed(5e7)                  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    whittaker_teach.errors.ModelError: the closed form ... a = 5e+07 needs about 5.00e+07 Bessel terms ...
    """
    if not _top(a) <= MAX_TERMS:
        raise ModelError(f"the closed form of the sledge with amplitude a = {a:.6g} needs about "
                         f"{_top(a):.2e} Bessel terms (limit MAX_TERMS = {MAX_TERMS}; each "
                         "evaluation costs one sine per term): use the full model, "
                         "system.simulate(...)")
    top = int(_top(a))
    j = np.abs(jv(np.arange(top), abs(a)))
    big = np.nonzero(j > CUT)[0]
    return int(big[-1]) + 1 if len(big) else 1


def _param(params, name):
    if not isinstance(params, dict):
        raise ModelError(f"params must be a dict with m, J and k, got {type(params).__name__}")
    for key, val in params.items():
        if (key if isinstance(key, str) else getattr(key, "name", None)) == name:
            x = real(val, f"params[{name}]")
            if x <= 0:
                raise ModelError(f"params[{name}] = {x} must be positive")
            return x
    raise ModelError(f"params: no value for the parameter {name} (the sledge needs J, k, m)")


class SledgeExact:
    """The exact motion of the sledge: ``ex(t)`` -> {x, y, theta, xdot, ydot, thetadot}.

    Give the amplitude ``a`` (or the energy ``h``, then a = sqrt(2h - m C^2)/k),
    the phase ``phi`` at t = t0, the speed ``C`` and the start (x0, y0).
    Attributes: ``omega``, ``period``, ``h`` (3.4), ``drift`` (C J_0(a)).
    """

    def __init__(self, params, a=None, phi=0.0, C=1.0, *, h=None, x0=0.0, y0=0.0, t0=0.0):
        try:
            self._init(params, a, phi, C, h, x0, y0, t0)
        except ARITHMETIC as err:
            raise ModelError(f"sledge_exact: the arithmetic failed ({err}): the parameters, "
                             "the amplitude or the speed are out of floating point's range"
                             ) from None

    def _init(self, params, a, phi, C, h, x0, y0, t0):
        self.m, self.J, self.k = (_param(params, n) for n in ("m", "J", "k"))
        self.C = real(C, "C")
        self.phi, self.x0, self.y0, self.t0 = (real(v, n) for v, n in
                                               ((phi, "phi"), (x0, "x0"), (y0, "y0"),
                                                (t0, "t0")))
        if (a is None) == (h is None):
            raise ModelError("give exactly one of the amplitude a and the energy h")
        if a is None:
            a = self._amplitude(real(h, "h"))
        self.a = real(a, "a")
        terms_needed(self.a)                       # refuses a hopeless amplitude first
        self.omega = self.k / math.sqrt(self.J)
        self.period = 2 * math.pi / self.omega
        self.h = 0.5 * self.m * self.C ** 2 + 0.5 * self.k ** 2 * self.a ** 2
        self._coefficients()

    def _amplitude(self, h):
        """a = sqrt(2h - m C^2)/k; a radicand within round-off below zero is clipped to 0
        (:data:`~whittaker_teach.numerics.validate.ROUNDOFF`), further below is an error."""
        rad = 2 * h - self.m * self.C ** 2
        if rad < 0:
            if rad < -ROUNDOFF * (abs(2 * h) + self.m * self.C ** 2):
                raise ModelError(f"h = {h} is below the kinetic energy m C^2/2 = "
                                 f"{self.m * self.C ** 2 / 2} of the speed C: no such motion "
                                 "(3.4)")
            rad = 0.0
        return math.sqrt(rad) / self.k

    def _coefficients(self):
        a, C, w = self.a, self.C, self.omega
        N = terms_needed(a)
        n = np.arange(N)
        J = jv(n, a)
        self.J0 = float(J[0])
        self.drift = C * self.J0
        sign = np.where((n // 2) % 2 == 0, 1.0, -1.0)          # (-1)^(n//2)
        even, odd = n[2::2], n[1::2]
        self._ke = even.astype(float)
        self._ce = 2 * C * sign[2::2] * J[2::2] / (even * w)
        self._ko = odd.astype(float)
        self._co = 2 * C * sign[1::2] * J[1::2] / (odd * w)
        self._se = np.sin(self._ke * self.phi)
        self._so = np.sin(self._ko * self.phi)
        self._even = list(zip(self._ke.tolist(), self._ce.tolist(), self._se.tolist()))
        self._odd = list(zip(self._ko.tolist(), self._co.tolist(), self._so.tolist()))

    def __call__(self, t):
        if np.ndim(t) == 0:
            return self._scalar(float(t))
        tt = np.asarray(t, dtype=float) - self.t0
        psi = self.omega * tt + self.phi
        th = self.a * np.cos(psi)
        # the series summed term by term in order (``combine``), not by the BLAS: the same
        # bits on every processor
        x = self.x0 + self.drift * tt + combine((np.sin(np.outer(psi, self._ke))
                                                 - self._se).T, self._ce)
        y = self.y0 + combine((np.sin(np.outer(psi, self._ko)) - self._so).T, self._co)
        out = {"x": x, "y": y, "theta": th, "xdot": self.C * np.cos(th),
               "ydot": self.C * np.sin(th), "thetadot": -self.a * self.omega * np.sin(psi)}
        return out

    def _scalar(self, t):
        """One instant, in plain floats (math.sin on each term: no array overhead)."""
        tt = t - self.t0
        psi = self.omega * tt + self.phi
        sin = math.sin
        x = self.x0 + self.drift * tt
        for k, c, s0 in self._even:
            x += c * (sin(k * psi) - s0)
        y = self.y0
        for k, c, s0 in self._odd:
            y += c * (sin(k * psi) - s0)
        th = self.a * math.cos(psi)
        return {"x": x, "y": y, "theta": th, "xdot": self.C * math.cos(th),
                "ydot": self.C * math.sin(th), "thetadot": -self.a * self.omega * sin(psi)}

    def energy(self, state):
        """The energy (3.4) of a state ``self(t)``, computed from its values (not assumed):
        m (xdot^2 + ydot^2)/2 + J thetadot^2/2 + k^2 theta^2/2."""
        s = state
        return (0.5 * self.m * (s["xdot"] ** 2 + s["ydot"] ** 2)
                + 0.5 * self.J * s["thetadot"] ** 2 + 0.5 * self.k ** 2 * s["theta"] ** 2)

    def phase(self, t):
        """psi = omega (t - t0) + phi, the phase of theta = a cos(psi)."""
        return self.omega * (np.asarray(t, dtype=float) - self.t0) + self.phi

    def initial(self, t=None):
        """(q0, qdot0) at t (default t0), for :meth:`ChaplyginSystem.simulate`."""
        s = self(self.t0 if t is None else t)
        return ({"x": s["x"], "theta": s["theta"], "y": s["y"]},
                {"x": s["xdot"], "theta": s["thetadot"]})

    def reduced_initial(self, t=None, direction=+1):
        """(q0, qp0, h) at t (default t0), for the reduction in x with sign(xdot) =
        ``direction``: theta' = thetadot/xdot."""
        s = self(self.t0 if t is None else t)
        if s["xdot"] * direction <= 0:
            raise ModelError(f"xdot = {s['xdot']:.6g} at this instant: not of the sign "
                             f"{direction:+d} of the reduction in x")
        return ({"x": s["x"], "theta": s["theta"], "y": s["y"]},
                {"theta": s["thetadot"] / s["xdot"]}, self.h)

    def __repr__(self):
        return (f"<SledgeExact: a = {self.a:g}, phi = {self.phi:g}, C = {self.C:g}, "
                f"omega = {self.omega:g}, {len(self._ke) + len(self._ko) + 1} Bessel terms>")


def sledge_exact(params, a=None, phi=0.0, C=1.0, **kw):
    """The sledge's exact motion, a :class:`SledgeExact` (callable t -> dict)."""
    return SledgeExact(params, a, phi, C, **kw)
