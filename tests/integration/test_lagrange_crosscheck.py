"""Cross-check the Chaplygin accelerations (1.4) against Lagrange's equations with
multipliers, derived independently of whittaker_teach.

For the systems with constraints linear in the velocities (sledge, offset sleigh,
rolling disk) the multiplier equations come from
``sympy.physics.mechanics.LagrangesMethod`` with ``nonhol_coneqs``, over ALL the
coordinates (dependent ones included).  The cone constraint
zdot = a sqrt(xdot^2 + ydot^2) is not linear in the velocities, which
LagrangesMethod does not accept, so its Chetaev form is written out by hand:

    d/dt dL/dqdot_s - dL/dq_s = lambda df/dqdot_s,   f = zdot - a sqrt(xdot^2 + ydot^2),

closed by df/dt = 0.  At random admissible points (coordinates in (0.1, 1.2),
independent velocities of modulus in (0.2, 1.5), parameters in (0.5, 2), the
dependent velocities set by the constraints) the independent accelerations of the
multiplier formulation must equal ``sys.accelerations()``, and its dependent
accelerations must equal d/dt of the constraints evaluated with them.

Everything is taken from the examples themselves (``sys.lagrangian``,
``sys.constraints``, ``sys.coordinates``), so nothing is retyped.
"""

import random

import mpmath
import pytest
import sympy as sp
from sympy.physics.mechanics import LagrangesMethod, dynamicsymbols

import whittaker_teach as wt

from .numbers import DPS, TOL, close, num, rat  # noqa: F401

t = dynamicsymbols._t
N_POINTS = 4


def random_point(system, rng):
    """Coordinates, independent velocities (random sign) and parameters; the
    dependent velocities follow from the constraints."""
    pt = {p: rat(rng, 0.5, 2.0) for p in system.parameters}
    for c in system.coordinates:
        pt[c] = rat(rng, 0.1, 1.2)
    for c in system.independent_coordinates:
        pt[c.diff(t)] = rng.choice((-1, 1)) * rat(rng, 0.2, 1.5)
    for qd, phi in system.constraints.items():
        pt[qd] = sp.sympify(phi).xreplace(pt)
    return pt


def constraint_rate(phi):
    """d/dt of a constraint phi(q_sigma, qdot_sigma), in dynamicsymbols."""
    return sp.sympify(phi).diff(t)


def acc_subs(system, acc, pt):
    """{q.diff(t, 2): exact value} of the library's accelerations at pt."""
    return {k: sp.sympify(v).xreplace(pt) for k, v in acc.items()}


# ------------------------------------------------------------ linear constraints
LINEAR = ["sledge", "offset_sleigh", "rolling_disk"]


@pytest.fixture(scope="module", params=LINEAR)
def linear_case(request):
    system = getattr(wt.examples, request.param)()
    coneqs = [qd - phi for qd, phi in system.constraints.items()]
    lm = LagrangesMethod(system.lagrangian, system.coordinates, nonhol_coneqs=coneqs)
    lm.form_lagranges_equations()
    return system, lm


def lagranges_method_solution(system, lm, pt):
    """Solve mass_matrix_full x = forcing_full at the point: x = [qdot, qddot, lambda]."""
    n = len(system.coordinates)
    M = lm.mass_matrix_full
    F = lm.forcing_full
    with mpmath.workdps(DPS + 10):
        Mn = mpmath.matrix([[num(M[i, j], pt) for j in range(M.cols)] for i in range(M.rows)])
        Fn = mpmath.matrix([num(F[i], pt) for i in range(F.rows)])
        x = mpmath.lu_solve(Mn, Fn)
    qdot = dict(zip(system.coordinates, [x[i] for i in range(n)]))
    qddot = dict(zip(system.coordinates, [x[n + i] for i in range(n)]))
    lam = [x[2 * n + i] for i in range(len(x) - 2 * n)]
    return qdot, qddot, lam


def test_linear_constraints_are_linear(linear_case):
    """Sanity: the constraints passed to LagrangesMethod are linear in all velocities."""
    system, _ = linear_case
    qds = [c.diff(t) for c in system.coordinates]
    for qd, phi in system.constraints.items():
        f = qd - phi
        for v in qds:
            assert sp.diff(f, v, 2) == 0


@pytest.mark.parametrize("seed", range(N_POINTS))
def test_independent_accelerations_match_lagranges_method(linear_case, seed):
    system, lm = linear_case
    rng = random.Random(1000 + seed)
    pt = random_point(system, rng)
    qdot_lm, qddot_lm, _ = lagranges_method_solution(system, lm, pt)
    acc = system.accelerations()
    assert set(acc) == {c.diff(t, 2) for c in system.independent_coordinates}
    with mpmath.workdps(DPS + 10):
        # the kinematic rows of the full system reproduce the velocities we put in
        for c in system.coordinates:
            assert close(qdot_lm[c], num(c.diff(t), pt))
        for c in system.independent_coordinates:
            mine = num(acc[c.diff(t, 2)], pt)
            assert close(mine, qddot_lm[c]), (system.name, c, mine, qddot_lm[c])


