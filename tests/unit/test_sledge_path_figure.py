"""The sledge_path figure draws the reaction R at an instant where it is not zero.

For the sledge R = m C thetadot n (chapter 3), so R vanishes at the extremes of the
heading, theta = +-a: drawing an arrow R there would show a force that is not there
(review B, item 2)."""

import importlib.util
from pathlib import Path

import numpy as np

SCRIPT = Path(__file__).resolve().parents[2] / "book" / "figures" / "systems" / "sledge_path.py"


def _load():
    spec = importlib.util.spec_from_file_location("sledge_path_fig", SCRIPT)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def test_reaction_drawn_where_it_is_not_zero():
    fig = _load()
    theta, thetadot = fig.heading(fig.T_DRAWN)
    assert abs(thetadot) > 0.5 * fig.A_AMP            # turning: R is at least half its largest
    assert abs(theta) > 0.5 * fig.A_AMP               # and the heading still visibly non-zero
    assert np.isclose(fig.reaction(fig.T_DRAWN), thetadot / fig.A_AMP)
    assert fig.reaction(2 * np.pi) == 0 or abs(fig.reaction(2 * np.pi)) < 1e-12   # theta = a


def test_caption_describes_the_instant():
    text = (SCRIPT.parents[2] / "06-sledge.ipynb").read_text(encoding="utf-8")
    assert "vanishes where the heading is at its largest" in text
