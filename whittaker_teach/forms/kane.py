"""Kane's equations F_r + F*_r = 0 (Kane 1961; Kane and Levinson 1985), for a system
given by its Lagrangian.

Honestly said: Kane's method is built on bodies, their velocities and
accelerations; ``sympy.physics.mechanics.KanesMethod`` needs them.  A system given
by a Lagrangian has no bodies, so here Kane's equations are written in the
Lagrangian setting: the generalized speeds are the independent velocities, u_r =
qdot_sigma; the partial velocities of the configuration are v_s,r = dqdot_s/du_r
on the constraints (1 or 0 for an independent coordinate, Chetaev's coefficient
B_beta,r for a dependent one) [Kv]; with T = L - L(qdot = 0), Q_s = -dV/dq_s,

    F_r  = sum_s Q_s v_s,r                                  (generalized active forces)
    F*_r = -sum_s (d/dt dT/dqdot_s - dT/dq_s) v_s,r         (generalized inertia forces)

(the inertia force of a body, -m a, dotted with its partial velocities and summed,
is Lagrange's expression of T: Kane and Levinson 1985, sect. 6), and

    F_r + F*_r = 0,   one per generalized speed                                  [Kane]

In this setting the result is Maggi's equations with T and V apart: the
difference between the methods is in how F*_r is computed for bodies (from the
accelerations, without T), which a Lagrangian cannot show.  When the system was
built with :func:`~whittaker_teach.forms.from_mechanics` from a ``KanesMethod``
(bodies, speeds u = qdot), ``via="KanesMethod"`` runs sympy's ``kanes_equations``
on it and reads its mass matrix and forcing back into this notation (KanesMethod
takes loads, not potential energies: the generalized active forces of the bodies'
``potential_energy`` are added to the rows of the independent speeds).

>>> from whittaker_teach.forms import examples, Kane
>>> Kane(examples.sledge()).accelerations()
{Derivative(x(t), (t, 2)): -tan(theta(t))*Derivative(theta(t), t)*Derivative(x(t), t), Derivative(theta(t), (t, 2)): -k**2*theta(t)/J}
"""

from __future__ import annotations

from ..canonical import add, mul
from ..errors import ModelError
from ..steps import Step, eq
from ._form import Form
from ._print import indexed

__all__ = ["Kane"]


class Kane(Form):
    """Kane's equations F_r + F*_r = 0 with u_r = qdot_sigma (Kane 1961, 1985)."""

    label = "Kane"
    title = "Kane: generalized active and inertia forces"
    source = "T. R. Kane (1961); Kane and Levinson (1985)"
    needs = "n - g equations; partial velocities, F_r and F*_r"

    def __init__(self, system, via="lagrangian"):
        self.via = via
        super().__init__(system)

    @property
    def name(self):
        return "Kane" if self.via == "lagrangian" else "Kane via KanesMethod"

    def _require(self):
        if self.via not in ("lagrangian", "KanesMethod"):
            raise ModelError("via must be 'lagrangian' or 'KanesMethod'")
        if self.via == "KanesMethod":
            from sympy.physics.mechanics import KanesMethod
            if not isinstance(self.system.source, KanesMethod):
                raise ModelError("via='KanesMethod' needs a system built by from_mechanics "
                                 "from a KanesMethod (bodies and speeds u = qdot); a "
                                 "Lagrangian alone has no bodies")

    def _partial_velocities(self):
        S = self.system
        return {(c, r): S.constrained(S.C(c, r)) for c in S.coordinates for r in S.sigma}

    def _forces(self):
        """(F_r, F*_r) per generalized speed."""
        if "F" not in self._cache:
            S, T = self.system, self.system.kinetic
            v = self._partial_velocities()
            Q = S.forces()
            inertia = [S.constrained(add(S.rate(S._d(T, S.qd[c])), -S._d(T, S.q[c])))
                       for c in S.coordinates]
            out = []
            for r in S.sigma:
                F = add(*[mul(q, v[c, r]) for c, q in zip(S.coordinates, Q) if v[c, r] != 0])
                Fs = add(*[-mul(i, v[c, r]) for c, i in zip(S.coordinates, inertia)
                           if v[c, r] != 0])
                out.append((F, Fs))
            self._cache["F"] = out
        return self._cache["F"]

    def _kanes_method(self):
        """sympy's KanesMethod's mass matrix and forcing, in the internal symbols: the
        equations M udot - f (one per speed), udot = qddot, the dependent speeds on the
        constraints."""
        if "km" not in self._cache:
            S, km = self.system, self.system.source
            km.kanes_equations(km.bodies, km.loads)
            u_to = {}
            for q, u in zip(km.q, km.u):
                u_to[u.diff(S._t)] = S.qdd[q]
                u_to[u] = S.qd[q]
            M = km.mass_matrix.xreplace(u_to)
            f = km.forcing.xreplace(u_to)
            qs = list(km.q)        # u_i = q_i' in this order (checked by from_mechanics)
            eqs = [add(*[mul(S.to_internal(M[i, j]), S.qdd[qs[j]])
                         for j in range(M.cols)], -S.to_internal(f[i]))
                   for i in range(M.rows)]
            # KanesMethod takes loads, not potential energies: the generalized active
            # forces of V (the bodies' potential_energy) are added to the rows of the
            # independent speeds, F_r = sum_s Q_s v_s,r
            p = len(km.u) - len(km._udep)
            Q = S.forces()
            for i in range(p):
                r = qs[i]
                F = add(*[mul(q_, S.C(c, r)) for c, q_ in zip(S.coordinates, Q) if q_ != 0])
                eqs[i] = add(eqs[i], -F)
            on = {S.qd[c]: phi for c, phi in S._phi.items()}
            from ..dag import substitute
            self._cache["km"] = [substitute(e, on) for e in eqs]
        return self._cache["km"]

    def _equations(self):
        if self.via == "KanesMethod":
            return self._kanes_method()
        return [add(F, Fs) for F, Fs in self._forces()]

    def _unknowns(self):
        S = self.system
        if self.via == "KanesMethod":
            return [S.qdd[c] for c in S.coordinates]
        return [S.qdd[c] for c in S.sigma]

    def _steps_before(self):
        S = self.system
        if self.via == "KanesMethod":
            return [Step("Kane", "sympy's KanesMethod: mass matrix times the speeds' rates "
                         "minus the forcing, read back (u = qdot)",
                         lambda: [eq(e, 0) for e in self._kanes_method()])]
        v = self._partial_velocities()
        return [
            Step("Kanev", r"the partial velocities $v_{s,r} = \partial\dot q_s/\partial u_r$ "
                 r"of the generalized speeds $u_r = \dot q_\sigma$", lambda: [
                     eq(indexed("v", [S.q[c], S.q[r]], sep=","), v[c, r])
                     for c in S.coordinates for r in S.sigma]),
            Step("KaneF", r"the generalized active forces $F_r$ and inertia forces $F^*_r$",
                 lambda: [e for r, (F, Fs) in zip(S.sigma, self._forces())
                          for e in (eq(indexed("F", [S.q[r]]), F),
                                    eq(indexed("F*", [S.q[r]], base_tex="F^{*}"), Fs))]),
            Step("Kane", r"Kane's equations $F_r + F^*_r = 0$",
                 lambda: [eq(e, 0) for e in self._equations()]),
        ]
