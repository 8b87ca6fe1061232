"""Targeted rewrites that make results readable, each exact and of known cost.

No ``simplify``: each function here is one well-defined normal form.

>>> import sympy as sp
>>> a, b, t = sp.symbols("a b theta")
>>> collected(a*b*sp.tan(t)**2 + a*b + a**2, [b])
a**2 + a*b*(tan(theta)**2 + 1)
"""

import sympy as sp

from . import polywalk
from .canonical import add, mul
from .dag import expanded_terms, instances, substitute

__all__ = ["collected", "rational", "rational_parts", "pythagoras", "factored"]

#: Above this operation count, a rewrite is skipped and the expression kept as built.
OPS_LIMIT = 2000


#: ``rational`` (cancel) is tried only below this size: its cost grows very fast with
#: the number of roots and functions it must treat as generators.
RATIONAL_OPS_LIMIT = 320
#: A rewrite is skipped when ``expand`` is estimated to give more terms than this.
SWELL_LIMIT = 50000
#: Coefficients larger than this are left expanded rather than factored.
FACTOR_LIMIT = 200
#: a fraction whose numerator and denominator have more than this many terms multiplied
#: is not brought to lowest terms (:func:`rational_parts` gives None: too large to read
#: as one fraction); the examples' largest product is 232
FRACTION_TERMS_LIMIT = 4000


def _ops_above(expr, limit):
    """``count_ops(expr) > limit``, without counting a huge tree: a tree of more than
    4 * limit + 1 nodes has more than ``limit`` operations (each operation joins at
    most four nodes), and its size is counted only that far; nor is a tree with more than
    ``limit`` powers, functions and terms joined in sums (``count_ops`` counts at least one
    operation for each).  Also True when
    ``expand`` would swell it beyond that (a power of a sum such as (1 + x)**40).

    ``count_ops`` itself (which builds a negated copy of each negative product and a
    fraction of each quotient) is called only when an upper bound counted in the same
    walk is above the limit (:func:`_ops_bound`).  On the examples and the scale
    families that spares all but a few of its calls."""
    n, least, seen, stack = 0, 0, [], [expr]
    while stack and n <= 4 * limit + 1:
        e = stack.pop()
        n += 1
        if e.is_Add:
            least += len(e.args) - 1       # count_ops counts one ADD or SUB per joined term,
        elif e.is_Pow or e.is_Function:
            least += 1                     # one POW, DIV or EXP per power, one per function
        seen.append(e)
        stack.extend(e.args)
    if n > 4 * limit + 1 or least > limit or expanded_terms(expr, SWELL_LIMIT) > SWELL_LIMIT:
        return True
    most = sum(_ops_bound(e) for e in seen)     # only for a tree that passed the cheap tests
    return most > limit and sp.count_ops(expr) > limit


def _ops_bound(e):
    """At most the operations ``count_ops`` counts at the node ``e``: for a sum of k
    terms, k - 1 joins and a NEG if all are negative; for a product of k factors, its
    joins above and below the fraction bar (k - 1 at most), a NEG and a DIV; one per
    power or function; a NEG and a DIV per rational number; one for any other atom
    (E is EXP)."""
    if e.is_Add:
        return len(e.args) - 1 + all(_negative(a) for a in e.args)
    if e.is_Mul:
        den = any((f.is_Pow and f.exp.is_Number and f.exp < 0) or (f.is_Rational and f.q != 1)
                  for f in e.args)
        return len(e.args) - 1 + _negative(e) + den
    if e.is_Pow or e.is_Function:
        return 1
    if e.is_Rational:
        return (e.p < 0) + (e.q != 1)
    return 0 if e.is_Symbol else 1


def _negative(e):
    c = e.as_coeff_Mul()[0]
    return bool(c.is_Number and c < 0)


_FACTORED = {}
_FACTORED_LIMIT = 20000
_EXPANDED = {}


def expanded(expr):
    """``sympy.expand(expr)``, the same expression, by one walk into a polynomial ring
    where that applies (:func:`.polywalk.groups` with no symbols to group by: the terms
    of ``expand``), else by ``expand``; remembered (a derivation expands its kinetic and
    potential coefficients for (1.12) and again to show them).

    >>> a, b, t = sp.symbols("a b theta")
    >>> e = a * (b + sp.tan(t))**2 / 2
    >>> expanded(e) == sp.expand(e), expanded(e).args == sp.expand(e).args
    (True, True)
    """
    r = _EXPANDED.get(expr)
    if r is None:
        try:
            parts = polywalk.groups(expr, [])
            r = parts.get(sp.S.One, sp.S.Zero) if set(parts) <= {sp.S.One} else None
        except polywalk.NotPolynomial:
            r = None
        if r is None:
            r = sp.expand(expr)
        if len(_EXPANDED) >= _FACTORED_LIMIT:
            _EXPANDED.clear()
        _EXPANDED[expr] = r
    return r


