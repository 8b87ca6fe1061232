"""Expressions as shared graphs: their size and substitution, at a cost bounded by the
number of distinct subexpressions.

The results of a derivation share subexpressions heavily (the same root or
fraction appears in many places).  ``Basic.xreplace`` and ``count_ops`` walk an
expression as a tree and so pay again for every repetition; the functions
here visit each distinct subexpression once (:func:`substitute`) or stop
counting at a bound (:func:`tree_size`).

>>> import sympy as sp
>>> x, y = sp.symbols("x y")
>>> e = sp.sin(x + y)**2 + sp.cos(x + y)
>>> substitute(e, {x: 2*y})
sin(3*y)**2 + cos(3*y)
>>> tree_size(e, 100)
11
>>> diff(e, x) == e.diff(x)
True
"""

import sympy as sp

from .canonical import _merges, _plain, _plain_product, _plain_sum, _sort_args, mul, over, power

__all__ = ["tree_size", "substitute", "renamed", "bottom_up", "instances", "along", "zeroed", "max_depth",
           "expanded_terms", "diff", "polynomial_in"]


def tree_size(expr, limit):
    """The number of nodes of ``expr`` as a tree, counted up to ``limit + 1`` only:
    a size measure whose cost is bounded, unlike ``count_ops`` on a huge tree.

    >>> x = sp.Symbol("x")
    >>> tree_size(sp.sin(x) + x**2, 100), tree_size(sp.expand((1 + x)**40), 10)
    (6, 11)
    """
    n, stack = 0, [expr]
    while stack and n <= limit:
        e = stack.pop()
        n += 1
        stack.extend(e.args)
    return n


def max_depth(expr, limit):
    """The nesting depth of ``expr`` (a symbol has depth 1), counted up to ``limit + 1``;
    each distinct subexpression is visited once.

    >>> x = sp.Symbol("x")
    >>> max_depth(sp.sin(sp.sin(x)), 50)
    3
    """
    seen, stack, deepest = set(), [(expr, 1)], 0
    while stack:
        e, d = stack.pop()
        deepest = max(deepest, d)
        if deepest > limit:
            break
        if (e, d) in seen or not e.args:
            continue
        seen.add((e, d))
        stack.extend((a, d + 1) for a in e.args)
    return deepest


def instances(expr, cls):
    """The subexpressions of ``expr`` that are instances of ``cls``, in the order first
    met, each distinct object visited once (``atoms`` visits a shared subtree again
    at every occurrence).

    >>> x = sp.Symbol("x")
    >>> instances(sp.sin(x) * sp.cos(sp.sin(x)) + sp.sin(x), sp.sin)
    [sin(x)]
    """
    seen, out, stack = set(), {}, [sp.sympify(expr)]
    while stack:
        e = stack.pop()
        if id(e) in seen:
            continue
        seen.add(id(e))
        if isinstance(e, cls):
            out.setdefault(e, None)
        stack.extend(reversed(e.args))
    return list(out)


def substitute(expr, mapping, memo=None):
    """``expr.xreplace(mapping)``, with each distinct subexpression rebuilt once (``memo``
    may be shared between calls with the same mapping).  ``mapping`` is anything with
    ``in`` and ``[]``: a dict, or an object that replaces every node of a kind."""
    memo = {} if memo is None else memo
    return _walk(sp.sympify(expr), mapping, memo)


def renamed(expr, mapping, memo=None):
    """``substitute(expr, mapping)`` where ``mapping`` sends symbols to distinct objects
    that are neither sums, products nor numbers (functions of a variable and their
    derivatives): each sum and product then keeps its terms and factors as they are,
    only their canonical order may change, so it is rebuilt by sorting them as
    ``flatten`` sorts them (``_addsort``, ``_mulsort``, the number first), without
    ``flatten``'s collecting and its assumption queries.  The same expression
    (equal, argument by argument) as ``substitute``'s.

    >>> x, y, t = sp.symbols("x y t")
    >>> f = sp.Function("f")(t)
    >>> e = 3*x**2*y + sp.sqrt(x + y)/y
    >>> renamed(e, {x: f, y: f.diff(t)}) == e.xreplace({x: f, y: f.diff(t)})
    True
    """
    if any(v.is_Add or v.is_Mul or v.is_Number for v in mapping.values()):
        raise ValueError("renamed: a value of the mapping is a sum, a product or a number")
    memo = {} if memo is None else memo
    return _renamed(sp.sympify(expr), mapping, memo)


