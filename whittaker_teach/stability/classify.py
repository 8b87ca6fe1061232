"""What the eigenvalues of a linearisation say, and what they do not.

:func:`classify` reads the characteristic polynomial p(lambda) = lambda^z q(lambda)
(z zero eigenvalues) with Lyapunov's first method:

* a root of q with positive real part: **unstable** (decided by the linearisation);
  with q's leading coefficient positive, a negative coefficient of q is enough;
* every root of q with negative real part (Hurwitz: all Hurwitz determinants
  positive) and z = 0: **asymptotically stable**;
* the same with z equal to the dimension of the family of steady motions through
  the point and A of rank n - z: **stable, and asymptotically stable relative to
  the family** (a nearby motion tends to a nearby steady motion; the theorem of
  Lyapunov and Malkin on a manifold of equilibria, used for non-holonomic systems
  by Neimark and Fufaev, 1972).  Its hypothesis is a *manifold* of equilibria of
  dimension z through the point, not a count of zero eigenvalues: the dimension is
  computed by :func:`family_dimension` (the steady motions through the point are
  the zeros of the equilibrium conditions; where the rank of their Jacobian is
  constant near the point they form a manifold of dimension "unknowns - rank").
  A ``family`` given by hand is checked against it, and refused when it differs;
  where the rank is not constant, the dimension is not decided, and the
  ``family`` (given, or the number of the motion's own symbols) is used as
  stated, at most the bound "unknowns - rank at the point", and the
  ``family_how`` of the result says so;
* roots on the imaginary axis and none to the right (a centre of the
  linearisation, or more zeros than the family explains): **critical**: the
  linearisation decides nothing; a Lyapunov function (the energy, other
  integrals) or the nonlinear terms must;
* otherwise, with symbols whose signs SymPy cannot decide: **undecided**, with
  the conditions (``conditions``: expressions that must all be positive for
  every root of q to lie to the left).

>>> import sympy as sp
>>> import whittaker_teach as wt
>>> from whittaker_teach.stability import steady_motion, linearize
>>> v = sp.Symbol("v", positive=True)
>>> c = classify(linearize(steady_motion(wt.examples.offset_sleigh(), {"theta": 0}, {"x": v})))
>>> c.verdict
'stable, asymptotically relative to the family'
>>> c.family, c.family_how
(1, 'computed: 2 unknowns, rank 1 at the point and near it')
"""

from __future__ import annotations

from dataclasses import dataclass

import random

import mpmath
import sympy as sp

from ..errors import ModelError, ModelTypeError
from .linear import Linearization
from .steady import SteadyMotion, _accelerations_plain, _sample_value

__all__ = ["Classification", "classify", "hurwitz_conditions", "FamilyDimension",
           "family_dimension"]

UNSTABLE = "unstable"
ASYMPTOTIC = "asymptotically stable"
FAMILY = "stable, asymptotically relative to the family"
CRITICAL = "critical: linearisation decides nothing"
UNDECIDED = "undecided: depends on the parameters"


@dataclass(frozen=True)
class Classification:
    """``verdict`` (one of the five strings of the module), ``reason`` (a sentence),
    ``zeros`` (how many zero eigenvalues), ``family`` (the family's dimension),
    ``q`` (p(lambda) / lambda^zeros), ``conditions`` (Hurwitz: all > 0 for every
    root of q to have a negative real part) and ``family_how`` (where ``family``
    comes from: computed by :func:`family_dimension`, or given and checked, or
    used unchecked)."""

    verdict: str
    reason: str
    zeros: int
    family: int
    q: sp.Expr
    conditions: tuple
    family_how: str = ""

    @property
    def decided(self):
        """True when the linearisation decides (unstable, or stable in one of the two senses)."""
        return self.verdict in (UNSTABLE, ASYMPTOTIC, FAMILY)

    def __str__(self):
        return f"{self.verdict}: {self.reason}"


@dataclass(frozen=True)
class FamilyDimension:
    """The outcome of :func:`family_dimension`: ``dimension`` (None when not decided),
    ``bound`` (an upper bound, always valid), ``unknowns`` and the two ranks of the
    Jacobian of the equilibrium conditions, at the point and generic (near it)."""

    dimension: int | None
    bound: int
    unknowns: int
    rank_at_point: int
    rank_generic: int

    def __str__(self):
        if self.dimension is not None:
            return (f"{self.unknowns} unknowns, rank {self.rank_at_point} at the point and "
                    "near it")
        return (f"not decided: rank {self.rank_at_point} at the point, {self.rank_generic} "
                f"near it; at most {self.bound}")


