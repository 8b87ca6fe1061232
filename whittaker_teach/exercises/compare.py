"""Is an answer equal to the right one, and if not, what kind of difference is it?

Equality is decided on the whole domain the exercise states (a range per
symbol, possibly infinite, and conditions): by evaluation with mpmath at 30
digits at admissible points of three kinds, every range cut into slices with a
point in each (:meth:`Domain.sample`): points of the moderate core of the
ranges and points over the whole domain, both fixed for a part (so that a
wrong answer gets the same hint at every check), and as many points over the
whole domain drawn afresh at every check from the operating system's
randomness (:meth:`Domain.fresh`), so that no answer can be fitted to known
points.  An infinite range is sampled over many decades (10**-3 to 10**3 on
either side of its end, or of 0), a bounded one up to near its ends.  Values
agree within a relative tolerance (1e-10) at every magnitude.  Where the two
expressions are rational functions of bounded size, an exact test decides
(:func:`exact_zero`, ``cancel`` of the difference, never ``simplify``).

The points respect the exercise's assumptions (positive masses, the
direction of travel, an energy above the potential), so any form of the
right answer (``1 + tan(theta)**2`` or ``sec(theta)**2``, expanded or
factored, ``sqrt(a)*sqrt(b)`` or ``sqrt(a*b)``) agrees with it to about 28
digits at every point, and a wrong answer, or one right on only part of the
domain (``sqrt(1 - sin(theta)**2)`` for ``cos(theta)``, ``Min(m, 2)`` for a
mass ``m``), does not.  The evaluation is guarded (:class:`_Fn`): a value
beyond 1e300 (``exp(exp(exp(100)))``) is never computed.

When the answer is wrong, :func:`compare` looks for a simple explanation,
in this order: complex values where the right answer is real, a wrong sign,
a constant factor, a factor that is a power of one or more symbols (a
missing factor, a wrong power), the answer being a power of the right one,
a wrong power of one factor, one term with the wrong sign (everywhere, or on
part of the domain), missing or changed, an extra term, a difference inside
one factor (a square root, a denominator), an additive constant, an answer
right at some points only; otherwise it says which symbols the difference
depends on.  The hints name the kind of difference, not the right answer.

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

import os
import random
from dataclasses import dataclass, field

import mpmath
import sympy as sp
from sympy.functions.elementary.piecewise import ExprCondPair

from .limits import TOO_EXPENSIVE, TooExpensive

__all__ = ["Domain", "Verdict", "compare", "equal", "exact_zero", "depends_on"]

DPS = 30
TOL = mpmath.mpf(10) ** -10   # relative: exact forms agree to ~28 digits, floats to ~15
FLOOR = mpmath.mpf(10) ** -20  # below this, a difference is rounding (a value that is 0)
POINTS = 8


INF = float("inf")
DECADES = 3        # an unbounded range: magnitudes from 10**-DECADES to 10**DECADES
REDRAWS = 40       # draws of a candidate's condition symbols before it is given up
EDGE = 1e-5        # the end slices of a bounded range reach within EDGE * width of its ends


def fresh_rng():
    """A generator seeded from the operating system: new points at every check."""
    try:
        seed = int.from_bytes(os.urandom(16), "big")
    except (NotImplementedError, OSError):  # pragma: no cover - no system randomness
        seed = random.SystemRandom().getrandbits(128)
    return random.Random(seed)


CORE = (mpmath.mpf("0.05"), mpmath.mpf(3))   # the core of a half-line: lo + 0.05 ... lo + 3


def _at(lo, hi, u, n, core=False):
    """The value at u in (0, 1) of the range (lo, hi) (ends may be infinite), mixing scales.

    The map is increasing.  A bounded range is uniform inside and, in its first and
    last 1/n, approaches its ends log-uniformly down to EDGE times its width.  A
    half-line is lo + 10**(-DECADES ... DECADES), and the whole line the same on either
    side of 0, so that a stratified u gives magnitudes over 2 * DECADES decades.
    ``core``: the moderate middle only (a bounded range uniformly, a half-line
    lo + 0.05 ... lo + 3, the line -3 ... 3), where the hints look for the kind of a
    difference.
    """
    u = min(max(u, 1e-12), 1 - 1e-12)
    if core:
        if lo > -INF and hi < INF:
            return mpmath.mpf(lo) + (mpmath.mpf(hi) - mpmath.mpf(lo)) * u
        if lo > -INF:
            return mpmath.mpf(lo) + CORE[0] + (CORE[1] - CORE[0]) * u
        if hi < INF:
            return mpmath.mpf(hi) - CORE[0] - (CORE[1] - CORE[0]) * (1 - u)
        return CORE[1] * (2 * u - 1)
    if lo > -INF and hi < INF:
        lo, hi = mpmath.mpf(lo), mpmath.mpf(hi)
        width = hi - lo
        if u < 1 / n or u > 1 - 1 / n:
            w = u * n if u < 1 / n else (1 - u) * n          # 0 at the end, 1 inside
            a = mpmath.log10(EDGE)
            d = width * mpmath.power(10, a + (mpmath.log10(mpmath.mpf(1) / n) - a) * w)
            return lo + d if u < 1 / n else hi - d
        return lo + width * u
    if lo > -INF:
        return mpmath.mpf(lo) + mpmath.power(10, -DECADES + 2 * DECADES * u)
    if hi < INF:
        return mpmath.mpf(hi) - mpmath.power(10, DECADES - 2 * DECADES * u)
    if u < 0.5:
        return -mpmath.power(10, DECADES - 4 * DECADES * u)
    return mpmath.power(10, -DECADES + 4 * DECADES * (u - 0.5))


@dataclass
class Domain:
    """Where answers are compared: ranges of values and conditions.

    ``ranges``: {symbol: (low, high)}, either end possibly infinite
    (``float("inf")``); ``conditions``: expressions that must be positive at a
    point; ``derived``: {symbol: expression of the others}, evaluated after the
    ranges are sampled (e.g. the energy constant h of a sampled motion).

    Two sets of points serve a check: :meth:`points` of a seed (the same at every
    check of a part, so that a wrong answer gets the same hint every time) and
    :meth:`fresh` ones, drawn anew at every check from the operating system's
    randomness, so that no answer can be fitted to known points.
    """

    ranges: dict
    conditions: tuple = ()
    derived: dict = field(default_factory=dict)

    def __post_init__(self):
        self.symbols = sorted([*self.ranges, *self.derived], key=str)
        for s, (lo, hi) in self.ranges.items():
            if not lo < hi:
                raise ValueError(f"the range of {s} is empty: ({lo}, {hi})")
        self._cond = None
        self._der = None
        self._points = {}

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
                for s, (lo, hi) in self.ranges.items():
                    v = pt[s]
                    if mpmath.im(v) != 0 or not lo <= mpmath.re(v) <= hi:
                        return False
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

    def points(self, seed, n=POINTS, core=False):
        """The n sample points of a seed (kept: every check of a part uses the same);
        ``core``: in the moderate middle of the ranges only (see :func:`_at`)."""
        key = (seed, n, core)
        if key not in self._points:
            self._points[key] = self.sample(random.Random(seed), n, core)
        return [dict(p) for p in self._points[key]]

    def fresh(self, n=POINTS):
        """n points over the whole domain, drawn anew (from the operating system's
        randomness) at every call."""
        return self.sample(fresh_rng(), n)

    def sample(self, rng, n=POINTS, core=False):
        """n admissible points over the whole of every range (Latin hypercube batches).

        Each batch of n candidates takes, for each symbol, one value from each of n
        equal slices of (0, 1), mapped onto the symbol's range by :func:`_at`: a
        bounded range is covered to within a small fraction of its ends, a half-line
        or the whole line over 2 * DECADES decades of magnitude (on both sides of 0),
        so that the points reach the ends of every range instead of clustering by
        chance.
        """
        pts = []
        items = sorted(self.ranges.items(), key=lambda kv: str(kv[0]))
        # the symbols of the conditions (and those the derived ones are made of): a
        # candidate that fails a condition is drawn again in these only, so that the
        # others keep one value in each slice
        tied = set().union(*[c.free_symbols for c in self.conditions], set())
        if self.derived:
            tied |= set().union(*[e.free_symbols for e in self.derived.values()])
        redraw = [(s, lo, hi) for s, (lo, hi) in items if s in tied]
        with mpmath.workdps(DPS):
            for _ in range(200):
                strata = {s: rng.sample(range(n), n) for s, _ in items}
                for i in range(n):
                    pt = {s: +_at(lo, hi, (strata[s][i] + rng.random()) / n, n, core)
                          for s, (lo, hi) in items}
                    for _ in range(REDRAWS if redraw else 0):
                        if self.admissible(self.complete(pt)):
                            break
                        for s, lo, hi in redraw:
                            pt[s] = +_at(lo, hi, rng.random(), n, core)
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
    kind: str = ""          # the kind of difference (GRADED_HINTS), without its quantities

    @property
    def graded_hint(self):
        """The hint for a graded check: the kind of mistake, no quantity that reveals
        the right answer (no factor, constant, point or symbol list)."""
        return GRADED_HINTS.get(self.kind, self.hint)


#: what a graded check says for each kind of difference
GRADED_HINTS = {
    "complex": "your answer takes complex values where the right answer is real",
    "zero-expected": "the right answer is identically 0 and yours is not",
    "zero": "your answer is 0, and the right one is not",
    "part": "your answer is right on part of the domain only",
    "sign": "the sign is wrong",
    "constant-factor": "your answer is off by a constant factor",
    "factor": "your answer is off by a factor: one is missing, extra, or has the wrong power",
    "power": "your answer looks like the right expression to some power: check the exponent",
    "term": "a term of your answer is missing, extra, or wrong",
    "inner": "your answer differs inside one factor (a square root or a denominator)",
    "constant": "your answer differs from the right one by a constant",
    "other": "your answer is not equal to the right one",
}


class _Fn:
    """An expression as a function of a point (dict), at DPS digits; None where undefined.

    The expression is compiled once into a list of steps (equal subexpressions
    shared), evaluated with mpmath and guarded: a step whose value would be
    beyond 1e300 (``exp(exp(exp(100)))``, ``2**(10**9*theta)``) is undefined
    at that point (and ``huge`` is set) instead of being computed, so that no
    evaluation can run away.
    """

    def __init__(self, expr, syms):
        self.expr = expr
        self.syms = list(syms)
        self.huge = False
        self.steps = []
        index = {}
        pos = {s: i for i, s in enumerate(self.syms)}

        def visit(e):
            j = index.get(e)
            if j is not None:
                return j
            if e.is_Symbol:
                step = ("symbol", pos[e]) if e in pos else ("unknown", e)
            elif e.is_Number or e.is_NumberSymbol or e is sp.I:
                with mpmath.workdps(DPS):
                    step = ("const", mpmath.mpmathify(complex(e)) if e.has(sp.I)
                            else mpmath.mpf(e.evalf(DPS + 5)))
            elif e.is_Pow and e.exp.is_Integer and abs(e.exp) <= 1000:
                step = (_int_pow, [visit(e.base)], int(e.exp))
            elif e.is_Pow and e.exp.is_Rational and e.exp.q == 2 and abs(e.exp) <= 1000:
                step = (_half_pow, [visit(e.base)], int(e.exp.p))
            else:
                step = (type(e), [visit(a) for a in e.args], e)
            index[e] = len(self.steps)
            self.steps.append(step)
            return index[e]

        self.out = visit(expr)

    def __call__(self, pt):
        vals = [None] * len(self.steps)
        with mpmath.workdps(DPS):
            try:
                for i, step in enumerate(self.steps):
                    kind = step[0]
                    if kind == "symbol":
                        v = pt[self.syms[step[1]]]
                    elif kind == "const":
                        v = step[1]
                    elif kind == "unknown":
                        return None
                    elif kind is _int_pow or kind is _half_pow:
                        v = kind(vals[step[1][0]], step[2])
                    else:
                        v = _apply(kind, [vals[j] for j in step[1]], step[2])
                    vals[i] = v
            except _Huge:
                self.huge = True
                return None
            except (ZeroDivisionError, ValueError, TypeError, OverflowError, ArithmeticError):
                return None
            v = mpmath.mpmathify(vals[self.out])
            if not (mpmath.isfinite(mpmath.re(v)) and mpmath.isfinite(mpmath.im(v))):
                return None
            if abs(v) > _HUGE:
                self.huge = True
                return None
            return mpmath.mpc(v)


class _Huge(Exception):
    pass


_HUGE = mpmath.mpf(10) ** 300
_EXP_MAX = 690            # exp(690) ~ 1e300


def _exp(z):
    if mpmath.re(z) > _EXP_MAX:
        raise _Huge()
    if mpmath.re(z) < -10**5:
        return mpmath.mpf(0)
    return mpmath.exp(z)


def _pow(b, e):
    if e == int(mpmath.re(e)) and mpmath.im(e) == 0 and abs(e) <= 1000:
        n = int(mpmath.re(e))
        if n < 0 and b == 0:
            raise ZeroDivisionError
        return b ** n
    if e == mpmath.mpf(0.5):
        return mpmath.sqrt(b)
    if b == 0:
        if mpmath.re(e) > 0:
            return mpmath.mpf(0)
        raise ZeroDivisionError
    return _exp(e * mpmath.log(b))


def _int_pow(b, n):
    if n < 0 and b == 0:
        raise ZeroDivisionError
    return b ** n


def _half_pow(b, n):
    """b**(n/2), the principal branch (as SymPy's)."""
    r = mpmath.sqrt(b)
    if n < 0 and r == 0:
        raise ZeroDivisionError
    return r ** n


def _trig(f):
    def g(args, e):
        if abs(args[0]) > 10**8:     # argument reduction would need huge precision
            raise _Huge()
        return f(args[0])
    return g


def _fn1(f):
    return lambda args, e: f(args[0])


def _cosh(z):
    return (_exp(z) + _exp(-z)) / 2


def _sinh(z):
    return (_exp(z) - _exp(-z)) / 2


def _reciprocal(f):
    def g(args, e):
        if abs(args[0]) > 10**8:
            raise _Huge()
        v = f(args[0])
        if v == 0:
            raise ZeroDivisionError
        return 1 / v
    return g


def _log(args, e):
    if args[0] == 0:
        raise ZeroDivisionError
    if len(args) == 2:
        return mpmath.log(args[0]) / mpmath.log(args[1])
    return mpmath.log(args[0])


def _real(z):
    if mpmath.im(z) != 0:
        raise ValueError("complex argument")
    return mpmath.re(z)


_APPLY = {
    sp.Add: lambda args, e: mpmath.fsum(args),
    sp.Mul: lambda args, e: mpmath.fprod(args),
    sp.Pow: lambda args, e: _pow(*args),
    sp.exp: _fn1(_exp), sp.log: _log,
    sp.sin: _trig(mpmath.sin), sp.cos: _trig(mpmath.cos), sp.tan: _trig(mpmath.tan),
    sp.sec: _reciprocal(mpmath.cos), sp.csc: _reciprocal(mpmath.sin),
    sp.cot: _reciprocal(mpmath.tan),
    sp.asin: _fn1(mpmath.asin), sp.acos: _fn1(mpmath.acos), sp.atan: _fn1(mpmath.atan),
    sp.atan2: lambda args, e: mpmath.atan2(_real(args[0]), _real(args[1])),
    sp.sinh: _fn1(_sinh), sp.cosh: _fn1(_cosh), sp.tanh: _trig(mpmath.tanh),
    sp.Abs: _fn1(abs), sp.sign: _fn1(mpmath.sign),
    sp.re: _fn1(mpmath.re), sp.im: _fn1(mpmath.im),
    # the forms a library or a student may hand over for a right answer
    sp.UnevaluatedExpr: lambda args, e: args[0],
    sp.Max: lambda args, e: max(_real(a) for a in args),
    sp.Min: lambda args, e: min(_real(a) for a in args),
    sp.Piecewise: lambda args, e: next(v for v, c in args if c),
    ExprCondPair: lambda args, e: (args[0], bool(args[1])),
    sp.StrictLessThan: lambda args, e: _real(args[0]) < _real(args[1]),
    sp.LessThan: lambda args, e: _real(args[0]) <= _real(args[1]),
    sp.StrictGreaterThan: lambda args, e: _real(args[0]) > _real(args[1]),
    sp.GreaterThan: lambda args, e: _real(args[0]) >= _real(args[1]),
    sp.And: lambda args, e: all(args), sp.Or: lambda args, e: any(args),
    sp.Not: lambda args, e: not args[0],
    type(sp.true): lambda args, e: True, type(sp.false): lambda args, e: False,
}


def _apply(kind, args, e):
    f = _APPLY.get(kind)
    if f is not None:
        return f(args, e)
    # a function without a rule here (from a library result): SymPy at these values
    if isinstance(e, sp.Function) and len(args) <= 3:
        v = e.func(*[sp.Float(a, DPS) if mpmath.im(a) == 0 else
                     sp.Float(mpmath.re(a), DPS) + sp.I * sp.Float(mpmath.im(a), DPS)
                     for a in args]).evalf(DPS)
        return mpmath.mpmathify(complex(v))
    raise ValueError(f"cannot evaluate {kind.__name__}")


def _same(u, v, rel=TOL):
    """|u - v| <= rel max(|u|, |v|), relative at every magnitude (FLOOR: the noise of 0)."""
    return abs(u - v) <= rel * max(abs(u), abs(v)) + FLOOR


def _close(u, v):
    return _same(u, v)


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


def depends_on(fn, s, p0, pts, domain, most=2):
    """Does fn change when only s changes (from p0 to the values of s at ``most`` other
    points, ``None``: all of them)?"""
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
        if most is not None and tried >= most:
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


_COMPILED = {}


def _compiled(expr, syms):
    """_Fn of a right answer, compiled once (answers are compiled at each check)."""
    key = (expr, tuple(syms))
    if key not in _COMPILED:
        if len(_COMPILED) > 500:
            _COMPILED.clear()
        _COMPILED[key] = _Fn(expr, syms)
    return _COMPILED[key]


def equal(answer, expected, domain, seed=0, tol=None, fresh=True):
    """Is answer equal to expected on the domain (no hint)?

    At the seed's points and, with ``fresh``, at points drawn anew; an exact zero
    test of the difference decides first where it is affordable (:func:`exact_zero`).
    """
    exact = exact_zero(answer, expected, domain)
    if exact is not None:
        return exact
    syms = domain.symbols
    fa, fe = _Fn(answer, syms), _compiled(expected, syms)
    rel = TOL if tol is None else mpmath.mpf(tol)
    n = 0
    for p in domain.points(seed, core=True) + domain.points(seed) + \
            (domain.fresh() if fresh else []):
        e = fe(p)
        if e is None:
            continue
        a = fa(p)
        if a is None or not _same(a, e, rel):
            return False
        n += 1
    return n >= 3


def compare(answer, expected, domain, seed=0, sign_note="", tol=None, fresh=True):
    """Compare two expressions of the domain's symbols: a :class:`Verdict`.

    Equal means equal at the seed's points (:meth:`Domain.points`, the same at every
    check) and at as many points drawn anew for this check (:meth:`Domain.fresh`,
    unless ``fresh`` is False), within the relative tolerance ``tol`` (default 1e-10;
    a measured number, such as where an integrator stopped, needs a looser one) at
    every magnitude.  Where the two are rational functions of the symbols (or of the
    same functions of them) of bounded size, :func:`exact_zero` decides exactly.
    A wrong answer's hint is read off the seed's points, so that it is the same at
    every check, unless only fresh points show the difference: then they are used too.
    """
    syms = domain.symbols
    exact = exact_zero(answer, expected, domain)
    if exact:
        return Verdict(True)
    fa, fe = _Fn(answer, syms), _compiled(expected, syms)
    rel = TOL if tol is None else mpmath.mpf(tol)

    def values(points):
        keep = [(p, fe(p)) for p in points]
        keep = [(p, e) for p, e in keep if e is not None]
        return [p for p, _ in keep], [fa(p) for p, _ in keep], [e for _, e in keep]

    pts, A, E = values(domain.points(seed, core=True))
    if len(pts) < 3:
        raise RuntimeError(f"the right answer cannot be evaluated on the domain: {expected}")

    def agree(a, e):
        return a is not None and _same(a, e, rel)

    if all(agree(a, e) for a, e in zip(A, E)):
        # the part's points over the whole domain; only if they see no difference, fresh ones
        # (so that a hint depends on the fresh points only when nothing else shows it)
        more, MA, ME = values(domain.points(seed))
        bad = [i for i, (a, e) in enumerate(zip(MA, ME)) if not agree(a, e)]
        if not bad and fresh:
            more, MA, ME = values(domain.fresh())
            bad = [i for i, (a, e) in enumerate(zip(MA, ME)) if not agree(a, e)]
        if not bad:
            if exact is False:
                return Verdict(False, "your answer is not equal to the right one: the "
                               "difference is too small to see in the numbers, but it is "
                               "not 0", "other")
            return Verdict(True)
        pts = pts + [more[i] for i in bad]
        A = A + [MA[i] for i in bad]
        E = E + [ME[i] for i in bad]
    if fa.huge:
        return Verdict(False, "your answer takes values beyond 1e300 at some admissible values "
                       f"of the symbols, where the right one does not: {TOO_EXPENSIVE}")
    try:
        return _explain(answer, expected, domain, sign_note, fa, fe, pts, A, E)
    except TooExpensive:
        return Verdict(False, "your answer is not equal to the right one (finding what kind of "
                       "difference it is took too long)")


#: the bounds of the exact test: nodes of each expression, |n| of an integer power,
#: terms of the expanded difference (an upper estimate, computed before expanding)
EXACT_NODES = 300
EXACT_POWER = 12
EXACT_TERMS = 3000


def _as_rational(e, gens):
    """e as a rational function of symbols and generators (other subexpressions, each
    replaced by one dummy symbol): the expression, or None beyond the bounds/with a Float."""
    if e.is_Symbol or e.is_Rational:
        return e
    if e.is_Float:
        return None
    if e.is_Add or e.is_Mul:
        args = [_as_rational(a, gens) for a in e.args]
        return None if any(a is None for a in args) else e.func(*args)
    if e.is_Pow and e.exp.is_Integer:
        if abs(e.exp) > EXACT_POWER:
            return None
        b = _as_rational(e.base, gens)
        return None if b is None else b ** e.exp
    if e.has(sp.Float):
        return None
    if e not in gens:
        gens[e] = sp.Dummy()
    return gens[e]


def _terms(e):
    """An upper estimate of the number of terms of e expanded (over a common denominator)."""
    if e.is_Add:
        return sum(_terms(a) for a in e.args)
    if e.is_Mul:
        n = 1
        for a in e.args:
            n *= _terms(a)
            if n > EXACT_TERMS:
                return n
        return n
    if e.is_Pow and e.exp.is_Integer:
        from math import comb
        t = _terms(e.base)
        return comb(t + abs(int(e.exp)) - 1, abs(int(e.exp))) if t <= EXACT_TERMS else t
    return 1


def exact_zero(answer, expected, domain):
    """An exact test of answer == expected, where it is affordable: True (the difference
    is 0 as a rational function of the symbols and of the functions in it), False (it is
    a rational function of the symbols alone that is not 0, so it is not 0 on any open
    set of the domain), or None (not decided: bounds exceeded, Floats, or functions).

    Bounded: at most EXACT_NODES nodes each, integer powers up to EXACT_POWER, and an
    estimated EXACT_TERMS terms once expanded; ``cancel`` of the difference, never
    ``simplify``.

    >>> x, y = sp.symbols("x y")
    >>> dom = Domain({x: (0, INF), y: (-INF, INF)})
    >>> exact_zero((x + y)**2 / (x + y), x + y, dom), exact_zero(x + y + x**2 / 10**40, x + y, dom)
    (True, False)
    >>> exact_zero(sp.sqrt(x**2), x, dom) is None
    True
    """
    if domain.derived or not isinstance(answer, sp.Expr) or not isinstance(expected, sp.Expr):
        return None
    if not (answer.free_symbols | expected.free_symbols) <= set(domain.symbols):
        return None
    for e in (answer, expected):
        if sum(1 for _ in zip(range(EXACT_NODES + 1), sp.preorder_traversal(e))) > EXACT_NODES:
            return None
    gens = {}
    a, b = _as_rational(answer, gens), _as_rational(expected, gens)
    if a is None or b is None:
        return None
    diff = a - b
    if _terms(diff) > EXACT_TERMS:
        return None
    if sp.cancel(sp.together(diff)) == 0:
        return True
    return False if not gens else None


def _explain(answer, expected, domain, sign_note, fa, fe, pts, A, E):
    """The kind of difference between a wrong answer and the right one: a Verdict."""
    syms = domain.symbols
    if any(a is None for a in A):
        return Verdict(False, "your answer cannot be evaluated at some admissible values of the "
                       "symbols (a division by zero or a logarithm of zero?), where the right "
                       "answer can")
    real_E = all(abs(mpmath.im(e)) <= TOL * max(1, abs(e)) for e in E)
    if real_E and any(abs(mpmath.im(a)) > TOL * max(1, abs(a)) for a in A):
        inner = (_inner_hint(answer, expected, fa, fe, syms, pts, domain)
                 or _argument_hint(answer, expected, fa, syms, pts))
        if inner:         # a power or a factor changed under a root: say that, not "signs"
            return Verdict(False, inner + " (so your answer takes complex values where the "
                           "right answer is real)", "inner")
        return Verdict(False, "your answer takes complex values where the right answer is real: "
                       "check the signs under a square root (or a logarithm)", "complex")
    zero_E = all(abs(e) <= TOL for e in E)
    if zero_E:
        deps = [str(s) for s in syms if depends_on(fa, s, pts[0], pts, domain)]
        extra = f"; it depends on {', '.join(deps)}" if deps else ""
        return Verdict(False, f"the right answer is identically 0 and yours is not{extra}",
                       "zero-expected")
    if all(abs(a) <= TOL for a in A):
        return Verdict(False, "your answer is 0, and the right one is not", "zero")
    part = _part_of_domain(answer, A, E, pts)       # cheap, and the most useful then
    if part:
        return Verdict(False, part, "part")
    p0 = pts[0]
    with mpmath.workdps(DPS):
        R = [a / e if abs(e) > TOL else None for a, e in zip(A, E)]
    Rk = [r for r in R if r is not None]
    note = f": {sign_note}" if sign_note else ""
    if len(Rk) >= 3 and all(_close(r, Rk[0]) for r in Rk):
        c = _nice(Rk[0])
        if isinstance(c, sp.Basic) and c == -1:
            return Verdict(False, f"the sign is wrong (your answer is -1 times the right one)"
                           f"{note}", "sign")
        return Verdict(False, f"your answer is off by a constant factor: it is {c} times the "
                       "right one", "constant-factor")

    def ratio(p):
        a, e = fa(p), fe(p)
        if a is None or e is None or abs(e) <= TOL:
            return None
        return a / e

    used = [s for s in syms if depends_on(fa, s, p0, pts, domain)
            or depends_on(fe, s, p0, pts, domain)]
    mono = _monomial(ratio, p0, pts, used, domain)
    if mono is not None:
        return Verdict(False, _monomial_text(*mono), "factor")
    k = _power_of(fa, fe, pts)
    if k is not None and k != 1:
        return Verdict(False, f"your answer looks like the right expression to the power {k}: "
                       "check the exponent (a square for a square root, or the other way round?)",
                       "power")
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
                           f"up to sign: {what}", "factor")
    hint = _term_hint(answer, expected, fa, fe, syms, pts, domain)
    if hint:
        return Verdict(False, hint, "term")
    hint = _inner_hint(answer, expected, fa, fe, syms, pts, domain)
    if hint:
        return Verdict(False, hint, "inner")
    with mpmath.workdps(DPS):
        D = [a - e for a, e in zip(A, E)]
    if all(_close(d, D[0]) for d in D):
        return Verdict(False, f"your answer differs from the right one by a constant "
                       f"(yours minus the right one is {_nice(D[0])})", "constant")

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
    return Verdict(False, msg, "other")


