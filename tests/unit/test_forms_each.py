"""Each classical form of whittaker_teach.forms: its steps, its preconditions (ModelError
naming the condition) and what it gives besides the accelerations."""

import mpmath
import pytest
import sympy as sp
from sympy.physics.mechanics import dynamicsymbols

import whittaker_teach as wt
from whittaker_teach.errors import ModelError, ModelTypeError
from whittaker_teach.forms import (BoltzmannHamel, GibbsAppell, Kane, Maggi, Nielsen,
                                   RouthVoss, Tzenoff, Voronets, agree, examples)
from whittaker_teach.forms.compare import FORMS, form_class
from whittaker_teach.verify import values_at

t = dynamicsymbols._t


def close(a, b):
    """a = b to 30 digits (relative, absolute below 1), in 40-digit arithmetic."""
    with mpmath.workdps(40):
        return abs(a - b) < mpmath.mpf(10)**-30 * max(1, abs(a), abs(b))


ALL = [RouthVoss, Voronets, Maggi, GibbsAppell, BoltzmannHamel, Nielsen, Tzenoff, Kane]


@pytest.mark.parametrize("cls", ALL)
def test_steps_are_labelled_in_square_brackets_and_verified(cls):
    F = cls(examples.sleigh())
    labels = F.steps.labels
    assert labels[-1] == F.label + "a"
    assert all(s.shown_label.startswith("[") for s in F.steps)
    assert F.verify().ok
    assert F.source and F.needs and F.title
    text = F.steps.to_unicode()
    assert f"[{F.label}]" in text


@pytest.mark.parametrize("cls", ALL)
def test_a_form_takes_only_a_nonholonomic_system(cls):
    with pytest.raises(ModelTypeError):
        cls(wt.examples.sledge())


def test_form_names_are_the_registry():
    assert [form_class(n).__name__ for n in FORMS] == list(FORMS)
    with pytest.raises(ModelTypeError):
        form_class("Lagrange")


def test_routh_voss_multipliers_match_the_core():
    """The multipliers of the sledge, given solved, are the core's (the same convention:
    LagrangesMethod's sign)."""
    S = examples.sledge()
    core = wt.examples.sledge()
    lam = RouthVoss(S).multipliers()
    assert len(lam) == 1
    assert sp.simplify(lam[0] - core.multipliers()[0]) == 0


def test_routh_voss_multipliers_depend_on_how_the_constraint_is_written():
    """Scaling a constraint scales its multiplier, not the motion."""
    x, th, y = dynamicsymbols("x theta y")
    S1 = examples.sleigh()
    S2 = type(S1)(S1.lagrangian, S1.coordinates,
                  constraints=[2 * (y.diff(t) * sp.cos(th) - x.diff(t) * sp.sin(th))],
                  dependent=[y])
    l1, l2 = RouthVoss(S1)._solution(), RouthVoss(S2)._solution()
    lam = sp.Symbol("lambda1")
    pt = S1.sample(__import__("random").Random(1))
    v1, v2 = values_at(l1[lam], [pt])[0], values_at(l2[lam], [pt])[0]
    with mpmath.workdps(40):
        assert close(v1, 2 * v2)
    assert agree(S2, forms=["RouthVoss", "Maggi"]).ok


def test_voronets_delegates_to_chaplygin_where_it_applies():
    S = examples.sleigh()
    C = Voronets(S).chaplygin()
    assert isinstance(C, wt.ChaplyginSystem)
    assert C.steps["1.4"].status == "verified"
    acc_core = C.accelerations()
    acc_vor = Voronets(S).accelerations()
    rng = __import__("random").Random(3)
    internal = S.sample(rng)
    for k in acc_vor:
        a = S.to_internal(acc_vor[k])
        b = S.to_internal(acc_core[k])
        va, vb = values_at(a, [internal])[0], values_at(b, [internal])[0]
        assert close(va, vb)


@pytest.mark.parametrize("name, words", [
    ("sledge_in_a_well", "L depends on the dependent coordinate y"),
    ("appell_hamel", "L depends on the dependent coordinate z"),
])
def test_voronets_refuses_chaplygin_with_the_condition(name, words):
    with pytest.raises(ModelError) as err:
        Voronets(examples.catalogue()[name]()).chaplygin()
    assert "(1.4) do not apply" in str(err.value) and words in str(err.value)


