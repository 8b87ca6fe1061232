"""canonical builds the sums, products and powers SymPy builds, argument by argument,
on random expressions (the shortcuts never change a result, only its cost)."""

import random

import sympy as sp

from whittaker_teach import canonical


def test_plain_sum_is_add_argument_by_argument(random_factor):
    """Sums built without ``Add.flatten`` where no terms combine are SymPy's ``Add``:
    random terms (sums among them, numbers, floats, zeros, like terms, I, powers of
    numbers, non-commutative products)."""
    rng = random.Random(7)
    for _ in range(1500):
        terms = [rng.choice([sp.S.Zero, random_factor(rng)]) for _ in range(rng.randint(1, 5))]
        built = canonical._plain_sum(terms)
        if built is not None:
            add = sp.Add(*terms)
            assert built == add and type(built) is type(add) and built.args == add.args, terms


def test_power_of_a_product_is_sympys_power_argument_by_argument(random_factor):
    """A product to an integer power, factor by factor, is SymPy's ``Pow``."""
    rng = random.Random(13)
    cases = 0
    while cases < 1500:
        base = sp.Mul(*[random_factor(rng) for _ in range(rng.randint(2, 4))])
        if type(base) is not sp.Mul:
            continue
        cases += 1
        k = sp.Integer(rng.choice([-3, -2, -1, 2, 3]))
        built, sympys = canonical.power(base, k), sp.Pow(base, k)
        assert built == sympys and built.args == sympys.args, (base, k)


def test_mul_and_add_are_sympys_argument_by_argument(random_factor):
    """``canonical.mul`` and ``canonical.add`` (no ``flatten`` where nothing combines) build SymPy's
    ``Mul`` and ``Add``, two arguments with a rational among them included."""
    rng = random.Random(17)
    for _ in range(1500):
        args = [random_factor(rng) for _ in range(rng.randint(1, 4))]
        for ours, sympys in ((canonical.mul, sp.Mul), (canonical.add, sp.Add)):
            built, ref = ours(*args), sympys(*args)
            assert built == ref and type(built) is type(ref) and built.args == ref.args, args


def test_order_key_sorts_as_basic_compare(random_factor):
    """Lists sorted by ``_order_key`` are sorted as SymPy sorts them (``Basic.compare``):
    random factors and terms, functions of time and their derivatives, dummies,
    symbols with assumptions."""
    from sympy.core.add import _args_sortkey
    rng = random.Random(23)
    t = sp.Symbol("t")
    extra = [sp.Function("x")(t), sp.Function("x")(t).diff(t), sp.Function("y")(t).diff(t, 2),
             sp.Dummy("d"), sp.Symbol("p", positive=True), sp.Symbol("p"), sp.Float(0.5),
             sp.Rational(1, 3), sp.Integer(7), sp.tan(t), sp.Symbol("x")]
    for _ in range(1500):
        items = [rng.choice(extra) if rng.random() < 0.3 else random_factor(rng)
                 for _ in range(rng.randint(2, 6))]
        items = list(dict.fromkeys(items))
        try:
            ours = sorted(items, key=canonical._order_key)
        except canonical._NoKey:
            continue
        assert ours == sorted(items, key=_args_sortkey), items


def _derivation_like(rng, depth=0):
    """A random piece such as a derivation builds: symbols, tan, sums, roots of sums,
    products and powers of these (no floats, no numbers but rationals)."""
    x, y, m, th = sp.symbols("x y m theta")
    atoms = [x, y, m, sp.tan(th), sp.cos(th), sp.sin(x), x + y, m * sp.tan(th)**2 + m,
             sp.sqrt(x**2 + y)]
    r = rng.random()
    if depth > 1 or r < 0.45:
        return rng.choice(atoms)
    if r < 0.6:
        return _derivation_like(rng, depth + 1)**rng.choice(
            [2, -1, sp.Rational(1, 2), sp.Rational(-3, 2), 3])
    parts = [_derivation_like(rng, depth + 1) for _ in range(rng.randint(2, 3))]
    return sp.Mul(*parts) if r < 0.85 else sp.Add(*parts)


