"""Expressions into SymPy's sparse polynomial rings in one walk: a rational function's
numerator and denominator in lowest terms (:func:`fraction`) and the factorization of a
polynomial (:func:`factor`), without the ``together`` that SymPy's ``cancel`` and
``factor`` first apply to any expression.

``together`` builds its common denominators with SymPy's own Mul and Add, and ``sring``
then parses the result again: on q'' of the sledge the two take 25 ms.  The walk here
builds the numerator and the denominator as sparse polynomials in one pass, a root
b**(1/q) of a polynomial b being one more generator r with r**q = b, and a denominator
kept as a product of the factors that appeared (so that a sum's common denominator is
their highest powers, with no gcd).  Generators are sorted as SymPy sorts them, so that
signs come out normalized as ``sring`` and ``factor`` normalize them.  Anything else
(floats, I, a symbolic exponent, nested roots) raises :class:`NotPolynomial`, and the
caller uses SymPy's own functions.

>>> x, y = sp.symbols("x y")
>>> fraction(x/sp.sqrt(x + y)/sp.sqrt(x + y) + y/(x + y))
(1, 1)
>>> factor(2*x**2*y + 4*x*y + 2*y)
2*y*(x + 1)**2
"""

import sympy as sp

__all__ = ["NotPolynomial", "TooLarge", "fraction", "fractions", "factor", "groups",
           "lowest_terms", "vanishes"]


class NotPolynomial(Exception):
    """The walk met something it does not treat as a generator or a rational number
    (the caller falls back to SymPy's own functions)."""


class TooLarge(Exception):
    """:func:`fraction`'s numerator and denominator are too large for their gcd to be
    taken within its ``limit`` (the caller keeps the expression as it is)."""


def _generators(expr, number_roots=False):
    """({generator: None}, {root generator: (base, q)}) of ``expr``; a root of a
    positive rational number (sqrt(2)) is a generator only if ``number_roots``."""
    gens, roots, seen, stack = {}, {}, set(), [expr]
    while stack:
        e = stack.pop()
        if e in seen:
            continue
        seen.add(e)
        if e.is_Rational:
            continue
        if e.is_Symbol or e.is_Function:
            gens[e] = None
        elif e.is_Add or e.is_Mul:
            stack.extend(e.args)
        elif e.is_Pow and e.exp.is_Integer:
            stack.append(e.base)
        elif e.is_Pow and e.exp.is_Rational and (
                not e.base.is_number or number_roots and e.base.is_Rational and e.base > 0):
            r = sp.Pow(e.base, sp.Rational(1, e.exp.q))
            if not (r.is_Pow and r.base == e.base and r.exp.q == e.exp.q):
                raise NotPolynomial(e)
            roots[r] = (e.base, e.exp.q)
            stack.append(e.base)
        else:
            raise NotPolynomial(e)
    return gens, roots


class _Walk:
    """Numerator and factored denominator of each node, as polynomials of ``ring``."""

    def __init__(self, ring, order, roots):
        self.ring, self.order, self.roots, self.memo = ring, order, roots, {}
        self.index = {g: i for i, g in enumerate(order)}

    def as_expr(self, p):
        return p.as_expr(*self.order)

    def __call__(self, e):
        r = self.memo.get(e)
        if r is None:
            r = self.memo[e] = self._node(e)
        return r

    def product(self, factors, k=1):
        """The product of f**(j*k) over ``factors`` {f: j}."""
        out = self.ring.one
        for f, j in factors.items():
            if j:
                out *= f**(j * k)
        return out

    def _node(self, e):
        R = self.ring
        if e.is_Rational:
            return R.ground_new(R.domain.convert(e)), {}
        if e in self.index:
            return R.gens[self.index[e]], {}
        if e.is_Add:
            return self._sum([self(a) for a in e.args])
        if e.is_Mul:
            num, den = R.one, {}
            for a in e.args:
                n, d = self(a)
                num *= n
                for f, k in d.items():
                    den[f] = den.get(f, 0) + k
            return num, den
        b, x = e.args
        if x.is_Integer:
            n, d = self(b)
            k = int(x)
            if k >= 0:
                return n**k, {f: j * k for f, j in d.items()}
            if not n:
                raise NotPolynomial(e)
            return self.product(d, -k), {n: -k}
        r = R.gens[self.index[sp.Pow(b, sp.Rational(1, x.q))]]
        return (r**x.p, {}) if x.p > 0 else (R.one, {r: -x.p})

    def _sum(self, parts):
        R = self.ring
        groups = {}                       # equal denominators first: the common case
        for n, d in parts:
            key = frozenset(d.items())
            groups[key] = groups.get(key, R.zero) + n
        common = {}
        for key in groups:
            for f, k in key:
                common[f] = max(common.get(f, 0), k)
        num = R.zero
        for key, n in groups.items():
            d = dict(key)
            num += n * self.product({f: k - d.get(f, 0) for f, k in common.items()})
        return num, common


