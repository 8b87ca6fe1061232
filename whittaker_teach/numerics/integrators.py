r"""A structure-preserving fixed-step method: the discrete Lagrange-d'Alembert integrator.

The motion is replaced by points q_0, q_1, ... a step dt apart; the action
integral over one step by the midpoint rule,

    L_d(q_k, q_{k+1}) = dt L( (q_k + q_{k+1})/2, (q_{k+1} - q_k)/dt ),

and the constraints, written A(q) qdot = 0 (multiplied through by their
denominators, so regular where (1.3) has a pole), by A at the midpoint:

    p_k + D_1 L_d(q_k, q_{k+1}) = A(q_k)^T lambda_k,     A(q_{k+1/2}) (q_{k+1} - q_k) = 0,
    p_{k+1} = D_2 L_d(q_k, q_{k+1})

(Cortes and Martinez 2001; McLachlan and Perlmutter 2006).  Each step solves
these n + g equations for (q_{k+1}, lambda_k) by Newton's method, with the
Jacobian generated symbolically.  For a holonomic system it is the midpoint
variational integrator, which is symplectic.  It is second order; what it
buys is the long-time behaviour: on the sledge it keeps the energy to rounding
(the heading is a linear oscillator, on which it is the implicit midpoint rule);
on other non-holonomic systems its energy error stays bounded in practice,
O(dt^2), instead of drifting (the offset sleigh, chapter 8), with no general
theorem behind it: the discrete motion inherits the reversibility of the
continuous one.

>>> import whittaker_teach as wt
>>> ex = wt.examples.sledge_exact({"m": 1, "J": 1, "k": 1}, a=0.5, C=1.0)
>>> traj = wt.examples.sledge().simulate(*ex.initial(), (0, 100), {"m": 1, "J": 1, "k": 1},
...                                      method="DLA", dt=0.05)
>>> traj.energy_error < 1e-3, traj.method
(True, 'DLA')
"""

from __future__ import annotations

import numpy as np

from ..errors import ModelError
from . import codegen
from .portable import matmul_stack, solve, solve_stack
from .results import CoordDict, Trajectory

__all__ = ["simulate_dla", "dla_steps", "MAX_ENERGY_ERROR"]

NEWTON_TOL = 1e-14      # on each increment, relative to |d_i| + dt
NEWTON_MAXITER = 20


def _legendre(m, q, P):
    """(M, b) at one point: p = M qdot + b."""
    M, b = m.legendre(*q, *P)
    return np.array(M, dtype=float), np.array(b, dtype=float)


def dla_steps(m, q0, p0, dt, N, P):
    """N steps of the DLA map from (q0, p0): arrays q (N+1, n), p (N+1, n), counts.

    Each step solves for the increment d = q_{k+1} - q_k and the multipliers by
    Newton's method (the Jacobian is generated symbolically); the positions are
    accumulated with compensated (Kahan) summation, so that neither the
    velocities d/dt nor the positions lose digits as |q| grows.
    """
    n = m.n
    Q = np.empty((N + 1, n))
    Pm = np.empty((N + 1, n))
    Q[0], Pm[0] = q0, p0
    lam = [0.0] * m.g
    res, jac, nxt = m.residual, m.jacobian, m.momentum_next
    nres = 0
    qa, comp = q0.tolist(), [0.0] * n
    pa = p0.tolist()
    M0, b0 = _legendre(m, q0, P)
    d = [dt * v for v in solve(M0, (p0 - b0).tolist())]     # in Python floats: portable
    for k in range(N):
        u = d + lam
        for _ in range(NEWTON_MAXITER):
            F = res(*qa, *u, *pa, dt, *P)
            J = jac(*qa, *u, *pa, dt, *P)
            nres += 1
            try:
                du = solve(J, [-float(e) for e in F])
            except np.linalg.LinAlgError:
                raise ModelError(f"DLA step {k} (t offset {k * dt:.6g}): the Newton matrix "
                                 "is singular; reduce dt") from None
            u = [a + b for a, b in zip(u, du)]
            if all(abs(e) <= NEWTON_TOL * (abs(x) + dt) for e, x in zip(du[:n], u[:n])):
                break
        else:
            raise ModelError(f"DLA step {k} (t offset {k * dt:.6g}): Newton's method did not "
                             f"converge in {NEWTON_MAXITER} iterations; reduce dt")
        d, lam = u[:n], u[n:]
        pa = list(nxt(*qa, *d, dt, *P))
        for i in range(n):                     # q_a += d, compensated
            y = d[i] - comp[i]
            t = qa[i] + y
            comp[i] = (t - qa[i]) - y
            qa[i] = t
        Q[k + 1], Pm[k + 1] = qa, pa
    if not (np.all(np.isfinite(Q)) and np.all(np.isfinite(Pm))):
        raise ModelError("DLA produced non-finite values; reduce dt")
    return Q, Pm, nres, nres


