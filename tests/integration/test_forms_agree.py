"""Every classical form against every other and against sympy's LagrangesMethod, at
random admissible points in 40-digit arithmetic, on the book's systems and on
generated ones.

Generated systems (seeded, so each is reproducible): n = 3 or 4 coordinates, g = 1
or 2 linear constraints qdot_beta = sum b_beta,sigma(q) qdot_sigma given as
expressions = 0 (scaled by a positive function, so that the multipliers differ from
the solved form's but the motion does not), a mass matrix diag(d) + w w^T
(positive definite for every q) with w depending on the coordinates or constant, a
random potential; half of them of Chaplygin type (nothing depends on the dependent
coordinates), half not.  Nonlinear ones: one Chetaev constraint zdot = b.qdot +
c sqrt(qdot_1^2 + a qdot_2^2) (homogeneous of degree one), compared with the
Routh-Voss form with Chetaev's multipliers and with LagrangesMethod, which takes
the constraint's Jacobian in the velocities (Chetaev's rule) too.
"""

import random

import pytest
import sympy as sp
from sympy.physics.mechanics import dynamicsymbols

from whittaker_teach.forms import NonholonomicSystem, agree, examples
from whittaker_teach.forms.compare import FORMS

t = dynamicsymbols._t


def _fn(rng, qs, allow):
    """A random smooth coefficient: a constant, or a constant plus a term in one of the
    coordinates ``allow``."""
    c = sp.Rational(rng.randint(1, 9), rng.randint(2, 5))
    if not allow or rng.random() < 0.3:
        return c
    q = rng.choice(allow)
    term = rng.choice([sp.sin(q), sp.cos(q), q, q**2 / 2])
    return c + sp.Rational(rng.choice([-1, 1]) * rng.randint(1, 4), rng.randint(2, 5)) * term


def generated(seed, nonlinear=False):
    rng = random.Random(seed)
    n = rng.choice([3, 4])
    g = 1 if (nonlinear or n == 3 and rng.random() < 0.6) else rng.choice([1, 2])
    qs = list(dynamicsymbols(" ".join(f"q{i}" for i in range(1, n + 1))))
    deps, inds = qs[n - g:], qs[:n - g]
    chaplygin = seed % 2 == 0
    allow = inds if chaplygin else qs
    m, k = sp.symbols("m k", positive=True)
    qd = [q.diff(t) for q in qs]
    d = [sp.Rational(rng.randint(1, 6), 2) for _ in qs]
    w = [_fn(rng, qs, allow) if rng.random() < 0.7 else sp.S.Zero for _ in qs]
    T = sum(di * v**2 for di, v in zip(d, qd)) / 2 * m + (sum(wi * v for wi, v in zip(w, qd)))**2 / 2
    V = k * sum(rng.randint(1, 4) * q**2 for q in allow) / 2
    V += rng.randint(0, 2) * sp.cos(rng.choice(allow))
    L = T - V
    if not nonlinear:
        cons = []
        for b in deps:
            expr = b.diff(t) - sum(_fn(rng, qs, allow) * v.diff(t) for v in inds)
            scale = 2 + sp.cos(rng.choice(allow)) if rng.random() < 0.5 else sp.S.One
            cons.append(scale * expr)
        return NonholonomicSystem(L, qs, constraints=cons, dependent=deps,
                                  name=f"generated({seed})")
    a = sp.Rational(rng.randint(1, 5), 2)
    c = _fn(rng, qs, allow)
    phi = sum(_fn(rng, qs, allow) * v.diff(t) for v in inds) + \
        c * sp.sqrt(inds[0].diff(t)**2 + a * inds[1].diff(t)**2)
    return NonholonomicSystem(L, qs, dependent={deps[0].diff(t): phi},
                              name=f"generated-nonlinear({seed})")


BOOK = ["sledge", "sleigh", "rolling_disk", "appell_hamel", "sledge_in_a_well"]


@pytest.mark.parametrize("name", BOOK)
def test_every_form_agrees_with_lagranges_method_on_the_book_systems(name):
    S = examples.catalogue()[name]()
    rec = agree(S)
    assert rec.points == 6
    assert rec.ok, str(rec)
    applied = [r["name"] for r in rec.rows if not r["reason"]]
    expected = set(FORMS) | {"LagrangesMethod"}
    if not S.is_linear:
        expected.discard("BoltzmannHamel")
    assert set(applied) == expected


@pytest.mark.parametrize("seed", range(24))
def test_generated_linear_systems(seed):
    S = generated(seed)
    assert S.is_linear
    if seed % 2 == 0:
        assert S.is_chaplygin
    rec = agree(S, points=4, seed=seed)
    assert rec.points == 4
    assert all(not r["reason"] for r in rec.rows), str(rec)
    assert rec.ok, str(rec)


def test_generated_family_covers_both_kinds():
    kinds = {(generated(s).is_chaplygin, len(generated(s).beta)) for s in range(24)}
    assert (True, 1) in kinds and (False, 1) in kinds and (False, 2) in kinds
    assert any(g == 2 for _, g in kinds)


@pytest.mark.parametrize("seed", range(100, 106))
def test_generated_chetaev_systems(seed):
    S = generated(seed, nonlinear=True)
    assert not S.is_linear
    rec = agree(S, points=4, seed=seed)
    assert rec.ok, str(rec)
    bh = [r for r in rec.rows if r["name"] == "BoltzmannHamel"][0]
    assert "linear" in bh["reason"]


def test_a_wrong_form_is_caught():
    """agree is not vacuous: a Maggi form that forgets the dependent coordinates'
    expressions (the constraint forces then do work) disagrees."""
    from whittaker_teach.forms.maggi import Maggi

    class Wrong(Maggi):
        def _equations(self):
            S = self.system
            E = self._expressions()
            return [E[S.coordinates.index(s)] for s in S.sigma]

    rec = agree(examples.sleigh(), forms=["RouthVoss", Wrong(examples.sleigh())])
    assert not rec.ok
    assert "NOT ALL AGREE" in str(rec)


def test_the_chain_of_sleighs():
    """The benchmark's chain, built with sympy.physics.mechanics: 7 coordinates, 2
    constraints, every form against LagrangesMethod."""
    rec = agree(examples.chain(7), points=3)
    assert rec.ok, str(rec)
    assert len(rec.rows) == len(FORMS) + 1
