"""The paper's numbers print in round brackets, the book's own labels in square ones;
the captions say what the library computes (issue 23, items 3 and 9)."""

import re

import pytest

import whittaker_teach as wt
from whittaker_teach.labels import PAPER_NUMBERS, shown_label
from whittaker_teach.render import step_latex


@pytest.fixture(scope="module")
def red():
    return wt.examples.sledge().reduce("x", +1)


def test_the_46_paper_numbers():
    assert len(PAPER_NUMBERS) == 46 and PAPER_NUMBERS[0] == "1.1" and PAPER_NUMBERS[-1] == "3.15"


def test_own_labels_in_square_brackets(red):
    steps = list(red.system.steps) + list(red.steps)
    for s in steps:
        tex = step_latex(s) if s.equations else ""
        if s.label in PAPER_NUMBERS and not s.tag:
            assert s.shown_label == f"({s.label})"
            assert not tex or rf"\tag{{{s.label}}}" in tex
        else:
            assert s.shown_label.startswith("[") and s.shown_label.endswith("]"), s.label
            assert not tex or r"\tag*{[" in tex
            assert not re.search(r"\\tag\{", tex)
    own = {s.label for s in steps if s.shown_label.startswith("[")}
    assert {"1.4a", "1.26a", "1.26b", "from 1.12", "1.2"} <= own
    assert shown_label("3.10 OCR") == "[3.10 OCR]"


def test_Ltilde_is_not_tagged_as_equation_1_2(red):
    step = red.system.steps["1.2"]
    assert step.shown_label == r"[$\tilde L$]"
    assert r"\tag{1.2}" not in step_latex(step)
    assert "(1.2)" in step.check.describe()      # the check is about (1.2) itself


def test_caption_of_1_26a_names_dL_not_Ltilde(red):
    claim = red.steps["1.26a"].check.claim
    assert r"\partial L/\partial\dot q_{\varepsilon+\beta}" in claim
    assert r"\tilde L" not in claim
    text = red.steps["1.26a"].to_unicode()
    assert "∂L/∂q̇_(ε+β)" in text and "∂L̃" not in text


def test_1_26b_separates_solved_and_cleared_forms(red):
    step = red.steps["1.26b"]
    tex = step_latex(step)
    solved, _, cleared = tex.partition(r"\text{(1.26) cleared of denominators:}")
    assert "{{\\theta}'}' &=" in solved or "{{\\theta}'}' =" in solved
    assert cleared.rstrip().split(r"\end{aligned}")[0].endswith("= 0")


def test_one_phi_glyph(red):
    tex = "".join(step_latex(s) for s in red.system.steps if s.equations)
    assert r"\varphi" in tex and not re.search(r"\\phi(?![A-Za-z])", tex) and "φ" not in tex


def test_check_table_folded_unless_a_check_failed(red):
    html = red.verify()._repr_html_()
    assert html.startswith('<details class="wt-report">') and "<summary>" in html
    assert "q_eps" not in html


def test_failed_check_table_is_open():
    from whittaker_teach.steps import Report
    from whittaker_teach.verify import Check
    bad = Report([Check("1.9", "a claim", False, "exact", "expand")])
    assert bad._repr_html_().startswith('<details class="wt-report" open>')
