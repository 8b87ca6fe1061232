"""Equivalence on the statement's whole domain, at points drawn afresh for every check
(issue 37, item 7).

Property tests: the sample points of one check cover the stated domain (an infinite
range over many decades, a bounded one up to both ends, both signs of the line), they
respect the exercise's conditions, and two checks of the same answer use different
points.  Attack tests: answers that agree with the right one only inside the old
fixed box (0.5 < m < 2, |theta'| < 3, 0.5 < h < 4, 0.05 < xdot < 3), or only at the
points fixed for a part, or by less than the numeric tolerance, are refused; right
answers are accepted at every check and a wrong one gets the same hint every time.
"""
import importlib.util
import json
import math
import zlib
from pathlib import Path

import mpmath
import pytest
import sympy as sp

from whittaker_teach.exercises import check, load
from whittaker_teach.exercises import compare as cmp
from whittaker_teach.exercises.authoring import PRESETS, SpecError, domain_data, read_spec
from whittaker_teach.exercises.catalog import EXERCISES
from whittaker_teach.exercises.compare import INF, Domain, compare, exact_zero

ROOT = Path(__file__).resolve().parents[2]
x, y = sp.symbols("x y", real=True)
DRAWS = 40            # checks simulated per property


def _values(points, s):
    return [float(mpmath.re(p[s])) for p in points]


# ------------------------------------------------------------ the points cover the domain
def test_a_half_line_is_covered_over_many_decades_at_every_check():
    dom = Domain({x: (0, INF)})
    for _ in range(DRAWS):
        v = _values(dom.fresh(), x)
        assert min(v) > 0
        assert min(v) < 10**-2 and max(v) > 10**2, v           # below 1 and above 100
        assert math.log10(max(v) / min(v)) >= 4, v              # at least 4 decades
    # over many checks, down to 10**-3 and up to 10**3 (DECADES)
    every = [s for _ in range(DRAWS) for s in _values(dom.fresh(), x)]
    assert min(every) < 2e-3 and max(every) > 5e2


def test_a_shifted_half_line_starts_at_its_end():
    dom = Domain({x: (-1.0, INF), y: (-INF, 2.0)})
    for _ in range(DRAWS):
        pts = dom.fresh()
        vx, vy = _values(pts, x), _values(pts, y)
        assert min(vx) > -1 and min(vx) < -1 + 1e-2 and max(vx) > 100
        assert max(vy) < 2 and max(vy) > 2 - 1e-2 and min(vy) < -100


def test_the_whole_line_is_covered_on_both_sides_of_zero():
    dom = Domain({x: (-INF, INF)})
    for _ in range(DRAWS):
        v = _values(dom.fresh(), x)
        assert sum(a < 0 for a in v) == sum(a > 0 for a in v) == 4, v
        assert min(abs(a) for a in v) < 0.05 and max(abs(a) for a in v) > 30, v
        assert min(v) < -30 and max(v) > 30


def test_a_bounded_range_is_covered_to_both_ends():
    half_pi = math.pi / 2
    dom = Domain({x: (0.0, half_pi)})
    every = []
    for _ in range(DRAWS):
        v = _values(dom.fresh(), x)
        assert 0 < min(v) < half_pi / 8 and half_pi * 7 / 8 < max(v) < half_pi, v
        # one point in each eighth of the range
        assert sorted(int(a / half_pi * 8) for a in v) == list(range(8)), v
        every += v
    assert min(every) < 1e-3 and max(every) > half_pi - 1e-3     # close to both ends


def test_every_exercise_samples_its_declared_domain():
    """For every exercise: the points lie in the declared ranges and satisfy the
    conditions; an unconditioned infinite range is covered over decades at every check."""
    for ex_id in EXERCISES:
        ex = load(ex_id)
        if ex.withheld:
            continue
        _, dom, _ = ex.build()
        cond_syms = set().union(*[c.free_symbols for c in dom.conditions])
        for _ in range(5):
            pts = dom.fresh()
            assert len(pts) == cmp.POINTS
            for p in pts:
                assert dom.admissible(p)
                for s, (lo, hi) in dom.ranges.items():
                    assert lo < p[s] < hi
            for s, (lo, hi) in dom.ranges.items():
                if s in cond_syms:
                    continue
                v = _values(pts, s)
                if lo == -INF and hi == INF:
                    assert min(v) < -30 and max(v) > 30, (ex_id, s, v)
                elif hi == INF:
                    assert min(v) < lo + 1e-2 and max(v) > lo + 1e2, (ex_id, s, v)
                elif lo == -INF:
                    assert max(v) > hi - 1e-2 and min(v) < hi - 1e2, (ex_id, s, v)
                else:
                    width = hi - lo
                    assert min(v) < lo + width / 8 and max(v) > hi - width / 8, (ex_id, s)


