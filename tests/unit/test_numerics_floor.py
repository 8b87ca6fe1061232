"""The error floor: DOP853 below scipy's rtol floor (method "DOP853-tight") takes the
paper's form (1.4) of the sledge to within 100 machine epsilons of the exact motion,
and the reduced model to within 100 machine epsilons of the exact path (its state,
compared at its own recovered time, carries the clock's error in every component)."""

import numpy as np
import pytest

import whittaker_teach as wt
from whittaker_teach.numerics.work_precision import _errors, _path_error, _scales

P = {"m": 1.0, "J": 1.0, "k": 1.0}
EPS100 = 100 * np.finfo(float).eps            # 2.2e-14


def _worst(S, ex, T, method, rtol):
    xs, ys = _scales(ex, T)
    tr = S.simulate(*ex.initial(), (0, T), P, method=method, rtol=rtol, atol=1e-20,
                    formulation="chaplygin", dense=False)
    return max(_errors(ex, T, tr.t, tr.q, xs, ys).values())


def test_tight_dop853_reaches_100_machine_epsilons(S):
    ex = wt.examples.sledge_exact(P, a=0.3, phi=0.3, C=1.0)
    T = 10 * ex.period
    tight = _worst(S, ex, T, "DOP853-tight", 1e-15)
    floor = _worst(S, ex, T, "DOP853", 2.3e-14)        # scipy's smallest rtol
    assert tight <= EPS100, tight
    assert floor > 2 * tight, (floor, tight)           # the tolerance set the old floor


def test_rtol_ranges(S):
    ex = wt.examples.sledge_exact(P, a=0.3, C=1.0)
    with pytest.raises(wt.ModelError, match="DOP853-tight' allows rtol down to 4.5e-16"):
        S.simulate(*ex.initial(), (0, 1), P, method="DOP853", rtol=1e-15)
    with pytest.raises(wt.ModelError, match=r"outside \[4.5e-16, 1\) for DOP853-tight"):
        S.simulate(*ex.initial(), (0, 1), P, method="DOP853-tight", rtol=1e-16)
    with pytest.raises(wt.ModelError, match="DOP853-tight"):
        S.simulate(*ex.initial(), (0, 1), P, method="dop853-tight")


def test_tight_method_warns_nothing(S, red, recwarn):
    ex = wt.examples.sledge_exact(P, a=0.3, C=1.0)
    S.simulate(*ex.initial(), (0, 1), P, method="DOP853-tight", rtol=1e-15)
    q0, qp0, h = ex.reduced_initial()
    red.simulate(q0, qp0, h, (0, 1), P, method="DOP853-tight", rtol=1e-15)
    assert not [w for w in recwarn if "rtol" in str(w.message)]


@pytest.mark.parametrize("a", [0.3, 1.5])
def test_reduced_model_reaches_100_machine_epsilons_of_the_path(red, a):
    ex = wt.examples.sledge_exact(P, a=a, phi=0.3, C=1.0)
    T = 10 * ex.period
    xs, ys = _scales(ex, T)
    q0, qp0, h = ex.reduced_initial()
    path = red.simulate(q0, qp0, h, (q0["x"], ex(T)["x"]), P, method="DOP853-tight",
                        rtol=1e-15, atol=1e-20, dense=False)
    along = _path_error(ex, T, path.t, path.q, xs, ys)
    state = max(_errors(ex, T, path.t, path.q, xs, ys, reduced=True).values())
    assert along <= EPS100, along
    assert state > 2 * along, (state, along)      # the clock's error, counted in theta and y
