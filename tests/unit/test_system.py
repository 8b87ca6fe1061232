"""The time-domain steps (1.1)-(1.4), (1.10), (1.11) on the sledge and the holonomic examples."""

import sympy as sp
from sympy.physics.mechanics import dynamicsymbols

import whittaker_teach as wt

T = dynamicsymbols._t
m, J, k = sp.symbols("m J k", positive=True)
g = sp.Symbol("g_0", positive=True)   # gravity (g counts the constraints)
x, th, y = dynamicsymbols("x theta y")


def _zero(e):
    return sp.expand(sp.expand_trig(e)) == 0 or sp.simplify(e) == 0


def test_sledge_model(sledge):
    assert sledge.independent_coordinates == [x, th]
    assert sledge.dependent_coordinates == [y]
    assert not sledge.is_holonomic
    assert sledge.parameters == [J, k, m]


def test_sledge_L_tilde_is_3_3(sledge):
    printed = m / 2 * x.diff(T)**2 * (1 + sp.tan(th)**2) + J / 2 * th.diff(T)**2 - k**2 * th**2 / 2
    assert sp.expand(sledge.L_tilde - printed) == 0


def test_sledge_chaplygin_equations(sledge):
    ex, eth = sledge.equations_of_motion()
    sec2 = 1 + sp.tan(th)**2
    # x: d/dt(m xdot sec^2) - 0 - m ydot * (d/dt tan(theta) - 0) = 0
    expected_x = m * sec2 * x.diff(T, 2) + m * x.diff(T) * th.diff(T) * sp.tan(th) * sec2
    assert sp.expand(ex - expected_x) == 0
    # theta: the m tan terms cancel: J thetaddot + k^2 theta = 0
    assert sp.expand(eth - (J * th.diff(T, 2) + k**2 * th)) == 0


def test_sledge_accelerations(sledge):
    acc = sledge.accelerations()
    assert set(acc) == {x.diff(T, 2), th.diff(T, 2)}
    assert sp.expand(acc[x.diff(T, 2)] + x.diff(T) * th.diff(T) * sp.tan(th)) == 0
    assert sp.expand(acc[th.diff(T, 2)] + k**2 * th / J) == 0


def test_sledge_energy_is_3_4(sledge):
    printed = m / 2 * x.diff(T)**2 * (1 + sp.tan(th)**2) + J / 2 * th.diff(T)**2 + k**2 * th**2 / 2
    assert sp.expand(sledge.energy() - printed) == 0


def test_sledge_time_steps_all_verified(sledge):
    labels = sledge.steps.labels
    for lab in ("1.1", "1.2", "1.4", "1.10", "1.11"):
        assert lab in labels
    report = sledge.verify()
    assert report.ok, str(report)
    assert {c.label for c in report} >= {"1.4", "1.10", "1.11"}


def test_projectile_holonomic():
    s = wt.examples.projectile()
    assert s.is_holonomic
    X, Y = s.coordinates
    acc = s.accelerations()
    assert acc[X.diff(T, 2)] == 0
    assert acc[Y.diff(T, 2)] == -g
    assert "1.10" not in s.steps.labels
    assert s.verify().ok


def test_kepler_accelerations():
    s = wt.examples.kepler()
    r, phi = s.coordinates
    mu = sp.Symbol("mu", positive=True)
    acc = s.accelerations()
    assert sp.simplify(acc[r.diff(T, 2)] - (r * phi.diff(T)**2 - mu / r**2)) == 0
    assert sp.simplify(acc[phi.diff(T, 2)] + 2 * r.diff(T) * phi.diff(T) / r) == 0


def test_energy_rate_vanishes_only_for_the_right_accelerations(sledge):
    """The (1.11) check can fail: with a wrong acceleration dE/dt is not zero."""
    from whittaker_teach.verify import check_zero
    rate = sledge._dt(sledge._energy())
    wrong = {a: v + 1 for a, v in sledge._accelerations().items()}
    assert not check_zero("1.11", "wrong", rate.xreplace(wrong), sledge._sample_time).holds
    assert check_zero("1.11", "right", rate.xreplace(sledge._accelerations()),
                      sledge._sample_time).holds


def test_nonlinear_constraint_energy():
    s = wt.examples.cone_particle()
    X, Y, Z = s.coordinates
    a = sp.Symbol("a", positive=True)
    E = s.energy()
    expected = m / 2 * (1 + a**2) * (X.diff(T)**2 + Y.diff(T)**2) + m * g * Y
    assert sp.expand(E - expected) == 0
    assert s.verify().ok


def test_lu_pivots_chosen_by_value_give_the_same_accelerations(monkeypatch):
    """A large mass matrix is solved with its LU pivots chosen by value at the sampled
    regular point (``system.PIVOT_BY_VALUE_NODES``).  Forced here on the cone particle
    (2x2, the only example that needs LU) and on a holonomic family member, in (1.4) and
    in (1.26): the accelerations agree with SymPy's own pivoting at random points, and
    every check still holds."""
    import random
    import mpmath
    from whittaker_teach import system
    from whittaker_teach.bench import family
    from whittaker_teach.verify import evaluate

    def build():
        L, coords, dep = family(3, holonomic=True)
        return [wt.examples.get("cone_particle").reduce(),
                wt.ChaplyginSystem(L, coords, dependent=dep).reduce(coords[0], +1)]
    default = build()
    monkeypatch.setattr(system, "PIVOT_BY_VALUE_NODES", 0)
    by_value = build()
    rng = random.Random(5)
    for a, b in zip(default, by_value):
        assert b.verify().ok
        for acc_a, acc_b, sample in ((a.system._accelerations(), b.system._accelerations(),
                                      a.system._sample_time),
                                     (a._accelerations(), b._accelerations(), a._sample)):
            for _ in range(3):
                pt = {s: mpmath.mpf(v) for s, v in sample(rng).items()}
                with mpmath.workdps(40):
                    for k in acc_a:
                        va, vb = evaluate(acc_a[k], dict(pt)), evaluate(acc_b[k], dict(pt))
                        assert abs(va - vb) <= mpmath.mpf(10)**-30 * max(1, abs(va))
