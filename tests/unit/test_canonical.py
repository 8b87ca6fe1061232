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
