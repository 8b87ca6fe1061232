"""simulate(..., tol=...): the package picks the model and the method, says which and why,
and the motion it returns is within tol (checked against the exact solution or a run at
the package's tightest tolerance)."""

import math

import numpy as np
import pytest

import whittaker_teach as wt
from whittaker_teach.numerics.scene import EXACT_ERROR

P = {"m": 1, "J": 1, "k": 1}
SLEIGH = {"m": 1, "J": 1, "k": 1, "b": 0.1}
Q0, QD0 = {"x": 0, "theta": 0.3, "y": 0}, {"x": 1, "theta": 0.1}


def _rel(got, ref, names):
    return max(float(np.max(np.abs(np.asarray(got[n]) - np.asarray(ref[n]))))
               / float(np.max(np.abs(ref[n]))) for n in names)


@pytest.fixture(scope="module")
def sleigh():
    return wt.examples.offset_sleigh()


def test_sledge_gets_the_closed_form_and_builds_no_code():
    S = wt.examples.sledge()                         # a fresh one: nothing compiled yet
    tr = S.simulate(Q0, QD0, (0, 30), P, tol=1e-9)
    assert tr.choice.model == "exact" and tr.method == "closed form" and tr.nfev == 0
    assert "closed form (3.15)" in tr.explain()
    assert "_numerics" not in S.__dict__            # no right-hand side generated
    ex = wt.examples.sledge_exact(P, a=math.hypot(0.3, 0.1), phi=math.atan2(-0.1, 0.3),
                                  C=1 / math.cos(0.3))
    assert _rel({n: tr.q[n] for n in ("x", "theta", "y")}, ex(tr.t), ("x", "theta", "y")) < 1e-14
    assert tr.energy_error < 1e-14                 # computed from the state, not assumed
    assert abs(tr(17.3)["y"] - ex(17.3)["y"]) < 1e-14


def test_closed_form_at_the_given_times():
    S = wt.examples.sledge()
    t = np.linspace(0, 5, 7)
    tr = S.simulate(Q0, QD0, (0, 5), P, tol=1e-6, t_eval=t)
    assert np.array_equal(tr.t, t) and tr._dense is None


def test_reduction_gets_the_closed_form_along_x(red):
    ex = wt.examples.sledge_exact(P, a=0.6, C=1.0)
    q0, qp0, h = ex.reduced_initial()
    path = red.simulate(q0, qp0, h, (0, 24), P, tol=1e-8)
    assert path.choice.model == "exact" and path.nfev == 0
    assert np.array_equal(path.q["x"], path.s)
    back = ex(path.t)                     # at t(x), the exact x is x: Newton converged
    assert np.max(np.abs(back["x"] - path.s)) < 1e-13
    assert np.max(np.abs(back["theta"] - path.q["theta"])) < 1e-15
    assert abs(path(5.0)["t"] - ex.t0) > 0 and abs(ex(path(5.0)["t"])["x"] - 5.0) < 1e-13


def test_reduced_model_on_request_meets_tol(red):
    ex = wt.examples.sledge_exact(P, a=0.6, C=1.0)
    q0, qp0, h = ex.reduced_initial()
    path = red.simulate(q0, qp0, h, (0, 24), P, tol=1e-8, model="reduced")
    c = path.choice
    assert c.model == "reduced" and path.method == "DOP853" and c.rtol <= 1e-9
    assert "model='reduced' was asked" in c.why and c.error <= 1e-8
    e = ex(path.t)                        # the true error, per component, at the path's steps
    assert np.max(np.abs(path.q["theta"] - e["theta"])) / ex.a <= 1e-8
    assert np.max(np.abs(path.q["y"] - e["y"])) / np.max(np.abs(e["y"])) <= 1e-8


def test_full_model_meets_tol_and_says_why(sleigh):
    tr = sleigh.simulate(Q0, QD0, (0, 20), SLEIGH, tol=1e-8)
    c = tr.choice
    assert c.model == "full" and tr.method == "DOP853" and c.error <= 1e-8
    assert "no closed form for the offset_sleigh" in tr.explain()
    assert [t[0] for t in c.tried] == ["full"] * len(c.tried)
    ref = sleigh.simulate(Q0, QD0, (0, 20), SLEIGH, rtol=2.3e-14, atol=1e-20)
    assert _rel(tr(ref.t), ref.q, ("x", "theta", "y")) <= 1e-8


def test_tighter_tol_tightens_rtol(sleigh):
    loose = sleigh.simulate(Q0, QD0, (0, 20), SLEIGH, tol=1e-5)
    tight = sleigh.simulate(Q0, QD0, (0, 20), SLEIGH, tol=1e-11)
    assert tight.choice.rtol < loose.choice.rtol and tight.nfev > loose.nfev


def test_unreachable_tol_names_the_best_error(sleigh, S):
    with pytest.raises(wt.ModelError, match=r"no model reaches the relative error 1e-15 .* "
                                            r"best available is about \d\.\de-1[0-4]"):
        sleigh.simulate(Q0, QD0, (0, 20), SLEIGH, tol=1e-15)
    with pytest.raises(wt.ModelError, match="closed form .* about 1e-15"):
        S.simulate(Q0, QD0, (0, 20), P, tol=EXACT_ERROR / 10)


@pytest.mark.parametrize("kw, match", [
    ({"tol": 0.0}, "must lie in"), ({"tol": 2.0}, "must lie in"),
    ({"tol": "tiny"}, "must be a real number"),
    ({"tol": 1e-6, "method": "RK45"}, "either tol"), ({"tol": 1e-6, "rtol": 1e-3}, "either tol"),
    ({"tol": 1e-6, "model": "reduced"}, "choose among exact, full"),
    ({"tol": 1e-6, "formulation": "chaplygin"}, "chosen by the package"),
])
def test_bad_requests(S, kw, match):
    with pytest.raises(wt.ModelError, match=match):
        S.simulate(Q0, QD0, (0, 1), P, **kw)


def test_model_exact_without_a_closed_form(sleigh):
    with pytest.raises(wt.ModelError, match="has no closed form"):
        sleigh.simulate(Q0, QD0, (0, 1), SLEIGH, tol=1e-6, model="exact")


def test_without_tol_nothing_changes(S, red):
    tr = S.simulate(Q0, QD0, (0, 2), P, rtol=1e-8)
    assert tr.choice is None and tr.method == "DOP853" and "chosen by the caller" in tr.explain()
    ex = wt.examples.sledge_exact(P, a=0.6, C=1.0)
    q0, qp0, h = ex.reduced_initial()
    path = red.simulate(q0, qp0, h, (0, 2), P, tol=None)
    assert path.choice is None and path.method == "DOP853"


def test_turning_point_still_reported_with_tol(red):
    """a >= pi/2: no closed form along x; the reduced model meets the turning point."""
    ex = wt.examples.sledge_exact(P, a=1.8, C=1.0)
    q0, qp0, h = ex.reduced_initial(t=ex.period / 4)         # theta = 0, xdot > 0
    with pytest.raises(wt.ChartError, match="turning point"):
        red.simulate(q0, qp0, h, (q0["x"], q0["x"] + 5), P, tol=1e-6)
