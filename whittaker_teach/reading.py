"""Reading forms: each result in the compact form the paper prints, for the system at hand.

The library derives its results in whatever form the derivation produces (a
long sum, after the chain rule).  The paper prints them compactly: L* as a
product of two roots (1.16)/(3.7), the generalized Whittaker equations as
d/dq_eps of a momentum minus a force (1.26)/(3.9), the reduced equation
cleared of denominators (3.10), the Nielsen form (2.4) as differences of
derivatives of L*.  Here each such form is built from the pieces (each piece
tidied by targeted rewrites: :func:`tidy`), and its equality with the
library's form is checked like every other identity (:func:`check_reading`):
a form shown is a claim, never an unchecked re-typing.

>>> import whittaker_teach as wt
>>> red = wt.examples.sledge().reduce("x")
>>> (form,) = whittaker_forms(red)            # (3.9): the sledge's (1.26), read
>>> [type(t).__name__ for t in sp.Add.make_args(form)]
['Mul', 'TotalD']
>>> check_reading("1.26", "the form shown equals (1.26)", [form], red._eqs, red).holds
True
"""

from __future__ import annotations

import sympy as sp

from .canonical import add, mul, power, sub
from .dag import bottom_up, expanded_terms, instances, substitute, tree_size
from .rewrite import RATIONAL_OPS_LIMIT, _ops_above, collected, expanded, factored, pythagoras
from .verify import check_identity, expand_may_equal

__all__ = ["TotalD", "TidyMemo", "powers_combined", "tidy", "evaluate", "carried_out", "check_reading",
           "velocity_form", "lstar_form", "momentum_forms", "whittaker_forms", "cleared_forms", "nielsen_forms",
           "total_derivative_form"]


class TotalD(sp.Function):
    """d/dx of an expression along a path, left unevaluated for display:
    ``TotalD(f, x)`` prints as d/dx (f) (SymPy's ``Derivative`` of an expression in
    several symbols prints as a partial derivative)."""

    nargs = 2
    #: the renderer breaks a long argument over lines inside d/dx( ... )
    is_total_derivative = True

    def _latex(self, printer):
        f, x = self.args
        return (rf"\frac{{d}}{{d {printer._print(x)}}}\left({printer._print(f)}\right)")

    def _pretty(self, printer):
        from sympy.printing.pretty.stringpict import prettyForm
        f, x = self.args
        body = printer._print(f)
        body = prettyForm(*body.parens())
        d = prettyForm(f"d/d{sp.pretty(x, use_unicode=True)}")
        return prettyForm(*d.right(body))

    def _sympystr(self, printer):
        return f"d/d{self.args[1]}({printer._print(self.args[0])})"


#: bases larger than this (tree nodes) are not expanded by :func:`powers_combined`
BASE_EXPAND_LIMIT = 200


def powers_combined(expr, memo=None):
    """In every product, powers of the same base (equal after ``expand``) are merged:
    sqrt(A)*A -> A**(3/2).  Exact: x**a * x**b = x**(a + b) for every base with the
    principal branch.  Only bases of at most ``BASE_EXPAND_LIMIT`` nodes, whose
    expansion is estimated at most as many terms, are expanded to compare them
    (others are compared as written, such as 2h - (1 + x/3 + theta/5)**40): the cost
    stays bounded on a large system.  ``memo`` (a :class:`TidyMemo`) is shared by the
    calls of one reduction, whose pieces share most of their subexpressions.

    >>> a, b = sp.symbols("a b")
    >>> A = a**2 + b
    >>> powers_combined(sp.sqrt(A) * sp.Mul(A, 1, evaluate=False) * a)
    a*(a**2 + b)**(3/2)
    >>> powers_combined(sp.sqrt(a + b) / sp.sqrt(a - b))      # different bases: unchanged
    sqrt(a + b)/sqrt(a - b)
    """
    def merge(m):
        bases = [f.as_base_exp()[0] for f in m.args]
        if sum(isinstance(b, sp.Add) for b in bases) < 2 and len(set(bases)) == len(bases):
            return m                # no two sums to compare, no base repeated: as it is
        groups, order = {}, []
        keys = _expansion_keys(bases, small)
        for f in sp.Mul.make_args(m):
            b, e = f.as_base_exp()
            key = keys.get(b, b)
            if key not in groups:
                order.append(key)
                groups[key] = [b, sp.S.Zero]
            groups[key][1] += e
        if len(order) == len(sp.Mul.make_args(m)):
            return m
        return sp.Mul(*[sp.Pow(groups[k][0], groups[k][1]) for k in order])
    memo = TidyMemo() if memo is None else memo
    small = memo.small          # sum -> whether it is small enough to expand (once each)
    return bottom_up(expr, lambda e: merge(e) if isinstance(e, sp.Mul) else e, memo.powers)


