"""The reduced equations (1.26) agree with the time-domain ones (1.4) by the chain rule.

Along a motion, q_nu becomes a function of q_eps with (1.5)

    q'_nu  = qdot_nu / qdot_eps,
    q''_nu = (qddot_nu qdot_eps - qdot_nu qddot_eps) / qdot_eps^3.

At random points: coordinates, q'_nu and qdot_eps with the sign of ``direction``;
qdot_nu = qdot_eps q'_nu; h = the energy (1.11) of that state.  Then
``red.accelerations()`` at (coordinates, q', h) must equal the chain-rule value
built from ``sys.accelerations()``, ``red.velocity`` at h must give back qdot_eps
(sign included), and the reduced constraint rates (1.23) must equal
qdot_dep / qdot_eps.  All arithmetic at 40 digits, tolerance 1e-20 relative.
"""

import random

import mpmath
import pytest
import sympy as sp
from sympy.physics.mechanics import dynamicsymbols

import whittaker_teach as wt

from .numbers import DPS, TOL, close, num, rat  # noqa: F401

t = dynamicsymbols._t
N_POINTS = 3

# (example, q_eps) for every built-in system: first the reduction the book uses,
# then every other choice of q_eps among the independent coordinates
DEFAULT_EPS = {
    "sledge": "x",
    "offset_sleigh": "x",
    "rolling_disk": "theta",
    "cone_particle": "x",
    "projectile": "x",
    "kepler": "theta",
    "charged_particle": "x",
}
OTHER_EPS = {
    "sledge": "theta",
    "offset_sleigh": "theta",
    "rolling_disk": "psi",
    "cone_particle": "y",
    "projectile": "y",
    "kepler": "r",
    "charged_particle": "y",
}
CASES = list(DEFAULT_EPS.items()) + list(OTHER_EPS.items())


_SYSTEMS, _REDUCTIONS = {}, {}


def system_of(name):
    if name not in _SYSTEMS:
        _SYSTEMS[name] = getattr(wt.examples, name)()
    return _SYSTEMS[name]


def reduction_of(name, eps, direction):
    key = (name, eps, direction)
    if key not in _REDUCTIONS:
        _REDUCTIONS[key] = system_of(name).reduce(eps, direction=direction)
    return _REDUCTIONS[key]


def coordinate(system, name):
    (c,) = [c for c in system.coordinates if c.func.__name__ == name]
    return c


def motion_point(system, eps, direction, rng):
    """A state (time domain) with sign(qdot_eps) = direction, and its reduced image.

    Returns (time_pt, primes, v): time_pt maps the dynamicsymbols q, qdot_sigma and
    the parameters to exact numbers (plus h: the energy of the state); primes maps
    each q_nu to q'_nu; v is qdot_eps."""
    pt = {p: rat(rng, 0.5, 2.0) for p in system.parameters}
    for c in system.coordinates:
        pt[c] = rat(rng, 0.1, 1.2)
    v = direction * rat(rng, 0.3, 1.5)
    pt[eps.diff(t)] = v
    primes = {}
    for c in system.independent_coordinates:
        if c != eps:
            primes[c] = rat(rng, -1, 1)
            pt[c.diff(t)] = v * primes[c]
    h = sp.sympify(system.energy()).xreplace(pt)
    assert not h.free_symbols
    return pt, primes, v, h


def reduced_point(red, system, pt, primes, h):
    """The substitution for reduced expressions: q_nu(x), q_nu'(x), x, h, parameters."""
    x = red.independent
    sub = {p: pt[p] for p in system.parameters}
    sub[red.h] = h
    nus = [c for c in system.independent_coordinates if c.func.__name__ != x.name]
    eps = [c for c in system.independent_coordinates if c.func.__name__ == x.name][0]
    sub[x] = pt[eps]
    by_name = {c.func.__name__: c for c in nus}
    for f in red.coordinates:
        c = by_name[f.func.__name__]
        sub[f.diff(x)] = primes[c]
        sub[f] = pt[c]
    return sub


