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
"""

import sympy as sp

__all__ = ["tree_size", "substitute", "max_depth", "expanded_terms"]


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


def substitute(expr, mapping, memo=None):
    """``expr.xreplace(mapping)``, with each distinct subexpression rebuilt once (``memo``
    may be shared between calls with the same mapping)."""
    memo = {} if memo is None else memo
    return _walk(sp.sympify(expr), mapping, memo)


def _walk(e, mapping, memo):
    r = memo.get(e)
    if r is None:
        if e in mapping:
            r = mapping[e]
        elif not e.args:
            r = e
        else:
            args = [_walk(a, mapping, memo) for a in e.args]
            r = e.func(*args) if any(a is not b for a, b in zip(args, e.args)) else e
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
