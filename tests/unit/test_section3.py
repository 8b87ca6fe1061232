"""Section 3: the sledge, (3.1)-(3.15), with the OCR errata shown by computation."""

import pytest

from whittaker_teach.examples import section3

LABELS = [f"3.{i}" for i in range(1, 16)]


@pytest.fixture(scope="module")
def sec3(sledge_red):
    return section3(reduction=sledge_red)


def test_every_equation_present(sec3):
    for lab in LABELS:
        assert lab in sec3.labels, lab


def test_every_check_holds(sec3):
    for step in sec3:
        if step.check is not None:
            assert step.check.holds, step.check.describe()


def test_3_10_coefficient_erratum(sec3):
    steps = sec3.only("3.10").steps           # (3.10) and its erratum, one label each
    assert [s.label for s in steps] == ["3.10", "3.10 OCR"]
    assert steps[0].check.method in ("exact", "numeric") and steps[0].check.holds
    ocr = steps[1]
    assert ocr.check.method == "refutation"
    assert ocr.check.max_residual > 1e-3        # the OCR form is really wrong


def test_direction_minus_one():
    d = section3(direction=-1)
    assert all(s.check.holds for s in d if s.check)


def test_3_5_to_3_7_check_the_corrected_form(sec3):
    """Erratum 3: the OCR prints J thetadot^2 in (3.5), (3.6) and (3.7); the checks compare
    the corrected form with J theta'^2 and must say so, not call it "the printed" one."""
    for lab in ("3.5", "3.6", "3.7"):
        (step,) = sec3.only(lab).steps
        assert "corrected form" in step.check.claim and "printed" not in step.check.claim
        assert "erratum 3" in step.check.claim
        assert step.check.holds


def test_3_9_is_labelled_expanded(sec3):
    """The paper's (3.9) is the general form; its expanded line is unnumbered."""
    (step,) = sec3.only("3.9").steps
    assert step.title.startswith("the paper's (3.9), expanded and simplified")
