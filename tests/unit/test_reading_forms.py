"""Reading forms: each compact form is checked against the library's form, and a wrong
one is reported as not holding."""

import pytest
import sympy as sp

import whittaker_teach as wt
from whittaker_teach import reading as R
from whittaker_teach.nielsen import nielsen
from whittaker_teach.verify import check_zero


@pytest.fixture(scope="module", params=["sledge", "offset_sleigh", "kepler", "charged_particle"])
def red(request):
    ex = wt.examples.get(request.param)
    return ex.build().reduce(ex.coordinate, +1)


FORMS = {
    "1.12": (lambda r: [R.velocity_form(r)], lambda r: [r._vstar]),
    "1.16": (lambda r: [R.lstar_form(r)], lambda r: [r._Lstar]),
    "1.26a": (R.momentum_forms, lambda r: r._Pstar),
    "1.26": (R.whittaker_forms, lambda r: r._eqs),
    "2.1": (lambda r: [R.total_derivative_form(r)],
            lambda r: [nielsen(r)["2.1"]]),
    "2.4": (R.nielsen_forms, lambda r: nielsen(r)["2.4"]),
}


@pytest.mark.parametrize("label", list(FORMS))
def test_reading_form_equals_library(red, label):
    shown, library = FORMS[label]
    forms, lib = shown(red), list(library(red))
    if not lib:
        pytest.skip("no dependent coordinate")
    assert R.check_reading(label, "reading form", forms, lib, red).holds is True


@pytest.mark.parametrize("label", list(FORMS))
def test_wrong_reading_form_is_refused(red, label):
    shown, library = FORMS[label]
    forms, lib = shown(red), list(library(red))
    if not lib:
        pytest.skip("no dependent coordinate")
    wrong = [forms[0] * sp.Rational(11, 10) + red.h] + forms[1:]   # deliberately wrong
    chk = R.check_reading(label, "a wrong reading form", wrong, lib, red)
    assert chk.holds is False and chk.max_residual > 1e-6


def test_cleared_form_vanishes_on_the_solved_acceleration(red):
    acc = red._tidy_accelerations()
    for cleared in R.cleared_forms(red):
        chk = check_zero("1.26b", "cleared", cleared.xreplace(acc), red._sample)
        assert chk.holds is True
        wrong = check_zero("1.26b", "cleared, wrong q''", cleared, red._sample)
        assert wrong.holds is False


def test_steps_carry_the_reading_checks(red):
    for lab in ("1.12", "1.16", "1.26", "1.26b", "2.1", "2.4"):
        step = red.steps[lab]
        assert step.check is not None and step.check.holds is True, lab
        assert "form shown" in step.check.claim or lab == "1.26b"


def test_sledge_reading_forms_are_the_papers(sledge_red):
    """(1.26) is (3.9): d/dx(J theta' sqrt(R)/sqrt(A)) + k^2 theta sqrt(A)/sqrt(R);
    (1.16) is (3.7), with m (1 + tan^2 theta) factored."""
    (form,) = R.whittaker_forms(sledge_red)
    terms = sp.Add.make_args(form)
    assert len(terms) == 2 and any(isinstance(t, R.TotalD) for t in terms)
    L = R.lstar_form(sledge_red)
    th = [s for s in L.free_symbols if s.name == "theta"][0]
    assert (1 + sp.tan(th)**2) in L.atoms(sp.Add)


def test_powers_combined_and_tidy():
    a, b = sp.symbols("a b")
    A = a**2 + b
    e = sp.sqrt(A) * sp.Mul(sp.expand(A), a, evaluate=False)
    assert R.powers_combined(e) == a * A**sp.Rational(3, 2)
    t = R.tidy(a * (2 * sp.tan(b)**2 + 2) / 2)
    assert t == a * (sp.tan(b)**2 + 1)


def test_total_derivative_prints_d_dx():
    x, f = sp.symbols("x f")
    assert sp.latex(R.TotalD(f, x)) == r"\frac{d}{d x}\left(f\right)"
    assert "d/dx" in sp.pretty(R.TotalD(f, x), use_unicode=True)


