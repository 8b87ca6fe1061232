"""Maggi's equations (Maggi 1896): Lagrange's expressions projected on the independent
virtual displacements, no multipliers.

Every coordinate's Lagrange expression E_s = d/dt dL/dqdot_s - dL/dq_s is kept; the
virtual displacements allowed by the constraints (Chetaev's, for a nonlinear one)
are delta q_s = sum_sigma C_s,sigma delta q_sigma, C = dqdot_s/dqdot_sigma on the
constraints (1 or 0 for an independent coordinate, B_beta,sigma =
dphi_beta/dqdot_sigma for a dependent one).  The constraint forces do no work on
them, so

    sum_s C_s,sigma E_s = 0,    one per independent coordinate               [Mag]

with the dependent velocities and accelerations taken from the constraints (the
second from the constraints differentiated once, [Magc]).

>>> from whittaker_teach.forms import examples, Maggi
>>> Maggi(examples.rolling_disk()).accelerations()
{Derivative(psi(t), (t, 2)): -k**2*psi(t)/C, Derivative(theta(t), (t, 2)): 0}

Cost: n - g equations, no multipliers, no new variables; Lagrange's expressions of
every coordinate are formed first (the dependent ones too).
"""

from __future__ import annotations

from ..canonical import add, mul
from ..steps import Step, eq
from ._form import Form
from ._print import indexed

__all__ = ["Maggi"]


class Maggi(Form):
    """Maggi's equations: the projection on the independent virtual displacements (1896)."""

    label = "Mag"
    title = "Maggi: Lagrange's expressions projected on the free virtual displacements"
    source = "G. A. Maggi (1896)"
    needs = "n - g equations; Lagrange's expression of every coordinate"

    def _expressions(self):
        """E_s with the constraints at velocity and acceleration level substituted."""
        if "E" not in self._cache:
            S = self.system
            self._cache["E"] = [S.constrained(E) for E in S.lagrange_expressions()]
        return self._cache["E"]

    def _equations(self):
        if "eqs" not in self._cache:
            S, E = self.system, self._expressions()
            out = []
            for s in S.sigma:
                terms = []
                for c, e in zip(S.coordinates, E):
                    C = S.constrained(S.C(c, s))
                    if C != 0:
                        terms.append(mul(C, e))
                out.append(add(*terms))
            self._cache["eqs"] = out
        return self._cache["eqs"]

    def _steps_before(self):
        S = self.system
        return [
            Step("MagE", r"Lagrange's expressions $E_s = (d/dt)\,\partial L/\partial\dot q_s"
                 r" - \partial L/\partial q_s$ of every coordinate",
                 lambda: [eq(indexed("E", [S.q[c]]), E)
                          for c, E in zip(S.coordinates, S.lagrange_expressions())]),
            Step("Magc", "the dependent velocities and accelerations, from the constraints "
                 "and their derivative", lambda: [eq(k, v) for k, v in S.on_constraints.items()]),
            Step("MagC", r"the free virtual displacements: $\delta q_s = \sum_\sigma "
                 r"C_{s\sigma}\,\delta q_\sigma$, $C_{s\sigma} = \partial\dot q_s/\partial"
                 r"\dot q_\sigma$", lambda: [
                     eq(indexed("C", [S.q[c], S.q[s]]), S.C(c, s))
                     for c in S.beta for s in S.sigma]),
            Step("Mag", r"Maggi's equations $\sum_s C_{s\sigma} E_s = 0$",
                 lambda: [eq(e, 0) for e in self._equations()]),
        ]
