"""The one-walk polynomial forms (polywalk) give what SymPy's own functions give."""

import pytest
import sympy as sp

import whittaker_teach as wt
from whittaker_teach import polywalk, rewrite
from whittaker_teach.polywalk import NotPolynomial

a, b, c, t = sp.symbols("a b c theta")
m = sp.Symbol("m", positive=True)
A = 2 * c - a**2 * t**2                 # the sledge's energy factor 2(h - V)
B = b * t**2 + m * sp.tan(t)**2 + m


def _same_fraction(mine, expr):
    """``mine`` is ``cancel``'s numerator and denominator, up to their common sign."""
    num, den = sp.fraction(sp.cancel(expr))
    return mine in ((num, den), (-num, -den))


@pytest.mark.parametrize("expr", [
    2 * a**2 * b + 4 * a * b + 2 * b,
    -a * b + a,
    a / 2 + b / 3,
    sp.tan(t)**2 * a + a,
    -3 * a,
    a**2 - b**2,
    sp.Rational(-1, 2) * a * b - a / 2,
    (a + b)**3 * (a - b) * m,
    sp.cos(a - b) * m + sp.cos(a - b) * b,
    a / (a + b),                                  # fractions: numerator and denominator
    m * sp.sin(t)**2 / sp.cos(t)**2 + m,
    m * sp.sin(t)**3 / sp.cos(t)**3 + m * sp.sin(t) / sp.cos(t),
    a / (a + b) + b / (a + b),
    1 / (a**2 - b**2) + 1 / (a - b),
    (2 * a + 2 * b) / (3 * a**2 - 3 * b**2) - a / (4 * b**2 * (a + b)**2),
])
def test_factor_is_sympys(expr):
    assert polywalk.factor(expr) == sp.factor(expr)


@pytest.mark.parametrize("expr", [sp.sqrt(a + b) * a, 0.5 * a, sp.I * a,
                                  a**c, sp.pi * a])
def test_factor_leaves_what_it_does_not_treat(expr):
    with pytest.raises(NotPolynomial):
        polywalk.factor(expr)


def test_factor_of_a_number_is_the_number():
    assert polywalk.factor(sp.Integer(6)) == 6


@pytest.mark.parametrize("expr", [
    a / (a + b) + b / (a + b),
    (a**2 - b**2) / (a - b),
    1 / (2 * a) - 1 / (2 * b),
    a / sp.sqrt(A) / sp.sqrt(A) + a * t**2 / A,          # the root multiplies out
    sp.sqrt(A) * (sp.tan(t)**2 + 1) / sp.sqrt(A),
    (m * sp.tan(t)**2 + m) * A**sp.Rational(3, 2) / (A * sp.sqrt(A) * m),
])
def test_fraction_is_cancels(expr):
    assert _same_fraction(polywalk.fraction(expr), expr)


def test_fraction_of_the_sledges_acceleration_is_the_old_route():
    """q'' of the sledge, solved from (1.26): the one-walk form is exactly the form of
    ``together`` followed by a polynomial gcd (the route it replaces)."""
    red = wt.examples.sledge().reduce("x", +1)
    (qpp,) = red._accelerations().values()
    num, den = sp.fraction(sp.together(qpp))
    ring, (p, q) = sp.polys.rings.sring([num, den])
    assert polywalk.fraction(qpp) == polywalk.lowest_terms(p, q)
    assert all(x.exp.is_Integer for x in polywalk.fraction(qpp)[1].atoms(sp.Pow))


@pytest.mark.parametrize("expr", [
    sp.sqrt(a + b) / sp.sqrt(a**2 + b),          # a root left below
    a / (a - a),
])
def test_fraction_leaves_what_it_cannot_reduce(expr):
    with pytest.raises((NotPolynomial, ZeroDivisionError)):
        polywalk.fraction(expr)


def test_a_root_inside_a_roots_base_is_one_more_generator():
    e = sp.sqrt(sp.sqrt(a) + b) / (a - b) + 1 / (b - a)
    num, den = polywalk.fraction(e)
    assert sp.expand(num * (a - b) - den * (sp.sqrt(sp.sqrt(a) + b) - 1)) == 0


def test_cancelled_falls_back_to_sympy_where_the_walk_stops():
    """A root left in the denominator: ``rewrite._cancelled`` takes SymPy's route and the
    result is still the same rational function."""
    e = sp.sqrt(a + b) / sp.sqrt(a**2 + b) + a
    num, den = rewrite._cancelled(e)
    assert sp.simplify(num / den - e) == 0


