"""Linearisation about a steady motion: of the time equations (1.4) and of the
reduced equation (1.26), their characteristic polynomials, and how they agree.

The **time** state is (shape coordinates, every independent velocity): the moving
coordinates' own values are left out, [1.4a] does not contain them (each adds a
zero eigenvalue and nothing else), and the dependent coordinates follow by (1.3).
The **reduced** state, with q_eps a moving coordinate of velocity v_eps != 0 as
the independent variable, is (shape coordinates, every q'_nu), at the energy h of
the steady motion.  Since d/dt = qdot_eps d/dq_eps and qdot_eps = v_eps on the
steady motion, the exponents correspond as lambda = v_eps mu, and the time system
has one more eigenvalue, 0 (the energy, i.e. the family of speeds): the library
checks p_time(lambda) = lambda v_eps^n p_red(lambda / v_eps) (:func:`compare`).

>>> import sympy as sp
>>> import whittaker_teach as wt
>>> from whittaker_teach.stability import steady_motion, linearize
>>> v = sp.Symbol("v", positive=True)
>>> sm = steady_motion(wt.examples.offset_sleigh(), {"theta": 0}, {"x": v})
>>> linearize(sm).charpoly()
lambda*(b*lambda*m*v + k**2 + lambda**2*(J + b**2*m))/(J + b**2*m)
"""

from __future__ import annotations

from dataclasses import dataclass, field

import sympy as sp

from ..errors import ModelError, ModelTypeError
from ..verify import check_identity, check_zero
from .steady import SteadyMotion, _accelerations_plain, sampler

__all__ = ["Linearization", "linearize", "linearize_reduced", "compare", "LAMBDA", "MU"]

#: The variable of the characteristic polynomials: lambda in time, mu along q_eps.
LAMBDA = sp.Symbol("lambda")
MU = sp.Symbol("mu")


def _tidy(e):
    e = sp.cancel(e)
    return sp.factor(e) if e != 0 else e


@dataclass
class Linearization:
    """d(delta z)/d(variable) = A delta z about a steady motion.

    ``state``: the state's components as expressions (q(t), q(t).diff(t) or, for
    the reduced equation, q(x), q(x).diff(x)); ``point``: their values; ``A``: the
    matrix; ``variable``: t or q_eps; ``dropped``: moving coordinates left out of
    the state; ``rate``: v_eps for a reduced linearisation (d/dt = v_eps d/dq_eps).
    """

    steady: SteadyMotion
    state: list
    point: list
    A: sp.Matrix
    variable: sp.Basic
    dropped: list
    rate: sp.Expr = None
    symbol: sp.Symbol = LAMBDA
    _cache: dict = field(default_factory=dict, repr=False)

    def charpoly(self):
        """det(symbol I - A), factored (monic in the symbol)."""
        if "p" not in self._cache:
            p = self.A.charpoly(self.symbol).as_expr()
            self._cache["p"] = sp.factor(p, self.symbol)
        return self._cache["p"]

    @property
    def eigenvalues(self):
        """{eigenvalue: multiplicity}, the roots of :meth:`charpoly` (``sympy.roots``;
        CRootOf where no formula is found)."""
        if "ev" not in self._cache:
            poly = sp.Poly(sp.expand(self.charpoly()), self.symbol)
            ev = sp.roots(poly)
            if sum(ev.values()) != poly.degree():
                ev = {}
                for f, mult in sp.factor_list(poly)[1]:
                    r = sp.roots(f)
                    if sum(r.values()) != f.degree():
                        r = {sp.CRootOf(f, i): 1 for i in range(f.degree())}
                    for k, n in r.items():
                        ev[k] = ev.get(k, 0) + n * mult
            ev = {_tidy(k): n for k, n in ev.items()}
            self._cache["ev"] = dict(sorted(ev.items(), key=lambda kv: sp.default_sort_key(kv[0])))
        return self._cache["ev"]

    def __repr__(self):
        return (f"Linearization(d/d{self.variable}, state {[str(s) for s in self.state]}, "
                f"A = {self.A.tolist()})")


