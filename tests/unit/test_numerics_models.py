"""The full and the reduced model (and DLA) against the sledge's exact solution;
the API's shape and its errors on bad input."""

import math
import subprocess
import sys

import numpy as np
import pytest

import whittaker_teach as wt
from whittaker_teach.numerics import codegen

P = {"m": 1.0, "J": 1.0, "k": 1.0}


@pytest.fixture(scope="module")
def ex():
    return wt.examples.sledge_exact(P, a=0.6, phi=0.3, C=1.2)


def _err(ex, t, q):
    e = ex(np.asarray(t))
    return max(float(np.max(np.abs(np.asarray(q[k]) - e[k]))) for k in ("x", "theta", "y"))


@pytest.mark.parametrize("formulation", ["chaplygin", "multiplier"])
@pytest.mark.parametrize("method", ["DOP853", "RK45", "Radau", "LSODA"])
def test_full_model_error_bound(S, ex, formulation, method):
    T = 3 * ex.period
    traj = S.simulate(*ex.initial(), (0, T), P, method=method, rtol=1e-10,
                      formulation=formulation)
    assert _err(ex, traj.t, traj.q) < 2e-7
    assert traj.energy_error < 1e-8
    assert traj.formulation == formulation and traj.nfev > 0


def test_trajectory_api(S, ex):
    T = 2 * ex.period
    traj = S.simulate(*ex.initial(), (0, T), P, rtol=1e-11)
    assert traj.formulation == "multiplier"          # auto: the constraint has a pole
    x, th, y = S.coordinates
    assert set(traj.q) == {x, th, y} and set(traj.qdot) == {x, th, y}
    np.testing.assert_array_equal(traj.q["y"], traj.q[y])
    e = ex(traj.t)
    np.testing.assert_allclose(traj.qdot["y"], e["ydot"], atol=1e-8)
    mid = traj(T / 3)
    assert abs(mid["x"] - ex(T / 3)["x"]) < 1e-8 and abs(mid[th] - ex(T / 3)["theta"]) < 1e-8
    arr = traj(np.linspace(0, T, 5))
    assert arr["y"].shape == (5,)
    assert traj.energy.shape == traj.t.shape and traj.h == pytest.approx(ex.h, rel=1e-14)
    with pytest.raises(wt.ModelError, match="outside"):
        traj(2 * T)


@pytest.mark.parametrize("method", ["DOP853", "RK45", "Radau", "LSODA"])
def test_reduced_model_error_bound(red, ex, method):
    q0, qp0, h = ex.reduced_initial()
    T = 3 * ex.period
    x_end = ex(T)["x"]
    path = red.simulate(q0, qp0, h, (q0["x"], x_end), P, method=method, rtol=1e-10)
    assert _err(ex, path.t, path.q) < 2e-7
    assert path.t[-1] == pytest.approx(T, abs=1e-7)      # time recovered by quadrature
    assert not path.switches and path.nfev > 0


def test_path_api(red, ex):
    q0, qp0, h = ex.reduced_initial()
    path = red.simulate(q0, qp0, h, (q0["x"], q0["x"] + 4.0), P, rtol=1e-11)
    np.testing.assert_array_equal(path.q["x"], path.s)
    np.testing.assert_allclose(path.qp["theta"], ex(path.t)["thetadot"] / ex(path.t)["xdot"],
                               atol=1e-8)
    mid = path(q0["x"] + 2.0)
    truth = ex(mid["t"])
    assert abs(mid["theta"] - truth["theta"]) < 1e-8 and abs(mid["y"] - truth["y"]) < 1e-8
    assert abs(truth["x"] - (q0["x"] + 2.0)) < 1e-8
    with pytest.raises(wt.ModelError, match="outside"):
        path(q0["x"] + 10)


def test_reduced_initial_state_roundtrip(red, ex):
    from whittaker_teach.numerics.reduced_model import reduced_initial_state
    q0, qd0 = ex.initial()
    rq, qp, h = reduced_initial_state(red, q0, qd0, P)
    assert h == pytest.approx(ex.h, rel=1e-14)
    assert qp["theta"] == pytest.approx(qd0["theta"] / qd0["x"], rel=1e-14)


def test_dla_second_order_and_energy(S, ex):
    T = 2 * ex.period
    errs = []
    for n in (200, 400):
        traj = S.simulate(*ex.initial(), (0, T), P, method="DLA", dt=T / n)
        errs.append(_err(ex, traj.t, traj.q))
        assert traj.energy_error < 1e-9
        assert len(traj.t) == n + 1 and traj.t[-1] == pytest.approx(T)
    assert 3.0 < errs[0] / errs[1] < 5.0                   # second order
    assert abs(traj(T / 2)["theta"] - ex(T / 2)["theta"]) < 1e-3


def test_dla_holonomic_midpoint():
    proj = wt.examples.projectile()
    names = [c.func.__name__ for c in proj.coordinates]
    params = {p.name: 1.0 for p in proj.parameters}
    traj = proj.simulate({n: 0.0 for n in names}, {n: 1.0 for n in names}, (0, 2), params,
                         method="DLA", dt=0.01)
    # a uniform field: the midpoint rule is exact for quadratic motions
    assert traj.energy_error < 1e-12


def test_codegen_built_once_and_only_what_is_asked():
    S = wt.examples.sledge()
    a = codegen.time_model(S, "chaplygin")
    assert codegen.time_model(S, "chaplygin") is a
    assert ("time", "chaplygin") in codegen.cache_of(S) and "dla" not in codegen.cache_of(S)
    red = S.reduce("x")
    assert codegen.reduced_model(red) is codegen.reduced_model(red)
    assert ("time", "multiplier") not in codegen.cache_of(S)


