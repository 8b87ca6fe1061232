"""Property-based tests: random Chaplygin systems, reduced and checked.

Each example is a random system with eps independent coordinates q1..q_eps and g
dependent ones y1..y_g:

* T = 1/2 qdot^T M(q) qdot over ALL velocities (dependent ones included), with
  M = D + symmetric off-diagonal entries c_ij f_ij(q), f_ij in {1, cos(q1),
  1 + q2^2}, and D_ii = d_i + sum_j |c_ij| max|f_ij| (with max|1 + q2^2| taken
  as 1 + q2^2 itself), so M is strictly diagonally dominant, hence positive
  definite, for every q; M never depends on the dependent coordinates;
* linear constraints y_b-dot = sum_i c_bi(q_sigma) qdot_i, c_bi an integer times
  one of 1, q1, q2^2, sin(q1), cos(q2);
* a polynomial potential V(q_sigma);
* optionally a gyroscopic term B q1 qdot2 (B a real symbol, sampled with either sign
  in the chain-rule check).

For each: ``red = sys.reduce(q_eps, direction)`` with a random independent q_eps
and direction, ``red.verify().ok`` must hold, and at two random states the
reduced accelerations must agree with the time-domain ones by the chain rule
q''_nu = (qddot_nu qdot_eps - qdot_nu qddot_eps)/qdot_eps^3 (h = the energy of
the state; coordinates here range over (-1.2, 1.2), beyond the library's own
sampling box).

Cost.  The library solves (1.4) and (1.26) without rewriting (the readable
one-fraction form of ``accelerations()`` is tried only on small expressions), so
systems with three independent coordinates, state-dependent coefficients and a
gyroscopic term reduce and verify in about a second.  Both families use
derandomize=True, so the run is deterministic.
"""

import random

import mpmath
import numpy as np
import sympy as sp
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from sympy.physics.mechanics import dynamicsymbols

import whittaker_teach as wt

from .numbers import DPS, TOL, close, num, rat  # noqa: F401

t = dynamicsymbols._t

SETTINGS = dict(deadline=None, derandomize=True, database=None, print_blob=False,
                suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])

# ------------------------------------------------------------------ building
FACTORS = ("1", "cos(q1)", "1+q2^2")           # multipliers of the off-diagonal entries
CONSTRAINT_BASIS = ("1", "q1", "q2^2", "sin(q1)", "cos(q2)")


def _factor(name, q):
    q1, q2 = q[0], q[1]
    return {"1": (sp.S.One, sp.S.One),
            "cos(q1)": (sp.cos(q1), sp.S.One),
            "1+q2^2": (1 + q2**2, 1 + q2**2)}[name]


def _basis(name, q):
    q1, q2 = q[0], q[1]
    return {"1": sp.S.One, "q1": q1, "q2^2": q2**2, "sin(q1)": sp.sin(q1),
            "cos(q2)": sp.cos(q2)}[name]


def build(spec):
    """A ChaplyginSystem from a spec of plain data (so hypothesis prints it readably)."""
    n_ind, n_dep = spec["n_ind"], spec["n_dep"]
    q = [dynamicsymbols(f"q{i + 1}") for i in range(n_ind)]
    y = [dynamicsymbols(f"y{j + 1}") for j in range(n_dep)]
    coords = q + y
    n = len(coords)
    M = sp.zeros(n, n)
    bound = [sp.S.Zero] * n
    for (i, j), (num, fac) in zip(_pairs(n), spec["offdiag"]):
        c = sp.Rational(num, 4)
        f, w = _factor(fac, q)
        M[i, j] = M[j, i] = c * f
        bound[i] += abs(c) * w
        bound[j] += abs(c) * w
    for i in range(n):
        M[i, i] = spec["diag"][i] + bound[i]
    qd = sp.Matrix([c.diff(t) for c in coords])
    T = sp.expand((qd.T * M * qd)[0, 0] / 2)
    a1, a2, a12, a3 = spec["V"]
    V = a1 * q[0]**2 + a2 * q[1]**2 + a12 * q[0] * q[1] + a3 * q[0]**3
    if n_ind > 2:
        V += spec["V3"] * q[2]**2
    L = T - V
    if spec["gyro"]:
        L += sp.Symbol("B", real=True) * q[0] * q[1].diff(t)     # B of either sign
    dep = {}
    for b, row in enumerate(spec["constraints"]):
        dep[y[b].diff(t)] = sum((k * _basis(base, q) * qi.diff(t)
                                 for (k, base), qi in zip(row, q)), sp.S.Zero)
    system = wt.ChaplyginSystem(L, coords, dependent=dep, name="random")
    return system, q[spec["eps"]]


def _pairs(n):
    return [(i, j) for i in range(n) for j in range(i + 1, n)]


