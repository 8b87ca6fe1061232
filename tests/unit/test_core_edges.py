"""Valid systems the core mishandled at its edges (issue 34, items 1-3).

1. A roller racer given as a ``System`` of rigid bodies: two no-slip constraints whose
   matrix of coefficients of the dependent velocities (xdot, ydot) is not diagonal.  LU's
   first pivot is -sin(theta), so every solved velocity had a pole at theta = 0 where the
   matrix (determinant sin(phi)) is regular.
2. A vertical rolling disk whose ``me.Lagrangian`` is written with the spin psi (a
   dependent coordinate): A sin(psi)**2 phidot**2 + A cos(psi)**2 phidot**2 does not
   depend on psi, yet a syntactic ``has(psi)`` refused it.
3. A sleigh with a rotor built with ``PlanarJoint`` + ``PinJoint``: q in joint order
   (theta, x, y, alpha), ``System.u`` reordered once u_y is dependent
   (u_theta, u_x, u_alpha, u_y), so that matching speeds to coordinates by position
   refused the system.

Each test failed on the code before the fix (run and seen failing: item 1, the solved
xdot at theta = 0 was zoo; item 2, ModelError "L depends on the dependent coordinate psi";
item 3, ModelError "the System's kinematic equations must be u = qdot (... in the order
of q and u)"), and each compares with an independent derivation: a velocity solved by
hand, and ``LagrangesMethod`` with the nonholonomic constraints solved numerically (its
full mass matrix, multipliers included) at random points at 40 digits, plus the engine's
own ``verify()``.
"""
import random

import mpmath
import pytest
import sympy as sp
import sympy.physics.mechanics as me
from sympy.physics.mechanics import dynamicsymbols

import whittaker_teach as wt
from whittaker_teach.errors import ModelError
from whittaker_teach.mechanics_input import solved_velocities, speeds_as_velocities

t = dynamicsymbols._t
DIGITS = 40


# ----------------------------------------------------------------------------- models
def roller_racer(order=("theta", "phi", "x", "y")):
    """Two bodies joined by a pin at distance d1 ahead of body 1's wheels, body 2's
    wheels d2 behind the pin; q = x, y (body 1's wheel point), theta (its heading), phi
    (the joint angle, a spring k); the dependent speeds u_x, u_y."""
    x, y, th, ph = dynamicsymbols("x y theta phi")
    ux, uy, uth, uph = dynamicsymbols("u_x u_y u_theta u_phi")
    m1, m2, I1, I2, d1, d2, k = sp.symbols("m1 m2 I1 I2 d1 d2 k", positive=True)
    N = me.ReferenceFrame("N")
    O = me.Point("O")
    O.set_vel(N, 0)
    B1 = N.orientnew("B1", "Axis", (th, N.z))
    B2 = B1.orientnew("B2", "Axis", (ph, B1.z))
    B1.set_ang_vel(N, uth * N.z)
    B2.set_ang_vel(B1, uph * B1.z)
    P1 = O.locatenew("P1", x * N.x + y * N.y)
    P1.set_vel(N, ux * N.x + uy * N.y)
    Q = P1.locatenew("Q", d1 * B1.x)
    Q.v2pt_theory(P1, N, B1)
    P2 = Q.locatenew("P2", -d2 * B2.x)
    P2.v2pt_theory(Q, N, B2)
    b1 = me.RigidBody("b1", P1, B1, m1, (me.inertia(B1, 0, 0, I1), P1))
    b2 = me.RigidBody("b2", P2, B2, m2, (me.inertia(B2, 0, 0, I2), P2))
    b2.potential_energy = k * ph**2 / 2
    coords = dict(x=x, y=y, theta=th, phi=ph)
    speeds = dict(x=ux, y=uy, theta=uth, phi=uph)
    system = me.System(N, O)
    system.add_coordinates(*[coords[n] for n in order])
    system.add_speeds(uth, uph)
    system.add_speeds(ux, uy, independent=False)
    system.add_kdes(*[speeds[n] - coords[n].diff(t) for n in order])
    system.add_bodies(b1, b2)
    system.add_nonholonomic_constraints(P1.vel(N).dot(B1.y), P2.vel(N).dot(B2.y))
    return system, (x, y, th, ph), (ux, uy, uth, uph), (m1, m2, I1, I2, d1, d2, k)


