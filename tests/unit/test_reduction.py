"""The Whittaker reduction (1.5)-(1.27) and the Nielsen form (2.1)-(2.4)."""

import pytest
import sympy as sp

import whittaker_teach as wt

m, J, k = sp.symbols("m J k", positive=True)
g = sp.Symbol("g_0", positive=True)   # gravity (g counts the constraints)
X = sp.Symbol("x")
TH = sp.Function("theta")(X)
h = sp.Symbol("h")

PAPER_LABELS = ["1.1", "1.2", "1.4", "1.5", "1.6", "1.7", "1.8", "1.9", "1.10", "1.11", "1.12",
                "1.13", "1.14", "1.15", "1.16", "1.17", "1.18", "1.19", "1.20", "1.21", "1.22",
                "1.23", "1.24", "1.25", "1.26", "2.1", "2.2", "2.3", "2.4"]


def test_public_names(sledge_red):
    red = sledge_red
    assert red.independent == X
    assert red.coordinates == [TH]
    assert red.h == h
    assert red.direction == 1


def test_every_paper_step_present_and_verified(sledge_red):
    labels = sledge_red.steps.labels
    for lab in PAPER_LABELS:
        assert lab in labels, lab
    report = sledge_red.verify()
    assert report.ok, str(report)
    claimed = {"1.7", "1.8", "1.9", "1.13", "1.14", "1.15", "1.19", "1.20", "1.21", "1.24",
               "1.25", "2.2", "2.3", "2.4", "1.26"}
    assert claimed <= {c.label for c in report}
    for c in report:
        assert c.method in ("exact", "numeric")
        if c.method == "numeric":
            assert c.points >= 5 and c.max_residual < 1e-25


def test_L_star_is_3_7(sledge_red):
    printed = sp.sqrt(2 * h - k**2 * TH**2) * sp.sqrt(m * (1 + sp.tan(TH)**2) + J * TH.diff(X)**2)
    assert sp.expand(sledge_red.L_star - printed) == 0


def test_velocity_is_3_5(sledge_red):
    printed = (2 * h - k**2 * TH**2) / (m * (1 + sp.tan(TH)**2) + J * TH.diff(X)**2)
    assert sp.expand(sledge_red.velocity**2 - printed) == 0


def test_reduced_acceleration_is_3_10(sledge_red):
    acc = sledge_red.accelerations()[TH.diff(X, 2)]
    R = 2 * h - k**2 * TH**2
    printed = (J * R * TH.diff(X, 2) + J * (-R * sp.tan(TH) + k**2 * TH) * TH.diff(X)**2
               + m * k**2 * TH * (1 + sp.tan(TH)**2))
    assert sp.expand(printed.subs(TH.diff(X, 2), acc) * 1) == 0 or \
        sp.simplify(printed.subs(TH.diff(X, 2), acc)) == 0


def test_constraint_rate_is_3_8(sledge_red):
    y = sp.Function("y")(X)
    assert sledge_red.constraint_rates == {y: sp.tan(TH)}
    assert sledge_red.dependent_rates == {y: sp.tan(TH)}


def test_time_rate(sledge_red):
    assert sp.expand(sledge_red.time_rate * sledge_red.velocity) == 1


def test_direction_minus_one_flips_L_star(sledge):
    plus, minus = sledge.reduce("x", +1), sledge.reduce("x", -1)
    assert sp.expand(plus.L_star + minus.L_star) == 0
    assert minus.verify().ok
    # the sledge is time-reversible: the reduced accelerations agree
    a1 = plus.accelerations()[TH.diff(X, 2)]
    a2 = minus.accelerations()[TH.diff(X, 2)]
    assert sp.simplify(a1 - a2) == 0


def test_gyroscopic_term_makes_directions_differ():
    s = wt.examples.charged_particle()
    plus, minus = s.reduce("x", +1), s.reduce("x", -1)
    Y = sp.Function("y")(X)
    a1 = plus.accelerations()[Y.diff(X, 2)]
    a2 = minus.accelerations()[Y.diff(X, 2)]
    pt = {Y: sp.Rational(1, 3), Y.diff(X): sp.Rational(1, 2), h: 3, X: sp.Rational(1, 5),
          sp.Symbol("m", positive=True): 1, sp.Symbol("B", positive=True): 1,
          sp.Symbol("k", positive=True): 1}
    d1 = sp.N(a1.subs(pt), 30)
    d2 = sp.N(a2.subs(pt), 30)
    assert abs(d1 - d2) > 0.1
    assert plus.verify().ok and minus.verify().ok


def test_nonlinear_constraint_rate_changes_sign():
    s = wt.examples.cone_particle()
    Y, Z = sp.Function("y")(X), sp.Function("z")(X)
    a = sp.Symbol("a", positive=True)
    assert s.reduce("x", +1).constraint_rates[Z] == a * sp.sqrt(Y.diff(X)**2 + 1)
    assert s.reduce("x", -1).constraint_rates[Z] == -a * sp.sqrt(Y.diff(X)**2 + 1)


