"""whittaker_teach.stability: steady motions, linearisation (time and reduced, agreeing),
classification and Routh's method, on cases with known answers."""

import pytest
import sympy as sp

import whittaker_teach as wt
from whittaker_teach import stability as st

v_pos = sp.Symbol("v", positive=True)
v_neg = sp.Symbol("v", negative=True)


def _sleigh(k0=None):
    s = wt.examples.offset_sleigh()
    if k0 is None:
        return s
    k = sp.Symbol("k", positive=True)
    return wt.ChaplyginSystem(s.lagrangian.subs(k, k0), s.coordinates, dependent=s.constraints,
                              name="sleigh_k0")


def test_sleigh_without_spring_eigenvalue_is_minus_mbv_over_J_plus_mb2():
    m, b, J = sp.symbols("m b J", positive=True)
    sm = st.steady_motion(_sleigh(0), {"theta": 0}, {"x": v_pos})
    lin = st.linearize(sm)
    assert lin.eigenvalues == {0: 2, -m * b * v_pos / (J + m * b**2): 1}
    c = st.classify(lin, family=2)     # straight motions: any speed, any heading
    assert c.verdict == "stable, asymptotically relative to the family"


def test_sleigh_with_spring_forward_and_backward():
    m, b, J, k = sp.symbols("m b J k", positive=True)
    lam = st.LAMBDA
    lin = st.linearize(st.steady_motion(_sleigh(), {"theta": 0}, {"x": v_pos}))
    want = lam * ((J + m * b**2) * lam**2 + m * b * v_pos * lam + k**2) / (J + m * b**2)
    assert sp.cancel(lin.charpoly() - want) == 0
    assert st.classify(lin).verdict == "stable, asymptotically relative to the family"
    back = st.linearize(st.steady_motion(_sleigh(), {"theta": 0}, {"x": v_neg}))
    assert st.classify(back).verdict == "unstable"


def test_time_and_reduced_linearisations_agree():
    for system, vel in ((_sleigh(), v_pos), (_sleigh(), v_neg), (wt.examples.sledge(), v_pos)):
        sm = st.steady_motion(system, {"theta": 0}, {"x": vel})
        agreement = st.compare(st.linearize(sm), st.linearize_reduced(sm))
        assert agreement.holds, str(agreement)


def test_sledge_centre_frequency_k_over_sqrt_J():
    J, k = sp.symbols("J k", positive=True)
    for vel in (0, 1, v_pos):
        lin = st.linearize(st.steady_motion(wt.examples.sledge(), {"theta": 0}, {"x": vel}))
        assert lin.eigenvalues == {0: 1, sp.I * k / sp.sqrt(J): 1, -sp.I * k / sp.sqrt(J): 1}
        assert st.classify(lin).verdict == "critical: linearisation decides nothing"


def test_sledge_speed_is_an_integral_and_xdot_is_not():
    s = wt.examples.sledge()
    x, th, _ = s.coordinates
    t = x.args[0]
    assert st.conserved(s, x.diff(t) / sp.cos(th)).holds
    assert st.conserved(s, s.energy()).holds
    assert not st.conserved(s, x.diff(t)).holds


def test_disk_threshold_matches_literature():
    """Thin uniform disk: upright straight rolling stable iff omega^2 > g/(3R);
    in general omega^2 > A m g R / (C (C + m R^2)) (Neimark & Fufaev 1972; Bloch 2003)."""
    w = sp.Symbol("omega", positive=True)
    m, R, g, A, C = sp.symbols("m R g A C", positive=True)
    lam = st.LAMBDA
    disk = st.tilting_disk()
    lin = st.linearize(st.steady_motion(disk, {"phi": 0}, {"psi": 0, "theta": w}))
    q = sp.cancel(lin.charpoly() / lam**2)
    (crit,) = sp.solve(q.subs(lam, 0), w)
    assert sp.simplify(crit**2 - g / (3 * R)) == 0
    general = st.tilting_disk(uniform=False)
    lin2 = st.linearize(st.steady_motion(general, {"phi": 0}, {"psi": 0, "theta": w}))
    q2 = sp.cancel(lin2.charpoly() / lam**2)
    (crit2,) = sp.solve(q2.subs(lam, 0), w)
    assert sp.simplify(crit2**2 - A * m * g * R / (C * (C + m * R**2))) == 0
    at = {R: 1, g: 1}
    assert st.classify(lin, at={**at, w: sp.Rational(7, 10)}).verdict.startswith("critical")
    assert st.classify(lin, at={**at, w: sp.Rational(1, 2)}).verdict == "unstable"
    sm = st.steady_motion(disk, {"phi": 0}, {"psi": 0, "theta": w})
    assert st.compare(lin, st.linearize_reduced(sm)).holds


def test_disk_steady_circles_found():
    w = sp.Symbol("omega", positive=True)
    Om, phi0 = sp.symbols("Omega phi_0", real=True)
    found = st.find_steady_motions(st.tilting_disk(), {"psi": Om, "theta": w},
                                   values={"phi": phi0}, unknowns=[w])
    assert len(found) == 1
    assert set(st.steady.residuals(found[0]).values()) == {0} or all(
        sp.simplify(r) == 0 for r in st.steady.residuals(found[0]).values())


def test_find_sleigh_straight_motion():
    found = st.find_steady_motions(wt.examples.offset_sleigh(), {"x": v_pos})
    assert [sm.values for sm in found] == [{wt.examples.offset_sleigh().coordinates[1]: 0}]