def test_voronets_coefficients_of_the_sledge():
    A = Voronets(examples.sledge()).coefficients()
    assert len(A) == 1
    value = next(iter(A.values()))
    assert sp.simplify(value - (-(1 + sp.tan(sp.Symbol("theta"))**2))) == 0 or \
        sp.simplify(value - (1 + sp.tan(sp.Symbol("theta"))**2)) == 0
    with pytest.raises(ModelError, match="belong to linear constraints"):
        Voronets(examples.appell_hamel()).coefficients()


def test_boltzmann_hamel_preconditions():
    with pytest.raises(ModelError, match="linear in the velocities"):
        BoltzmannHamel(examples.appell_hamel())
    S = examples.sleigh()
    x, th, y = S.coordinates
    with pytest.raises(ModelError, match="give n - g = 2"):
        BoltzmannHamel(S, quasi_velocities=[th.diff(t)])
    with pytest.raises(ModelError, match="not linear and homogeneous"):
        BoltzmannHamel(S, quasi_velocities=[x.diff(t)**2, th.diff(t)])
    # the forward speed and the sideways one (the constraint) together: singular
    with pytest.raises(ModelError, match="not independent"):
        BoltzmannHamel(S, quasi_velocities=[y.diff(t) * sp.cos(th) - x.diff(t) * sp.sin(th),
                                            th.diff(t)])


def test_boltzmann_hamel_with_the_forward_speed():
    S = examples.sleigh()
    x, th, y = S.coordinates
    bh = BoltzmannHamel(S, quasi_velocities=[x.diff(t) * sp.cos(th) + y.diff(t) * sp.sin(th),
                                             th.diff(t)])
    gam = bh.hamel_coefficients()
    assert list(gam.values()) == [-1]           # gamma^3_12 = -1 for the sleigh's frame
    assert bh.name == "BoltzmannHamel (omega given)"
    assert agree(S, forms=["RouthVoss", bh]).ok


def test_gibbs_appell_energy_is_quadratic_in_the_accelerations():
    ga = GibbsAppell(examples.rolling_disk())
    S = ga.system
    St = ga._S_tilde()
    for c in S.sigma:
        assert sp.diff(St, S.qdd[c], 3) == 0
    assert ga.acceleration_energy().has(S.coordinates[0].diff(t, 2))


def test_nielsen_and_tzenoff_expressions_are_lagranges():
    for cls in (Nielsen, Tzenoff):
        F = cls(examples.sledge_in_a_well())
        assert F.steps[F.label + "s"].status == "verified"
    # Tzenoff's second rate has jerks; its derivative in the accelerations has none
    tz = Tzenoff(examples.sleigh())
    S = tz.system
    assert tz.Tddot().has(*S.qddd.values())
    assert not any(e.has(*S.qddd.values()) for e in tz._full())


def test_kane_partial_velocities_and_forces():
    K = Kane(examples.sledge())
    S = K.system
    x, th, y = S.coordinates
    v = K._partial_velocities()
    assert v[(x, x)] == 1 and v[(th, x)] == 0 and v[(y, x)] == sp.tan(S.q[th])
    with pytest.raises(ModelError, match="via must be"):
        Kane(examples.sledge(), via="bodies")


def test_dependent_accelerations_are_the_constraints_rate():
    S = examples.rolling_disk()
    acc = Maggi(S).accelerations(dependent=True)
    x, y = S.coordinates[:2]
    assert set(acc) == {c.diff(t, 2) for c in S.coordinates}
    rv = RouthVoss(S)._solution()
    pt = S.sample(__import__("random").Random(5))
    for c in (x, y):
        a = values_at(S.to_internal(acc[c.diff(t, 2)]), [pt])[0]
        b = values_at(rv[S.qdd[c]], [pt])[0]
        assert close(a, b)


def test_singular_kinetic_energy_is_a_model_error():
    x, th, y = dynamicsymbols("x theta y")
    S = type(examples.sledge())(x.diff(t)**2 / 2, [x, th, y],
                                dependent={y.diff(t): x.diff(t)})
    for cls in (Maggi, GibbsAppell, RouthVoss):
        with pytest.raises(ModelError, match="singular"):
            cls(S).accelerations()
    rec = agree(S, forms=["Maggi"], reference=False)
    assert rec.rows[0]["reason"] and "singular" in rec.rows[0]["reason"]