def _renamed(e, mapping, memo):
    return _replaced(e, mapping, memo, _resorted)


def _resorted(e, args):
    """``e`` with new ``args``: a commutative sum or product only re-sorted (renaming
    symbols changes their order, never what combines), a power by :func:`power`."""
    t = type(e)
    if (t is sp.Add or t is sp.Mul) and e.is_commutative:
        rest = [a for a in args if not a.is_Number]
        _sort_args(rest)
        return t._from_args([a for a in args if a.is_Number] + rest, True)
    if t is sp.Pow:
        return power(*args)
    return e.func(*args)


def bottom_up(expr, f, memo=None):
    """``expr.replace(lambda e: True, f)``: ``f`` applied to every node once its arguments
    are rebuilt (``f`` returns the node or its replacement; as in ``replace``, a node is
    rebuilt only if an argument changed, and replaced only by something unequal), each
    distinct subexpression once (``replace`` pays again for every repetition).  ``memo``
    (a dict) may be shared by calls with the same ``f``.

    >>> x, y = sp.symbols("x y")
    >>> bottom_up(sp.sin(x*y) + x*y, lambda e: e.args[0] if e.is_Mul else e)
    x + sin(x)
    """
    memo = {} if memo is None else memo

    def walk(e):
        r = memo.get(e)
        if r is None:
            r = e
            if e.args:
                args = tuple(walk(a) for a in e.args)
                if args != e.args:
                    r = e.func(*args)
            v = f(r)
            r = memo[e] = r if v is None or v == r else v
        return r
    return walk(sp.sympify(expr))


def zeroed(expr, symbols, memo=None):
    """``expr`` with every symbol of ``symbols`` set to 0 (the part of an equation free
    of the accelerations), rebuilding only what changes: a product with a factor that
    becomes 0 is 0 at once, and a sum that only loses terms keeps its other terms as
    they stand (dropping terms leaves SymPy's sorted, collected sum canonical), where
    ``substitute`` would rebuild each through SymPy's ``flatten`` and its assumption
    queries.  For expressions whose subexpressions are finite (0 times a pole is not 0).

    >>> a, b, x = sp.symbols("a b x")
    >>> e = a*x + b*(1 + x*a) + sp.sin(b)
    >>> zeroed(e, [x]) == e.xreplace({x: 0})
    True
    """
    zero = frozenset(symbols)
    memo = {} if memo is None else memo

    def walk(e):
        r = memo.get(e)
        if r is None:
            r = memo[e] = _zeroed(e, zero, walk)
        return r
    return walk(sp.sympify(expr))


def polynomial_in(expr, s):
    """Whether ``expr`` is a polynomial in the symbol ``s`` with coefficients free of it
    and of infinities: ``s`` enters only through sums, products and positive integer
    powers.  Then setting ``s`` to 0 meets no pole, and :func:`zeroed` gives exactly
    what ``xreplace`` gives.

    >>> x, y = sp.symbols("x y")
    >>> polynomial_in(x**2*sp.sin(y)/y + x, x), polynomial_in(x/(x + y), x)
    (True, False)
    """
    memo, seen = {}, {}

    def ok(e):
        r = seen.get(e)
        if r is None:
            if not _has(e, s, memo):
                r = not _singular(e, memo)
            elif e == s:    # not `is`: SymPy's caches may hold another object for it
                r = True
            elif e.is_Add or e.is_Mul:
                r = all(ok(a) for a in e.args)
            else:
                r = e.is_Pow and e.exp.is_Integer and e.exp > 0 and ok(e.base)
            seen[e] = r
        return r
    return ok(sp.sympify(expr))


