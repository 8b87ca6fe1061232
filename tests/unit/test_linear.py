"""lu_solve builds the very expressions of SymPy's LUsolve, without products by zero."""

import random

import pytest
import sympy as sp

from whittaker_teach import bench
from whittaker_teach.linear import lu_solve

x, y, z = sp.symbols("x y z")
ATOMS = [x, y, z, sp.sin(x), sp.cos(y) + 2, x * y + 1, sp.Integer(3), sp.Rational(1, 2)]


def _random_matrix(rng, n, zeros):
    return sp.Matrix(n, n, lambda i, j: sp.S.Zero if rng.random() < zeros
                     else rng.choice(ATOMS) * rng.choice(ATOMS) + rng.choice(ATOMS))


@pytest.mark.parametrize("seed", range(30))
def test_same_expressions_as_sympy(seed):
    rng = random.Random(seed)
    n = rng.randint(2, 5)
    M = _random_matrix(rng, n, zeros=0.5)
    rhs = sp.Matrix(n, 1, lambda i, j: rng.choice(ATOMS + [sp.S.Zero]))
    try:
        want = list(M.LUsolve(rhs))
    except (ValueError, sp.matrices.exceptions.NonInvertibleMatrixError):
        with pytest.raises(ValueError):
            lu_solve(M, rhs)
        return
    assert lu_solve(M, rhs) == want


def test_pivoting_and_banded_mass_matrix():
    M = sp.Matrix([[0, x], [y, 1]])                 # the first pivot needs a row swap
    rhs = sp.Matrix([1, z])
    assert lu_solve(M, rhs) == list(M.LUsolve(rhs))
    L, coords, _ = bench.family(5, True)            # tridiagonal couplings b cos(q_i - q_j)
    qd = [sp.Symbol(f"v{i}") for i in range(5)]
    M = sp.Matrix(5, 5, lambda i, j: sp.diff(L.subs({c.diff(): v for c, v in zip(coords, qd)}),
                                             qd[i], qd[j]))
    assert sum(e == 0 for e in M) > 0
    rhs = sp.Matrix(5, 1, lambda i, j: sp.sin(coords[i]))
    assert lu_solve(M, rhs) == list(M.LUsolve(rhs))


def test_singular_is_a_value_error():
    with pytest.raises(ValueError):
        lu_solve(sp.Matrix([[x, x], [1, 1]]), sp.Matrix([1, 2]))
    with pytest.raises(ValueError):
        lu_solve(sp.Matrix([[1, 2, 3]]), sp.Matrix([1]))
