"""Nielsen's (Nielsen 1935) and Tzenoff's (Tzenoff 1924) forms of the equations of
motion, for a non-holonomic system.

With T = L - L(qdot = 0) and V = -L(qdot = 0), Q_s = -dV/dq_s, Nielsen's form
differentiates the rate of T in the velocities,

    N_s = dTdot/dqdot_s - 2 dT/dq_s - Q_s                                    [Ni]

and Tzenoff's its second rate in the accelerations,

    Z_s = 1/2 dTddot/dqddot_s - 3/2 dT/dq_s - Q_s                             [Tz]

(Tdot, Tddot: total time derivatives over every coordinate; Tddot contains the
jerks qdddot, which the derivative in qddot leaves out).  Both equal Lagrange's
expression d/dt dT/dqdot_s - dT/dq_s - Q_s (by dfdot/dqdot = d/dt df/dqdot +
df/dq), which the steps check.  For the non-holonomic system each is projected
on the free virtual displacements, as Maggi projects Lagrange's:
sum_s C_s,sigma N_s = 0 (resp. Z_s), with the dependent velocities and
accelerations from the constraints.  This is the form Mei's (2.1)-(2.4)
generalise (there in the reduced, Whittaker variables: :mod:`whittaker_teach.nielsen`).

>>> from whittaker_teach.forms import examples, Nielsen, Tzenoff
>>> Nielsen(examples.sledge()).accelerations() == Tzenoff(examples.sledge()).accelerations()
True
"""

from __future__ import annotations

import sympy as sp

from ..canonical import add, mul
from ..steps import Step, eq
from ..verify import check_identity
from ._form import Form
from ._print import indexed

__all__ = ["Nielsen", "Tzenoff"]


class _Projected(Form):
    """An operator applied to T per coordinate, projected with C (Maggi's coefficients)."""

    def _operator(self):
        raise NotImplementedError

    def _full(self):
        """The operator per coordinate, before the constraints are substituted."""
        if "full" not in self._cache:
            self._cache["full"] = self._operator()
        return self._cache["full"]

    def _equations(self):
        if "eqs" not in self._cache:
            S = self.system
            E = [S.constrained(e) for e in self._full()]
            self._cache["eqs"] = [add(*[mul(S.constrained(S.C(c, s)), e)
                                        for c, e in zip(S.coordinates, E)
                                        if S.C(c, s) != 0]) for s in S.sigma]
        return self._cache["eqs"]

    def _lagrange_check(self):
        """The operator equals d/dt dT/dqdot_s - dT/dq_s - Q_s, per coordinate."""
        S, T = self.system, self.system.kinetic
        lag = [add(S.rate(S._d(T, S.qd[c])), -S._d(T, S.q[c]), -Q)
               for c, Q in zip(S.coordinates, S.forces())]
        return check_identity(f"{self.label}s", "each is Lagrange's expression "
                              r"$\frac{d}{dt}\frac{\partial T}{\partial\dot q_s} - "
                              r"\frac{\partial T}{\partial q_s} - Q_s$ of every coordinate",
                              self._full(), lag, S.sample, seed=7)


class Nielsen(_Projected):
    """Nielsen's form dTdot/dqdot_s - 2 dT/dq_s = Q_s, projected (Nielsen 1935)."""

    label = "Ni"
    title = "Nielsen: the rate of T differentiated in the velocities"
    source = "J. Nielsen (1935)"
    needs = "n - g equations; Tdot, then its derivatives in the velocities"

    def Tdot(self):
        """dT/dt over every coordinate (internal symbols)."""
        if "Td" not in self._cache:
            S = self.system
            self._cache["Td"] = S.rate(S.kinetic)
        return self._cache["Td"]

    def _operator(self):
        S, T, Td = self.system, self.system.kinetic, self.Tdot()
        return [add(S._d(Td, S.qd[c]), mul(-2, S._d(T, S.q[c])), -Q)
                for c, Q in zip(S.coordinates, S.forces())]

    def _steps_before(self):
        S = self.system
        return [Step("NiT", r"$\dot T$, the rate of $T = L - L|_{\dot q = 0}$",
                     lambda: [eq(sp.Symbol("Tdot"), self.Tdot())]),
                Step("Nis", r"Nielsen's expressions $\partial\dot T/\partial\dot q_s - "
                     r"2\,\partial T/\partial q_s - Q_s$ of every coordinate",
                     lambda: [eq(indexed("N", [S.q[c]]), e)
                              for c, e in zip(S.coordinates, self._full())],
                     self._lagrange_check()),
                Step("Ni", r"Nielsen's equations projected: $\sum_s C_{s\sigma} N_s = 0$",
                     lambda: [eq(e, 0) for e in self._equations()])]


class Tzenoff(_Projected):
    """Tzenoff's form 1/2 dTddot/dqddot_s - 3/2 dT/dq_s = Q_s, projected (Tzenoff 1924)."""

    label = "Tz"
    title = "Tzenoff: the second rate of T differentiated in the accelerations"
    source = "I. Tzenoff (1924)"
    needs = "n - g equations; Tddot (with the jerks), then its derivatives in the accelerations"

    def Tddot(self):
        """d^2T/dt^2 over every coordinate (contains the jerks qdddot)."""
        if "Tdd" not in self._cache:
            S = self.system
            self._cache["Tdd"] = S.rate(S.rate(S.kinetic))
        return self._cache["Tdd"]

    def _operator(self):
        S, T, Tdd = self.system, self.system.kinetic, self.Tddot()
        half = sp.Rational(1, 2)
        return [add(mul(half, S._d(Tdd, S.qdd[c])), mul(-sp.Rational(3, 2), S._d(T, S.q[c])),
                    -Q) for c, Q in zip(S.coordinates, S.forces())]

    def _steps_before(self):
        S = self.system
        return [Step("TzT", r"$\ddot T$, the second rate of $T$ (with the jerks)",
                     lambda: [eq(sp.Symbol("Tddot"), self.Tddot())]),
                Step("Tzs", r"Tzenoff's expressions $\frac{1}{2}\,\partial\ddot T/\partial\ddot q_s"
                     r" - \frac{3}{2}\,\partial T/\partial q_s - Q_s$ of every coordinate",
                     lambda: [eq(indexed("Z", [S.q[c]]), e)
                              for c, e in zip(S.coordinates, self._full())],
                     self._lagrange_check()),
                Step("Tz", r"Tzenoff's equations projected: $\sum_s C_{s\sigma} Z_s = 0$",
                     lambda: [eq(e, 0) for e in self._equations()])]
