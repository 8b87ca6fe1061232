"""Whittaker's reduction in Hamiltonian form, for a reduction of the core.

The momenta, in the independent coordinates q_sigma of a Chaplygin system, are those
of L~ (Chaplygin's Lagrangian, L with the dependent velocities (1.3) substituted):
p_sigma = dL~/dqdot_sigma.  L~ is quadratic in the velocities,
L~ = 1/2 qdot.M.qdot + c.qdot + L0, so p = M qdot + c is inverted by
qdot = M^-1 (p - c) and the energy (1.11) in the momenta is the Hamiltonian

    H(q, p) = 1/2 (p - c).M^-1.(p - c) - L0.

**The branch.**  H is a quadratic a p_eps^2 + b p_eps + c0 in the momentum of q_eps,
with a = 1/2 (M^-1)_(eps eps) > 0 (M positive definite).  Its two roots of H = h are
p_eps = -b/(2a) +- sqrt(X), X = (b^2 - 4a(c0 - h))/(4a^2), and on them
qdot_eps = dH/dp_eps = 2a p_eps + b = +- 2a sqrt(X): the root with the sign
``direction`` of the reduction is the one on which q_eps moves as the reduction
assumes.  K = -p_eps on that branch.

**Hamilton's equations in q_eps.**  Along a motion, (1.4) in the momenta reads
qdot_sigma = dH/dp_sigma, pdot_sigma = -dH/dq_sigma + F_sigma, with F_sigma the
constraint term of (1.4), sum_beta P_beta (d/dt dphi_beta/dqdot_sigma -
dphi_beta/dq_sigma), P_beta = dL/dqdot_(eps+beta) with (1.3) substituted
(dL~/dq_sigma at fixed qdot is -dH/dq_sigma at fixed p, the usual Legendre identity).
Differentiating H(q_nu, p_nu, q_eps, -K) = h with respect to p_nu and q_nu gives
dK/dp_nu = (dH/dp_nu)/(dH/dp_eps) and dK/dq_nu = (dH/dq_nu)/(dH/dp_eps), so, with
dH/dp_eps = qdot_eps,

    dq_nu/dq_eps = qdot_nu/qdot_eps = dK/dp_nu,
    dp_nu/dq_eps = pdot_nu/qdot_eps = -dK/dq_nu + Q_nu,   Q_nu = F_nu/qdot_eps.

By (1.25), Q_nu is Mei's constraint term of (1.26),
sum_beta (dL/dqdot_(eps+beta))* [d/dq_eps (dqdot*/dq'_nu) - dqdot*/dq_nu], written in
(q, p); for g = 0 it is 0 and these are Hamilton's equations of K.  When a constraint
is linear in the velocities, d/dt dphi/dqdot_nu has no accelerations and Q_nu is a
function of (q, p) alone; a constraint that is not linear (the cone particle) makes
it depend on dp/dq_eps as well, and such a system is refused.

**What ``verify`` checks** (the book's labels, in square brackets):

* [K] ``H(q, p_nu, -K) = h`` and ``dH/dp_eps`` has the sign ``direction`` there;
* [K=L*] K is the Legendre transform of Whittaker's reduced Lagrangian L* (1.16) in
  q_eps-time: with p_nu = dL*/dq'_nu, ``K = sum p_nu q'_nu - L*``, and
  ``dK/dp_nu = q'_nu`` (the transform is inverted by K);
* [H=1.27] (holonomic) / [H=1.26] (Chaplygin): q''_nu = d/dq_eps (dK/dp_nu) from
  Hamilton's equations, at p_nu = dL*/dq'_nu, equals the core's q''_nu solved from
  (1.27) / (1.26).

Each is tried exactly, else at random admissible points in 40-digit mpmath
(:func:`whittaker_teach.verify.check_identity`).  The points: parameters in (0.5, 2),
coordinates in (0.1, 1.2), slopes q' in (-1, 1), qdot_eps of the reduction's sign
and modulus in (0.3, 1.5), and h the energy (1.11) of that motion.

>>> import whittaker_teach as wt
>>> iso = isoenergetic(wt.examples.kepler().reduce("theta"))
>>> iso.K
-sqrt(r)*sqrt(2*h*m*r + 2*m**2*mu - p_r**2*r)
>>> for e in iso.equations():
...     print(e)
Eq(Derivative(r, theta), p_r*r**(3/2)/sqrt(2*h*m*r + 2*m**2*mu - p_r**2*r))
Eq(Derivative(p_r, theta), (2*h*m*r + m**2*mu - p_r**2*r)/(sqrt(r)*sqrt(2*h*m*r + 2*m**2*mu - p_r**2*r)))
>>> print(iso.verify().summary())
4 checks: 4 held (1 exactly, 3 numerically, largest residual 8.7e-40); 0 did not
"""

