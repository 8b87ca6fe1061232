"""The reduction's checks fail when what they check is wrong.

Since the checks at (1.12) evaluate their sides on the energy surface (the sampled
qdot_eps is the value of the root (1.12) there) instead of on the starred expressions,
and (1.26) and [1.26b] replace the accelerations at evaluation (``check_identity``'s
``at``), each is shown here to catch a wrong root, a wrong L*, a wrong equation and a
wrong q'': a result changed by a part in a thousand makes its check fail, and only
the checks that depend on it.
"""

import pytest
import sympy as sp

import whittaker_teach as wt
from whittaker_teach import bench

SYSTEMS = {
    "sledge": lambda: wt.examples.sledge().reduce("x"),
    "chain4": lambda: _chain(4),       # two equations (1.26): q'' by LU of (1.26)
    "chain8": lambda: _chain(8),       # five: q'' read from the accelerations of (1.4)
}


def _chain(n):
    F = bench.chain(n)
    return wt.ChaplyginSystem(F["L"], F["q"], nonhol_coneqs=F["coneqs"],
                              dependent=F["dependent"]).reduce(F["q"][0], +1)


def _failed(red):
    report = red.verify()
    return {c.label for c in report if c.holds is False}


@pytest.fixture(params=sorted(SYSTEMS))
def red(request):
    return SYSTEMS[request.param]()


def test_the_unchanged_reduction_verifies(red):
    assert red.verify().ok


def test_a_wrong_root_fails_1_12(red):
    red._vstar = red._vstar * sp.Rational(1001, 1000)
    assert "1.12" in _failed(red)


def test_a_wrong_reduced_lagrangian_fails_its_checks(red):
    qp = next(iter(red._qp.values()))
    red._Lstar = red._Lstar + qp**2 / 1000
    failed = _failed(red)
    assert {"1.16", "1.17", "1.19", "1.21"} <= failed, failed
    assert "1.12" not in failed and "1.26b" not in failed


def test_a_wrong_equation_fails_1_26(red):
    q = red.system.q[red._nus[0]]
    red._eqs = [red._eqs[0] + q / 1000] + red._eqs[1:]
    red._cache.pop("tidy", None)
    assert "1.26" in _failed(red)


def test_a_wrong_acceleration_fails_1_26b(red):
    acc = dict(red._tidy_accelerations())
    first = next(iter(acc))
    acc[first] = acc[first] * sp.Rational(1001, 1000) + sp.Rational(1, 1000)
    red._cache["acc_tidy"] = acc
    failed = _failed(red)
    assert "1.26b" in failed and "1.26" not in failed, failed


def test_sampled_points_lie_on_the_energy_surface():
    """qdot_eps at a sampled point is the value of (1.12) there, equal to the drawn
    qdot_eps up to rounding."""
    import random

    from whittaker_teach.verify import value_at
    red = SYSTEMS["chain4"]()
    rng = random.Random(3)
    for _ in range(3):
        pt = red._sample(rng)
        v = pt[red._v]
        assert v == value_at(red._vstar, pt)
        assert abs(v - pt[red._drawn]) < 1e-35 * abs(v)
        assert pt[red.system.qd[red._eps]] == v


@pytest.mark.parametrize("name", ["sledge", "chain8"])
def test_wrong_accelerations_fail_the_energy_integral_1_11(name, monkeypatch):
    """(1.11) is checked with the accelerations of (1.4) substituted (small systems) or
    replaced at evaluation (large ones): wrong accelerations fail it either way."""
    S = SYSTEMS[name]().system
    chk = S._check_energy_rate()
    assert chk.holds and bool(chk.at) == (name == "chain8")      # the route taken
    right = S._accelerations()
    first = next(iter(right))
    wrong = {**right, first: right[first] * sp.Rational(1001, 1000)}
    monkeypatch.setattr(S, "_accelerations", lambda: wrong)
    assert S._check_energy_rate().holds is False