_RANK_DPS = 50
_RANK_TOL = mpmath.mpf(10) ** -30


def _numeric_rank(M, values):
    """The rank of the matrix function M at ``values`` (mpmath, 50 digits,
    singular values below 1e-30 of the largest counted as 0); None if it cannot be
    evaluated there."""
    with mpmath.workdps(_RANK_DPS):
        try:
            rows = M(*[mpmath.mpf(v) for v in values])
            Mm = mpmath.matrix(rows)
        except (ZeroDivisionError, ValueError, TypeError, OverflowError):
            return None
        if Mm.rows == 0 or Mm.cols == 0:
            return 0
        entries = [Mm[i, j] for i in range(Mm.rows) for j in range(Mm.cols)]
        if any(not mpmath.isfinite(e) for e in entries):
            return None
        if any(isinstance(e, mpmath.mpc) and abs(e.imag) > _RANK_TOL for e in entries):
            return None
        Mm = mpmath.matrix([[mpmath.re(Mm[i, j]) for j in range(Mm.cols)] for i in range(Mm.rows)])
        sv = mpmath.svd_r(Mm, compute_uv=False)
        top = max([abs(x) for x in sv] + [mpmath.mpf(1)])
        return sum(1 for x in sv if abs(x) > _RANK_TOL * top)


def family_dimension(steady, at=None, samples=3, seed=1983):
    """The dimension of the family of steady motions through ``steady``, as a
    manifold of equilibria of the linearised state (shape coordinates, velocities).

    The equilibria are the zeros of g(p) = [1.4a] with the shape velocities 0, as
    functions of the unknowns p = (shape coordinates, moving velocities).  The
    tangent space of a manifold of zeros lies in the kernel of the Jacobian Dg at
    the point, so "unknowns - rank at the point" is an upper bound (``bound``).
    When the rank at the point equals the generic rank (the largest, attained
    near the point), the rank is constant near it and by the constant-rank theorem
    the zeros near the point form a manifold of exactly that dimension
    (``dimension``); otherwise ``dimension`` is None (a bifurcation point, or a
    degenerate one: the Jacobian cannot tell).  Ranks are computed at 50 digits at
    ``samples`` random values of the parameters (and of the unknowns, for the
    generic rank); ``at`` fixes values of symbols first.

    >>> import sympy as sp
    >>> import whittaker_teach as wt
    >>> from whittaker_teach.stability import steady_motion
    >>> v = sp.Symbol("v", positive=True)
    >>> sleigh = wt.examples.offset_sleigh()                     # with the spring
    >>> family_dimension(steady_motion(sleigh, {"theta": 0}, {"x": v})).dimension
    1
    >>> no_spring = wt.ChaplyginSystem(sleigh.lagrangian.subs(sp.Symbol("k", positive=True), 0),
    ...                                sleigh.coordinates, dependent=sleigh.constraints)
    >>> family_dimension(steady_motion(no_spring, {"theta": 0}, {"x": v})).dimension
    2
    """
    if not isinstance(steady, SteadyMotion):
        raise ModelTypeError(f"expected a SteadyMotion, got {type(steady).__name__}")
    if at is not None and not isinstance(at, dict):
        raise ModelTypeError("at must be a dict {symbol: value}")
    system = steady.system
    Q, V, acc = _accelerations_plain(system)
    shape, moving = steady.shape, steady.moving
    still = {V[q]: sp.S.Zero for q in shape}
    g = sp.Matrix([acc[q].xreplace(still) for q in system.independent_coordinates])
    p = [Q[q] for q in shape] + [V[q] for q in moving]
    n = len(p)
    if n == 0:
        return FamilyDimension(0, 0, 0, 0, 0)
    Dg = g.jacobian(p)
    if at:
        Dg = Dg.subs(at)
    params = sorted(Dg.free_symbols - set(p), key=str)
    where = [steady.values[q] for q in shape] + [steady.velocities[q] for q in moving]
    where = [sp.sympify(w).subs(at) if at else sp.sympify(w) for w in where]
    extra = sorted(set().union(*(w.free_symbols for w in where)) - set(params), key=str)
    args = list(p) + params + extra
    M = sp.lambdify(args, Dg.tolist(), modules="mpmath")
    atpoint = sp.lambdify(params + extra, where, modules="mpmath")
    rng = random.Random(seed)
    r0 = rg = None
    for _ in range(4 * samples):
        vals = [_sample_value(s, rng) for s in params + extra]
        with mpmath.workdps(_RANK_DPS):
            try:
                pt = [mpmath.mpf(x) if not isinstance(x, mpmath.mpc) else x
                      for x in atpoint(*vals)]
            except (ZeroDivisionError, ValueError, TypeError, OverflowError):
                continue
        if any(isinstance(x, mpmath.mpc) for x in pt):
            continue
        ra = _numeric_rank(M, pt + vals)
        rgen = _numeric_rank(M, [_sample_value(s, rng) for s in p] + vals)
        if ra is not None:
            r0 = ra if r0 is None else max(r0, ra)
        if rgen is not None:
            rg = rgen if rg is None else max(rg, rgen)
        samples -= 1
        if samples <= 0 and r0 is not None and rg is not None:
            break
    if r0 is None or rg is None:
        return FamilyDimension(None, n, n, -1 if r0 is None else r0, -1 if rg is None else rg)
    rg = max(rg, r0)
    return FamilyDimension(n - r0 if r0 == rg else None, n - r0, n, r0, rg)


