"""Numerical integration of the rolling bodies (numpy and scipy; import this module
only where the numerics are installed: ``whittaker_teach.rolling`` imports it lazily).

The equations are the symbolic ones of :mod:`.ball` and :mod:`.rattleback_model`, turned
into numpy functions by ``sympy.lambdify``; the orientation is carried as the rotation
matrix Q (body -> space components), dQ/dt = Q [omega]x, so that the body can be drawn,
and the centre's horizontal position as dG/dt = Q v_G.  Runs use DOP853 with tight
tolerances; each result carries the integrals evaluated along it, so that their drift
is measured, not assumed.

numpy and scipy are imported at the first call, not at import (every module of the
package imports without them); without them a call raises ``ModuleNotFoundError``
naming the ``[numerics]`` extra.
"""

from __future__ import annotations

import sympy as sp

np = solve_ivp = None          # numpy and scipy.integrate.solve_ivp, set by _load()

__all__ = ["simulate_rattleback", "simulate_ball", "ball_volume_ratio", "disk_run",
           "tilt_rotation"]


def _load():
    global np, solve_ivp
    if np is None:
        try:
            import numpy
            from scipy.integrate import solve_ivp as ivp
        except ImportError as err:
            raise ModuleNotFoundError(
                "whittaker_teach.rolling.simulate needs numpy and scipy, the [numerics] "
                "extra: pip install 'whittaker-teach[numerics]'") from err
        np, solve_ivp = numpy, ivp


def _hat(w):
    return np.array([[0.0, -w[2], w[1]], [w[2], 0.0, -w[0]], [-w[1], w[0], 0.0]])


def tilt_rotation(angle, axis):
    """The rotation matrix by ``angle`` about the unit ``axis`` (Rodrigues)."""
    _load()
    a = np.asarray(axis, float)
    a = a / np.linalg.norm(a)
    K = _hat(a)
    return np.eye(3) + np.sin(angle) * K + (1 - np.cos(angle)) * K @ K


def _run(rhs, s0, t_end, n, rtol, atol, what):
    """DOP853 from 0 to ``t_end``, the state at n equally spaced times; a failure named."""
    t = np.linspace(0.0, t_end, n)
    sol = solve_ivp(rhs, (0.0, t_end), s0, method="DOP853", rtol=rtol, atol=atol, t_eval=t)
    if not sol.success:
        raise RuntimeError(f"{what} failed: {sol.message}")
    return sol


def _rattleback_functions(values):
    from .rattleback_model import RattlebackVectors
    rv = RattlebackVectors()
    sub = rv.values(values)
    args = [*rv.omega, *rv.gamma]
    K = sp.lambdify(args, rv.mass_matrix.xreplace(sub), "numpy")
    f = sp.lambdify(args, rv.force.xreplace(sub), "numpy")
    r = sp.lambdify(args[3:], rv.r.xreplace(sub), "numpy")
    E = sp.lambdify(args, rv.energy.xreplace(sub), "numpy")
    return K, f, r, E


def simulate_rattleback(values, omega0, tilt=(0.0, 0.0), t_end=20.0, n=2001,
                        rtol=1e-10, atol=1e-12):
    """Integrate the rattleback from the orientation tilted by ``tilt`` = (about x, about
    y) radians from the lowest position, with body angular velocity ``omega0``.
    ``values``: {name: number} for m, g, h, rho_1, rho_2, A, B, C, delta.

    Returns a dict: t, omega (n x 3, body), gamma (n x 3), Q (n x 3 x 3), G (n x 3, the
    centre in space), P (n x 2, the contact point on the plane), energy, spin (the
    vertical component of omega, gamma . omega)."""
    _load()
    K, f, rfun, Efun = _rattleback_functions(values)
    Q0 = tilt_rotation(tilt[0], [1, 0, 0]) @ tilt_rotation(tilt[1], [0, 1, 0])

    def rhs(t, s):
        w, Q = s[:3], s[3:12].reshape(3, 3)
        gm = Q[2]                                   # space z in body components
        wdot = np.linalg.solve(np.array(K(*w, *gm), float), np.array(f(*w, *gm), float).ravel())
        Qdot = Q @ _hat(w)
        r = np.array(rfun(*gm), float).ravel()
        vG = Q @ np.cross(r, w)
        return np.concatenate([wdot, Qdot.ravel(), vG[:2]])

    s0 = np.concatenate([np.asarray(omega0, float), Q0.ravel(), [0.0, 0.0]])
    sol = _run(rhs, s0, t_end, n, rtol, atol, "the rattleback's integration")
    w = sol.y[:3].T
    Q = sol.y[3:12].T.reshape(-1, 3, 3)
    gm = Q[:, 2, :]
    r = np.array([np.array(rfun(*g), float).ravel() for g in gm])
    height = -np.einsum("ij,ij->i", r, gm)
    G = np.column_stack([sol.y[12], sol.y[13], height])
    P = G[:, :2] + np.einsum("nij,nj->ni", Q, r)[:, :2]
    energy = np.array([float(Efun(*wi, *gi)) for wi, gi in zip(w, gm)])
    spin = np.einsum("ij,ij->i", w, gm)
    return dict(t=sol.t, omega=w, gamma=gm, Q=Q, G=G, P=P, energy=energy, spin=spin,
                orthogonality=float(np.max(np.abs(np.einsum("nij,nkj->nik", Q, Q)
                                                  - np.eye(3)))), nfev=sol.nfev)


