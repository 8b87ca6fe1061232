"""The line-breaking renderers (LaTeX and Unicode), the captions and the wrapped text outputs."""

import re

import pytest
import sympy as sp

import whittaker_teach as wt
from whittaker_teach.render import (PAGE_WIDTH, display_width, equation_latex, tag_width,
                                    equation_unicode, math_latex, step_unicode, tex_width,
                                    text_markdown, text_unicode)
from whittaker_teach.reading import TotalD
from whittaker_teach.steps import Report, Step
from whittaker_teach.verify import check_zero

a, b, c, x, y = sp.symbols("a b c x y")
LONG = sp.Eq(y, sum(sp.sqrt(a + k * b) / (c + k) for k in range(1, 8))
             + (a + b) * (x**2 + 3 * x * a + b / c + sp.sqrt(a * b) + a**3 * b**2 + c**4
                          + x * y * c))
ZERO = sp.Eq(sum((a + k) ** k * x ** k for k in range(1, 9)) - sp.tan(x) / (1 + a), 0)
DERIV = sp.Eq(TotalD(sum(sp.cos(k * x) * a ** k for k in range(1, 9)), x)
              - b * sp.sin(x), 0)


def _unbroken(tex):
    """The broken LaTeX as one line: alignment, row ends and \\left. \\right. removed."""
    return re.sub(r"\\begin\{aligned\}|\\end\{aligned\}|&|\\quad|\{\}|\\cr|\\left\.|\\right\.",
                  " ", tex)


def _rows(tex):
    return tex.split(r"\cr")


@pytest.mark.parametrize("e", [LONG, ZERO], ids=["rhs", "zero"])
@pytest.mark.parametrize("width", [6, 10, 16])
def test_latex_rows_fit_and_parse_back(e, width):
    from sympy.parsing.latex import parse_latex
    tex = equation_latex(e, width=width, mul_symbol="dot")
    assert tex.startswith(r"\begin{aligned}")
    rows = _rows(tex)
    assert len(rows) > 1
    for r in rows:
        # every row is balanced (MathJax refuses a \left without its \right in a cell) ...
        assert r.count(r"\left") == r.count(r"\right"), r
        # ... and fits when every single term does (at width 6 some terms are wider)
        if width >= 10:
            assert tex_width(r) <= width, r
    back = parse_latex(_unbroken(tex), backend="lark")      # round trip
    assert sp.expand(back.lhs - e.lhs) == 0
    assert sp.expand(back.rhs - e.rhs) == 0


def test_latex_short_equation_unchanged():
    e = sp.Eq(y, a + b)
    assert equation_latex(e) == sp.latex(e)


def test_latex_total_derivative_breaks_inside():
    tex = equation_latex(DERIV, width=12)
    assert r"\frac{d}{d x}\left(" in tex and tex.count(r"\cr") >= 2
    assert all(r.count(r"\left") == r.count(r"\right") for r in _rows(tex))


def test_one_tag_for_the_whole_block():
    tex = math_latex([LONG, ZERO], "1.26", width=10)
    assert tex.count(r"\tag{1.26}") == 1 and tex.endswith(r"\tag{1.26}")
    assert tex.count(r"\begin{aligned}") == 1          # one block, no nested aligned
    assert r"\\" not in tex                             # rows end with \cr (see render.py)
    assert math_latex([ZERO], "from 1.12").endswith(r"\tag*{[from 1.12]}")   # the book's own


@pytest.mark.parametrize("e", [LONG, ZERO, DERIV], ids=["rhs", "zero", "derivative"])
@pytest.mark.parametrize("width", [30, 50, 100])
def test_unicode_lines_fit(e, width):
    text = equation_unicode(e, width)
    assert max(len(line) for line in text.splitlines()) <= width
    assert "↩" not in text or width < 40             # cut into blocks only when too narrow


def test_unicode_break_keeps_every_term():
    text = equation_unicode(LONG, 40)
    for k in range(1, 8):
        assert f"c + {k}" in text
    assert text.count("(") >= 1 and text.count(")") >= 1


