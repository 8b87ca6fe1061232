"""The identity checker decides, and can fail."""

import sympy as sp

from whittaker_teach.verify import check_identity, check_zero

x = sp.Symbol("x")


def sample(rng):
    return {x: rng.uniform(0.1, 1.2)}


def test_exact_and_numeric():
    c = check_identity("t", "polynomial", (x + 1)**2, x**2 + 2 * x + 1, sample)
    assert c.holds and c.method == "exact" and c.detail == "common denominator"
    # the walk takes sin(x*(x + 1)) and sin(x**2 + x) for two generators; expand does not
    c = check_identity("t", "expand", sp.sin(x * (x + 1)), sp.sin(x**2 + x), sample)
    assert c.holds and c.method == "exact" and c.detail == "expand"
    c = check_identity("t", "trig", 1 / sp.cos(x)**2, 1 + sp.tan(x)**2, sample)
    assert c.holds and c.method == "numeric" and c.points == 6 and c.max_residual < 1e-30


def test_wrong_identity_fails():
    c = check_identity("t", "wrong", sp.sin(x)**2, 1 - sp.cos(x)**2 + 1e-12, sample)
    assert c.holds is False and c.max_residual > 1e-13
    assert "FAILED" in c.describe()


def test_unevaluable_is_not_verified():
    c = check_zero("t", "pole at every sample", 1 / (x - sp.Rational(1, 2)),
                   lambda rng: {x: 0.5}, exact=False)
    assert c.holds is None and c.status == "not verified"


def test_raw_evaluation_gives_evaluates_bits():
    """The checks evaluate on mpmath's raw numbers (``verify._raw``); at each point the
    value is the very mpf ``evaluate`` gives, and what the raw path cannot do (a root of
    a negative number, a function without a raw form) goes to ``evaluate``."""
    import mpmath
    from whittaker_teach import verify
    y = sp.Symbol("y")
    exprs = [sp.sqrt(x**2 + 1) / (x - y)**3 + sp.tan(x) * sp.exp(-y) - sp.Rational(1, 3),
             sp.log(x + 2) * sp.atan(y) + sp.cosh(x * y)**2 + sp.pi * x,
             sp.sqrt(y - 2) + x,                      # complex at these points
             sp.besselj(0, x) + y]                    # no raw form
    with mpmath.workdps(verify.DPS):
        prec = mpmath.mp.prec
        for k in range(5):
            pt = {x: mpmath.mpf(0.3 + k / 7), y: mpmath.mpf(1.7 - k / 9)}
            raw = {s: v._mpf_ for s, v in pt.items()}
            for e in exprs:
                mine = verify._value(e, dict(pt), raw, prec)
                theirs = verify.evaluate(e, dict(pt))
                assert mine == theirs and type(mine) is type(theirs)
            for e in exprs[:2]:
                assert verify._raw(e, raw, prec) == verify.evaluate(e, dict(pt))._mpf_


def test_definitions_small_sides_are_rebuilt_for_an_exact_attempt():
    d = sp.Function("D")(x)                   # an unevaluated node standing for cos(x) - 1
    c = check_identity("t", "defined", d + 1, sp.cos(x), sample, definitions={d: sp.cos(x) - 1})
    assert c.holds and c.method == "exact" and c.definitions == {}
    assert c.lhs == (sp.cos(x),)


def test_definitions_large_sides_evaluate_each_node_as_its_definition(monkeypatch):
    import whittaker_teach.verify as V
    monkeypatch.setattr(V, "SUBSTITUTE_LIMIT", 0)
    d = sp.Function("D")(x)
    c = check_identity("t", "defined", d * sp.sin(x) + 1, sp.cos(x) * sp.sin(x) + 1, sample,
                       definitions={d: sp.cos(x)})
    assert c.holds and c.method == "numeric" and c.max_residual < 1e-30
    assert c.lhs == (d * sp.sin(x) + 1,) and c.definitions == {d: sp.cos(x)}
    # the node is evaluated as its definition, so a wrong definition fails
    c = check_identity("t", "wrong", d * sp.sin(x) + 1, sp.cos(x) * sp.sin(x) + 1, sample,
                       definitions={d: sp.cos(x) + x / 1000})
    assert c.holds is False and c.max_residual > 1e-6


