"""SymPy's sums, products and powers, the same expressions SymPy builds, without the
work of ``flatten`` and of the assumption queries where nothing in them combines.

A derivation builds a great many products and sums whose parts are already in
canonical form and distinct: a factor replaced by its derivative, a symbol
renamed, a coefficient taken to a power.  ``Mul.flatten`` and ``Add.flatten``
then only multiply the numbers, merge the powers of a base and sort; that is done
here directly (:func:`mul`, :func:`add`, :func:`power`), and anything else (a
float, an infinity, I, an exponential, a number times a sum, which ``flatten``
distributes) is left to SymPy.  Every function returns the expression SymPy's own
constructor returns, argument by argument (tests/unit/test_canonical.py compares
them on random expressions).

>>> x, y = sp.symbols("x y")
>>> mul(2, x, y**2, 1/y) == sp.Mul(2, x, y**2, 1/y)
True
"""

import sympy as sp

__all__ = ["power", "mul", "add", "sub", "negated", "over"]


def power(base, exp):
    """``base**exp`` as SymPy builds it, without the assumption queries that cannot
    change the result.

    For a sum with symbols and a rational exponent other than 0 and 1, SymPy's
    ``Add._eval_power`` returns nothing (the power stays as built) unless the sum is
    ``a + I*b`` with an infinite term; to find that out it asks ``is_infinite`` of both
    terms of every two-term sum, a deep query on a term such as ``m*tan(theta)**2``.
    Such a power is built here unevaluated, which is the object evaluation gives.

    >>> x, y = sp.symbols("x y")
    >>> sp.srepr(power(x*sp.tan(y)**2 + x, -1)) == sp.srepr(1/(x*sp.tan(y)**2 + x))
    True
    >>> power(sp.Integer(4), sp.S.Half)
    2
    """
    base, exp = sp.sympify(base), sp.sympify(exp)
    if (base.is_Add and exp.is_Rational and exp not in (0, 1) and not base.is_number
            and not (len(base.args) == 2
                     and any(sp.I in sp.Mul.make_args(a) for a in base.args))):
        return sp.Pow(base, exp, evaluate=False)
    if base.is_Mul and exp.is_Integer and exp not in (0, 1) and base.is_commutative:
        r = _power_of_product(base, exp)
        if r is not None:
            return r
    return sp.Pow(base, exp)


def _power_of_product(base, k):
    """``base**k`` for a product ``base`` and an integer ``k``, as ``Mul._eval_power``
    builds it: each factor to the power k (a power's exponent multiplied by k, which
    is exact for an integer k), then their product; each power by :func:`power` (a
    power of a sum without its queries) and the product by :func:`_plain_product`.
    None where ``flatten`` would do more than multiply numbers, merge the powers of a
    base and sort.

    >>> x, y = sp.symbols("x y")
    >>> e = 3 * x * sp.sqrt(x**2 + y) / 2
    >>> _power_of_product(e, sp.Integer(-2)) == sp.Pow(e, -2)
    True
    """
    parts = []
    for f in base.args:
        p = power(f.base, f.exp * k) if f.is_Pow else power(f, k)
        parts.extend(p.args if type(p) is sp.Mul else (p,))
    return _plain_product(parts)


class _NoKey(Exception):
    """A node that :func:`_order_key` does not order (a class with its own ``compare``,
    a set in its content): the caller sorts as SymPy does."""


_ORDER_KEYS = {}
_RANKS = {}
_ORDER_KEYS_LIMIT = 50_000