@pytest.mark.parametrize("name", sorted(examples.catalogue()))
def test_chetaev_force_does_no_work(name):
    from whittaker_teach.forms import chetaev
    d = chetaev(examples.catalogue()[name]())
    assert d.labels == ["Ch1", "Ch2", "Ch3"]
    assert d["Ch3"].status == "verified"


def test_chetaev_conditions_of_the_appell_hamel_weight():
    from whittaker_teach.forms import chetaev
    S = examples.appell_hamel()
    (lhs, rhs), = [(e.lhs, e.rhs) for e in chetaev(S)["Ch2"].equations]
    dx, dy = sp.symbols("delta_x delta_y")
    x, y, z = S.coordinates
    xd, yd = S.qd[x], S.qd[y]
    c = sp.Symbol("c", positive=True)
    assert lhs == sp.Symbol("delta_z")
    assert sp.simplify(rhs - c * (xd * dx + yd * dy) / sp.sqrt(xd**2 + yd**2)) == 0


def test_a_holonomic_system_takes_every_form():
    """No constraints: every form is Lagrange's equations; they agree with LagrangesMethod."""
    from whittaker_teach.forms import NonholonomicSystem
    r, ph = dynamicsymbols("r phi")
    m, k = sp.symbols("m k", positive=True)
    S = NonholonomicSystem(m / 2 * (r.diff(t)**2 + r**2 * ph.diff(t)**2) - k * r**2 / 2, [r, ph])
    assert S.is_holonomic and S.is_chaplygin
    rec = agree(S)
    assert rec.ok and all(not row["reason"] for row in rec.rows), str(rec)
    assert RouthVoss(S).multipliers() == []


def test_routh_voss_prints_the_multipliers_tidied_and_checks_them():
    """[RVl] shows the multipliers of multipliers(), tidied (one fraction, sin^2 + cos^2 = 1),
    and its check proves them equal to those solved."""
    for S, n_ops in ((examples.appell_hamel(), 8), (examples.sleigh(), 25)):
        rv = RouthVoss(S)
        step = rv.steps["RVl"]
        assert step.status == "verified"
        shown = [S.to_public(e.rhs) for e in step.equations]
        assert shown == rv.multipliers()
        assert sum(sp.count_ops(e) for e in shown) <= n_ops
    m, c, g0 = sp.symbols("m c g_0", positive=True)
    assert RouthVoss(examples.appell_hamel()).multipliers() == [-g0 * m / (1 + c**2)]


def test_hamel_coefficient_of_the_sleigh_is_tidied():
    (gam,) = BoltzmannHamel(examples.sleigh()).hamel_coefficients().values()
    th = sp.Symbol("theta")
    assert gam == -1 / sp.cos(th)**2


@pytest.mark.parametrize("cls, label, bad", [
    (Voronets, "VorA", "psitheta"), (Maggi, "MagC", "x,psi"), (Kane, "Kanev", "x,psi"),
    (Tzenoff, "Tzs", "Z_{psi}"), (Nielsen, "Nis", "N_{psi}")])
def test_names_with_greek_indices_print_greek(cls, label, bad):
    import re
    step = cls(examples.rolling_disk() if label != "VorA" else examples.sleigh()).steps[label]
    tex, text = step.to_latex(), step.to_unicode()
    assert bad not in tex and not re.search(r"(?<!\\)(psi|theta)", tex)
    assert "psi" not in text and "theta" not in text and "frac" not in text
    assert "ψ" in text or "θ" in text


def test_titles_keep_tall_maths_out_of_the_caption():
    """A caption's in-line maths must not be taller than its line (the site scrolls)."""
    for F, label in ((Maggi, "MagE"), (BoltzmannHamel, "BHg")):
        title = F(examples.rolling_disk()).steps[label].title
        assert r"\frac" not in title and "^r_" not in title


def test_only_can_pick_exactly_one_label():
    d = RouthVoss(examples.sledge()).steps
    assert d.only("RV").labels == ["RV", "RVc", "RVl", "RVa"]
    assert d.only("RV", exact=True).labels == ["RV"]
    assert d.only("RV", "RVa", exact=True).labels == ["RV", "RVa"]
