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
