"""Is an answer equal to the right one, and if not, what kind of difference is it?

Equality is decided by evaluation at random admissible points, with mpmath
at 30 digits: the points respect the exercise's assumptions (positive
masses, the direction of travel, an energy above the potential), so any
form of the right answer (``1 + tan(theta)**2`` or ``sec(theta)**2``,
expanded or factored, ``sqrt(a)*sqrt(b)`` or ``sqrt(a*b)``) agrees with it
to about 28 digits at every point, and a wrong answer does not.  This is
the method of the library's own checks (``whittaker_teach.verify``); an
identity that fails only outside the sampled box is not seen.

When the answer is wrong, :func:`compare` looks for a simple explanation,
in this order: complex values where the right answer is real, a wrong sign,
a constant factor, a factor that is a power of one or more symbols (a
missing factor, a wrong power), the answer being a power of the right one,
a wrong power of one factor, one term with the wrong sign, missing or
changed, an extra term, an additive constant; otherwise it says which
symbols the difference depends on.  The hints name the kind of difference,
not the right answer.

>>> import sympy as sp
>>> th, k = sp.symbols("theta k", positive=True)
>>> dom = Domain({th: (0.1, 1.2), k: (0.5, 2.0)})
>>> compare(1 + sp.tan(th)**2, sp.sec(th)**2, dom).ok
True
>>> print(compare(-k*th, k*th, dom).hint)
the sign is wrong (your answer is -1 times the right one)
>>> print(compare(k*th, k**2*th, dom).hint)
your answer is 1/k times the right one: a factor k is missing (or the power of k is one too low)
"""

from __future__ import annotations

import random
from dataclasses import dataclass, field

import mpmath
import sympy as sp

__all__ = ["Domain", "Verdict", "compare", "depends_on"]

DPS = 30
TOL = mpmath.mpf(10) ** -10   # relative: exact forms agree to ~28 digits, floats to ~15
POINTS = 8


@dataclass
class Domain:
    """Where answers are compared: a box of values and conditions.

    ``ranges``: {symbol: (low, high)}; ``conditions``: expressions that must
    be positive at a point; ``derived``: {symbol: expression of the others},
    evaluated after the box is sampled (e.g. the energy constant h of a
    sampled motion).
    """

    ranges: dict
    conditions: tuple = ()
    derived: dict = field(default_factory=dict)

    def __post_init__(self):
        self.symbols = sorted([*self.ranges, *self.derived], key=str)
        self._cond = None
        self._der = None

    def _compiled(self):
        if self._cond is None:
            base = sorted(self.ranges, key=str)
            self._der = [(s, base, sp.lambdify(base, e, modules="mpmath"))
                         for s, e in self.derived.items()]
            self._cond = [sp.lambdify(self.symbols, c, modules="mpmath")
                          for c in self.conditions]
        return self._cond

    def admissible(self, pt):
        conds = self._compiled()
        try:
            with mpmath.workdps(DPS):
                for c in conds:
                    v = mpmath.mpmathify(c(*[pt[s] for s in self.symbols]))
                    if not (abs(mpmath.im(v)) == 0 and mpmath.re(v) > 0):
                        return False
        except (ZeroDivisionError, ValueError, TypeError, OverflowError):
            return False
        return True

    def complete(self, pt):
        """Fill in the derived symbols of a point (in place) and return it."""
        self._compiled()
        with mpmath.workdps(DPS):
            for s, base, fn in self._der:
                pt[s] = mpmath.mpmathify(fn(*[pt[b] for b in base]))
        return pt

    def sample(self, rng, n=POINTS):
        pts = []
        for _ in range(200 * n):
            pt = {s: mpmath.mpf(rng.uniform(lo, hi)) for s, (lo, hi) in
                  sorted(self.ranges.items(), key=lambda kv: str(kv[0]))}
            self.complete(pt)
            if self.admissible(pt):
                pts.append(pt)
                if len(pts) == n:
                    return pts
        raise RuntimeError("the exercise's domain has too few admissible points")


@dataclass
class Verdict:
    ok: bool
    hint: str = ""


class _Fn:
    """An expression as a function of a point (dict), at DPS digits; None where undefined."""

    def __init__(self, expr, syms):
        self.expr = expr
        self.syms = syms
        try:
            self._f = sp.lambdify(syms, expr, modules="mpmath")
        except Exception:  # noqa: BLE001 - a printer gap: fall back to evalf
            self._f = None

    def __call__(self, pt):
        with mpmath.workdps(DPS):
            try:
                if self._f is not None:
                    v = self._f(*[pt[s] for s in self.syms])
                else:
                    v = sp.N(self.expr.xreplace({s: sp.Float(pt[s], DPS) for s in self.syms}),
                             DPS)
                v = mpmath.mpmathify(complex(v) if isinstance(v, sp.Basic) else v)
            except Exception:  # noqa: BLE001 - undefined at this point
                return None
            if not (mpmath.isfinite(mpmath.re(v)) and mpmath.isfinite(mpmath.im(v))):
                return None
            return mpmath.mpc(v)


