"""The Whittaker reduction (1.5)-(1.27): removing time with the energy integral.

One independent coordinate q_eps takes the place of time; the others, q_nu,
become functions of it, with q'_nu = dq_nu/dq_eps (1.5).  The energy
integral (1.11), written in the new variables (1.13), gives qdot_eps (1.12);
the reduced Lagrangian L* (1.16) and the reduced constraints qdot* (1.23)
then give the generalized Whittaker equations (1.26).

>>> import whittaker_teach as wt
>>> red = wt.examples.sledge().reduce("x", direction=+1)
>>> red.independent, red.coordinates
(x, [theta(x)])
>>> red.L_star
sqrt(2*h - k**2*theta(x)**2)*sqrt(J*Derivative(theta(x), x)**2 + m*tan(theta(x))**2 + m)
>>> red.verify().ok
True

The direction matters.  The energy fixes only |qdot_eps|; the branch of the
square root in (1.12) is chosen by ``direction`` (the sign of qdot_eps), not
by whatever a solver returns first.  With terms linear in the velocities, or
with a constraint that is only positively homogeneous (phi(-v) != -phi(v)),
the reduced equations for the two directions differ.

How the branch is chosen: with qdot_eps a symbol of known sign s, every
square root of (qdot_eps^2 * X) is rewritten as s*qdot_eps*sqrt(X) (a
targeted ``factor_terms`` on the radicands, no ``simplify``), so Omega (1.6)
is a polynomial A2 qdot_eps^2 + A1 qdot_eps + A0 and (1.13) reads
A2 qdot_eps^2 - A0 = h, whence qdot_eps = s sqrt((h + A0)/A2).  A Lagrangian
whose Omega is not of that form (not quadratic in the velocities) is refused
with a ModelError naming (1.13).
"""

from __future__ import annotations

import mpmath
import sympy as sp

from .coordinates import name as _name, sign_assumptions as _assume
from .canonical import add, mul, over, power, sub
from .dag import along, diff, polynomial_in, renamed, substitute, tree_size, zeroed
from .errors import ModelError, ModelTypeError, guarded
from .reading import (check_reading, cleared_forms, lstar_form, momentum_forms,
                      velocity_form, whittaker_forms)
from .rewrite import collected, expanded, rational_parts
from .steps import Derivation, Report, Step, eq, notation, partial, tex, text
from .verify import (DPS, EXACT_SIZE_LIMIT, check_identity, check_zero, shared_points,
                     values_at, within_size)

__all__ = ["Reduction"]


def _check_direction(direction):
    if isinstance(direction, bool) or direction not in (1, -1):
        raise ModelError(f"direction must be +1 or -1 (the sign of qdot_eps, which the energy "
                         f"integral 1.13 does not fix), got {direction!r}")
    return int(direction)


def _pull_speed(expr, v):
    """Rewrite sqrt(v**2 * X) as |v| sqrt(X) (|v| = s v, v has a known sign)."""
    def fix(p):
        return sp.Pow(sp.factor_terms(p.base), p.exp)
    return expr.replace(lambda e: e.is_Pow and not e.exp.is_Integer and e.base.has(v), fix)


_NOT_QUADRATIC = ("the energy equation (1.13) cannot be solved for qdot_eps in closed form: "
                  "Omega (1.6) is not quadratic in qdot_eps (is L quadratic in the velocities?)")


def _velocity_coefficients(Omega, v, memo=None, sample=None, sign=1):
    """A2, A1, A0 with Omega = A2 v**2 + A1 v + A0, by differentiating in v and putting
    v = 0 (collecting the powers of the velocity without expanding the rest of Omega).

    Omega is quadratic in v when its third derivative d3 is the zero function.  That is
    decided on the function itself, not on ``expand``'s polynomial form (a nonlinear
    constraint such as (xdot**2 + ydot**2)/sqrt(xdot**2 + 2 ydot**2) makes d3 a sum of
    fractions that ``expand`` leaves nonzero): d3 brought over one common denominator
    (``polywalk.vanishes``) or ``expand``, else d3 at ``sample``'s random points in 40
    digits (:func:`.verify.check_zero`); a d3 that is not 0 there is a ModelError.  Where
    v = 0 is not in the domain of the pieces (v**2/v**2 gives nan at 0), the coefficients
    are taken at v = ``sign`` instead, which has the sign of the motion: A2 = d2/2,
    A1 = d1 - 2 sign A2, A0 = Omega - A2 - sign A1 there (d2 is constant in v)."""
    d1 = diff(Omega, v, memo)
    d2 = diff(d1, v, memo)
    d3 = diff(d2, v, memo)
    if d3 != 0 and (tree_size(d3, 2000) > 2000 or sp.expand(d3) != 0):
        if sample is None or not check_zero(
                "1.13", r"$\Omega$ is quadratic in $\dot q_\varepsilon$", d3, sample,
                seed=13).holds:
            raise ModelError(_NOT_QUADRATIC)
    at0 = {}
    if polynomial_in(Omega, v):     # no pole at v = 0: each product with v is 0 at once
        A = [zeroed(e, [v], at0) for e in (d2 / 2, d1, Omega)]
    else:
        A = [substitute(e, {v: sp.S.Zero}, at0) for e in (d2 / 2, d1, Omega)]
    if any(a.has(sp.zoo, sp.nan, sp.oo, -sp.oo) for a in A):
        at = {}
        s = sp.Integer(sign)
        A2, D1, Om = [substitute(e, {v: s}, at) for e in (d2 / 2, d1, Omega)]
        A1 = D1 - 2 * s * A2
        A = [A2, A1, Om - A2 - s * A1]
        if any(a.has(sp.zoo, sp.nan, sp.oo, -sp.oo) for a in A):
            raise ModelError(_NOT_QUADRATIC)
    return A


