"""The sledge of chapter 3 and of the paper's section 3 (``wt.examples.sledge()``).

Seen from above: the horizontal plane with the axes x, y; the runner (the blade)
through the contact point P = (x, y), which is also the projection of the centre;
the heading theta between the runner and the x direction; the torsional spring,
a spiral at P (potential k^2 theta^2 / 2, pulling the heading back to theta = 0); the allowed velocity v,
along the runner (no sideways slip: ydot = xdot tan(theta), (3.2)); and the
reaction R of the plane on the runner, normal to it.

Run ``python book/figures/systems/sledge.py``: it writes ``sledge.svg`` beside this
file (deterministic output).
"""

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
import _draw  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

_draw.style("sledge")

TH = np.radians(32.0)                     # the heading drawn
P = np.array([3.0, 2.0])                  # the contact point
E = np.array([np.cos(TH), np.sin(TH)])    # along the runner
N = np.array([-np.sin(TH), np.cos(TH)])   # sideways

arrow = _draw.arrow


def main():
    fig, ax = plt.subplots(figsize=(7.4, 5.6))
    ax.set_aspect("equal")
    ax.axis("off")

    _draw.plane(ax, 6.4, 4.6)               # axes of the plane
    _draw.coordinates(ax, P)                # coordinates of the contact point

    # the runner (blade)
    half = 1.55
    A, B = P - half * E, P + half * E
    ax.plot(*zip(A, B), color="#2c3e50", lw=9, solid_capstyle="round", zorder=3)
    ax.text(*(A + 0.1 * E - 0.42 * N), "runner", fontsize=17, rotation=np.degrees(TH),
            ha="center", va="center", color="#2c3e50")

    # the heading theta, from the x direction
    ax.plot([P[0], P[0] + 2.3], [P[1], P[1]], "--", color="0.45", lw=1.4, zorder=1)
    ang = np.linspace(0, TH, 40)
    rr = 1.95
    ax.plot(P[0] + rr * np.cos(ang), P[1] + rr * np.sin(ang), color="k", lw=1.4)
    ax.text(P[0] + 2.12 * np.cos(TH / 2), P[1] + 2.12 * np.sin(TH / 2), r"$\theta$",
            va="center")

    # the torsional spring: a spiral about P
    s = np.linspace(0, 1, 300)
    phi = 2 * np.pi * 2.2 * s
    rad = 0.18 + 0.32 * s
    sx, sy = P[0] + rad * np.cos(phi + np.pi), P[1] + rad * np.sin(phi + np.pi)
    ax.plot(sx, sy, color="#b9770e", lw=1.8, zorder=4)
    ax.text(P[0] - 0.7, P[1] - 0.08, "$k^2$", color="#b9770e", ha="right",
            va="top", fontsize=20)

    # the allowed velocity: along the runner
    arrow(ax, P + 0.05 * E, P + 2.6 * E, color="#c0392b", lw=3.0, ms=26)
    ax.text(*(P + 2.7 * E + 0.05 * N), r"$\mathbf{v}$", color="#c0392b",
            fontsize=24, va="bottom")
    # the reaction: normal to the runner
    arrow(ax, P, P + 1.75 * N, color="#1f6f3f", lw=3.0, ms=26)
    ax.text(*(P + 1.85 * N), r"$\mathbf{R}$", color="#1f6f3f", fontsize=24,
            ha="right", va="bottom")

    ax.plot(*P, "o", color="white", mec="k", mew=2, ms=11, zorder=6)
    ax.text(*(P + 0.25 * E - 0.55 * N), "$P$", ha="left", va="center", zorder=6)

    ax.set_xlim(-0.6, 6.9)
    ax.set_ylim(-0.7, 5.1)
    return _draw.save(fig, __file__)


if __name__ == "__main__":
    print(main())