def _reduce_roots(p, walk):
    """``p`` with every r**k, k >= q, of a root generator r = b**(1/q) rewritten as
    b**(k // q) r**(k % q); repeated while a rewrite leaves a power of a root that
    occurs in another root's base (at most once per root)."""
    R = walk.ring
    for _ in range(len(walk.roots) + 1):
        high = [(r, b, q) for r, (b, q) in walk.roots.items()
                if any(m[walk.index[r]] >= q for m in p.itermonoms())]
        if not high:
            return p
        for r, b, q in high:
            i = walk.index[r]
            bn, bd = walk(b)
            if bd:
                raise NotPolynomial(b)
            parts = {}
            for m, c in p.iterterms():
                j, k = divmod(m[i], q)
                parts.setdefault(j, {})[m[:i] + (k,) + m[i + 1:]] = c
            p = sum((R.from_dict(t) * bn**j for j, t in parts.items()), R.zero)
    raise NotPolynomial(p)                 # roots nested in a cycle: not reduced


_SPLIT = {}


def _has_content(b):
    """Whether ``factor_terms`` can take anything out of every term of the sum ``b``: a
    numeric content other than 1, or a base common to all terms (only then can the root
    of ``b`` split)."""
    from math import gcd, lcm
    coeffs = [t.as_coeff_Mul()[0] for t in b.args]
    if not all(c.is_Rational for c in coeffs):
        return True
    if gcd(*[abs(int(c.p)) for c in coeffs]) != 1 or lcm(*[int(c.q) for c in coeffs]) != 1:
        return True
    common = None
    for t in b.args:
        bases = {f.as_base_exp()[0] for f in sp.Mul.make_args(t) if not f.is_Number}
        common = bases if common is None else common & bases
        if not common:
            return False
    return True


def _split_roots(roots):
    """{b**(p/q): the same root of b with its common factor taken out} where SymPy then
    splits it, as ``together`` does: sqrt(m*y'**2 + m) = sqrt(m)*sqrt(y'**2 + 1) for m
    positive, so that sqrt(m) can cancel."""
    out = {}
    for r, (b, q) in roots.items():
        if b.is_Add and _has_content(b):
            s = _SPLIT.get(b)
            if s is None:
                if len(_SPLIT) >= 4096:
                    _SPLIT.clear()
                s = _SPLIT[b] = sp.factor_terms(b)
            if s != b and not sp.Pow(s, r.exp).is_Pow:
                out.update({b**sp.Rational(p, q): sp.Pow(s, sp.Rational(p, q))
                            for p in range(-3 * q, 3 * q + 1) if p % q})
    return out


def _walked(expr, number_roots=False, merge_roots=False):
    """The walk of ``expr`` (its roots split as ``together`` splits them) and the
    numerator and factored denominator it gives; with ``merge_roots``, roots of equal
    degree whose bases are the same rational function
    (sqrt(m*(t**2 + 1)) and sqrt(m*t**2 + m)) are one generator."""
    gens, roots = _generators(expr, number_roots)
    split = _split_roots(roots)
    if split:
        expr = expr.xreplace(split)
        gens, roots = _generators(expr, number_roots)
    walk = _walker(list(gens) + list(roots), roots)
    if merge_roots and len(roots) > 1:
        _merge_roots(walk)
    return walk, walk(expr)


