"""The model of whittaker_teach.forms: its inputs, its ModelErrors, the mechanics input."""

import pytest
import sympy as sp
import sympy.physics.mechanics as me
from sympy.physics.mechanics import dynamicsymbols

from whittaker_teach.errors import ModelError, ModelTypeError
from whittaker_teach.forms import NonholonomicSystem, agree, examples, from_mechanics

t = dynamicsymbols._t
x, th, y, z = dynamicsymbols("x theta y z")
m, J, k = sp.symbols("m J k", positive=True)
L = m / 2 * (x.diff(t)**2 + y.diff(t)**2) + J / 2 * th.diff(t)**2 - k * th**2 / 2
SIDE = y.diff(t) * sp.cos(th) - x.diff(t) * sp.sin(th)


def test_the_input_forms_give_the_same_constraint():
    a = NonholonomicSystem(L, [x, th, y], constraints=[SIDE], dependent=[y])
    b = NonholonomicSystem(L, [x, th, y], constraints=[sp.Eq(y.diff(t) * sp.cos(th),
                                                             x.diff(t) * sp.sin(th))])
    c = NonholonomicSystem(L, [x, th, y], dependent={y.diff(t): x.diff(t) * sp.tan(th)})
    d = NonholonomicSystem(L, [x, th, y], nonhol_coneqs=[SIDE], dependent=[y])
    for S in (a, b, c, d):
        assert S.dependent_coordinates == [y] and S.independent_coordinates == [x, th]
        assert S.is_linear and S.is_chaplygin
        assert sp.simplify(S.constraints[y.diff(t)] - x.diff(t) * sp.tan(th)) == 0


def test_floats_are_taken_as_rationals():
    S = NonholonomicSystem(0.5 * m * x.diff(t)**2 + J / 2 * th.diff(t)**2 + m / 2 * y.diff(t)**2,
                           [x, th, y], dependent={y.diff(t): 0.25 * x.diff(t)})
    assert S.rationalized == {sp.Float(0.5): sp.Rational(1, 2), sp.Float(0.25): sp.Rational(1, 4)}


def test_not_chaplygin_is_accepted_and_named():
    S = examples.sledge_in_a_well()
    assert not S.is_chaplygin and "L depends on the dependent coordinate y" in S.why_not_chaplygin
    S2 = NonholonomicSystem(L, [x, th, y], dependent={y.diff(t): x.diff(t) * y})
    assert "constraint for ydot depends on the dependent coordinate y" in S2.why_not_chaplygin


def test_chaplygin_type_is_decided_on_the_dependence_not_the_spelling():
    """A sin(x)**2 + A cos(x)**2 (as ``me.Lagrangian`` writes a symmetric disk's spin term
    with its angle) does not depend on the dependent coordinate x: the system is of
    Chaplygin type (a syntactic ``has`` said it was not); a term that does depend on x is
    still named."""
    psi, phi = dynamicsymbols("psi phi")
    A, C, R = sp.symbols("A C R", positive=True)
    spin = A * sp.sin(x)**2 * phi.diff(t)**2 + A * sp.cos(x)**2 * phi.diff(t)**2
    Lq = m / 2 * (x.diff(t)**2 + y.diff(t)**2) + spin / 2 + C / 2 * psi.diff(t)**2
    rolling = {x.diff(t): R * phi.diff(t) * sp.cos(th), y.diff(t): R * phi.diff(t) * sp.sin(th)}
    Lq = Lq + J / 2 * th.diff(t)**2
    S = NonholonomicSystem(Lq, [th, phi, psi, x, y], dependent=rolling)
    assert S.why_not_chaplygin is None and S.is_chaplygin
    Sx = NonholonomicSystem(Lq + k * sp.sin(x) * psi.diff(t), [th, phi, psi, x, y],
                            dependent=rolling)
    assert "dependent coordinate x" in Sx.why_not_chaplygin


@pytest.mark.parametrize("kwargs, words", [
    (dict(dependent={y.diff(t): x.diff(t)**2}), "not homogeneous of degree one"),
    (dict(dependent={y.diff(t): x.diff(t) + 1}), "not homogeneous of degree one"),
    (dict(dependent={y.diff(t): t * x.diff(t)}), "explicitly on t"),
    (dict(dependent={y.diff(t): x.diff(t), x.diff(t): th.diff(t)}), None),
    (dict(constraints=[SIDE, SIDE, SIDE]), "at least one velocity"),
    (dict(constraints=[th.diff(t)], dependent=[y]), "contains none of the dependent"),
    (dict(constraints=[SIDE], dependent={y.diff(t): 0}), "dependent names the dependent"),
    (dict(dependent={y.diff(t): x.diff(t).diff(t)}), "acceleration"),
    (dict(dependent={y.diff(t): z * x.diff(t)}), "not among the coordinates"),
])
def test_model_errors_name_the_condition(kwargs, words):
    with pytest.raises(ModelError) as err:
        NonholonomicSystem(L, [x, th, y], **kwargs)
    if words:
        assert words in str(err.value)


