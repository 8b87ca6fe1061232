"""The rattleback (``whittaker_teach.rolling.rattleback()``), not to scale.

Two 2-D projections.  Left, the vertical section along the long axis x at rest: the
paraboloidal bottom z = x^2/(2 rho_1) touching the table at P, its osculating circle
of radius rho_1 (dashed), the centre of mass G a height h above P.  Right, from above:
the body's rim, the axes of curvature x, y of the bottom (dashed), the principal axes
of inertia xi, eta turned from them by the angle delta, and the spin Omega about the
vertical.

Run ``python book/figures/systems/rattleback.py``: it writes ``rattleback.svg``
beside this file (deterministic output).
"""

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
import _draw  # noqa: E402
import numpy as np  # noqa: E402

_draw.style("rattleback")
arrow = _draw.arrow
DELTA = np.radians(14.0)          # exaggerated for the drawing


def side(ax):
    ax.plot([-2.6, 2.6], [0, 0], color="0.3", lw=2)
    for xh in np.linspace(-2.5, 2.4, 16):
        ax.plot([xh, xh - 0.18], [0, -0.18], color="0.55", lw=1)
    rho = 3.2
    x = np.linspace(-2.2, 2.2, 200)
    z = x**2 / (2 * rho)
    ax.fill_between(x, z, 1.0, color="#44546a", alpha=0.18)
    ax.plot(x, z, color="#44546a", lw=2.4)
    ax.plot([-2.2, 2.2], [1.0, 1.0], color="#44546a", lw=2.4)
    s = np.linspace(np.pi * 1.25, np.pi * 1.75, 100)
    ax.plot(rho * np.cos(s), rho + rho * np.sin(s), "--", color="0.45", lw=1.2)
    ax.plot(0, 0.45, "o", color="k", ms=9, zorder=6)
    ax.text(0.15, 0.5, "$G$")
    arrow(ax, (-0.35, 0.0), (-0.35, 0.45), color="#6c3483", lw=1.4, style="<|-|>", ms=14)
    ax.text(-0.75, 0.1, "$h$", color="#6c3483")
    ax.plot(0, 0, "o", color="white", mec="k", mew=2, ms=10, zorder=6)
    ax.text(0.12, -0.5, "$P$")
    ax.text(1.55, -0.55, r"radius $\rho_1$", color="0.35", fontsize=16)
    arrow(ax, (1.9, 1.3), (2.5, 1.3), color="k", lw=1.4, ms=14)
    ax.text(2.55, 1.22, "$x$", fontsize=17)
    ax.set_title("section along x", fontsize=18)
    ax.set_xlim(-2.7, 2.9)
    ax.set_ylim(-0.8, 1.8)


def top(ax):
    s = np.linspace(0, 2 * np.pi, 200)
    ax.fill(2.2 * np.cos(s), 0.7 * np.sin(s), color="#44546a", alpha=0.18)
    ax.plot(2.2 * np.cos(s), 0.7 * np.sin(s), color="#44546a", lw=2)
    ax.plot([-2.6, 2.6], [0, 0], "--", color="0.45", lw=1.3)
    ax.plot([0, 0], [-1.3, 1.3], "--", color="0.45", lw=1.3)
    ax.text(2.65, -0.1, "$x$", fontsize=17)
    ax.text(0.1, 1.3, "$y$", fontsize=17)
    e1 = np.array([np.cos(DELTA), np.sin(DELTA)])
    e2 = np.array([-np.sin(DELTA), np.cos(DELTA)])
    arrow(ax, (0, 0), 2.5 * e1, color="#6c3483", lw=2)
    ax.text(*(2.55 * e1 + np.array([0.0, 0.05])), r"$\xi\,(A)$", color="#6c3483",
            fontsize=17)
    arrow(ax, (0, 0), 1.2 * e2, color="#6c3483", lw=2)
    ax.text(*(1.25 * e2 + np.array([-1.05, -0.1])), r"$\eta\,(B)$", color="#6c3483",
            fontsize=17)
    a = np.linspace(0, DELTA, 20)
    ax.plot(1.6 * np.cos(a), 1.6 * np.sin(a), color="k", lw=1.4)
    ax.text(1.7, 0.12, r"$\delta$")
    a = np.linspace(np.radians(200), np.radians(330), 50)
    ax.plot(0.45 * np.cos(a) - 1.2, 0.45 * np.sin(a) + 0.05, color="#c0392b", lw=2)
    arrow(ax, (0.45 * np.cos(a[-2]) - 1.2, 0.45 * np.sin(a[-2]) + 0.05),
          (0.45 * np.cos(a[-1]) - 1.2, 0.45 * np.sin(a[-1]) + 0.05), color="#c0392b", lw=2)
    ax.text(-1.45, -0.75, r"$\Omega$", color="#c0392b")
    ax.set_title("from above", fontsize=18)
    ax.set_xlim(-2.5, 3.2)
    ax.set_ylim(-1.4, 1.6)


def main():
    return _draw.panels(__file__, (side, top), figsize=(10.4, 3.6),
                        ratios=(1, 1))


if __name__ == "__main__":
    print(main())