def rolling_disk():
    """A vertical disk: contact point x, y, heading phi, spin psi about the axle; rolling
    and no lateral slip; dependent y and psi."""
    x, y, ph, ps = dynamicsymbols("x y phi psi")
    m, A, C, R, k = sp.symbols("m A C R k", positive=True)
    N = me.ReferenceFrame("N")
    F = N.orientnew("F", "Axis", (ph, N.z))
    D = F.orientnew("D", "Axis", (ps, F.y))
    G = me.Point("G")
    G.set_vel(N, x.diff(t) * N.x + y.diff(t) * N.y)
    disk = me.RigidBody("disk", G, D, m, (me.inertia(D, A, C, A), G))
    disk.potential_energy = k * ph**2 / 2
    xd, yd = x.diff(t), y.diff(t)
    coneqs = [yd * sp.cos(ph) - xd * sp.sin(ph),
              xd * sp.cos(ph) + yd * sp.sin(ph) - R * ps.diff(t)]
    return me.Lagrangian(N, disk), [x, y, ph, ps], coneqs


def sleigh_with_rotor():
    """A sleigh in the plane of a PlanarJoint (rotation theta about N.x, planar
    coordinates x, y), a rotor on a PinJoint at distance a along the sleigh's axis, no
    lateral slip of the sleigh's mass centre; u_y made dependent."""
    th, x, y, al = dynamicsymbols("theta x y alpha")
    uth, ux, uy, ual = dynamicsymbols("u_theta u_x u_y u_alpha")
    m, J, M, Jr, a, k = sp.symbols("m J M J_r a k", positive=True)
    ground = me.RigidBody("ground")
    sled = me.RigidBody("sled", mass=m)
    sled.inertia = (me.inertia(sled.frame, J, 0, 0), sled.masscenter)
    rotor = me.RigidBody("rotor", mass=M)
    rotor.inertia = (me.inertia(rotor.frame, Jr, 0, 0), rotor.masscenter)
    planar = me.PlanarJoint("planar", ground, sled, rotation_coordinate=th,
                            planar_coordinates=[x, y], rotation_speed=uth,
                            planar_speeds=[ux, uy])
    pin = me.PinJoint("pin", sled, rotor, coordinates=al, speeds=ual,
                      parent_point=a * sled.frame.y, joint_axis=sled.frame.x)
    sled.potential_energy = k * th**2 / 2
    system = me.System.from_newtonian(ground)
    system.add_joints(planar, pin)
    system.add_nonholonomic_constraints(sled.masscenter.vel(ground.frame).dot(sled.frame.z))
    system.u_ind = [uth, ux, ual]
    system.u_dep = [uy]
    return system, (th, x, y, al), (uth, ux, uy, ual)


# ----------------------------------------------------- the independent derivation
def _values(point, coords, extra=()):
    """{Derivative(q, t): v, q: v, parameter: v} for xreplace (velocities first)."""
    out = {}
    for c in coords:
        out[c.diff(t)] = point[c.diff(t)]
    for c in coords:
        out[c] = point[c]
    for p in extra:
        out[p] = point[p]
    return out


def _n(expr, values):
    v = sp.N(sp.sympify(expr).xreplace(values), DIGITS)
    assert v.is_finite, f"not finite: {v}"
    return mpmath.mpf(str(v))


def lagrange_accelerations(L, coords, coneqs, point):
    """{q_i'': value} of ``LagrangesMethod`` (the nonholonomic constraints, their
    multipliers) at ``point`` (every coordinate, every velocity on the constraints,
    every parameter), its full mass matrix solved numerically at 40 digits."""
    lm = me.LagrangesMethod(L, coords, nonhol_coneqs=coneqs)
    lm.form_lagranges_equations()
    MM, F = lm.mass_matrix_full, lm.forcing_full
    vals = {**point}
    for lam in lm.lam_vec:
        vals.pop(lam, None)
    with mpmath.workdps(DIGITS):
        A = mpmath.matrix([[_n(e, vals) for e in MM.row(i)] for i in range(MM.rows)])
        b = mpmath.matrix([_n(e, vals) for e in F])
        sol = mpmath.lu_solve(A, b)
    n = len(coords)
    return {c.diff(t, 2): sol[n + i] for i, c in enumerate(coords)}


