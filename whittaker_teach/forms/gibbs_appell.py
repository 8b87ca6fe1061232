"""The Gibbs-Appell equations (Gibbs 1879, Appell 1899): the acceleration energy S.

For bodies, S = 1/2 sum m a^2; for a system given by its Lagrangian, with T = L -
L(qdot = 0) (the part with the velocities) and V = -L(qdot = 0), the acceleration
energy is, up to terms free of the accelerations,

    S = 1/2 sum_r,s M_rs qddot_r qddot_s + sum_s qddot_s G_s,
    M_rs = d^2T/dqdot_r dqdot_s,  G_s = sum_r d^2T/dqdot_s dq_r qdot_r - dT/dq_s   [GAs]

(so that dS/dqddot_s = d/dt dT/dqdot_s - dT/dq_s, which is what defines it).  The
constraints are substituted at velocity and acceleration level (qddot_beta =
d phi_beta/dt, linear in the independent accelerations), giving S~(q, qdot_sigma,
qddot_sigma) [GAr], and with the generalized forces of V on the free virtual
displacements, Q~_sigma = sum_s C_s,sigma (-dV/dq_s) [GAq], Appell's equations are

    dS~/dqddot_sigma = Q~_sigma,   one per independent coordinate              [GA]

valid for linear constraints and for nonlinear ones with Chetaev's virtual
displacements (the accelerations' derivatives qddot_beta'(qddot_sigma) are
Chetaev's coefficients).

>>> from whittaker_teach.forms import examples, GibbsAppell
>>> ga = GibbsAppell(examples.appell_hamel())
>>> ga.accelerations()[list(ga.accelerations())[0]]
-c*g_0*Derivative(x(t), t)/((c**2 + 1)*sqrt(Derivative(x(t), t)**2 + Derivative(y(t), t)**2))

Cost: one scalar S, quadratic in the accelerations, and n - g derivatives of it;
no multipliers, no Lagrange expressions of the dependent coordinates.
"""

from __future__ import annotations

import sympy as sp

from ..canonical import add, mul
from ..dag import substitute
from ..steps import Step, eq
from ._form import Form
from ._print import indexed

__all__ = ["GibbsAppell"]


