"""Voronets' equations (Voronets 1901): the dependent coordinates kept, the multipliers
eliminated; Chaplygin's equations (Chaplygin 1897; Mei's (1.4)) where they apply.

With L~(q, qdot_sigma) = L with the constraints qdot_beta = phi_beta(q, qdot_sigma)
substituted (it still depends on the dependent coordinates q_beta), and
B_beta,sigma = dphi_beta/dqdot_sigma, P_beta = (dL/dqdot_beta)~:

    d/dt dL~/dqdot_sigma - dL~/dq_sigma - sum_beta B_beta,sigma dL~/dq_beta
        - sum_beta P_beta [d/dt B_beta,sigma - dphi_beta/dq_sigma
                           - sum_gamma dphi_beta/dq_gamma B_gamma,sigma] = 0       [Vor]

one equation per independent coordinate, d/dt along the constrained motion
(qdot_beta = phi_beta).  For linear constraints phi_beta = sum b_beta,tau qdot_tau
the bracket is sum_tau A^beta_sigma,tau qdot_tau with Voronets' coefficients
A^beta_sigma,tau = X_tau b_beta,sigma - X_sigma b_beta,tau (X_sigma = d/dq_sigma +
sum_gamma b_gamma,sigma d/dq_gamma), shown in step [VorA]; for Chetaev constraints the
same equation holds with Chetaev's coefficients (Mei's (1.2) is this nonlinear form).
When neither L nor the phi_beta contain a q_beta (Chaplygin's condition, 1.3) the
terms in d/dq_beta vanish and [Vor] is Chaplygin's (1.4): :meth:`Voronets.chaplygin`
delegates to :class:`~whittaker_teach.system.ChaplyginSystem`.

>>> from whittaker_teach.forms import examples, Voronets
>>> v = Voronets(examples.sledge_in_a_well())
>>> x, th, y = v.system.coordinates
>>> v.accelerations()[th.diff(examples.t, 2)]
0
>>> v.steps.labels
['VorL', 'VorP', 'VorA', 'Vor', 'Vora']
>>> v.chaplygin()
Traceback (most recent call last):
...
whittaker_teach.errors.ModelError: Chaplygin's equations (1.4) do not apply: L depends on the dependent coordinate y (Chaplygin condition, 1.3: L must be free of the dependent coordinates); use Voronets' equations
"""

from __future__ import annotations

import sympy as sp

from ..canonical import add, mul
from ..dag import along, substitute
from ..errors import ModelError, guarded
from ..steps import Step, eq
from ._form import Form
from ._print import indexed, tidy

__all__ = ["Voronets"]


class Voronets(Form):
    """Voronets' equations: dependent coordinates kept, no multipliers (Voronets 1901)."""

    label = "Vor"
    title = "Voronets: the dependent coordinates kept"
    source = "P. V. Voronets (1901); Chaplygin (1897) where L and phi are free of q_beta"
    needs = "n - g equations in the independent accelerations; L~ and the constraints' derivatives"

    def _rate(self, f):
        """d/dt of f(q, qdot_sigma) along the constrained motion."""
        S = self.system
        rates = {}
        for c in S.coordinates:
            rates[S.q[c]] = S._phi[c] if c in S._phi else S.qd[c]
        for c in S.sigma:
            rates[S.qd[c]] = S.qdd[c]
        return along(f, rates, self._cache.setdefault("along", {}))

    def _Ltilde(self):
        if "Lt" not in self._cache:
            S = self.system
            self._cache["Lt"] = substitute(S._L, {S.qd[c]: phi for c, phi in S._phi.items()})
        return self._cache["Lt"]

    def _momenta(self):
        """P_beta = (dL/dqdot_beta)~."""
        S = self.system
        on = {S.qd[c]: phi for c, phi in S._phi.items()}
        return {c: substitute(S._d(S._L, S.qd[c]), on) for c in S.beta}

    def _bracket(self, b, s):
        """d/dt B_b,s - dphi_b/dq_s - sum_gamma dphi_b/dq_gamma B_gamma,s."""
        S = self.system
        phi = S._phi[b]
        terms = [self._rate(S.B(b, s)), -S._d(phi, S.q[s])]
        for g in S.beta:
            d = S._d(phi, S.q[g])
            if d != 0:
                terms.append(-mul(d, S.B(g, s)))
        return add(*terms)

    def _equations(self):
        if "eqs" not in self._cache:
            S, Lt, P = self.system, self._Ltilde(), self._momenta()
            out = []
            for s in S.sigma:
                terms = [self._rate(S._d(Lt, S.qd[s])), -S._d(Lt, S.q[s])]
                for b in S.beta:
                    dq = S._d(Lt, S.q[b])
                    if dq != 0:
                        terms.append(-mul(S.B(b, s), dq))
                    br = self._bracket(b, s)
                    if br != 0:
                        terms.append(-mul(P[b], br))
                out.append(add(*terms))
            self._cache["eqs"] = out
        return self._cache["eqs"]

    def coefficients(self):
        """Voronets' coefficients {(beta, sigma, tau): A} of linear constraints (internal
        symbols): A = X_tau b_beta,sigma - X_sigma b_beta,tau; ModelError for nonlinear ones."""
        S = self.system
        if not S.is_linear:
            raise ModelError("Voronets' coefficients A^beta_sigma,tau belong to linear "
                             "constraints; for Chetaev constraints the bracket of [Vor] is "
                             "used as it stands")
        if "A" not in self._cache:
            def X(f, s):
                return add(S._d(f, S.q[s]), *[mul(S.B(g, s), S._d(f, S.q[g])) for g in S.beta])
            out = {}
            for b in S.beta:
                for i, s in enumerate(S.sigma):
                    for tau in S.sigma[i + 1:]:
                        A = add(X(S.B(b, s), tau), -X(S.B(b, tau), s))
                        if A != 0:
                            out[(b, s, tau)] = A
            self._cache["A"] = out
        return self._cache["A"]

    def _steps_before(self):
        S = self.system
        st = [Step("VorL", r"$\tilde L$: the Lagrangian with the dependent velocities "
                   "substituted (the dependent coordinates stay)",
                   lambda: [eq(sp.Symbol("Ltilde"), self._Ltilde())]),
              Step("VorP", r"the dependent momenta $P_\beta = (\partial L/\partial\dot "
                   r"q_\beta)\tilde{}$", lambda: [eq(indexed("P", [S.q[b]]), p)
                                                  for b, p in self._momenta().items()])]
        if S.is_linear and S.beta:
            st.append(Step("VorA", r"Voronets' coefficients $A^\beta_{\sigma\tau}$ "
                           "(those not zero)", lambda: [
                               eq(indexed("A", [S.q[s], S.q[tau]], sup=S.q[b]), tidy(A))
                               for (b, s, tau), A in self.coefficients().items()]))
        st.append(Step("Vor", "Voronets' equations, one per independent coordinate",
                       lambda: [eq(e, 0) for e in self._equations()]))
        return st

    @guarded("Chaplygin's equations (1.4)")
    def chaplygin(self):
        """The :class:`~whittaker_teach.system.ChaplyginSystem` of this system, whose
        steps show Chaplygin's equations (1.4) (and whose reduction is Mei's): only when
        L and the constraints are free of the dependent coordinates, else ModelError
        naming the condition."""
        S = self.system
        why = S.why_not_chaplygin
        if why:
            raise ModelError(f"Chaplygin's equations (1.4) do not apply: {why}; use "
                             "Voronets' equations")
        from ..system import ChaplyginSystem
        return ChaplyginSystem(S.lagrangian, S.coordinates, dependent=dict(S.constraints),
                               name=S.name)
