"""Simulations of the rolling bodies (whittaker_teach.rolling.simulate): the integrals
hold along them, the flow preserves Chaplygin's measure (not volume), and the
rattleback reverses quickly from its unstable spin direction only; and (symbolic, but
slow: about 35 s) the mechanics model of the rattleback has the vector model's energy."""

import numpy as np
import pytest

pytest.importorskip("scipy")

import sympy as sp  # noqa: E402

from whittaker_teach import rolling  # noqa: E402
from whittaker_teach.rolling import simulate as sim  # noqa: E402
from whittaker_teach.rolling.rattleback_model import RattlebackVectors  # noqa: E402

BALL = dict(A=0.3, B=0.4, C=0.5, m=1.0, R=1.0)
TOY = dict(m=1.0, g=9.81, h=0.01, rho_1=0.5, rho_2=0.02, A=1.6e-4, B=2.08e-3, C=2.08e-3,
           delta=0.05)


def test_ball_integrals_and_invariant_measure():
    run = sim.simulate_ball(BALL, [0.3, 0.8, 1.5], Q0=sim.tilt_rotation(0.7, [1, 1, 0]),
                            t_end=10.0, n=501)
    for name, v in run["integrals"].items():
        assert np.max(np.abs(v - v[0])) < 1e-9, name
    assert np.max(np.abs(run["K_space"] - run["K_space"][0])) < 1e-9
    det, ratio, _ = sim.ball_volume_ratio(BALL, run["M"][0], run["gamma"][0], 5.0)
    assert abs(det - ratio) < 1e-5 * ratio
    assert abs(det - 1) > 1e-3            # volume itself is not preserved


def test_rattleback_reverses_from_the_unstable_direction_only():
    runs = {s: sim.simulate_rattleback(TOY, [0, 0, s], tilt=(0.0, 0.002), t_end=4.0, n=401)
            for s in (-5, 5)}
    bad, good = runs[-5], runs[5]
    assert bad["spin"][0] == pytest.approx(-5, abs=1e-4)   # gamma . omega, tilted 0.002
    assert np.any(bad["spin"] > 4)        # reversed, and spinning the other way
    assert np.all(good["spin"] > 4.5)     # still spinning its way
    for r in runs.values():
        assert np.max(np.abs(r["energy"] - r["energy"][0])) < 1e-8 * r["energy"][0]
        assert r["orthogonality"] < 1e-8


def test_disk_run_is_the_librarys_simulation():
    run = sim.disk_run(0.7, 1e-3, 10.0, n=101)
    assert np.max(np.abs(run.q["phi"])) < 2e-3         # above the threshold: stays upright


def test_rattleback_mechanics_model_has_the_vector_models_energy():
    from whittaker_teach.stability.steady import sampler
    from whittaker_teach.verify import check_zero
    rb = rolling.rattleback()
    assert [q.func.__name__ for q in rb.dependent_coordinates] == ["x", "y"]
    rv = RattlebackVectors()
    t = rb.coordinates[0].args[0]
    w, g = rolling.euler_vectors()
    E_vec = rv.energy.xreplace(dict(zip([*rv.omega, *rv.gamma], [*w, *g])))
    plain = {q.diff(t): sp.Symbol(q.func.__name__ + "_dot", real=True) for q in rb.coordinates}
    plain.update({q: sp.Symbol(q.func.__name__, real=True) for q in rb.coordinates})
    d = (rb.energy().subs(rb.constraints) - E_vec).subs(plain)
    assert check_zero("E", "", d, sampler(d.free_symbols), exact=False).holds is True
    # and a wrong model is caught: h doubled in the vector energy
    h = rv.parameters[2]
    wrong = (rb.energy().subs(rb.constraints) - E_vec.subs(h, 2 * h)).subs(plain)
    assert check_zero("E", "", wrong, sampler(wrong.free_symbols), exact=False).holds is False
