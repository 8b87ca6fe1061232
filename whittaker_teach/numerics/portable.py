"""Arithmetic whose results do not depend on the processor.

A run of an adaptive integrator is a chain of decisions (accept the step or not,
how long the next one is) taken on values rounded to the last bit; two machines
that round one sum differently take different steps after a while, and print
other evaluation counts and errors.  Three things here differ between x86-64
machines with the same Python packages:

- numpy's ``dot``, ``matmul``, ``linalg.solve`` and ``linalg.norm`` call the BLAS
  and LAPACK of OpenBLAS, whose kernels (chosen for the processor, or by
  ``OPENBLAS_CORETYPE``) add in different orders and fuse multiplications;
- numpy's ``exp``, ``log``, ``tan``, ``arctan``, ``power`` (other than squares,
  reciprocals and square roots) and the other transcendental functions use
  vector code of their own on processors with AVX-512, and the C library's
  functions elsewhere;
- scipy's explicit Runge-Kutta methods take their weighted sums of stages and
  their error norms with ``np.dot`` and ``np.linalg.norm``.

What replaces them here uses only elementwise ``+ - * /`` and square roots (each
rounded exactly as IEEE 754 prescribes, on every processor), sums in a fixed
order, and the C library's functions through Python's ``math`` module, as the
compiled right-hand sides already do.  With them the book's stored runs of the
explicit methods are the same bits on every machine
(``tests/unit/test_numerics_portable.py`` runs a model under other BLAS kernels
and without numpy's AVX-512 code).  Radau (LAPACK's LU) and LSODA (compiled
Fortran) are not replaced: their counts differ slightly between processors.

>>> solve([[2.0, 1.0], [1.0, 3.0]], [3.0, 5.0])
[0.8, 1.4]
"""

from __future__ import annotations

import math
from math import fsum

import numpy as np
from scipy.integrate import DOP853, RK23, RK45
# scipy's dense outputs (private names; scipy is pinned, and the tests compare with it)
from scipy.integrate._ivp.rk import Dop853DenseOutput, RkDenseOutput

__all__ = ["solve", "solve_stack", "dot", "matmul_stack", "combine", "rms", "PortableDOP853",
           "PortableRK45", "PortableRK23", "PORTABLE", "numpy_functions", "FUNCTIONS",
           "power", "atan2"]


# ----------------------------------------------------------------- linear algebra
def solve(K, b):
    """x with K x = b for a small dense matrix (lists or arrays of floats): Gaussian
    elimination with partial pivoting (the first largest pivot), in Python floats.
    ``numpy.linalg.LinAlgError`` (a ValueError) when K is singular, as numpy's.

    >>> solve([[0.0, 1.0], [1.0, 0.0]], [2.0, 3.0])
    [3.0, 2.0]
    """
    n = len(b)
    A = [[float(v) for v in row] + [float(bi)] for row, bi in zip(K, b)]
    for k in range(n):
        p = max(range(k, n), key=lambda i: abs(A[i][k]))
        if A[p][k] == 0.0:
            raise np.linalg.LinAlgError("singular matrix")
        A[k], A[p] = A[p], A[k]
        pivot = A[k]
        for i in range(k + 1, n):
            f = A[i][k] / pivot[k]
            if f != 0.0:
                row = A[i]
                for j in range(k + 1, n + 1):
                    row[j] -= f * pivot[j]
    x = [0.0] * n
    for k in range(n - 1, -1, -1):
        s = A[k][n]
        for j in range(k + 1, n):
            s -= A[k][j] * x[j]
        x[k] = s / A[k][k]
    return x


def solve_stack(M, B):
    """X with M[i] X[i] = B[i] for a stack of small systems: M of shape (N, n, n), B of
    shape (N, n) or (N, n, m); the same elimination as :func:`solve`, pivoting for each
    system, on whole columns of the stack (elementwise numpy only).

    >>> M = np.array([[[2.0, 1.0], [1.0, 3.0]], [[0.0, 1.0], [1.0, 0.0]]])
    >>> solve_stack(M, np.array([[3.0, 5.0], [2.0, 3.0]])).tolist()
    [[0.8, 1.4], [3.0, 2.0]]
    """
    A = np.array(M, dtype=float)
    vec = np.ndim(B) == 2
    X = np.array(B, dtype=float)[..., None] if vec else np.array(B, dtype=float)
    N, n = A.shape[0], A.shape[1]
    rows = np.arange(N)
    for k in range(n):
        p = k + np.argmax(np.abs(A[:, k:, k]), axis=1)
        if np.any(A[rows, p, k] == 0.0):
            raise np.linalg.LinAlgError("singular matrix")
        A[rows, k], A[rows, p] = A[rows, p].copy(), A[rows, k].copy()
        X[rows, k], X[rows, p] = X[rows, p].copy(), X[rows, k].copy()
        for i in range(k + 1, n):
            f = A[:, i, k] / A[:, k, k]
            A[:, i, k + 1:] -= f[:, None] * A[:, k, k + 1:]
            X[:, i] -= f[:, None] * X[:, k]
    for k in range(n - 1, -1, -1):
        s = X[:, k].copy()
        for j in range(k + 1, n):
            s -= A[:, k, j][:, None] * X[:, j]
        X[:, k] = s / A[:, k, k][:, None]
    return X[..., 0] if vec else X