def _zeroed(e, zero, walk):
    if e in zero:
        return sp.S.Zero
    if not e.args:
        return e
    args = [walk(a) for a in e.args]
    if all(a is b for a, b in zip(args, e.args)):
        return e
    if e.is_Mul and any(a is sp.S.Zero for a in args):
        return sp.S.Zero
    if e.is_Add and all(a is b or a is sp.S.Zero for a, b in zip(args, e.args)):
        return sp.Add._from_args([a for a in args if a is not sp.S.Zero])
    return e.func(*args)


def _walk(e, mapping, memo):
    return _replaced(e, mapping, memo, _rebuilt)


def _rebuilt(e, args):
    t = type(e)
    if t is sp.Pow:
        return power(*args)        # Pow(*args), without its queries that change nothing
    if t is sp.Add or t is sp.Mul:
        r = _plain(t, args)
        if r is not None:
            return r
    return e.func(*args)


def _replaced(e, mapping, memo, rebuild):
    """``e`` with each key of ``mapping`` replaced, every distinct subexpression visited
    once (``memo``); a node whose arguments changed is made by ``rebuild(e, args)``."""
    r = memo.get(e)
    if r is None:
        if e in mapping:
            r = mapping[e]
        elif not e.args:
            r = e
        else:
            args = [_replaced(a, mapping, memo, rebuild) for a in e.args]
            r = e if all(a is b for a, b in zip(args, e.args)) else rebuild(e, args)
        memo[e] = r
    return r


def expanded_terms(expr, limit):
    """An estimate of the number of terms ``expand(expr)`` produces (sums add, products
    multiply, a power n of a sum multiplies n times), capped at ``limit + 1``: what an
    exact attempt by ``expand`` would cost, known before paying it.

    >>> x, y = sp.symbols("x y")
    >>> expanded_terms((x + y)**2 * (x + 1), 100), expanded_terms((1 + x + y)**40, 100)
    (8, 101)
    """
    memo = {}

    def terms(e):
        r = memo.get(e)
        if r is None:
            if e.is_Add:
                r = sum(terms(a) for a in e.args)
            elif e.is_Mul:
                r = 1
                for a in e.args:
                    r = min(r * terms(a), limit + 1)
            elif e.is_Pow and e.exp.is_Integer and e.exp > 0 and e.base.is_Add:
                r = terms(e.base) ** min(int(e.exp), 64)
            else:
                r = max([1] + [terms(a) for a in e.args])
            r = min(r, limit + 1)
            memo[e] = r
        return r
    return terms(expr)


def diff(expr, s, memo=None):
    """``expr.diff(s)`` for a Symbol ``s``, the same expression SymPy builds, with each
    distinct subexpression differentiated once (``memo``, a dict, may be shared between
    calls: it is keyed by the subexpression and the symbol).

    SymPy's ``diff`` walks the whole tree below every node it differentiates (its
    ``free_symbols`` test and the ``Derivative`` clean-up after each step), so its
    cost grows with the square of a large expression's size and is paid again for
    every repetition of a shared subexpression.  Here sums, products, powers and
    functions whose derivative is the chain rule over ``fdiff`` are differentiated
    by SymPy's own rules (``Add``: the sum of the derivatives; ``Mul``: the Leibniz
    rule as ``Mul._eval_derivative_n_times`` writes it; ``Pow``:
    ``Pow._eval_derivative``; a function: ``Function._eval_derivative``), so the
    result is identical to SymPy's; any other node is left to SymPy's ``diff``.

    >>> x, y = sp.symbols("x y")
    >>> e = sp.sqrt(x**2 + y) * sp.cos(x*y) / (1 + x)
    >>> diff(e, x) == e.diff(x), diff(e, sp.Symbol("z"))
    (True, 0)
    """
    if not isinstance(s, sp.Symbol):
        raise TypeError("dag.diff differentiates with respect to a Symbol")
    memo = {} if memo is None else memo
    return _d(sp.sympify(expr), s, memo)