def _stack(nested, N):
    """A nested list (lists only) of scalars and length-N arrays as one array (N, ...)."""
    leaves, shape = [], []

    def walk(x, depth):
        if isinstance(x, (list, tuple)):
            if len(shape) <= depth:
                shape.append(len(x))
            for y in x:
                walk(y, depth + 1)
        else:
            leaves.append(np.broadcast_to(np.asarray(x, dtype=float), (N,)))
    walk(nested, 0)
    return np.moveaxis(np.array(leaves).reshape(tuple(shape) + (N,)), -1, 0)


def _velocities(m, Q, Pm, P):
    """qdot at the points from p = M qdot + b, projected onto A(q) qdot = 0 (M-orthogonally)."""
    N = len(Q)
    cols = [Q[:, i] for i in range(m.n)]
    Mq, bq = m.legendre(*cols, *P)
    M, b = _stack(Mq, N), _stack(bq, N)
    v = solve_stack(M, Pm - b)                 # elementwise elimination: portable
    if m.g:
        A = _stack(m.rows(*cols, *P), N)
        MinvAT = solve_stack(M, np.swapaxes(A, 1, 2))
        S = matmul_stack(A, MinvAT)
        corr = matmul_stack(MinvAT, solve_stack(S, matmul_stack(A, v[..., None])))
        v = v - corr[..., 0]
    return v


#: A fixed-step run whose relative energy error exceeds this is refused (the step is
#: too coarse for the motion, e.g. a close approach in the Kepler problem).
MAX_ENERGY_ERROR = 1e-2


def _guard_energy(E, t, dt, limit):
    if limit is None:
        return
    dev = np.abs(E - E[0]) / max(abs(E[0]), 1e-300)
    worst = int(np.argmax(dev))
    if dev[worst] > limit:
        raise ModelError(f"DLA: the relative energy error reached {dev[worst]:.2g} at t = "
                         f"{t[worst]:.6g} (limit max_energy_error = {limit:g}): the fixed step "
                         f"dt = {dt:.3g} is too coarse for this motion; reduce dt (or pass "
                         "max_energy_error=None to accept the run)")


def simulate_dla(system, inp):
    """The full model by the DLA integrator with a fixed step close to ``inp.dt``, from
    the checked input ``inp`` (:func:`.validate.time_input`; ``system.simulate(...,
    method="DLA", dt=...)`` calls it).

    The number of steps is N = round((t1 - t0)/dt) (at least 1) and the step
    actually used is (t1 - t0)/N, so that the last point is t1.  A fixed-step
    method does not estimate its error; as a guard, a run whose relative energy
    error exceeds ``max_energy_error`` (None: no guard) raises a ModelError.
    """
    t0, t1 = inp.span
    dense, max_energy_error, P = inp.dense, inp.max_energy_error, inp.p
    N = max(1, int(round(abs(t1 - t0) / inp.dt)))
    if N > 10**8:
        raise ModelError(f"dt = {inp.dt} gives {N} steps: too many")
    h = (t1 - t0) / N
    m = codegen.dla_model(system)
    q, p = m.initial_state(inp.q, inp.v, P)
    Q, Pm, nres, njac = dla_steps(m, q, p, h, N, P)
    t = t0 + h * np.arange(N + 1)
    V = _velocities(m, Q, Pm, P)
    E = np.broadcast_to(np.asarray(m.energy(*Q.T, *V.T, *P), dtype=float), t.shape)
    if not (np.all(np.isfinite(V)) and np.all(np.isfinite(E))):
        raise ModelError("DLA: non-finite velocities or energy; reduce dt")
    _guard_energy(E, t, h, max_energy_error)
    S = system
    qd = CoordDict((c, Q[:, i]) for i, c in enumerate(S.coordinates))
    vd = CoordDict((c, V[:, i]) for i, c in enumerate(S.coordinates))
    interp = None
    if dense:
        from scipy.interpolate import CubicHermiteSpline
        spline = CubicHermiteSpline(t, Q, V, axis=0)

        def interp(tt):
            return np.moveaxis(spline(tt), -1, 0)
    return Trajectory(t, qd, vd, np.array(E), float(E[0]), nres, njac, "DLA",
                      "discrete Lagrange-d'Alembert (midpoint)", list(S.coordinates), interp)