def test_the_ops_bound_is_never_below_count_ops():
    """``rewrite._ops_above`` skips ``count_ops`` when an upper bound counted in its walk
    is within the limit: the bound is never below ``count_ops`` (the sledge's results
    and 2000 random expressions), and ``_ops_above`` answers as ``count_ops`` would."""
    import random
    red = wt.examples.sledge().reduce("x", +1)
    exprs = list(red._eqs) + list(red._accelerations().values()) + [
        sp.Rational(-1, 3), -a / b, -a - b, a**-2 * b**sp.Rational(-3, 2) / 7, -1 / (a + b)]
    rng = random.Random(1)
    atoms = [a, b, c, sp.Rational(-1, 3), sp.Integer(2), sp.sqrt(a), sp.tan(b), -a, 1 / (a + b)]
    for _ in range(2000):
        e = rng.choice(atoms)
        for _ in range(rng.randint(1, 6)):
            x, op = rng.choice(atoms), rng.choice("+-*/p")
            e = {"+": lambda: e + x, "-": lambda: e - x, "*": lambda: e * x, "/": lambda: e / x,
                 "p": lambda: e ** rng.choice([2, -1, sp.Rational(1, 2), -2])}[op]()
        exprs.append(e)
    for e in exprs:
        ops = sp.count_ops(e)
        for limit in (ops - 1, ops, 2 * ops + 5):
            assert rewrite._ops_above(e, limit) == (ops > limit) or rewrite.expanded_terms(
                e, rewrite.SWELL_LIMIT) > rewrite.SWELL_LIMIT



@pytest.mark.parametrize("expr", [
    -a**2 * b * (sp.tan(t)**2 + 1),               # monomial content, then degree one in b?
    2 * c * sp.tan(t) - a**2 * t**2 * sp.tan(t) - a**2 * t,
    6 * a * b + 4 * a,
    a**2 - b**2,                                  # no generator of degree one: factor_list
    a**2 * sp.sin(t)**2 + a**2 * sp.cos(t)**2,     # a**2 out, then positive squares
    3 * sp.tan(t)**2 + 5,
    a**2 + 2 * b**2 + c**2 + 4,
    a**2 + 2 * a * b + b**2,                      # a square, not a sum of squares
    a**2 + b**2 - 1,
    a**4 + 4 * b**4,                              # reducible (Sophie Germain): not squares
    (a * b + 1) * (a + b),
    -7 * a**3,
    -4 * a * b,
])
def test_the_factor_list_shortcut_is_factor_list(expr):
    """Where the shortcut answers (degree one in a generator whose coefficient is one
    term), it answers what ``factor_list`` answers."""
    from sympy.polys.domains import ZZ
    from sympy.polys.rings import sring
    ring, p = sring(expr, domain=ZZ)
    (c1, f1), (c2, f2) = polywalk._factor_list(p), p.factor_list()
    assert c1 == c2 and {f.as_expr(): k for f, k in f1} == {f.as_expr(): k for f, k in f2}


def test_generators_are_sorted_as_sympy_sorts_them():
    from sympy.polys.polyutils import _sort_gens
    x1, x10, x2, z = sp.symbols("x1 x10 x2 z")
    gens = [sp.tan(t), z, x10, sp.sqrt(a + b), x2, m, x1, sp.cos(a - b), t, a, c, b,
            sp.Dummy("a"), sp.Function("q")(t)]
    order = polywalk._walker(gens, {}).order     # then placeholders to a multiple of 4
    assert order[:len(gens)] == list(_sort_gens(gens))
    assert len(order) % polywalk.RING_STEP == 0 and len(order) - len(gens) < polywalk.RING_STEP


@pytest.mark.parametrize("base", [m * b**2 + m, A, a / 2 + b / 2, 2 * a + 4 * b, a + b,
                                  a * (b + 1) + a * c, sp.sqrt(a) * b + sp.sqrt(a)])
def test_content_screen_misses_no_split(base):
    """``factor_terms`` is skipped only where it could not split the root of the base."""
    from whittaker_teach.polywalk import _has_content
    if not _has_content(base):
        assert sp.sqrt(sp.factor_terms(base)).is_Pow


# ----------------------------------------------------------------- vanishes
x, y = sp.symbols("x y", positive=True)