def _close(u, v):
    return abs(u - v) <= TOL * max(1, abs(u), abs(v))


def _nice(c):
    """A constant as a short SymPy number if there is one (2, 1/2, sqrt(2)), else rounded."""
    c = complex(c)
    if abs(c.imag) > 1e-12 * max(1.0, abs(c)):
        return f"{c.real:.4g}{c.imag:+.4g}i"
    x = c.real
    for cand in (sp.nsimplify(x, tolerance=1e-12, rational=True),
                 sp.nsimplify(x, [sp.pi], tolerance=1e-12)):
        if abs(float(cand) - x) <= 1e-11 * max(1.0, abs(x)) and sp.count_ops(cand) <= 4 and \
                all(abs(r) <= 100 for r in (cand.as_numer_denom())
                    if r.is_Integer):
            return cand
    return sp.Float(x, 4)


def depends_on(fn, s, p0, pts, domain):
    """Does fn change when only s changes (from p0 to other admissible values)?"""
    v0 = fn(p0)
    tried = 0
    for p in pts[1:]:
        p1 = dict(p0)
        p1[s] = p[s]
        if p1[s] == p0[s] or not domain.admissible(p1):
            continue
        v1 = fn(p1)
        tried += 1
        if v0 is None or v1 is None:
            if (v0 is None) != (v1 is None):
                return True
            continue
        if not _close(v0, v1):
            return True
        if tried >= 2:
            break
    return False


def _monomial(ratio, p0, pts, syms, domain):
    """ratio(p) = c * prod(s**k_s) with half-integer k_s? Return (c, {s: k}) or None."""
    r0 = ratio(p0)
    if r0 is None or abs(r0) < TOL:
        return None
    ks = {}
    with mpmath.workdps(DPS):
        for s in syms:
            if p0[s] == 0:
                continue
            for f in (mpmath.mpf("1.1"), mpmath.mpf("0.9"), mpmath.mpf("1.3"), mpmath.mpf("0.7")):
                p1 = dict(p0)
                p1[s] = p0[s] * f
                if domain.admissible(p1):
                    break
            else:
                continue
            r1 = ratio(p1)
            if r1 is None:
                return None
            q = r1 / r0
            if _close(q, 1):
                continue
            if abs(mpmath.im(q)) > TOL or mpmath.re(q) <= 0:
                return None
            k = mpmath.log(mpmath.re(q)) / mpmath.log(f)
            k2 = mpmath.nint(2 * k) / 2
            if abs(k - k2) > mpmath.mpf(10) ** -8 or k2 == 0:
                return None
            ks[s] = sp.Rational(int(2 * k2), 2)
        if not ks:
            return None

        def mono(p):
            return mpmath.fprod(mpmath.power(p[s], mpmath.mpf(k.p) / k.q) for s, k in ks.items())

        c = r0 / mono(p0)
        for p in pts:
            r = ratio(p)
            if r is None or not _close(r, c * mono(p)):
                return None
    return c, ks


def _monomial_text(c, ks, what="your answer", ref="the right one", verb="is"):
    factor = sp.Mul(*[s**k for s, k in sorted(ks.items(), key=lambda kv: str(kv[0]))])
    cn = _nice(c)
    shown = factor if (isinstance(cn, sp.Basic) and cn == 1) else \
        (-factor if (isinstance(cn, sp.Basic) and cn == -1) else f"{cn}*{factor}")
    notes = []
    for s, k in sorted(ks.items(), key=lambda kv: str(kv[0])):
        if k == -1:
            notes.append(f"a factor {s} is missing (or the power of {s} is one too low)")
        elif k == 1:
            notes.append(f"there is an extra factor {s} (or the power of {s} is one too high)")
        elif k < 0:
            notes.append(f"the power of {s} is too low by {-k}")
        else:
            notes.append(f"the power of {s} is too high by {k}")
    if isinstance(cn, sp.Basic) and cn == -1:
        notes.append("the sign is wrong")
    elif not (isinstance(cn, sp.Basic) and cn == 1):
        notes.append("and a numerical factor is off")
    return f"{what} {verb} {shown} times {ref}: " + ", ".join(notes)


