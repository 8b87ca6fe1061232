import pytest
import sympy as sp
from sympy.physics.mechanics import dynamicsymbols

import whittaker_teach as wt

T = dynamicsymbols._t


@pytest.fixture(scope="session")
def sledge():
    return wt.examples.sledge()


@pytest.fixture(scope="session")
def sledge_red(sledge):
    return sledge.reduce("x", +1)


# the short names the numerics tests use for the same two objects
@pytest.fixture(scope="session")
def S(sledge):
    return sledge


@pytest.fixture(scope="session")
def red(sledge_red):
    return sledge_red


def numerically_zero(expr, values, tol=1e-25):
    """|expr| at a point (dict), evaluated at 40 digits, is below tol."""
    val = sp.N(expr.xreplace(values), 40)
    return abs(complex(val)) < tol


def random_expression(rng, depth=0):
    """A random factor for the tests that compare a shortcut with SymPy's own
    constructor: symbols, sums, functions, exp, roots of numbers, pi, E, I, floats,
    rationals, infinities, a non-commutative symbol, and powers, products and sums
    of these."""
    x, y, z = sp.symbols("x y z")
    n = sp.Symbol("n", commutative=False)
    atoms = [x, y, z, sp.Symbol("a", positive=True), x + y, x * y + 1, sp.sin(x), sp.cos(y),
             sp.exp(x), sp.sqrt(2), sp.pi, sp.E, sp.I, sp.Float(1.5), sp.Rational(3, 2),
             sp.Integer(-1), sp.Integer(2), n, sp.zoo, sp.oo, sp.nan]
    r = rng.random()
    if depth > 1 or r < 0.5:
        return rng.choice(atoms)
    if r < 0.65:
        return random_expression(rng, depth + 1)**rng.choice(
            [2, -1, sp.Rational(1, 2), sp.Rational(-3, 2), y])
    if r < 0.85:
        return sp.Mul(*[random_expression(rng, depth + 1) for _ in range(rng.randint(2, 4))])
    return sp.Add(*[random_expression(rng, depth + 1) for _ in range(rng.randint(2, 3))])


@pytest.fixture(scope="session")
def random_factor():
    """:func:`random_expression`, for the tests that take it."""
    return random_expression