def _order_key(e):
    """A key whose order is ``Basic.compare``'s (the order SymPy sorts the terms of a sum
    and the factors of a product in), built once per subexpression: the class's place
    in ``ordering_of_classes`` (then its name), the length of the hashable content, then
    the keys of its items.  ``compare`` walks both expressions again for every pair
    that a sort compares, and looks each class name up in a list.

    >>> x, y = sp.symbols("x y")
    >>> terms = [sp.sin(x), y**2, x, 3*x*y]
    >>> sorted(terms, key=_order_key) == sorted(terms, key=sp.core.add._args_sortkey)
    True
    """
    t = type(e)
    k = _ORDER_KEYS.get((t, e))
    if k is None:
        rank = _RANKS.get(t)
        if rank is None:
            from sympy.core.basic import Basic, ordering_of_classes
            if t.compare is not Basic.compare:
                raise _NoKey(t)
            name = t.__name__
            i = ordering_of_classes.index(name) if name in ordering_of_classes else None
            rank = _RANKS[t] = (len(ordering_of_classes) + 1, name) if i is None else (i, "")
        content = e._hashable_content()
        items = []
        for x in content:
            if isinstance(x, sp.Basic):
                items.append(_order_key(x))
            elif isinstance(x, (frozenset, list, dict, set)) or (
                    isinstance(x, tuple) and any(isinstance(y, sp.Basic) for y in x)):
                raise _NoKey(t)
            else:
                items.append(x)             # a name, an index, an assumption (name, value)
        k = (rank, len(content), tuple(items))
        if len(_ORDER_KEYS) >= _ORDER_KEYS_LIMIT:
            _ORDER_KEYS.clear()
        _ORDER_KEYS[t, e] = k
    return k


def _sort_args(args):
    """``_addsort`` / ``_mulsort`` (``args.sort`` in ``Basic.compare``'s order), by
    :func:`_order_key`, or by ``compare`` itself where a node has no key."""
    try:
        args.sort(key=_order_key)
    except (_NoKey, TypeError):
        from sympy.core.add import _addsort
        _addsort(args)


def mul(*factors):
    """``Mul(*factors)``, the same expression, built without ``flatten`` where nothing
    in it combines (:func:`_plain`).

    >>> x, y = sp.symbols("x y")
    >>> mul(3, x + y, sp.cos(x)) == sp.Mul(3, x + y, sp.cos(x))
    True
    """
    factors = [sp.sympify(f) for f in factors]
    r = _plain(sp.Mul, factors)
    return sp.Mul(*factors) if r is None else r


def add(*terms):
    """``Add(*terms)``, the same expression, built without ``flatten`` where no two
    terms combine (:func:`_plain_sum`)."""
    terms = [sp.sympify(t) for t in terms]
    r = _plain_sum(terms)
    return sp.Add(*terms) if r is None else r


def negated(x):
    """``-x`` as SymPy builds it: a sum is ``Mul(-1, x)``, which distributes (here by
    :func:`mul`); anything else has SymPy's own ``__neg__``, which does not flatten.

    >>> x, y = sp.symbols("x y")
    >>> negated(2*x - y/3) == -(2*x - y/3)
    True
    """
    from sympy.core.parameters import global_parameters
    x = sp.sympify(x)
    if type(x) is sp.Add and global_parameters.distribute:
        return mul(sp.S.NegativeOne, x)
    return -x


def sub(a, b):
    """``a - b`` as SymPy builds it, ``Add(a, -b)``, by :func:`add` and :func:`negated`.

    >>> x, y = sp.symbols("x y")
    >>> sub(x + 2*y, 2*(x + y)) == (x + 2*y) - 2*(x + y)
    True
    """
    return add(a, negated(b))


def over(a, b):
    """``a / b`` as SymPy builds it, ``Mul(a, Pow(b, -1))``, by :func:`mul` and :func:`power`.

    >>> x, y = sp.symbols("x y")
    >>> over(2*x + y, x + y) == (2*x + y) / (x + y)
    True
    """
    return mul(a, power(b, sp.S.NegativeOne))


def _plain(t, args):
    """``t(*args)`` for ``t`` Add or Mul, without ``flatten`` where nothing combines
    (:func:`_plain_sum`, :func:`_plain_product`; a product's factors that are products
    taken one by one, as ``flatten`` takes them; a rational times a sum distributed,
    :func:`_distributed`); None otherwise."""
    if t is sp.Add:
        return _plain_sum(args)
    kept = [a for a in args if a is not sp.S.One]         # the identity, dropped first
    if len(kept) < 2:
        return kept[0] if kept else sp.S.One              # one argument: itself, as built
    if len(kept) == 2 and (kept[0].is_Rational or kept[1].is_Rational):
        a, b = kept if kept[0].is_Rational else kept[::-1]
        if not a.is_zero and b.as_coeff_Mul()[1].is_Add:
            return _distributed(a, b)                       # flatten's rule for two
    return _plain_product([f for a in kept for f in (a.args if type(a) is sp.Mul else (a,))])