def linearize(steady):
    """The linearisation of (1.4) (its accelerations [1.4a]) about ``steady``.

    Each entry of A is put over one denominator and factored.

    >>> import sympy as sp
    >>> import whittaker_teach as wt
    >>> from whittaker_teach.stability import steady_motion
    >>> lin = linearize(steady_motion(wt.examples.sledge(), {"theta": 0}, {"x": 0}))
    >>> lin.state
    [theta(t), Derivative(x(t), t), Derivative(theta(t), t)]
    >>> lin.eigenvalues
    {0: 1, -I*k/sqrt(J): 1, I*k/sqrt(J): 1}
    """
    if not isinstance(steady, SteadyMotion):
        raise ModelTypeError(f"expected a SteadyMotion (from steady_motion), got "
                             f"{type(steady).__name__}")
    system = steady.system
    t = system.coordinates[0].args[0]
    Q, V, acc = _accelerations_plain(system)
    shape, moving = steady.shape, steady.moving
    z = [Q[q] for q in shape] + [V[q] for q in system.independent_coordinates]
    f = [V[q] for q in shape] + [acc[q] for q in system.independent_coordinates]
    rep = {}
    for q in system.independent_coordinates:
        rep[V[q]] = steady.velocities.get(q, sp.S.Zero)
        rep[Q[q]] = steady.values.get(q, sp.S.Zero)
    A = sp.Matrix(len(f), len(z), lambda i, j: _tidy(f[i].diff(z[j]).xreplace(rep)))
    state = [q for q in shape] + [q.diff(t) for q in system.independent_coordinates]
    point = [steady.values[q] for q in shape] + [steady.velocities.get(q, sp.S.Zero)
                                                 for q in system.independent_coordinates]
    return Linearization(steady, state, point, A, t, moving)


def _direction(v, q):
    if v.is_positive:
        return +1
    if v.is_negative:
        return -1
    if v == 0:
        raise ModelError(f"the velocity of {q.func.__name__} is 0 on this steady motion: it cannot "
                         "be the independent variable q_eps of the reduction (1.5) needs "
                         "qdot_eps != 0")
    raise ModelError(f"the sign of the velocity {v} of {q.func.__name__} is unknown: declare its "
                     "symbol positive or negative (the branch of (1.12) depends on it)")


def linearize_reduced(steady, coordinate=None, reduction=None):
    """The linearisation of the reduced equation (1.26) about the path of ``steady``.

    ``coordinate`` (q_eps): a moving coordinate with a velocity of known sign
    (default: the first moving one with a velocity not 0).  The system is reduced with that direction
    (or ``reduction`` is used, if given); the state is (shape coordinates, every
    q'_nu) at h = the steady motion's energy.

    >>> import sympy as sp
    >>> import whittaker_teach as wt
    >>> from whittaker_teach.stability import steady_motion
    >>> v = sp.Symbol("v", positive=True)
    >>> red = linearize_reduced(steady_motion(wt.examples.sledge(), {"theta": 0}, {"x": v}))
    >>> red.A
    Matrix([
    [             0, 1],
    [-k**2/(J*v**2), 0]])
    """
    if not isinstance(steady, SteadyMotion):
        raise ModelTypeError(f"expected a SteadyMotion, got {type(steady).__name__}")
    system = steady.system
    moving = steady.moving
    if coordinate is None:
        if not moving:
            raise ModelError("this steady motion is an equilibrium (nothing moves): there is no "
                             "q_eps with qdot_eps != 0 to reduce by (1.5)")
        q_eps = next((q for q in moving if steady.velocities[q] != 0), moving[0])
    else:
        from .steady import _coordinate
        q_eps = _coordinate(system, coordinate)
        if q_eps not in moving:
            raise ModelError(f"{q_eps.func.__name__} is held fixed on this steady motion: q_eps must "
                             "be a moving coordinate (qdot_eps != 0, 1.5)")
    v_eps = steady.velocities[q_eps]
    direction = _direction(v_eps, q_eps)
    red = reduction if reduction is not None else system.reduce(q_eps, direction)
    s = red.independent
    qs = red.coordinates                         # q_nu(s)
    names = {q.func.__name__: q for q in system.independent_coordinates}
    acc = red.accelerations()
    Q = {c: sp.Dummy(c.func.__name__, real=True) for c in qs}
    P = {c: sp.Dummy(c.func.__name__ + "prime", real=True) for c in qs}
    rep = {c.diff(s): P[c] for c in qs}
    rep.update({c: Q[c] for c in qs})
    F = {c: acc[c.diff(s, 2)].xreplace(rep) for c in qs}
    shape = [c for c in qs if names[c.func.__name__] in steady.values]
    z = [Q[c] for c in shape] + [P[c] for c in qs]
    f = [P[c] for c in shape] + [F[c] for c in qs]
    at = {red.h: steady.energy()}
    for c in qs:
        q = names[c.func.__name__]
        at[Q[c]] = steady.values.get(q, sp.S.Zero)
        at[P[c]] = steady.velocities.get(q, sp.S.Zero) / v_eps
    dropped = [c for c in qs if c not in shape]
    for c in dropped:                             # cyclic in [1.4a]; check (1.26) too
        d = [e.diff(Q[c]) for e in F.values()]
        if any(e != 0 for e in d):
            syms = set().union(*(e.free_symbols for e in d))
            chk = check_zero("cyclic", f"(1.26) free of {c}", d, sampler(syms))
            if not chk.holds:
                raise ModelError(f"{c} appears in the reduced equations (1.26): it cannot be left "
                                 "out of the reduced state")
    A = sp.Matrix(len(f), len(z), lambda i, j: _tidy(f[i].diff(z[j]).xreplace(at)))
    state = list(shape) + [c.diff(s) for c in qs]
    point = [at[Q[c]] for c in shape] + [at[P[c]] for c in qs]
    return Linearization(steady, state, point, A, s, dropped, rate=v_eps, symbol=MU)