def _ball_functions(values):
    from .ball import BallVectors
    bv = BallVectors()
    A, B, C, D = bv.parameters
    sub = {A: values["A"], B: values["B"], C: values["C"], D: values["m"] * values["R"]**2}
    args = [*bv.M, *bv.gamma]
    omega = sp.lambdify(args, bv.omega.xreplace(sub), "numpy")
    ints = {k: sp.lambdify(args, e.xreplace(sub), "numpy") for k, e in bv.integrals.items()}
    rho = sp.lambdify(args[3:], bv.density.xreplace(sub), "numpy")
    Mof = sp.lambdify([*sp.symbols("w1:4"), *args[3:]],
                      bv.momentum_of(sp.symbols("w1:4"), bv.gamma).xreplace(sub), "numpy")
    return omega, ints, rho, Mof


def simulate_ball(values, omega0, Q0=None, t_end=20.0, n=2001, rtol=1e-11, atol=1e-13):
    """Integrate the Chaplygin ball (``values``: A, B, C, m, R) from the orientation Q0
    (body -> space; identity by default) with body angular velocity ``omega0``.

    Returns a dict: t, M (body), gamma, Q, omega, P (the contact point), the integrals
    {name: array} of :class:`.ball.BallVectors`, K_space (Q M: the angular momentum
    about the contact point in space components, constant) and the density rho(gamma)."""
    _load()
    omega, ints, rho, Mof = _ball_functions(values)
    Q0 = np.eye(3) if Q0 is None else np.asarray(Q0, float)
    g0 = Q0[2]
    M0 = np.array(Mof(*omega0, *g0), float).ravel()
    R = values["R"]

    def rhs(t, s):
        M, Q = s[:3], s[3:12].reshape(3, 3)
        gm = Q[2]
        w = np.array(omega(*M, *gm), float).ravel()
        vG = Q @ np.cross(w, R * gm)
        return np.concatenate([np.cross(M, w), (Q @ _hat(w)).ravel(), vG[:2]])

    s0 = np.concatenate([M0, Q0.ravel(), [0.0, 0.0]])
    sol = _run(rhs, s0, t_end, n, rtol, atol, "the ball's integration")
    M = sol.y[:3].T
    Q = sol.y[3:12].T.reshape(-1, 3, 3)
    gm = Q[:, 2, :]
    w = np.array([np.array(omega(*Mi, *gi), float).ravel() for Mi, gi in zip(M, gm)])
    integrals = {k: np.array([float(fn(*Mi, *gi)) for Mi, gi in zip(M, gm)])
                 for k, fn in ints.items()}
    return dict(t=sol.t, M=M, gamma=gm, Q=Q, omega=w, P=sol.y[12:14].T, integrals=integrals,
                K_space=np.einsum("nij,nj->ni", Q, M),
                rho=np.array([float(rho(*g)) for g in gm]))


def ball_volume_ratio(values, M0, gamma0, t_end, h=1e-5, rtol=1e-12, atol=1e-14):
    """The invariant measure checked along a motion: the flow map's Jacobian Phi in the
    variables (M, gamma) of R^6 by central differences of step ``h``; returns
    (det Phi, rho(x0)/rho(x(t_end)), rho(x0)), which are equal when rho dM dgamma is
    invariant (det Phi alone, the Lebesgue volume ratio, is not 1)."""
    _load()
    omega, ints, rho, Mof = _ball_functions(values)

    def rhs(t, s):
        M, gm = s[:3], s[3:]
        w = np.array(omega(*M, *gm), float).ravel()
        return np.concatenate([np.cross(M, w), np.cross(gm, w)])

    def flow(x):
        sol = solve_ivp(rhs, (0.0, t_end), x, method="DOP853", rtol=rtol, atol=atol)
        return sol.y[:, -1]

    x0 = np.concatenate([np.asarray(M0, float), np.asarray(gamma0, float)])
    Phi = np.empty((6, 6))
    for j in range(6):
        e = np.zeros(6)
        e[j] = h
        Phi[:, j] = (flow(x0 + e) - flow(x0 - e)) / (2 * h)
    x1 = flow(x0)
    return float(np.linalg.det(Phi)), float(rho(*x0[3:]) / rho(*x1[3:])), float(rho(*x0[3:]))


def disk_run(omega, tilt_rate, t_end, n=2001, rtol=1e-10):
    """The uniform tilting disk (R = g = m = 1) of
    :func:`whittaker_teach.stability.tilting_disk`, started upright rolling at
    ``omega`` with tilt rate ``tilt_rate``, integrated by the library's ``simulate``;
    returns the library's trajectory."""
    _load()
    from ..stability import tilting_disk
    disk = tilting_disk()
    return disk.simulate({"x": 0, "y": 0, "psi": 0, "phi": 0, "theta": 0},
                         {"psi": 0, "phi": tilt_rate, "theta": omega}, (0, t_end),
                         {"m": 1.0, "R": 1.0, "g": 1.0}, rtol=rtol,
                         t_eval=np.linspace(0, t_end, n))