def test_difference_above_is_a_lower_bound_on_the_built_difference():
    import random

    from whittaker_teach.dag import tree_size
    from whittaker_teach.verify import _difference_above
    y = sp.Symbol("y")
    atoms = [x, y, sp.sin(x), sp.sqrt(1 + x * y), sp.Integer(2), sp.Rational(-1, 3), x * y**2]
    rng, decided = random.Random(5), 0
    for _ in range(300):
        shared = [rng.choice(atoms) * rng.choice(atoms) for _ in range(rng.randint(0, 6))]
        a = sp.Add(*shared, *[rng.choice(atoms) ** rng.randint(1, 3) for _ in range(rng.randint(0, 3))])
        b = sp.Add(*shared, *[rng.randint(1, 3) * rng.choice(atoms) for _ in range(rng.randint(0, 3))])
        for limit in (0, 3, 10, 30):
            if _difference_above(a, b, limit):
                decided += 1
                assert tree_size(a - b, limit) > limit, (a, b, limit)
    assert decided > 100
    big = sp.Add(*[sp.Symbol(f"z{i}") * sp.sin(i * x) for i in range(1, 60)])
    assert not _difference_above(big + x, big, 10)     # the large parts cancel: built
    assert _difference_above(big, -big, 10)


def test_block_evaluation_gives_the_points_bits():
    """The first POINTS points are evaluated together (``verify._vector``: one visit per
    node, a value per point); at each point the value is the very mpf ``evaluate`` gives,
    a root of a negative number goes to ``evaluate`` at that point only, and a pole at one
    point makes only that point fail."""
    import mpmath
    from whittaker_teach import verify
    y = sp.Symbol("y")
    xs = [0.3, 0.5, 1.1, 2.5, 0.7, 1.9]                # x - 1/2 vanishes at point 1

    def smp(rng):
        return {x: xs.pop(0) if xs else rng.uniform(0.1, 3.0), y: rng.uniform(0.5, 2.0)}
    exprs = [sp.sqrt(x**2 + 1) / (x - y)**3 + sp.tan(x) * sp.exp(-y) - sp.Rational(1, 3),
             sp.log(x + 2) * sp.atan(y) + sp.cosh(x * y)**2 + sp.pi * x,
             sp.sqrt(x - 1) + y,                      # complex at the points with x < 1
             sp.besselj(0, x) + y,                    # no raw form
             1 / (2 * x - 1) + y]                     # a pole at point 1
    pts = verify._Points(smp, 0)
    with mpmath.workdps(verify.DPS):
        prec = mpmath.mp.prec
        block = pts.block()
        for e in exprs:
            vec = verify._vector(e, block, prec)
            for i in range(verify.POINTS):
                try:
                    theirs = verify.evaluate(e, dict(pts[i]))
                except ZeroDivisionError:
                    assert e == exprs[-1] and i == 1 and vec[i] is verify._FAIL
                    continue
                mine = verify._at(e, vec, i, pts)
                assert mine == theirs and type(mine) is type(theirs), (e, i)
        assert type(verify._vector(exprs[2], block, prec)) is verify._Marked
        assert type(verify._vector(exprs[0], block, prec)) is list     # clean: no marker


def test_block_and_point_by_point_checks_agree(monkeypatch):
    """A check's residuals are the same whether its first points are evaluated as a block
    or one by one, also when a pole at one of them sends it to a seventh point."""
    from whittaker_teach import verify
    y = sp.Symbol("y")
    lhs = [sp.sqrt(x**2 + 1) * sp.sin(y) / (2 * x - 1), sp.sqrt(x - 1) * y]
    rhs = [sp.sin(y) * sp.sqrt(1 + x**2) / (2 * x - 1) + 1e-28 * x, y * sp.sqrt(x - 1)]

    def smp(rng):
        return {x: rng.choice([0.5, 0.3, 1.7, 2.2]), y: rng.uniform(0.5, 2.0)}
    # seed 2: x = 0.5 (a pole) at point 0, x = 0.3 (complex roots) at points 3 and 4
    block = check_identity("b", "", lhs, rhs, smp, exact=False, seed=2)
    monkeypatch.setattr(verify._Points, "block", lambda self: None)
    single = check_identity("b", "", lhs, rhs, smp, exact=False, seed=2)
    assert block.points == single.points == 6 and block.holds and single.holds
    assert block.max_residual == single.max_residual > 0


