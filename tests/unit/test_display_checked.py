"""What a step shows is what its check verified, for every example and both directions.

A step whose displayed equation states the claim it checks ((1.7)-(1.9), (1.12),
(1.16), (1.19), (1.20), the printed forms (3.3)-(3.8), (3.10), (3.12)-(3.14))
must display the very expression that was compared: identical, or a tidied
form of it (``collected``) equal to it at 40 digits at the check's own sample
points.  Before the fix, ``section3(direction=-1)`` showed xdot = C cos theta
while checking xdot = -C cos theta; this test fails on that.
"""

import random

import mpmath
import pytest

from whittaker_teach.examples import catalogue, section3
from whittaker_teach.steps import Notation
from whittaker_teach.verify import DPS, evaluate

CLAIMS = {"1.7", "1.8", "1.9", "1.12", "1.16", "1.19", "1.20",
          "3.3", "3.4", "3.5", "3.6", "3.7", "3.8", "3.10", "3.12", "3.13", "3.14"}


def _values(sample, rng):
    return {k: mpmath.mpf(v) if isinstance(v, (int, float)) else v
            for k, v in sample(rng).items()}


def _among(shown, compared, sample):
    """``shown`` is one of ``compared``: identical, or equal at three sample points."""
    if any(shown == c for c in compared):
        return True
    rng, left = random.Random(1), list(compared)
    with mpmath.workdps(DPS):
        for _ in range(3):
            pt = _values(sample, rng)
            a = evaluate(shown, dict(pt))
            left = [c for c in left
                    if abs(evaluate(c, dict(pt)) - a) <= 1e-25 * max(1, abs(a))]
    return bool(left)


def _shown_sides(step):
    for q in step.equations:
        for side in (q.rhs, q.lhs):
            if not (side.atoms(Notation) or side.is_Symbol or side == 0):
                yield side
                break


@pytest.mark.parametrize("direction", [1, -1])
@pytest.mark.parametrize("example", catalogue(), ids=lambda e: e.name)
def test_displayed_equation_is_the_checked_one(example, direction):
    red = example.build().reduce(example.coordinate, direction)
    steps = list(red.steps)
    if example.name == "sledge":
        steps += list(section3(direction, reduction=red))
    seen = set()
    for step in steps:
        if step.label not in CLAIMS or step.check is None or step.check.method == "refutation":
            continue
        chk = step.check
        assert chk.lhs and chk.sample is not None, step.label
        for side in _shown_sides(step):
            assert _among(side, chk.lhs + chk.rhs, chk.sample), (
                f"({step.label}) shows {side}, which is not what its check compared")
            seen.add(step.label)
    assert {"1.7", "1.12", "1.16"} <= seen
    if example.name == "sledge":
        assert {"3.5", "3.7", "3.12", "3.13", "3.14"} <= seen


def test_section3_direction_minus_one_shows_minus():
    d = section3(direction=-1)
    for label, sign in (("3.12", -1), ("3.13", -1)):
        rhs = d[label].equations[0].rhs
        assert rhs.could_extract_minus_sign(), (label, rhs)
    d = section3(direction=+1)
    assert not d["3.12"].equations[0].rhs.could_extract_minus_sign()