@pytest.mark.parametrize("seed", range(N_POINTS))
def test_dependent_accelerations_are_constraint_rates(linear_case, seed):
    """LagrangesMethod's qddot_dep equals d/dt phi evaluated with the library's
    independent accelerations."""
    system, lm = linear_case
    rng = random.Random(2000 + seed)
    pt = random_point(system, rng)
    _, qddot_lm, _ = lagranges_method_solution(system, lm, pt)
    acc = system.accelerations()
    full = dict(pt)
    full.update(acc_subs(system, acc, pt))
    with mpmath.workdps(DPS + 10):
        for qd, phi in system.constraints.items():
            dep = qd.expr
            rate = num(constraint_rate(phi), full)
            assert close(rate, qddot_lm[dep]), (system.name, dep, rate, qddot_lm[dep])


@pytest.mark.parametrize("seed", range(2))
def test_equations_of_motion_vanish_at_lagranges_method_accelerations(linear_case, seed):
    """(1.4) itself (not only its solved form) holds at the multiplier solution."""
    system, lm = linear_case
    rng = random.Random(3000 + seed)
    pt = random_point(system, rng)
    _, qddot_lm, _ = lagranges_method_solution(system, lm, pt)
    full = dict(pt)
    for c in system.independent_coordinates:
        full[c.diff(t, 2)] = sp.Float(mpmath.nstr(qddot_lm[c], DPS + 5), DPS + 10)
    with mpmath.workdps(DPS + 10):
        for e in system.equations_of_motion():
            assert abs(num(e, full)) < TOL


# ------------------------------------------------------------ the cone: by hand
@pytest.fixture(scope="module")
def cone_case():
    system = wt.examples.cone_particle()
    (qd_dep, phi), = system.constraints.items()
    f = qd_dep - phi                                  # zdot - a sqrt(xdot^2 + ydot^2)
    lam = sp.Symbol("lambda_")
    L = system.lagrangian
    eqs = [sp.diff(L, c.diff(t)).diff(t) - sp.diff(L, c) - lam * sp.diff(f, c.diff(t))
           for c in system.coordinates]
    eqs.append(f.diff(t))
    return system, eqs, lam, f


def chetaev_solution(system, eqs, lam, pt):
    """Solve the multiplier equations (linear in qddot and lambda) at the point."""
    qdd = [c.diff(t, 2) for c in system.coordinates]
    A = sp.Symbol("A_0"), sp.Symbol("A_1"), sp.Symbol("A_2")
    unknowns = list(A[:len(qdd)]) + [lam]
    lin = [e.xreplace(dict(zip(qdd, A))).xreplace(pt) for e in eqs]
    Mat, rhs = sp.linear_eq_to_matrix(lin, unknowns)
    with mpmath.workdps(DPS + 10):
        Mn = mpmath.matrix([[num(Mat[i, j], {}) for j in range(Mat.cols)]
                            for i in range(Mat.rows)])
        Fn = mpmath.matrix([num(rhs[i], {}) for i in range(rhs.rows)])
        x = mpmath.lu_solve(Mn, Fn)
    return dict(zip(system.coordinates, [x[i] for i in range(len(qdd))])), x[len(qdd)]


def test_cone_constraint_is_not_linear(cone_case):
    system, _, _, f = cone_case
    x, y, z = system.coordinates
    assert sp.diff(f, x.diff(t), 2) != 0


@pytest.mark.parametrize("seed", range(N_POINTS))
def test_cone_accelerations_match_chetaev_multipliers(cone_case, seed):
    system, eqs, lam, _ = cone_case
    rng = random.Random(4000 + seed)
    pt = random_point(system, rng)
    qddot_ch, _ = chetaev_solution(system, eqs, lam, pt)
    acc = system.accelerations()
    assert set(acc) == {c.diff(t, 2) for c in system.independent_coordinates}
    full = dict(pt)
    full.update(acc_subs(system, acc, pt))
    with mpmath.workdps(DPS + 10):
        for c in system.independent_coordinates:
            mine = num(acc[c.diff(t, 2)], pt)
            assert close(mine, qddot_ch[c]), (c, mine, qddot_ch[c])
        # the dependent acceleration: d/dt of the constraint with the library's accelerations
        for qd, phi in system.constraints.items():
            rate = num(constraint_rate(phi), full)
            assert close(rate, qddot_ch[qd.expr]), (qd, rate, qddot_ch[qd.expr])


@pytest.mark.parametrize("direction", [+1, -1])
def test_cone_both_directions_of_travel(cone_case, direction):
    """phi(-v) = phi(v): reversing every independent velocity keeps zdot > 0; the
    accelerations must still match the multiplier solution (no hidden sign choice)."""
    system, eqs, lam, _ = cone_case
    rng = random.Random(5000 + direction)
    pt = random_point(system, rng)
    for c in system.independent_coordinates:
        pt[c.diff(t)] = direction * abs(pt[c.diff(t)])
    for qd, phi in system.constraints.items():
        pt[qd] = sp.sympify(phi).xreplace(pt)
    qddot_ch, _ = chetaev_solution(system, eqs, lam, pt)
    acc = system.accelerations()
    with mpmath.workdps(DPS + 10):
        for c in system.independent_coordinates:
            assert close(num(acc[c.diff(t, 2)], pt), qddot_ch[c])