from __future__ import annotations

import random

import mpmath
import sympy as sp

from ..coordinates import name as _name, sign_assumptions as _assume
from ..errors import ChartError, ModelError, ModelTypeError, guarded
from ..reduction import Reduction
from ..steps import Report
from ..verify import DPS, check_identity, value_at

__all__ = ["IsoenergeticForm", "isoenergetic"]


def _require_reduction(red):
    if not isinstance(red, Reduction):
        raise ModelTypeError("expected a Reduction (system.reduce(coordinate, direction)), "
                             f"got {type(red).__name__}")
    return red


#: above this many operations (``count_ops``) an expression is shown as derived
TIDY_OPS = 300


def _tidy(e):
    """A short form to read: ``cancel`` (the arguments of roots are left as they are),
    then ``factor`` when that is shorter; an expression of more than ``TIDY_OPS``
    operations is returned as it is (tidying it would cost more than reading it)."""
    if sp.count_ops(e) > TIDY_OPS:
        return e
    e = sp.cancel(e)
    f = sp.factor(e)
    return f if sp.count_ops(f) < sp.count_ops(e) else e


def _trig(e):
    """``trigsimp`` where both sin and cos occur (sin^2 + cos^2 = 1); other forms, such as
    the paper's 1 + tan^2, are kept as written."""
    return sp.trigsimp(e) if e.has(sp.sin) and e.has(sp.cos) else e


