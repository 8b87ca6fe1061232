"""The projectile of chapter 2 (``wt.examples.projectile()``).

A particle of mass m in a vertical plane: x horizontal, y up, the weight
m g_0 downwards, thrown from height c_0 with horizontal velocity u and slope
c_1; its path is the parabola y(x).

Run ``python book/figures/systems/projectile.py``: it writes
``projectile.svg`` beside this file (deterministic output).
"""

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
import _draw  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

_draw.style("projectile")

C0, C1, K = 0.8, 1.0, 0.32                 # the parabola y = c0 + c1 x - K x^2

arrow = _draw.arrow


def main():
    fig, ax = plt.subplots(figsize=(7.4, 4.8))
    ax.set_aspect("equal")
    ax.axis("off")

    x_end = (C1 + np.sqrt(C1**2 + 4 * K * C0)) / (2 * K)
    arrow(ax, (0, 0), (x_end + 0.6, 0))
    arrow(ax, (0, 0), (0, 2.9))
    ax.text(x_end + 0.7, 0, "$x$", va="center")
    ax.text(0, 3.0, "$y$", ha="center", va="bottom")
    ax.text(-0.1, -0.1, "$O$", ha="right", va="top")

    xs = np.linspace(0, x_end, 300)
    ax.plot(xs, C0 + C1 * xs - K * xs**2, color="#2c3e50", lw=2.2)
    ax.text(-0.12, C0, "$c_0$", ha="right", va="center", color="#44546a")
    # the initial slope c_1 and the horizontal velocity u
    arrow(ax, (0, C0), (0.9, C0 + 0.9 * C1), color="#44546a", lw=1.6, ms=18)
    ax.text(0.85, C0 + 0.9 * C1 + 0.12, "slope $c_1$", fontsize=18, ha="center",
            va="bottom", color="#44546a")

    # the particle at (x, y)
    xp = 2.6
    yp = C0 + C1 * xp - K * xp**2
    ax.plot([xp, xp], [0, yp], ":", color="#44546a", lw=1.4)
    ax.plot([0, xp], [yp, yp], ":", color="#44546a", lw=1.4)
    ax.text(xp, -0.12, "$x$", ha="center", va="top", color="#44546a")
    ax.text(-0.12, yp, "$y$", ha="right", va="center", color="#44546a")
    ax.plot(xp, yp, "o", color="k", ms=13, zorder=6)
    ax.text(xp + 0.15, yp + 0.12, "$m$", va="bottom")
    arrow(ax, (xp, yp), (xp + 0.9, yp), color="#c0392b", lw=2.6, ms=22)
    ax.text(xp + 1.0, yp, "$u$", color="#c0392b", va="center")
    arrow(ax, (xp, yp), (xp, yp - 1.0), color="#1f6f3f", lw=2.6, ms=22)
    ax.text(xp + 0.12, yp - 0.85, "$m g_0$", color="#1f6f3f", va="center")

    return _draw.save(fig, __file__)


if __name__ == "__main__":
    print(main())
