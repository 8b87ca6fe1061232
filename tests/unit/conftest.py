import os
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest
import sympy as sp
from sympy.physics.mechanics import dynamicsymbols

import whittaker_teach as wt

T = dynamicsymbols._t
ROOT = Path(__file__).resolve().parents[2]

#: a meta-path finder that makes numpy, scipy and matplotlib unimportable
NUMERICS_BLOCKER = textwrap.dedent(r"""
    import importlib.abc, sys
    class Block(importlib.abc.MetaPathFinder):
        def find_spec(self, name, path=None, target=None):
            if name.split(".")[0] in ("numpy", "scipy", "matplotlib"):
                raise ModuleNotFoundError(name, name=name)
            return None
    sys.meta_path.insert(0, Block())
""")


@pytest.fixture
def run_without_numerics():
    """Run ``code`` in a fresh Python where numpy, scipy and matplotlib cannot be
    imported (as in the browser's Pyodide) and return its stdout; fail with its stderr."""
    def run(code, timeout=600):
        env = dict(os.environ, PYTHONHASHSEED="0",
                   PYTHONPATH=os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")]))
        r = subprocess.run([sys.executable, "-c", NUMERICS_BLOCKER + textwrap.dedent(code)],
                           cwd=ROOT, env=env, capture_output=True, text=True, timeout=timeout)
        assert r.returncode == 0, r.stderr[-3000:]
        return r.stdout
    return run


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