class IsoenergeticForm:
    """Whittaker's reduction ``reduction`` in Hamiltonian form (see the module).

    Two steps: build (the Legendre transform, the branch of p_eps and the constraint
    term are derived, and bad input is refused), then ask.  Everything is in plain
    symbols: ``q`` {coordinate: Symbol} (the reduction's names, ``x``, ``theta``),
    ``p`` {independent coordinate: Symbol ``p_x``, ...}, ``qprime`` {q_nu: Symbol
    ``theta'``}, ``h`` the energy and ``independent`` q_eps (the reduction's).
    Results: ``momenta`` {p: M qdot + c}, ``hamiltonian``, ``radicand`` X and ``p_eps``
    (the branch, -b/(2a) + direction sqrt(X)), ``K``, ``constraint_term`` [Q_nu],
    ``rates`` {q_nu or p_nu: its d/dq_eps}, ``time_rate`` and ``equations()``; ``verify()`` is a
    :class:`~whittaker_teach.steps.Report`; ``p_eps_at(values)`` evaluates the branch
    at a point (ModelError where the energy surface does not reach it).
    """

    @guarded("the isoenergetic (Hamiltonian) form")
    def __init__(self, reduction):
        self.reduction = red = _require_reduction(reduction)
        self.system = S = red.system
        self.direction = red.direction
        self.independent, self.h = red.independent, red.h
        self._eps = next(c for c in S.independent_coordinates
                         if _name(c) == str(red.independent))
        self._sig = list(S.independent_coordinates)
        self._nus = [c for c in self._sig if c != self._eps]
        self._make_symbols()
        self._derive()

    # ----- notation -------------------------------------------------------
    def _make_symbols(self):
        S = self.system
        self.q = {c: sp.Symbol(_name(c), **_assume(c)) for c in S.coordinates}
        self.v = {c: sp.Symbol(_name(c) + "dot", real=True) for c in S.coordinates}
        self.p = {c: sp.Symbol("p_" + _name(c), real=True) for c in self._sig}
        self.qprime = {c: sp.Symbol(_name(c) + "'", real=True) for c in self._nus}
        taken = {p.name for p in S.parameters} | {str(self.h)}
        for s in [*self.p.values(), *self.qprime.values()]:
            if s.name in taken:
                raise ModelError(f"a parameter is called {s.name}, the name of a symbol the "
                                 "Hamiltonian form makes (a momentum or a slope); rename it")
        t = S.coordinates[0].args[0]
        self._time = {}
        for c in S.coordinates:
            self._time[c.diff(t)] = self.v[c]
            self._time[c] = self.q[c]
        x = self.independent
        self._reduced = {}
        for c, f in zip(self._nus, self.reduction.coordinates):
            self._reduced[f.diff(x)] = self.qprime[c]
            self._reduced[f] = self.q[c]

    def plain(self, expr):
        """An expression of the system (q(t), qdot(t)) or of the reduction (theta(x),
        theta'(x)) in this form's plain symbols."""
        return sp.sympify(expr).xreplace(self._time).xreplace(self._reduced)

    # ----- derivation -----------------------------------------------------
    def _derive(self):
        S = self.system
        L = self.plain(S.lagrangian)
        self._phi = {d: self.plain(S.constraints[d.diff(S.coordinates[0].args[0])])
                     for d in S.dependent_coordinates}
        self._Lt = L.xreplace({self.v[d]: phi for d, phi in self._phi.items()})
        self._P_dep = {d: L.diff(self.v[d]).xreplace({self.v[e]: phi for e, phi
                                                       in self._phi.items()})
                       for d in self._phi}
        self._legendre()
        self._branch()
        self.constraint_term = [self._Q(c) for c in self._nus]
        self.rates = {}
        for c, Q in zip(self._nus, self.constraint_term):
            self.rates[self.q[c]] = self.K.diff(self.p[c])
            self.rates[self.p[c]] = -self.K.diff(self.q[c]) + Q

    def _legendre(self):
        """M, c, L0 of L~; the momenta p = M qdot + c; H(q, p)."""
        vs = [self.v[c] for c in self._sig]
        zero = {w: 0 for w in vs}
        M = sp.Matrix(len(vs), len(vs), lambda i, j: _trig(self._Lt.diff(vs[i], vs[j])))
        if any(sp.simplify(e.diff(w)) != 0 for e in M for w in vs):
            raise ModelError("L~ (L with the constraints 1.3 substituted) is not quadratic in "
                             "the independent velocities: the Legendre transform p = M qdot + c "
                             "needs a kinetic energy quadratic in the velocities (1.11)")
        c = sp.Matrix([_trig(self._Lt.diff(w).xreplace(zero)) for w in vs])
        L0 = _trig(self._Lt.xreplace(zero))
        self._M, self._c = M, c
        self.momenta = {self.p[k]: (M * sp.Matrix(vs) + c)[i] for i, k in enumerate(self._sig)}
        pv = sp.Matrix([self.p[k] for k in self._sig])
        if M.det() == 0:
            raise ModelError("singular kinetic energy: det M = 0, the momenta cannot be "
                             "inverted for the velocities (1.4)")
        vel = M.LUsolve(pv - c)
        self._velocity = {w: sp.cancel(e) for w, e in zip(vs, vel)}
        self.hamiltonian = _tidy(((pv - c).T * vel)[0] / 2 - L0)

    def _branch(self):
        """p_eps on the branch of the reduction's direction; K = -p_eps."""
        pe, H, s = self.p[self._eps], self.hamiltonian, self.direction
        a = sp.cancel(H.diff(pe, 2) / 2)
        if a == 0:
            raise ModelError(f"H does not depend on p_{self.independent} quadratically "
                             "(d2H/dp_eps2 = 0): H = h cannot be solved for p_eps")
        b, c0 = H.diff(pe).xreplace({pe: 0}), H.xreplace({pe: 0})
        self._abc = (a, b, c0)
        self.radicand = _tidy((b**2 - 4 * a * (c0 - self.h)) / (4 * a**2))      # X
        self.p_eps = sp.cancel(-b / (2 * a)) + s * sp.sqrt(self.radicand)
        self.K = -self.p_eps
        self._velocity_eps = 2 * a * self.p_eps + b      # dH/dp_eps on the branch

    def _Q(self, c):
        """Q_nu = F_nu / qdot_eps in (q, p), on the branch (see the module): a sum over the
        constraints of P_beta (tidied) times (d/dt dphi/dqdot_nu - dphi/dq_nu)/qdot_eps."""
        vs = {k: self.v[k] for k in self._sig}
        terms = []
        for d, phi in self._phi.items():
            dphi = phi.diff(vs[c])
            if any(sp.simplify(dphi.diff(w)) != 0 for w in vs.values()):
                raise ModelError(
                    f"the constraint {_name(d)}dot = {sp.sstr(phi)} is not linear in the "
                    f"velocities: d/dt(dphi/d{_name(c)}dot) in (1.4), d/dq_eps(dqdot*/dq'_nu) "
                    "in (1.26), contains the accelerations, so the constraint term is not a "
                    "function of (q, p) and the equations in q_eps are not of Hamilton's "
                    "form; supported: g = 0, or constraints linear in the velocities")
            rate = _trig(sum(dphi.diff(self.q[k]) * vs[k] for k in self._sig)
                         - phi.diff(self.q[c]))
            if sp.simplify(rate) != 0:
                terms.append(self._on_branch(_trig(self._P_dep[d])) * self._on_branch(
                    rate / vs[self._eps]))
        return _tidy(sp.Add(*terms))

    def _on_branch(self, f):
        """f(q, qdot) in (q, p_nu) on the branch: qdot = M^-1 (p - c), p_eps = -K."""
        f = f.xreplace(self._velocity).xreplace({self.p[self._eps]: self.p_eps})
        return _tidy(f)

    # ----- results ----------------------------------------------------------
    @property
    def time_rate(self):
        """dt/dq_eps = 1/qdot_eps, qdot_eps = dH/dp_eps on the branch."""
        return 1 / self._velocity_eps

    def equations(self):
        """Hamilton's equations in q_eps: [Eq(dq_nu/dq_eps, dK/dp_nu), Eq(dp_nu/dq_eps,
        -dK/dq_nu + Q_nu)] for each q_nu (the derivatives d/dq_eps shown unevaluated)."""
        x, out = self.independent, []
        for c in self._nus:
            for s in (self.q[c], self.p[c]):
                out.append(sp.Eq(sp.Derivative(s, x), _tidy(self.rates[s])))
        return out

    @guarded("evaluating p_eps at a point")
    def p_eps_at(self, values):
        """p_eps at a point: ``values`` {symbol or name: number} for q_sigma, p_nu, h and
        the parameters.  ModelError where H = h has no real root there (h below the
        least energy H takes at those q, p_nu); ChartError where qdot_eps = 0 (a turning
        point: q_eps stops being a usable time)."""
        names = {str(s): s for s in self.radicand.free_symbols | self.p_eps.free_symbols}
        pt = {(names.get(k, k) if isinstance(k, str) else k): v for k, v in values.items()}
        missing = sorted(str(s) for s in self.p_eps.free_symbols if s not in pt)
        if missing:
            raise ModelError(f"p_eps_at: no value for {', '.join(missing)}")
        with mpmath.workdps(DPS):
            X = value_at(self.radicand, pt)
            if not isinstance(X, mpmath.mpf) or X < 0:
                a, b, c0 = self._abc
                least = value_at(c0 - b**2 / (4 * a), pt)
                raise ModelError(f"H = h has no real root p_{self.independent} at this point: "
                                 f"h = {mpmath.nstr(value_at(self.h, pt), 8)} is below "
                                 f"{mpmath.nstr(least, 8)}, the least value of H over "
                                 f"p_{self.independent} there (the energy surface does not "
                                 "reach this point; for L = T - V: h is below the potential "
                                 "plus the kinetic energy of the other momenta)")
            if X == 0:
                raise ChartError(f"qdot_{self.independent} = 0 at this point (a turning "
                                 "point): the two branches of p_eps meet and q_eps stops "
                                 "being a usable time (1.5)")
            return value_at(self.p_eps, pt)

    def __repr__(self):
        kind = "holonomic" if not self._phi else "Chaplygin"
        return (f"<IsoenergeticForm of {self.system.name!r} ({kind}): K = -p_"
                f"{self.independent}, direction {self.direction:+d}>")

    # ----- checks -----------------------------------------------------------
    def _sample(self, rng):
        """A random admissible point: parameters, q_sigma, q'_nu, and h the energy of a
        motion with qdot_eps of the reduction's sign (see the module)."""
        S, pt = self.system, {}
        for s in S.parameters:
            pt[s] = rng.uniform(0.5, 2.0) * (-1 if s.is_negative else 1)
        for c in self._sig:
            pt[self.q[c]] = rng.uniform(0.1, 1.2) * (-1 if self.q[c].is_negative else 1)
        v = self.direction * rng.uniform(0.3, 1.5)
        motion = {self.v[self._eps]: v}
        for c in self._nus:
            pt[self.qprime[c]] = rng.uniform(-1, 1)
            motion[self.v[c]] = v * pt[self.qprime[c]]
        for c in S.dependent_coordinates:  # used only where L was written with one (1.3)
            pt[self.q[c]] = rng.uniform(0.1, 1.2) * (-1 if self.q[c].is_negative else 1)
        vs = list(motion)
        E = sum(w * self._Lt.diff(w) for w in vs) - self._Lt          # (1.11) in time
        pt[self.h] = value_at(E, {**pt, **motion})
        return pt

    def _lagrangian_momenta(self):
        """p_nu = dL*/dq'_nu, L* the core's (1.16) in plain symbols."""
        Ls = self.plain(self.reduction.L_star)
        return Ls, {self.p[c]: Ls.diff(self.qprime[c]) for c in self._nus}

    def _hamilton_q2(self, K, Q):
        """q''_nu = d/dq_eps (dK/dp_nu) along Hamilton's equations of K (with Q)."""
        x, nus = self.independent, self._nus
        qrate = {c: K.diff(self.p[c]) for c in nus}
        prate = {c: -K.diff(self.q[c]) + Qc for c, Qc in zip(nus, Q)}
        out = []
        for c in nus:
            f = qrate[c]
            out.append(f.diff(x) + sum(f.diff(self.q[k]) * qrate[k]
                                       + f.diff(self.p[k]) * prate[k] for k in nus))
        return out

    @guarded("checking the isoenergetic form")
    def verify(self, K=None, constraint_term=None):
        """The checks [K], [K=L*], [H=1.27] or [H=1.26] (see the module), as a Report.
        ``K`` and ``constraint_term`` replace this form's, to see a wrong one fail."""
        K = self.K if K is None else sp.sympify(K)
        Q = self.constraint_term if constraint_term is None else list(constraint_term)
        pe, smp, nus = self.p[self._eps], self._sample, self._nus
        Ls, P = self._lagrangian_momenta()
        checks = [check_identity("K", f"$H(q, p_\\nu, p_{{{sp.latex(self.independent)}}} = "
                                 "-K) = h$", [self.hamiltonian.xreplace({pe: -K}).xreplace(P)],
                                 [self.h], smp)]
        checks.append(self._sign_check(K, P))
        qp = [self.qprime[c] for c in nus]
        checks.append(check_identity(
            "K=L*", r"$K = \sum_\nu p_\nu q'_\nu - L^*$ and $\partial K/\partial p_\nu = q'_\nu$"
            r" at $p_\nu = \partial L^*/\partial q'_\nu$ (the Legendre transform of (1.16))",
            [K.xreplace(P)] + [K.diff(self.p[c]).xreplace(P) for c in nus],
            [sum(P[self.p[c]] * self.qprime[c] for c in nus) - Ls] + qp, smp))
        label = "H=1.27" if not self._phi else "H=1.26"
        acc = self.reduction.accelerations()
        x = self.independent
        core = [self.plain(acc[f.diff(x, 2)]) for f in self.reduction.coordinates]
        checks.append(check_identity(
            label, "$q''_\\nu$ from Hamilton's equations of $K$"
            + (" with the constraint term $Q_\\nu$" if self._phi else "")
            + f" equals the core's $q''_\\nu$ solved from ({label[2:]})",
            [e.xreplace(P) for e in self._hamilton_q2(K, Q)], core, smp))
        return Report(checks)

    def _sign_check(self, K, P):
        """[K]: dH/dp_eps at p_eps = -K has the sign of the reduction's direction."""
        from ..verify import Check
        rate = self.hamiltonian.diff(self.p[self._eps]).xreplace(
            {self.p[self._eps]: -K}).xreplace(P)
        rng, worst = random.Random(5), True
        with mpmath.workdps(DPS):
            for _ in range(6):
                val = value_at(rate, self._sample(rng))
                worst = worst and isinstance(val, mpmath.mpf) and val * self.direction > 0
        return Check("K", f"the branch: $\\dot q_\\varepsilon = \\partial H/\\partial p_"
                     f"\\varepsilon$ at $p_\\varepsilon = -K$ has the sign {self.direction:+d} "
                     "of the reduction", bool(worst), "numeric", f"mpmath at {DPS} digits", 6,
                     0.0)


@guarded("the isoenergetic (Hamiltonian) form")
def isoenergetic(reduction):
    """:class:`IsoenergeticForm` of ``reduction`` (a function, for a one-liner)."""
    return IsoenergeticForm(reduction)