def dot(row, v):
    """sum_j row[j] v[j], left to right, in Python floats."""
    out = 0.0
    for a, b in zip(row, v):
        out += float(a) * float(b)
    return out


def matmul_stack(A, B):
    """The products A[i] @ B[i] of a stack, summed over the inner index in order."""
    A, B = np.asarray(A, dtype=float), np.asarray(B, dtype=float)
    out = A[..., :, 0, None] * B[..., None, 0, :]
    for k in range(1, A.shape[-1]):
        out = out + A[..., :, k, None] * B[..., None, k, :]
    return out


def combine(K, a):
    """sum_j a[j] K[j] (rows of K, weights a), in the order of j, zero weights left out."""
    out = None
    for row, w in zip(K, a):
        if w != 0.0:
            out = row * w if out is None else out + row * w
    return np.zeros(K.shape[1]) if out is None else out


def rms(x):
    """The root mean square of a vector: sqrt(sum x_i^2 / n), the sum exactly rounded."""
    x = np.asarray(x, dtype=float)
    return math.sqrt(math.fsum((x * x).tolist()) / x.size) if x.size else 0.0


# ----------------------------------------------------------------- explicit Runge-Kutta
# A method's step for n coordinates is generated once as straight-line Python: every
# weighted sum of stages written out term by term, left to right, in Python floats (each
# product and each sum rounded once, as IEEE 754 prescribes, on every machine), with the
# tableau's zeros left out.  For the few coordinates of a model this is faster than a
# numpy call per stage, and unlike ``np.dot`` it is the same everywhere.
def _sum_text(weights, rows, i):
    """The text of sum_j weights[j] * k<rows[j]>_<i>, left to right (0.0 if empty)."""
    terms = [f"{float(w)!r}*k{j}_{i}" for j, w in zip(rows, weights) if w != 0.0]
    return "(" + " + ".join(terms) + ")" if terms else "0.0"


def _sums_text(weights, n):
    return "[" + ", ".join(_sum_text(weights, range(len(weights)), i) for i in range(n)) + "]"


def _unpack(j, n):
    return ", ".join(f"k{j}_{i}" for i in range(n)) + f", = k{j}"


def _compile(text, name):
    space = {}
    exec(compile(text, f"<portable {name}>", "exec"), space)
    return space[name]


_CODE = {}


def _step_function(cls, n):
    """``step(fun, t, h, y, f, array) -> (y_new list, f_new, stages, errors)`` for the
    tableau of ``cls`` and n coordinates, generated once."""
    key = ("step", id(cls.A), n)          # one per tableau (TightDOP853 shares DOP853's)
    if key not in _CODE:
        S = cls.n_stages
        lines = ["def step(fun, t, h, y, f, array):",
                 "    " + ", ".join(f"y_{i}" for i in range(n)) + ", = y",
                 "    k0 = f", "    " + _unpack(0, n)]
        for s in range(1, S):
            args = ", ".join(f"y_{i} + {_sum_text(cls.A[s][:s], range(s), i)}*h"
                             for i in range(n))
            lines += [f"    k{s} = fun(t + {float(cls.C[s])!r}*h, array([{args}])).tolist()",
                      "    " + _unpack(s, n)]
        lines += ["    y_new = [" + ", ".join(f"y_{i} + h*{_sum_text(cls.B, range(S), i)}"
                                             for i in range(n)) + "]",
                  "    f_new = fun(t + h, array(y_new))",
                  f"    k{S} = f_new.tolist()", "    " + _unpack(S, n),
                  "    errors = [" + ", ".join(_sums_text(e, n) for e in cls._error_rows())
                  + "]",
                  "    return y_new, f_new, [" + ", ".join(f"k{j}" for j in range(S + 1))
                  + "], errors"]
        _CODE[key] = _compile("\n".join(lines), "step")
    return _CODE[key]