def chain_rule_second_derivatives(system, eps, pt, v):
    """q''_nu = (qddot_nu qdot_eps - qdot_nu qddot_eps) / qdot_eps^3 from (1.4)."""
    acc = system.accelerations()
    a_eps = num(acc[eps.diff(t, 2)], pt)
    vv = num(v, {})
    out = {}
    for c in system.independent_coordinates:
        if c == eps:
            continue
        a_nu = num(acc[c.diff(t, 2)], pt)
        qd_nu = num(pt[c.diff(t)], {})
        out[c] = (a_nu * vv - qd_nu * a_eps) / vv**3
    return out


PARAMS = [(name, eps, d) for name, eps in CASES for d in (+1, -1)]


@pytest.mark.parametrize("name,eps_name,direction", PARAMS)
def test_reduced_accelerations_follow_the_chain_rule(name, eps_name, direction):
    system = system_of(name)
    red = reduction_of(name, eps_name, direction)
    eps = coordinate(system, eps_name)
    racc = red.accelerations()
    x = red.independent
    assert set(racc) == {f.diff(x, 2) for f in red.coordinates}
    rng = random.Random(17 * len(name) + direction)
    with mpmath.workdps(DPS + 10):
        for _ in range(N_POINTS):
            pt, primes, v, h = motion_point(system, eps, direction, rng)
            expected = chain_rule_second_derivatives(system, eps, pt, v)
            sub = reduced_point(red, system, pt, primes, h)
            by_name = {c.func.__name__: c for c in expected}
            for f in red.coordinates:
                got = num(racc[f.diff(x, 2)], sub)
                want = expected[by_name[f.func.__name__]]
                assert close(got, want), (name, direction, f, got, want)


@pytest.mark.parametrize("name,eps_name,direction", PARAMS)
def test_reduced_velocity_gives_back_qdot_eps(name, eps_name, direction):
    """(1.12) at h = energy of the state returns qdot_eps, with its sign."""
    system = system_of(name)
    red = reduction_of(name, eps_name, direction)
    eps = coordinate(system, eps_name)
    rng = random.Random(31 * len(name) + direction)
    with mpmath.workdps(DPS + 10):
        for _ in range(N_POINTS):
            pt, primes, v, h = motion_point(system, eps, direction, rng)
            sub = reduced_point(red, system, pt, primes, h)
            got = num(red.velocity, sub)
            assert mpmath.sign(got) == direction
            assert close(got, num(v, {})), (name, direction, got, v)
            # and t(q_eps) by quadrature: dt/dq_eps = 1/qdot_eps
            assert close(num(red.time_rate, sub), 1 / num(v, {}))


NONHOLONOMIC = [(n, e, d) for n, e, d in PARAMS
                if n in ("sledge", "offset_sleigh", "rolling_disk", "cone_particle")]


@pytest.mark.parametrize("name,eps_name,direction", NONHOLONOMIC)
def test_constraint_rates_follow_the_chain_rule(name, eps_name, direction):
    """dq_dep/dq_eps = qdot*_dep (1.23) = qdot_dep / qdot_eps along the motion."""
    system = system_of(name)
    red = reduction_of(name, eps_name, direction)
    eps = coordinate(system, eps_name)
    rates = red.constraint_rates
    assert {f.func.__name__ for f in rates} == {c.func.__name__
                                                 for c in system.dependent_coordinates}
    rng = random.Random(57 * len(name) + direction)
    with mpmath.workdps(DPS + 10):
        for _ in range(N_POINTS):
            pt, primes, v, h = motion_point(system, eps, direction, rng)
            sub = reduced_point(red, system, pt, primes, h)
            for f, rate in rates.items():
                qd = [k for k in system.constraints if k.expr.func.__name__ == f.func.__name__][0]
                want = num(system.constraints[qd], pt) / num(v, {})
                assert close(num(rate, sub), want), (name, direction, f)