def test_nielsen_equivalent_to_whittaker(sledge_red):
    n, w = sledge_red.nielsen_equations, sledge_red.equations
    assert len(n) == len(w) == 1
    assert sp.expand(n[0] - w[0]) == 0
    assert sledge_red.steps["2.4"].status == "verified"


def test_projectile_path_is_a_parabola():
    red = wt.examples.projectile().reduce("x")
    Y = red.coordinates[0]
    c0, c1, u = sp.symbols("c0 c1 u", positive=True)
    path = c0 + c1 * X - g * X**2 / (2 * u**2)
    energy = m * u**2 * (1 + c1**2) / 2 + m * g * c0   # at x = 0, xdot = u
    for eq in red.equations:
        res = eq.subs(Y.diff(X, 2), path.diff(X, 2)).subs(Y.diff(X), path.diff(X))
        res = res.subs(Y, path).subs(red.h, energy)
        assert sp.simplify(res) == 0
    assert red.steps["1.27"].status == "verified"


def test_kepler_orbit_is_a_conic():
    red = wt.examples.kepler().reduce("theta")
    theta, R = red.independent, red.coordinates[0]
    p, e = sp.symbols("p e", positive=True)
    mu = sp.Symbol("mu", positive=True)
    r = p / (1 + e * sp.cos(theta))
    energy = -m * mu * (1 - e**2) / (2 * p)
    acc = red.accelerations()[R.diff(theta, 2)]
    res = r.diff(theta, 2) - acc.subs(R.diff(theta), r.diff(theta)).subs(R, r).subs(red.h, energy)
    for val in ("0.3", "1.1", "2.0"):
        point = {theta: sp.Rational(val), p: sp.Rational(13, 10), e: sp.Rational(1, 2), mu: 2, m: 1}
        assert abs(sp.N(res.subs(point), 30)) < 1e-25
    assert red.steps["1.27"].status == "verified"


def test_holonomic_has_1_27_and_no_constraint_terms():
    red = wt.examples.projectile().reduce("x")
    assert "1.27" in red.steps.labels
    assert red.steps["2.3"].check is None
    assert red.constraint_rates == {}


@pytest.mark.parametrize("direction", [1, -1])
@pytest.mark.parametrize("make", ["projectile", "kepler", "family3"])
def test_1_27_route_is_sympys_own_diff(make, direction):
    """(1.27) takes d/dq_eps in one pass through the tree (``dag.along``); the route it
    stands for, SymPy's own ``diff`` in s of L*'s derivative moved along the path, then
    s = 0, gives the same functions (so the check of (1.26) against (1.27) is as good
    as one against SymPy's Euler-Lagrange operator, at a fraction of its cost)."""
    from whittaker_teach.verify import check_identity
    if make == "family3":
        from whittaker_teach.bench import family
        L, coords, dep = family(3, holonomic=True)
        red = wt.ChaplyginSystem(L, coords, dep).reduce(coords[0], direction)
    else:
        ex = wt.examples.get(make)
        red = ex.build().reduce(ex.coordinate, direction)
    s, x = sp.Dummy("s"), red.independent
    moved = {x: x + s}
    for c in red._nus:
        q, p = red.system.q[c], red._qp[c]
        moved.update({q: q + s * p, p: p + s * red._qpp[c]})
    sympys = [sp.diff(sp.diff(red._Lstar, red._qp[c]).xreplace(moved), s).subs(s, 0)
              - sp.diff(red._Lstar, red.system.q[c]) for c in red._nus]
    ours = red._whittaker_127()
    assert check_identity("1.27", "the two routes", ours, sympys, red._sample).holds
    wrong = [ours[0] + red._qpp[red._nus[0]] / 10**6] + ours[1:]
    assert check_identity("1.27", "wrong", wrong, sympys, red._sample).holds is False
    assert red.steps["1.27"].check.holds


@pytest.mark.parametrize("name", [e.name for e in wt.examples.catalogue()])
def test_every_example_verifies(name):
    red = wt.examples.get(name).reduce()
    report = red.verify()
    assert report.ok, str(report)


def test_rolling_disk_reduces_with_theta():
    red = wt.examples.rolling_disk().reduce("theta")
    assert [str(c) for c in red.coordinates] == ["psi(theta)"]
    assert set(map(str, red.constraint_rates)) == {"x(theta)", "y(theta)"}


def test_dependent_momenta_and_step_order(sledge_red):
    y = sp.Function("y")(X)
    P = sledge_red.dependent_momenta[y]
    # (dL/dydot)* = m ydot = m xdot tan(theta), with xdot from (1.12)
    assert sp.expand(P - m * sledge_red.velocity * sp.tan(TH)) == 0
    assert sledge_red.steps["1.26"].title.startswith("the generalized Whittaker equations")