@st.composite
def rich_specs(draw, n_ind=2, max_dep=2):
    """eps = n_ind, g in 0..max_dep: every ingredient of the family: one off-diagonal
    entry of M carries a state-dependent factor and one constraint coefficient is
    state-dependent; the other entries and coefficients are rational constants."""
    n_dep = draw(st.integers(0, max_dep))
    n = n_ind + n_dep
    pairs = _pairs(n)
    special = draw(st.integers(0, len(pairs) - 1))
    special_factor = draw(st.sampled_from(FACTORS))
    offdiag = [(draw(st.integers(-2, 2)), special_factor if k == special else "1")
               for k in range(len(pairs))]
    diag = [draw(st.integers(1, 3)) for _ in range(n)]
    constraints = []
    if n_dep:
        which = (draw(st.integers(0, n_dep - 1)), draw(st.integers(0, n_ind - 1)))
        base = draw(st.sampled_from(CONSTRAINT_BASIS))
    for b in range(n_dep):
        row = [(draw(st.integers(-2, 2)), base if (b, i) == which else "1")
               for i in range(n_ind)]
        if all(k == 0 for k, _ in row):            # keep the constraint non-trivial
            row[0] = (1, row[0][1])
        constraints.append(row)
    spec = dict(n_ind=n_ind, n_dep=n_dep, offdiag=offdiag, diag=diag,
                constraints=constraints,
                V=(draw(st.integers(0, 3)), draw(st.integers(0, 3)), draw(st.integers(-1, 1)),
                   draw(st.integers(0, 1))),
                gyro=draw(st.booleans()),
                eps=draw(st.integers(0, n_ind - 1)),
                direction=draw(st.sampled_from((1, -1))),
                seed=draw(st.integers(0, 10**6)))
    if n_ind > 2:
        spec["V3"] = draw(st.integers(0, 2))
    return spec


# ------------------------------------------------------------------ numerics


def check_chain_rule(system, red, eps, rng, points=2):
    """red.accelerations() at (q, q', h) equals the chain-rule value from (1.4), and
    red.velocity gives back qdot_eps."""
    acc = system.accelerations()
    racc = red.accelerations()
    x = red.independent
    nus = [c for c in system.independent_coordinates if c != eps]
    fn = {f.func.__name__: f for f in red.coordinates}
    with mpmath.workdps(DPS + 10):
        for _ in range(points):
            # parameters without a sign assumption (B) take either sign here
            pt = {p: rat(rng, 0.5, 2.0) * (1 if p.is_positive else rng.choice((-1, 1)))
                  for p in system.parameters}
            for c in system.independent_coordinates:
                pt[c] = rat(rng, -1.2, 1.2)
            v = red.direction * rat(rng, 0.3, 1.5)
            pt[eps.diff(t)] = v
            primes = {c: rat(rng, -1, 1) for c in nus}
            for c in nus:
                pt[c.diff(t)] = v * primes[c]
            h = sp.sympify(system.energy()).xreplace(pt)
            sub = {p: pt[p] for p in system.parameters}
            sub[red.h] = h
            sub[x] = pt[eps]
            for c in nus:
                f = fn[c.func.__name__]
                sub[f.diff(x)] = primes[c]
                sub[f] = pt[c]
            vv = num(v, {})
            assert close(num(red.velocity, sub), vv)
            a_eps = num(acc[eps.diff(t, 2)], pt)
            for c in nus:
                want = (num(acc[c.diff(t, 2)], pt) * vv - num(pt[c.diff(t)], {}) * a_eps) / vv**3
                f = fn[c.func.__name__]
                got = num(racc[f.diff(x, 2)], sub)
                assert close(got, want), (c, got, want)


def run(spec):
    system, eps = build(spec)
    red = system.reduce(eps, direction=spec["direction"])
    report = red.verify()
    failed = [c for c in report if not c.holds]
    assert report.ok, "\n".join(c.describe() for c in failed)
    check_chain_rule(system, red, eps, random.Random(spec["seed"]))


@settings(max_examples=15, **SETTINGS)
@given(rich_specs())
def test_random_two_dof_systems_verify_and_follow_the_chain_rule(spec):
    run(spec)


@settings(max_examples=6, **SETTINGS)
@given(rich_specs(n_ind=3, max_dep=2))
def test_random_three_dof_systems_verify_and_follow_the_chain_rule(spec):
    run(spec)


# ------------------------------------------------------------------ fixed cases
def test_builder_gives_positive_definite_mass_matrix():
    """The construction itself: M is diagonally dominant for any q (spot check)."""
    spec = dict(n_ind=2, n_dep=2, offdiag=[(2, "1+q2^2"), (-2, "cos(q1)"), (1, "1"),
                                           (-1, "1+q2^2"), (2, "cos(q1)"), (-2, "1")],
                diag=[1, 1, 1, 1], constraints=[[(1, "sin(q1)"), (-2, "q2^2")],
                                                [(2, "cos(q2)"), (1, "q1")]],
                V=(1, 1, 1, 1), gyro=True, eps=0, direction=1, seed=0)
    system, _ = build(spec)
    qd = [c.diff(t) for c in system.coordinates]
    T = system.lagrangian.xreplace({s: 0 for s in system.parameters})
    T = T - T.xreplace({v: 0 for v in qd})
    H = sp.hessian(T, qd)
    rng = random.Random(5)
    for _ in range(5):
        pt = {c: rng.uniform(-3, 3) for c in system.coordinates}
        Hn = sp.matrix2numpy(H.xreplace(pt).evalf(), dtype=float)
        assert np.all(np.linalg.eigvalsh(Hn) > 0)