def _argument_hint(answer, expected, fa, syms, pts, limit=20):
    """Is the answer the right one with the argument of one function changed?"""
    mine = [f for f in answer.atoms(sp.Function) if len(f.args) == 1]
    right = [f for f in expected.atoms(sp.Function) if len(f.args) == 1]
    tried = 0
    for r in right:
        for m in mine:
            if m.func is not r.func or m == r:
                continue
            tried += 1
            if tried > limit:
                return ""
            fc = _Fn(expected.xreplace({r: m}), syms)
            if all(_close(fc(p), a) for p, a in zip(pts, (fa(p) for p in pts))
                   if fc(p) is not None):
                return (f"the rest is right, but the argument of {r.func.__name__}(...) is "
                        "not the right one")
    return ""


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
                if one and not all(_close(q, Q[0]) for q in Q):
                    flip = _sign_flip(Q, pts, terms[subset[0]])
                    if flip:
                        return flip
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
                if len(subset) > 4:          # up to four terms: the rest is too costly
                    continue
                one = len(subset) == 1
                T = [mpmath.fsum(vals[j][i] for j in subset) for i in range(len(pts))]
                if any(abs(t) <= TOL for t in T):
                    continue
                Q = [(a - e + t) / t for a, e, t in zip(A, E, T)]
                if all(_close(v, 1) for v in Q):
                    continue
                ft = _Fn(sp.Add(*[terms[j] for j in subset]), syms)

                def q(p, ft=ft):
                    a, e, tt = fa(p), fe(p), ft(p)
                    if a is None or e is None or tt is None or abs(tt) <= TOL:
                        return None
                    return (a - e + tt) / tt
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


