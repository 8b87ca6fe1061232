"""Lagrange's equations with multipliers: the Routh-Voss form (Routh 1884, Voss 1885).

Every coordinate keeps its equation; each constraint f_beta(q, qdot) = 0 adds a
multiplier lambda_beta and the constraint force lambda_beta df_beta/dqdot_s (Chetaev's
definition of the virtual displacements for a nonlinear constraint):

    d/dt dL/dqdot_s - dL/dq_s + sum_beta lambda_beta df_beta/dqdot_s = 0     [RV]

(the sign of ``sympy.physics.mechanics.LagrangesMethod``: its ``rhs()`` lists
-lambda), closed by the constraints differentiated once,

    sum_s df_beta/dq_s qdot_s + df_beta/dqdot_s qddot_s = 0                   [RVc]

n + g equations, linear in the n accelerations and the g multipliers, solved
together ([RVa] the accelerations, [RVl] the multipliers).  The constraints are
used as given: ``constraints=[...]`` in their order and form, or f = qdot_beta -
phi_beta when they were given solved.

>>> from whittaker_teach.forms import examples, RouthVoss
>>> rv = RouthVoss(examples.sledge())
>>> rv.steps.labels
['RV', 'RVc', 'RVl', 'RVa']
>>> rv.multipliers()
[-m*Derivative(theta(t), t)*Derivative(x(t), t)]

Cost: the largest linear system of the forms (n + g unknowns); it needs no
elimination of the constraints first, and gives the constraint forces.
"""

from __future__ import annotations

import sympy as sp

from ..canonical import add, mul
from ..errors import guarded
from ..steps import Step, eq
from ..verify import check_identity
from ._form import Form
from ._print import tidy

__all__ = ["RouthVoss"]


class RouthVoss(Form):
    """Lagrange's equations of the first kind with multipliers (Routh 1884, Voss 1885)."""

    label = "RV"
    title = "Routh-Voss: Lagrange's equations with multipliers"
    source = "E. J. Routh (1884), A. Voss (1885)"
    needs = "n + g equations in the n accelerations and the g multipliers"
    multipliers_used = True

    def _lambdas(self):
        g = len(self.system.beta)
        return list(sp.symbols(f"lambda1:{g + 1}")) if g else []

    def _jacobian(self):
        """df_beta/dqdot_s on the constraints (Chetaev's coefficients)."""
        if "J" not in self._cache:
            S = self.system
            self._cache["J"] = [[S.constrained(S._d(f, S.qd[c])) for c in S.coordinates]
                                for f in S._f]
        return self._cache["J"]

    def _dynamic(self):
        """[RV]: one expression per coordinate, the dependent velocities substituted, the
        accelerations of every coordinate and the multipliers unknown."""
        if "dyn" not in self._cache:
            S, J, lam = self.system, self._jacobian(), self._lambdas()
            on = {S.qd[c]: phi for c, phi in S._phi.items()}
            from ..dag import substitute
            memo = {}
            out = []
            for s, E in enumerate(S.lagrange_expressions()):
                terms = [substitute(E, on, memo)]
                terms += [mul(l, row[s]) for l, row in zip(lam, J) if row[s] != 0]
                out.append(add(*terms))
            self._cache["dyn"] = out
        return self._cache["dyn"]

    def _acceleration_constraints(self):
        """[RVc]: d f_beta/dt = 0, linear in the accelerations."""
        if "acc_c" not in self._cache:
            S = self.system
            on = {S.qd[c]: phi for c, phi in S._phi.items()}
            from ..dag import substitute
            self._cache["acc_c"] = [substitute(S.rate(f), on) for f in S._f]
        return self._cache["acc_c"]

    def _equations(self):
        return self._dynamic() + self._acceleration_constraints()

    def _unknowns(self):
        S = self.system
        return [S.qdd[c] for c in S.coordinates] + self._lambdas()

    def _solution(self):
        """The n + g unknowns, eliminated in the order the constraints suggest: the
        constraints and the dependent coordinates' equations first, for the dependent
        accelerations and the multipliers, then the independent ones (the same solution;
        on the sleigh a tenth of the size of the order as listed)."""
        if "sol" not in self._cache:
            S = self.system
            dyn, con = self._dynamic(), self._acceleration_constraints()
            pos = {c: i for i, c in enumerate(S.coordinates)}
            eqs = con + [dyn[pos[c]] for c in S.beta] + [dyn[pos[c]] for c in S.sigma]
            unknowns = ([S.qdd[c] for c in S.beta] + self._lambdas()
                        + [S.qdd[c] for c in S.sigma])
            sol = S.solve_linear(eqs, unknowns, "the matrix of Lagrange's equations with "
                                 "multipliers and the constraints")
            self._cache["sol"] = dict(zip(unknowns, sol))
        return self._cache["sol"]

    def _steps_before(self):
        lam = self._lambdas()
        st = [Step("RV", "Lagrange's equations with the multipliers "
                   r"$\lambda_\beta$ of the constraints, one per coordinate "
                   r"($\partial f_\beta/\partial\dot q_s$: Chetaev's virtual displacements)",
                   lambda: [eq(e, 0) for e in self._dynamic()])]
        if lam:
            st.append(Step("RVc", "the constraints differentiated once (linear in the "
                           "accelerations)", lambda: [eq(e, 0) for e in
                                                       self._acceleration_constraints()]))
            sol, shown = self._solution(), self._tidied()
            S = self.system
            chk = check_identity("RVl", "the multipliers shown (one fraction, "
                                 r"$\sin^2 + \cos^2 = 1$ where it shortens) are those solved",
                                 [shown[l] for l in lam], [sol[l] for l in lam], S.sample,
                                 seed=23)
            st.append(Step("RVl", "the multipliers, solved with the accelerations",
                           [eq(l, shown[l]) for l in lam], chk))
        return st

    def _tidied(self):
        """{lambda_beta: the multiplier solved, tidied}: one fraction, the numerator
        collected on the independent velocities, sin^2 + cos^2 read as 1 where it
        shortens (:func:`._print.tidy`; internal symbols)."""
        if "lam" not in self._cache:
            S, sol = self.system, self._solution()
            sig = [S.qd[c] for c in S.sigma]
            self._cache["lam"] = {l: tidy(sol[l], sig) for l in self._lambdas()}
        return self._cache["lam"]

    @guarded("solving for the multipliers")
    def multipliers(self):
        """lambda_beta, one per constraint as given (LagrangesMethod's sign), as functions
        of the coordinates and the independent velocities."""
        S, lam = self.system, self._tidied()
        return [S.to_public(lam[l]) for l in self._lambdas()]
