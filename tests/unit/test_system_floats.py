"""Float coefficients (issue 26, item 2): taken as the exact rationals they print as.

Users type 0.5.  Each Float of L and of the constraints becomes ``Rational(str(f))``
(0.845 -> 169/200), listed in ``system.rationalized`` and stated by step (1.1) and its
check; the derivation is then the rational model's, so that verify() holds and the
equations are those of the float-free system, identically.
"""
import pytest
import sympy as sp
from sympy.physics.mechanics import dynamicsymbols

import whittaker_teach as wt

t = dynamicsymbols._t
x, th, y, z = dynamicsymbols("x theta y z")
xd, yd, thd, zd = (c.diff(t) for c in (x, y, th, z))
m = sp.Symbol("m", positive=True)

CASES = {
    # the issue's example
    "sledge": (0.5*(xd**2 + yd**2) + 0.25*thd**2 - 0.845*th**2, [x, th, y], {yd: xd*sp.tan(th)}),
    "parameter and float": (m*0.5*(xd**2 + yd**2) + 0.1*thd**2 - 1.3*sp.cos(th), [x, th, y],
                            {yd: 0.75*xd*sp.sin(th)}),
    "holonomic": (0.5*(xd**2 + thd**2) - 0.3*x**2 - 2.5*th**2 - 0.2*x*th, [x, th], None),
    "chetaev": ((xd**2 + yd**2 + zd**2)/2.0 - 0.7*y**2, [x, y, z],
                {zd: 1.5*sp.sqrt(xd**2 + yd**2)}),
    "float exponent": (0.5*(xd**2.0 + yd**2) + 0.25*thd**2 - th**2.0, [x, th, y],
                       {yd: xd*sp.tan(th)}),
}


def _rational(e):
    return e.xreplace({f: sp.Rational(str(f)) for f in e.atoms(sp.Float)})


@pytest.mark.parametrize("name", sorted(CASES))
def test_float_system_verifies_and_equals_the_rational_one(name):
    L, qs, dep = CASES[name]
    S = wt.ChaplyginSystem(L, qs, dependent=dep, name=name)
    assert S.rationalized and all(isinstance(r, sp.Rational) for r in S.rationalized.values())
    exact = wt.ChaplyginSystem(_rational(L), qs, dependent=dep and {k: _rational(v)
                                                                     for k, v in dep.items()})
    assert not exact.rationalized
    red, red_exact = S.reduce(qs[0]), exact.reduce(qs[0])
    report = red.verify()
    assert report.ok, str(report)
    assert not any(e.atoms(sp.Float) for e in red.equations + S.equations_of_motion())
    assert [sp.expand(a - b) for a, b in zip(S.equations_of_motion(),
                                             exact.equations_of_motion())] == [0] * len(S._sig)
    assert [sp.expand(a - b) for a, b in zip(red.equations, red_exact.equations)] == \
        [0] * len(red.equations)
    first = report[0]
    assert first.label == "1.1" and "exact rationals they print as" in first.claim
    assert "Float" in S.steps["1.1"].note and "exact rational" in repr(S)


def test_the_issue_example_names_each_rational():
    S = wt.ChaplyginSystem(*CASES["sledge"])
    assert S.rationalized == {sp.Float(0.5): sp.Rational(1, 2), sp.Float(0.25): sp.Rational(1, 4),
                              sp.Float(-0.845): sp.Rational(-169, 200)}
    assert "-0.845 = -169/200" in S.steps["1.1"].note
    assert str(S.verify()).startswith("(1.1) the Float coefficients")


def test_high_precision_float_is_its_printed_digits():
    S = wt.ChaplyginSystem(sp.Float("0.1", 30) * (xd**2 + thd**2) - th**2, [x, th])
    (r,) = S.rationalized.values()
    assert r == sp.Rational(1, 10)
    assert S.verify().ok


def test_no_floats_no_note():
    S = wt.examples.sledge()
    assert S.rationalized == {} and S.steps["1.1"].check is None