def _random_point(rng, coords, dependent_solved, params, fixed=None):
    """A point with random coordinates, independent velocities and parameters, the
    dependent velocities from the given solved forms (the hand-solved ones)."""
    pt = {p: sp.Rational(rng.randint(50, 200), 100) for p in params}
    for c in coords:
        pt[c] = sp.Rational(rng.randint(10, 120), 100)
        pt[c.diff(t)] = sp.Rational(rng.choice((-1, 1)) * rng.randint(20, 150), 100)
    pt.update(fixed or {})
    for v, phi in dependent_solved.items():
        pt[v] = sp.nsimplify(sp.N(phi.xreplace(_values(pt, coords, params)), 60), rational=True)
    return pt


def _agree(S, L, coords, coneqs, point, params):
    acc = S.accelerations(dependent=True)
    want = lagrange_accelerations(L, coords, coneqs, point)
    vals = _values(point, coords, params)
    with mpmath.workdps(DIGITS):
        for a, w in want.items():
            got = _n(acc[a], vals)
            assert abs(got - w) <= mpmath.mpf(10)**-30 * max(1, abs(w)), (a, got, w)


# ------------------------------------------------------------------------- item 1
def test_roller_racer_solved_velocities_have_no_pole_where_the_matrix_is_regular():
    system, (x, y, th, ph), _, params = roller_racer()
    m1, m2, I1, I2, d1, d2, k = params
    S = wt.ChaplyginSystem.from_system(system)
    assert S.dependent_coordinates == [x, y]
    xd, yd, thd, phd = (c.diff(t) for c in (x, y, th, ph))
    # by hand: body 1 moves along B1.x at speed v; body 2's wheels do not slip sideways
    v = (d1 * sp.cos(ph) * thd - d2 * (thd + phd)) / sp.sin(ph)
    hand = {xd: v * sp.cos(th), yd: v * sp.sin(th)}
    for key, phi in S.constraints.items():
        # the only denominator is sin(phi): det of the coefficients of (xdot, ydot)
        den = sp.fraction(sp.together(phi))[1]
        assert (den / sp.sin(ph)).free_symbols <= set(params), den
        for theta in (0, sp.pi / 2, sp.pi, sp.Rational(7, 10)):
            at = {th: theta, ph: sp.Rational(3, 5)}
            got = phi.xreplace(at)
            assert got.is_finite is not False and not got.has(sp.zoo, sp.nan), (key, theta, got)
            assert sp.simplify(got - hand[key].xreplace(at)) == 0
    # at theta = 0 the whole model: accelerations equal LagrangesMethod's at 40 digits,
    # the numeric right-hand side evaluates, verify() holds
    L = S.lagrangian
    coneqs = list(S._coneqs)
    rng = random.Random(34)
    coords = [th, ph, x, y]
    for theta in (sp.S.Zero, None, None):
        fixed = {} if theta is None else {th: theta}
        pt = _random_point(rng, coords, hand, params, fixed)
        _agree(S, L, coords, coneqs, pt, params)
    f = S.lambdify_rhs()
    state = [0.0, 0.6, 0.1, 0.2, 0.7, -0.3]          # theta = 0
    assert f.state[:2] == ["theta", "phi"]
    out = f(0.0, state, {p.name: 1.0 for p in params})
    assert all(abs(o) < 10 for o in out)
    assert S.verify().ok and S.reduce(th).verify().ok


