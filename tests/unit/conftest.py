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