def _merge_roots(walk):
    seen = []                                 # (q, numerator, denominator, generator)
    for r, (b, q) in walk.roots.items():
        n, d = walk(b)
        d = walk.product(d)
        same = next((g for q1, n1, d1, g in seen if q1 == q and n * d1 == n1 * d), None)
        if same is None:
            seen.append((q, n, d, walk(r)))
        else:
            walk.memo[r] = same


def fraction(expr, limit=None):
    """Numerator and denominator of ``expr`` over the integers, their gcd removed (the
    roots and functions as generators), by one walk; ``NotPolynomial`` if the walk
    cannot treat ``expr``; ``TooLarge`` if ``limit`` is given and the product of their
    numbers of terms exceeds it (a gcd of two large multivariate polynomials can take
    minutes).

    >>> x, y = sp.symbols("x y")
    >>> fraction(x/sp.sqrt(x + y)/sp.sqrt(x + y) + y/(x + y))
    (1, 1)
    """
    walk, (num, den) = _walked(expr)
    R, roots = walk.ring, walk.roots
    p, q = _reduce_roots(num, walk), _reduce_roots(walk.product(den), walk)
    if not q:
        raise NotPolynomial(expr)
    cp, p = p.clear_denoms()
    cq, q = q.clear_denoms()
    Z = _ring(R.ngens, "ZZ")
    p, q = (p * cq).set_ring(Z), (q * cp).set_ring(Z)
    if limit is not None and len(p) * len(q) > limit:
        raise TooLarge(expr)
    _, p, q = _cofactors(p, q)          # the gcd, and both sides divided by it
    if any(m[walk.index[r]] for r in roots for m in q.itermonoms()):
        raise NotPolynomial(expr)   # a root left below: ``together`` may cancel it, with
                                   # a relation (r**2 = b) that the gcd does not see
    return _signed(p, q, walk.order)


def _gcd_ring(k):
    """A ``PolyRing`` over the integers in ``k`` placeholders named so that dropping its
    first generator gives ``_gcd_ring(k - 1)``: SymPy's heuristic gcd drops one generator
    per level, building each smaller ring (with ``exec``, about a millisecond) the first
    time it meets it, and with these names every gcd shares one chain of rings."""
    from sympy.polys.domains import ZZ
    from sympy.polys.rings import PolyRing
    R = _RINGS.get((k, "gcd"))
    if R is None:
        larger = [n for n, kind in _RINGS if kind == "gcd" and n > k]
        if larger:                  # dropped to, as the gcd drops (SymPy keeps those)
            R = _RINGS[min(larger), "gcd"]
            while R.ngens > k:
                R = R.drop(R.gens[0])
        else:
            R = PolyRing([sp.Symbol(f"_g{i}") for i in range(k - 1, -1, -1)], ZZ)
        _RINGS[k, "gcd"] = R
    return R


def _cofactors(p, q):
    """``p.cofactors(q)`` (the gcd and both quotients), computed in a ring of only the
    generators that occur in p or q (:func:`_gcd_ring`), in their order: a ring padded
    with unused generators (``RING_STEP``) costs the heuristic gcd one level, and the
    first time one new ring, per unused generator.  The same polynomials: the order of
    the generators that occur is kept, so the leading coefficients and signs are too."""
    R = p.ring
    used = sorted({i for f in (p, q) for m in f.itermonoms() for i, e in enumerate(m) if e})
    if len(used) == R.ngens or not used:
        return p.cofactors(q)
    Rk = _gcd_ring(len(used))

    def down(f):
        return Rk.from_dict({tuple(m[i] for i in used): c for m, c in f.items()})

    def up(f):
        out = {}
        for m, c in f.items():
            full = [0] * R.ngens
            for j, i in enumerate(used):
                full[i] = m[j]
            out[tuple(full)] = c
        return R.from_dict(out)

    return tuple(up(f) for f in down(p).cofactors(down(q)))