def _sums_function(rows, n, name):
    """``f(K) -> [[sum_j row[j] K[j][i] for i] for row in rows]``, generated once."""
    key = (name, n)
    if key not in _CODE:
        m = max(len(r) for r in rows)
        lines = ["def sums(K):"] + [f"    k{j} = K[{j}]\n    " + _unpack(j, n)
                                    for j in range(m)]
        lines.append("    return [" + ", ".join(_sums_text(r, n) for r in rows) + "]")
        _CODE[key] = _compile("\n".join(lines), "sums")
    return _CODE[key]


def _initial_step(fun, t0, y0, t_bound, max_step, f0, direction, order, rtol, atol):
    """scipy's ``select_initial_step`` with :func:`rms` for its norms."""
    if y0.size == 0:
        return np.inf
    interval = abs(t_bound - t0)
    if interval == 0.0:
        return 0.0
    scale = atol + np.abs(y0) * rtol
    d0, d1 = rms(y0 / scale), rms(f0 / scale)
    h0 = 1e-6 if d0 < 1e-5 or d1 < 1e-5 else 0.01 * d0 / d1
    h0 = min(h0, interval)
    f1 = fun(t0 + h0 * direction, y0 + h0 * direction * f0)
    d2 = rms((f1 - f0) / scale) / h0
    if d1 <= 1e-15 and d2 <= 1e-15:
        h1 = max(1e-6, h0 * 1e-3)
    else:
        h1 = (0.01 / max(d1, d2)) ** (1 / (order + 1))
    return min(100 * h0, h1, interval, max_step)


class _Portable:
    """The parts of scipy's ``RungeKutta`` that use the BLAS (the weighted sums of the
    stages, the error norm, the first step, the dense output), generated as plain
    Python arithmetic; the step-size control is scipy's, line for line."""

    def __init__(self, fun, t0, y0, t_bound, max_step=np.inf, rtol=1e-3, atol=1e-6,
                 vectorized=False, first_step=None, **extraneous):
        given, interval = first_step, abs(t_bound - t0)
        # a placeholder first step within the bounds (scipy's own choice would use the BLAS)
        super().__init__(fun, t0, y0, t_bound, max_step=max_step, rtol=rtol, atol=atol,
                         vectorized=vectorized, first_step=given or interval or None,
                         **extraneous)
        if given is None and interval:
            self.h_abs = _initial_step(self.fun, self.t, self.y, t_bound, self.max_step,
                                       self.f, self.direction, self.error_estimator_order,
                                       self.rtol, self.atol)
        self._step_fn = _step_function(type(self), self.n)
        self._stages = self._errors = None

    @classmethod
    def _error_rows(cls):
        return [cls.E]

    def _error_norm(self, h, scale):
        return rms(np.array(self._errors[0]) * h / scale)

    def _step_impl(self):
        t, y, rtol, atol = self.t, self.y, self.rtol, self.atol
        min_step = 10 * np.abs(np.nextafter(t, self.direction * np.inf) - t)
        h_abs = min(max(self.h_abs, min_step), self.max_step)
        accepted = rejected = False
        while not accepted:
            if h_abs < min_step:
                return False, self.TOO_SMALL_STEP
            h = h_abs * self.direction
            t_new = t + h
            if self.direction * (t_new - self.t_bound) > 0:
                t_new = self.t_bound
            h = t_new - t
            h_abs = np.abs(h)
            y_new, f_new, self._stages, self._errors = self._step_fn(
                self.fun, t, float(h), y.tolist(), self.f.tolist(), np.array)
            y_new = np.array(y_new)
            scale = atol + np.maximum(np.abs(y), np.abs(y_new)) * rtol
            error_norm = self._error_norm(h, scale)
            if error_norm < 1:
                factor = (_MAX_FACTOR if error_norm == 0 else
                          min(_MAX_FACTOR, _SAFETY * error_norm ** self.error_exponent))
                h_abs *= min(1, factor) if rejected else factor
                accepted = True
            else:
                h_abs *= max(_MIN_FACTOR, _SAFETY * error_norm ** self.error_exponent)
                rejected = True
        self.h_previous, self.y_old = h, y
        self.t, self.y, self.h_abs, self.f = t_new, y_new, h_abs, f_new
        return True, None

    def _dense_output_impl(self):
        sums = _sums_function([p for p in self.P.T], self.n, ("Q", id(self.A)))
        return _Dense(self.t_old, self.t, self.y_old, np.array(sums(self._stages)).T)


_SAFETY, _MIN_FACTOR, _MAX_FACTOR = 0.9, 0.2, 10     # scipy's rk.py