def _distributed(a, b):
    """``Mul(a, b)`` for a rational ``a`` (or ``b``) and a commutative sum, as
    ``Mul.flatten``'s rule for two factors builds it: the sum of the terms each times
    the rational (``_keep_coeff``), a sum built by :func:`_plain_sum` where it can;
    None for anything else (SymPy's rules then apply).

    >>> x, y = sp.symbols("x y")
    >>> _distributed(sp.Integer(-2), 3*x + y/2) == sp.Mul(-2, 3*x + y/2)
    True
    """
    from sympy.core.mul import _keep_coeff
    from sympy.core.parameters import global_parameters
    if b.is_Rational:
        a, b = b, a
    if (not a.is_Rational or a.is_zero or type(b) is not sp.Add or not b.is_commutative
            or not global_parameters.distribute):
        return None
    terms = [_keep_coeff(a, t) for t in b.args]
    r = _plain_sum(terms)
    return sp.Add(*terms) if r is None else r


def _merges(o):
    """Whether the factor or term ``o`` may combine in ``flatten`` with anything but a
    factor of the same base (a term of the same non-numeric part): a number, an
    infinity or a power of a number (3**x * 2**x, sqrt(2) * sqrt(3)), I, an exponential
    (exp(x) * exp(y)), an order term, a bounds object, anything non-commutative."""
    if o.is_Pow:
        return o.base.is_Number or o.base is sp.S.Exp1 or not o.is_commutative
    return (o.is_Number or o is sp.S.ImaginaryUnit or o is sp.S.ComplexInfinity
            or o.is_Order or not o.is_commutative or isinstance(o, _COMBINING)
            or not isinstance(o, sp.Expr))


def _combining():
    from sympy.functions.elementary.exponential import ExpBase
    return ExpBase, sp.AccumBounds   # ExpBase, not exp: exp's metaclass checks in Python


_COMBINING = _combining()


def _built(t, args):
    """``t._from_args(args)`` for a commutative sum or product, with SymPy's constructor
    postprocessors where one is registered for the class of an argument (matrix
    expressions register them; they are never among the plain factors)."""
    obj = t._from_args(args, True)
    mapping = sp.Basic._constructor_postprocessor_mapping
    if len(mapping) != _POSTPROCESSED[0]:        # a class registered since: start again
        _POSTPROCESSED[:] = [len(mapping), tuple(mapping), {}]
    _, keys, by_type = _POSTPROCESSED
    if keys:
        for a in args:
            hit = by_type.get(type(a))
            if hit is None:
                hit = by_type[type(a)] = issubclass(type(a), keys)
            if hit:
                return t._exec_constructor_postprocessors(obj)
    return obj


#: the classes with constructor postprocessors, their count, and which argument types
#: are instances of one (``_built``)
_POSTPROCESSED = [-1, (), {}]


def _plain_product(factors):
    """``Mul(*factors)`` where ``flatten`` would only multiply the rational numbers, add
    the rational exponents of a base met more than once (a sum, a symbol or a function
    that a power leaves as it is, such as sin: b**(x1 + x2), as ``flatten`` builds it)
    and sort; every factor plain (:func:`_merges`) and no number times a single sum
    (which ``flatten`` distributes).  None otherwise.  (``flatten``'s rules for exactly
    two factors are the caller's to rule out.)"""
    coeff, first, exps = sp.S.One, [], {}
    for o in factors:
        if o.is_Rational:
            coeff *= o
            continue
        if _merges(o) or type(o) is sp.Mul:
            return None
        b, x = (o.base, o.exp) if o.is_Pow else (o, sp.S.One)
        if b in exps:
            exps[b].append(x)
        else:
            exps[b] = [x]
            first.append(o)
    out = []
    for o in first:
        b = o.base if o.is_Pow else o
        xs = exps[b]
        if len(xs) > 1:
            o = _merged_power(b, xs)
            if o is None:
                return None
            if o is sp.S.One:
                continue
        out.append(o)
    if coeff.is_zero:
        return None
    if len(out) == 1 and coeff is not sp.S.One and out[0].is_Add:
        return _spread(coeff, out[0])
    return _assembled(sp.Mul, out, coeff)