def _power_of(R, B, pts):
    """R(p) = +-B(p)**k for one half-integer k != 0 at every point? Return k or None."""
    ks = []
    with mpmath.workdps(DPS):
        for p in pts:
            r, b = R(p), B(p)
            if r is None or b is None or abs(b) == 0 or abs(r) == 0:
                return None
            lb = mpmath.log(abs(b))
            if abs(lb) < mpmath.mpf("0.05"):
                continue
            ks.append(mpmath.log(abs(r)) / lb)
        if len(ks) < 3:
            return None
        k = mpmath.nint(2 * ks[0]) / 2
        if k == 0 or any(abs(x - k) > mpmath.mpf(10) ** -8 for x in ks):
            return None
        for p in pts:
            r, b = R(p), B(p)
            pw = mpmath.power(b, k)
            if not (_close(r, pw) or _close(r, -pw)):
                return None
    return sp.Rational(int(2 * k), 2)


def _power_text(b, k):
    if k == 1:
        return f"({b})"
    if k == -1:
        return f"1/({b})"
    return f"({b})**({k})"


def _bases(expr):
    out = []
    for f in sp.Mul.make_args(expr):
        b, _ = f.as_base_exp()
        if b.free_symbols and not b.is_Symbol and b not in out:
            out.append(b)
    return out


def _expanded_terms(expr, limit=30):
    if sp.count_ops(expr) >= 400:
        return []
    try:
        terms = sp.Add.make_args(sp.expand(expr))
    except Exception:  # noqa: BLE001
        return []
    return list(terms) if len(terms) <= limit else []


def compare(answer, expected, domain, seed=0, sign_note="", tol=None):
    """Compare two expressions of the domain's symbols: a :class:`Verdict`.

    ``tol``: the relative tolerance of equality (default 1e-10; a measured
    number, such as where an integrator stopped, needs a looser one).
    """
    syms = domain.symbols
    rng = random.Random(seed)
    pts = domain.sample(rng)
    fa, fe = _Fn(answer, syms), _Fn(expected, syms)
    A = [fa(p) for p in pts]
    E = [fe(p) for p in pts]
    keep = [i for i, e in enumerate(E) if e is not None]
    if len(keep) < 3:
        raise RuntimeError(f"the right answer cannot be evaluated on the domain: {expected}")
    pts = [pts[i] for i in keep]
    A = [A[i] for i in keep]
    E = [E[i] for i in keep]
    rel = TOL if tol is None else mpmath.mpf(tol)
    if all(a is not None and abs(a - e) <= rel * max(1, abs(a), abs(e)) for a, e in zip(A, E)):
        return Verdict(True)
    if any(a is None for a in A):
        return Verdict(False, "your answer cannot be evaluated at some admissible values of the "
                       "symbols (a division by zero or a logarithm of zero?), where the right "
                       "answer can")
    real_E = all(abs(mpmath.im(e)) <= TOL * max(1, abs(e)) for e in E)
    if real_E and any(abs(mpmath.im(a)) > TOL * max(1, abs(a)) for a in A):
        return Verdict(False, "your answer takes complex values where the right answer is real: "
                       "check the signs under a square root (or a logarithm)")
    zero_E = all(abs(e) <= TOL for e in E)
    if zero_E:
        deps = [str(s) for s in syms if depends_on(fa, s, pts[0], pts, domain)]
        extra = f"; it depends on {', '.join(deps)}" if deps else ""
        return Verdict(False, f"the right answer is identically 0 and yours is not{extra}")
    if all(abs(a) <= TOL for a in A):
        return Verdict(False, "your answer is 0, and the right one is not")
    p0 = pts[0]
    with mpmath.workdps(DPS):
        R = [a / e if abs(e) > TOL else None for a, e in zip(A, E)]
    Rk = [r for r in R if r is not None]
    note = f": {sign_note}" if sign_note else ""
    if len(Rk) >= 3 and all(_close(r, Rk[0]) for r in Rk):
        c = _nice(Rk[0])
        if isinstance(c, sp.Basic) and c == -1:
            return Verdict(False, f"the sign is wrong (your answer is -1 times the right one)"
                           f"{note}")
        return Verdict(False, f"your answer is off by a constant factor: it is {c} times the "
                       "right one")

    def ratio(p):
        a, e = fa(p), fe(p)
        if a is None or e is None or abs(e) <= TOL:
            return None
        return a / e

    used = [s for s in syms if depends_on(fa, s, p0, pts, domain)
            or depends_on(fe, s, p0, pts, domain)]
    mono = _monomial(ratio, p0, pts, used, domain)
    if mono is not None:
        return Verdict(False, _monomial_text(*mono))
    k = _power_of(fa, fe, pts)
    if k is not None and k != 1:
        return Verdict(False, f"your answer looks like the right expression to the power {k}: "
                       "check the exponent (a square for a square root, or the other way round?)")
    for b in _bases(expected) + [b for b in _bases(answer) if b not in _bases(expected)]:
        k = _power_of(ratio, _Fn(b, syms), pts)
        if k is not None:
            if k == -1:
                what = f"a factor ({b}) is missing, or its power is too low by one"
            elif k == 1:
                what = f"there is an extra factor ({b}), or its power is too high by one"
            else:
                what = f"the power of the factor ({b}) is too {'low' if k < 0 else 'high'} " \
                       f"by {abs(k)}"
            return Verdict(False, f"your answer is {_power_text(b, k)} times the right one, "
                           f"up to sign: {what}")
    hint = _term_hint(answer, expected, fa, fe, syms, pts, domain)
    if hint:
        return Verdict(False, hint)
    with mpmath.workdps(DPS):
        D = [a - e for a, e in zip(A, E)]
    if all(_close(d, D[0]) for d in D):
        return Verdict(False, f"your answer differs from the right one by a constant "
                       f"(yours minus the right one is {_nice(D[0])})")

    def diff(p):
        a, e = fa(p), fe(p)
        return None if a is None or e is None else a - e

    deps = [str(s) for s in used if depends_on(diff, s, p0, pts, domain)]
    msg = "your answer is not equal to the right one"
    if deps:
        msg += f"; the difference depends on {', '.join(deps)}"
    missing = [str(s) for s in used if depends_on(fe, s, p0, pts, domain)
               and not depends_on(fa, s, p0, pts, domain)]
    if missing:
        msg += f"; your answer does not depend on {', '.join(missing)}, the right one does"
    return Verdict(False, msg)