def _reduced_accel_values(red, system, pt, primes, h):
    sub = reduced_point(red, system, pt, primes, h)
    return [num(e, sub) for _, e in sorted(red.accelerations().items(), key=str)]


def test_charged_particle_directions_differ():
    """The gyroscopic term B x ydot makes (1.26) depend on the direction of travel:
    at the same (x, y, y', h) the two reductions give different y''."""
    system = system_of("charged_particle")
    eps = coordinate(system, "x")
    plus = reduction_of("charged_particle", "x", +1)
    minus = reduction_of("charged_particle", "x", -1)
    diff = sp.expand(plus.L_star - minus.L_star)
    assert diff != 0
    rng = random.Random(99)
    with mpmath.workdps(DPS + 10):
        for _ in range(N_POINTS):
            pt, primes, v, h = motion_point(system, eps, +1, rng)
            # the energy has no term linear in the velocities: the reversed state has the same h
            rev = dict(pt)
            for c in system.independent_coordinates:
                rev[c.diff(t)] = -pt[c.diff(t)]
            assert sp.sympify(system.energy()).xreplace(rev) == h
            a_plus = _reduced_accel_values(plus, system, pt, primes, h)
            a_minus = _reduced_accel_values(minus, system, pt, primes, h)
            assert all(abs(p - m) > mpmath.mpf("1e-6") for p, m in zip(a_plus, a_minus))
            # each agrees with the chain rule of its own direction
            exp_plus = chain_rule_second_derivatives(system, eps, pt, v)
            exp_minus = chain_rule_second_derivatives(system, eps, rev, -v)
            y = coordinate(system, "y")
            assert len(a_plus) == len(a_minus) == 1
            assert close(a_plus[0], exp_plus[y]) and close(a_minus[0], exp_minus[y])


@pytest.mark.parametrize("name", ["sledge", "projectile", "kepler"])
def test_time_reversible_systems_do_not_depend_on_direction(name):
    """Without terms linear in the velocities, and with odd constraints, q''(q, q', h)
    is the same for both directions (the contrast to the charged particle)."""
    system = system_of(name)
    eps_name = DEFAULT_EPS[name]
    eps = coordinate(system, eps_name)
    plus, minus = reduction_of(name, eps_name, +1), reduction_of(name, eps_name, -1)
    rng = random.Random(7)
    with mpmath.workdps(DPS + 10):
        pt, primes, v, h = motion_point(system, eps, +1, rng)
        a_plus = _reduced_accel_values(plus, system, pt, primes, h)
        a_minus = _reduced_accel_values(minus, system, pt, primes, h)
        assert all(close(p, m) for p, m in zip(a_plus, a_minus))


def test_cone_constraint_rate_changes_sign_with_direction():
    """zdot = a sqrt(xdot^2 + ydot^2) is only positively homogeneous: z rises whichever
    way the particle goes, so dz/dx = zdot/xdot has the sign of xdot."""
    plus = reduction_of("cone_particle", "x", +1).constraint_rates
    minus = reduction_of("cone_particle", "x", -1).constraint_rates
    assert len(plus) == len(minus) == 1
    (fp, rp), = plus.items()
    (fm, rm), = minus.items()
    assert fp.func.__name__ == fm.func.__name__ == "z"
    assert sp.expand(rp + rm) == 0
    assert rp != 0
    system = system_of("cone_particle")
    red = reduction_of("cone_particle", "x", +1)
    rng = random.Random(3)
    pt, primes, v, h = motion_point(system, coordinate(system, "x"), +1, rng)
    sub = reduced_point(red, system, pt, primes, h)
    assert num(rp, sub) > 0 > num(rm, sub)


def test_sledge_constraint_rate_does_not_change_sign():
    """A linear (odd) constraint: dy/dx = tan(theta) for both directions."""
    plus = reduction_of("sledge", "x", +1).constraint_rates
    minus = reduction_of("sledge", "x", -1).constraint_rates
    assert [sp.expand(a - b) for a, b in zip(plus.values(), minus.values())] == [0]