def test_the_stored_domains_are_the_sources_declared_ones():
    """The answer data keeps each exercise's domain as its source declares it (presets
    by name, so that they mean the whole half-line or line), not a small box."""
    spec = importlib.util.spec_from_file_location("make_exercises",
                                                  ROOT / "scripts" / "make_exercises.py")
    make_exercises = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(make_exercises)
    data_dir = ROOT / "whittaker_teach" / "exercises" / "data"
    checked = 0
    for ex_id, path in make_exercises.sources().items():
        target = data_dir / f"{ex_id}.json"
        if not target.exists():
            continue
        declared = domain_data(make_exercises.spec_of(ex_id, path.read_text(encoding="utf-8")))
        assert json.loads(target.read_text(encoding="utf-8"))["domain"] == declared, ex_id
        checked += 1
    assert checked >= 11
    assert PRESETS["positive"] == PRESETS["speed"] == (0.0, INF)
    assert PRESETS["slope"] == PRESETS["real"] == PRESETS["energy"] == (-INF, INF)
    assert PRESETS["angle"] == (-math.pi / 2, math.pi / 2)


def test_a_half_line_can_be_declared_with_none():
    """[low, None] is s > low (a > pi/2 of turning-point), kept as such in the data."""
    from whittaker_teach.exercises.authoring import domain_range
    spec = read_spec("EXERCISE = {'title': 't', 'symbols': 'a e', 'domain': "
                     "{'a': [1.5708, None], 'e': [None, 0]}, 'parts': {'p': {'what': 'w'}}}")
    assert domain_data(spec) == {"a": [1.5708, None], "e": [None, 0.0]}
    assert domain_range([1.5708, None]) == (1.5708, INF)
    assert domain_range([None, 0.0]) == (-INF, 0.0)
    dom = Domain({x: domain_range([1.5708, None])})
    v = _values(dom.fresh(), x)
    assert min(v) > 1.5708 and min(v) < 1.5708 + 1e-2 and max(v) > 100


def test_a_positive_symbol_cannot_be_given_a_negative_domain():
    with pytest.raises(SpecError, match="declared positive"):
        read_spec("EXERCISE = {'title': 't', 'symbols': 'm+', 'domain': {'m': [-1, 1]}, "
                  "'parts': {'a': {'what': 'w'}}}")
    with pytest.raises(SpecError, match="declared positive"):
        read_spec("EXERCISE = {'title': 't', 'symbols': 'm+', 'domain': {'m': [None, 1]}, "
                  "'parts': {'a': {'what': 'w'}}}")
    for bad in ("[0, 1e999]", "[2, 1]", "[0, True]", "[0]"):
        with pytest.raises(SpecError, match="finite"):
            read_spec("EXERCISE = {'title': 't', 'symbols': 'm', 'domain': {'m': " + bad +
                      "}, 'parts': {'a': {'what': 'w'}}}")


# ------------------------------------------------------------ fresh points at every check
def _recording(monkeypatch):
    seen = []
    original = Domain.fresh

    def fresh(self, n=cmp.POINTS):
        pts = original(self, n)
        seen.append(pts)
        return pts
    monkeypatch.setattr(Domain, "fresh", fresh)
    return seen


def test_two_checks_of_the_same_answer_use_different_points(monkeypatch):
    seen = _recording(monkeypatch)
    answer = "sqrt(2*h - k^2*theta^2)*sqrt(m*sec(theta)^2 + J*theta'^2)"
    assert check("sledge-L-star", answer, part="L_star").ok
    assert check("sledge-L-star", answer, part="L_star").ok
    assert len(seen) == 2
    first = {tuple(sorted((str(s), v) for s, v in p.items())) for p in seen[0]}
    second = {tuple(sorted((str(s), v) for s, v in p.items())) for p in seen[1]}
    assert not first & second
    # no coordinate value is shared either
    vals = lambda pts: {v for p in pts for v in p.values()}       # noqa: E731
    assert not vals(seen[0]) & vals(seen[1])


def test_fresh_points_come_from_the_operating_system(monkeypatch):
    """The generator is seeded from os.urandom (not a seed of the part): fixed bytes give
    the same points, different bytes different ones."""
    dom = Domain({x: (0, INF)})
    monkeypatch.setattr(cmp.os, "urandom", lambda n: b"\x01" * n)
    a, b = dom.fresh(), dom.fresh()
    monkeypatch.setattr(cmp.os, "urandom", lambda n: b"\x02" * n)
    c = dom.fresh()
    assert _values(a, x) == _values(b, x) != _values(c, x)


