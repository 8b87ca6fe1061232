"""Nonlinear homogeneous constraints whose square is not a polynomial in the velocities
(issue 26, item 1): the reduction (1.26) agrees with a multiplier derivation done by hand.

L = (xdot^2 + ydot^2 + zdot^2)/2 - y^2/2 with zdot = phi(y, xdot, ydot), phi homogeneous of
degree one.  The multiplier (Chetaev) equations, independent of whittaker_teach:

    d/dt dL/dqdot_s - dL/dq_s = lambda df/dqdot_s,   f = zdot - phi,   df/dt = 0,

solved at a random point for (xddot, yddot, zddot, lambda) in 40 digits.  The reduced
q'' = y'' (q_eps = x) is then (yddot xdot - ydot xddot)/xdot^3, to compare with
``red.accelerations()`` at y' = ydot/xdot and h = the energy at the point.
"""

import random

import mpmath
import pytest
import sympy as sp
from sympy.physics.mechanics import dynamicsymbols

import whittaker_teach as wt
from whittaker_teach.errors import ModelError

from .numbers import DPS, close, num, rat

t = dynamicsymbols._t
x, y, z = dynamicsymbols("x y z")
xd, yd, zd = (c.diff(t) for c in (x, y, z))
L = (xd**2 + yd**2 + zd**2) / 2 - y**2 / 2

CONSTRAINTS = {
    "ratio": (xd**2 + yd**2) / sp.sqrt(xd**2 + 2 * yd**2),   # refused before issue 26
    "product": xd * yd / sp.sqrt(xd**2 + yd**2),              # refused before issue 26
    "chetaev-y": sp.sqrt(xd**2 + y**2 * yd**2),
    "chetaev-x": sp.sqrt(xd**2 + yd**2) + x * yd / 2,
}


@pytest.fixture(scope="module", params=sorted(CONSTRAINTS))
def case(request):
    phi = CONSTRAINTS[request.param]
    system = wt.ChaplyginSystem(L, [x, y, z], dependent={zd: phi}, name=request.param)
    lam = sp.Symbol("lambda_")
    f = zd - phi
    eqs = [sp.diff(L, c.diff(t)).diff(t) - sp.diff(L, c) - lam * sp.diff(f, c.diff(t))
           for c in (x, y, z)]
    eqs.append(f.diff(t))
    return system, eqs, lam


def multiplier_accelerations(eqs, lam, pt):
    qdd = [c.diff(t, 2) for c in (x, y, z)]
    unknowns = sp.symbols("a_x a_y a_z") + (lam,)
    lin = [e.xreplace(dict(zip(qdd, unknowns[:3]))).xreplace(pt) for e in eqs]
    M, rhs = sp.linear_eq_to_matrix(lin, unknowns)
    with mpmath.workdps(DPS + 10):
        Mn = mpmath.matrix([[num(M[i, j], {}) for j in range(4)] for i in range(4)])
        sol = mpmath.lu_solve(Mn, mpmath.matrix([num(rhs[i], {}) for i in range(4)]))
    return dict(zip((x, y, z), sol[:3]))


@pytest.mark.parametrize("direction", [+1, -1])
def test_reduces_verifies_and_agrees_with_multipliers(case, direction):
    system, eqs, lam = case
    red = system.reduce(x, direction=direction)
    assert red.verify().ok
    (ypp, expr), = red.accelerations().items()
    Y = red.coordinates[0]
    X = red.independent
    E = system.energy()
    rng = random.Random(26 + direction)
    for _ in range(3):
        pt = {x: rat(rng, 0.1, 1.2), y: rat(rng, 0.1, 1.2), z: rat(rng, 0.1, 1.2),
              xd: direction * rat(rng, 0.3, 1.5), yd: rng.choice((-1, 1)) * rat(rng, 0.2, 1.5)}
        pt[zd] = CONSTRAINTS[system.name].xreplace(pt)
        acc = multiplier_accelerations(eqs, lam, pt)
        with mpmath.workdps(DPS + 10):
            xdot, ydot = num(xd, pt), num(yd, pt)
            expected = (acc[y] * xdot - ydot * acc[x]) / xdot**3
            h = E.xreplace(pt)
            at = {Y.diff(X): pt[yd] / pt[xd], red.h: h}
            mine = num(expr.xreplace(at).xreplace({Y: pt[y], X: pt[x]}), {})
            assert close(mine, expected), (system.name, direction, mine, expected)


def test_not_quadratic_is_still_refused():
    """Omega quartic in the velocity: the clear ModelError naming (1.13) stays."""
    S = wt.ChaplyginSystem(xd**4 / 4 + yd**2 / 2 - y**2 / 2, [x, y])
    with pytest.raises(ModelError, match=r"1\.13.*not quadratic"):
        S.reduce(x)
    S = wt.ChaplyginSystem(L, [x, y, z], dependent={zd: (xd**3 + yd**3) / (xd**2 + yd**2)
                                                    + (xd**2 + yd**2) ** sp.Rational(3, 4)})
    with pytest.raises(ModelError, match=r"1\.10"):
        S.reduce(x)