def _tidy_coefficient(e):
    """``expand``, except powers of sums with exponents above 4, which are kept (a
    potential (1 + x/3 + theta/5)**40 stays one term, as the user wrote it)."""
    if any(p.base.is_Add and p.exp.is_Integer and abs(p.exp) > 4 for p in e.atoms(sp.Pow)):
        return sp.expand(e, multinomial=False)
    return expanded(e)


#: above this many equations (1.26), q'' is read from the accelerations of (1.4)
#: (``Reduction._accelerations``) instead of a symbolic LU of the full matrix d(1.26)/dq''
SOLVE_NU_LIMIT = 3


class _Sampler:
    """The random points of a reduction's checks, on the energy surface.

    A call draws one point: a motion (:meth:`Reduction._motion`) whose energy (1.11) is
    h, with qdot_eps then given the value of the root (1.12) at its (q', q, h), computed
    from the expression the library derived (the drawn value up to rounding).  So an
    expression in qdot_eps evaluated at these points is its value at (1.12), the paper's
    ``*``, without the substituted expression being built; the check of (1.12) compares
    the root with the drawn value (``Reduction._drawn``).  With ``energy=False`` the
    drawn motion is returned as it is (h not set).  ``batch`` draws a block of points
    and evaluates their energies and roots together; ``kept`` is then what the roots'
    evaluation computed, the values of every node of (1.12) at those points, which the
    checks' block of the same points takes over (:func:`.verify.values_at`)."""

    def __init__(self, red):
        self.red, self.kept = red, None

    def __call__(self, rng, energy=True):
        pt = self.red._motion(rng)
        if energy:
            self.red._on_surface([pt])
        return pt

    def batch(self, rng, n):
        pts = [self.red._motion(rng) for _ in range(n)]
        self.kept = {}
        self.red._on_surface(pts, self.kept)
        return pts