def _where(k):
    if k == sp.Rational(1, 2):
        return "inside the square root"
    if k == -sp.Rational(1, 2):
        return "inside the square root in the denominator"
    if k == -1:
        return "in the denominator"
    if k == 1:
        return "in the factor"
    return f"inside the factor raised to the power {k}"


def _factors(expr):
    """[(base, exponent)] of the factors of expr whose base is a sum (not expr itself).

    A root of a quotient counts as the roots of its parts (review C, item 10: a slip
    inside ``sqrt(N/D)`` is named as one inside ``sqrt(N)/sqrt(D)`` is); which factor
    differs is then decided numerically, so splitting the root assumes nothing.

    >>> x, y = sp.symbols("x y")
    >>> sorted(_factors(sp.sqrt((x + 1)/(y + 2))), key=str)
    [(x + 1, 1/2), (y + 2, -1/2)]
    """
    out = []
    for form in (expr, sp.expand_power_base(expr, force=True)):
        factors = sp.Mul.make_args(form)
        for f in factors:
            b, k = f.as_base_exp()
            while isinstance(b, sp.Pow) and b.exp.is_Rational and k.is_Rational:
                b, k = b.base, k * b.exp
            if k == 1 and len(factors) == 1:
                continue
            if isinstance(b, sp.Add) and b.free_symbols and k.is_Rational and (b, k) not in out:
                out.append((b, k))
    return out


