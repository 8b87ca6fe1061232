"""The roller racer of issue 34 (item 1) integrated from theta = 0.

Before the fix every solved velocity carried LU's pivot -sin(theta), so that ``simulate``
from theta = 0 failed in every formulation (a ZeroDivisionError blamed on the initial
state).  Now the solved velocities' only denominator is sin(phi), the determinant of the
constraints' matrix: both formulations start at theta = 0, agree with each other, keep
the energy (1.11) and the constraints.  (The spring k is soft and the time short, so
that phi stays away from 0, where the two axles are parallel and the constraints'
matrix is singular: a real singularity of the model.)
"""
import math

import pytest

import whittaker_teach as wt
from tests.unit.test_core_edges import roller_racer


@pytest.fixture(scope="module")
def racer():
    system, coords, _, params = roller_racer()
    return wt.ChaplyginSystem.from_system(system), coords, params


def test_simulate_from_theta_zero_in_both_formulations(racer):
    S, (x, y, th, ph), params = racer
    values = {p: v for p, v in zip(params, (1.0, 0.7, 0.3, 0.2, 0.8, 0.5, 0.2))}
    q0 = {th: 0.0, ph: 0.6, x: 0.0, y: 0.0}
    qd0 = {th: 0.2, ph: -0.3}
    runs = {f: S.simulate(q0, qd0, (0, 1), values, formulation=f, rtol=1e-10)
            for f in ("chaplygin", "multiplier")}
    a, b = runs["chaplygin"], runs["multiplier"]
    assert min(abs(v) for v in a.q[ph]) > 0.1       # away from the real singularity phi = 0
    for c in (x, y, th, ph):
        assert a.q[c][-1] == pytest.approx(b.q[c][-1], rel=1e-6, abs=1e-8)
    for tr in runs.values():
        assert tr.energy_error < 1e-7
        # no lateral slip of body 1: -xdot sin(theta) + ydot cos(theta) = 0
        slip = max(abs(-xd * math.sin(t) + yd * math.cos(t))
                   for xd, yd, t in zip(tr.qdot[x], tr.qdot[y], tr.q[th]))
        assert slip < 1e-8
