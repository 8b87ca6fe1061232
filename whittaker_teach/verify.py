"""Checking the identities the paper claims, for the system at hand.

An identity ``lhs = rhs`` is first tried exactly, by a cheap targeted
rewrite (the difference is identically zero as built, or ``expand`` makes it
zero), and otherwise by evaluating both sides in high precision (mpmath, 40
significant digits) at random admissible points.  A :class:`Check` records
which method decided, at how many points, and the largest relative residual,
so that a reader sees how each claim was shown.

>>> import sympy as sp
>>> x = sp.Symbol("x", positive=True)
>>> check_identity("demo", "sec^2 = 1 + tan^2", 1/sp.cos(x)**2, 1 + sp.tan(x)**2,
...                sample=lambda rng: {x: rng.uniform(0.1, 1.2)})
Check('demo', holds=True, method='numeric', points=6, max_residual<1e-30)
"""

from __future__ import annotations

import cmath
import random
from dataclasses import dataclass, field

import mpmath
import sympy as sp
from mpmath import libmp
from mpmath.libmp import (ComplexResult, mpf_add, mpf_mul, mpf_pow_int, mpf_sqrt, mpf_sum,
                          normalize)

from .canonical import sub
from .dag import expanded_terms, substitute, tree_size
from .polywalk import vanishes

__all__ = ["Check", "check_identity", "check_zero", "evaluate", "At", "value_at", "values_at", "within_size", "largest_value",
           "shared_points", "DPS", "TOLERANCE"]

#: Working precision (decimal digits) of the numeric checks.
DPS = 40
#: Largest relative residual accepted by a numeric check.
TOLERANCE = 1e-25
#: Number of random admissible points of a numeric check.
POINTS = 6
#: Above this number of nodes (``tree_size``), the exact attempt is skipped: it
#: would cost more than the numeric check.
EXACT_SIZE_LIMIT = 450
#: ... and so is an ``expand`` estimated to produce more terms than this.
EXACT_TERMS_LIMIT = 200
#: Sides with nodes that stand for larger expressions (``check_identity``'s
#: ``definitions``) are rebuilt with them for an exact attempt only when the sides and
#: the definitions together have at most this many nodes: above it, the rebuilt sides
#: would be well over ``EXACT_SIZE_LIMIT`` (and rebuilding a large sum costs more
#: than checking it numerically).
SUBSTITUTE_LIMIT = 4 * EXACT_SIZE_LIMIT


@dataclass(frozen=True)
class Check:
    """The outcome of checking one identity.

    ``holds`` is True or False when the check decided, None when it could not
    (for example no point could be evaluated); ``method`` is ``"exact"`` or
    ``"numeric"``; ``detail`` says which rewrite or which precision was used.
    """

    label: str
    claim: str
    holds: bool | None
    method: str
    detail: str
    points: int = 0
    max_residual: float = 0.0
    #: the expressions compared, ``lhs[i] == rhs[i]``, and the sampler of the points:
    #: what was checked, so that a display can be compared with it
    lhs: tuple = field(default=(), repr=False, compare=False)
    rhs: tuple = field(default=(), repr=False, compare=False)
    sample: object = field(default=None, repr=False, compare=False)
    #: {node: its definition}: a node of ``lhs`` or ``rhs`` (such as an unevaluated
    #: d/dx) that was evaluated as the expression it stands for (empty: none)
    definitions: dict = field(default_factory=dict, repr=False, compare=False)
    #: {symbol: expression}: the sides were evaluated with each symbol replaced by its
    #: expression (``check_identity``'s ``at``; empty: none)
    at: dict = field(default_factory=dict, repr=False, compare=False)

    @property
    def status(self) -> str:
        """``"verified"``, ``"FAILED"`` or ``"not verified"``."""
        return {True: "verified", False: "FAILED", None: "not verified"}[self.holds]

    def describe(self) -> str:
        """One line: the claim, whether it held, and how it was shown.

        >>> Check("1.9", "dOmega/dq = dL~/dq", True, "exact", "expand").describe()
        '(1.9) dOmega/dq = dL~/dq: verified exactly (expand)'
        """
        from .labels import shown_label
        from .render import text_unicode     # the claim's $...$ maths as Unicode
        head = f"{shown_label(self.label)} {text_unicode(self.claim)}: {self.status}"
        if self.method == "exact":
            return f"{head} exactly ({self.detail})"
        if self.method == "numeric":
            return (f"{head} numerically at {self.points} random admissible points, "
                    f"{self.detail}, largest relative residual {self.max_residual:.1e}")
        return f"{head} ({self.detail})"

    def __repr__(self) -> str:
        res = "" if self.method != "numeric" else (
            ", max_residual<1e-30" if self.max_residual < 1e-30
            else f", max_residual={self.max_residual:.1e}")
        pts = f", points={self.points}" if self.method == "numeric" else ""
        return f"Check({self.label!r}, holds={self.holds}, method={self.method!r}{pts}{res})"


def _as_list(x):
    return list(x) if isinstance(x, (list, tuple)) else [x]


def within_size(exprs, limit):
    """Whether the tree sizes of ``exprs`` add up to at most ``limit`` (each counted only
    that far: the cost stays bounded on large expressions).

    >>> x = sp.Symbol("x")
    >>> within_size([x + 1, sp.sin(x)], 5), within_size([x + 1, sp.sin(x)], 4)
    (True, False)
    """
    total = 0
    for e in exprs:
        total += tree_size(e, limit)
        if total > limit:
            return False
    return True