def _inner_hint(answer, expected, fa, fe, syms, pts, domain):
    """Is the difference inside one factor (a square root, a denominator)? Say what it is there.

    Looks for a factor (a sum under a power: sqrt(...), 1/(...)) of the
    answer and one of the right answer, with the same power, such that the
    answer is the right one with that factor replaced; then explains the
    difference between the two sums (a wrong power of a symbol in a term, a
    term with the wrong sign, a missing term).
    """
    mine, right = _factors(answer), _factors(expected)
    with mpmath.workdps(DPS):
        for bb, kb in mine:
            for be, ke in right:
                if kb != ke or bb == be:
                    continue
                fb, fbe = _Fn(bb, syms), _Fn(be, syms)
                ok = True
                for p in pts:
                    a, e, u, w = fa(p), fe(p), fb(p), fbe(p)
                    if None in (a, e, u, w) or abs(w) <= TOL or abs(e) <= TOL:
                        ok = False
                        break
                    # compared to the power q (k = p/q): a root's branch (sqrt(N/D)
                    # against sqrt(N)/sqrt(D) where D < 0) changes only a q-th root of 1
                    if not _close((a / e) ** ke.q, _pow(u / w, mpmath.mpf(ke.p))):
                        ok = False
                        break
                if not ok:
                    continue
                where = f"{_where(ke)} ({_shorten(bb)})"
                inner = _term_hint(bb, be, fb, fbe, syms, pts, domain)
                if not inner:
                    def ratio(p, fb=fb, fbe=fbe):
                        u, w = fb(p), fbe(p)
                        return None if u is None or w is None or abs(w) <= TOL else u / w
                    mono = _monomial(ratio, pts[0], pts, syms, domain)
                    if mono is not None:
                        inner = _monomial_text(*mono, what="that sum", ref="the right one")
                if not inner:
                    used = [str(s) for s in syms
                            if depends_on(lambda p: _diff(fb, fbe, p), s, pts[0], pts, domain)]
                    inner = "that sum is not the right one" + \
                        (f"; the difference depends on {', '.join(used)}" if used else "")
                inner = inner.replace("your answer", "that sum")
                return f"the rest is right, but {where}: {inner}"
    return ""


