"""dag.diff builds exactly the expression SymPy's diff builds (the derivation relies on it
for identical displayed results), for every piece of real derivations."""

import random

import pytest
import sympy as sp

import whittaker_teach as wt
from whittaker_teach import bench, dag


def _pieces(red):
    S = red.system
    exprs = [red._Omega, red._Lstar, red._vstar, S._Ltilde, S._energy(), *red._eqs,
             *red._Pstar, *red._qdstar, *S._eom()]
    syms = sorted({*red._qp.values(), *red._qpp.values(), *S.q.values(), *S.qd.values(),
                   red._v, red.h}, key=str)
    subs = sorted({e for x in exprs for e in sp.preorder_traversal(x)}, key=sp.default_sort_key)
    return exprs + random.Random(0).sample(subs, min(40, len(subs))), syms


@pytest.mark.parametrize("make", [
    lambda: wt.examples.sledge().reduce("x", -1),
    lambda: wt.examples.cone_particle().reduce("x", +1),
    lambda: wt.examples.charged_particle().reduce("x", -1),
    lambda: wt.ChaplyginSystem(*bench.family(3)[:2], dependent=bench.family(3)[2])
    .reduce("q1", +1),
], ids=["sledge", "cone", "charged", "family3"])
def test_diff_is_sympys_diff(make):
    exprs, syms = _pieces(make())
    memo = {}
    for e in exprs:
        for s in syms:
            assert dag.diff(e, s, memo) == e.diff(s)


def test_diff_other_nodes_fall_back_to_sympy():
    x, y = sp.symbols("x y", real=True)
    f = sp.Function("f")
    for e in (sp.Abs(x * y), sp.sign(x) * x**2, f(x, y) * sp.exp(x), sp.atan2(y, x),
              sp.Piecewise((x, y > 0), (x**2, True)), sp.sqrt(x**2 + 1)**sp.Rational(3, 2)):
        assert dag.diff(e, x) == e.diff(x)
    with pytest.raises(TypeError, match="Symbol"):
        dag.diff(x, f(x))


def test_diff_products_with_zero_derivatives_match_sympy():
    """Zero terms are left out only when no factor can be infinite; with a symbol assumed
    zero or infinite, or an infinity in the expression, SymPy's own terms are built."""
    x, y = sp.symbols("x y")
    z0, inf = sp.Symbol("z0", zero=True), sp.Symbol("w", infinite=True)
    big = sp.expand((1 + x / 3 + y / 5)**12)
    for e in (sp.sqrt(big) * sp.cos(y) / (1 + x), sp.log(y) * inf * x, x * y / z0,
              sp.Pow(big, sp.Rational(3, 2)) * inf, sp.Pow(z0 + y, -1) * x, sp.Pow(inf, y) * x,
              sp.Mul(sp.zoo, x, y, evaluate=False), x**y * sp.sin(x)):
        for s_ in (x, y):
            assert dag.diff(e, s_) == e.diff(s_)


def test_zeroed_is_substitute_on_every_example_and_family():
    """``zeroed`` (the part of (1.4) and (1.26) free of the accelerations) builds the
    very expression ``xreplace`` builds: same tree, same hash."""
    import whittaker_teach as wt
    from whittaker_teach.bench import family
    from whittaker_teach.dag import zeroed
    cases = []
    for ex in wt.examples.catalogue():
        red = ex.reduce()
        S = red.system
        cases += [(red._eqs, [red._qpp[c] for c in red._nus]),
                  (S._eom(), [S.qdd[c] for c in S._sig])]
    for hol in (False, True):
        L, coords, dep = family(4, hol)
        red = wt.ChaplyginSystem(L, coords, dep).reduce(coords[0], 1)
        cases.append((red._eqs, [red._qpp[c] for c in red._nus]))
    for eqs, syms in cases:
        memo = {}
        for e in eqs:
            z, x = zeroed(e, syms, memo), e.xreplace({a: 0 for a in syms})
            assert z == x and sp.srepr(z) == sp.srepr(x)


def test_zeroed_drops_terms_and_keeps_the_sum_canonical():
    from whittaker_teach.dag import zeroed
    a, b, c, x = sp.symbols("a b c x")
    e = 3 + a * x + b * (c + x * a) + sp.sin(a) * x**2 + b**2
    z = zeroed(e, [x])
    assert z == 3 + b * c + b**2 and z == sp.Add(*z.args)
    assert zeroed(x * a, [x]) == 0 and zeroed(x, [x]) == 0 and zeroed(a + b, [x]) == a + b


