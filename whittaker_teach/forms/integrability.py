"""Are linear constraints integrable?  Frobenius' test (Frobenius 1877), decided for the
constraints at hand.

Linear constraints A(q) qdot = 0, solved as qdot_beta = sum_sigma B_beta,sigma(q)
qdot_sigma, allow the velocities spanned by the vector fields

    X_sigma = d/dq_sigma + sum_beta B_beta,sigma d/dq_beta                    [Fr1]

The constraints are holonomic (integrable: q moves on a manifold F(q) = const of
dimension n - g) exactly when this distribution is involutive (Frobenius): every
bracket [X_sigma, X_tau] lies in it.  The brackets have only d/dq_beta components,

    [X_sigma, X_tau] = sum_beta (X_sigma B_beta,tau - X_tau B_beta,sigma) d/dq_beta  [Fr2]

so the test is that each component vanishes.  Each is checked exactly where a cheap
rewrite shows it, otherwise at random points to 40 digits
(:func:`whittaker_teach.verify.check_zero`): a component that does not vanish at
a point proves the constraints non-holonomic, and the step shows it [Fr2].  Where
they are integrable, [Fr3] shows the integrals F_beta(q) = const found by
integrating the closed forms dq_beta - sum B dq_sigma in turn (the dependent
coordinates already integrated substituted), or for one constraint whose B
contains its own q_beta, an integrating factor of the form as given (1, one over a
coefficient, its square or a product of two; in two coordinates also 1/x^2, 1/y^2,
1/(x^2 + y^2) and a factor of one variable); each integral is checked: dF/dt = 0 on
the constraints.

>>> import sympy as sp
>>> from sympy.physics.mechanics import dynamicsymbols
>>> t = dynamicsymbols._t
>>> x, y = dynamicsymbols("x y")
>>> disguised = frobenius([x*x.diff(t) + y*y.diff(t)], [x, y])
>>> disguised.is_holonomic, disguised.integrals
(True, [x(t)**2/2 + y(t)**2/2])
>>> frobenius([y*x.diff(t) - x*y.diff(t)], [x, y]).integrals
[x(t)/y(t)]
>>> from whittaker_teach.forms import examples
>>> sledge = frobenius(examples.sledge())
>>> sledge.is_holonomic, sledge.brackets
(False, {(x(t), theta(t)): {y(t): -tan(theta(t))**2 - 1}})
"""

from __future__ import annotations

import sympy as sp

from ..canonical import add, mul
from ..errors import ModelError, guarded
from ..steps import Derivation, Step, eq
from ..verify import DPS, Check, check_zero, largest_value, shared_points
from ._form import Shown
from ._print import bracket, indexed, tidy
from .model import NonholonomicSystem

__all__ = ["frobenius", "Integrability"]


@guarded("the Frobenius test")
def frobenius(constraints, coordinates=None, dependent=None):
    """The :class:`Integrability` of linear constraints: a
    :class:`~whittaker_teach.forms.NonholonomicSystem` (its constraints), or the
    constraints (expressions = 0 linear in the velocities, or ``{ydot: phi}``) with
    their ``coordinates`` (and optionally the ``dependent`` coordinates, default the
    last g)."""
    return Integrability(constraints, coordinates, dependent)


