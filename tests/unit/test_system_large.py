"""Large systems (issue 26, item 4): the shortcuts taken above a size change no result.

Above ``system.COLLECT_SIGMA_LIMIT`` independent coordinates, (1.4) and (1.11) are
solved and checked as derived and collected only to show; above
``reduction.SOLVE_NU_LIMIT`` equations (1.26), q'' is read from the accelerations of
(1.4).  On the chain of sleighs (n = 8: six independent coordinates, five q_nu) the
shown forms equal the derived ones, and q'' equals the LU solution of (1.26).
"""
import random

import mpmath
import pytest

import whittaker_teach as wt
from whittaker_teach import bench, reduction
from whittaker_teach.verify import DPS, evaluate


def _system():
    F = bench.chain(8)
    return wt.ChaplyginSystem(F["L"], F["q"], nonhol_coneqs=F["coneqs"],
                              dependent=F["dependent"]), F["q"][0]


def _equal(a, b, sample, points=3):
    rng = random.Random(8)
    with mpmath.workdps(DPS):
        for _ in range(points):
            pt = {k: mpmath.mpf(v) if isinstance(v, (int, float)) else v
                  for k, v in sample(rng).items()}
            x, y = evaluate(a, dict(pt)), evaluate(b, dict(pt))
            if abs(x - y) > 1e-25 * max(1, abs(x)):
                return False
    return True


def test_shown_forms_equal_the_derived_ones():
    S, _ = _system()
    assert S._large
    for shown, derived in zip(S._eom_shown(), S._eom()):
        assert shown != derived and _equal(shown, derived, S._sample_time)
    assert _equal(S._energy_shown(), S._energy(), S._sample_time)
    steps = S.steps
    assert [q.lhs for q in steps["1.4"].equations] == S._eom_shown()
    assert steps["1.11"].equations[0].lhs == S._energy_shown()
    assert S.verify().ok


def test_accelerations_from_time_equal_the_lu_solution(monkeypatch):
    S, x1 = _system()
    red = S.reduce(x1)
    assert len(red._nus) > reduction.SOLVE_NU_LIMIT
    fast = red._accelerations()
    monkeypatch.setattr(reduction, "SOLVE_NU_LIMIT", 100)
    lu = S.reduce(x1)._accelerations()
    for a in fast:
        assert _equal(fast[a], lu[a], red._sample)
    assert red.verify().ok


def test_q2_matrix_is_the_jacobian_of_1_26():
    """The matrix shown regular for the shortcut is d(1.26)/d(q''), entry by entry."""
    import sympy as sp
    S, x1 = _system()
    red = S.reduce(x1)
    qpp = [red._qpp[c] for c in red._nus]
    jac = sp.Matrix([[red._d(e, a) for a in qpp] for e in red._eqs])
    for a, b in zip(red._q2_matrix(), jac):
        assert _equal(a, b, red._sample)
