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
  by Neimark and Fufaev, 1972);
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
"""

from __future__ import annotations

from dataclasses import dataclass

import mpmath
import sympy as sp

from ..errors import ModelError, ModelTypeError
from .linear import Linearization

__all__ = ["Classification", "classify", "hurwitz_conditions"]

UNSTABLE = "unstable"
ASYMPTOTIC = "asymptotically stable"
FAMILY = "stable, asymptotically relative to the family"
CRITICAL = "critical: linearisation decides nothing"
UNDECIDED = "undecided: depends on the parameters"


@dataclass(frozen=True)
class Classification:
    """``verdict`` (one of the five strings of the module), ``reason`` (a sentence),
    ``zeros`` (how many zero eigenvalues), ``family`` (the family's dimension),
    ``q`` (p(lambda) / lambda^zeros) and ``conditions`` (Hurwitz: all > 0 for every
    root of q to have a negative real part)."""

    verdict: str
    reason: str
    zeros: int
    family: int
    q: sp.Expr
    conditions: tuple

    @property
    def decided(self):
        """True when the linearisation decides (unstable, or stable in one of the two senses)."""
        return self.verdict in (UNSTABLE, ASYMPTOTIC, FAMILY)

    def __str__(self):
        return f"{self.verdict}: {self.reason}"


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
    it (default: the number of the motion's own symbols, ``lin.steady.family``);
    ``at``: values for symbols whose signs the parameters' assumptions leave open.

    >>> import whittaker_teach as wt
    >>> from whittaker_teach.stability import steady_motion, linearize
    >>> classify(linearize(steady_motion(wt.examples.sledge(), {"theta": 0}, {"x": 0}))).verdict
    'critical: linearisation decides nothing'
    """
    if not isinstance(lin, Linearization):
        raise ModelTypeError(f"expected a Linearization, got {type(lin).__name__}")
    if family is None:
        family = len(lin.steady.family)
    if not isinstance(family, int) or family < 0:
        raise ModelError(f"family must be a dimension (an integer >= 0), got {family!r}")
    if at is not None and not isinstance(at, dict):
        raise ModelTypeError("at must be a dict {symbol: value}")
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
        return Classification(verdict, reason, z, family, sp.factor(q.as_expr()), conds)

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