def _exactly_zero(diff):
    """Return the name of the rewrite that shows ``diff == 0``, or None."""
    if diff == 0:
        return "identical as built"
    if (tree_size(diff, EXACT_SIZE_LIMIT) > EXACT_SIZE_LIMIT
            or expanded_terms(diff, EXACT_TERMS_LIMIT) > EXACT_TERMS_LIMIT):
        return None
    if vanishes(diff):
        return "common denominator"
    if sp.expand(diff) == 0:
        return "expand"
    return None


def _exact_ways(lhs, rhs):
    """The rewrite that shows each ``lhs[i] == rhs[i]``, or None as soon as one pair is
    not shown exactly.  Before any ``expand``, each pair is screened
    (:func:`expand_may_equal`, then :func:`expand_may_vanish` on the difference): one
    that ``expand`` cannot make zero spares every attempt, and a pair screened out
    spares building the differences; then the smallest differences are tried first.
    A pair whose sides are equal as built is "identical as built" without a screen."""
    pairs = [(a, b) for a, b in zip(lhs, rhs)
             if not (a is b or (hash(a) == hash(b) and a == b))]     # hashes are kept
    same = ["identical as built"] * (len(lhs) - len(pairs))
    if not pairs:
        return same
    lhs, rhs = [a for a, _ in pairs], [b for _, b in pairs]
    if not all(expand_may_equal(a, b) for a, b in zip(lhs, rhs)):
        return None                    # before building any difference of large sides
    if any(_difference_above(a, b, EXACT_SIZE_LIMIT) for a, b in zip(lhs, rhs)):
        return None                    # a difference too large for an attempt: not built
    diffs = [sub(a, b) for a, b in zip(lhs, rhs)]
    if not all(expand_may_vanish(d) for d in diffs):
        return None
    diffs.sort(key=lambda d: tree_size(d, EXACT_SIZE_LIMIT))
    ways = []
    for d in diffs:
        way = _exactly_zero(d)
        if not way:
            return None
        ways.append(way)
    return same + ways


def _difference_above(a, b, limit):
    """Whether ``a - b`` as SymPy builds it certainly has more than ``limit`` nodes,
    decided without building it: the terms that remain once equal terms are merged
    (coefficients added, as ``Add`` does) have more nodes than that, apart from their
    coefficients.  False when unsure (the difference is then built and measured)."""
    terms = {}
    for sign, side in ((1, a), (-1, b)):
        for t in sp.Add.make_args(side):
            if not isinstance(t, sp.Expr):
                return False
            c, rest = t.as_coeff_Mul()
            terms[rest] = terms.get(rest, 0) + sign * c
    size = 0
    for rest, c in terms.items():
        if c != 0:
            size += tree_size(rest, limit)
            if size > limit:
                return True
    return False


# ----------------------------------------------------------------- screening
# What ``expand`` can prove is a polynomial identity in its atoms: it multiplies out
# sums and integer powers, and splits a root of a sum, X**(3/2) = X*sqrt(X), but it never
# puts fractions over a common denominator (a/(a + b) + b/(a + b) stays two terms) and
# knows nothing of tan**2 + 1 = 1/cos**2.  So the value of a difference at a point where
# every such atom (a function such as tan, the inverse or the root of a sum) takes an
# independent random value, in double precision, predicts expand's outcome: a value far
# from zero there means ``expand`` cannot give zero, and its attempt (often the dearest
# part of a check) is skipped.  Equal atoms, even written differently, get the same value
# (each atom's value is keyed by the values of its arguments).  The screen decides only
# whether to *try* ``expand``; a check skipped by it is decided numerically at 40 digits.
# It is a prediction, not a proof: where ``expand`` multiplies out a product and so
# merges two powers of the same sum into another kind of atom (sqrt(X) * sqrt(X) -> X,
# sqrt(X) * (1/X) -> X**(-1/2)), the atoms disagree and an attempt that would have
# succeeded is skipped.  On the examples (both directions) and the scale families
# n = 3..5 it skipped 207 of 246 failing attempts (0.63 s of 0.64 s) and 8 of 551
# succeeding ones, which are then verified numerically instead of exactly.

#: a screened value below this, relative to the size of its terms, may be zero
SCREEN_TOLERANCE = 1e-8
_SCREEN_VALUES = {}
_SCREEN_ATOMS = {}
_MEMO_LIMIT = 50_000           # entries kept by the screen's and the numeric memos
_SCREEN_FUNCTIONS = {"exp": cmath.exp, "log": cmath.log}    # what expand rewrites: kept


def _key(c):
    """A value to 9 digits, relative to its modulus (so that -0.0, +0.0 and a round-off
    imaginary part of 1e-17 give the same key)."""
    r = abs(c)
    if r == 0:
        return "0"
    return format(r, ".9e"), round(c.real / r, 9) + 0.0, round(c.imag / r, 9) + 0.0


def _atom(key):
    """The random value of one atom, the same for the same key in every run."""
    w = _SCREEN_ATOMS.get(key)
    if w is None:
        rng = random.Random(repr(key))
        w = _SCREEN_ATOMS[key] = complex(rng.uniform(0.5, 2.0) * rng.choice((-1, 1)))
    return w