def along(expr, rates, memo=None):
    """The derivative in s at s = 0 of ``expr`` with every symbol z of ``rates`` moved
    to z + s * rates[z]: the rate of ``expr`` along a path through the point, taken
    in one pass through the tree (forward differentiation: each distinct
    subexpression's rate once, by the rules of :func:`diff` with a symbol's
    derivative its rate).  The same value as ``diff(expr.subs(z, z + s*rate), s)``
    at s = 0, without building the moved expression.

    >>> x, y, u, w = sp.symbols("x y u w")
    >>> along(sp.sin(x*y), {x: 1, y: u})
    (u*x + y)*cos(x*y)
    >>> along(x**2 + w, {x: u})
    2*u*x
    """
    direction = _Direction({sp.sympify(z): sp.sympify(r) for z, r in rates.items()})
    return _d(sp.sympify(expr), direction, {} if memo is None else memo)


class _Direction:
    """The rates of the symbols along a path (:func:`along`); a memo key by identity."""

    def __init__(self, rates):
        self.rates = rates


_FREE = object()
_EMPTY = frozenset()


def _has(e, s, memo):
    """``s in e.free_symbols`` (for a path: any of its symbols), from the free symbols of
    each distinct subexpression, found once for every symbol (one walk of the tree, not
    one per symbol differentiated by)."""
    free = _free(e, memo)
    if isinstance(s, _Direction):
        return not free.isdisjoint(s.rates)
    return s in free


def _free(e, memo):
    """The free symbols of ``e`` (a frozenset), each distinct subexpression visited once
    (``memo``: the derivative memo, under the key ``(_FREE, e)``)."""
    key = (_FREE, e)
    r = memo.get(key)
    if r is None:
        if isinstance(e, sp.Symbol):
            r = frozenset((e,))
        elif not e.args:
            r = _EMPTY
        elif type(e) in (sp.Add, sp.Mul, sp.Pow) or _plain_function(type(e)):
            sets = [_free(a, memo) for a in e.args]
            sets = [x for x in sets if x]
            r = (_EMPTY if not sets else sets[0] if len(sets) == 1
                 else frozenset().union(*sets))
        else:
            r = frozenset(e.free_symbols)
        memo[key] = r
    return r


_SINGULAR = object()


def _singular(e, memo):
    """True when ``e`` contains an infinity or NaN, or a symbol assumed zero or infinite:
    only then can SymPy find a factor infinite (``is_finite`` False) or a base zero, so
    that a product with 0 is not 0.  Otherwise the zero terms of SymPy's rules are left
    out without building them (building them asks SymPy's assumptions about every
    factor, which costs a walk over a large sum each time)."""
    key = (_SINGULAR, e)
    r = memo.get(key)
    if r is None:
        if isinstance(e, sp.Symbol):
            r = bool(e.is_zero or e.is_finite is False)
        elif not e.args:
            r = bool(e.is_number and e.is_finite is not True)    # oo, zoo, nan
        else:
            r = any(_singular(a, memo) for a in e.args)
        memo[key] = r
    return r


_PLAIN = {}


def _plain_function(cls):
    """True for a function class differentiated by ``Function._eval_derivative`` (the
    chain rule over ``fdiff``), such as sin, cos, tan, exp, log."""
    r = _PLAIN.get(cls)
    if r is None:
        from sympy.core.basic import Basic
        r = _PLAIN[cls] = (issubclass(cls, sp.Function)
                           and cls._eval_derivative is sp.Function._eval_derivative
                           and cls._eval_derivative_n_times is Basic._eval_derivative_n_times)
    return r


def _product_with(args, i, da):
    """``Mul(*(args[:i] + (da,) + args[i + 1:]))`` for the factors ``args`` of a
    product: the same expression, without ``Mul.flatten`` where nothing can merge.

    Differentiating a product replaces one factor by its derivative, so the other
    factors are already in canonical order and distinct.  When the derivative's
    factors and the others have distinct bases, are plain (:func:`_merges`) and the
    numbers among them are rational, ``flatten`` only multiplies the numbers and
    sorts the factors (``_mulsort``); that is done here (:func:`_plain_product`).  In
    any other case (a common base, a float, two factors of which one is rational, a
    number times a sum, which ``flatten`` distributes) :func:`.canonical.mul` builds
    it, with SymPy's ``Mul`` or by the same rules.

    >>> x, y = sp.symbols("x y")
    >>> e = 3 * x**2 * sp.sin(y)
    >>> _product_with(e.args, 1, 2*x) == sp.Mul(3, 2*x, sp.sin(y))
    True
    """
    rest = args[:i] + args[i + 1:]
    r = None
    if da is not sp.S.One and not (len(rest) == 1 and (da.is_Rational or rest[0].is_Rational)):
        r = _plain_product(rest + (da.args if type(da) is sp.Mul else (da,)))
    return mul(*(args[:i] + (da,) + args[i + 1:])) if r is None else r