class GibbsAppell(Form):
    """Appell's equations dS~/dqddot_sigma = Q~_sigma (Gibbs 1879, Appell 1899).

    ``via="lagrangian"`` (default): S from T as above.  ``via="bodies"``: for a system
    built by :func:`~whittaker_teach.forms.from_mechanics` from a model with bodies
    (KanesMethod, System, LagrangesMethod with ``bodies`` and ``frame``), S is summed
    over the bodies themselves, 1/2 m a_G.a_G + 1/2 alpha.I_G.alpha + alpha.(omega x
    I_G.omega) for a rigid body (1/2 m a.a for a particle), the accelerations taken by
    sympy.physics.vector in the inertial frame: another route to the same equations."""

    label = "GA"
    title = "Gibbs-Appell: the acceleration energy"
    source = "J. W. Gibbs (1879), P. Appell (1899)"
    needs = "n - g equations; the acceleration energy S with the constraints substituted"

    def __init__(self, system, via="lagrangian"):
        self.via = via
        super().__init__(system)

    @property
    def name(self):
        return "GibbsAppell" if self.via == "lagrangian" else "GibbsAppell from bodies"

    def _require(self):
        from ..errors import ModelError
        if self.via not in ("lagrangian", "bodies"):
            raise ModelError("via must be 'lagrangian' or 'bodies'")
        if self.via == "bodies" and _bodies(self.system.source) is None:
            raise ModelError("via='bodies' needs a system built by from_mechanics from a "
                             "model with bodies and an inertial frame (KanesMethod, System, "
                             "or LagrangesMethod(..., bodies=..., frame=...)); a Lagrangian "
                             "alone has no bodies")

    def _S_bodies(self):
        """S summed over the bodies of the mechanics model (internal symbols)."""
        import sympy.physics.mechanics as me
        S = self.system
        frame, bodies, speeds = _bodies(S.source)
        t = S._t
        back = {}
        for q, u in speeds:                     # u = qdot: speeds and their rates
            back[u.diff(t)] = q.diff(t, 2)
            back[u] = q.diff(t)
        terms = []
        for b in bodies:
            a = b.masscenter.acc(frame)
            terms.append(b.mass * a.dot(a) / 2)
            if isinstance(b, me.RigidBody):
                I = b.central_inertia
                w = b.frame.ang_vel_in(frame)
                al = b.frame.ang_acc_in(frame)
                terms.append(al.dot(I.dot(al)) / 2 + al.dot(w.cross(I.dot(w))))
        return S.to_internal(sp.Add(*terms).xreplace(back))

    def acceleration_energy(self, constrained=False):
        """S (or S~, ``constrained=True``) in dynamicsymbols."""
        S = self.system
        return S.to_public(self._S_tilde() if constrained else self._S())

    def _S(self):
        if "S" not in self._cache and self.via == "bodies":
            self._cache["S"] = self._S_bodies()
        if "S" not in self._cache:
            S, T = self.system, self.system.kinetic
            dT = {c: S._d(T, S.qd[c]) for c in S.coordinates}
            terms = []
            cs = S.coordinates
            for i, r in enumerate(cs):
                for s in cs[i:]:
                    M = S._d(dT[r], S.qd[s])
                    if M != 0:
                        k = sp.Rational(1, 2) if r == s else sp.S.One
                        terms.append(mul(k, M, S.qdd[r], S.qdd[s]))
            for s in cs:
                G = add(*[mul(S._d(dT[s], S.q[r]), S.qd[r]) for r in cs], -S._d(T, S.q[s]))
                if G != 0:
                    terms.append(mul(S.qdd[s], G))
            self._cache["S"] = add(*terms)
        return self._cache["S"]

    def _S_tilde(self):
        if "St" not in self._cache:
            S = self.system
            self._cache["St"] = S.constrained(self._S())
        return self._cache["St"]

    def _forces(self):
        if "Q" not in self._cache:
            S = self.system
            Q = S.forces()
            self._cache["Q"] = [S.constrained(add(*[mul(S.C(c, s), q)
                                                    for c, q in zip(S.coordinates, Q)]))
                                for s in S.sigma]
        return self._cache["Q"]

    def _equations(self):
        if "eqs" not in self._cache:
            S, St = self.system, self._S_tilde()
            self._cache["eqs"] = [add(S._d(St, S.qdd[s]), -Q)
                                  for s, Q in zip(S.sigma, self._forces())]
        return self._cache["eqs"]

    def _steps_before(self):
        S = self.system
        return [
            Step("GAs", "the acceleration energy of the unconstrained system, from "
                 + (r"$T = L - L|_{\dot q = 0}$ (terms free of the accelerations left out)"
                    if self.via == "lagrangian" else "the bodies: "
                    r"$\frac12 m\,a_G^2 + \frac12\alpha\cdot I_G\alpha + "
                    r"\alpha\cdot(\omega\times I_G\omega)$ each"),
                 lambda: [eq(sp.Symbol("S"), self._S())]),
            Step("GAr", r"$\tilde S$: the constraints substituted at velocity and "
                 "acceleration level",
                 lambda: [eq(sp.Symbol("Stilde"), self._S_tilde())]),
            Step("GAq", r"the generalized forces on the free virtual displacements, "
                 r"$\tilde Q_\sigma = -\sum_s C_{s\sigma}\,\partial V/\partial q_s$",
                 lambda: [eq(indexed("Q̃", [S.q[s]], base_tex=r"\tilde{Q}"), Q)
                          for s, Q in zip(S.sigma, self._forces())]),
            Step("GA", r"Appell's equations $\partial\tilde S/\partial\ddot q_\sigma = "
                 r"\tilde Q_\sigma$", lambda: [eq(e, 0) for e in self._equations()]),
        ]


def _bodies(source):
    """(inertial frame, bodies, [(q, u)] with u = qdot) of a mechanics model, or None."""
    if source is None:
        return None
    from sympy.physics.mechanics import KanesMethod, LagrangesMethod
    if isinstance(source, KanesMethod):
        if not source.bodies:
            return None
        return source._inertial, list(source.bodies), list(zip(source.q, source.u))
    if isinstance(source, LagrangesMethod):
        if not source._bodies or source.inertial is None:
            return None
        return source.inertial, list(source._bodies), []
    if type(source).__name__ == "System" and len(source.bodies):
        return source.frame, list(source.bodies), list(zip(source.q, source.u))
    return None