def test_right_answers_are_accepted_at_every_check_and_wrong_ones_get_one_hint():
    right = "sqrt(2*h - k^2*theta^2)*sqrt(m*(1 + tan(theta)^2) + J*thetaprime^2)"
    wrong = "sqrt(2*h - k^2*theta^2)*sqrt(m*(1 + tan(theta)^2) + J*thetaprime^2)/k"
    messages = set()
    for _ in range(10):
        assert check("sledge-L-star", right, part="L_star").ok
        f = check("sledge-L-star", wrong, part="L_star")
        assert not f.ok
        messages.add(f.message)
    assert len(messages) == 1, messages
    assert "1/k" in messages.pop()


def test_every_solution_is_accepted_at_every_check():
    for ex_id in EXERCISES:
        ex = load(ex_id)
        if ex.withheld:
            continue
        for name, p in ex.parts.items():
            answer = p.answer_key if p.is_choice else p.expected
            if not p.is_choice:     # a form the exact test does not decide: only numbers
                answer = sp.UnevaluatedExpr(answer) if answer.free_symbols else answer
            for _ in range(3):
                assert check(ex_id, answer, part=name).ok, (ex_id, name)


def test_an_answer_fitted_to_the_parts_fixed_points_is_refused():
    """Zero at every point fixed for the part (it could be computed from the code), so only
    the points drawn afresh see it: without them it would be accepted."""
    ex = load("sledge-L-star")
    _, dom, parts = ex.build()
    part = parts["L_star"]
    seed = zlib.crc32(f"{ex.id}:{part.name}".encode())
    tp = [s for s in dom.symbols if s.name == "thetaprime"][0]
    fixed = dom.points(seed, core=True) + dom.points(seed)
    bump = sp.Mul(*[tp - sp.Float(mpmath.nstr(p[tp], 40), 40) for p in fixed])
    answer = part.expected + bump / 10**6
    assert compare(answer, part.expected, dom, seed, fresh=False).ok     # the fixed points
    for _ in range(5):
        f = check("sledge-L-star", answer, part="L_star")
        assert not f.ok and f.status == "wrong", f.message


# ------------------------------------------------------------ attacks on the old box
ATTACKS = [
    # right + a term that is zero for |theta'| < 3 (the old slope box)
    ("sledge-L-star", "L_star",
     "sqrt(2*h - k^2*theta^2)*sqrt(m*sec(theta)^2 + J*theta'^2) + Max(0, theta' - 3)"),
    ("sledge-L-star", "L_star",
     "Piecewise((sqrt(2*h - k^2*theta^2)*sqrt(m*sec(theta)^2 + J*theta'^2), Abs(theta') < 3),"
     " (0, True))"),
    # equal to the right one only for 0 < b < 2 (the old box of a positive constant)
    ("chaplygin-sleigh", "J_eff", "J + m*Min(b, 2)^2"),
    ("chaplygin-sleigh", "J_eff", "J + m*b^2 + Heaviside(b - 2)*(b - 2)"),
    # only for h < 4 (the old energy box)
    ("sledge-L-star", "xdot",
     "sqrt(2*Min(h, 4) - k^2*theta^2)/sqrt(m*(1 + tan(theta)^2) + J*theta'^2)"),
    # only for xdot > 0.05 (the old speed box): a term for small speeds
    ("identity-1-19", "dxdot_dthetaprime",
     "-xdot*J*thetaprime/(m + J*thetaprime^2) + Heaviside(1/20 - xdot)"),
    # the slope clamped to the old box
    ("identity-1-19", "dxdot_dthetaprime",
     "-xdot*J*Max(-3, Min(3, thetaprime))/(m + J*thetaprime^2)"),
    # only for m < 2 (a mass of the old box)
    ("kepler-orbit", "h", "-Min(m, 2)*mu*(1 - e^2)/(2*p)"),
    # a factor that is 1 to ten digits on the old box (a relative 1e-10 there)
    ("kepler-orbit", "h", "-m*mu*(1 - e^2)/(2*p)*(1 + m^4/10**13)"),
]


def _sympy(text):
    """A SymPy object (as a student's code builds it: Max, Piecewise, Heaviside are not
    typed functions, but a SymPy answer may contain them)."""
    return sp.sympify(text.replace("theta'", "thetaprime").replace("^", "**"))