def factored(expr):
    """``sympy.factor(expr)``, remembered: a derivation factors the same coefficient in
    several places (the mass matrix in (1.4), in (1.12) and in (1.16)), and ``factor``
    costs some milliseconds even on a small polynomial.

    >>> a, b = sp.symbols("a b")
    >>> factored(a**2 + 2*a*b + b**2)
    (a + b)**2
    """
    r = _FACTORED.get(expr)
    if r is None:
        if len(_FACTORED) >= _FACTORED_LIMIT:
            _FACTORED.clear()
        try:
            r = polywalk.factor(expr)
        except polywalk.NotPolynomial:
            r = sp.factor(expr)
        _FACTORED[expr] = r
    return r


def collected(expr, symbols):
    """``expand``, group the terms by their monomial in ``symbols`` (velocities,
    accelerations) and ``factor`` each coefficient: the form a student would write.

    Unlike ``sympy.collect`` it does not recurse into function arguments, so its
    cost is one ``expand`` and one ``factor`` per monomial; for a polynomial in symbols
    and functions of atoms, the grouped terms come from one walk into a polynomial ring
    (:func:`.polywalk.groups`) instead of ``expand``.
    """
    if _ops_above(expr, OPS_LIMIT):
        return expr
    if _expanded_free_of(expr, symbols):       # one group, expr itself: no ring needed
        return pythagoras(expr if _ops_above(expr, FACTOR_LIMIT) else factored(expr))
    try:
        groups = polywalk.groups(expr, symbols)
    except polywalk.NotPolynomial:
        groups = {}
        for term in sp.Add.make_args(sp.expand(expr)):
            coeff, mono = term.as_independent(*symbols, as_Add=False)
            groups.setdefault(mono, []).append(coeff)
        groups = {mono: sp.Add(*coeffs) for mono, coeffs in groups.items()}
    out = []
    for mono, c in groups.items():
        if not _ops_above(c, FACTOR_LIMIT):
            c = factored(c)
        out.append(mul(c, mono))
    return pythagoras(add(*out))


def _expanded_free_of(expr, symbols):
    """Whether ``expr`` is a sum of monomials (rational coefficients, positive integer
    powers of symbols and of functions of atoms) free of ``symbols``: then
    :func:`collected` has one group, ``expr`` as it stands (``expand`` leaves it so)."""
    if not isinstance(expr, sp.Add) or expr.free_symbols & set(symbols):
        return False
    for t in expr.args:
        for f in sp.Mul.make_args(t):
            if f.is_Rational:
                continue
            b, e = f.as_base_exp()
            if not (e.is_Integer and e > 0
                    and (b.is_Symbol or b.is_Function and all(a.is_Atom for a in b.args))):
                return False
    return True


def pythagoras(expr):
    """Replace every literal factor sin(u)**2 + cos(u)**2 by 1 (and nothing else).

    >>> u = sp.Symbol("u")
    >>> pythagoras((sp.sin(u)**2 + sp.cos(u)**2)*sp.cos(u))
    cos(u)
    """
    found = instances(expr, (sp.sin, sp.cos, sp.Add))      # one walk of the shared tree
    args = {f.args[0] for f in found if isinstance(f, (sp.sin, sp.cos))}
    if not args:
        return expr
    sums = {sp.sin(u)**2 + sp.cos(u)**2 for u in args}
    present = [f for f in found if isinstance(f, sp.Add) and f in sums]
    if not present:
        return expr
    return substitute(expr, dict.fromkeys(present, sp.S.One))    # xreplace, once a node


def rational(expr, symbols=()):
    """``cancel`` (one fraction, common factors removed; roots and functions such as
    tan are treated as generators), then the numerator collected on ``symbols``.

    Expressions larger than ``RATIONAL_OPS_LIMIT`` operations are returned as they
    are: the rewrite is for reading, and results are correct either way."""
    parts = rational_parts(expr, symbols)
    return expr if parts is None else parts[0] / parts[1]


def rational_parts(expr, symbols=()):
    """The numerator and the denominator of :func:`rational`'s form (the numerator
    collected on ``symbols``, the denominator factored), or None above
    ``RATIONAL_OPS_LIMIT`` operations."""
    if _ops_above(expr, RATIONAL_OPS_LIMIT):
        return None
    try:
        num, den = _cancelled(expr)
    except polywalk.TooLarge:
        return None
    return collected(num, symbols), pythagoras(factored(den))


def _cancelled(expr):
    """Numerator and denominator of ``expr`` with their gcd removed, the roots and
    functions as generators: what ``cancel`` computes.  First by one walk into a
    polynomial ring (:func:`.polywalk.fraction`); where that walk does not apply,
    ``together`` (which merges the roots that multiply out) then one polynomial gcd over
    the integers, at half the cost of ``cancel`` (which first rewrites the whole
    expression with ``factor_terms``); ``cancel`` itself where the coefficients are not
    rational numbers."""
    from sympy.polys.polyerrors import PolynomialError
    from sympy.polys.rings import sring
    try:
        return polywalk.fraction(expr, FRACTION_TERMS_LIMIT)
    except polywalk.NotPolynomial:
        pass
    num, den = sp.fraction(sp.together(expr))
    try:
        ring, (p, q) = sring([num, den])
    except PolynomialError:
        return sp.fraction(sp.cancel(expr))
    if not (ring.domain.is_ZZ or ring.domain.is_QQ):
        return sp.fraction(sp.cancel(expr))
    return polywalk.lowest_terms(p, q)