class _Dense(RkDenseOutput):
    """scipy's ``RkDenseOutput`` with ``Q @ p`` summed in order."""

    def _call_impl(self, t):
        x = (t - self.t_old) / self.h
        if t.ndim == 0:
            p = np.cumprod(np.tile(x, self.order + 1))
            return self.h * combine(self.Q.T, p) + self.y_old
        p = np.cumprod(np.tile(x, (self.order + 1, 1)), axis=0)
        return self.h * matmul_stack(self.Q[None], p[None])[0] + self.y_old[:, None]


class PortableRK45(_Portable, RK45):
    """scipy's RK45, with results that do not depend on the processor."""


class PortableRK23(_Portable, RK23):
    """scipy's RK23, with results that do not depend on the processor."""


class PortableDOP853(_Portable, DOP853):
    """scipy's DOP853, with results that do not depend on the processor."""

    @classmethod
    def _error_rows(cls):
        return [cls.E5, cls.E3]

    def _error_norm(self, h, scale):
        err5 = np.array(self._errors[0]) / scale
        err3 = np.array(self._errors[1]) / scale
        n5, n3 = fsum((err5 * err5).tolist()), fsum((err3 * err3).tolist())
        if n5 == 0 and n3 == 0:
            return 0.0
        return abs(h) * n5 / math.sqrt((n5 + 0.01 * n3) * len(scale))

    def _dense_output_impl(self):
        n, h, name = self.n, float(self.h_previous), id(self.A)
        K = list(self._stages)
        yl = self.y_old.tolist()
        for s, (a, c) in enumerate(zip(self.A_EXTRA, self.C_EXTRA), start=self.n_stages + 1):
            (dy,) = _sums_function([a[:s]], n, ("extra", s, name))(K)
            K.append(self.fun(self.t_old + c * h,
                              np.array([u + d * h for u, d in zip(yl, dy)])).tolist())
        F = np.empty((len(self.D) + 3, n))
        f_old, delta_y = np.array(K[0]), self.y - self.y_old
        F[0] = delta_y
        F[1] = h * f_old - delta_y
        F[2] = 2 * delta_y - h * (self.f + f_old)
        F[3:] = h * np.array(_sums_function(list(self.D), n, ("D", name))(K))
        return Dop853DenseOutput(self.t_old, self.t, self.y_old, F)


#: scipy's method names -> their portable classes
PORTABLE = {"RK45": PortableRK45, "RK23": PortableRK23, "DOP853": PortableDOP853}


# ----------------------------------------------------------------- functions of arrays
def _elementwise(fn):
    """``fn`` (a ``math`` function) on each element of an array, or on a float."""
    vec = np.frompyfunc(fn, 1, 1)

    def f(x):
        if np.ndim(x) == 0:
            return fn(float(x))
        return vec(np.asarray(x, dtype=float)).astype(float)
    f.__name__ = fn.__name__
    return f


def power(x, e):
    """x**e on arrays with the C library's ``pow``, element by element: the value Python's
    ``x ** e`` gives for each float (numpy's ``power`` uses AVX-512 code of its own)."""
    if np.ndim(x) == 0:
        return math.pow(float(x), e)
    return _POW(np.asarray(x, dtype=float), float(e)).astype(float)


_POW = np.frompyfunc(math.pow, 2, 1)
_ATAN2 = np.frompyfunc(math.atan2, 2, 1)


def atan2(y, x):
    """The angle of (x, y) with the C library's ``atan2``, element by element."""
    if np.ndim(y) == 0 and np.ndim(x) == 0:
        return math.atan2(float(y), float(x))
    return _ATAN2(np.asarray(y, dtype=float), np.asarray(x, dtype=float)).astype(float)


#: the functions (SymPy's names, which are also math's) that the array functions take from
#: ``math``; atan2 and powers besides (:func:`atan2`, :func:`power`)
FUNCTIONS = ("exp", "log", "sin", "cos", "tan", "atan", "asin", "acos", "sinh", "cosh",
             "tanh", "asinh", "acosh", "atanh")


def numpy_functions():
    """A namespace for ``lambdify(..., modules=[numpy_functions(), "numpy"])`` with the
    printer of ``codegen._lambdify(..., "numpy")``: the functions whose numpy versions
    depend on the processor, taken from ``math`` element by element (sin and cos too,
    which numpy takes from the C library today: the same values as the compiled scalar
    functions, by construction)."""
    out = {f"_pt_{n}": _elementwise(getattr(math, n)) for n in FUNCTIONS}
    out["_pt_atan2"] = atan2
    out["_pt_power"] = power
    return out