@pytest.mark.parametrize("ex_id, part, answer", ATTACKS)
def test_an_answer_right_only_inside_the_old_box_is_refused(ex_id, part, answer):
    """Refused at every check, with the same practice hint (the part's own points over the
    whole domain see it) and no quantity in the graded one."""
    messages = set()
    for _ in range(3):
        f = check(ex_id, _sympy(answer), part=part)
        assert not f.ok and f.status == "wrong", (answer, f.message)
        messages.add(f.message)
    assert len(messages) == 1, messages
    graded = check(ex_id, _sympy(answer), part=part, graded=True)
    assert not graded.ok
    assert graded.message in {h[:1].upper() + h[1:] + "." for h in cmp.GRADED_HINTS.values()}


def test_the_hint_of_a_case_answer_names_the_cases_and_their_symbol():
    for ex_id, part, answer in ATTACKS[:4] + ATTACKS[5:]:
        f = check(ex_id, _sympy(answer), part=part)
        assert "part of the domain" in f.message, (answer, f.message)
    f = check("identity-1-19", _sympy(ATTACKS[5][2]), part="dxdot_dthetaprime")
    assert "for example at xdot = " in f.message and "Heaviside" in f.message, f.message
    f = check("kepler-orbit", _sympy(ATTACKS[8][2]), part="h")
    assert "negligible at moderate values" in f.message, f.message


def test_a_number_part_with_a_hidden_dependence_is_refused():
    """A number plus a term that depends on a symbol only beyond the old box (theta' > 20):
    the symbol is varied over the whole domain, at fixed and at fresh points."""
    value = load("turning-point").parts["x_turn"].expected
    tp = sp.Symbol("thetaprime")
    f = check("turning-point", value + sp.Max(0, tp - 20), part="x_turn")
    assert not f.ok and "depends on thetaprime" in f.message, f.message
    assert check("turning-point", value + sp.sin(tp)**2 + sp.cos(tp)**2 - 1,
                 part="x_turn").ok


def test_an_expression_part_with_a_hidden_dependence_is_refused():
    """theta is not a variable of J_eff: a term in it that vanishes on the fixed points is
    not substituted away, the comparison varies theta too."""
    f = check("chaplygin-sleigh", _sympy("J + m*b^2 + Max(0, thetaprime - 20)"),
              part="J_eff")
    assert not f.ok, f.message


# ------------------------------------------------------------ tolerance and the exact test
def test_the_tolerance_is_relative_at_every_magnitude():
    dom = Domain({x: (0, INF)})
    # 1e-12 absolute: below the old absolute tolerance, but 1e-9 relative at x ~ 1e-3
    assert not compare(sp.sin(x) + sp.Float("1e-12"), sp.sin(x), dom).ok
    assert not compare(sp.sin(x) * (1 + sp.Float("1e-9")), sp.sin(x), dom).ok
    assert compare(sp.sin(x) * (1 + sp.Float("1e-14")), sp.sin(x), dom).ok
    # large values: 1e-10 relative is the tolerance, whatever the magnitude
    assert compare(sp.exp(x / 100) * (1 + sp.Float("1e-12")), sp.exp(x / 100), dom).ok


def test_the_exact_test_decides_rational_answers():
    dom = Domain({x: (0, INF), y: (-INF, INF)})
    assert exact_zero((x**2 - y**2) / (x - y), x + y, dom) is True
    assert exact_zero(x + y + x**2 / 10**40, x + y, dom) is False
    assert exact_zero(sp.sqrt(x**2), x, dom) is None            # a function: numbers decide
    assert exact_zero(sp.sin(x)**2 + sp.cos(x)**2, sp.S(1), dom) is None
    assert exact_zero(sp.tan(x) * (x + 1) / (x + 1), sp.tan(x), dom) is True
    assert exact_zero(x + sp.Float("0.5"), x + sp.Rational(1, 2), dom) is None
    # what the numbers cannot see, the exact test does
    f = compare(x + y + x**2 / 10**40, x + y, dom)
    assert not f.ok and "not 0" in f.hint
    f = check("kepler-orbit", "-m*mu*(1 - e^2)/(2*p) + e^2/10^40", part="h")
    assert not f.ok and "not 0" in f.message
    assert check("kepler-orbit", "-m*mu*(1 - e^2)*(e^2 + 3*e + 2)/(2*p*(e + 1)*(e + 2))",
                 part="h").ok


def test_the_exact_test_is_bounded():
    """A large product of sums is not expanded: the test declines (None) at once."""
    import time
    syms = sp.symbols("a0:12")
    big = sp.Mul(*[sum(syms[i:i + 5]) for i in range(7)]) ** 3
    dom = Domain({s: (-INF, INF) for s in syms})
    start = time.process_time()
    assert exact_zero(big, big * (1 + syms[11]), dom) is None
    assert exact_zero(syms[0]**50, syms[0]**50 + 1, dom) is None          # power bound
    assert time.process_time() - start < 0.5