def _spread(c, s):
    """A rational ``c`` (not 1) times the sum ``s``, as ``Mul.flatten`` ends a product of
    a number and one sum: ``Add(*[c*f for f in s.args])``; None where SymPy would not
    distribute (its global ``distribute`` off, or a non-commutative sum)."""
    from sympy.core.parameters import global_parameters
    if not global_parameters.distribute or not s.is_commutative:
        return None
    return add(*[mul(c, f) for f in s.args])


def _merged_power(b, xs):
    """b**sum(xs) as ``flatten`` merges powers of one base: for rational exponents and a
    base that a power leaves as it is (a sum, a symbol, a function without its own
    ``_eval_power``); 1 for a zero sum; None where ``flatten`` may do otherwise."""
    if not all(x.is_Rational for x in xs):
        return None                 # x**y * x**2: exponents of other kinds stay apart
    if not (isinstance(b, (sp.Add, sp.Symbol))
            or (isinstance(b, sp.Function) and type(b)._eval_power is sp.Expr._eval_power)):
        return None
    total = sp.Add(*xs)
    if total is sp.S.Zero:
        return None if b.is_Add and b.has(sp.oo, -sp.oo, sp.zoo) else sp.S.One
    p = b if total is sp.S.One else power(b, total)
    return p if p is b or (p.is_Pow and p.base == b) else None


def _plain_sum(terms):
    """``Add(*terms)`` where ``flatten`` would only add rational numbers and coefficients
    and sort the terms: each term (those of a sum among them taken one by one) is a
    rational number or plain (:func:`_merges`: no float coefficient), a rational times
    its own part;
    terms with the same part are merged as ``flatten`` merges them (the coefficients
    added, a zero dropped, the term rebuilt as ``flatten`` rebuilds it); None otherwise
    (SymPy's ``Add`` then builds it).

    >>> x, y = sp.symbols("x y")
    >>> _plain_sum([x*y, -2*sp.sin(x), x + y**2]) == sp.Add(x*y, -2*sp.sin(x), x + y**2)
    True
    >>> _plain_sum([x*y + 3*sp.sin(x), -x*y, sp.sin(x)/2]) == 7*sp.sin(x)/2
    True
    """
    terms = [t for t in terms if t is not sp.S.Zero]      # the identity, dropped first
    if len(terms) < 2:
        return terms[0] if terms else sp.S.Zero           # one term: itself, as built
    out, coeffs, merged, number = [], {}, False, sp.S.Zero
    for t in terms:
        for o in (t.args if type(t) is sp.Add else (t,)):
            if o.is_Rational:
                number += o                  # flatten's number, first in the sum
                continue
            c = sp.S.One
            if type(o) is sp.Mul:
                c = o.args[0]
                if not o.is_commutative or (c.is_Number and not c.is_Rational):
                    return None
                if c.is_Rational:
                    rest = o._new_rawargs(*o.args[1:])
                else:
                    c, rest = sp.S.One, o
            elif _merges(o):
                return None
            else:
                rest = o
            if rest in coeffs:
                coeffs[rest] += c
                merged = True
            else:
                coeffs[rest] = c
                out.append(o)
    if merged:
        out = [_term(c, rest) for rest, c in coeffs.items() if c is not sp.S.Zero]
    return _assembled(sp.Add, out, number)


def _assembled(t, parts, number):
    """``t`` (Add or Mul) as ``flatten`` returns it: the plain ``parts`` sorted, the
    rational ``number`` first unless it is the identity; a single argument is itself."""
    if len(parts) > 1:
        _sort_args(parts)
    if number is not t.identity:
        parts.insert(0, number)
    if len(parts) < 2:
        return parts[0] if parts else t.identity
    return _built(t, parts)


def _term(c, rest):
    """The term c*rest of a sum, as ``Add.flatten`` rebuilds a merged term."""
    if c is sp.S.One:
        return rest
    if rest.is_Mul:
        return rest._new_rawargs(c, *rest.args)
    if rest.is_Add:
        return sp.Mul(c, rest, evaluate=False)
    return sp.Mul(c, rest)