def test_a_dependent_velocity_written_with_another_is_refused():
    with pytest.raises(ModelError, match="written with the dependent velocity"):
        NonholonomicSystem(L + m * z.diff(t)**2, [x, th, y, z],
                           dependent={y.diff(t): x.diff(t), z.diff(t): y.diff(t)})


def test_type_errors():
    with pytest.raises(ModelTypeError):
        NonholonomicSystem("L", [x, th, y])
    with pytest.raises(ModelTypeError):
        from_mechanics(42)


def test_from_lagranges_method():
    lm = me.LagrangesMethod(L, [x, th, y], nonhol_coneqs=[SIDE])
    S = from_mechanics(lm)
    assert S.dependent_coordinates == [y] and S.source is lm
    assert agree(S, forms=["Maggi"]).ok


def _sleigh_bodies(kane):
    N = me.ReferenceFrame("N")
    O = me.Point("O")
    O.set_vel(N, 0)
    q = [x, th, y]
    u = dynamicsymbols("u1:4")
    sp_ = dict(zip([c.diff(t) for c in q], u)) if kane else {}
    B = N.orientnew("B", "Axis", (th, N.z))
    B.set_ang_vel(N, th.diff(t).xreplace(sp_) * N.z)
    P = O.locatenew("P", x * N.x + y * N.y)
    P.set_vel(N, (x.diff(t) * N.x + y.diff(t) * N.y).xreplace(sp_))
    body = me.RigidBody("S", P, B, m, (me.inertia(B, 0, 0, J), P))
    body.potential_energy = k * th**2 / 2
    return N, q, u, P, B, body


def test_from_kanes_method_and_kane_through_kanes_method():
    from whittaker_teach.forms import Kane, RouthVoss
    N, q, u, P, B, body = _sleigh_bodies(kane=True)
    km = me.KanesMethod(N, q_ind=q, u_ind=u[:2], u_dependent=[u[2]],
                        kd_eqs=[ui - c.diff(t) for ui, c in zip(u, q)],
                        velocity_constraints=[P.vel(N).dot(B.y)], bodies=[body])
    S = from_mechanics(km)
    assert S.dependent_coordinates == [y]
    rec = agree(S, forms=[RouthVoss(S), Kane(S), Kane(S, via="KanesMethod")])
    assert rec.ok, str(rec)
    with pytest.raises(ModelError, match="needs a system built by from_mechanics"):
        Kane(examples.sledge(), via="KanesMethod")


def test_from_system():
    N, q, _, P, B, body = _sleigh_bodies(kane=False)
    system = me.System(N)
    system.add_coordinates(*q)
    us = dynamicsymbols("v1:4")
    system.add_speeds(*us)
    system.add_kdes(*[ui - c.diff(t) for ui, c in zip(us, q)])
    system.add_bodies(body)
    system.add_nonholonomic_constraints(P.vel(N).dot(B.y).xreplace(
        {c.diff(t): ui for c, ui in zip(q, us)}))
    system.u_ind = us[:2]
    system.u_dep = [us[2]]
    S = from_mechanics(system)
    assert S.dependent_coordinates == [y]
    assert agree(S, forms=["RouthVoss", "GibbsAppell"]).ok


def test_gibbs_appell_from_the_bodies_of_an_offset_sleigh():
    """S summed over the bodies (a_G, alpha, omega by sympy.physics.vector) gives the same
    motion as S from T, Routh-Voss and LagrangesMethod; a Lagrangian alone has no bodies."""
    from whittaker_teach.forms import GibbsAppell, RouthVoss
    b = sp.Symbol("b", positive=True)
    N = me.ReferenceFrame("N")
    O = me.Point("O")
    O.set_vel(N, 0)
    q = [x, th, y]
    u = dynamicsymbols("u1:4")
    B = N.orientnew("B", "Axis", (th, N.z))
    B.set_ang_vel(N, u[1] * N.z)
    P = O.locatenew("P", x * N.x + y * N.y)
    P.set_vel(N, u[0] * N.x + u[2] * N.y)
    G = P.locatenew("G", b * B.x)
    G.v2pt_theory(P, N, B)
    body = me.RigidBody("S", G, B, m, (me.inertia(B, 0, 0, J), G))
    body.potential_energy = k * th**2 / 2
    km = me.KanesMethod(N, q_ind=q, u_ind=u[:2], u_dependent=[u[2]],
                        kd_eqs=[ui - c.diff(t) for ui, c in zip(u, q)],
                        velocity_constraints=[P.vel(N).dot(B.y)], bodies=[body])
    S = from_mechanics(km)
    ga = GibbsAppell(S, via="bodies")
    assert ga.name == "GibbsAppell from bodies"
    assert ga.acceleration_energy().has(b)
    rec = agree(S, forms=[RouthVoss(S), ga, GibbsAppell(S)])
    assert rec.ok, str(rec)
    with pytest.raises(ModelError, match="has no bodies"):
        GibbsAppell(examples.sleigh(), via="bodies")