def _diff(f, g, p):
    a, b = f(p), g(p)
    return None if a is None or b is None else a - b


def _shorten(e, n=60):
    text = sp.sstr(e)
    return text if len(text) <= n else text[:n - 3] + "..."


def _sign_flip(Q, pts, term):
    """One term right at some points and of the wrong sign at others: say where."""
    plus = [i for i, q in enumerate(Q) if _close(q, 1)]
    minus = [i for i, q in enumerate(Q) if _close(q, -1)]
    if not plus or not minus or len(plus) + len(minus) != len(Q):
        return ""
    p = pts[minus[0]]
    at = ", ".join(f"{s} = {float(mpmath.re(p[s])):.3g}"
                   for s in sorted(term.free_symbols, key=str) if s in p)
    return ("one term of your answer has the right size but the wrong sign on part of the "
            f"domain (for example at {at}), and is right elsewhere: check a root of a square "
            "(sqrt(x**2) is |x|, sqrt(1 - sin(x)**2) is |cos(x)|) or the branch of an inverse "
            "function (asin(sin(x)) is x only for |x| <= pi/2)")


def _part_of_domain(answer, A, E, pts):
    """Right at some sample points, wrong at others: say so, with a point where it is wrong,
    and what to look at (cases, a root or an inverse function, or a term that is small
    at moderate values only)."""
    right = [i for i, (a, e) in enumerate(zip(A, E)) if _close(a, e)]
    if not right or len(right) == len(A):
        return ""
    wrong = [i for i in range(len(A)) if i not in right][0]
    p = pts[wrong]
    cases = set()
    for f in answer.atoms(sp.Max, sp.Min, sp.Piecewise, sp.Heaviside):
        cases |= f.free_symbols
    branchy = set()
    for f in answer.atoms(sp.Abs, sp.sign, sp.asin, sp.acos, sp.atan, sp.Pow):
        if not f.is_Pow or (f.exp.is_Rational and not f.exp.is_Integer):
            branchy |= f.free_symbols
    shown = sorted(cases, key=str) + sorted(branchy - cases, key=str)
    shown = (shown or sorted(answer.free_symbols, key=str))[:5]
    at = ", ".join(f"{s} = {float(mpmath.re(p[s])):.3g}" for s in shown if s in p)
    if cases:
        advice = ("check the cases of your answer (Max, Min, Piecewise, Heaviside): the formula "
                 "must hold on the whole domain")
    elif branchy:
        advice = ("check a root of a square (sqrt(x**2) is |x|) or the branch of an inverse "
                 "function (asin(sin(x)) is x only for |x| <= pi/2)")
    else:
        advice = ("a term or factor that is negligible at moderate values of the symbols is not "
                 "at others (try large and small values)")
    return ("your answer is right at some admissible values and wrong at others (for example "
            f"at {at}): it holds on only part of the domain the exercise states; {advice}")