def fractions(exprs):
    """One walk of several expressions into one ring: ``(walk, parts)``, ``parts`` the
    numerator and the denominator (the product of its factors) of each expression as
    polynomials over the rationals, every power r**k (k >= q) of a root r = b**(1/q)
    reduced; ``walk.as_expr`` turns a polynomial back into an expression.  The
    generators (symbols, functions, roots) are treated as independent: a relation such
    as sin**2 + cos**2 = 1 is not used.  ``NotPolynomial`` as for :func:`fraction`.

    >>> x, y = sp.symbols("x y")
    >>> walk, parts = fractions([x/(x + y), y**2])
    >>> [(walk.as_expr(n), walk.as_expr(d)) for n, d in parts]
    [(x, x + y), (y**2, 1)]
    """
    exprs = [sp.sympify(e) for e in exprs]
    gens, roots = _all_generators(exprs)
    split = _split_roots(roots)
    if split:
        exprs = [e.xreplace(split) for e in exprs]
        gens, roots = _all_generators(exprs)
    walk = _walker(list(gens) + list(roots), roots)
    parts = []
    for e in exprs:
        num, den = walk(e)
        q = _reduce_roots(walk.product(den), walk)
        if not q:
            raise NotPolynomial(e)
        parts.append((_reduce_roots(num, walk), q))
    return walk, parts


def _all_generators(exprs):
    """The generators and roots of several expressions together (first seen first)."""
    gens, roots = {}, {}
    for e in exprs:
        g, r = _generators(e)
        gens.update(g)
        roots.update(r)
    return gens, roots


def vanishes(expr):
    """Whether ``expr`` is shown to be 0 by rational arithmetic alone: brought over one
    common denominator in a polynomial ring whose generators are its symbols, functions
    and roots, each root r = b**(1/q) reduced by r**q = b, the numerator is the zero
    polynomial and no factor of the denominator is.  The generators are treated as
    independent, so ``False`` means "not shown" (sin(x)**2 + cos(x)**2 - 1 is not),
    never "shown nonzero".  This decides most of a derivation's identities at less than
    half the cost of ``expand`` (which multiplies out every term through SymPy's Mul).

    >>> x, y = sp.symbols("x y", positive=True)
    >>> vanishes(x/(x + y) + y/(x + y) - 1)
    True
    >>> vanishes(sp.sqrt(x + y)**3 - (x + y)*sp.sqrt(x + y) + sp.sqrt(2)**2 - 2)
    True
    >>> vanishes(sp.sin(x)**2 + sp.cos(x)**2 - 1)
    False
    """
    try:
        walk, (num, den) = _walked(expr, number_roots=True, merge_roots=True)
        if _reduce_roots(num, walk):
            return False
        return all(_reduce_roots(f, walk) for f in den)
    except NotPolynomial:
        return False


def lowest_terms(p, q, gens=()):
    """p/q as expressions in ``gens`` (default: the ring's own symbols), their gcd
    removed, the denominator's leading coefficient > 0."""
    _, p, q = p.cofactors(q)
    return _signed(p, q, gens)


def _signed(p, q, gens):
    if q.LC < 0:
        p, q = -p, -q
    return p.as_expr(*gens), q.as_expr(*gens)


_RINGS = {}


def _ring(n, domain):
    """A ``PolyRing`` in ``n`` placeholder generators over ``domain`` ("QQ" or "ZZ"),
    remembered: SymPy builds each new ring's monomial code with ``exec`` (about a
    millisecond), and a ring (and the smaller rings a gcd drops to) depends only on the
    number of generators.  The walk maps its own generators to the placeholders."""
    from sympy.polys.domains import QQ, ZZ
    from sympy.polys.rings import PolyRing
    R = _RINGS.get((n, domain))
    if R is None:
        R = _RINGS[n, domain] = PolyRing(sp.symbols(f"_w0:{n}"), QQ if domain == "QQ" else ZZ)
    return R


