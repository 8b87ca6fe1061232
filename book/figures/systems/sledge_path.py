"""The sledge on its path: the sketch of chapter 6 (``wt.examples.sledge()``).

The path is the exact motion of section 3 of the paper, (3.12)-(3.15):
theta = a cos(omega t), xdot = C cos(theta), ydot = C sin(theta), here with
a = 0.9, C = omega = 1, summed by the trapezoidal rule (only for drawing).
On it, the sledge at one instant, with the labels and colours of the chapter 3
figure of the sledge (sledge.py): the runner, the contact point P = (x, y), the
heading theta measured from the x direction, the torsional spring k^2 (force
function U = -k^2 theta^2 / 2, pulling theta back to 0), the velocity v along
the runner (the constraint direction, ydot = xdot tan theta, (3.2)) and the
reaction R of the plane, across the runner.

The reaction is R = m C thetadot n, n = (-sin theta, cos theta) (chapter 3: the
multiplier is lambda = -m C thetadot cos theta): it vanishes where theta = +-a
(thetadot = 0) and is largest, m C a omega, where theta = 0. So the instant drawn,
T_DRAWN = 7 pi / 4, is one where the heading is still large (theta = a cos 7pi/4)
and still growing towards a (theta > 0, thetadot > 0), and R is drawn to scale against its largest
value (R_FULL at theta = 0).

Run ``python book/figures/systems/sledge_path.py``: it writes
``sledge_path.svg`` beside this file (deterministic output).
"""

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
import _draw  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

_draw.style("sledge_path")

A_AMP, SPEED = 0.9, 1.0                    # amplitude a (rad) and speed C
T_DRAWN = 1.75 * np.pi                     # the instant drawn (omega = 1)
R_FULL = 1.5                               # the arrow of the largest reaction, m C a omega


def heading(t):
    """theta and thetadot of (3.15) with omega = 1 and phase 0."""
    return A_AMP * np.cos(t), -A_AMP * np.sin(t)


def reaction(t):
    """The sideways reaction R . n = m C thetadot, in units of its largest value m C a omega."""
    return heading(t)[1] / A_AMP


def path(t_end=2.45 * np.pi, n=4001):
    """(x, y, theta) of the exact motion (3.12)-(3.15), from the origin."""
    t = np.linspace(0.0, t_end, n)
    th = A_AMP * np.cos(t)
    dx, dy = SPEED * np.cos(th), SPEED * np.sin(th)
    step = np.diff(t)
    x = np.concatenate([[0.0], np.cumsum(0.5 * (dx[1:] + dx[:-1]) * step)])
    y = np.concatenate([[0.0], np.cumsum(0.5 * (dy[1:] + dy[:-1]) * step)])
    return x, y, th


def arrow(ax, P, Q, color, lw=3.0):
    _draw.arrow(ax, P, Q, color=color, lw=lw, ms=26, zorder=None)


# the colours of the chapter 3 figure (sledge.py)
RUNNER, SPRING, VELOCITY, REACTION = "#2c3e50", "#b9770e", "#c0392b", "#1f6f3f"


def draw():
    x, y, th = path()
    fig, ax = plt.subplots(figsize=(10.0, 6.4))
    ax.plot(x, y, color="0.55", lw=2.0, ls=(0, (6, 4)))
    ax.text(x[1200], y[1200] - 0.45, "path", color="0.4", ha="center", va="top")

    # the sledge at one instant, T_DRAWN: theta = a cos T_DRAWN, turning (R is not zero)
    i = np.searchsorted(np.linspace(0.0, 2.45 * np.pi, len(x)), T_DRAWN)
    P, h = np.array([x[i], y[i]]), th[i]
    u, nrm = np.array([np.cos(h), np.sin(h)]), np.array([-np.sin(h), np.cos(h)])
    half = 1.0
    ax.plot(*zip(P - half * u, P + half * u), color=RUNNER, lw=9,
            solid_capstyle="round", zorder=3)
    ax.text(*(P - 0.75 * half * u - 0.5 * nrm), "runner", color=RUNNER, fontsize=19,
            rotation=np.degrees(h), ha="center", va="center")

    # the x direction and the heading theta
    ax.plot([P[0], P[0] + 2.1], [P[1], P[1]], color="0.45", lw=1.4, ls="--", zorder=2)
    arc = np.linspace(0.0, h, 40)
    ax.plot(P[0] + 1.6 * np.cos(arc), P[1] + 1.6 * np.sin(arc), color="k", lw=1.5)
    ax.text(P[0] + 1.78, P[1] + 0.45, r"$\theta$", fontsize=26)

    # the torsional spring at the contact point: a spiral, labelled k^2 as in chapter 3
    s = np.linspace(0.0, 3.2 * np.pi, 300)
    r = 0.06 + 0.035 * s
    ax.plot(P[0] + r * np.cos(s + h), P[1] + r * np.sin(s + h), color=SPRING, lw=2.0,
            zorder=4)
    ax.text(P[0] - 0.5, P[1] + 0.05, r"$k^2$", color=SPRING, ha="right", va="center")

    # the contact point P = (x, y)
    ax.plot(*P, "o", ms=11, mfc="white", mec="k", mew=2, zorder=6)
    ax.text(*(P + 0.3 * u - 0.6 * nrm), r"$P$", ha="left", va="center", zorder=6)

    # v along the runner (the constraint direction) and the reaction R across it
    arrow(ax, P + half * u, P + (half + 1.1) * u, VELOCITY)
    ax.text(*(P + (half + 1.25) * u), r"$\mathbf{v}$", color=VELOCITY, fontsize=26,
            ha="left", va="bottom")
    R = R_FULL * reaction(T_DRAWN)          # signed, along n
    arrow(ax, P, P + R * nrm, REACTION)
    ax.text(*(P + (R + 0.1 * np.sign(R)) * nrm), r"$\mathbf{R}$", color=REACTION, fontsize=26,
            ha="center", va="bottom" if R > 0 else "top")

    # the axes
    x0, y0 = -0.4, y.min() - 1.6
    arrow(ax, (x0, y0), (x[-1] + 0.3, y0), "k", lw=1.5)
    arrow(ax, (x0, y0), (x0, y.max() + 1.2), "k", lw=1.5)
    ax.text(x[-1] + 0.4, y0, r"$x$", va="center")
    ax.text(x0, y.max() + 1.3, r"$y$", ha="center", va="bottom")
    ax.text(x0 - 0.15, y0 - 0.1, r"$O$", ha="right", va="top")

    ax.set_aspect("equal")
    ax.axis("off")
    return fig


def main():
    return _draw.save(draw(), __file__)


if __name__ == "__main__":
    print(main())
