"""Fixed-step Runge-Kutta methods (numerics.fixed_step): their orders on the sledge
against the closed form (3.15), their real stability intervals against the textbook
values, and clear errors for bad input."""

import math

import pytest

import whittaker_teach as wt
from whittaker_teach.numerics import fixed_step as fs

P = {"m": 1.0, "J": 1.0, "k": 1.0}


def _sledge_errors(method, steps, T=20.0):
    ex = wt.examples.sledge_exact(P, a=0.5, phi=-math.pi / 2, C=1.0)
    end = ex(T)
    f = fs.sledge_rhs(P, 1.0)
    out = []
    for N in steps:
        _, U, nfev = fs.integrate(f, (0.0, T), [0.0, 0.5, 0.0, 0.0], N, method)
        assert nfev == len(fs.TABLEAUS[method][1]) * N
        out.append(max(abs(U[-1, 0] - end["theta"]), abs(U[-1, 2] - end["x"]),
                       abs(U[-1, 3] - end["y"])))
    return out


@pytest.mark.parametrize("method, steps, tol", [("rk4", (400, 800), 0.05),
                                                ("midpoint", (400, 800), 0.05),
                                                ("euler", (6400, 12800), 0.05)])
def test_observed_order_is_the_method_order(method, steps, tol):
    e1, e2 = _sledge_errors(method, steps)
    assert abs(fs.observed_order(e1, e2) - fs.ORDERS[method]) < tol * fs.ORDERS[method]


def _scaled_errors(method, steps, T=20.0):
    """Chapter 15's error measure: at t = T, the largest over theta, x, y of the absolute
    error divided by the component's scale (0.5; the largest |x|, |y| on 401 times)."""
    ex = wt.examples.sledge_exact(P, a=0.5, phi=-math.pi / 2, C=1.0)
    end, grid = ex(T), [ex(T * i / 400) for i in range(401)]
    scale = {"theta": 0.5, "x": max(abs(g["x"]) for g in grid),
             "y": max(abs(g["y"]) for g in grid)}
    f = fs.sledge_rhs(P, 1.0)
    out = []
    for N in steps:
        _, U, _ = fs.integrate(f, (0.0, T), [0.0, 0.5, 0.0, 0.0], N, method)
        got = {"theta": U[-1, 0], "x": U[-1, 2], "y": U[-1, 3]}
        out.append(max(abs(got[c] - end[c]) / scale[c] for c in scale))
    return out


def test_euler_is_not_yet_asymptotic_at_coarse_steps():
    """Chapter 15: with N = 100 Euler's error is several times the scale, its heading's
    amplitude has grown by (1 + dt^2)^(N/2), about e^2, and the observed order from 100
    and 200 steps is far above 1 (the amplitude error e^(T dt/2) - 1 is convex in dt)."""
    e1, e2 = _scaled_errors("euler", (100, 200))
    assert e1 > 2 and 1.5 < fs.observed_order(e1, e2) < 1.8
    assert abs((1 + 0.2**2) ** 50 - math.e**2) < 0.05 * math.e**2


def test_rk4_keeps_order_4_down_to_3e_14():
    """Chapter 15: rounding does not yet bend RK4's line at 12800 and 25600 steps."""
    e1, e2, e3 = _scaled_errors("rk4", (6400, 12800, 25600))
    assert e3 < 1e-13
    assert abs(fs.observed_order(e1, e2) - 4) < 0.1 and abs(fs.observed_order(e2, e3) - 4) < 0.1


def test_rk4_on_the_imaginary_axis_damps():
    """Exercise ch15-ex5: |R(iy)|^2 = 1 - y^6/72 + y^8/576 < 1 for 0 < y^2 < 8."""
    for y in (0.1, 0.3, 1.0, 2.0, 2.8):
        r2 = abs(fs.stability_function("rk4", 1j * y)) ** 2
        assert abs(r2 - (1 - y**6 / 72 + y**8 / 576)) < 1e-14 and r2 < 1
    assert abs(fs.stability_function("rk4", 1j * 3.0)) > 1


@pytest.mark.parametrize("method, beta", [("euler", 2.0), ("midpoint", 2.0),
                                          ("rk4", 2.785293563405)])
def test_stability_intervals(method, beta):
    """Hairer & Wanner II, section IV.2: RK4's real interval ends at -2.7853."""
    assert abs(fs.stability_interval(method) - beta) < 1e-9


def test_rk4_stability_function_is_the_taylor_polynomial():
    for z in (-1.3, 0.2j, 0.5 - 0.7j):
        assert abs(fs.stability_function("rk4", z)
                   - (1 + z + z**2 / 2 + z**3 / 6 + z**4 / 24)) < 1e-14


def test_linear_decay_is_stable_below_the_interval_and_not_above():
    lam = -50.0
    beta = fs.stability_interval("rk4")
    n_stable = math.ceil(300 * -lam / beta)
    _, U, _ = fs.integrate(lambda t, u: lam * u, (0, 300), [1.0], n_stable, "rk4")
    assert abs(U[-1, 0]) < 1
    _, U, _ = fs.integrate(lambda t, u: lam * u, (0, 300), [1.0], int(0.98 * n_stable), "rk4")
    assert abs(U[-1, 0]) > 1e10


@pytest.mark.parametrize("kw, match", [
    ({"method": "rk5"}, "one of euler, midpoint, rk4"),
    ({"steps": 0}, "positive integer"), ({"steps": 2.5}, "positive integer"),
    ({"steps": True}, "positive integer"),
    ({"t_span": (1.0, 1.0)}, "two different finite times"),
    ({"y0": [[1.0]]}, "flat list"), ({"y0": [float("nan")]}, "finite"),
])
def test_bad_input(kw, match):
    args = {"f": lambda t, u: -u, "t_span": (0.0, 1.0), "y0": [1.0], "steps": 4,
            "method": "rk4"} | kw
    with pytest.raises(wt.ModelError, match=match):
        fs.integrate(**args)


def test_observed_order_refuses_a_zero_error():
    with pytest.raises(wt.ModelError, match="two positive errors"):
        fs.observed_order(0.0, 1e-8)
    assert fs.observed_order(1.6e-5, 1e-6) == pytest.approx(4.0)


def test_f_of_the_wrong_shape_is_refused():
    with pytest.raises(wt.ModelError, match="one number per component"):
        fs.integrate(lambda t, u: [1.0, 2.0], (0.0, 1.0), [1.0], 4, "rk4")


@pytest.mark.parametrize("args, match", [
    ((1e-3, 1e-4, 1.0), "other than 1"), ((1e-3, 1e-4, -2.0), "positive"),
    ((float("inf"), 1e-4), "finite errors"), ((float("nan"), 1e-4), "positive errors")])
def test_observed_order_bad_input(args, match):
    with pytest.raises(wt.ModelError, match=match):
        fs.observed_order(*args)


@pytest.mark.parametrize("params, match", [({"J": 1.0}, "lacks k"),
                                           ({"J": 0.0, "k": 1.0}, "J must be positive")])
def test_sledge_rhs_bad_params(params, match):
    with pytest.raises(wt.ModelError, match=match):
        fs.sledge_rhs(params, 1.0)