def _screen(e):
    """(value, size) of ``e`` at the screening point: size bounds the terms' magnitudes."""
    r = _SCREEN_VALUES.get(e)
    if r is not None:
        return r
    if e.is_Add or e.is_Mul:
        vals = [_screen(a) for a in e.args]
        v, m = (0, 0) if e.is_Add else (1, 1)
        for va, ma in vals:
            v, m = (v + va, m + ma) if e.is_Add else (v * va, m * ma)
        r = v, m
    elif e.is_Pow and e.exp.is_Rational and e.base.is_Add and not e.exp.is_Integer:
        p, q = int(e.exp.p), int(e.exp.q)       # X**(p/q) = X**(p // q) * (X**(1/q))**r
        vb = _screen(e.base)[0]
        root = _atom(("root", q, _key(vb)))
        w = root ** p if p < 0 else vb ** (p // q) * root ** (p % q)
        r = w, abs(w)
    elif e.is_Pow and e.exp.is_Integer and e.exp < 0 and e.base.is_Add:
        w = _atom(("inverse", _key(_screen(e.base)[0]))) ** int(-e.exp)
        r = w, abs(w)
    elif e.is_Pow:
        (vb, mb), (vx, _) = _screen(e.base), _screen(e.exp)
        w = vb ** (int(e.exp) if e.exp.is_Integer else vx)
        r = w, (mb ** int(e.exp) if e.exp.is_Integer and e.exp > 0 else abs(w))
    elif e.is_Symbol:
        u = _atom(("symbol", e.name)).real
        u = abs(u) if e.is_nonnegative else -abs(u) if e.is_nonpositive else u
        r = complex(u), abs(u)
    elif e.is_Rational:
        r = complex(e.p / e.q), abs(e.p / e.q)
    elif e.is_number and not e.args:
        r = complex(e), abs(complex(e))
    elif isinstance(e, sp.Function) and e.func.__name__ in _SCREEN_FUNCTIONS:
        w = _SCREEN_FUNCTIONS[e.func.__name__](*[_screen(a)[0] for a in e.args])
        r = w, abs(w)
    else:                       # tan(theta), theta(x), Abs(...): an independent atom
        w = _atom((type(e).__name__,) + tuple(_key(_screen(a)[0]) for a in e.args))
        r = w, abs(w)
    _SCREEN_VALUES[e] = r
    return r


def expand_may_vanish(diff):
    """False when ``expand(diff)`` cannot be 0 (see the comment above); True otherwise,
    or when the screen cannot tell (a pole or an overflow at its point).

    >>> a, b, t = sp.symbols("a b theta")
    >>> expand_may_vanish((a + b)**2 - a**2 - 2*a*b - b**2)
    True
    >>> expand_may_vanish(a/(a + b) + b/(a + b) - 1), expand_may_vanish(sp.tan(t)**2 + 1 - 1/sp.cos(t)**2)
    (False, False)
    """
    if len(_SCREEN_VALUES) > _MEMO_LIMIT:
        _SCREEN_VALUES.clear()
    try:
        v, m = _screen(diff)
    except (ZeroDivisionError, OverflowError, ValueError, TypeError, RecursionError):
        return True
    return not abs(v) > SCREEN_TOLERANCE * max(1.0, m)


def expand_may_equal(a, b):
    """False when ``expand(a) == expand(b)`` cannot hold (their values at the screening
    point differ): the test of :func:`expand_may_vanish` for ``a - b``, without building
    the difference.

    >>> x, y = sp.symbols("x y")
    >>> expand_may_equal((x + y)**2, x**2 + 2*x*y + y**2), expand_may_equal(x + y, x - y)
    (True, False)
    """
    if len(_SCREEN_VALUES) > _MEMO_LIMIT:
        _SCREEN_VALUES.clear()
    try:
        (va, ma), (vb, mb) = _screen(a), _screen(b)
    except (ZeroDivisionError, OverflowError, ValueError, TypeError, RecursionError):
        return True
    return not abs(va - vb) > SCREEN_TOLERANCE * max(1.0, ma, mb)


class Unevaluable(Exception):
    """An expression the numeric checks cannot evaluate (an unknown function)."""


_FAIL = object()
_EVAL_ERRORS = (ZeroDivisionError, ValueError, OverflowError, TypeError)


def _mpmath_function(cls, nargs):
    """The mpmath function of a SymPy function class (sin -> mpmath.sin), made once."""
    key = (cls, nargs)
    if key not in _FUNCTIONS:
        fn = _KNOWN.get(cls.__name__)
        if fn is None:
            dummies = sp.symbols(f"_a0:{nargs}", cls=sp.Dummy)
            try:
                fn = sp.lambdify(dummies, cls(*dummies), modules="mpmath", docstring_limit=0)
            except Exception as err:      # the printer knows no mpmath form for it
                raise Unevaluable(f"{cls.__name__} has no mpmath form ({type(err).__name__})")
        _FUNCTIONS[key] = fn
    return _FUNCTIONS[key]


_FUNCTIONS = {}
_KNOWN = {name: getattr(mpmath, name) for name in (
    "sin", "cos", "tan", "cot", "sec", "csc", "exp", "asin", "acos", "atan", "sinh", "cosh",
    "tanh", "coth", "sech", "csch", "asinh", "acosh", "atanh", "sign")}
_KNOWN.update(Abs=abs, atan2=mpmath.atan2, re=mpmath.re, im=mpmath.im,
              conjugate=mpmath.conj, log=mpmath.log)


def _number(e):
    if e.is_Integer:
        return mpmath.mpf(int(e))
    if e.is_Rational:
        return mpmath.mpf(int(e.p)) / int(e.q)
    if e.is_Float:
        return mpmath.mpf(e._mpf_)
    if e is sp.pi:
        return +mpmath.pi
    if e is sp.E:
        return +mpmath.e
    if e is sp.I:
        return mpmath.mpc(0, 1)
    if e in (sp.oo, -sp.oo, sp.zoo, sp.nan):
        raise ValueError(f"{e} is not a finite number")
    re_, im_ = sp.N(e, DPS + 5).as_real_imag()
    return mpmath.mpc(re_._mpf_, im_._mpf_) if im_ else mpmath.mpf(re_._mpf_)


def evaluate(expr, memo):
    """The value of ``expr`` in mpmath, every subexpression looked up in (and added to)
    ``memo``, a dict that starts with the values of the free symbols.

    The memo makes a common subexpression cost one evaluation, within an expression,
    across the expressions of a check and across checks at the same point: the
    shared form of common-subexpression elimination, without generating code.
    Raises ZeroDivisionError, ValueError, OverflowError (a pole, a domain error),
    KeyError (a symbol without a value) or :class:`Unevaluable`.

    >>> x = sp.Symbol("x")
    >>> with mpmath.workdps(30):
    ...     print(evaluate(sp.sin(x)**2 + sp.cos(x)**2, {x: mpmath.mpf(1)/3}))
    1.0
    """
    known = _IDS.get(id(expr))
    if known is not None and known[0] is expr:
        expr = known[1]            # the representative of its equal copies (_canonical)
    val = memo.get(expr)
    if val is None:
        val = memo[expr] = _FAIL
        try:
            val = _compute(expr, memo)
        except RecursionError:
            raise Unevaluable("an expression too deeply nested to evaluate")
        memo[expr] = val
    elif val is _FAIL:
        raise ValueError("this subexpression failed to evaluate at this point")
    return val


# Equal subexpressions built apart (a derivative of L* in (1.26) and again in a reading
# form) are distinct objects; a memo keyed by the expression finds one from the other
# only through SymPy's structural ``==``, which walks both trees, at every point.  So the
# expressions of a check are mapped once to one representative per class of equal
# copies (``_canonical``), and ``evaluate`` looks each object up by its identity.
_REPS = {}      # expression -> its representative
_IDS = {}       # id(object) -> (object, representative); the object is kept alive


def _canonical(exprs, definitions=None):
    """Register every subexpression of ``exprs`` with its representative (the first
    equal one seen); below a copy nothing is registered: its representative's
    subexpressions are evaluated in its place.  A node of ``definitions`` gets the
    representative of its definition (it is evaluated as that)."""
    definitions = definitions or {}
    if definitions:
        _canonical(list(definitions.values()))
    stack = list(exprs)
    while stack:
        e = stack.pop()
        if id(e) in _IDS:
            continue
        if e in definitions:
            d = definitions[e]
            rep = _REPS[e] = _IDS[id(d)][1]
            _IDS[id(e)] = (e, rep)
            continue
        rep = _REPS.setdefault(e, e)
        _IDS[id(e)] = (e, rep)
        if rep is e:
            stack.extend(e.args)


def _forget_canonical():
    _REPS.clear()
    _IDS.clear()


def _compute(e, memo):
    if e.is_Add or e.is_Mul:
        vals = [evaluate(a, memo) for a in e.args]
        if all(isinstance(v, mpmath.mpf) for v in vals):    # as the raw path does it
            raw = (_sum_raw if e.is_Add else _product_raw)([v._mpf_ for v in vals],
                                                           mpmath.mp.prec)
            return mpmath.mp.make_mpf(raw)
        out = vals[0]
        for v in vals[1:]:
            out = out + v if e.is_Add else out * v
        return out
    if e.is_Pow:
        b, x = evaluate(e.base, memo), e.exp
        if x.is_Integer:
            return b ** int(x)
        if x.is_Rational and x.q == 2:
            return mpmath.sqrt(b) ** int(x.p)
        return mpmath.power(b, evaluate(x, memo))
    if e.is_Symbol:
        raise KeyError(f"no sample value for {e}")
    if e.is_Number or e.is_NumberSymbol or e is sp.I or e.is_number and not e.args:
        return _number(e)
    if isinstance(e, sp.Function):
        args = [evaluate(a, memo) for a in e.args]
        return _mpmath_function(e.func, len(args))(*args)
    if e.is_number:
        return _number(e)
    raise Unevaluable(f"cannot evaluate {type(e).__name__} numerically")


# The checks' evaluation at a point works on mpmath's raw real numbers (the tuples
# behind each mpf) with the functions of mpmath.libmp, as mpf arithmetic does inside:
# the same operations in the same order, so the same bits, without an mpf object and
# its type dispatch for every node.  A value that is not real (the root or logarithm of
# a negative number) or a function without a raw form sends the pair to ``evaluate``.
class _NotRaw(Exception):
    """This expression is evaluated by :func:`evaluate` (mpf and mpc objects) instead."""


_NOT_RAW = object()


_RAW = {name: getattr(libmp, "mpf_" + name) for name in (
    "sin", "cos", "tan", "exp", "log", "atan", "sinh", "cosh", "tanh")}


# The first ``POINTS`` points of a sampler are evaluated together: each node is visited
# once and its values at all of them are computed in one loop (a "vector", a list with
# one raw value per point), instead of one visit, one memo look-up and one type dispatch
# per node and point.  The operations and their order are those of mpf arithmetic, so the
# bits are ``evaluate``'s.  A point where a node cannot be done raw holds a marker instead
# of a value: ``_NOT_RAW`` (that point's expression goes to ``evaluate``) or ``_FAIL`` (a
# pole or a domain error there: the point is skipped); a vector with a marker is a
# ``_Marked`` list, so that a clean one is checked by type.  A single point (the points
# after the block, when a check needs more) is a block of width 1 (:func:`_raw`).
class _Marked(list):
    """A vector with at least one marker (``_FAIL`` or ``_NOT_RAW``) among its values."""


def _vector(e, memo, prec):
    """The values of ``e`` at the points of the block (``memo``: node -> vector)."""
    known = _IDS.get(id(e))
    if known is not None and known[0] is e:
        e = known[1]
    v = memo.get(e)
    if v is None:
        link = memo.get(_BASE)
        try:
            if link is not None and not link[1].involves(e):
                v = _vector(e, link[0], prec)       # the same value as at the base points
            else:
                v = _vector_compute(e, memo, prec, memo[_WIDTH])
        except RecursionError:
            raise Unevaluable("an expression too deeply nested to evaluate")
        memo[e] = v
    return v


_WIDTH = object()          # the block memo's entry for its number of points
_BASE = object()           # a derived block's entry: (the base block, the _Derived points)


def _sum_raw(xs, prec):
    """The sum of raw mpf values, rounded once (``mpf_sum``: the terms are added exactly,
    then rounded to ``prec`` bits), as the sum of a node's terms."""
    return mpf_sum(xs, prec, "n")


def _product_raw(xs, prec):
    """The product of raw mpf values, rounded once: the mantissas multiplied exactly and
    the result rounded to ``prec`` bits (one ``normalize`` for the node, not one per
    factor); with a zero, an infinity or nan among them, ``mpf_mul``'s rules, in order."""
    sign, man, exp = 0, 1, 0
    for xsign, xman, xexp, _ in xs:
        if not xman:
            out = xs[0]
            for y in xs[1:]:
                out = mpf_mul(out, y, prec, "n")
            return out
        sign ^= xsign
        man *= xman
        exp += xexp
    return normalize(sign, man, exp, man.bit_length(), prec, "n")


def _fold(op, vecs, prec):
    """The sum (``op`` mpf_add) or product (mpf_mul) of the vectors, point by point, each
    rounded once (:func:`_sum_raw`, :func:`_product_raw`)."""
    kernel = _sum_raw if op is mpf_add else _product_raw
    if any(type(v) is _Marked for v in vecs):
        out = _Marked()
        for col in zip(*vecs):
            if any(x is _FAIL for x in col):
                out.append(_FAIL)
            elif any(x is _NOT_RAW for x in col):
                out.append(_NOT_RAW)
            else:
                out.append(kernel(col, prec))
        return out
    return [kernel(col, prec) for col in zip(*vecs)]


def _map(fn, vec):
    """``fn`` at each point; a marker stays, ComplexResult gives ``_NOT_RAW``, another
    evaluation error ``_FAIL``."""
    out, marked = [], type(vec) is _Marked
    for x in vec:
        if x is _FAIL or x is _NOT_RAW:
            out.append(x)
            continue
        try:
            out.append(fn(x))
        except ComplexResult:
            out.append(_NOT_RAW)
            marked = True
        except _EVAL_ERRORS:
            out.append(_FAIL)
            marked = True
    return _Marked(out) if marked else out


def _vector_compute(e, memo, prec, width):
    if e.is_Add or e.is_Mul:
        return _fold(mpf_add if e.is_Add else mpf_mul,
                     [_vector(a, memo, prec) for a in e.args], prec)
    if e.is_Pow:
        b, x = _vector(e.base, memo, prec), e.exp
        if x.is_Integer:
            k = int(x)
            return _map(lambda v: mpf_pow_int(v, k, prec, "n"), b)
        if x.is_Rational and x.q == 2:
            k = int(x.p)
            return _map(lambda v: mpf_pow_int(mpf_sqrt(v, prec, "n"), k, prec, "n"), b)
        return _Marked([_NOT_RAW] * width)
    if e.is_Symbol:
        raise KeyError(f"no sample value for {e}")
    if e.is_Number or e.is_NumberSymbol:
        try:
            v = _number(e)
        except _EVAL_ERRORS:
            return _Marked([_FAIL] * width)
        if not isinstance(v, mpmath.mpf):
            return _Marked([_NOT_RAW] * width)
        return [v._mpf_] * width
    if isinstance(e, sp.Function) and len(e.args) == 1:
        fn = _RAW.get(e.func.__name__)
        if fn is not None:
            return _map(lambda v: fn(v, prec, "n"), _vector(e.args[0], memo, prec))
    return _Marked([_NOT_RAW] * width)


def _raw_values(point):
    """{symbol: raw mpf value (a tuple)} of a point; ``_NOT_RAW`` for a value that is
    not an mpf (an mpc, say), which :func:`evaluate` then takes."""
    return {s: v._mpf_ if isinstance(v, mpmath.mpf) else _NOT_RAW for s, v in point.items()}


def _block_of(raws):
    """The block memo of the points whose raw values are ``raws`` ({symbol: raw value or
    ``_NOT_RAW``} each); None when they do not all give the same symbols."""
    keys = raws[0].keys()
    if not all(r.keys() == keys for r in raws):
        return None
    block = {_WIDTH: len(raws)}
    for sym in keys:
        vec = [r[sym] for r in raws]
        block[sym] = _Marked(vec) if _NOT_RAW in vec else vec
    return block


def _raw(e, memo, prec):
    """The raw mpf value (a tuple) of ``e`` at one point: ``memo`` is that point's block of
    width 1 (:func:`_block_of`), or its raw values {symbol: raw value}, made into one in
    place; :class:`_NotRaw` where :func:`evaluate` must do it, ValueError at a pole."""
    if _WIDTH not in memo:
        memo.update(_block_of([dict(memo)]))
    v = _vector(e, memo, prec)[0]
    if v is _NOT_RAW:
        raise _NotRaw
    if v is _FAIL:
        raise ValueError("this subexpression failed to evaluate at this point")
    return v


def _value(e, memo, raw, prec):
    """The value of ``e`` at a point: from raw arithmetic when it can, else
    :func:`evaluate` (the memo ``memo`` of mpf values)."""
    try:
        return mpmath.mp.make_mpf(_raw(e, raw, prec))
    except _NotRaw:
        return evaluate(e, memo)


class _Points:
    """Random admissible points of one sampler and seed, drawn on demand, each with
    the memo of the values computed there (shared by every check that uses them), as
    mpf objects (:func:`evaluate`) and as raw mpf values (:func:`_vector`, :func:`_raw`)."""

    def __init__(self, sample, seed):
        self.sample, self.rng, self.points, self.raws = sample, random.Random(seed), [], []
        self.singles = []

    def __getitem__(self, i):
        while len(self.points) <= i:
            batch = getattr(self.sample, "batch", None)   # a sampler that draws a block at once
            new = batch(self.rng, POINTS) if batch and not self.points else [self.sample(self.rng)]
            for pt in new:
                pt = {s: mpmath.mpf(v) if isinstance(v, (int, float)) else v
                      for s, v in pt.items()}
                self.points.append(pt)
                self.raws.append(_raw_values(pt))
        return self.points[i]

    def raw(self, i):
        """The block of width 1 of point ``i`` (:func:`_raw`)."""
        self[i]
        while len(self.singles) <= i:
            self.singles.append(_block_of([self.raws[len(self.singles)]]))
        return self.singles[i]

    def derived(self, at):
        """These points with the symbols of ``at`` set to their expressions' values
        (:class:`_Derived`), one per ``at``."""
        key = tuple(at.items())
        table = self.__dict__.setdefault("_derived", {})
        if key not in table:
            table[key] = _Derived(self, at)
        return table[key]

    def block(self):
        """The memo of the vectors at points 0 .. POINTS - 1 (:func:`_vector`), made with
        the sampled values; None when the points do not all give the same symbols."""
        if not hasattr(self, "_block"):
            self[POINTS - 1]
            self._block = _block_of(self.raws[:POINTS])
            kept = getattr(self.sample, "kept", None)
            if kept and self._block is not None:
                _take_over(self._block, kept)
        return self._block


def _take_over(block, kept):
    """Add to ``block`` the node values of ``kept`` (another block), when each symbol of
    ``kept`` has the same values, bit for bit, in both: every node of ``kept`` was
    computed from those symbols' values alone, so it has the same values here."""
    if kept.get(_WIDTH) != block[_WIDTH] or _BASE in kept:
        return
    if all(block.get(s) == v for s, v in kept.items() if isinstance(s, sp.Symbol)):
        for e, v in kept.items():
            block.setdefault(e, v)


class _Derived:
    """The points of ``base`` (a :class:`_Points`) with each symbol of ``at`` ({symbol:
    expression}) given the value of its expression there: a substitution carried out
    at evaluation, without the substituted expression being built.  A node free of
    those symbols has its value at the base points, taken from (or added to) the base
    memo; only the nodes that involve them are evaluated again."""

    def __init__(self, base, at):
        self.base, self.at, self.symbols = base, dict(at), frozenset(at)
        self.points, self.raws, self.singles, self._involves = [], [], [], {}

    def involves(self, e):
        """Whether ``e`` contains a symbol of ``at`` (remembered per node)."""
        r = self._involves.get(e)
        if r is None:
            r = e in self.symbols
            if not r:
                for a in e.args:
                    if self.involves(a):
                        r = True
                        break
            self._involves[e] = r
        return r

    def _at_base(self, x, i):
        """The value (an mpf or mpc) of ``x`` at base point ``i``."""
        base = self.base
        if i < POINTS and base.block() is not None:
            return _at(x, _vector(x, base.block(), mpmath.mp.prec), i, base)
        return _value(x, base[i], base.raw(i), mpmath.mp.prec)

    def __getitem__(self, i):
        while len(self.points) <= i:
            j = len(self.points)
            pt = {k: v for k, v in self.base[j].items() if isinstance(k, sp.Symbol)}
            with mpmath.workdps(DPS):
                for s_, x in self.at.items():
                    try:
                        pt[s_] = self._at_base(x, j)
                    except _EVAL_ERRORS:
                        pt[s_] = mpmath.nan        # the substitution fails here: unusable
            self.points.append(pt)
            self.raws.append(_raw_values(pt))
        return self.points[i]

    def raw(self, i):
        """The block of width 1 of point ``i``, linked to the base's (:func:`_raw`)."""
        self[i]
        while len(self.singles) <= i:
            k = len(self.singles)
            single = _block_of([self.raws[k]])
            single[_BASE] = (self.base.raw(k), self)
            self.singles.append(single)
        return self.singles[i]

    def block(self):
        """The vectors at points 0 .. POINTS - 1, linked to the base block."""
        if not hasattr(self, "_block"):
            self[POINTS - 1]
            self._block = None if self.base.block() is None else _block_of(self.raws[:POINTS])
            if self._block is not None:
                self._block[_BASE] = (self.base.block(), self)
        return self._block


_SHARED = []


class shared_points:
    """Within this context, checks with the same sampler and seed share their random
    points and the values computed at them (a derivation's checks overlap a lot).

    >>> x = sp.Symbol("x")
    >>> with shared_points():
    ...     a = check_zero("a", "", sp.sin(x)**2 + sp.cos(x)**2 - 1, lambda r: {x: 0.5})
    """

    def __enter__(self):
        _SHARED.append({} if not _SHARED else _SHARED[-1])
        return self

    def __exit__(self, *exc):
        _SHARED.pop()
        if not _SHARED:                  # the derivation is done: free the memos
            _SCREEN_VALUES.clear()
            _forget_canonical()
        return False


def _points(sample, seed):
    if not _SHARED:
        return _Points(sample, seed)
    table = _SHARED[-1]
    try:
        key = (sample, seed)
        hash(key)
    except TypeError:
        return _Points(sample, seed)
    if key not in table:
        table[key] = _Points(sample, seed)
    return table[key]


def _numeric(lhs, rhs, sample, points, seed, definitions=None, at=None):
    """Largest relative residual of lhs - rhs over random points, and the count."""
    pts = _points(sample, seed)
    if at:
        pts = pts.derived(at)
    _canonical(list(lhs) + list(rhs), definitions)
    try:
        return _residuals(lhs, rhs, pts, points)
    finally:
        if not _SHARED or len(_IDS) > _MEMO_LIMIT:
            _forget_canonical()


def _at(e, vec, i, pts):
    """The value of ``e`` at point ``i`` of the block, from its vector ``vec``."""
    v = vec[i]
    if v is _FAIL:
        raise ValueError("this subexpression failed to evaluate at this point")
    if v is _NOT_RAW:
        return evaluate(e, pts[i])
    return mpmath.mp.make_mpf(v)


def _residuals(lhs, rhs, pts, points):
    worst, used, attempts = 0.0, 0, 0
    with mpmath.workdps(DPS):
        prec = mpmath.mp.prec
        block = pts.block()
        if block is not None:              # the first POINTS points: all at once
            vecs = [(_vector(a, block, prec), _vector(b, block, prec)) for a, b in zip(lhs, rhs)]
        while used < points and attempts < 4 * points:
            i = attempts
            attempts += 1
            if block is not None and i < POINTS:
                r = _raw_residual(vecs, i, prec)
                if r is not None:          # every value raw and finite: rounded as below
                    worst, used = max(worst, r), used + 1
                    continue
            try:
                if block is not None and i < POINTS:
                    vals = [(_at(a, va, i, pts), _at(b, vb, i, pts))
                            for (a, b), (va, vb) in zip(zip(lhs, rhs), vecs)]
                else:
                    memo, raw = pts[i], pts.raw(i)
                    vals = [(_value(a, memo, raw, prec), _value(b, memo, raw, prec))
                            for a, b in zip(lhs, rhs)]
            except (ZeroDivisionError, ValueError, OverflowError, TypeError):
                continue
            if not all(mpmath.isfinite(a) and mpmath.isfinite(b) for a, b in vals):
                continue
            for a, b in vals:
                scale = max(1, abs(a), abs(b))
                worst = max(worst, float(abs(a - b) / scale))
            used += 1
    return worst, used


_FINITE_SPECIAL = (libmp.fnan, libmp.finf, libmp.fninf)


def _raw_residual(vecs, i, prec):
    """The largest ``|a - b| / max(1, |a|, |b|)`` at point ``i`` over the pairs of
    vectors, in raw mpf arithmetic with the operations and rounding of the mpf objects'
    (so the same float); None when a value there is a marker or not finite."""
    worst = 0.0
    for va, vb in vecs:
        a, b = va[i], vb[i]
        if type(a) is not tuple or type(b) is not tuple or a in _FINITE_SPECIAL \
                or b in _FINITE_SPECIAL:
            return None
        if a == b:
            continue                        # the same bits: the residual is 0
        scale = libmp.fone
        for x in (libmp.mpf_abs(a, prec, "n"), libmp.mpf_abs(b, prec, "n")):
            if libmp.mpf_gt(x, scale):
                scale = x
        d = libmp.mpf_abs(libmp.mpf_sub(a, b, prec, "n"), prec, "n")
        worst = max(worst, libmp.to_float(libmp.mpf_div(d, scale, prec, "n"), rnd="n"))
    return worst


class At:
    """The values of expressions at one point {symbol: number}, at ``DPS`` digits, by the
    checks' raw arithmetic where it can (:func:`_raw`), else :func:`evaluate`; the
    expressions evaluated share the values of their common subexpressions.  A call
    raises as :func:`evaluate` raises.

    >>> x = sp.Symbol("x")
    >>> at = At({x: 4})
    >>> print(at(sp.sqrt(x) + 1), at(sp.sqrt(x) * 3))
    3.0 6.0
    """

    def __init__(self, point):
        with mpmath.workdps(DPS):
            self.memo = {s: mpmath.mpf(v) if isinstance(v, (int, float)) else v
                         for s, v in point.items()}
        self.raw = _raw_values(self.memo)

    def __call__(self, expr):
        with mpmath.workdps(DPS):
            return _value(expr, self.memo, self.raw, mpmath.mp.prec)


def values_at(expr, points, kept=None):
    """The values of ``expr`` at several points {symbol: number} with the same symbols,
    evaluated together as the checks' blocks are (:func:`_vector`); nan at a point where
    it cannot be evaluated (a pole, a domain error).  ``kept``, a dict, receives the block
    (the values of every node and symbol): a sampler that offers it as ``kept`` has
    them taken over by the checks' block of the same points (:meth:`_Points.block`).

    >>> x = sp.Symbol("x")
    >>> [float(v) for v in values_at(sp.sqrt(x) + 1, [{x: 4}, {x: 9}, {x: 0}])]
    [3.0, 4.0, 1.0]
    """
    with mpmath.workdps(DPS):
        pts = [{s: mpmath.mpf(v) if isinstance(v, (int, float)) else v for s, v in p.items()}
               for p in points]
        block = _block_of([_raw_values(p) for p in pts])
        if block is None:
            raise ValueError("values_at: the points do not all give the same symbols")
        vec = _vector(expr, block, mpmath.mp.prec)
        if kept is not None:
            kept.update(block)
        out = []
        for i in range(len(pts)):
            try:
                out.append(_at(expr, vec, i, pts))
            except _EVAL_ERRORS:
                out.append(mpmath.nan)
        return out


def value_at(expr, point):
    """The value (an mpf, or mpc where it is not real) of ``expr`` at one point
    {symbol: number} (:class:`At`).

    >>> x = sp.Symbol("x")
    >>> print(value_at(sp.sqrt(x) + 1, {x: 4}))
    3.0
    """
    return At(point)(expr)


def largest_value(expr, sample, points=POINTS, seed=0):
    """The largest ``abs(expr)`` over ``points`` random admissible points (those of
    ``sample`` and ``seed``, shared within :class:`shared_points` with the checks that
    use them, and so their values): the evidence that a misprinted form is wrong.

    >>> x = sp.Symbol("x")
    >>> largest_value(x - 1, lambda rng: {x: 3}, points=2)
    2.0
    """
    pts, worst = _points(sample, seed), 0.0
    with mpmath.workdps(DPS):
        block = pts.block() if points <= POINTS else None
        vec = None if block is None else _vector(expr, block, mpmath.mp.prec)
        for i in range(points):
            if vec is None or vec[i] is _FAIL or vec[i] is _NOT_RAW:
                v = evaluate(expr, pts[i])      # (a failure raises as evaluate raises it)
            else:
                v = mpmath.mp.make_mpf(vec[i])
            worst = max(worst, float(abs(v)))
    return worst


def check_identity(label, claim, lhs, rhs, sample, *, exact=True, points=POINTS, seed=0,
                   definitions=None, at=None):
    """Check ``lhs == rhs`` (expressions or equal-length lists of them).

    ``sample(rng)`` returns a dict {Symbol: float} of one random admissible
    point; it must give a value for every free symbol.  ``definitions``, a dict
    {node: expression}, says that each such node of the sides (an unevaluated
    d/dx, say) stands for its expression.  Where the sides with every node
    replaced would be small enough for an exact attempt (at most
    ``SUBSTITUTE_LIMIT`` nodes before the replacement) they are rebuilt so;
    otherwise the numeric check evaluates each node as its definition, and the
    large sides are never rebuilt.  Within :class:`shared_points` a node keeps its
    definition for the later checks too: define only nodes that mean the same
    everywhere (a d/dx of a given function, not a symbol that other checks sample).

    ``at``, a dict {symbol: expression}, checks the sides with each such symbol
    replaced by its expression (``lhs.xreplace(at) == rhs.xreplace(at)``), the
    replacement carried out at evaluation: at each point the symbol takes the value
    of its expression there, and only the nodes that involve it are evaluated again
    (the substituted sides, often large, are never built; the check is numeric).

    >>> x, y = sp.symbols("x y")
    >>> check_zero("at", "", x**2 - y, lambda rng: {x: 0.7, y: 0.1}, at={y: x**2}).holds
    True
    >>> d = sp.Function("D")(x)
    >>> check_identity("d", "", d + 1, sp.cos(x), lambda rng: {x: 0.3},
    ...                definitions={d: sp.cos(x) - 1}).detail
    'identical as built'
    """
    lhs = [sp.sympify(a) for a in _as_list(lhs)]
    rhs = [sp.sympify(b) for b in _as_list(rhs)]
    definitions = dict(definitions or {})
    if definitions and within_size(lhs + rhs + list(definitions.values()), SUBSTITUTE_LIMIT):
        lhs = [substitute(a, definitions) for a in lhs]
        rhs = [substitute(b, definitions) for b in rhs]
        definitions = {}
    elif definitions:
        exact = False          # the sides as they stand are not the expressions meant
    if at:
        exact = False          # nor are they with symbols still to be replaced
    what = dict(lhs=tuple(lhs), rhs=tuple(rhs), sample=sample, definitions=definitions,
                at=dict(at or {}))
    if len(lhs) != len(rhs):
        return Check(label, claim, False, "exact", f"{len(lhs)} left sides, {len(rhs)} right sides",
                     **what)
    if exact:
        ways = _exact_ways(lhs, rhs)
        if ways:
            return Check(label, claim, True, "exact", ", ".join(sorted(set(ways))), **what)
    try:
        worst, used = _numeric(lhs, rhs, sample, points, seed, definitions, at)
    except Unevaluable as err:
        return Check(label, claim, None, "unverified", f"not evaluable numerically: {err}", **what)
    detail = f"mpmath at {DPS} digits"
    if used == 0:
        return Check(label, claim, None, "unverified", "no admissible point could be evaluated",
                     **what)
    return Check(label, claim, worst <= TOLERANCE, "numeric", detail, used, worst, **what)


def check_zero(label, claim, expr, sample, **kw):
    """Check that ``expr`` (or each of a list) vanishes: ``check_identity(expr, 0)``."""
    exprs = _as_list(expr)
    return check_identity(label, claim, exprs, [sp.S.Zero] * len(exprs), sample, **kw)