def test_instances_visits_shared_subtrees_once():
    x, y = sp.symbols("x y")
    s = sp.sin(x + y)
    e = s * sp.cos(s) + sp.cos(x) + s**2
    assert dag.instances(e, sp.cos) == list(dict.fromkeys(
        a for a in sp.preorder_traversal(e) if isinstance(a, sp.cos)))
    assert set(dag.instances(e, sp.sin)) == e.atoms(sp.sin) == {s}
    assert dag.instances(x + y, sp.sin) == []


@pytest.mark.parametrize("seed", range(20))
def test_along_is_the_derivative_along_the_moved_path(seed):
    rng = random.Random(seed)
    x, y, u, w = sp.symbols("x y u w")
    atoms = [x, y, u, x * y, sp.sin(x), sp.cos(x - y), sp.sqrt(1 + x**2), sp.exp(y) + w]
    e = sum(rng.choice(atoms) * rng.choice(atoms) ** rng.randint(-2, 2) for _ in range(4))
    rates = {x: sp.Integer(1), y: u}
    s = sp.Dummy("s")
    want = sp.diff(e.xreplace({x: x + s, y: y + s * u}), s).subs(s, 0)
    got = dag.along(e, rates)
    pt = {x: 0.3, y: -0.7, u: 1.9, w: 0.4}
    assert abs(complex((got - want).evalf(30, subs=pt))) < 1e-20
    assert dag.along(e, {w: u}) == sp.diff(e, w) * u or sp.expand(dag.along(e, {w: u})
                                                                  - sp.diff(e, w) * u) == 0


def test_renamed_is_substitute_on_the_reductions_results():
    """The public results (symbols renamed as functions of q_eps and their derivatives)
    are the expressions ``xreplace`` builds, argument by argument, on the examples and a
    chain of sleighs (sums and products re-sorted, not flattened)."""
    import whittaker_teach as wt
    from whittaker_teach import bench
    from whittaker_teach.dag import renamed
    from whittaker_teach.examples import catalogue
    F = bench.chain(8)
    reds = [wt.ChaplyginSystem(F["L"], F["q"], nonhol_coneqs=F["coneqs"],
                               dependent=F["dependent"]).reduce(F["q"][0], +1)]
    reds += [ex.build().reduce(ex.coordinate, d) for ex in catalogue() for d in (1, -1)]
    for red in reds:
        exprs = list(red._eqs) + list(red._tidy_accelerations().values())
        exprs += [red._Lstar, red._vstar, red._Omega, *red._qdstar, *red._Pstar]
        for e in exprs:
            mine, theirs = renamed(e, red._to_public), e.xreplace(red._to_public)
            assert mine == theirs and sp.srepr(mine) == sp.srepr(theirs)


def test_renamed_refuses_a_sum_as_a_value():
    x, y = sp.symbols("x y")
    with pytest.raises(ValueError):
        dag.renamed(x * y, {x: x + y})


def test_product_with_a_new_factor_is_mul_argument_by_argument(random_factor):
    """The Leibniz rule's products, built without ``Mul.flatten`` where nothing merges,
    are SymPy's ``Mul`` to the order of the arguments: on random products (common
    bases, floats, I, exp, roots of numbers, sums, non-commutative factors) and on
    the rules ``flatten`` applies to two factors and to a number times a sum."""
    rng = random.Random(3)
    x, y = sp.symbols("x y")
    cases = [((sp.Integer(2), x), 1, x + y), ((x, y), 1, sp.Integer(3)),
             ((sp.Integer(3), x, y), 2, 1 / x), ((sp.Integer(2), x + y, y), 2, sp.Rational(1, 2)),
             ((sp.exp(x), y, x), 1, sp.exp(y)), ((sp.sqrt(2), x, y), 1, sp.sqrt(3))]
    while len(cases) < 1500:
        e = sp.Mul(*[random_factor(rng) for _ in range(rng.randint(2, 5))])
        if type(e) is sp.Mul:
            cases.append((e.args, rng.randrange(len(e.args)), random_factor(rng)))
    for args, i, da in cases:
        built = dag._product_with(args, i, da)
        mul = sp.Mul(*(args[:i] + (da,) + args[i + 1:]))
        assert built == mul and type(built) is type(mul) and built.args == mul.args, (args, i, da)


