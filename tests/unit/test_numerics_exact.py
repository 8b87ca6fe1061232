"""The sledge's closed form (Jacobi-Anger) against mpmath quadrature at 30 digits."""

import math

import mpmath as mp
import numpy as np
import pytest

import whittaker_teach as wt
from whittaker_teach.numerics.exact import SledgeExact, terms_needed

P = {"m": 1.0, "J": 1.0, "k": 1.0}


def _quad(a, phi, C, omega, t):
    """x(t), y(t) by mpmath quadrature at 30 digits, split at every half period."""
    with mp.workdps(30):
        a, phi, C, w, T = (mp.mpf(v) for v in (a, phi, C, omega, t))
        pts = mp.linspace(0, T, 2 * int(t * omega / math.pi) + 3)
        x = mp.quad(lambda s: C * mp.cos(a * mp.cos(w * s + phi)), pts)
        y = mp.quad(lambda s: C * mp.sin(a * mp.cos(w * s + phi)), pts)
        return x, y


@pytest.mark.parametrize("a, phi, C, params", [
    (0.3, 0.0, 1.0, P),
    (1.2, 0.3, 1.0, P),
    (math.pi / 2 - 1e-3, 1.0, 2.0, {"m": 2.0, "J": 0.5, "k": 1.5}),
    (2.5, -0.7, 0.5, P),
])
@pytest.mark.parametrize("t", [0.7, 5.0, 23.0])
def test_closed_form_matches_quadrature(a, phi, C, params, t):
    ex = SledgeExact(params, a, phi, C)
    x, y = _quad(a, phi, C, ex.omega, t)
    got = ex(t)
    scale = max(1.0, abs(float(x)))
    assert abs(got["x"] - float(x)) <= 2e-15 * scale * max(1.0, t)
    assert abs(got["y"] - float(y)) <= 2e-15 * scale * max(1.0, t)
    assert got["theta"] == pytest.approx(a * math.cos(ex.omega * t + phi), abs=1e-15)


def test_velocities_and_energy():
    ex = SledgeExact(P, 0.8, 0.2, 1.5)
    s = ex(3.0)
    assert s["xdot"] == pytest.approx(1.5 * math.cos(s["theta"]), abs=1e-15)
    assert s["ydot"] == pytest.approx(1.5 * math.sin(s["theta"]), abs=1e-15)
    E = 0.5 * (s["xdot"] ** 2 + s["ydot"] ** 2) + 0.5 * s["thetadot"] ** 2 + 0.5 * s["theta"] ** 2
    assert E == pytest.approx(ex.h, rel=1e-15)


def test_drift_is_C_J0():
    ex = SledgeExact(P, 1.0, 0.4, 2.0)
    T = 7 * ex.period
    assert (ex(T)["x"] - ex(0.0)["x"]) / T == pytest.approx(2.0 * 0.7651976865579666, rel=1e-14)


def test_vector_and_scalar_agree():
    ex = SledgeExact(P, 1.4, 0.1, 1.0, x0=1.0, y0=-2.0, t0=0.5)
    tt = np.linspace(0.5, 40, 9)
    v = ex(tt)
    for i, t in enumerate(tt):
        s = ex(float(t))
        for k in s:
            assert s[k] == pytest.approx(v[k][i], abs=1e-14)
    assert ex(0.5)["x"] == 1.0 and ex(0.5)["y"] == -2.0


def test_from_energy_and_roundoff_clip():
    ex = SledgeExact(P, h=0.5 + 0.5 * 0.36, C=1.0)
    assert ex.a == pytest.approx(0.6, rel=1e-14)
    assert SledgeExact(P, h=0.5 - 5e-18, C=1.0).a == 0.0          # round-off: clipped
    with pytest.raises(wt.ModelError, match="below the kinetic energy"):
        SledgeExact(P, h=0.4, C=1.0)


def test_bad_input():
    with pytest.raises(wt.ModelError, match="exactly one"):
        SledgeExact(P, 0.5, h=1.0)
    with pytest.raises(wt.ModelError, match="no value for the parameter k"):
        SledgeExact({"m": 1, "J": 1}, 0.5)
    with pytest.raises(wt.ModelError, match="positive"):
        SledgeExact({"m": 1, "J": -1, "k": 1}, 0.5)
    with pytest.raises(wt.ModelError, match="finite"):
        SledgeExact(P, float("nan"))


def test_terms_and_public_entry():
    assert terms_needed(0.0) >= 1 and terms_needed(3.0) > terms_needed(0.5)
    ex = wt.examples.sledge_exact(P, a=0.5, phi=0.0, C=1.0)
    assert ex.initial()[0]["theta"] == 0.5
    with pytest.raises(wt.ModelError, match="sign"):
        wt.examples.sledge_exact(P, a=2.0, phi=0.0).reduced_initial()