def lagrange_multipliers(L, coords, coneqs, point):
    """The multipliers of ``LagrangesMethod`` at ``point`` in the sign of its ``eom``
    (d/dt dL/dqdot - dL/dq + lambda df/dqdot, that of ``multipliers()``): minus the last
    entries of its full system's solution (mass_matrix_full carries the opposite sign),
    solved numerically at 40 digits."""
    lm = me.LagrangesMethod(L, coords, nonhol_coneqs=coneqs)
    lm.form_lagranges_equations()
    MM, F = lm.mass_matrix_full, lm.forcing_full
    with mpmath.workdps(DIGITS):
        A = mpmath.matrix([[_n(e, point) for e in MM.row(i)] for i in range(MM.rows)])
        b = mpmath.matrix([_n(e, point) for e in F])
        sol = mpmath.lu_solve(A, b)
        return [-sol[2 * len(coords) + i] for i in range(len(coneqs))]   # (negated at 40 digits)


def test_roller_racer_multipliers_have_no_pole_where_the_matrix_is_regular():
    """The multipliers solve C^T lambda = -E, C the (non-diagonal) coefficients of the
    dependent velocities: LU pivoted on sin(theta) and gave nan at theta = 0 (seen failing);
    solved fraction-free in C alone, they are finite there and equal LagrangesMethod's."""
    system, (x, y, th, ph), _, params = roller_racer()
    S = wt.ChaplyginSystem.from_system(system)
    xd, yd, thd, phd = (c.diff(t) for c in (x, y, th, ph))
    m1, m2, I1, I2, d1, d2, k = params
    v = (d1 * sp.cos(ph) * thd - d2 * (thd + phd)) / sp.sin(ph)
    hand = {xd: v * sp.cos(th), yd: v * sp.sin(th)}
    lam = S.multipliers()
    rng = random.Random(37)
    coords = [th, ph, x, y]
    for theta in (sp.S.Zero, sp.pi, None):
        pt = _random_point(rng, coords, hand, params, {} if theta is None else {th: theta})
        vals = _values(pt, coords, params)
        for key, phi in hand.items():        # exactly on the constraints, not to 16 digits
            vals[key] = phi.xreplace(vals)
        want = lagrange_multipliers(S.lagrangian, coords, list(S._coneqs), vals)
        with mpmath.workdps(DIGITS):
            for got, w in zip(lam, want):
                g = _n(got, vals)
                assert abs(g - w) <= mpmath.mpf(10)**-30 * max(1, abs(w)), (theta, g, w)


def test_non_diagonal_constraints_solved_without_pivot_denominators():
    """solved_velocities on its own: a lower-triangular matrix whose LU pivots are its
    diagonal, and a full one whose first pivot is sin(theta) but whose determinant is 1."""
    x, y, z, th = dynamicsymbols("x y z theta")
    xd, yd, zd = (c.diff(t) for c in (x, y, z))
    # rotation by theta: (xdot, ydot) = R(theta) (zdot, 0), det 1
    fs = [sp.sin(th) * xd - sp.cos(th) * yd, sp.cos(th) * xd + sp.sin(th) * yd - zd]
    sol = solved_velocities(fs, [xd, yd], t)
    assert sol == {xd: sp.cos(th) * zd, yd: sp.sin(th) * zd}
    for e, f in zip(fs, fs):
        assert sp.simplify(e.xreplace(sol)) == 0


# ------------------------------------------------------------------------- item 2
def test_lagrangian_written_with_a_dependent_coordinate_it_does_not_depend_on():
    L, coords, coneqs = rolling_disk()
    x, y, ph, ps = coords
    assert L.has(ps)                              # A sin(psi)**2 + A cos(psi)**2, as given
    S = wt.ChaplyginSystem(L, coords, nonhol_coneqs=coneqs, dependent=[y, ps])
    assert S.dependent_coordinates == [y, ps]
    assert not S.L_tilde.has(ps)
    step = [s for s in S.steps if s.label == "1.3"][0]
    assert step.check is not None and step.check.holds
    assert S.verify().ok and S.reduce(x).verify().ok
    m, A, C, R, k = sorted(S.parameters, key=str)
    params = S.parameters
    xd, phd = x.diff(t), ph.diff(t)
    hand = {y.diff(t): xd * sp.tan(ph), ps.diff(t): xd / (R * sp.cos(ph))}
    rng = random.Random(2)
    for _ in range(3):
        pt = _random_point(rng, coords, hand, params)
        _agree(S, L, coords, coneqs, pt, params)
    # a Lagrangian that does depend on psi is still refused
    with pytest.raises(ModelError, match="L depends on the dependent coordinate psi"):
        wt.ChaplyginSystem(L + k * sp.cos(ps) * phd**2, coords, nonhol_coneqs=coneqs,
                           dependent=[y, ps])


