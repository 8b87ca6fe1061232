"""How a typed answer is read and shown back, and what a graded check may say
(issue 37, items 4 and 7; review C, items 8-10)."""
import re

import pytest
import sympy as sp

from whittaker_teach.exercises import check, load

L_STAR = "sqrt(2*h - k^2*theta^2)*sqrt(m*sec(theta)^2 + J*theta'^2)"


@pytest.mark.parametrize("text", [
    "sqrt(2h - k^2 theta^2)*sqrt(m sec(theta)^2 + J theta'^2)",     # 2h, k^2 theta^2, J theta'
    "√(2h − k²θ²)·√(m sec²θ + Jθ′²)",                               # the index page's example
    "sqrt(2h - k^2*theta^2) sqrt(m*sec(theta)^2 + J*theta'^2)",      # two factors apart
])
def test_implicit_products_are_read_and_shown(text):
    f = check("sledge-L-star", text, part="L_star")
    assert f.ok, f.message
    assert f.read == "sqrt(2*h - k**2*theta**2)*sqrt(J*thetaprime**2 + m*sec(theta)**2)"
    assert str(f).index("Read as") < str(f).index("Correct")


def test_the_issue_s_implicit_products():
    assert check("turning-point", "C cos(theta)", part="xdot").ok
    assert check("projectile-path", "x tan(alpha) - g_0 x^2/(2 v0^2 cos(alpha)^2)",
                 part="path").ok


@pytest.mark.parametrize("v0", ["v0", "v_0", "v₀"])
def test_every_subscripted_spelling_of_a_statement_symbol(v0):
    f = check("projectile-path", f"x*tan(alpha) - g_0*x^2/(2*{v0}^2*cos(alpha)^2)",
              part="path")
    assert f.ok, f.message


def test_a_name_that_splits_into_symbols_gets_did_you_mean():
    f = check("chaplygin-sleigh", "J + mb^2", part="J_eff")
    assert f.status == "invalid" and "did you mean m·b?" in f.message


@pytest.mark.parametrize("text", ["sin^-1(theta)", "sin^(-1)(theta)", "sin⁻¹(theta)",
                                  "sin**-1(theta)"])
def test_sin_to_the_minus_one_is_refused_as_ambiguous(text):
    f = check("turning-point", f"sqrt(J)*{text.replace('theta', 'pi/(2*a)')}/k",
              part="t_turn")
    assert f.status == "invalid" and "ambiguous" in f.message and "asin" in f.message


def test_two_numbers_apart_are_not_guessed():
    f = check("kepler-orbit", "2 3*m", part="h")
    assert f.status == "invalid" and "write products with *" in f.message


@pytest.mark.parametrize("text", ["RK45 rather than e.g. DOP853", "not DOP853",
                                  "DOP853 or RK45", "e.g. DOP853"])
def test_a_choice_is_read_as_a_whole(text):
    f = check("work-precision", text, part="method")
    assert not f.ok and f.status == "invalid" and "one option alone" in f.message


def test_a_dotted_name_still_selects_its_option():
    assert check("work-precision", "scipy.DOP853", part="method").ok


def test_numbers_are_relative_at_every_magnitude():
    x = float(load("turning-point").parts["x_turn"].expected)
    assert x < 1
    assert not check("turning-point", 0.5372873646, part="x_turn").ok   # where it stopped
    assert check("turning-point", x * (1 + 5e-7), part="x_turn").ok
    assert not check("turning-point", x * (1 + 5e-6), part="x_turn").ok


def test_graded_hints_give_no_quantity():
    x = float(load("turning-point").parts["x_turn"].expected)
    for value in (x * 1.0026, x * 400, x * 0.5):
        f = check("turning-point", value, part="x_turn", graded=True)
        assert not f.ok and re.fullmatch(r"Your number is too (large|small)\.", f.message)
        g = check("turning-point", value, part="x_turn")
        assert re.search(r"\d", g.message)                    # practice: by how much
    f = check("sledge-L-star", f"2*{L_STAR}", part="L_star", graded=True)
    assert f.message == "Your answer is off by a constant factor."
    f = check("sledge-L-star", f"k*{L_STAR}", part="L_star", graded=True)
    assert "k" not in f.message.replace("kind", "")
    assert "factor" in f.message


def test_a_lecturer_s_wrong_value_for_a_number_is_used():
    from whittaker_teach.exercises.specs import Part, check_part
    ex = load("work-precision")
    part = ex.parts["nfev"]
    mine = Part(name=part.name, what=part.what, expected=part.expected, rtol=part.rtol,
                wrong=[(sp.Integer(1157), "that counts the dense output's evaluations too")])
    f = check_part(ex, mine, "1157")
    assert not f.ok and f.message == "That counts the dense output's evaluations too."


def test_a_square_root_slip_is_named_before_complex_values():
    f = check("sledge-L-star", "sqrt(2*h - k^2*theta^2)*sqrt(m*sec(theta)^2 + J*theta')",
              part="L_star")
    assert "inside the square root" in f.message
    f = check("turning-point", "sqrt(J)*asin(pi/a)/k", part="t_turn")
    assert "argument of asin" in f.message


@pytest.mark.parametrize("wrap", [sp.UnevaluatedExpr, lambda e: sp.Max(e, 0),
                                  lambda e: sp.Piecewise((e, sp.Symbol("theta") < 10),
                                                         (0, True))])
def test_equivalent_objects_of_other_kinds_are_right(wrap):
    e = load("sledge-L-star").parts["L_star"].expected
    f = check("sledge-L-star", wrap(e), part="L_star")
    assert f.ok, f.message
