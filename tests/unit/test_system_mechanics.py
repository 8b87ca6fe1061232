"""sympy.physics.mechanics in and out (issue 26, item 3).

The sledge (Chaplygin sleigh) is built as a mechanics user builds it: a ReferenceFrame
B turned by theta, the contact point P, a RigidBody with its potential energy, L from
``me.Lagrangian`` and the no-slip constraint ``P.vel(N).dot(B.y)`` (= 0).  It goes in
each way (nonhol_coneqs, an Eq, a dict value, a LagrangesMethod, a System) and its
results (every acceleration, the multiplier, the numeric right-hand side) match
``LagrangesMethod.rhs()`` of the same model.
"""
import math

import pytest
import sympy as sp
import sympy.physics.mechanics as me
from sympy.physics.mechanics import dynamicsymbols

import whittaker_teach as wt
from whittaker_teach.errors import ModelError, ModelTypeError

t = dynamicsymbols._t
m, J, k = sp.symbols("m J k", positive=True)
x, th, y = dynamicsymbols("x theta y")
xd, thd, yd = (c.diff(t) for c in (x, th, y))


def sleigh():
    N = me.ReferenceFrame("N")
    B = N.orientnew("B", "Axis", (th, N.z))
    O = me.Point("O")
    O.set_vel(N, 0)
    P = O.locatenew("P", x * N.x + y * N.y)
    P.set_vel(N, xd * N.x + yd * N.y)
    body = me.RigidBody("sledge", P, B, m, (me.inertia(B, 0, 0, J), P))
    body.potential_energy = k**2 * th**2 / 2
    return N, B, P, body, me.Lagrangian(N, body), P.vel(N).dot(B.y)


POINT = {x: 0.3, th: 0.7, y: -0.2, xd: 1.1, thd: -0.4, m: 1.3, J: 0.8, k: 1.7}


def _lm():
    _, _, _, _, L, f = sleigh()
    lm = me.LagrangesMethod(L, [x, th, y], nonhol_coneqs=[f])
    lm.form_lagranges_equations()
    return lm


def _at(e, pt):
    return float(sp.sympify(e).subs(pt).evalf(30))


def _lm_values():
    """LagrangesMethod.rhs() at POINT: [qdot (3), qddot (3), lambda]."""
    lm = _lm()
    pt = dict(POINT)
    pt[yd] = pt[xd] * math.tan(pt[th])
    rhs = lm.rhs()
    return [_at(e, pt) for e in rhs]


def test_multiplier_satisfies_lagranges_method_eom():
    lm = _lm()
    S = wt.ChaplyginSystem(lm._L[0], [x, th, y], nonhol_coneqs=list(lm.coneqs), dependent=[y])
    pt = dict(POINT)
    pt[yd] = pt[xd] * math.tan(pt[th])
    acc = S.accelerations(dependent=True)
    (lam,) = S.multipliers()
    vals = {a: _at(e, pt) for a, e in acc.items()}
    vals[lm.lam_vec[0]] = _at(lam, pt)
    vals.update(pt)
    for e in lm.eom:
        assert abs(_at(e, vals)) < 1e-12
    vals[lm.lam_vec[0]] = -vals[lm.lam_vec[0]]
    assert max(abs(_at(e, vals)) for e in lm.eom) > 0.1


def _ways():
    _, _, _, _, L, f = sleigh()
    yield "nonhol_coneqs", wt.ChaplyginSystem(L, [x, th, y], nonhol_coneqs=[f], dependent=[y])
    yield "nonhol_coneqs Eq", wt.ChaplyginSystem(L, [x, th, y], nonhol_coneqs=sp.Eq(f, 0),
                                                 dependent=["y"])
    yield "dict value", wt.ChaplyginSystem(L, [x, th, y], dependent={yd: f})
    yield "dict Eq", wt.ChaplyginSystem(L, [x, th, y], dependent={yd: sp.Eq(f, 0)})
    yield "list of Eq", wt.ChaplyginSystem(L, [x, th, y], dependent=[sp.Eq(yd, xd * sp.tan(th))])
    yield "LagrangesMethod", wt.ChaplyginSystem.from_lagranges_method(_lm(), dependent=[y])
    yield "System", _system()


def _system():
    N, B, P, body, _, _ = sleigh()
    u1, u2, u3 = dynamicsymbols("u1:4")
    O = me.Point("O")
    O.set_vel(N, 0)
    sys = me.System(N, O)
    sys.add_coordinates(x, th, y)
    sys.add_speeds(u1, u2)
    sys.add_speeds(u3, independent=False)
    sys.add_kdes(u1 - xd, u2 - thd, u3 - yd)
    B.set_ang_vel(N, u2 * N.z)
    P.set_vel(N, u1 * N.x + u3 * N.y)
    sys.add_bodies(body)
    sys.add_nonholonomic_constraints(P.vel(N).dot(B.y))
    return wt.ChaplyginSystem.from_system(sys)


@pytest.fixture(scope="module")
def lm_values():
    return _lm_values()


