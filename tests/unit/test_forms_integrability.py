"""Frobenius' test on constraints whose integrability is known."""

import pytest
import sympy as sp
from sympy.physics.mechanics import dynamicsymbols

from whittaker_teach.errors import ModelError
from whittaker_teach.forms import NonholonomicSystem, examples, frobenius

t = dynamicsymbols._t
x, y, z, th, phi, psi = dynamicsymbols("x y z theta phi psi")
D = {c: c.diff(t) for c in (x, y, z, th, phi, psi)}


def rate_on_constraints(I, F):
    """dF/dt with the dependent velocities of the constraints: zero for an integral."""
    S = I.system
    return sp.simplify(sum(sp.diff(F, c) * S.constraints.get(c.diff(t), c.diff(t))
                           for c in S.coordinates))


@pytest.mark.parametrize("make, cs", [
    (lambda: frobenius(examples.sledge()), None),
    (lambda: frobenius(examples.rolling_disk()), None),
    (lambda: frobenius([D[z] - y * D[x]], [x, y, z]), None),              # the contact form
    (lambda: frobenius([D[y] - D[x] * sp.tan(th)], [x, th, y]), None),
    # the rolling disk with its tilt-free heading as a third coordinate set
    (lambda: frobenius({D[x]: sp.cos(psi) * D[th], D[y]: sp.sin(psi) * D[th]},
                       [psi, th, x, y]), None),
])
def test_non_integrable(make, cs):
    I = make()
    assert I.is_holonomic is False
    assert I.integrals is None
    assert I.brackets                                   # a component that does not vanish
    step = I.steps["Fr2"]
    # the verdict is a finding, confirmed by a check that the bracket is not zero
    assert step.check.holds is True and step.check.method == "refutation"
    assert step.status == "verified" and "not integrable" in step.note
    assert "does not vanish" in step.check.claim
    assert I.verify().ok


@pytest.mark.parametrize("make, n_integrals", [
    # holonomic in disguise: x xdot + y ydot = 0, x^2 + y^2 = const
    (lambda: frobenius([x * D[x] + y * D[y]], [x, y]), 1),
    # ydot cos x - y sin x xdot = 0: d(y cos x) = 0
    (lambda: frobenius([D[y] * sp.cos(x) - y * sp.sin(x) * D[x]], [x, y]), 1),
    # zdot = 2 x xdot + ydot: exact, z - x^2 - y = const
    (lambda: frobenius({D[z]: 2 * x * D[x] + D[y]}, [x, y, z]), 1),
    # two constraints, each alone not integrable (zdot = y xdot is the contact form), whose
    # combination is: y - x and z - x^2/2 - (y - x) x are constant
    (lambda: frobenius([D[z] - y * D[x], D[y] - D[x]], [x, y, z], dependent=[y, z]), 2),
    # one coordinate free: a line field is always integrable
    (lambda: frobenius({D[y]: sp.cos(x) * D[x], D[z]: D[x]}, [x, y, z]), 2),
    # y xdot - x ydot = 0: the integrating factor 1/y^2, x/y = const
    (lambda: frobenius([y * D[x] - x * D[y]], [x, y]), 1),
    # 2 y xdot + x ydot = 0: closed after 1/(x y) (or x), x^2 y = const
    (lambda: frobenius([2 * y * D[x] + x * D[y]], [x, y]), 1),
])
def test_integrable_with_the_integrals(make, n_integrals):
    I = make()
    assert I.is_holonomic is True
    assert I.brackets == {}
    F = I.integrals
    assert F is not None and len(F) == n_integrals
    for f in F:
        assert rate_on_constraints(I, f) == 0
    assert I.steps["Fr3"].status == "verified"
    assert I.verify().ok


def test_the_disguised_integral_is_the_circle():
    F = frobenius([x * D[x] + y * D[y]], [x, y]).integrals[0]
    assert sp.expand(2 * F - (x**2 + y**2)) == 0


def test_each_of_the_pair_alone_is_not_integrable():
    assert frobenius([D[z] - y * D[x]], [x, y, z]).is_holonomic is False
    assert frobenius([D[z] - y * D[x], D[y] - D[x]], [x, y, z],
                     dependent=[y, z]).is_holonomic is True


def test_preconditions():
    with pytest.raises(ModelError, match="linear constraints"):
        frobenius(examples.appell_hamel())
    with pytest.raises(ModelError, match="needs the coordinates"):
        frobenius([D[y] - D[x]])
    with pytest.raises(ModelError, match="no constraints"):
        frobenius(NonholonomicSystem(D[x]**2, [x]))


def test_an_integrating_factor_over_a_coefficient_squared():
    F = frobenius([y * D[x] - x * D[y]], [x, y]).integrals[0]
    assert sp.simplify(F - x / y) == 0


def test_the_brackets_are_tidied_and_named_in_latex():
    I = frobenius(examples.sleigh())
    (comp,) = I.brackets.values()
    assert list(comp.values()) == [-1 / sp.cos(th)**2]
    tex = frobenius(examples.rolling_disk()).steps["Fr2"].to_latex()
    assert r"\begin{aligned}[" not in tex
    assert r"[X_{\psi}, X_{\theta}]^{x}" in tex
    assert "psi," not in frobenius(examples.rolling_disk()).steps["Fr1"].to_latex()