def _power_rule(e, dbase):
    """``e * (dbase * e.exp / e.base)``, the derivative of the power ``e`` = b**x with a
    constant exponent: the same expression, b**x / b merged into b**(x - 1) directly
    where x is a rational number (a symbolic x stays apart: x**y * x**-1), b is a sum,
    a symbol or a plain function and nothing else in the product has the base b
    (``flatten`` then merges only these two; where dbase * x has a power of b, SymPy
    divides it by b first, which may leave a number times a sum that it distributes);
    else the two products as SymPy builds them (:func:`.canonical.mul`).  The base
    is not a number (it holds the variable differentiated by; 1/sqrt(2 + I) would
    evaluate otherwise).

    >>> x, y = sp.symbols("x y")
    >>> e = sp.sqrt(x**2 + y)
    >>> _power_rule(e, 2*x) == e * (2*x * e.exp / e.base)
    True
    """
    b, x = e.base, e.exp
    scaled = mul(dbase, x)                   # as SymPy's: a number times a sum is distributed
    if x.is_Rational and (isinstance(b, (sp.Add, sp.Symbol))
                          or (_plain_function(type(b)) and not _merges(b))):
        k = x - 1
        own = () if k is sp.S.Zero else (b,) if k is sp.S.One else (sp.Pow(b, k),)
        rest = scaled.args if type(scaled) is sp.Mul else (scaled,)
        if all((f.base if f.is_Pow else f) != b for f in rest):   # else scaled / b first
            r = _plain_product(own + rest)
            if r is not None:
                return r
    return mul(e, over(scaled, b))                                 # e * (scaled / b)


def _d(e, s, memo):
    key = (e, s)
    r = memo.get(key)
    if r is not None:
        return r
    t = type(e)
    if not _has(e, s, memo):
        r = sp.S.Zero
    elif isinstance(e, sp.Symbol):
        r = s.rates[e] if isinstance(s, _Direction) else sp.S.One
    elif t is sp.Add:
        terms = [_d(a, s, memo) for a in e.args]
        r = _plain_sum(terms) or sp.Add(*terms)
    elif t is sp.Mul:
        args, terms = e.args, []
        for i, a in enumerate(args):
            da = _d(a, s, memo)
            if da is sp.S.Zero and not _singular(e, memo):
                continue                  # Mul(..., 0, ...) is 0: no factor is infinite
            terms.append(_product_with(args, i, da))
        r = _plain_sum(terms) or sp.Add(*terms)
    elif t is sp.Pow:
        from sympy import log
        dbase, dexp = _d(e.base, s, memo), _d(e.exp, s, memo)
        if dexp is sp.S.Zero and not _singular(e.base, memo):
            r = _power_rule(e, dbase)        # 0*log(base) is 0: base is not 0 or infinite
        else:
            r = e * (dexp * log(e.base) + dbase * e.exp / e.base)
    elif _plain_function(t):
        from sympy.core.function import ArgumentIndexError
        terms = []
        for i, a in enumerate(e.args, 1):
            da = _d(a, s, memo)
            if da.is_zero:
                continue
            try:
                df = e.fdiff(i)
            except ArgumentIndexError:
                df = sp.Function.fdiff(e, i)
            terms.append(df * da)
        r = sp.Add(*terms)
    elif isinstance(s, _Direction):
        r = sp.Add(*[rate * e.diff(z) for z, rate in s.rates.items()])
    else:
        r = e.diff(s)
    memo[key] = r
    return r
