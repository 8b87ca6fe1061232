"""The Chaplygin ball (``whittaker_teach.rolling.chaplygin_ball()``).

Two 2-D projections.  Left, a vertical section through the contact point: the ball of
radius R on the plane, its centre G (the centre of mass), the contact point P, the
upward vertical gamma, two of its principal axes e1, e2 (moments A, B; the third, C,
points out of the page), the angular velocity omega and the angular momentum about the
contact point K_P.  Right, from above: the contact point P = (x, y) on the plane and
the velocity of the centre, v_G = omega x R gamma, with its two components.

Run ``python book/figures/systems/chaplygin_ball.py``: it writes ``chaplygin_ball.svg``
beside this file (deterministic output).
"""

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
import _draw  # noqa: E402
import numpy as np  # noqa: E402

_draw.style("chaplygin_ball")
arrow = _draw.arrow
TURN = np.radians(25.0)


def section(ax):
    ax.plot([-2.4, 2.4], [0, 0], color="0.3", lw=2)
    for xh in np.linspace(-2.3, 2.2, 15):
        ax.plot([xh, xh - 0.18], [0, -0.18], color="0.55", lw=1)
    G = np.array([0.0, 1.6])
    s = np.linspace(0, 2 * np.pi, 200)
    ax.fill(G[0] + 1.6 * np.cos(s), G[1] + 1.6 * np.sin(s), color="#44546a", alpha=0.18)
    ax.plot(G[0] + 1.6 * np.cos(s), G[1] + 1.6 * np.sin(s), color="#44546a", lw=2)
    e1 = np.array([np.cos(TURN), np.sin(TURN)])
    e2 = np.array([-np.sin(TURN), np.cos(TURN)])
    arrow(ax, G, G + 1.25 * e1, color="#6c3483", lw=1.8)
    ax.text(*(G + 1.35 * e1 + np.array([0.0, 0.05])), "$e_1\\,(A)$", color="#6c3483",
            fontsize=17)
    arrow(ax, G, G + 1.25 * e2, color="#6c3483", lw=1.8)
    ax.text(*(G + 1.3 * e2 + np.array([-0.75, 0.0])), "$e_2\\,(B)$", color="#6c3483",
            fontsize=17)
    ax.plot([0, 0], [0, 1.6], color="k", lw=1.2)
    ax.text(0.12, 0.55, "$R$")
    arrow(ax, (-1.95, 0.4), (-1.95, 1.5), color="k", lw=2)
    ax.text(-2.3, 1.05, r"$\gamma$")
    arrow(ax, G, G + np.array([1.0, -0.6]), color="#c0392b", lw=2.4)
    ax.text(*(G + np.array([1.05, -0.45])), r"$\omega$", color="#c0392b")
    arrow(ax, (0, 0), (1.25, 0.95), color="#1f7a3a", lw=2.4)
    ax.text(1.35, 0.55, "$K_P$", color="#1f7a3a")
    ax.plot(*G, "o", color="k", ms=9, zorder=6)
    ax.text(-0.38, 1.55, "$G$")
    ax.plot(0, 0, "o", color="white", mec="k", mew=2, ms=10, zorder=6)
    ax.text(-0.35, -0.5, "$P$")
    ax.set_title("section through P", fontsize=18)
    ax.set_xlim(-2.5, 2.6)
    ax.set_ylim(-0.7, 3.5)


def top(ax):
    _draw.plane(ax, 4.2, 3.4)
    P = np.array([1.8, 1.4])
    _draw.coordinates(ax, P)
    s = np.linspace(0, 2 * np.pi, 200)
    ax.plot(P[0] + 1.0 * np.cos(s), P[1] + 1.0 * np.sin(s), "--", color="#44546a", lw=1.2)
    v = np.array([1.3, 0.8])
    arrow(ax, P, P + v, color="#c0392b", lw=2.4)
    ax.text(*(P + v + np.array([0.05, 0.1])), r"$v_G$", color="#c0392b")
    arrow(ax, P, P + np.array([v[0], 0]), color="#c0392b", lw=1.2, ls="--", ms=14)
    arrow(ax, P, P + np.array([0, v[1]]), color="#c0392b", lw=1.2, ls="--", ms=14)
    ax.text(P[0] + 0.55, P[1] - 0.4, r"$R\omega_y$", color="#c0392b", fontsize=16)
    ax.text(P[0] - 1.25, P[1] + 0.75, r"$-R\omega_x$", color="#c0392b", fontsize=16)
    ax.plot(*P, "o", color="white", mec="k", mew=2, ms=10, zorder=6)
    ax.text(*(P + np.array([0.1, -0.45])), "$P$")
    ax.set_title("from above", fontsize=18)
    ax.set_xlim(-0.5, 4.7)
    ax.set_ylim(-0.6, 3.8)


def main():
    return _draw.panels(__file__, (section, top), figsize=(9.6, 4.6),
                        ratios=(1, 1.05))


if __name__ == "__main__":
    print(main())
