"""The numerics give the same bits on every processor (``numerics.portable``).

The stored outputs of the book's chapters 6-8 are checked exactly by nbval; they used to
change with the BLAS kernel OpenBLAS picks for the processor and with numpy's AVX-512 code.
Here: the portable pieces agree with numpy's and scipy's to round-off, and a run of every
model gives identical bits under other BLAS kernels and without numpy's AVX-512 code.
"""

import hashlib
import os
import platform
import subprocess
import sys

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from whittaker_teach.numerics import portable


def _f(t, y):
    return np.array([y[1], -np.sin(y[0]) - 0.1 * y[1] * y[2], 0.3 * y[0] - y[2]])


@pytest.mark.parametrize("name", ["DOP853", "RK45", "RK23"])
def test_portable_methods_take_scipys_steps(name):
    """Same step-size control as scipy's: the same number of steps, whose ends agree to
    round-off (amplified: the error estimate is a sum of nearly cancelling stages, whose
    rounding moves the next step by about 1e-8), dense output and events included."""
    def ev(t, y):
        return y[0]
    kw = dict(rtol=1e-7, atol=1e-10, dense_output=True, events=ev)
    a = solve_ivp(_f, (0, 60), [1.0, 0.0, 0.5], method=name, **kw)
    b = solve_ivp(_f, (0, 60), [1.0, 0.0, 0.5], method=portable.PORTABLE[name], **kw)
    assert a.nfev == b.nfev and len(a.t) == len(b.t)
    assert np.max(np.abs(a.t - b.t)) < 1e-5 and np.max(np.abs(a.y - b.y)) < 1e-5
    te = np.linspace(0, 60, 333)
    assert np.max(np.abs(a.sol(te) - b.sol(te))) < 1e-5
    assert np.max(np.abs(a.sol(12.3) - b.sol(12.3))) < 1e-5
    assert len(a.t_events[0]) == len(b.t_events[0]) > 5
    assert np.max(np.abs(a.t_events[0] - b.t_events[0])) < 1e-5


def test_solvers_agree_with_numpy():
    rng = np.random.default_rng(3)
    for n in (1, 2, 4, 7):
        M = rng.normal(size=(50, n, n)) + 3 * np.eye(n)
        B = rng.normal(size=(50, n))
        ref = np.linalg.solve(M, B[..., None])[..., 0]
        assert np.allclose(portable.solve_stack(M, B), ref, rtol=1e-12, atol=1e-12)
        assert np.allclose(portable.solve(M[0], B[0]), ref[0], rtol=1e-12, atol=1e-12)
        C = rng.normal(size=(50, n, 3))
        assert np.allclose(portable.solve_stack(M, C), np.linalg.solve(M, C), rtol=1e-12)
        assert np.allclose(portable.matmul_stack(M, C), M @ C, rtol=1e-13)
    with pytest.raises(np.linalg.LinAlgError):
        portable.solve([[1.0, 2.0], [2.0, 4.0]], [1.0, 1.0])
    with pytest.raises(np.linalg.LinAlgError):
        portable.solve_stack(np.zeros((3, 2, 2)), np.ones((3, 2)))


def test_array_functions_equal_the_compiled_scalar_ones():
    """A model's numpy functions (energy, velocities) give, point by point, the very
    floats of its scalar functions (math): tan, exp, atan2 and powers included."""
    import sympy as sp

    from whittaker_teach.numerics.codegen import _lambdify
    x, y = sp.symbols("x y")
    exprs = [x**3 * sp.tan(y) + sp.sqrt(x) / (1 + x**2) + sp.exp(-y) * x**sp.Rational(3, 2),
             1 / x + sp.log(x) * sp.atan(y), sp.atan2(y, x) + sp.Abs(x)**-2 + sp.cos(x)]
    fa, fs = _lambdify([x, y], exprs, "numpy"), _lambdify([x, y], exprs)
    xs = np.random.default_rng(0).uniform(0.1, 2, 500)
    ys = np.random.default_rng(1).uniform(-1, 1, 500)
    arrays = fa(xs, ys)
    for k in range(3):
        assert [float(v) for v in arrays[k]] == [fs(u, v)[k] for u, v in zip(xs, ys)]


# ----------------------------------------------------------------- other processors
SCRIPT = r"""
import hashlib, numpy as np, whittaker_teach as wt
P = {"m": 1.0, "J": 1.0, "k": 1.0}
ex = wt.examples.sledge_exact(P, a=0.3, phi=0.3, C=1.0)
T = 3 * ex.period
S = wt.examples.sledge(); red = S.reduce("x", +1)
q0, qd0 = ex.initial(); rq0, qp0, h = ex.reduced_initial()
runs = [S.simulate(q0, qd0, (0, T), P, method="DOP853", rtol=1e-9, atol=1e-20),
        S.simulate(q0, qd0, (0, T), P, method="RK45", rtol=1e-7, formulation="chaplygin"),
        S.simulate(q0, qd0, (0, T), P, method="DLA", dt=ex.period / 32)]
path = red.simulate(rq0, qp0, h, (rq0["x"], ex(T)["x"]), P, method="DOP853", rtol=1e-9,
                    atol=1e-20)
g = ex(np.linspace(0, T, 301))
parts = [r.q[c].tobytes() + r.qdot[c].tobytes() for r in runs for c in ("x", "theta", "y")]
parts += [r.energy_error.hex().encode() + str(r.nfev).encode() for r in runs]
parts += [path.t.tobytes(), path.q["theta"].tobytes(), g["x"].tobytes(), g["y"].tobytes()]
x = np.linspace(0.1, 3, 1000)
control = hashlib.sha256((x ** 3).tobytes() + np.linalg.solve(
    np.eye(40) + np.outer(x[:40], x[:40]) / 9, x[:40]).tobytes()).hexdigest()
print(hashlib.sha256(b"".join(parts)).hexdigest(), control)
"""


def _run(env_changes):
    env = dict(os.environ, PYTHONHASHSEED="0")
    env.update(env_changes)
    out = subprocess.run([sys.executable, "-c", SCRIPT], env=env, capture_output=True,
                         text=True, timeout=600)
    assert out.returncode == 0, out.stderr[-2000:]
    return out.stdout.split()


@pytest.mark.skipif(platform.machine() not in ("x86_64", "AMD64"),
                    reason="the OpenBLAS kernels named here are x86-64's")
def test_same_bits_under_other_blas_kernels_and_without_avx512():
    """The models run in subprocesses as on other machines: OpenBLAS's SSE3 kernels
    (Prescott) and AVX kernels (Sandybridge) instead of the ones chosen here, and numpy
    without its AVX-512 code where this processor has it.  Every run, exact solution and
    energy error has the same bits.  The control (numpy's own x**3 and linalg.solve) shows
    that the settings do change numpy's results where they can."""
    from numpy._core._multiarray_umath import __cpu_dispatch__, __cpu_features__
    wide = [f for f in __cpu_dispatch__ if __cpu_features__.get(f) and
            (f.startswith("AVX512") or f == "X86_V4")]
    here = _run({})
    others = [_run({"OPENBLAS_CORETYPE": "Prescott"}),
              _run({"OPENBLAS_CORETYPE": "Sandybridge",
                    **({"NPY_DISABLE_CPU_FEATURES": " ".join(wide)} if wide else {})})]
    for other in others:
        assert other[0] == here[0]
    if wide:           # numpy's AVX-512 power differs from the C library's pow
        assert others[1][1] != here[1]