def test_power_rule_is_sympys_product_argument_by_argument(random_factor):
    """The derivative of a power with a constant exponent, b**x / b merged directly, is
    SymPy's ``e * (dbase * x / b)``: random bases (sums, symbols, functions, exp,
    powers, products) and exponents (rational, symbolic, float), random dbase."""
    rng = random.Random(5)
    x, y = sp.symbols("x y")
    exps = [2, 3, -1, -2, sp.Rational(1, 2), sp.Rational(-1, 2), sp.Rational(3, 2), y,
            sp.Float(0.5)]
    z, a = sp.symbols("z a")
    e = z**3                # z / z leaves 3*(a + 1.5) to SymPy, which distributes it
    assert dag._power_rule(e, z * (a + 1.5)).args == (e * (z * (a + 1.5) * 3 / z)).args
    cases = 0
    while cases < 1500:
        e = sp.Pow(random_factor(rng), rng.choice(exps))
        if type(e) is not sp.Pow or not e.base.free_symbols:     # as in a derivative
            continue
        dbase = random_factor(rng)
        cases += 1
        built = dag._power_rule(e, dbase)
        sympys = e * (dbase * e.exp / e.base)
        assert built == sympys and built.args == sympys.args, (e, dbase)


def test_substitute_is_xreplace_argument_by_argument(random_factor):
    """Rebuilt sums and products (without ``flatten`` where nothing combines) are those
    ``xreplace`` builds, on random expressions and replacements."""
    rng = random.Random(11)
    x, y, z = sp.symbols("x y z")
    for _ in range(600):
        e = sp.Add(*[sp.Mul(*[random_factor(rng) for _ in range(rng.randint(1, 4))])
                     for _ in range(rng.randint(1, 4))])
        mapping = {s_: rng.choice([random_factor(rng), sp.S.Zero, sp.S.One, 2 * s_])
                   for s_ in rng.sample([x, y, z], rng.randint(1, 3))}
        built, sympys = dag.substitute(e, mapping), e.xreplace(mapping)
        assert built == sympys and built.args == sympys.args, (e, mapping)


def test_polynomial_in_compares_the_symbol_by_equality_not_identity():
    """Issue 32: once SymPy's cache has dropped Symbol('x') (its LRU holds 1000 entries),
    Symbol('x') is a new object while a cached power still holds the old one; the
    answer must not depend on which object the caller holds."""
    from sympy.core.cache import clear_cache
    old = sp.Symbol("x")
    y = sp.Symbol("y")
    e = old**3 * sp.sqrt(y) / y + 2 * old * y + sp.tan(y)
    clear_cache()
    new = sp.Symbol("x")
    assert new == old and new is not old
    assert dag.polynomial_in(e, new) and dag.polynomial_in(e, old)
    assert dag.zeroed(e, [new]) == e.xreplace({new: 0}) == sp.tan(y)


def test_polynomial_in_after_the_denial_of_service_checks():
    """The order that failed in a full run (tests/unit/test_exercise_checks.py's
    denial-of-service answers, then this file's test): 6000 new symbols flush
    SymPy's symbol cache, and x is built afresh."""
    import sys
    from pathlib import Path
    sys.path.insert(0, str(Path(__file__).parent))
    import test_exercise_checks as checks
    from whittaker_teach.exercises import check
    x, y = sp.symbols("x y")
    e = x**3 * sp.sqrt(y) / y + 2 * x * y + sp.tan(y)
    check("chaplygin-sleigh", None, part="L_star")
    for answer in checks.DOS + checks._dos_objects():
        check("chaplygin-sleigh", answer, part="L_star")
    x, y = sp.symbols("x y")
    assert dag.polynomial_in(x**3 * sp.sqrt(y) / y + 2 * x * y + sp.tan(y), x)
    assert dag.polynomial_in(e, x)


def test_polynomial_in_lets_zeroed_stand_for_xreplace(random_factor):
    """Where ``polynomial_in(e, x)`` holds, ``zeroed(e, [x])`` is ``e.xreplace({x: 0})``
    argument by argument; it fails for x under a root, in a denominator or in a
    function, and for an infinite coefficient (0 * oo is nan, not 0)."""
    x, y = sp.symbols("x y")
    w = sp.Symbol("w", infinite=True)
    assert not dag.polynomial_in(x / (x + y), x)
    assert not dag.polynomial_in(sp.sqrt(x**2 + y) * x, x)
    assert not dag.polynomial_in(sp.sin(x) + x, x)
    assert not dag.polynomial_in(w * x + y, x)
    assert dag.polynomial_in(x**3 * sp.sqrt(y) / y + 2 * x * y + sp.tan(y), x)
    rng = random.Random(19)
    held = 0
    for _ in range(1500):
        e = sp.Add(*[sp.Mul(*[random_factor(rng) for _ in range(rng.randint(1, 4))])
                     for _ in range(rng.randint(1, 4))])
        if dag.polynomial_in(e, x):
            held += 1
            built, sympys = dag.zeroed(e, [x]), e.xreplace({x: sp.S.Zero})
            assert built == sympys and built.args == sympys.args, e
    assert held > 100