class Reduction:
    """The generalized Whittaker equations of a system, with q_eps = ``coordinate``.

    Made by :meth:`ChaplyginSystem.reduce`.  Results are properties
    (``L_star``, ``equations``, ``nielsen_equations``, ...), in the reduced
    notation: ``independent`` is the Symbol q_eps and ``coordinates`` are the
    q_nu as functions of it.  ``steps`` is every step of the paper for this
    system, each with its verification; ``verify()`` re-runs the checks.
    """

    @guarded("the Whittaker reduction")
    def __init__(self, system, coordinate, direction=+1):
        self.system = S = system
        self.direction = _check_direction(direction)
        self._eps = self._check_eps(coordinate)
        self._nus = [c for c in S.independent_coordinates if c != self._eps]
        if not self._nus:
            raise ModelError("the reduction needs at least two independent coordinates "
                             "(eps >= 2, 1.5): with one, the energy integral (1.11) already "
                             "gives t(q_eps) by a quadrature")
        S.check_homogeneity()
        S._accelerations()          # (1.4) must be solvable: a regular kinetic energy
        self._make_symbols()
        self._cache = {}
        self._derive()

    # ----- notation -------------------------------------------------------
    def _check_eps(self, coordinate):
        S = self.system
        if isinstance(coordinate, str):
            match = [c for c in S.coordinates if _name(c) == coordinate]
            if not match:
                raise ModelError(f"{coordinate!r} is not a coordinate of the system "
                                 f"{[_name(c) for c in S.coordinates]} (1.5: q_eps must be one "
                                 "of the independent coordinates)")
            coordinate = match[0]
        if not isinstance(coordinate, sp.Basic):
            raise ModelTypeError(f"the coordinate q_eps must be a dynamicsymbol or its name, "
                                 f"got {type(coordinate).__name__}")
        if coordinate in S.dependent_coordinates:
            raise ModelError(f"{_name(coordinate)} is a dependent coordinate: q_eps must be one "
                             "of the independent coordinates q_sigma (1.5), since the "
                             "constraints (1.3) are solved for the dependent velocities")
        if coordinate not in S.independent_coordinates:
            raise ModelError(f"{coordinate} is not a coordinate of the system "
                             f"{S.coordinates} (1.5: q_eps must be one of the independent "
                             "coordinates); pass the dynamicsymbol, e.g. x, or its name 'x'")
        return coordinate

    def _make_symbols(self):
        S, eps = self.system, self._eps
        self.independent = S.q[eps]
        n = _name(eps)
        sign = {"positive": True} if self.direction > 0 else {"negative": True}
        self._v = sp.Symbol(n + "dot", **sign)
        self._qp = {c: sp.Symbol(_name(c) + "prime") for c in self._nus}
        self._qpp = {c: sp.Symbol(_name(c) + "primeprime") for c in self._nus}
        self.h = sp.Symbol("h")
        self._drawn = sp.Dummy(n + "dot_drawn")   # qdot_eps as drawn (``_sample``)
        made = [self.h, *self._qp.values(), *self._qpp.values()]
        for s in made:
            what = ("the parameter" if s.name in {p.name for p in S.parameters} else
                    "the coordinate" if s.name in {_name(c) for c in S.coordinates} else
                    "the velocity or acceleration" if s.name in S._names else None)
            if what:
                role = ("the energy constant h of (1.11)-(1.13)" if s is self.h else
                        "a derivative with respect to q_eps (1.5)")
                raise ModelError(f"{what} {s.name} has the name of a symbol the reduction "
                                 f"makes, {role}; rename it (nothing is renamed silently)")
        x = self.independent
        self.coordinates = [sp.Function(_name(c), **_assume(c))(x) for c in self._nus]
        self._to_public = {}
        for c, f in zip(self._nus, self.coordinates):
            self._to_public[S.q[c]] = f
            self._to_public[self._qp[c]] = sp.Derivative(f, x)        # f.diff(x), unwalked
            self._to_public[self._qpp[c]] = sp.Derivative(f, (x, 2))
        self._to_internal = {v: k for k, v in self._to_public.items()}

    def to_public(self, expr):
        """Rewrite internal symbols (theta, thetaprime) as functions of q_eps (theta(x), ...)
        (one memo for the reduction: the public results share most of their pieces)."""
        return renamed(expr, self._to_public, self._cache.setdefault("public", {}))

    # ----- the operations of the paper ------------------------------------
    def _sub15(self, expr):
        """Substitute (1.5): qdot_nu = qdot_eps q'_nu, with the branch of |qdot_eps| fixed."""
        S, v = self.system, self._v
        sub = {S.qd[self._eps]: v}
        sub.update({S.qd[c]: v * self._qp[c] for c in self._nus})
        return _pull_speed(substitute(expr, sub), v)

    def _star(self, expr):
        """Put qdot_eps = qdot_eps(q', q, h) from (1.12)."""
        return substitute(expr, {self._v: self._vstar}, self._cache.setdefault("star", {}))

    def _D(self, f):
        """d/dq_eps of f(q', q) along a path (q'' taken as independent, as in 2.1), once
        per f and reduction (the equations, their reading forms and (2.2) take the same)."""
        memo = self._cache.setdefault("D", {})
        out = memo.get(f)
        if out is None:
            S, d = self.system, self._d
            terms = [d(f, S.q[self._eps])]
            for c in self._nus:
                terms += [mul(d(f, self._qp[c]), self._qpp[c]), mul(d(f, S.q[c]), self._qp[c])]
            out = memo[f] = add(*terms)         # one sum: no partial sums re-flattened
        return out

    def _chain(self, a, f, z):
        """a * df/dz, built only when df/dz is not 0 (a product with a factor 0 asks
        whether every other factor is finite, a deep query on a large sum)."""
        df = self._d(f, z)
        return sp.S.Zero if df == 0 else mul(a, df)

    def _d(self, f, z):
        """df/dz, as ``f.diff(z)`` builds it, each shared subexpression differentiated once
        (``dag.diff``, with one memo per system)."""
        return diff(f, z, self.system._dmemo)

    def _derive(self):
        S, v, h = self.system, self._v, self.h
        self._Omega = self._sub15(S._Ltilde)                                    # (1.6)
        A2, A1, A0 = _velocity_coefficients(self._Omega, v, self.system._dmemo,
                                            lambda rng: self._sample(rng, energy=False),
                                            self.direction)
        twoA2, twoK = _tidy_coefficient(2 * A2), _tidy_coefficient(2 * (h + A0))
        if twoA2 == 0:
            raise ModelError("the energy equation (1.13) cannot be solved for qdot_eps: Omega "
                             "(1.6) has no term in qdot_eps**2 (the kinetic energy vanishes "
                             "along q_eps)")
        s = self.direction
        self._A = (A2, A1, A0)
        self._vstar = s * power(twoK, sp.S.Half) / power(twoA2, sp.S.Half)          # (1.12)
        self._Lstar = s * power(twoK, sp.S.Half) * power(twoA2, sp.S.Half) + A1     # (1.16)
        self._Pstar = [self._star(self._sub15(P)) for P in S._dLdqdep_tilde()]
        self._omega = [self._sub15(phi) for phi in S._phi.values()]               # (1.22)
        self._qdstar = [self._d(w, v) for w in self._omega]                           # (1.23)
        self._qdstar = [self._star(q) if q.has(v) else q for q in self._qdstar]
        self._eqs = [self._whittaker(c) for c in self._nus]                       # (1.26)

    def _whittaker(self, c):
        """The nu-th generalized Whittaker equation (1.26), for nu = c."""
        S, Ls, d = self.system, self._Lstar, self._d
        qp, q = self._qp[c], S.q[c]
        e = sub(self._D(d(Ls, qp)), d(Ls, q))
        for P, qs in zip(self._Pstar, self._qdstar):
            term = sub(self._D(d(qs, qp)), d(qs, q))
            if term != 0:           # P*0 would ask whether every factor of P is finite
                e = sub(e, mul(P, term))
        return e

    def _accelerations(self):
        """q''_nu solved from (1.26).  Up to ``SOLVE_NU_LIMIT`` equations by LU on their
        matrix d(1.26)/d(q''); beyond, the matrix is only shown regular at a sampled
        point (as for a solve) and q'' is read from the accelerations of (1.4), which
        are cheaper to solve (the time-domain mass matrix is sparse where the reduced
        one, through the roots of L*, is full): q''_nu = (qddot_nu - q'_nu qddot_eps) /
        qdot_eps**2 with (1.5) and (1.12).  Either way step [1.26b] checks that (1.26)
        vanishes at the q'' found."""
        if "acc" not in self._cache:
            qpp = [self._qpp[c] for c in self._nus]
            if len(qpp) > SOLVE_NU_LIMIT:
                self.system._require_regular(self._q2_matrix(), "d(1.26)/d(q''_nu)",
                                             self._sample)
                sol = self._accelerations_from_time()
            else:
                eqs = sp.Matrix(self._eqs)
                M = sp.Matrix([[self._d(e, a) for a in qpp] for e in eqs])
                memo = {}
                rest = sp.Matrix([zeroed(e, qpp, memo) for e in eqs])
                sol = self.system._solve(M, rest, "d(1.26)/d(q''_nu)", self._sample)
            self._cache["acc"] = dict(zip(qpp, sol))
        return self._cache["acc"]

    def _q2_matrix(self):
        """d(1.26)/d(q''), entry (nu, mu): (1.26) is linear in q'', which enters only
        through d/dq_eps (``_D``) as d f/dq'_mu q''_mu, so the entry is
        d^2 L*/dq'_nu dq'_mu - sum_beta P_beta d^2 qdot*_beta/dq'_nu dq'_mu: second
        derivatives that building (1.26) took already (one memo), not a derivative of
        each whole equation.  The entries are only evaluated (the matrix is shown regular
        at a point), so each sum and product of them is built unevaluated (no
        ``flatten`` of the large pieces: the same value)."""
        Ls, qp = self._Lstar, self._qp
        rows = []
        for c in self._nus:
            row = []
            for k in self._nus:
                terms = [self._d(self._d(Ls, qp[c]), qp[k])]
                for P, qs in zip(self._Pstar, self._qdstar):
                    inner = self._d(qs, qp[c])
                    if inner != 0:
                        outer = self._d(inner, qp[k])
                        if outer != 0:
                            terms.append(sp.Mul(sp.S.NegativeOne, P, outer, evaluate=False))
                row.append(terms[0] if len(terms) == 1 else sp.Add(*terms, evaluate=False))
            rows.append(row)
        return sp.Matrix(rows)

    def _accelerations_from_time(self):
        """q''_nu from the accelerations of (1.4) under (1.5) and (1.12), one per q_nu."""
        S, vs = self.system, self._vstar
        acc = S._accelerations()
        sub = {S.qd[self._eps]: vs}
        sub.update({S.qd[c]: vs * self._qp[c] for c in self._nus})
        memo = {}
        a_eps = substitute(acc[S.qdd[self._eps]], sub, memo)
        inv = power(vs, -2)
        return [mul(substitute(acc[S.qdd[c]], sub, memo) - mul(self._qp[c], a_eps), inv)
                for c in self._nus]

    def _tidy_accelerations(self):
        """q''_nu as one fraction each, to read (``rewrite.rational``); the numerator and
        denominator of each are kept (``_cache["acc_parts"]``, None where q''_nu is too
        large for one fraction) for the cleared form (3.10)."""
        if "acc_tidy" not in self._cache:
            qp = list(self._qp.values())
            parts = {a: rational_parts(x, qp) for a, x in self._accelerations().items()}
            self._cache["acc_parts"] = parts
            self._cache["acc_tidy"] = {a: x if parts[a] is None else parts[a][0] / parts[a][1]
                                       for a, x in self._accelerations().items()}
        return self._cache["acc_tidy"]

    # ----- public results -------------------------------------------------
    @property
    def Omega(self):
        """Omega (1.6): L~ with qdot_nu = qdot_eps q'_nu."""
        return self.to_public(self._Omega)

    @property
    def velocity(self):
        """qdot_eps(q', q, h), the root of (1.13) with the sign ``direction`` (1.12)."""
        return self.to_public(self._vstar)

    @property
    def L_star(self):
        """The reduced Lagrangian L* = dOmega/dqdot_eps at (1.12) (1.16)."""
        return self.to_public(self._Lstar)

    @property
    def constraint_rates(self):
        """qdot*_(eps+beta) = d omega/d qdot_eps (1.23): {dependent coordinate: expression}."""
        return {self._dep_fn(c): self.to_public(q)
                for c, q in zip(self.system.dependent_coordinates, self._qdstar)}

    def _dep_fn(self, c):
        return sp.Function(_name(c), **_assume(c))(self.independent)

    @property
    @guarded("the equations (1.26)")
    def equations(self):
        """The generalized Whittaker equations (1.26), expressions (= 0), one per q_nu."""
        return [self.to_public(e) for e in self._eqs]

    @property
    @guarded("the Nielsen form (2.4)")
    def nielsen_equations(self):
        """The same equations in Nielsen form (2.4)."""
        from .nielsen import nielsen
        return [self.to_public(e) for e in nielsen(self)["2.4"]]

    @guarded("solving (1.26) for q''")
    def accelerations(self):
        """q''_nu solved from (1.26): {theta(x).diff(x, 2): expression}."""
        return {self.to_public(k): self.to_public(v)
                for k, v in self._tidy_accelerations().items()}

    @guarded("generating the numeric right-hand side")
    def lambdify_rhs(self, modules="math"):
        """``f(x, state, h, params)``, the reduced model as one numeric function
        (``lambdify`` with common subexpressions): state = [q_nu..., q'_nu..., t,
        q_dep...], result = its derivative in q_eps ((1.26), dt/dq_eps = 1/qdot_eps
        (1.12), dq_dep/dq_eps (1.23)); see :mod:`.numeric_rhs`."""
        from .numeric_rhs import reduction_rhs
        return reduction_rhs(self, modules)

    @property
    def dependent_momenta(self):
        """(dL/dqdot_(eps+beta))* of (1.26), in q', q and h: {dependent coordinate: expr}."""
        return {self._dep_fn(c): self.to_public(P)
                for c, P in zip(self.system.dependent_coordinates, self._Pstar)}

    @property
    def time_rate(self):
        """dt/dq_eps = 1/qdot_eps, with qdot_eps from (1.12): t(q_eps) by quadrature."""
        return self.to_public(1 / self._vstar)

    @property
    def dependent_rates(self):
        """dq_(eps+beta)/dq_eps = qdot*_(eps+beta) (1.23)-(1.24): {y(x): expression}."""
        return self.constraint_rates

    # ----- random admissible points --------------------------------------
    @property
    def _sample(self):
        """The sampler of the checks' random points (:class:`_Sampler`), one per reduction
        (the checks share its points within ``verify.shared_points``)."""
        sampler = self.__dict__.get("_sampler")
        if sampler is None:
            sampler = self.__dict__["_sampler"] = _Sampler(self)
        return sampler

    def _motion(self, rng):
        """A random motion: the parameters, q, q', q'' and qdot_eps = v0 with the sign of
        ``direction``, qdot_nu = v0 q'_nu (1.5)."""
        S = self.system
        pt = S._sample_time(rng)
        v = self.direction * rng.uniform(0.3, 1.5)
        pt[self._v] = v
        pt[S.qd[self._eps]] = v
        with mpmath.workdps(DPS):
            for c in self._nus:
                pt[self._qp[c]] = rng.uniform(-1, 1)
                pt[self._qpp[c]] = rng.uniform(-1, 1)
                pt[S.qd[c]] = mpmath.mpf(v) * mpmath.mpf(pt[self._qp[c]])
        return pt

    def _on_surface(self, pts, kept=None):
        """Put the drawn motions on the energy surface, as :class:`_Sampler` says, all
        evaluated together (``verify.values_at``); a point where the energy or the root
        cannot be evaluated (or is not real) is unusable (nan).  ``kept``: a dict that
        receives the values of the root's nodes, computed from its own symbols only."""
        S = self.system
        for pt, h in zip(pts, values_at(S._energy(), pts)):
            pt[self.h], pt[self._drawn] = h, pt[self._v]
        own = self._vstar.free_symbols
        with mpmath.workdps(DPS):
            roots = values_at(self._vstar, [{s: pt[s] for s in own} for pt in pts], kept)
            for pt, v in zip(pts, roots):
                if not isinstance(v, mpmath.mpf):
                    v = mpmath.nan
                pt[self._v] = pt[S.qd[self._eps]] = v
                for c in self._nus:
                    pt[S.qd[c]] = v * mpmath.mpf(pt[self._qp[c]])

    # ----- steps ----------------------------------------------------------
    def _steps(self):
        from .nielsen import nielsen_steps
        steps = list(self.system.steps) + self._reduction_steps() + nielsen_steps(self)
        return steps

    def _check_at_112(self, label, claim, sides, starred):
        """Check ``sides`` at (1.12) (the paper's ``*``: qdot_eps = qdot_eps(q', q, h)) equal
        ``starred``, functions of q', q and h.  Small sides are starred as built, so that
        an exact attempt may decide; larger ones are evaluated as they stand at the
        sampled points, which lie on the energy surface (:meth:`_sample`): their value
        there is the starred one's, and no substituted expression is built."""
        sides, starred = list(sides), list(starred)
        if within_size(sides + starred, EXACT_SIZE_LIMIT):
            return check_identity(label, claim, starred, [self._star(e) for e in sides],
                                  self._sample)
        return check_identity(label, claim, starred, sides, self._sample, exact=False)

    def _reduction_steps(self):
        S, v, h, smp = self.system, self._v, self.h, self._sample
        eps, nus, sig = self._eps, self._nus, S.independent_coordinates
        Lt, Om = S._Ltilde, self._Omega
        Omv, vs, Ls = self._d(Om, v), self._vstar, self._Lstar
        qp = self._qp
        qs = {c: S.q[c] for c in S.coordinates}
        ne = _name(eps)
        def d(f, z):
            return partial(*{"Omega": ("Ω", r"\Omega"), "L^*": ("L*", "L^{*}")}[f], z)

        def OM(z, w=None):
            return partial("Ω", r"\Omega", z, w)

        def LS(z):
            return partial("L*", "L^{*}", z)

        def XD(z):
            return partial(text(v), tex(v), z)
        st = []
        xl = tex(self.independent)
        st.append(Step("1.5", f"change of variable: ${xl}$ replaces $t$, $q' = dq/d{xl}$",
                       lambda: [eq(S.qd[c], v * qp[c]) for c in nus]))
        st.append(Step("1.6", r"$\Omega$: $\tilde L$ with (1.5) substituted",
                       lambda: [eq(sp.Symbol("Omega"), collected(Om, [v]))]))
        tidy = lambda e: collected(e, [v] + list(qp.values()))  # noqa: E731
        st.append(Step("1.7", r"$\partial\Omega/\partial\dot q_\varepsilon$",
                       lambda: [eq(d("Omega", v), tidy(Omv))],
                       check_identity(
            "1.7", r"$\partial\Omega/\partial\dot q_\varepsilon = \sum_\sigma (\partial\tilde L/"
            r"\partial\dot q_\sigma)\,\dot q_\sigma/\dot q_\varepsilon$", Omv,
            over(self._sub15(add(*[mul(self._d(Lt, S.qd[c]), S.qd[c]) for c in sig])), v),
            smp)))
        st.append(Step("1.8", r"$\partial\Omega/\partial q'_\nu$", lambda: [eq(d("Omega", qp[c]),
                                                          tidy(self._d(Om, qp[c]))) for c in nus],
                       check_identity(
            "1.8", r"$\partial\Omega/\partial q'_\nu = \dot q_\varepsilon\,\partial\tilde L/"
            r"\partial\dot q_\nu$", [self._d(Om, qp[c]) for c in nus],
            [mul(v, self._sub15(self._d(Lt, S.qd[c]))) for c in nus], smp)))
        st.append(Step("1.9", r"$\partial\Omega/\partial q_\sigma$", lambda: [eq(d("Omega", qs[c]),
                                                             tidy(self._d(Om, qs[c]))) for c in sig],
                       check_identity(
            "1.9", r"$\partial\Omega/\partial q_\sigma = \partial\tilde L/\partial q_\sigma$",
            [self._d(Om, qs[c]) for c in sig],
            [self._sub15(self._d(Lt, qs[c])) for c in sig], smp)))
        E13 = sub(mul(v, Omv), Om)
        st.append(Step("1.13", "the energy integral in the new variables",
                       lambda: [eq(collected(E13, [v]), h)], check_identity(
            "1.13", r"$\dot q_\varepsilon\,\partial\Omega/\partial\dot q_\varepsilon - \Omega$ "
            "is the energy (1.11) under (1.5)", E13, self._sub15(S._energy()), smp),
            note="shown before (1.12), which is (1.13) solved for the velocity"))
        vform = velocity_form(self)
        st.append(Step("1.12", r"(1.13) solved for $\dot q_\varepsilon$, the branch with "
                       rf"$\operatorname{{sign}}\dot q_\varepsilon = {self.direction:+d}$",
                       [eq(S.qd[eps], vform)], check_reading(
            "1.12", "the chosen root solves (1.13) and has the sign of the motion; the form "
            "shown is that root", [vform], [vs], self, also=([vs, E13], [self._drawn, h]))))
        Ovv = self._d(Omv, v)
        for lab, vars_, what in (("1.14", [qp[c] for c in nus], r"q'_\nu"),
                                 ("1.15", [qs[c] for c in sig], r"q_\sigma")):
            st.append(Step(lab, f"(1.13) differentiated with respect to ${what}$",
                           lambda vars_=vars_: [eq(v * OM(v, v) * XD(z) + v * OM(v, z) - OM(z), 0)
                                                for z in vars_],
                           self._check_at_112(lab, r"$\dot q_\varepsilon\,\Omega_{\dot "
                                              r"q_\varepsilon\dot q_\varepsilon}\,\partial\dot "
                                              rf"q_\varepsilon/\partial {what} + "
                                              r"\dot q_\varepsilon\,\Omega_{\dot "
                                              rf"q_\varepsilon {what}}} - \partial\Omega/"
                                              rf"\partial {what} = 0$ at (1.12)",
                                              [sub(add(self._chain(mul(v, Ovv), vs, z),
                                                       mul(v, self._d(Omv, z))), self._d(Om, z))
                                               for z in vars_],
                                              [sp.S.Zero] * len(vars_))))
        lform = lstar_form(self)
        st.append(Step("1.16", r"the reduced Lagrangian $L^* = \partial\Omega/\partial\dot "
                       r"q_\varepsilon$ at (1.12)", [eq(LSTAR, lform)], check_reading(
            "1.16", r"$L^*$ equals $\partial\Omega/\partial\dot q_\varepsilon$ with "
            r"$\dot q_\varepsilon$ from (1.12); the form shown is $L^*$", [lform], [Ls], self,
            also=([Ls], [Omv]))))
        for lab, vars_, what in (("1.17", [qp[c] for c in nus], r"q'_\nu"),
                                 ("1.18", [qs[c] for c in sig], r"q_\sigma")):
            st.append(Step(lab, rf"$\partial L^*/\partial {what}$ by the chain rule",
                           lambda vars_=vars_: [eq(LS(z), OM(v, v) * XD(z) + OM(v, z))
                                                for z in vars_], self._check_at_112(
                lab, rf"$\partial L^*/\partial {what} = \Omega_{{\dot q_\varepsilon\dot "
                r"q_\varepsilon}\,\partial\dot q_\varepsilon/\partial " f"{what} + "
                rf"\Omega_{{\dot q_\varepsilon {what}}}$",
                [add(self._chain(Ovv, vs, z), self._d(Omv, z)) for z in vars_],
                [self._d(Ls, z) for z in vars_])))
        st.append(Step("1.19", "from (1.14) and (1.17)",
                       lambda: [eq(d("L^*", qp[c]), self._d(Ls, qp[c])) for c in nus],
                       self._check_at_112(
            "1.19", r"$\partial L^*/\partial q'_\nu = (1/\dot q_\varepsilon)\,\partial\Omega/"
            r"\partial q'_\nu$", [over(self._d(Om, qp[c]), v) for c in nus],
            [self._d(Ls, qp[c]) for c in nus])))
        st.append(Step("1.20", "from (1.15) and (1.18)",
                       lambda: [eq(d("L^*", qs[c]), self._d(Ls, qs[c])) for c in sig],
                       self._check_at_112(
            "1.20", r"$\partial L^*/\partial q_\sigma = (1/\dot q_\varepsilon)\,\partial\Omega/"
            r"\partial q_\sigma$ (the OCR prints $1/\dot q_\sigma$)",
            [over(self._d(Om, qs[c]), v) for c in sig], [self._d(Ls, qs[c]) for c in sig])))
        st.append(Step("1.21", "with (1.8) and (1.9)", lambda: [
            eq(LS(qp[c]), partial("L̃", r"\tilde{L}", S.qd[c])) for c in nus] + [
            eq(LS(qs[c]), partial("L̃", r"\tilde{L}", qs[c]) / v) for c in sig], self._check_at_112(
            "1.21", r"$\partial L^*/\partial q'_\nu = \partial\tilde L/\partial\dot q_\nu$ and "
            r"$\partial L^*/\partial q_\sigma = (1/\dot q_\varepsilon)\,\partial\tilde L/"
            r"\partial q_\sigma$",
            [self._sub15(self._d(Lt, S.qd[c])) for c in nus]
            + [over(self._sub15(self._d(Lt, qs[c])), v) for c in sig],
            [self._d(Ls, qp[c]) for c in nus] + [self._d(Ls, qs[c]) for c in sig])))
        st += self._constraint_steps()
        st += self._equation_steps()
        return st

    def _constraint_steps(self):
        S, v, smp = self.system, self._v, self._sample
        deps, nus, sig = S.dependent_coordinates, self._nus, S.independent_coordinates
        if not deps:
            return [Step("1.22", r"no constraints ($g = 0$): $\omega$, $\dot q^*$ and the "
                         "constraint term of (1.26) are absent", [])]
        qp, qs = self._qp, {c: S.q[c] for c in S.coordinates}
        def stars():            # the names, printed only when a step is shown
            return [notation(text(S.qd[c]) + "*", tex(S.qd[c]) + "^{*}") for c in deps]
        om = [sp.Symbol("omega_" + _name(c)) for c in deps]
        st = [Step("1.22", r"$\omega$: the constraints with (1.5) substituted",
                   lambda: [eq(o, w) for o, w in zip(om, self._omega)]),
              Step("1.23", r"$\dot q^* = \partial\omega/\partial\dot q_\varepsilon$",
                   lambda: [eq(s_, q) for s_, q in zip(stars(), self._qdstar)], check_zero(
                       "1.23", r"$\dot q^*$ is free of $\dot q_\varepsilon$",
                       [self._d(q, v) for q in self._qdstar],
                       smp)),
              Step("1.24", "(1.10) in the new variables", lambda: [
                  eq(v * partial(text(o), tex(o), v) - o, 0) for o in om], check_zero(
                  "1.24", r"$\dot q_\varepsilon\,\partial\omega/\partial\dot q_\varepsilon - \omega"
                  " = 0$",
                  [v * self._d(w, v) - w for w in self._omega], smp))]
        phis = list(S._phi.values())
        lhs = [self._d(q, qp[c]) for q in self._qdstar for c in nus]
        lhs += [self._d(q, qs[c]) for q in self._qdstar for c in sig]
        rhs = [self._sub15(self._d(p, S.qd[c])) for p in phis for c in nus]
        rhs += [self._sub15(self._d(p, qs[c])) / v for p in phis for c in sig]
        def shown():
            out = []
            for c_dep, s_ in zip(deps, stars()):
                qd_t, qd_l = text(S.qd[c_dep]), tex(S.qd[c_dep])
                out += [eq(partial(s_.name, sp.latex(s_), qp[c]), partial(qd_t, qd_l, S.qd[c]))
                        for c in nus]
                out += [eq(partial(s_.name, sp.latex(s_), qs[c]), partial(qd_t, qd_l, qs[c]) / v)
                        for c in sig]
            return out
        st.append(Step("1.25", r"derivatives of $\dot q^*$", shown, check_identity(
            "1.25", r"$\partial\dot q^*/\partial q'_\nu = \partial\dot q_{\varepsilon+\beta}/"
            r"\partial\dot q_\nu$ and $\partial\dot q^*/\partial q_\sigma = (1/\dot "
            r"q_\varepsilon)\,\partial\dot q_{\varepsilon+\beta}/\partial q_\sigma$", lhs, rhs,
            smp)))
        return st

    def _momentum_step(self):
        """(1.26a): (dL/dqdot_dep)* written in q', q and h, as used in (1.26)."""
        S = self.system
        def names():            # printed only when the step is shown
            return [notation(f"(∂L/∂{text(S.qd[c])})*",
                             rf"\left(\frac{{\partial L}}{{\partial {tex(S.qd[c])}}}\right)^{{*}}")
                    for c in S.dependent_coordinates]
        forms = momentum_forms(self)
        return Step("1.26a", r"used in (1.26): $(\partial L/\partial\dot q_{\varepsilon+\beta})^*$,"
                    r" $\partial L/\partial\dot q_{\varepsilon+\beta}$ in $q'$, $q$ and $h$",
                    lambda: [eq(a, b) for a, b in zip(names(), forms)], check_reading(
                        "1.26a", r"the form shown is $\partial L/\partial\dot "
                        r"q_{\varepsilon+\beta}$, differentiated first, then with the "
                        "constraints (1.3), (1.5) and (1.12) substituted", forms, self._Pstar,
                        self))

    def _equation_steps(self):
        S, smp = self.system, self._sample
        nus, eps = self._nus, self._eps
        vs, v = self._vstar, self._v
        # (1.4) along a path of (1.26): qdot_eps = (1.12) and qdot_nu = qdot_eps q'_nu are
        # the sampled points' own (``_sample``); the accelerations are replaced at each
        # point (``at``), vs d/dq_eps(vs) and its product with q' plus qdot_eps^2 q''
        vdot = vs * self._D(vs)
        sub = {S.qdd[eps]: vdot}
        for c in nus:
            sub[S.qdd[c]] = vdot * self._qp[c] + v**2 * self._qpp[c]
        eom = dict(zip(S.independent_coordinates, S._eom()))
        forms = whittaker_forms(self)
        st = [Step("1.26", r"the generalized Whittaker equations, one per $q_\nu$, each "
                   r"derivative carried out but $d/d" + tex(self.independent) + "$",
                   [eq(f, 0) for f in forms], check_reading(
                       "1.26", r"$\dot q_\varepsilon$ times (1.26) is the $\nu$-th equation of "
                       "(1.4) on the energy surface (1.12); the form shown is (1.26)",
                       forms, self._eqs, self, at=sub,
                       also=([mul(vs, e) for e in self._eqs], [eom[c] for c in nus])))]
        if S.dependent_coordinates:
            st.append(self._momentum_step())
        self._accelerations()       # (1.26) must be solvable for q''
        tidy_acc = self._tidy_accelerations()
        cleared = cleared_forms(self)
        on = dict(tidy_acc)
        title = r"$q''_\nu$ solved from (1.26), and (1.26) cleared of denominators"
        if len(cleared) < len(nus):
            title += (" (where $q''_\\nu$ is small enough to read as one fraction; "
                      "the others are too large for a cleared form)")
        st.append(Step("1.26b", title, lambda: [eq(k, v) for k, v in tidy_acc.items()]
                       + ["(1.26) cleared of denominators:" if cleared else ""][:len(cleared)]
                       + [eq(c, 0) for c in cleared], check_zero(
                           "1.26b", r"(1.26) and the cleared form vanish at the $q''_\nu$ shown",
                           list(self._eqs) + cleared, smp, at=on)))
        if S.is_holonomic:
            st.append(self._step_127())
        x = self.independent

        def rates():
            return [eq(_dd("t", x), 1 / vs)] + [
                eq(_dd(_name(c), x), q) for c, q in zip(S.dependent_coordinates, self._qdstar)]
        chk = None
        if S.dependent_coordinates:
            chk = check_identity("from 1.12", r"$dq_{\varepsilon+\beta}/dq_\varepsilon = "
                                 r"\dot q_{\varepsilon+\beta}/\dot q_\varepsilon = \dot q^*$ "
                                 "(1.23)", [over(self._sub15(p), self._v) for p in S._phi.values()],
                                 self._qdstar, smp)
        st.append(Step("from 1.12", "time and the dependent coordinates recovered by quadrature",
                       rates, chk))
        return st

    def _whittaker_127(self):
        """Whittaker's equations (1.27), d/dq_eps(dL*/dq'_nu) - dL*/dq_nu, one per q_nu,
        by a route other than (1.26)'s: d/dq_eps along the path is the derivative in s of
        f(q_eps + s, q + s q', q' + s q'') at s = 0, taken in one pass through the tree of
        f (:func:`.dag.along`), not the chain-rule sum of partial derivatives ``_D``."""
        x = self.independent
        path = {x: sp.S.One}
        for c in self._nus:
            path[self.system.q[c]] = self._qp[c]
            path[self._qp[c]] = self._qpp[c]
        out, memo = [], {}                  # one memo: the equations share most pieces
        for c in self._nus:
            rate = along(self._d(self._Lstar, self._qp[c]), path, memo)
            out.append(rate - self._d(self._Lstar, self.system.q[c]))
        return out

    def _step_127(self):
        """(1.27): Whittaker's equations, the Euler-Lagrange equations of L* with q_eps
        as the independent variable, checked against (1.26) for g = 0."""
        e27 = self._whittaker_127()
        chk = check_identity("1.27", "for $g = 0$, (1.26) is Whittaker's (1.27): the "
                             "Euler-Lagrange equations of $L^*$, with $d/dq_\\varepsilon$ taken "
                             "along the path (not by the chain rule of (1.26)), agree", e27,
                             self._eqs, self._sample)
        return Step("1.27", "Whittaker's equations ($g = 0$)", [eq(e, 0) for e in e27], chk)

    @property
    @guarded("deriving the steps")
    def steps(self):
        """Every step of the paper for this system: a :class:`Derivation` of :class:`Step`."""
        if "steps" not in self._cache:
            title = (f"{self.system.name}: Whittaker reduction with $q_\\varepsilon = "
                     f"{tex(self.independent)}$, $\\operatorname{{sign}}\\dot q_\\varepsilon = "
                     f"{self.direction:+d}$")
            with shared_points():
                self._cache["steps"] = Derivation(title, self._steps())
        return self._cache["steps"]

    @guarded("verifying the reduction")
    def verify(self):
        """Re-run every check of the derivation; a :class:`Report` of how each was shown."""
        self._cache.pop("steps", None)
        self.system._cache.pop("steps", None)
        return Report(s.check for s in self.steps if s.check)

    @guarded("showing the steps")
    def show(self, latex=False):
        """Every step, tagged with the paper's number (notebook: maths; terminal: Unicode)."""
        return self.steps.show(latex=latex)

    def __repr__(self):
        return (f"<Reduction of {self.system.name!r}: q_eps = {self.independent}, "
                f"direction {self.direction:+d}, {len(self._nus)} equation(s) (1.26)>")

    # ----- numerics (whittaker_teach.numerics) -----------------------------
    def simulate(self, q0, qp0, h, span, params, method="DOP853", rtol=1e-9, atol=None,
                 **options):
        """Integrate the reduced model (1.26) in q_eps, with t(q_eps) and the dependent
        coordinates recovered by quadrature alongside (1.12), (1.23).

        ``q0``: {coordinate: value} at the start, q_eps included; ``qp0``:
        {q_nu: dq_nu/dq_eps}; ``h``: the energy; ``span``: (q_eps start, q_eps
        end).  Options: ``on_turning_point`` (``"raise"``: a ChartError where
        qdot_eps vanishes; ``"switch"``: continue in time across it),
        ``turning_tol``, ``t0``, ``dense``.  Returns a
        :class:`~whittaker_teach.numerics.results.Path`.  With ``tol=`` (a relative
        error) instead of method/rtol, the package picks the model and the method
        (the closed form where one exists, else the reduced model with a checked
        rtol); ``path.explain()`` says which and why
        (:mod:`whittaker_teach.numerics.scene`).
        """
        from .backends import provided      # numerics registers it: the core imports none
        return provided("simulate")(self, q0, qp0, h, span, params, method, rtol, atol,
                                    **options)


LSTAR = notation("L*", "L^{*}")


def _dd(f, x):
    """The notation d f / d x (a total derivative along the path), for display."""
    fx = text(sp.Symbol(f), use_unicode=True)
    return notation(f"d{fx}/d{x}", rf"\frac{{d {tex(sp.Symbol(f))}}}{{d {tex(x)}}}")