def test_tex_width_is_monotone_and_counts_fractions():
    assert tex_width("a + b + c") > tex_width("a + b")
    assert tex_width(r"\frac{a + b + c}{d}") == pytest.approx(tex_width("a + b + c") + 0.3)
    assert tex_width(r"x^{2}") < tex_width("x2")
    assert display_width(r"\begin{aligned}y &= a \cr &\quad {} + b\end{aligned}") == \
        pytest.approx(tex_width("y") + max(tex_width("= a"), tex_width(r"\quad {} + b")))


def test_captions_typeset_and_unicode():
    cap = r"$\partial\Omega/\partial\dot q_\varepsilon$, $q_\sigma$, $\tilde L$, $\dot q^*$"
    assert text_unicode(cap) == "∂Ω/∂q̇_ε, q_σ, L̃, q̇*"
    md = text_markdown("the form of $L^*$ in x_1 * y")
    assert "$L^*$" in md and r"x\_1 \* y" in md          # maths kept, emphasis escaped


def test_step_unicode_wraps_title_and_check():
    chk = check_zero("9.9", "a claim " * 30, sp.S.Zero, lambda rng: {})
    s = Step("3.9", "a long title " * 20, [LONG], chk, note="a note " * 30)
    text = step_unicode(s, 60)
    assert max(len(line) for line in text.splitlines()) <= 60
    assert text.startswith("(3.9) a long title")


def test_report_wraps_and_renders_html(sledge_red):
    report = Report(s.check for s in sledge_red.steps.only("1.16", "1.26") if s.check)
    text = report.to_text(50)
    assert max(len(line) for line in text.splitlines()) <= 50
    assert text.splitlines()[-1].strip().endswith("0 did not") or "0 did not" in text
    html = report._repr_html_()
    assert html.startswith('<details class="wt-report">') and html.count("<tr>") == len(report) + 1
    assert r'<span class="math notranslate nohighlight">\(' in html    # claims typeset


def test_derivation_latex_has_no_empty_display(sledge_red):
    tex = sledge_red.steps.to_latex()
    assert r"\begin{equation} \tag" not in tex and r"\begin{equation}\tag" not in tex
    for lab in ("2.2", "2.3"):
        assert rf"\tag{{{lab}}}" in tex                     # shown with what they claim


@pytest.mark.parametrize("name", ["sledge", "offset_sleigh", "rolling_disk", "kepler",
                                  "projectile", "cone_particle", "charged_particle"])
def test_every_step_fits_the_column(name):
    """Every display of every example, with its tag on both sides (MathJax centres the
    body between two tag-wide margins), fits the book's column, PAGE_WIDTH em (688 px);
    5 % are allowed for a single term that cannot be broken."""
    ex = wt.examples.get(name)
    red = ex.build().reduce(ex.coordinate, +1)
    steps = list(red.steps)
    if name == "sledge":
        steps += list(wt.examples.section3(reduction=red))
    widths = {s.label: display_width(s.to_latex()) + 2 * tag_width(s.label)
              for s in steps if s.equations}
    assert max(widths.values()) <= 1.05 * PAGE_WIDTH, widths


def test_labels_one_per_object(sledge_red):
    labels = sledge_red.steps.labels
    assert len(labels) == len(set(labels))
    assert {"1.4a", "1.26a", "1.26b", "from 1.12"} <= set(labels)
    assert sledge_red.steps["from 1.12"].check.label == "from 1.12"
    assert sledge_red.steps.only("1.26").labels == ["1.26", "1.26a", "1.26b"]
    # (1.10) shows Euler's relation and its pieces, not "phi = phi"
    eqs = sledge_red.steps["1.10"].equations
    assert len(eqs) >= 3 and all(e.lhs != e.rhs for e in eqs)


def test_paper_order_is_said_where_not_kept(sledge_red):
    labels = sledge_red.steps.labels
    assert labels.index("1.13") < labels.index("1.12")
    assert "(1.12)" in sledge_red.steps["1.13"].note