def test_import_stays_light():
    code = ("import sys, whittaker_teach, whittaker_teach.numerics; "
            "print(sorted(m for m in ('numpy', 'scipy', 'sympy') if m in sys.modules))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True).stdout.strip()
    assert out == "[]"


# ----------------------------------------------------------------- bad input
def test_bad_time_input(S, ex):
    q0, qd0 = ex.initial()
    with pytest.raises(wt.ModelError, match="no initial value for the coordinate y"):
        S.simulate({"x": 0, "theta": 0}, qd0, (0, 1), P)
    with pytest.raises(wt.ModelError, match="y is a dependent coordinate"):
        S.simulate(q0, {**qd0, "y": 1.0}, (0, 1), P)
    with pytest.raises(wt.ModelError, match="no initial value for the coordinate theta"):
        S.simulate(q0, {"x": 1.0}, (0, 1), P)
    with pytest.raises(wt.ModelError, match="unknown method 'Euler'"):
        S.simulate(q0, qd0, (0, 1), P, method="Euler")
    with pytest.raises(wt.ModelError, match="no value for the parameter k"):
        S.simulate(q0, qd0, (0, 1), {"m": 1, "J": 1})
    with pytest.raises(wt.ModelError, match="'g' is not a parameter"):
        S.simulate(q0, qd0, (0, 1), {**P, "g": 9.8})
    with pytest.raises(wt.ModelError, match="declared positive"):
        S.simulate(q0, qd0, (0, 1), {**P, "m": -1})
    with pytest.raises(wt.ModelError, match="finite"):
        S.simulate({**q0, "x": math.nan}, qd0, (0, 1), P)
    with pytest.raises(wt.ModelError, match="'z' is not a coordinate"):
        S.simulate({**q0, "z": 0}, qd0, (0, 1), P)
    with pytest.raises(wt.ModelError, match="rtol"):
        S.simulate(q0, qd0, (0, 1), P, rtol=1e-16)
    with pytest.raises(wt.ModelError, match="empty"):
        S.simulate(q0, qd0, (1, 1), P)
    with pytest.raises(wt.ModelError, match="pass its step dt"):
        S.simulate(q0, qd0, (0, 1), P, method="DLA")
    with pytest.raises(wt.ModelError, match="unknown formulation"):
        S.simulate(q0, qd0, (0, 1), P, formulation="hamilton")
    with pytest.raises(wt.ModelError, match="at a pole of the constraints"):
        S.simulate({**q0, "theta": math.pi / 2}, qd0, (0, 1), P)


def test_bad_reduced_input(red, ex):
    q0, qp0, h = ex.reduced_initial()
    with pytest.raises(wt.ModelError, match="violates the energy integral"):
        red.simulate(q0, qp0, -1.0, (q0["x"], 1.0), P)
    with pytest.raises(wt.ModelError, match="x has no slope here"):
        red.simulate(q0, {**qp0, "x": 1.0}, h, (q0["x"], 1.0), P)
    with pytest.raises(wt.ModelError, match="y has no slope here"):
        red.simulate(q0, {**qp0, "y": 1.0}, h, (q0["x"], 1.0), P)
    with pytest.raises(wt.ModelError, match="span starts at"):
        red.simulate(q0, qp0, h, (q0["x"] + 1, 3.0), P)
    with pytest.raises(wt.ModelError, match="against the direction"):
        red.simulate(q0, qp0, h, (q0["x"], q0["x"] - 1), P)
    with pytest.raises(wt.ModelError, match="'DLA' integrates the full model"):
        red.simulate(q0, qp0, h, (q0["x"], 1.0), P, method="DLA")
    with pytest.raises(wt.ModelError, match="on_turning_point"):
        red.simulate(q0, qp0, h, (q0["x"], 1.0), P, on_turning_point="ignore")


def test_dla_refuses_a_too_coarse_step():
    kep = wt.examples.kepler()
    params = {p.name: 1.0 for p in kep.parameters}
    names = [c.func.__name__ for c in kep.coordinates]
    q0, qd0 = {n: 0.3 for n in names}, {n: 0.7 for n in names}   # a close approach to r = 0
    with pytest.raises(wt.ModelError, match="too coarse"):
        kep.simulate(q0, qd0, (0, 3), params, method="DLA", dt=0.01)
    traj = kep.simulate(q0, qd0, (0, 3), params, method="DLA", dt=0.01, max_energy_error=None)
    assert np.all(np.isfinite(traj.energy))
    fine = kep.simulate(q0, qd0, (0, 3), params, rtol=1e-10)     # adaptive: fine
    assert fine.energy_error < 1e-7


def test_dla_bad_input(S, ex):
    q0, qd0 = ex.initial()
    with pytest.raises(wt.ModelError, match="t_eval is not available"):
        S.simulate(q0, qd0, (0, 1), P, method="DLA", dt=0.1, t_eval=[0.5])
    with pytest.raises(wt.ModelError, match="at a pole of the constraints"):
        S.simulate({**q0, "theta": math.pi / 2}, qd0, (0, 1), P, method="DLA", dt=0.1)
    with pytest.raises(wt.ModelError, match="must be positive"):
        S.simulate(q0, qd0, (0, 1), P, method="DLA", dt=-0.1)