def test_routh_kepler_and_refusals():
    r = st.routh(wt.examples.kepler(), "theta")
    ((r0, d2),) = r.critical_points()
    m, mu = sp.symbols("m mu", positive=True)
    c = r.momentum
    assert sp.simplify(r0 - c**2 / (m**2 * mu)) == 0 and sp.simplify(d2).is_positive is not False
    rd = st.routh(wt.examples.rolling_disk(), "theta")
    assert rd.critical_points() == [(0, sp.Symbol("k", positive=True)**2)]
    with pytest.raises(wt.ModelError, match="not conserved"):
        st.routh(wt.examples.sledge(), "x")
    with pytest.raises(wt.ModelError, match="not cyclic"):
        st.routh(wt.examples.sledge(), "theta")


def test_family_dimension_is_computed_not_counted():
    """Lyapunov-Malkin needs a manifold of equilibria: classify computes its dimension."""
    no_spring = _sleigh(0)
    lin = st.linearize(st.steady_motion(no_spring, {"theta": 0}, {"x": v_pos}))
    c = st.classify(lin)                 # the motion has one symbol (v), the family two
    assert (c.family, c.verdict) == (2, "stable, asymptotically relative to the family")
    assert c.family_how.startswith("computed")
    assert st.classify(lin, family=2).family_how.startswith("given, and checked")
    assert st.family_dimension(st.steady_motion(_sleigh(), {"theta": 0}, {"x": v_pos})).dimension == 1
    # the sledge at rest: no symbol in the motion, but any speed is steady
    rest = st.linearize(st.steady_motion(wt.examples.sledge(), {"theta": 0}, {"x": 0}))
    assert st.classify(rest).family == 1


def test_family_given_by_hand_is_refused_when_wrong():
    lin = st.linearize(st.steady_motion(_sleigh(0), {"theta": 0}, {"x": v_pos}))
    with pytest.raises(wt.ModelError, match="manifold of dimension 2"):
        st.classify(lin, family=1)
    lin_k = st.linearize(st.steady_motion(_sleigh(), {"theta": 0}, {"x": v_pos}))
    with pytest.raises(wt.ModelError, match="manifold of dimension 1"):
        st.classify(lin_k, family=2)


def test_disk_family_of_steady_circles_has_dimension_two():
    w = sp.Symbol("omega", positive=True)
    lin = st.linearize(st.steady_motion(st.tilting_disk(), {"phi": 0}, {"psi": 0, "theta": w}))
    fd = st.family_dimension(lin.steady)
    assert (fd.dimension, fd.unknowns, fd.rank_at_point) == (2, 3, 1)
    assert st.classify(lin).family == 2


def test_family_undecided_where_the_rank_drops():
    """A quartic spring: the rank of the equilibrium conditions drops at theta = 0,
    so the dimension is not decided; a hand-supplied family is used, up to the bound."""
    s = wt.examples.sledge()
    k = sp.Symbol("k", positive=True)
    th = s.coordinates[1]
    quartic = wt.ChaplyginSystem(s.lagrangian.subs(k, 0) - th**4, s.coordinates,
                                 dependent=s.constraints, name="quartic")
    lin = st.linearize(st.steady_motion(quartic, {"theta": 0}, {"x": v_pos}))
    fd = st.family_dimension(lin.steady)
    assert (fd.dimension, fd.bound, fd.rank_at_point, fd.rank_generic) == (None, 2, 0, 1)
    c = st.classify(lin)
    assert c.family == 1 and "not checked" in c.family_how
    assert "not checked" in st.classify(lin, family=2).family_how
    with pytest.raises(wt.ModelError, match="at most a manifold of dimension 2"):
        st.classify(lin, family=3)


@pytest.mark.parametrize("call, match", [
    (lambda: st.steady_motion("sledge", {"theta": 0}, {"x": 0}), "ChaplyginSystem"),
    (lambda: st.steady_motion(wt.examples.sledge(), {"theta": 0}, {}), "no value or velocity"),
    (lambda: st.steady_motion(wt.examples.sledge(), {"theta": 0, "x": 0}, {"x": 1}), "both"),
    (lambda: st.steady_motion(wt.examples.sledge(), {"theta": 0}, {"y": 1}), "dependent"),
    (lambda: st.steady_motion(wt.examples.sledge(), {"theta": 0}, {"z": 1}), "not a coordinate"),
    (lambda: st.steady_motion(wt.examples.sledge(), {"x": 0}, {"theta": 1}), "not cyclic"),
    (lambda: st.steady_motion(wt.examples.sledge(), {"theta": 1}, {"x": 1}), "not a steady motion"),
    (lambda: st.steady_motion(wt.examples.sledge(), {"theta": sp.oo}, {"x": 1}), "not finite"),
    (lambda: st.steady_motion(wt.examples.sledge(), {"theta": sp.I}, {"x": 1}), "real"),
    (lambda: st.steady_motion(wt.examples.sledge(), {"theta": "0"}, {"x": 1}), "number"),
    (lambda: st.linearize("motion"), "SteadyMotion"),
    (lambda: st.linearize_reduced(st.steady_motion(wt.examples.sledge(), {"theta": 0}, {"x": 0})),
     "qdot_eps != 0"),
    (lambda: st.linearize_reduced(st.steady_motion(wt.examples.sledge(), {"theta": 0},
                                                   {"x": sp.Symbol("u", real=True)})), "sign"),
    (lambda: st.linearize_reduced(st.steady_motion(wt.examples.sledge(), {"theta": 0}, {"x": 1}),
                                  "theta"), "held fixed"),
    (lambda: st.classify(st.linearize(st.steady_motion(wt.examples.sledge(), {"theta": 0},
                                                       {"x": 1})), family=-1), "dimension"),
    (lambda: st.find_steady_motions(wt.examples.sledge(), {}), "velocities"),
    (lambda: st.routh(wt.examples.sledge(), "x", momentum="c"), "Symbol"),
])
def test_model_errors(call, match):
    with pytest.raises(wt.ModelError, match=match):
        call()