def test_powers_combined_leaves_a_base_holding_a_high_power_unexpanded(monkeypatch):
    """A base that is small as written but huge when expanded, y + (1 + x/3)**40, is
    compared as written: expanding it is what once made the Nielsen reading forms of
    a system with the issue's potential (1 + x/3 + theta/5)**40 take 90 s."""
    a, x, y = sp.symbols("a x y")
    A = y + (1 + x / 3)**40
    expanded, real = [], sp.expand
    monkeypatch.setattr(sp, "expand", lambda e, *args, **kw: expanded.append(e) or real(e, *args, **kw))
    out = R.powers_combined(sp.sqrt(A) * sp.Mul(A, 1, evaluate=False) * a)
    assert out == a * A**sp.Rational(3, 2)
    assert A not in expanded
    small, z = x * (a + 1) + y, sp.Symbol("z")
    out = R.powers_combined(sp.sqrt(small) * (a * x + x + y) * z)
    assert small in expanded                  # small bases are still compared expanded
    assert out in (z * small**sp.Rational(3, 2), z * (a * x + x + y)**sp.Rational(3, 2))


def test_powers_combined_expands_nothing_when_no_two_factors_are_sums(monkeypatch):
    """With at most one sum among the factors of a product there is nothing to merge
    (SymPy's Mul has merged equal bases as written): no ``expand``."""
    a, x, y = sp.symbols("a x y")
    expanded, real = [], sp.expand
    monkeypatch.setattr(sp, "expand", lambda e, *args, **kw: expanded.append(e) or real(e, *args, **kw))
    e = sp.sqrt(x * (a + 1) + y) * sp.tan(a)**2 * x / (a - y)**0 * sp.sqrt(a)
    assert R.powers_combined(e) == e
    assert not expanded


def _powers_combined_by_expand(expr):
    """The merge as first written: every small sum of a product with two sums or more
    expanded to compare it, through ``replace``."""
    from whittaker_teach.dag import expanded_terms, tree_size

    def merge(m):
        groups, order = {}, []
        sums = sum(isinstance(f.as_base_exp()[0], sp.Add) for f in m.args)
        for f in sp.Mul.make_args(m):
            b, e = f.as_base_exp()
            small = (sums > 1 and isinstance(b, sp.Add) and tree_size(b, 200) <= 200
                     and expanded_terms(b, 200) <= 200)
            key = sp.expand(b) if small else b
            if key not in groups:
                order.append(key)
                groups[key] = [b, sp.S.Zero]
            groups[key][1] += e
        if len(order) == len(sp.Mul.make_args(m)):
            return m
        return sp.Mul(*[sp.Pow(groups[k][0], groups[k][1]) for k in order])
    return expr.replace(lambda e: isinstance(e, sp.Mul), merge)


def test_powers_combined_expands_only_sums_that_may_be_equal():
    """The screen (``verify.expand_may_equal``) expands only the sums of a product that
    may be equal: on random products of powers of sums, some equal after ``expand``,
    the result is the one of expanding them all."""
    import random
    a, b, t = sp.symbols("a b theta")
    sums = [a + b, a**2 + 2 * a * b + b**2, (a + b) * (a - b), a**2 - b**2, a * (a + 2 * b),
            a**2 + 2 * a * b, sp.tan(t)**2 + 1, 1 + sp.tan(t) * sp.tan(t), a - b]
    exps = [sp.S.Half, -1, 2, sp.Rational(-3, 2), 3]
    rng = random.Random(5)
    merged = 0
    for _ in range(150):
        e = sp.Mul(*[sp.Pow(rng.choice(sums), rng.choice(exps), evaluate=False)
                     for _ in range(rng.randint(2, 4))], a, evaluate=False)
        e = e + b * e
        mine = R.powers_combined(e)
        assert mine == _powers_combined_by_expand(e)
        merged += mine != e
    assert merged > 20


def test_reading_checks_without_rebuilding_agree(red, monkeypatch):
    """With every d/dq_eps of (1.26) evaluated as its derivative (the large-system path)
    instead of carried out into a rebuilt form, the forms hold and a wrong one fails."""
    label = "1.26"
    import whittaker_teach.verify as V
    monkeypatch.setattr(V, "SUBSTITUTE_LIMIT", 0)
    shown, library = FORMS[label]
    forms, lib = shown(red), list(library(red))
    chk = R.check_reading(label, "reading form", forms, lib, red)
    assert chk.holds is True and chk.method == "numeric" and chk.definitions
    assert all(isinstance(n, R.TotalD) for n in chk.definitions)
    wrong = [forms[0] * sp.Rational(11, 10) + red.h] + forms[1:]
    assert R.check_reading(label, "wrong", wrong, lib, red).holds is False


def test_carried_out_matches_evaluate(red):
    """The definitions of the TotalD nodes are what ``evaluate`` substitutes."""
    from whittaker_teach.dag import substitute
    forms = R.whittaker_forms(red)
    defs = R.carried_out(forms, red, [])
    assert defs and all(isinstance(n, R.TotalD) for n in defs)
    for f in forms:
        assert substitute(f, defs) == R.evaluate(f, red, [])