def test_sums_with_like_terms_and_a_rational_times_a_sum_are_sympys():
    """Terms with the same part merge as ``Add.flatten`` merges them (coefficients added,
    zeros dropped, each term rebuilt as flatten rebuilds it), and a rational times a sum
    is distributed as ``Mul.flatten``'s rule for two factors does it: argument by
    argument SymPy's, on sums drawn from a small pool so that terms often meet."""
    rng = random.Random(29)
    pool = [_derivation_like(rng) for _ in range(30)]
    merged = 0
    for _ in range(1500):
        terms = []
        for _ in range(rng.randint(1, 7)):
            t, r = rng.choice(pool), rng.random()
            if r < 0.5:
                t = sp.Mul(sp.Rational(rng.randint(-4, 4), rng.randint(1, 3)), t)
            elif r < 0.65:
                t = sp.Add(t, rng.choice(pool))
            terms.append(t)
        built, ref = canonical._plain_sum(terms), sp.Add(*terms)
        assert built is not None and built == ref and built.args == ref.args, terms
        merged += len(ref.args) < sum(len(sp.Add.make_args(t)) for t in terms)
        a = sp.Rational(rng.choice([-3, -2, -1, 2, 3, 5]), rng.choice([1, 2, 7]))
        for args in ((a, ref), (ref, a)):
            built, sympys = canonical.mul(*args), sp.Mul(*args)
            assert built == sympys and type(built) is type(sympys), args
            assert built.args == sympys.args, args
    assert merged > 500                  # the merging path was taken, often


def test_sub_and_negated_are_sympys(random_factor):
    """``sub(a, b)`` is ``a - b`` and ``negated(a)`` is ``-a``, argument by argument, on
    random expressions and on derivation-like sums whose terms meet."""
    rng = random.Random(31)
    pool = [_derivation_like(rng) for _ in range(20)]
    for _ in range(1500):
        make = random_factor if rng.random() < 0.5 else (
            lambda r: sp.Add(*[r.choice(pool) * r.choice([1, -2, sp.Rational(1, 3)])
                               for _ in range(r.randint(1, 4))]))
        a, b = make(rng), make(rng)
        for built, sympys in ((canonical.sub(a, b), a - b), (canonical.negated(a), -a)):
            assert built == sympys and type(built) is type(sympys), (a, b)
            assert built.args == sympys.args, (a, b)


def test_a_number_times_one_sum_left_by_merged_powers_is_distributed_as_sympy_does():
    """Powers of one sum that merge to the sum itself, times a number, leave a number times
    a sum, which ``Mul.flatten`` distributes; ``mul`` and ``_plain_product`` give SymPy's
    expression, argument by argument (the derivative of a spring's (x2 - x1)**2)."""
    rng = random.Random(37)
    pool = [_derivation_like(rng) for _ in range(20)]
    spread = 0
    for _ in range(800):
        s = sp.Add(*[rng.choice(pool) * rng.choice([1, -1, 2, sp.Rational(1, 3)])
                     for _ in range(rng.randint(2, 3))])
        if type(s) is not sp.Add:
            continue
        k = rng.choice([2, 3, sp.Rational(3, 2)])
        factors = [sp.Rational(rng.choice([-2, 3, 5]), rng.choice([1, 2])), s**k, s**(1 - k)]
        if rng.random() < 0.3:
            factors.append(rng.choice(pool))
        rng.shuffle(factors)
        built, sympys = canonical.mul(*factors), sp.Mul(*factors)
        assert built == sympys and type(built) is type(sympys), factors
        assert built.args == sympys.args, factors
        ours = canonical._plain_product([f for a in factors for f in sp.Mul.make_args(a)])
        spread += type(sympys) is sp.Add and ours is not None     # distributed here
    assert spread > 200


def test_one_argument_is_returned_as_built():
    """``Add`` and ``Mul`` of one argument (the identities dropped) return it as it is,
    even a product or sum SymPy would build otherwise (factor's 1/2*(x + 2*y))."""
    x, y = sp.symbols("x y")
    half = sp.Mul(sp.Rational(1, 2), x + 2 * y, evaluate=False)
    twice = sp.Add(x, x, evaluate=False)
    for built, sympys in ((canonical.mul(half, 1), sp.Mul(half, 1)),
                          (canonical.add(twice, 0), sp.Add(twice, 0)),
                          (canonical.add(half), sp.Add(half)), (canonical.mul(twice), twice)):
        assert built is sympys