def _small_sum(b, small):
    r = small.get(b)
    if r is None:
        r = small[b] = (tree_size(b, BASE_EXPAND_LIMIT) <= BASE_EXPAND_LIMIT
                        and expanded_terms(b, BASE_EXPAND_LIMIT) <= BASE_EXPAND_LIMIT)
    return r


def _expansion_keys(bases, small=None):
    """{base: expand(base)} for the small sums among ``bases`` that may equal another
    one after ``expand``; a sum whose value at the screening point
    (:func:`.verify.expand_may_equal`) differs from every other's keeps itself as key,
    with no ``expand`` (most products, whose sums all differ)."""
    small = {} if small is None else small     # (a memo shared by one powers_combined)
    sums = [b for b in dict.fromkeys(bases) if isinstance(b, sp.Add) and _small_sum(b, small)]
    alike = set()
    for i, b in enumerate(sums):
        for c in sums[i + 1:]:
            if expand_may_equal(b, c):
                alike.update((b, c))
    return {b: sp.expand(b) for b in alike}


#: a piece larger than this (tree nodes) is shown as built: no reading form of it would
#: be readable, and tidying it costs more than deriving it
TIDY_SIZE_LIMIT = 1500


class TidyMemo:
    """What :func:`tidy` learns about subexpressions, kept for the pieces of one
    reduction (they share most of their subexpressions: the same roots of the energy
    and of the mass in every derivative of L*), so that each is examined once: its tree
    size (capped), whether its powers are all integer, whether it holds a literal
    sin^2 + cos^2, its collected form, and :func:`powers_combined`'s walk."""

    def __init__(self):
        self.sizes, self.integral, self.pythagorean = {}, {}, {}
        self.collected, self.powers, self.small = {}, {}, {}

    def size(self, e, limit):
        """``tree_size(e, limit)`` for ``e`` up to ``limit + 1`` nodes (the tree size,
        capped, counted once per distinct subexpression)."""
        r = self.sizes.get(e)
        if r is None:
            r = 1
            for a in e.args:
                r += self.size(a, limit)
                if r > limit:
                    break
            r = self.sizes[e] = min(r, limit + 1)
        return r

    def integer_powers(self, e):
        """Whether every power in ``e`` has an integer exponent."""
        r = self.integral.get(e)
        if r is None:
            r = (not isinstance(e, sp.Pow) or e.exp.is_Integer) and all(
                self.integer_powers(a) for a in e.args)
            self.integral[e] = r
        return r

    def has_pythagoras(self, e):
        """Whether ``e`` holds a sum sin(u)**2 + cos(u)**2 (what ``pythagoras`` replaces)."""
        r = self.pythagorean.get(e)
        if r is None:
            r = _pythagorean_sum(e) or any(self.has_pythagoras(a) for a in e.args)
            self.pythagorean[e] = r
        return r


def _pythagorean_sum(e):
    if not (isinstance(e, sp.Add) and len(e.args) == 2):
        return False
    a, b = e.args
    if not all(isinstance(t, sp.Pow) and t.exp == 2 for t in (a, b)):
        return False
    fa, fb = a.base, b.base
    return ({type(fa), type(fb)} == {sp.sin, sp.cos} and fa.args == fb.args)


def tidy(expr, symbols=(), memo=None):
    """The readable form of one piece, without expanding it: every polynomial factor
    (a sum free of roots) collected on ``symbols`` with factored coefficients
    (``rewrite.collected``), sin^2 + cos^2 = 1, powers of the same base merged.
    A piece of more than ``TIDY_SIZE_LIMIT`` nodes is returned as it is.  ``memo``, a
    :class:`TidyMemo`, may be shared by the pieces of one reduction.

    >>> a, b, t = sp.symbols("a b theta")
    >>> tidy(sp.sqrt(a + b)*(a*b*sp.tan(t)**2 + a*b)*(a + b)*(sp.sin(t)**2 + sp.cos(t)**2), [b])
    a*b*(a + b)**(3/2)*(tan(theta)**2 + 1)
    """
    expr = sp.sympify(expr)
    memo = TidyMemo() if memo is None else memo
    if memo.size(expr, TIDY_SIZE_LIMIT) > TIDY_SIZE_LIMIT:
        return expr
    key = tuple(symbols)

    def factor_of(f):
        if isinstance(f, sp.Pow) and isinstance(f.base, sp.Add) and f.exp.is_Integer:
            return sp.Pow(factor_of(f.base), f.exp)
        if isinstance(f, sp.Add) and memo.integer_powers(f):
            r = memo.collected.get((f, key))
            if r is None:
                r = memo.collected[f, key] = collected(f, list(symbols))
            return r
        return f

    def term(t):
        return mul(*[factor_of(f) for f in sp.Mul.make_args(t)])
    if isinstance(expr, sp.Add) and memo.integer_powers(expr):
        return powers_combined(factor_of(expr), memo)       # a polynomial: collect it whole
    out = sp.Add(*[term(t) for t in sp.Add.make_args(expr)])
    if memo.has_pythagoras(out):
        out = pythagoras(out)
    return powers_combined(out, memo)


