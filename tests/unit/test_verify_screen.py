"""The screen that decides whether ``expand`` is worth trying (verify.expand_may_vanish)."""

import pytest
import sympy as sp

import whittaker_teach as wt
from whittaker_teach import verify
from whittaker_teach.verify import expand_may_vanish

a, b, c, t = sp.symbols("a b c theta")
p = sp.Symbol("p", positive=True)
X = a**2 + b


@pytest.mark.parametrize("diff", [
    (a + b)**2 - a**2 - 2*a*b - b**2,
    X**sp.Rational(3, 2) - a**2 * sp.sqrt(X) - b * sp.sqrt(X),
    sp.exp(a + b) - sp.exp(a) * sp.exp(b),
    sp.sin(a * (b + c)) - sp.sin(a * b + a * c),            # equal arguments, written apart
    sp.tan(t) * (1 + sp.tan(t)) - sp.tan(t) - sp.tan(t)**2,
    sp.sqrt(4 * p * a**2) - 2 * sp.sqrt(p) * sp.sqrt(a**2),
])
def test_what_expand_proves_passes_the_screen(diff):
    assert sp.expand(diff) == 0
    assert expand_may_vanish(diff)


@pytest.mark.parametrize("diff", [
    a / (a + b) + b / (a + b) - 1,                           # needs a common denominator
    sp.tan(t)**2 + 1 - 1 / sp.cos(t)**2,                     # needs trigonometry
    sp.sin(t)**2 + sp.cos(t)**2 - 1,
    a + b - c,                                               # simply not zero
])
def test_what_expand_cannot_prove_is_screened_out(diff):
    assert sp.expand(diff) != 0
    assert not expand_may_vanish(diff)


def test_a_known_miss_is_decided_numerically():
    """sqrt(X)**2 made by expand is a case the screen misses (see verify.py): the check
    is then shown numerically, and still holds."""
    lhs, rhs = (sp.sqrt(X) + 1) * (sp.sqrt(X) - 1), X - 1
    assert sp.expand(lhs - rhs) == 0 and not expand_may_vanish(lhs - rhs)
    chk = verify.check_identity("t", "", lhs, rhs, lambda rng: {a: rng.uniform(0.5, 1),
                                                                b: rng.uniform(0.5, 1)})
    assert chk.holds and chk.method == "numeric"


def test_the_screen_is_deterministic_and_survives_poles():
    e = sp.tan(t)**2 + 1 - 1 / sp.cos(t)**2
    assert [expand_may_vanish(e) for _ in range(3)] == [False] * 3
    assert expand_may_vanish(1 / (a - a + sp.Symbol("z", zero=True))) in (True, False)


@pytest.mark.parametrize("name", ["sledge", "offset_sleigh", "projectile"])
def test_the_screen_changes_how_a_check_is_shown_never_whether_it_holds(name, monkeypatch):
    """With and without the screen, every check holds; a check the screen sends to the
    numeric route was shown exactly at most (never the other way round)."""
    ex = wt.examples.get(name)
    screened = {c.label: c for c in ex.build().reduce(ex.coordinate, 1).verify()}
    monkeypatch.setattr(verify, "expand_may_vanish", lambda d: True)
    plain = {c.label: c for c in ex.build().reduce(ex.coordinate, 1).verify()}
    assert screened.keys() == plain.keys()
    for label, chk in screened.items():
        assert chk.holds and plain[label].holds, label
        if chk.method == "exact":
            assert plain[label].method == "exact", label