@pytest.mark.parametrize("way", [w for w, _ in _ways()])
def test_each_way_in_matches_lagranges_method(way, lm_values):
    S = dict(_ways())[way]
    assert S.dependent_coordinates == [y] and S.independent_coordinates == [x, th]
    pt = dict(POINT)
    acc = S.accelerations(dependent=True)
    assert set(acc) == {x.diff(t, 2), th.diff(t, 2), y.diff(t, 2)}
    for i, c in enumerate((x, th, y)):
        assert _at(acc[c.diff(t, 2)], pt) == pytest.approx(lm_values[3 + i], rel=1e-12, abs=1e-12)
    (lam,) = S.multipliers()
    scale = 1.0
    if way in ("list of Eq",):       # given solved: g = ydot - xdot tan(theta) = f / cos(theta)
        scale = 1 / math.cos(POINT[th])
    # LagrangesMethod.eom is d/dt dL/dqdot - dL/dq + lambda df/dqdot (the book's sign and
    # multipliers()'); its mass_matrix_full, and so rhs(), carry the opposite sign of lambda
    assert _at(lam, pt) * scale == pytest.approx(-lm_values[6], rel=1e-12)
    # the numeric function: no substitution maps
    f = S.lambdify_rhs()
    assert f.state == ["x", "theta", "y", "xdot", "thetadot"] and f.parameters == ["J", "k", "m"]
    out = f(0.0, [pt[x], pt[th], pt[y], pt[xd], pt[thd]], {"m": pt[m], "J": pt[J], "k": pt[k]})
    expected = lm_values[:3] + lm_values[3:5]
    assert out == pytest.approx(expected, rel=1e-12, abs=1e-12)
    assert S.reduce(x).verify().ok


def test_reduced_function_matches_the_reduction():
    red = wt.examples.sledge().reduce("x")
    f = red.lambdify_rhs()
    Y, X = red.coordinates[0], red.independent
    (ypp,) = red.accelerations().values()
    vals = {Y.diff(X): 0.4, Y: 0.3, X: 0.1, red.h: 2.0, m: 1.3, J: 0.8, k: 1.7}
    got = f(0.1, [0.3, 0.4, 0.0, 0.0], 2.0, [0.8, 1.7, 1.3])
    assert got[1] == pytest.approx(_at(ypp.subs(Y.diff(X), 0.4), vals), rel=1e-12)
    assert got[2] == pytest.approx(_at(red.time_rate.subs(Y.diff(X), 0.4), vals), rel=1e-12)
    assert got[3] == pytest.approx(math.tan(0.3), rel=1e-12)


def test_real_time_symbol():
    tr = sp.Symbol("t", real=True)
    X, TH, Y = (sp.Function(n)(tr) for n in ("x", "theta", "y"))
    L = m / 2 * (X.diff(tr)**2 + Y.diff(tr)**2) + J / 2 * TH.diff(tr)**2 - k**2 * TH**2 / 2
    S = wt.ChaplyginSystem(L, [X, TH, Y], dependent={Y.diff(tr): X.diff(tr) * sp.tan(TH)})
    acc = S.accelerations()
    assert set(acc) == {X.diff(tr, 2), TH.diff(tr, 2)}
    assert acc[TH.diff(tr, 2)] == -k**2 * TH / J
    assert S.reduce("x").verify().ok


def test_clear_errors():
    _, _, _, _, L, f = sleigh()
    with pytest.raises(ModelError, match="name the dependent|dependent coordinates named"):
        wt.ChaplyginSystem(L, [x, th, y], nonhol_coneqs=[f])
    with pytest.raises(ModelError, match="2 solutions"):
        wt.ChaplyginSystem(L, [x, th, y], nonhol_coneqs=[yd**2 - xd**2], dependent=[y])
    with pytest.raises(ModelError, match="none of the dependent"):
        wt.ChaplyginSystem(L, [x, th, y], nonhol_coneqs=[xd - thd], dependent=[y])
    with pytest.raises(ModelError, match="1 constraint.*2 dependent"):
        wt.ChaplyginSystem(L, [x, th, y], nonhol_coneqs=[f], dependent=[y, th])
    with pytest.raises(ModelError, match="nonhol_coneqs"):
        wt.ChaplyginSystem(L, [x, th, y], dependent=[y])
    with pytest.raises(ModelTypeError):
        wt.ChaplyginSystem(L, [x, th, y], dependent=[f])
    lm = me.LagrangesMethod(L, [x, th, y], forcelist=[(me.Point("Q"), me.ReferenceFrame("A").x)])
    with pytest.raises(ModelError, match="forcelist"):
        wt.ChaplyginSystem.from_lagranges_method(lm, dependent=[y])


@pytest.mark.parametrize("name", ["h", "thetaprime"])
def test_a_parameter_named_like_a_made_symbol_is_an_error(name):
    p = sp.Symbol(name, positive=True)
    S = wt.ChaplyginSystem(m / 2 * (xd**2 + yd**2) + J / 2 * thd**2 - p * th**2, [x, th, y],
                           dependent={yd: xd * sp.tan(th)})
    with pytest.raises(ModelError, match=f"parameter {name} has the name of a symbol the "
                                         "reduction makes"):
        S.reduce(x)
    with pytest.raises(ModelError, match="name of a coordinate or velocity"):
        wt.ChaplyginSystem(m / 2 * xd**2 + sp.Symbol("xdot") * thd**2, [x, th])
