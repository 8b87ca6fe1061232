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
