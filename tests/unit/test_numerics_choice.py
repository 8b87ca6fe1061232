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


# ----------------------------------------------------------------- stiffness (review C, item 6)
FAST = {"m": 1, "J": 1, "k": 1, "b": 1}
FAST_Q0, FAST_QD0 = {"x": 0, "theta": 0.3, "y": 0}, {"x": 100 * math.cos(0.3), "theta": 0}


def test_dop853_stability_interval_from_its_tableau():
    from whittaker_teach.numerics.scene import dop853_stability
    stages, beta = dop853_stability()
    assert stages == 12 and 6.3 < beta < 6.5          # Hairer-Wanner II, fig. IV.2.1: ~6.4


def test_fast_sleigh_is_stiff_and_gets_an_implicit_or_switching_method(sleigh):
    """The offset sleigh at speed has an overdamped heading (rates near -50 and -0.01):
    tol= must not pick an explicit method (DOP853 would need ~28,000 evaluations)."""
    from whittaker_teach.numerics.scene import stiffness
    st = stiffness(sleigh, FAST_Q0, FAST_QD0, (0, 300), FAST)
    assert st.stiff and 49 < st.rate < 51 and st.floor > 20_000
    tr = sleigh.simulate(FAST_Q0, FAST_QD0, (0, 300), FAST, tol=1e-6)
    assert tr.method in ("LSODA", "Radau", "BDF") and tr.choice.method == tr.method
    assert "stiff" in tr.explain() and "stability" in tr.explain()
    assert tr.nfev < 5_000 and tr.choice.nfev_all < 10_000
    # the motion is within tol: against Radau at rtol 1e-13 (the two agree within 1e-14)
    grid = np.linspace(0, 300, 301)
    ref = sleigh.simulate(FAST_Q0, FAST_QD0, (0, 300), FAST, method="Radau", rtol=1e-13,
                          atol=1e-20, t_eval=grid)
    assert _rel(tr(grid), ref.q, ("x", "theta", "y")) <= 1e-6


def test_the_whole_call_counts_each_run_once_and_returns_the_tighter_one(sleigh):
    """Issue 33 (c): the call's cost is every run it made, each counted once (LSODA's
    nfev already holds its difference-quotient Jacobians; an rtol run twice is not run
    again), plus the stiffness test; the run returned is the tighter of the accepted
    pair (rtol / 10), no more work and more accurate.  Counts, not timings."""
    for tol in (1e-6, 1e-9):
        tr = sleigh.simulate(FAST_Q0, FAST_QD0, (0, 300), FAST, tol=tol)
        c = tr.choice
        assert c.method == "LSODA" and all(t[1] == "LSODA" for t in c.tried)
        looser = [t[2] for t in c.tried]
        assert looser == sorted(looser, reverse=True) and len(set(looser)) == len(looser)
        assert c.rtol == pytest.approx(looser[-1] / 10)        # the tighter run of the pair
        # every distinct rtol once: the looser run of each rung, and the last check run
        assert c.nfev_all == sum(t[4] for t in c.tried) + tr.nfev + 2 * 6
        assert c.check_nfev == c.tried[-1][4]


def test_oscillations_are_not_stiff_and_get_an_explicit_method(S, sleigh):
    """The sledge (b = 0: rates +-i, no decay) and the slow sleigh of chapter 7: DOP853."""
    from whittaker_teach.numerics.scene import stiffness
    tr = S.simulate(Q0, QD0, (0, 30), P, tol=1e-8, model="full")
    assert tr.method == "DOP853" and not tr.choice.stiffness.stiff
    assert tr.choice.stiffness.rate < 1e-6
    assert "in the sledge study" in tr.explain() and "not stiff" in tr.explain()
    st = stiffness(sleigh, Q0, {"x": 1, "theta": 0}, (0, 20 * math.pi), SLEIGH)
    assert not st.stiff and st.rate < 0.1
    tr = sleigh.simulate(Q0, {"x": 1, "theta": 0}, (0, 20 * math.pi), SLEIGH, tol=1e-9)
    assert tr.method == "DOP853"


def test_fast_oscillation_is_not_stiffness(S):
    """A stiff spring (k^2/J = 1e4: the sledge oscillates at omega = 100) has eigenvalues
    +-100i, no decaying mode: an explicit method, whatever the frequency."""
    from whittaker_teach.numerics.scene import stiffness
    st = stiffness(S, Q0, QD0, (0, 1), {"m": 1, "J": 1, "k": 100})
    assert not st.stiff and st.rate < 1e-6
    assert np.max(np.abs(st.eigenvalues.imag)) == pytest.approx(100, rel=1e-3)