def _subsets(n):
    from itertools import combinations
    sizes = range(1, n) if n <= 8 else range(1, min(3, n))
    for size in sizes:
        yield from combinations(range(n), size)


def _term_hint(answer, expected, fa, fe, syms, pts, domain):
    """Is the difference confined to some terms of the right answer (a sign, a factor)?"""
    decompositions = []
    for terms in (list(sp.Add.make_args(expected)), _expanded_terms(expected)):
        terms = [t for t in terms if t.free_symbols]
        if len(terms) >= 2 and terms not in decompositions:
            decompositions.append(terms)
    with mpmath.workdps(DPS):
        A = [fa(p) for p in pts]
        E = [fe(p) for p in pts]
        for terms in decompositions:
            fts = [_Fn(t, syms) for t in terms]
            vals = [[ft(p) for p in pts] for ft in fts]
            if any(v is None for row in vals for v in row):
                continue
            for subset in _subsets(len(terms)):
                one = len(subset) == 1
                T = [mpmath.fsum(vals[j][i] for j in subset) for i in range(len(pts))]
                if any(abs(t) <= TOL for t in T):
                    continue
                Q = [(a - e + t) / t for a, e, t in zip(A, E, T)]
                if not all(_close(q, Q[0]) for q in Q):
                    continue
                c = _nice(Q[0])
                if isinstance(c, sp.Basic) and c == -1:
                    return "one term has the wrong sign" if one else \
                        f"{len(subset)} terms have the wrong sign"
                if isinstance(c, sp.Basic) and c == 0:
                    return "a term is missing from your answer" if one else \
                        f"{len(subset)} terms are missing from your answer"
                what = "one term of your answer is" if one else \
                    f"{len(subset)} terms of your answer are"
                return f"{what} {c} times what {'it' if one else 'they'} should be"
            for subset in _subsets(len(terms)):
                one = len(subset) == 1
                ft = _Fn(sp.Add(*[terms[j] for j in subset]), syms)

                def q(p, ft=ft):
                    a, e, tt = fa(p), fe(p), ft(p)
                    if a is None or e is None or tt is None or abs(tt) <= TOL:
                        return None
                    return (a - e + tt) / tt
                Q = [q(p) for p in pts]
                if any(v is None for v in Q) or all(_close(v, 1) for v in Q):
                    continue
                what = "one term of your answer" if one else f"{len(subset)} terms of your answer"
                mono = _monomial(q, pts[0], pts, syms, domain)
                if mono is not None:
                    return _monomial_text(*mono, what=what + ("" if one else " together"),
                                          ref="what it should be" if one else
                                          "what they should be", verb="is" if one else "are")
                if one:
                    for b in _bases(terms[subset[0]]):
                        k = _power_of(q, _Fn(b, syms), pts)
                        if k is not None:
                            return (f"one term of your answer is {_power_text(b, k)} times "
                                    "what it "
                                    f"should be, up to sign: check the power of the factor {b} "
                                    "in that term")
        args = sp.Add.make_args(answer)
        if len(args) >= 2:
            for u in args:
                fu = _Fn(u, syms)
                U = [fu(p) for p in pts]
                if all(v is not None for v in U) and all(_close(a - v, e) for a, v, e in
                                                         zip(A, U, E)):
                    return "your answer has an extra term"
    return ""