def _tidy(red, expr, symbols):
    """``tidy(expr, symbols)``, once per piece and reduction: the readings of (1.26), (2.1)
    and (2.4) share many pieces (the same derivative of L* tidied in each), and the
    pieces share one :class:`TidyMemo`."""
    memo = red._cache.setdefault("tidy", {})
    key = (expr, tuple(symbols))
    if key not in memo:
        memo[key] = tidy(expr, symbols, red._cache.setdefault("tidy_memo", TidyMemo()))
        red._cache.setdefault("untidy", {}).setdefault(memo[key], expr)
    return memo[key]


def evaluate(expr, red, pieces=None):
    """``expr`` with every :class:`TotalD` carried out (``red._D``: d/dq_eps along a path).

    A TotalD of a tidied piece is carried out on the piece as the library built it (whose
    derivative the derivation has mostly taken already); the pair (tidied, as built) is
    then added to ``pieces``, a list, so that a check compares them too: equal functions
    have equal derivatives along every path, so the two checks together show the form."""
    return substitute(expr, carried_out([expr], red, pieces))


def carried_out(shown, red, pieces=None):
    """{TotalD node: its derivative} for every :class:`TotalD` in the list ``shown``: what
    :func:`evaluate` substitutes, as definitions for :func:`.verify.check_identity`
    (which then evaluates each d/dx as its derivative, without rebuilding a large
    form).  The pairs (tidied piece, piece as built) go to ``pieces`` as in
    :func:`evaluate`, once per piece."""
    untidy = red._cache.get("untidy", {})
    out = {}
    for s in shown:
        for node in instances(s, TotalD):
            if node in out:
                continue
            f = node.args[0]
            built = untidy.get(f, f) if pieces is not None else f
            if built is not f:
                pieces.append((f, built))
            out[node] = red._D(built)
    return out


def check_reading(label, claim, shown, library, red, sample=None, at=None, also=((), ())):
    """Check that the reading forms ``shown`` (a list) equal the library's ``library``:
    exactly by ``expand`` when cheap, else at random admissible points (40 digits).  Each
    piece under a d/dq_eps is compared with the piece the library built, and the form
    with the library's pieces differentiated is compared with ``library``.  ``at``: as
    for :func:`.verify.check_identity` (symbols replaced at evaluation).  ``also``, two
    lists (lhs, rhs) of the library's own expressions, checked first in the same check:
    they hold no d/dq_eps, so they are not searched for one (a walk of every node)."""
    pieces = []
    definitions = carried_out(shown, red, pieces)
    lhs = list(also[0]) + list(shown) + [a for a, _ in pieces]
    rhs = list(also[1]) + list(library) + [b for _, b in pieces]
    return check_identity(label, claim, lhs, rhs, sample or red._sample,
                          definitions=definitions, at=at)


def _times(a, b):
    """``a * b``, and 0 at once where ``b`` is 0 (SymPy's 0 * a asks whether every factor
    of ``a`` is finite, a deep query on a large sum; the sum then drops the 0 alike)."""
    return sp.S.Zero if b == 0 else mul(a, b)


def _primes(red):
    return list(red._qp.values())


#: a polynomial of more terms than this (estimated before expanding) is not factored
FACTOR_TERMS_LIMIT = 60


def _factored(e):
    """``factor(expand(e))`` for reading, when ``e`` expands to at most
    ``FACTOR_TERMS_LIMIT`` terms; otherwise ``e`` as it is (factoring a large
    multivariate polynomial can take minutes, and the form is only for reading)."""
    if _ops_above(e, RATIONAL_OPS_LIMIT) or expanded_terms(e, FACTOR_TERMS_LIMIT) > FACTOR_TERMS_LIMIT:
        return e
    return factored(expanded(e))


def velocity_form(red):
    """(1.12): qdot_eps = s sqrt(2 (h + A0) / (2 A2)), numerator and denominator tidied."""
    A2, _, A0 = red._A
    num = _factored(2 * (red.h + A0))
    den = _tidy(red, expanded(2 * A2), _primes(red))
    return red.direction * power(num, sp.S.Half) / power(den, sp.S.Half)


