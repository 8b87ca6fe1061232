"""The offset (Chaplygin) sleigh of chapter 3 (``wt.examples.offset_sleigh()``).

Seen from above: the runner through the contact point P = (x, y), the heading
theta between the runner and the x direction, and the centre of mass G a
distance b ahead of P along the runner; the velocity v of P is along the runner
(the same constraint as the sledge's, ydot = xdot tan(theta)).

Run ``python book/figures/systems/offset_sleigh.py``: it writes
``offset_sleigh.svg`` beside this file (deterministic output).
"""

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
import _draw  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

_draw.style("offset_sleigh")

TH = np.radians(28.0)                     # the heading drawn
P = np.array([2.2, 1.5])                  # the contact point
E = np.array([np.cos(TH), np.sin(TH)])    # along the runner
N = np.array([-np.sin(TH), np.cos(TH)])   # sideways
B = 2.2                                   # the offset drawn

arrow = _draw.arrow


def main():
    fig, ax = plt.subplots(figsize=(7.4, 5.4))
    ax.set_aspect("equal")
    ax.axis("off")

    _draw.plane(ax, 6.6, 4.6)
    _draw.coordinates(ax, P)

    # the body, an outline around the runner, and the runner (blade) under P
    body = [P - 0.6 * E - 0.55 * N, P + (B + 0.9) * E - 0.55 * N,
            P + (B + 0.9) * E + 0.55 * N, P - 0.6 * E + 0.55 * N]
    ax.fill(*zip(*body), color="#e3ebf6", ec="#44546a", lw=1.4, zorder=1)
    ax.plot(*zip(P - 0.5 * E, P + 0.5 * E), color="#2c3e50", lw=9,
            solid_capstyle="round", zorder=3)

    # the heading theta
    ax.plot([P[0], P[0] + 2.3], [P[1], P[1]], "--", color="0.45", lw=1.4, zorder=2)
    ang = np.linspace(0, TH, 40)
    ax.plot(P[0] + 1.6 * np.cos(ang), P[1] + 1.6 * np.sin(ang), color="k", lw=1.4,
            zorder=4)
    ax.text(P[0] + 1.72 * np.cos(TH / 2), P[1] + 1.72 * np.sin(TH / 2) - 0.08,
            r"$\theta$", va="center")

    # the centre of mass G, b ahead of P along the runner
    G = P + B * E
    ax.plot(*zip(P, G), color="#44546a", lw=1.2, zorder=2)
    ax.plot(*G, "o", color="k", ms=12, zorder=6)
    ax.plot(*G, marker=(4, 0, 0), color="white", ms=5, zorder=7)
    ax.text(*(G + 0.35 * N + 0.1 * E), "$G$", ha="center", va="bottom", zorder=6)
    # the offset b, dimensioned beside the body
    off = 0.95 * N
    arrow(ax, P + off, G + off, color="#6c3483", lw=1.6, ms=18, style="<|-|>")
    for Q in (P, G):
        ax.plot(*zip(Q + 0.6 * N, Q + 1.05 * N), color="#6c3483", lw=1.0)
    ax.text(*(P + 0.5 * B * E + 1.2 * N), "$b$", color="#6c3483", ha="center",
            va="bottom", fontsize=24)

    # the velocity of the contact point: along the runner
    arrow(ax, P, P + 1.3 * E, color="#c0392b", lw=3.0, ms=26)
    ax.text(*(P + 1.0 * E + 0.25 * N), r"$\mathbf{v}$", color="#c0392b", fontsize=24,
            ha="center", va="bottom", zorder=6)
    ax.plot(*P, "o", color="white", mec="k", mew=2, ms=11, zorder=6)
    ax.text(*(P + 0.2 * E - 0.5 * N), "$P$", ha="left", va="center", zorder=6)

    ax.set_xlim(-0.6, 7.0)
    ax.set_ylim(-0.7, 5.0)
    return _draw.save(fig, __file__)


if __name__ == "__main__":
    print(main())