@pytest.mark.parametrize("expr", [
    x / (x + y) + y / (x + y) - 1,
    sp.sqrt(x + y) * (x + y + 1) - sp.sqrt(x + y)**3 - sp.sqrt(x + y),
    sp.sqrt(2) * (sp.sqrt(2) * a + 1) - 2 * a - sp.sqrt(2),
    (sp.sqrt(A) + 1)**2 - A - 2 * sp.sqrt(A) - 1,
    # equal bases written apart: one generator (the sledge's (3.7))
    sp.sqrt(A) * sp.sqrt(b + m * (sp.tan(t)**2 + 1)) - sp.sqrt(A) * sp.sqrt(B - b * t**2 + b),
    # a root inside another root's base
    sp.sqrt(x + sp.sqrt(y))**2 * sp.sqrt(y) - x * sp.sqrt(y) - y,
    a / (sp.sqrt(A) + 1) - a * (sp.sqrt(A) - 1) / (A - 1),
])
def test_vanishes_proves_rational_identities(expr):
    assert expr != 0 and polywalk.vanishes(expr)


@pytest.mark.parametrize("expr", [
    sp.sin(t)**2 + sp.cos(t)**2 - 1,           # needs a relation between generators
    x / (x + y) - 1,
    sp.sqrt(a * (a + 1)) - sp.sqrt(a) * sp.sqrt(a + 1),     # false for a < -1
    a**c - a**c * a / a + 1,                    # a symbolic exponent: not treated
    0.5 * a - a / 2 + a,
    # the numerator vanishes but a denominator factor is 0 once r**2 = x
    sp.Mul(0, 1 / ((sp.sqrt(x) + 1) * (sp.sqrt(x) - 1) - x + 1), evaluate=False),
])
def test_vanishes_says_false_when_not_shown(expr):
    assert polywalk.vanishes(expr) is False


def test_vanishes_never_claims_a_nonzero_expression():
    """Sums of random products of the building blocks of a derivation: whenever
    ``vanishes`` says True, the expression is 0 at random points to 40 digits; and it
    says True on each difference of an expression and its ``expand``."""
    import random
    import mpmath
    rng = random.Random(7)
    blocks = [x, y, a, sp.sqrt(x + y), 1 / (x + 1), sp.tan(a), sp.sqrt(2), (x + y)**-2,
              sp.sqrt(x * y + 1), sp.Rational(3, 2)]
    syms = [x, y, a]
    for _ in range(120):
        e = sum(sp.Mul(*rng.sample(blocks, 3)) * rng.choice([-1, 2, sp.Rational(1, 3)])
                for _ in range(rng.randint(1, 4)))
        assert polywalk.vanishes(e - sp.expand(e))
        if polywalk.vanishes(e):
            with mpmath.workdps(40):
                for _ in range(3):
                    pt = {s: rng.uniform(0.2, 2) for s in syms}
                    assert abs(sp.N(e.subs(pt), 40)) < 1e-30


# ----------------------------------------------------------------- groups
def _expand_groups(expr, symbols):
    """The grouping ``rewrite.collected`` made from ``expand`` (its fallback)."""
    out = {}
    for term in sp.Add.make_args(sp.expand(expr)):
        coeff, mono = term.as_independent(*symbols, as_Add=False)
        out.setdefault(mono, []).append(coeff)
    return {mono: sp.Add(*c) for mono, c in out.items()}


def _family_equations():
    from whittaker_teach.bench import family
    for hol in (False, True):
        L, coords, dep = family(3, hol)
        S = wt.ChaplyginSystem(L, coords, dependent=dep)
        L_qd = [S._d(S._Ltilde, S.qd[c]) for c in S._sig]
        yield from ((e, S._velocity_symbols()) for e in S._eom() + [S._energy()] + L_qd)


def test_groups_are_expands_on_the_families():
    """(1.4) and the energy of the scale families (cos(q_i - q_j), cos(q)**2): the same
    grouped coefficients as ``expand`` gives, as expressions."""
    n = 0
    for expr, symbols in _family_equations():
        assert polywalk.groups(expr, symbols) == _expand_groups(expr, symbols)
        n += 1
    assert n == 12          # 2 + 3 equations of (1.4), the energies, 2 + 3 momenta


@pytest.mark.parametrize("expr", [
    (a + b * sp.tan(t))**2 * (c - a) + sp.cos(a - b) * a * c,
    sp.Rational(1, 2) * m * (a * sp.sin(t) + b)**3 - sp.sin(2 * t) * a,
    (a * b + 1) * (a - c)**2 / 3,
])
def test_groups_are_expands(expr):
    assert polywalk.groups(expr, [a, b]) == _expand_groups(expr, [a, b])