@dataclass(frozen=True)
class Agreement:
    """The outcome of :func:`compare`: ``check`` (a verify.Check of the identity
    p_time(lambda) = lambda v^n p_red(lambda/v)), and the two polynomials."""

    check: object
    time_poly: sp.Expr
    reduced_poly: sp.Expr
    rate: sp.Expr

    @property
    def holds(self):
        return self.check.holds

    def __str__(self):
        c = self.check
        how = c.detail if c.method == "exact" else f"{c.detail}, {c.points} points, largest residual {float(c.max_residual):.1e}"
        return (f"p_time(lambda) = lambda * v^n * p_red(lambda/v) with v = {self.rate}: "
                f"{'holds' if c.holds else 'FAILS'} ({c.method}: {how})")


def compare(time_lin, reduced_lin):
    """Check that the time and the reduced linearisations have the same exponents:
    lambda = v_eps mu for every mu, plus one more lambda = 0.

    The identity p_time(lambda) = lambda v^n p_red(lambda / v) between the monic
    characteristic polynomials (n the reduced dimension) is checked coefficient by
    coefficient, exactly or else at 40 digits at random values of the parameters.

    >>> import sympy as sp
    >>> import whittaker_teach as wt
    >>> from whittaker_teach.stability import steady_motion, linearize
    >>> v = sp.Symbol("v", positive=True)
    >>> sm = steady_motion(wt.examples.offset_sleigh(), {"theta": 0}, {"x": v})
    >>> compare(linearize(sm), linearize_reduced(sm)).holds
    True
    """
    for lin, what in ((time_lin, "time"), (reduced_lin, "reduced")):
        if not isinstance(lin, Linearization):
            raise ModelTypeError(f"the {what} linearisation must be a Linearization")
    if reduced_lin.rate is None or time_lin.rate is not None:
        raise ModelError("compare(time, reduced): the first from linearize, the second from "
                         "linearize_reduced")
    if reduced_lin.steady is not time_lin.steady and (
            reduced_lin.steady.values != time_lin.steady.values
            or reduced_lin.steady.velocities != time_lin.steady.velocities):
        raise ModelError("the two linearisations are about different steady motions")
    lam, v = LAMBDA, reduced_lin.rate
    n = reduced_lin.A.rows
    pt = sp.Poly(sp.expand(time_lin.charpoly()), lam)
    pr = sp.expand(reduced_lin.charpoly().subs(MU, lam / v) * lam * v**n)
    pr = sp.Poly(sp.cancel(pr), lam)
    if pt.degree() != pr.degree():
        chk = check_identity("exponents", "degrees", sp.Integer(pt.degree()), sp.Integer(pr.degree()),
                             lambda rng: {})
    else:
        a, b = pt.all_coeffs(), pr.all_coeffs()
        syms = set().union(*(sp.sympify(e).free_symbols for e in a + b))
        chk = check_identity("exponents", "lambda = v mu, and one lambda = 0", a, b, sampler(syms))
    return Agreement(chk, pt.as_expr(), reduced_lin.charpoly(), v)
