"""The hard cases of the numerics: each ends within its tolerance or with a clear error.

Every case runs on the sledge (against the exact solution) and on the offset
sleigh (against a reference at rtol 1e-13), at the ``quick`` size.  The
assertions are on errors and outcomes, never on timings.
"""

import math

import numpy as np
import pytest

import whittaker_teach as wt
from whittaker_teach.numerics import hard_cases as hc

SYSTEMS = ["sledge", "offset_sleigh"]


@pytest.mark.parametrize("system", SYSTEMS)
@pytest.mark.parametrize("case", [1, 2, 3, 4, 5, 7])
def test_case_outcome(case, system):
    r = hc.run(case, system, quick=True)
    assert r.ok, str(r)
    if r.error is not None:
        assert r.error <= r.tolerance


def test_case1_no_switch_and_moderate_slopes():
    r = hc.run(1, "sledge")
    assert r.details["max_thetaprime"] < 100          # the chart stays regular
    assert r.details["nfev_reduced"] > r.details["nfev_full"]   # but it is costly


def test_case2_chart_error_names_coordinate_and_place():
    ex = wt.examples.sledge_exact(hc.SLEDGE, a=2.0, phi=math.pi / 2, C=1.0)
    red = wt.examples.sledge().reduce("x", +1)
    q0, qp0, h = ex.reduced_initial()
    with pytest.raises(wt.ChartError) as info:
        red.simulate(q0, qp0, h, (0.0, 5.0), hc.SLEDGE, rtol=1e-10)
    err = info.value
    t_turn = math.acos(-math.pi / 4) - math.pi / 2          # theta = 2 cos(t + pi/2) = -pi/2
    assert err.coordinate == "x"
    assert err.value == pytest.approx(ex(t_turn)["x"], abs=1e-7)
    assert err.t == pytest.approx(t_turn, abs=1e-7)
    assert isinstance(err, wt.ModelError)
    assert "qdot_x vanishes, or nearly vanishes, within the integration error at x = " in str(err)


def test_case2_switch_reports_where():
    ex = wt.examples.sledge_exact(hc.SLEDGE, a=2.0, phi=math.pi / 2, C=1.0)
    red = wt.examples.sledge().reduce("x", +1)
    q0, qp0, h = ex.reduced_initial()
    T = 2 * ex.period
    path = red.simulate(q0, qp0, h, (0.0, ex(T)["x"]), hc.SLEDGE, rtol=1e-10,
                        on_turning_point="switch")
    first = path.switches[0]
    assert first.frm == "x (+1)" and first.to == "t"
    assert path.switches[1].to == "x (-1)"                    # x runs backward after it
    # every turning point is where theta = +-pi/2, i.e. xdot = 0
    for s, t in path.turning_points:
        assert abs(math.cos(ex(t)["theta"])) < 1e-8 and s == pytest.approx(ex(t)["x"], abs=1e-7)
    with pytest.raises(wt.ModelError, match="not a function of x"):
        path(1.0)


def test_case3_multiplier_runs_through_the_pole():
    ex = wt.examples.sledge_exact(hc.SLEDGE, a=2.5, phi=0.0, C=1.0)
    S = wt.examples.sledge()
    traj = S.simulate(*ex.initial(), (0, 3 * ex.period), hc.SLEDGE, rtol=1e-11)
    e = ex(traj.t)
    assert np.max(np.abs(traj.q["y"] - e["y"])) < 1e-7
    assert np.max(np.abs(traj.qdot["y"] - e["ydot"])) < 1e-7   # finite at theta = pi/2
    assert np.min(np.abs(np.cos(traj.q["theta"]))) < 0.05      # it did pass near pi/2


def test_case6_long_run_energy():
    r = hc.run(6, "sledge", quick=True)
    assert r.ok, str(r)
    runs = {rec["method"]: rec for rec in r.details["runs"]}
    assert runs["DLA"]["energy_max"] < 1e-9                     # bounded, tiny
    assert runs["RK45"]["energy_final"] > 100 * runs["DLA"]["energy_max"]
    assert runs["DOP853"]["phase_error"] < runs["DLA"]["phase_error"]   # DLA: O(dt^2) phase


def test_case6_sleigh_reports_drift():
    r = hc.run(6, "offset_sleigh", quick=True)
    assert all(np.isfinite(rec["energy_final"]) for rec in r.details["runs"])


def test_case7_no_nan_at_turning_point():
    red = wt.examples.sledge().reduce("theta", +1)
    path = red.simulate({"x": 0, "theta": 0, "y": 0}, {"x": 0.0}, 0.5, (0.0, 1.0), hc.SLEDGE,
                        rtol=1e-12)
    assert np.all(np.isfinite(path.t)) and path.t[-1] == pytest.approx(math.pi / 2, abs=1e-6)


def test_unknown_case():
    with pytest.raises(wt.ModelError, match="no hard case"):
        hc.run(9)