def hurwitz_conditions(q, lam):
    """The Hurwitz determinants Delta_1..Delta_n of q (made monic): every root of q has
    a negative real part exactly when all are positive.

    >>> a, b = sp.symbols("a b")
    >>> lam = sp.Symbol("lambda")
    >>> hurwitz_conditions(lam**2 + a*lam + b, lam)
    (a, a*b)
    """
    poly = sp.Poly(q, lam)
    c = [sp.cancel(x / poly.LC()) for x in poly.all_coeffs()]   # c0 = 1, c1, ..., cn
    n = poly.degree()

    def coef(k):
        return c[k] if 0 <= k <= n else sp.S.Zero
    H = sp.Matrix(n, n, lambda i, j: coef(2 * j - i + 1))
    return tuple(sp.factor(H[:k, :k].det()) for k in range(1, n + 1))


def _sign(e, at):
    e = sp.sympify(e).subs(at) if at else sp.sympify(e)
    if e.is_positive:
        return 1
    if e.is_negative:
        return -1
    if e.is_zero:
        return 0
    if not e.free_symbols:
        x = mpmath.mpf(sp.N(e, 40))
        return (x > 0) - (x < 0)
    return None


def classify(lin, family=None, at=None):
    """Classify the steady motion of ``lin`` (a :class:`Linearization`) by its
    eigenvalues.  ``family``: the dimension of the family of steady motions through
    it.  By default it is computed (:func:`family_dimension`); where that cannot
    decide (the rank of the equilibrium conditions not constant near the point),
    the number of the motion's own symbols, ``lin.steady.family``, is used and
    ``family_how`` says it is unchecked.  A ``family`` given by hand is checked the
    same way and refused (ModelError) when it differs from the computed dimension,
    or exceeds the bound when there is none.  For a reduced linearisation (1.26)
    nothing is computed: ``family`` is used as given.  ``at``: values for symbols
    whose signs the parameters' assumptions leave open.

    >>> import whittaker_teach as wt
    >>> from whittaker_teach.stability import steady_motion, linearize
    >>> classify(linearize(steady_motion(wt.examples.sledge(), {"theta": 0}, {"x": 0}))).verdict
    'critical: linearisation decides nothing'
    """
    if not isinstance(lin, Linearization):
        raise ModelTypeError(f"expected a Linearization, got {type(lin).__name__}")
    if family is not None and (not isinstance(family, int) or isinstance(family, bool)
                               or family < 0):
        raise ModelError(f"family must be a dimension (an integer >= 0), got {family!r}")
    if at is not None and not isinstance(at, dict):
        raise ModelTypeError("at must be a dict {symbol: value}")
    if lin.rate is not None:                        # reduced (1.26): not computed
        how = "given, not checked (reduced linearisation)" if family is not None else \
            "the motion's own symbols, not checked (reduced linearisation)"
        if family is None:
            family = len(lin.steady.family)
    else:
        fd = family_dimension(lin.steady, at=at)
        if fd.dimension is not None:
            if family is not None and family != fd.dimension:
                raise ModelError(f"family={family} given, but the steady motions through this point "
                                 f"form a manifold of dimension {fd.dimension} ({fd})")
            how = ("given, and checked: " if family is not None else "computed: ") + str(fd)
            family = fd.dimension
        elif family is not None:
            if family > fd.bound:
                raise ModelError(f"family={family} given, but the steady motions through this "
                                 f"point form at most a manifold of dimension {fd.bound} ({fd})")
            how = f"given, not checked ({fd})"
        else:
            family = min(len(lin.steady.family), fd.bound)
            how = f"the motion's own symbols, not checked ({fd})"
    lam = lin.symbol
    p = sp.Poly(sp.expand(lin.charpoly()), lam)
    coeffs = p.all_coeffs()[::-1]                 # constant first
    z = 0
    while z < len(coeffs) - 1 and sp.cancel(coeffs[z]) == 0:
        z += 1
    q = sp.Poly(sum(coeffs[k] * lam**(k - z) for k in range(z, len(coeffs))), lam)
    n = q.degree()
    A = lin.A.subs(at) if at else lin.A
    rank = A.rank(simplify=True)
    if n == 0:
        conds = ()
    else:
        conds = hurwitz_conditions(q.as_expr(), lam)
    mono = [sp.cancel(x / q.LC()) for x in q.all_coeffs()]
    signs = [_sign(x, at) for x in mono[1:]]
    hs = [_sign(x, at) for x in conds]

    def result(verdict, reason):
        return Classification(verdict, reason, z, family, sp.factor(q.as_expr()), conds, how)

    if any(s == -1 for s in signs):
        return result(UNSTABLE, "a coefficient of q(lambda) = p(lambda)/lambda^z is negative, "
                      "so q has a root with a positive real part (Lyapunov's first method)")
    if n == 0 or all(h == 1 for h in hs):
        if z == 0:
            return result(ASYMPTOTIC, "every eigenvalue has a negative real part")
        if z == family and rank == A.rows - z:
            return result(FAMILY, f"{z} zero eigenvalue(s), as many as the dimension of the "
                          "family of steady motions (A of rank n - z), every other eigenvalue "
                          "with a negative real part: a nearby motion tends to a nearby steady "
                          "motion of the family (Lyapunov-Malkin)")
        return result(CRITICAL, f"{z} zero eigenvalue(s) for a family of dimension {family}: "
                      "the zeros the family does not explain leave the question to the "
                      "nonlinear terms")
    # q even in lambda with positive coefficients: look for roots on the imaginary axis
    even = all(c == 0 for c in q.all_coeffs()[1::2])
    if even and all(s == 1 for s in signs[1::2]):
        s = sp.Symbol("s")
        qs = sp.Poly(sum(c * s**k for k, c in enumerate(q.all_coeffs()[::-2])), s)
        if qs.degree() == 1 or (not (qs.free_symbols - {s}) or at):
            qn = sp.Poly(qs.as_expr().subs(at), s) if at else qs
            if qs.degree() == 1:
                imaginary = True
            else:
                roots = [complex(r) for r in sp.Poly(qn, s).nroots(n=40)]
                imaginary = all(abs(r.imag) < 1e-30 and r.real < 0 for r in roots)
            if imaginary:
                return result(CRITICAL, "the non-zero eigenvalues are purely imaginary (a centre "
                              "of the linearisation): Lyapunov's first method decides nothing; "
                              "an integral or a Lyapunov function must")
            return result(UNSTABLE, "q(lambda) is even and has a root off the imaginary axis, "
                          "so one with a positive real part")
    if all(h is not None for h in hs) and all(sg is not None for sg in signs):
        if not at and not (q.free_symbols - {lam}):
            pass
        roots = [complex(r) for r in q.nroots(n=40)] if not (q.free_symbols - {lam}) else None
        if roots is not None:
            if any(r.real > 1e-30 for r in roots):
                return result(UNSTABLE, "an eigenvalue has a positive real part")
            return result(CRITICAL, "eigenvalues on the imaginary axis: linearisation decides "
                          "nothing")
    return result(UNDECIDED, "the signs of the Hurwitz conditions are not decided by the "
                  "symbols' assumptions; give values with at=..., or read the conditions")