def test_at_replaces_symbols_at_evaluation():
    """``at`` checks the sides with symbols replaced by expressions, without building
    them: right and wrong replacements, numeric even where the sides are equal as built,
    and the node free of the replaced symbol taken from the base points' values."""
    from whittaker_teach import verify
    y = sp.Symbol("y")

    def pts(rng):
        return {x: rng.uniform(0.1, 1.2), y: rng.uniform(2, 3)}
    big = sp.sin(x)**3 + sp.exp(x)
    with verify.shared_points():
        c = check_identity("at", "y = x**2", big * x**2, big * y, pts, at={y: x**2})
        assert c.holds and c.method == "numeric" and c.at == {y: x**2}
        assert check_zero("at", "y = x**2 + 1e-9", x**2 - y, pts,
                          at={y: x**2 + sp.Float(1e-9)}).holds is False
        assert check_zero("no at", "y is not x**2", x**2 - y, pts, exact=False).holds is False
        base = verify._points(pts, 0)
        derived = base.derived({y: x**2})
        block, dblock = base.block(), derived.block()
        assert dblock[big] is block[big]          # one evaluation, shared
        assert derived.involves(x**2 - y) and not derived.involves(big)
        assert [float(v) for v in (derived[0][y], base[0][x]**2)] == [float(base[0][x]**2)] * 2


def test_raw_residual_is_the_mpf_objects_residual():
    """The residual in raw arithmetic gives the float the mpf objects give, and None at a
    marker or an infinity (the point is then left to the general path)."""
    import random

    import mpmath
    from whittaker_teach import verify as V
    rng = random.Random(3)
    with mpmath.workdps(V.DPS):
        prec = mpmath.mp.prec
        for _ in range(300):
            pairs = [(mpmath.mpf(rng.uniform(-3, 3)) / 7, mpmath.mpf(rng.uniform(-3, 3)) / 7
                      * (1 + mpmath.mpf(10) ** -rng.randint(1, 40)))
                     for _ in range(rng.randint(1, 4))]
            vecs = [([a._mpf_], [b._mpf_]) for a, b in pairs]
            expected = max(float(abs(a - b) / max(1, abs(a), abs(b))) for a, b in pairs)
            assert V._raw_residual(vecs, 0, prec) == expected
        inf = mpmath.mpf("inf")._mpf_
        assert V._raw_residual([([inf], [inf])], 0, prec) is None
        assert V._raw_residual([([V._NOT_RAW], [inf])], 0, prec) is None


def test_a_block_takes_over_a_samplers_values_only_where_its_symbols_agree():
    """A sampler that offers ``kept`` (the block its own evaluation made, as the energy
    surface's sampler does with the root (1.12)) has those node values taken over by the
    checks' block of the same points, and only when every symbol of ``kept`` has the
    same bits there; the values taken over are the ones the block would compute."""
    import mpmath
    from whittaker_teach import verify
    y = sp.Symbol("y")
    root = sp.sqrt(x**2 + 1) / (x + 3)

    class Sampler:
        def __init__(self, shift=0.0):
            self.kept, self.shift = None, shift

        def __call__(self, rng):
            return {x: rng.uniform(0.1, 2.0), y: rng.uniform(0.5, 1.5)}

        def batch(self, rng, n):
            pts = [self(rng) for _ in range(n)]
            self.kept = {}
            verify.values_at(root, [{x: p[x] + self.shift} for p in pts], self.kept)
            return pts

    with mpmath.workdps(verify.DPS):
        prec = mpmath.mp.prec
        good, bad = verify._Points(Sampler(), 0).block(), verify._Points(Sampler(1e-9), 0).block()
        fresh = verify._Points(lambda rng: Sampler()(rng), 0).block()   # the same points
        assert root in good and root not in bad            # x's values differ in ``bad``
        assert good[root] == verify._vector(root, fresh, prec)
        assert good[y] == fresh[y]                          # symbols are the block's own
    assert check_identity("k", "", root * y, y * root, Sampler(), exact=False).holds