@pytest.mark.parametrize("expr", [
    m * a**2 * sp.sin(t)**2 / sp.cos(t)**2 + m * a**2 + b**2,      # tan written sin/cos
    (a + b * sp.sin(t))**2 / (c * sp.cos(t)**3) - a / c + b * c,
    a * b / sp.sin(t) + a * sp.sin(t) / b,                          # a symbol below
])
def test_groups_over_a_denominator_of_generators_are_expands(expr):
    mine, theirs = polywalk.groups(expr, [a, b]), _expand_groups(expr, [a, b])
    assert mine == theirs
    assert all(sp.srepr(mine[k]) == sp.srepr(theirs[k]) for k in theirs)


@pytest.mark.parametrize("expr", [
    sp.exp(a + b) * a,                 # expand opens exp(a + b)
    sp.cos(a * (b + 1)) * a,           # and the argument a*(b + 1)
    a / (a + b), sp.sqrt(a) * b, 0.5 * a,
])
def test_groups_leave_what_expand_would_open(expr):
    with pytest.raises(NotPolynomial):
        polywalk.groups(expr, [a])


def test_plainly_irreducible_sums_are_what_factor_gives_back():
    """The ring-free shortcut of ``factor`` answers as sympy.factor does (random sums of
    monomials; those it takes are returned as they stand, srepr-equal to factor's)."""
    import random
    gens = sp.symbols("a b c d e") + (sp.sin(t), sp.cos(t))
    rng, taken = random.Random(1), 0
    for _ in range(400):
        e = sp.Add(*[rng.choice([1, -1, 2, -3, 4, -6]) * sp.Mul(*[
            rng.choice(gens)**rng.randint(1, 2) for _ in range(rng.randint(0, 3))])
            for _ in range(rng.randint(2, 6))])
        assert sp.srepr(polywalk.factor(e)) == sp.srepr(sp.factor(e)), e
        taken += polywalk._plainly_irreducible(e)
    assert 100 < taken < 390                 # both routes were taken


def test_collected_shortcut_for_a_sum_free_of_the_symbols(monkeypatch):
    """``collected`` of a sum of monomials free of its symbols skips the ring walk into
    groups; the result is the one the walk gives (random sums, and the examples' mass
    and potential coefficients)."""
    import random

    from whittaker_teach import rewrite
    gens = sp.symbols("a b c d e") + (sp.sin(t), sp.cos(t))
    rng, cases = random.Random(2), []
    for _ in range(150):
        cases.append(sp.Add(*[rng.choice([1, -1, 2, -3, sp.Rational(1, 2)]) * sp.Mul(*[
            rng.choice(gens)**rng.randint(1, 3) for _ in range(rng.randint(0, 3))])
            for _ in range(rng.randint(2, 6))]))
    for name in ("sledge", "offset_sleigh", "rolling_disk", "kepler"):
        S = getattr(wt.examples, name)()
        cases += [S._energy(), *[sp.expand(e) for e in S._eom()]]
    w = [sp.Symbol("w")]
    fast = [rewrite.collected(e, w) for e in cases]
    taken = sum(rewrite._expanded_free_of(e, w) for e in cases)
    rewrite._FACTORED.clear()
    monkeypatch.setattr(rewrite, "_expanded_free_of", lambda e, s: False)
    slow = [rewrite.collected(e, w) for e in cases]
    assert [sp.srepr(a) for a in fast] == [sp.srepr(b) for b in slow]
    assert taken > 50


def test_sums_of_positive_squares_are_irreducible_as_factor_list_says():
    from sympy.polys.domains import ZZ
    from sympy.polys.rings import ring
    import random
    R, *xs = ring("x0:4", ZZ)
    rng = random.Random(2)
    for _ in range(300):
        p = R(rng.randint(0, 3)) + sum(rng.randint(1, 5) * x**2 for x in rng.sample(xs, 2))
        if polywalk._positive_squares(p):
            c, factors = p.factor_list()
            assert len(factors) == 1 and factors[0][1] == 1, p


@pytest.mark.parametrize("expr", [
    (a + b * sp.tan(t))**2 * (c - a) + sp.cos(a - b) * a * c,
    m * (2 * sp.sin(t)**2 / sp.cos(t)**2 + 2) / 2 + m * (a * b + 1)**2 / 2,   # the chain's 2 A2
    -c * (b - a)**2 - 3 * (a - t)**2 + 2 * m,                                # 2 (h + A0)
    sp.exp(a + b) * a, a / (a + b), sp.sqrt(a) * (a + b), 0.5 * a * (a + 1), sp.S.Zero,
])
def test_expanded_is_expand_argument_by_argument(expr):
    """``rewrite.expanded`` (a ring walk where it applies, else ``expand``) is expand's
    expression, to the order of the arguments."""
    assert sp.srepr(rewrite.expanded(expr)) == sp.srepr(sp.expand(expr))