class Integrability(Shown):
    """Frobenius' test for linear constraints; ``is_holonomic``, ``brackets``,
    ``integrals`` and ``steps``."""

    def __init__(self, constraints, coordinates=None, dependent=None):
        if isinstance(constraints, NonholonomicSystem):
            S = constraints
        else:
            if coordinates is None:
                raise ModelError("frobenius needs the coordinates: frobenius(constraints, "
                                 "[x, y, ...])")
            if isinstance(constraints, dict):
                S = NonholonomicSystem(sp.S.Zero, coordinates, dependent=constraints,
                                       name="constraints")
            else:
                S = NonholonomicSystem(sp.S.Zero, coordinates, constraints=constraints,
                                       dependent=dependent, name="constraints")
        if not S.is_linear:
            raise ModelError("Frobenius' test is for linear constraints A(q) qdot = 0 "
                             "(Pfaffian forms); a nonlinear constraint has no distribution "
                             "of allowed velocities to test")
        if S.is_holonomic:
            raise ModelError("there are no constraints to test")
        self.system = S
        self._cache = {}

    # ----- [Fr1], [Fr2] ----------------------------------------------------
    def _B(self, b, s):
        return self.system.B(b, s)

    def _X(self, f, s):
        S = self.system
        return add(S._d(f, S.q[s]), *[mul(self._B(g, s), S._d(f, S.q[g])) for g in S.beta])

    def _components(self):
        """{(sigma, tau): {beta: component}} for sigma before tau (internal symbols)."""
        if "K" not in self._cache:
            S = self.system
            out = {}
            for i, s in enumerate(S.sigma):
                for tau in S.sigma[i + 1:]:
                    out[(s, tau)] = {b: add(self._X(self._B(b, tau), s),
                                            -self._X(self._B(b, s), tau)) for b in S.beta}
            self._cache["K"] = out
        return self._cache["K"]

    def _checks(self):
        if "checks" not in self._cache:
            S = self.system
            out = {}
            with shared_points():
                for (s, tau), comps in self._components().items():
                    for b, K in comps.items():
                        out[(s, tau, b)] = check_zero(
                            "Fr2", f"the {S.q[b]}-component of [X_{S.q[s]}, X_{S.q[tau]}] "
                            "vanishes", K, S.sample, seed=13)
            self._cache["checks"] = out
        return self._cache["checks"]

    @property
    def is_holonomic(self):
        """True when every bracket lies in the distribution (Frobenius): the constraints
        are integrable; False when a component was found not zero."""
        return all(c.holds for c in self._checks().values())

    @property
    def brackets(self):
        """{(q_sigma, q_tau): {q_beta: component}}: the components of the brackets that do
        not vanish (empty when holonomic), in dynamicsymbols, tidied."""
        S = self.system
        out = {}
        for (s, tau, b), chk in self._checks().items():
            if not chk.holds:
                out.setdefault((s, tau), {})[b] = S.to_public(
                    tidy(self._components()[(s, tau)][b]))
        return out

    # ----- [Fr3] ------------------------------------------------------------
    def _potential(self, P):
        """Phi with dPhi = sum_sigma P[sigma] dq_sigma (a closed form), by integrating one
        coordinate at a time; None when ``integrate`` gives no closed form."""
        S = self.system
        Phi = sp.S.Zero
        done = []
        for s in S.sigma:
            x = S.q[s]
            rest = sp.cancel(sp.together(add(P[s], -S._d(Phi, x))))
            if any(rest.has(S.q[d]) for d in done):
                # independent of them by closedness: take them at a point
                rest = rest.xreplace({S.q[d]: sp.Rational(1, 3) for d in done})
            if rest == 0:
                done.append(s)
                continue
            I = sp.integrate(rest, x)
            if I.has(sp.Integral):
                return None
            Phi = add(Phi, I)
            done.append(s)
        return Phi

    def _integrals(self):
        """[F_beta] in the internal symbols (= const on the motion), or None."""
        if "F" in self._cache:
            return self._cache["F"]
        S = self.system
        F, pending = {}, list(S.beta)
        const = {}
        progress = True
        while pending and progress:
            progress = False
            for b in list(pending):
                B = {s: self._B(b, s) for s in S.sigma}
                others = [g for g in S.beta if g != b]
                if any(B[s].has(S.q[g]) for s in S.sigma for g in pending):
                    continue
                sub = {S.q[g]: const[g][0] for g in others if g in const}
                Phi = self._potential({s: B[s].xreplace(sub) for s in S.sigma})
                if Phi is None:
                    continue
                back = {const[g][1]: const[g][2] for g in const}
                Fb = add(S.q[b], -Phi).xreplace(back)
                F[b] = Fb
                c = sp.Symbol(f"_c{len(const)}")
                const[b] = (add(Phi, c), c, Fb)
                pending.remove(b)
                progress = True
        if pending and len(S.beta) == 1:
            F = self._integrating_factor()
            self._cache["F"] = F
            return F
        self._cache["F"] = [F[b] for b in S.beta] if not pending else None
        return self._cache["F"]

    def _integrating_factor(self):
        """One constraint: mu * (its form as given) closed, mu tried in turn among 1, one
        over a coefficient, over its square, over the product of two; in two coordinates
        x, y also 1/x^2, 1/y^2, 1/(x y), 1/(x^2 + y^2) and the factors of one variable
        solving the equation for mu (:meth:`_one_variable_factors`).  Each closed form
        is integrated one coordinate at a time; the integral is checked in [Fr3]."""
        S = self.system
        f = S._f[0]
        a = {c: S._d(f, S.qd[c]) for c in S.coordinates}
        nz = [v for v in a.values() if v != 0]
        tries = ([sp.S.One] + [1 / v for v in nz] + [1 / v**2 for v in nz]
                 + [1 / (u * v) for i, u in enumerate(nz) for v in nz[i + 1:]])
        if len(S.coordinates) == 2:
            x, y = (S.q[c] for c in S.coordinates)
            tries += [1 / x**2, 1 / y**2, 1 / (x * y), 1 / (x**2 + y**2)]
            tries += self._one_variable_factors(a)
        seen = set()
        for mu in tries:
            w = {c: sp.cancel(mu * v) for c, v in a.items()}
            key = tuple(w.values())
            if key in seen:
                continue
            seen.add(key)
            closed = all(sp.cancel(S._d(w[c], S.q[e]) - S._d(w[e], S.q[c])) == 0
                         for i, c in enumerate(S.coordinates) for e in S.coordinates[i + 1:])
            if not closed:
                continue
            Phi = sp.S.Zero
            for c in S.coordinates:
                x = S.q[c]
                rest = sp.cancel(w[c] - S._d(Phi, x))
                if rest == 0:
                    continue
                I = sp.integrate(rest, x)
                if I.has(sp.Integral):
                    break
                Phi = Phi + I
            else:
                return [Phi]
        return None

    def _one_variable_factors(self, a):
        """For P dx + Q dy: the integrating factors mu(x) = exp(int (P_y - Q_x)/Q dx) when
        that ratio is free of y, and mu(y) = exp(int (Q_x - P_y)/P dy) when free of x
        (the equation for mu, d(mu P)/dy = d(mu Q)/dx, solved where it is one of one
        variable); [] when neither is."""
        S = self.system
        (cx, P), (cy, Q) = a.items()
        x, y = S.q[cx], S.q[cy]
        curl = sp.cancel(S._d(P, y) - S._d(Q, x))
        out = []
        for coef, z, sign in ((Q, x, 1), (P, y, -1)):
            if coef == 0 or curl == 0:
                continue
            r = sp.cancel(sign * curl / coef)
            if r.has(y if z == x else x):
                continue
            I = sp.integrate(r, z)
            if not I.has(sp.Integral):
                out.append(sp.exp(I))
        return out

    @property
    def integrals(self):
        """The integrals F(q) (= const on every motion), in dynamicsymbols, when the
        constraints are holonomic and the library finds them in closed form; None
        otherwise (see :attr:`is_holonomic` for the decision)."""
        if not self.is_holonomic:
            return None
        F = self._integrals()
        return None if F is None else [self.system.to_public(e) for e in F]

    def _integral_check(self):
        S = self.system
        F = self._integrals()
        on = {S.qd[c]: phi for c, phi in S._phi.items()}
        rates = [add(*[mul(S._d(e, S.q[c]), on.get(S.qd[c], S.qd[c])) for c in S.coordinates])
                 for e in F]
        return check_zero("Fr3", "each integral is constant on the constraints: "
                          r"$dF/dt = \sum_s \partial F/\partial q_s\,\dot q_s = 0$", rates,
                          S.sample, seed=17)

    def _refutation(self, s, tau, b):
        """The verdict on a component that does not vanish: a check that it is not zero
        (its largest value at the sampled points, well above rounding), and the note."""
        S, q = self.system, self.system.q
        name = f"$[X_{{{sp.latex(q[s])}}}, X_{{{sp.latex(q[tau])}}}]$"
        K = self._components()[(s, tau)][b]
        worst = largest_value(K, S.sample, seed=13)
        chk = Check("Fr2", f"the ${sp.latex(q[b])}$-component of {name} does not vanish",
                    worst > 1e-6, "refutation", f"numerically at 6 random admissible points, "
                    f"mpmath at {DPS} digits: non-zero, as large as {worst:.2g}", 6, worst)
        return chk, (f"not integrable (non-holonomic): the bracket {name} does not vanish"
                     if chk.holds else "")

    @property
    @guarded("the steps of the Frobenius test")
    def steps(self):
        """[Fr1] the vector fields, [Fr2] the brackets (the first non-vanishing component
        carries its check), [Fr3] the verdict and the integrals."""
        if "steps" in self._cache:
            return self._cache["steps"]
        S = self.system
        q = S.q
        st = [Step("Fr1", r"the allowed velocities: the fields $X_\sigma = \partial/\partial "
                   r"q_\sigma + B_{\beta\sigma}\,\partial/\partial q_\beta$ (summed over "
                   r"$\beta$), their coefficients",
                   lambda: [eq(indexed("B", [q[b], q[s]]), self._B(b, s))
                            for b in S.beta for s in S.sigma])]
        checks = self._checks()
        bad = [k for k, c in checks.items() if c.holds is False]
        undecided = [c for c in checks.values() if c.holds is None]
        if bad:
            shown, note = self._refutation(*bad[0])
        else:
            shown = undecided[0] if undecided else max(
                checks.values(), key=lambda c: c.max_residual, default=None)
            note = ""
        st.append(Step("Fr2", "the brackets $[X_\\sigma, X_\\tau]$, component by component "
                       "(Frobenius: holonomic if and only if all vanish)", lambda: [
                           eq(bracket(q[s], q[tau], q[b]), K)
                           for (s, tau), comps in self._components().items()
                           for b, K in comps.items()], shown, note=note))
        if self.is_holonomic:
            F = self._integrals()
            if F is None:
                st.append(Step("Fr3", "holonomic (Frobenius); the library found no integral "
                               "in closed form", []))
            else:
                st.append(Step("Fr3", "holonomic: the integrals, constant on every motion",
                               lambda: [eq(e, sp.Symbol(f"C_{i + 1}"))
                                        for i, e in enumerate(F)], self._integral_check()))
        self._cache["steps"] = Derivation("Frobenius' test", st)
        return self._cache["steps"]

    def __repr__(self):
        return (f"<Integrability of {len(self.system.beta)} constraint(s): "
                f"{'holonomic' if self.is_holonomic else 'non-holonomic'}>")