def lstar_form(red):
    """(1.16)/(3.7): L* = s sqrt(2 (h + A0)) sqrt(2 A2) + A1, each part tidied."""
    A2, A1, A0 = red._A
    qp = _primes(red)
    return (red.direction * sp.sqrt(_factored(2 * (red.h + A0)))
            * sp.sqrt(_tidy(red, expanded(2 * A2), qp)) + _tidy(red, A1, qp))


def momentum_forms(red):
    """(dL/dqdot_dep)* of (1.26), one per dependent coordinate, tidied."""
    return [_tidy(red, P, _primes(red)) for P in red._Pstar]


def _pieces(red, c):
    S, Ls = red.system, red._Lstar
    qp, q, x = red._qp[c], S.q[c], S.q[red._eps]
    pr = _primes(red)
    return S, Ls, qp, q, x, pr


def whittaker_forms(red):
    """(1.26)/(3.9), one per q_nu: d/dq_eps(dL*/dq'_nu) - dL*/dq_nu
    - sum_beta (dL/dqdot_beta)* (d/dq_eps(dqdot*_beta/dq'_nu) - dqdot*_beta/dq_nu),
    every derivative carried out and tidied, the d/dq_eps left to read."""
    out = []
    for c in red._nus:
        S, Ls, qp, q, x, pr = _pieces(red, c)
        e = sub(TotalD(_tidy(red, red._d(Ls, qp), pr), x), _tidy(red, red._d(Ls, q), pr))
        for P, qs in zip(red._Pstar, red._qdstar):
            # - P (d/dx(dq*/dq') - dq*/dq), written term by term so that equal terms of
            # opposite sign cancel as built (the sledge's m tan(theta)(1 + tan^2 theta))
            inner, P = red._d(qs, qp), _tidy(red, P, pr)
            e = add(e, _times(P, _tidy(red, red._d(qs, q), pr)))
            if inner != 0:
                e = sub(e, mul(P, TotalD(_tidy(red, inner, pr), x)))
        out.append(e)
    return out


def cleared_forms(red):
    """(3.10): each q''_nu = N/D of (1.26) cleared of denominators, D q''_nu - N,
    collected in q''_nu and the q'.

    A q''_nu larger than ``rewrite.RATIONAL_OPS_LIMIT`` operations has no one-fraction
    reading form (``rewrite.rational`` leaves it as it is) and gets no cleared form:
    the list then has fewer entries than q_nu, and the step says so."""
    if "cleared" not in red._cache:
        out = []
        acc = red._tidy_accelerations()
        parts = red._cache["acc_parts"]          # N and D of q''_nu = N / D as shown
        for c in red._nus:
            a = red._qpp[c]
            if parts[a] is None or _ops_above(acc[a], RATIONAL_OPS_LIMIT):
                continue
            num, den = parts[a]
            out.append(powers_combined(collected(den * a - num, [a] + _primes(red))))
        red._cache["cleared"] = out
    return list(red._cache["cleared"])


def total_derivative_form(red):
    """(2.1): dL*/dq_eps = sum_nu (dL*/dq'_nu q''_nu + dL*/dq_nu q'_nu) + dL*/dq_eps,
    the partial derivatives tidied."""
    S, Ls, pr = red.system, red._Lstar, _primes(red)
    x = S.q[red._eps]
    terms = [_tidy(red, red._d(Ls, x), pr)]
    for c in red._nus:
        terms += [mul(_tidy(red, red._d(Ls, red._qp[c]), pr), red._qpp[c]),
                  mul(_tidy(red, red._d(Ls, S.q[c]), pr), red._qp[c])]
    return add(*terms)


def nielsen_forms(red):
    """(2.4), one per q_nu: d(dL*/dq_eps)/dq'_nu - 2 dL*/dq_nu
    - sum_beta (dL/dqdot_beta)* (d(dqdot*_beta/dq_eps)/dq'_nu - 2 dqdot*_beta/dq_nu),
    each piece tidied."""
    dL = red._D(red._Lstar)             # (2.1), the object nielsen.nielsen gives (one memo)
    out = []
    for c in red._nus:
        S, Ls, qp, q, x, pr = _pieces(red, c)
        e = sub(_tidy(red, red._d(dL, qp), pr + [red._qpp[c]]),
                mul(2, _tidy(red, red._d(Ls, q), pr)))
        for P, qs in zip(red._Pstar, red._qdstar):
            P = _tidy(red, P, pr)
            e = add(e, sub(_times(mul(2, P), _tidy(red, red._d(qs, q), pr)),
                           _times(P, _tidy(red, red._d(red._D(qs), qp), pr))))
        out.append(e)
    return out