_GEN_KEYS = {}


def _gen_key(g):
    """The key by which SymPy's ``_sort_gens`` (default options) sorts ``g``, remembered:
    it prints each generator, about 0.1 ms for tan(theta)."""
    k = _GEN_KEYS.get(g)
    if k is None:
        from sympy.polys.polyutils import _gens_order, _max_order, _re_gen
        if len(_GEN_KEYS) >= 4096:
            _GEN_KEYS.clear()
        name, index = _re_gen.match(g.name if type(g) is sp.Symbol else str(g)).groups()
        k = _GEN_KEYS[g] = (_gens_order.get(name, _max_order), name, int(index) if index else 0)
    return k


#: rings have a multiple of this many generators (the walk's own, then placeholders that
#: stay at exponent 0): a derivation then builds a few rings instead of one per count of
#: generators (each new ring costs SymPy 0.4 to 1.1 ms of ``exec``).  With 8 the chain
#: at n = 8 builds rings of 8 and 16 instead of 4, 8, 12 and 16: about 1.5 ms less,
#: while the operations in the larger rings cost no measurable time more
RING_STEP = 8


def _walker(gens, roots):
    """A :class:`_Walk` over the rationals with ``gens`` in SymPy's own order (the order
    ``sring`` and ``factor`` choose, so that signs are normalized as theirs are), in a
    ring of ``RING_STEP``-rounded size whose last generators are unused: as the last
    in the lexicographic order, always at exponent 0, they change neither the leading
    terms nor the factors."""
    order = sorted(gens, key=_gen_key)
    size = -(-max(len(order), 1) // RING_STEP) * RING_STEP
    order += [sp.Dummy() for _ in range(size - len(order))]
    return _Walk(_ring(size, "QQ"), order, roots)


def factor(expr):
    """``sympy.factor(expr)`` for a polynomial in its symbols and functions, without the
    ``together`` that ``factor`` first applies to any expression (half its cost on a
    polynomial): one walk into a polynomial ring and its ``factor_list``, the result
    built as ``factor`` builds it.  A rational function is factored as ``factor`` does
    it, numerator and denominator each (the product of the factors' powers then merges
    the factors they share, as ``factor``'s product does): one walk, without
    ``together``'s rebuilding of the sum over a common denominator.  ``NotPolynomial``
    for anything else (a root, a float).

    >>> x, y = sp.symbols("x y")
    >>> factor(2*x**2*y + 4*x*y + 2*y)
    2*y*(x + 1)**2
    >>> factor(x*sp.tan(y)**2/2 + x/2) == sp.factor(x*sp.tan(y)**2/2 + x/2)
    True
    """
    from sympy.core.mul import _keep_coeff
    gens, roots = _generators(expr)
    if roots:
        raise NotPolynomial(expr)
    if not gens or _plainly_irreducible(expr):
        return expr
    walk = _walker(list(gens), {})
    num, den = walk(expr)
    ZZ = _ring(walk.ring.ngens, "ZZ")
    c, p = num.clear_denoms()
    coeff, factors = _factor_list(p.set_ring(ZZ))
    coeff = sp.Rational(int(coeff), int(c))
    pieces = [walk.as_expr(f)**k for f, k in factors]
    for f, k in den.items():        # a denominator: its factors with exponents -k
        cd, q = f.clear_denoms()
        dc, dfs = _factor_list(q.set_ring(ZZ))
        coeff *= sp.Rational(int(cd), int(dc))**k
        pieces += [walk.as_expr(g)**(-j * k) for g, j in dfs]
    return _keep_coeff(coeff, sp.Mul(*pieces))


def _plainly_irreducible(expr):
    """Whether ``expr``, a sum of monomials (integer coefficients, positive integer powers
    of symbols and functions), is irreducible with no content, so that ``factor`` gives
    it back as it is, read off the terms without a ring: the coefficients have gcd 1, no
    generator divides every term, and some generator x is of degree one in exactly one
    term (the test of :func:`_factor_list_of`: a factor of such a polynomial would
    contain x, and the other factor would divide x's coefficient, a single term, so every
    term).  The sign needs no normalizing: ``factor``'s -1 times a sum is that sum
    negated, as SymPy builds the product.

    >>> x, y, z = sp.symbols("x y z")
    >>> _plainly_irreducible(2*x*y - 3*z**2 + 1), _plainly_irreducible(2*x*y + 4*z)
    (True, False)
    """
    from math import gcd
    if not isinstance(expr, sp.Add):
        return False
    content, powers, count = 0, [], {}
    for t in expr.args:
        c, rest = t.as_coeff_Mul()
        if not c.is_Integer:
            return False
        content = gcd(content, int(c))
        d = {}
        for f in sp.Mul.make_args(rest):
            b, e = f.as_base_exp()
            if not (e.is_Integer and e > 0 and (b.is_Symbol or b.is_Function)):
                if f is sp.S.One:
                    continue
                return False
            d[b] = d.get(b, 0) + int(e)
        powers.append(d)
        for b in d:
            count[b] = count.get(b, 0) + 1
    if content != 1 or any(k == len(powers) for k in count.values()):
        return False
    return any(count[b] == 1 and k == 1 for d in powers for b, k in d.items())


def groups(expr, symbols):
    """{monomial in ``symbols``: its coefficient} of the expanded polynomial ``expr``:
    the terms of ``expand(expr)`` grouped as ``as_independent(*symbols)`` splits them,
    by one walk into a polynomial ring (no ``expand``, which multiplies out through
    SymPy's own Mul).  ``NotPolynomial`` unless ``expr`` is a polynomial with rational
    coefficients in symbols and functions that ``expand`` keeps as they are, over a
    denominator that is a product of such generators (m tan^2 written sin^2/cos^2:
    terms with negative exponents, as ``expand`` writes them); where ``expand`` would
    open a function or its arguments, a root or a denominator that is a sum, the caller
    uses ``expand``.

    >>> x, y, t = sp.symbols("x y theta")
    >>> g = groups((x + y*sp.tan(t))**2, [x])
    >>> g[x**2], g[x], g[1]
    (1, 2*y*tan(theta), y**2*tan(theta)**2)
    """
    gens, roots = _generators(expr)
    if roots or not all(_kept_by_expand(g) for g in gens if g.is_Function):
        raise NotPolynomial(expr)
    walk = _walker(list(gens), {})
    num, den = walk(expr)
    R = walk.ring
    shift = [0] * R.ngens           # a denominator of generators: their exponents
    for f, k in den.items():
        if f not in R.gens:
            raise NotPolynomial(expr)
        shift[R.gens.index(f)] += k
    symbols = set(symbols)
    mono_at = [i for i, g in enumerate(walk.order) if g in symbols or g.free_symbols & symbols]
    parts = {}
    for m, c in num.iterterms():
        m = tuple(a - b for a, b in zip(m, shift))
        key = tuple(m[i] for i in mono_at)
        rest = list(m)
        for i in mono_at:
            rest[i] = 0
        parts.setdefault(key, {})[tuple(rest)] = c
    if any(shift):
        # terms with negative exponents (what expand gives a polynomial over a monomial)
        to = R.domain.to_sympy

        def coefficient(terms):
            return sp.Add(*[sp.Mul(to(c), *[g**k for g, k in zip(walk.order, m) if k])
                            for m, c in terms.items()])
    else:
        def coefficient(terms):
            return R.from_dict(terms).as_expr(*walk.order)
    return {sp.Mul(*[walk.order[i]**k for i, k in zip(mono_at, key)]): coefficient(terms)
            for key, terms in parts.items()}


_TRIG = frozenset(("sin", "cos", "tan", "cot", "sec", "csc", "sinh", "cosh", "tanh", "coth"))


def _kept_by_expand(f):
    """Whether ``expand`` leaves the function ``f`` as it stands: its arguments are atoms,
    or, for a trigonometric or hyperbolic function (which ``expand`` does not open by
    default), sums of products of atoms and their positive integer powers."""
    if all(a.is_Atom for a in f.args):
        return True
    return type(f).__name__ in _TRIG and all(
        all(_monomial(t) for t in sp.Add.make_args(a)) for a in f.args)


def _monomial(t):
    return all(x.is_Atom or x.is_Pow and x.base.is_Atom and x.exp.is_Integer and x.exp > 0
               for x in sp.Mul.make_args(t))


#: a polynomial (its contents out) of more terms than this in more generators than
#: ``FACTOR_GENERATORS_LIMIT`` is not factored further: ``factor`` is for reading, and
#: Wang's algorithm on, say, the 38-term potential of a chain of eight sleighs (17
#: generators) takes a quarter of a second to find it irreducible
FACTOR_TERMS_LIMIT = 24
FACTOR_GENERATORS_LIMIT = 6


_FACTOR_LISTS = {}
_FACTOR_LISTS_LIMIT = 20000


def _factor_list(p):
    """:func:`_factor_list_of`, remembered by the polynomial's terms (exponent vectors and
    coefficients) and its ring: the same polynomial in other generators (the coefficient
    m tan^2 + m of each sleigh of a chain, with its own angle) is factored once, its
    factors then written in the generators at hand."""
    R = p.ring
    key = (R.ngens, R.domain, tuple(sorted(p.items())))
    hit = _FACTOR_LISTS.get(key)
    if hit is None:
        if len(_FACTOR_LISTS) >= _FACTOR_LISTS_LIMIT:
            _FACTOR_LISTS.clear()
        c, factors = _factor_list_of(p)
        hit = _FACTOR_LISTS[key] = (c, [(dict(f.items()), k) for f, k in factors])
    c, factors = hit
    return c, [(R.from_dict(f), k) for f, k in factors]


def _positive_squares(q):
    """Whether ``q`` is a1 x1**2 + a2 x2**2 + ... (+ a0) with every a positive, such as
    sin**2 + cos**2 or tan**2 + 1: positive at every real point, so it has no factor of
    degree one (which vanishes somewhere), and of degree two it is then irreducible."""
    return len(q) > 1 and all(c > 0 and (sum(m) == 0 or sorted(m)[-1] == sum(m) == 2)
                              for m, c in q.iterterms())


def _factor_list_of(p):
    """``p.factor_list()`` over the integers, at once where the answer is plain: once the
    integer and monomial contents are out, a polynomial of degree one in a generator x
    whose x-coefficient is a single term is irreducible (a factor would divide that term,
    and so every term), and so is a sum of positive multiples of squares of single
    generators (:func:`_positive_squares`).  Most coefficients of a derivation are such;
    ``factor_list`` spends half a millisecond on each.  A large polynomial in many generators
    (``FACTOR_TERMS_LIMIT``, ``FACTOR_GENERATORS_LIMIT``) keeps its contents out and
    is left as one factor (a form to read; equal to the input either way)."""
    R = p.ring
    if not p:
        return p.factor_list()
    c, q = p.primitive()
    low = tuple(min(m) for m in zip(*q.itermonoms()))
    if any(low):
        q = q.exquo(R({low: 1}))
    if q.LC < 0:
        c, q = -c, -q
    factors = [(R.gens[i], k) for i, k in enumerate(low) if k]
    if q == 1:
        return c, factors
    for i in range(R.ngens):
        degrees = [m[i] for m in q.itermonoms()]
        if max(degrees) == 1 and degrees.count(1) == 1:
            return c, factors + [(q, 1)]
    if _positive_squares(q):
        return c, factors + [(q, 1)]
    if len(q) > FACTOR_TERMS_LIMIT and sum(map(any, zip(*q.itermonoms()))) \
            > FACTOR_GENERATORS_LIMIT:
        return c, factors + [(q, 1)]
    return p.factor_list()