# ------------------------------------------------------------------------- item 3
def test_joint_built_system_with_speeds_reordered():
    system, (th, x, y, al), (uth, ux, uy, ual) = sleigh_with_rotor()
    assert list(system.q) == [th, x, y, al] and list(system.u) == [uth, ux, ual, uy]
    S = wt.ChaplyginSystem.from_system(system)
    assert S.dependent_coordinates == [y] and S.independent_coordinates == [th, x, al]
    assert speeds_as_velocities(list(system.kdes), list(system.q), list(system.u), t) == {
        uth: th.diff(t), ux: x.diff(t), ual: al.diff(t), uy: y.diff(t)}
    # the independent derivation: L with the speeds replaced by name, LagrangesMethod
    by_name = {uth: th.diff(t), ux: x.diff(t), uy: y.diff(t), ual: al.diff(t)}
    L = me.Lagrangian(system.frame, *system.bodies).xreplace(by_name)
    coneqs = [f.xreplace(by_name) for f in system.nonholonomic_constraints]
    assert sp.expand(S.lagrangian - L) == 0
    coords = [th, x, y, al]
    hand = {y.diff(t): x.diff(t) * sp.tan(th)}
    params = S.parameters
    rng = random.Random(3)
    for _ in range(3):
        pt = _random_point(rng, coords, hand, params)
        _agree(S, L, coords, coneqs, pt, params)
    assert S.verify().ok and S.reduce(x).verify().ok


def test_roller_racer_in_any_coordinate_order():
    """Items 1 and 3 together: q listed x, y, theta, phi while System.u lists the
    independent speeds first (u_theta, u_phi, u_x, u_y)."""
    system, (x, y, th, ph), _, params = roller_racer(order=("x", "y", "theta", "phi"))
    S = wt.ChaplyginSystem.from_system(system)
    assert S.dependent_coordinates == [x, y] and S.independent_coordinates == [th, ph]
    assert S.reduce(th).verify().ok


def test_speeds_that_are_not_one_velocity_need_the_dependent_coordinates_named():
    x, th, y = dynamicsymbols("x theta y")
    u1, u2, u3 = dynamicsymbols("u1:4")
    xd, thd, yd = (c.diff(t) for c in (x, th, y))
    # body-fixed speeds: u1 along the sleigh, u3 across it
    kdes = [u1 - (sp.cos(th) * xd + sp.sin(th) * yd), u2 - thd,
            u3 - (-sp.sin(th) * xd + sp.cos(th) * yd)]
    sol = speeds_as_velocities(kdes, [x, th, y], [u1, u2, u3], t)
    assert sol[u3] == -sp.sin(th) * xd + sp.cos(th) * yd
    m, J = sp.symbols("m J", positive=True)
    N = me.ReferenceFrame("N")
    B = N.orientnew("B", "Axis", (th, N.z))
    B.set_ang_vel(N, u2 * N.z)
    O = me.Point("O")
    O.set_vel(N, 0)
    P = O.locatenew("P", x * N.x + y * N.y)
    P.set_vel(N, u1 * B.x + u3 * B.y)
    system = me.System(N, O)
    system.add_coordinates(x, th, y)
    system.add_speeds(u1, u2)
    system.add_speeds(u3, independent=False)
    system.add_kdes(*kdes)
    system.add_bodies(me.RigidBody("s", P, B, m, (me.inertia(B, 0, 0, J), P)))
    system.add_nonholonomic_constraints(u3)
    with pytest.raises(ModelError, match="not the velocity of one coordinate"):
        wt.ChaplyginSystem.from_system(system)
    S = wt.ChaplyginSystem.from_system(system, dependent=[y])
    assert sp.simplify(S.constraints[yd] - xd * sp.tan(th)) == 0
    assert S.reduce(x).verify().ok
