"""Appell and Hamel's weight (``whittaker_teach.forms.examples.appell_hamel()``) and the
mechanism of chapter 10 whose limit gives its non-linear constraint.

Left, seen from the side along the wheel's plane: a wheel of radius a rolls without
slipping on the horizontal plane (rolling angle phi); a drum of radius b is fixed
to its axle; a rope wound on the drum runs over a pulley on the carriage that carries
the axle and holds the weight m at height z, in gravity g_0.  Rolling forward by
a dphi winds b dphi of rope: the weight rises by b dphi while it moves horizontally
by a dphi, so zdot = (b/a) sqrt(xdot^2 + ydot^2), c = b/a.  Right, seen from above:
the weight's horizontal position (x, y) and the wheel's heading psi along its
horizontal velocity.

Run ``python book/figures/systems/appell_hamel.py``: it writes ``appell_hamel.svg``
beside this file (deterministic output).
"""

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
import _draw  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

_draw.style("appell_hamel")
arrow = _draw.arrow
PSI = np.radians(30.0)
PHI = np.radians(40.0)


def side(ax):
    ax.plot([-2.6, 3.4], [0, 0], color="0.3", lw=2)
    for xh in np.linspace(-2.5, 3.2, 19):
        ax.plot([xh, xh - 0.18], [0, -0.18], color="0.55", lw=1)
    a, b = 1.2, 0.5
    C = np.array([0.0, a])
    s = np.linspace(0, 2 * np.pi, 200)
    ax.fill(C[0] + a * np.cos(s), C[1] + a * np.sin(s), color="#44546a", alpha=0.15)
    ax.plot(C[0] + a * np.cos(s), C[1] + a * np.sin(s), color="#44546a", lw=2.4)
    ax.fill(C[0] + b * np.cos(s), C[1] + b * np.sin(s), color="#b9770e", alpha=0.35)
    ax.plot(C[0] + b * np.cos(s), C[1] + b * np.sin(s), color="#b9770e", lw=2)
    M = C + a * np.array([-np.sin(PHI), np.cos(PHI)])         # a marked radius: phi
    ax.plot(*zip(C, M), color="#6c3483", lw=2)
    ax.plot([0, 0], [a, 2 * a + 0.3], "--", color="0.45", lw=1.2)
    ang = np.linspace(np.pi / 2, np.pi / 2 + PHI, 30)
    ax.plot(C[0] + 0.85 * np.cos(ang), C[1] + 0.85 * np.sin(ang), color="k", lw=1.3)
    ax.text(-0.5, C[1] + 0.95, r"$\varphi$")
    ax.plot(*zip(C, C + np.array([-a * np.sin(0.7), -a * np.cos(0.7)])), color="0.2", lw=1.2)
    ax.text(-0.85, 0.75, "$a$", color="0.2")
    ax.text(0.12, C[1] - 0.45, "$b$", color="#b9770e")
    # the carriage: an arm from the axle up and forward to the pulley
    Q = np.array([2.2, 3.0])
    ax.plot([C[0], 0.0, Q[0]], [C[1], 3.0, Q[1]], color="0.25", lw=3)
    ax.plot(*C, "o", color="k", ms=7, zorder=6)
    s2 = np.linspace(0, 2 * np.pi, 60)
    rp = 0.22
    ax.plot(Q[0] + rp * np.cos(s2), Q[1] + rp * np.sin(s2), color="0.2", lw=1.8)
    # the rope: from the top of the drum to the pulley, then down to the weight
    ax.plot([C[0], Q[0]], [C[1] + b, Q[1] + rp], color="#1f6f43", lw=1.6)
    W = np.array([Q[0] + rp, 1.1])
    ax.text(1.0, 2.55, "rope", color="#1f6f43", fontsize=15, rotation=17)
    ax.plot([W[0], W[0]], [Q[1], W[1] + 0.25], color="#1f6f43", lw=1.6)
    ax.add_patch(plt.Rectangle((W[0] - 0.3, W[1] - 0.25), 0.6, 0.5, color="#7f8c8d", zorder=5))
    ax.text(W[0] + 0.42, W[1] - 0.1, "$m$")
    arrow(ax, (W[0] + 0.95, 1.55), (W[0] + 0.95, 0.55), color="#c0392b", lw=2.2)
    ax.text(W[0] + 1.08, 0.85, "$g_0$", color="#c0392b")
    arrow(ax, (W[0] - 0.75, 0.0), (W[0] - 0.75, W[1]), style="<|-|>", lw=1.4, ms=14)
    ax.text(W[0] - 1.1, 0.45, "$z$")
    arrow(ax, C + np.array([0, -0.0]), C + np.array([1.05, 0.0]), color="#c0392b", lw=2.4)
    ax.text(1.3, C[1] - 0.2, r"$a\dot\varphi$", color="#c0392b")
    ax.set_title("the mechanism, from the side", fontsize=18)
    ax.set_xlim(-2.7, 4.0)
    ax.set_ylim(-0.3, 3.4)


def top(ax):
    _draw.plane(ax, 4.0, 3.2)
    P = np.array([1.6, 1.2])
    _draw.coordinates(ax, P)
    E = np.array([np.cos(PSI), np.sin(PSI)])
    ax.plot(*zip(P - 0.9 * E, P + 0.9 * E), color="#44546a", lw=9, alpha=0.35,
            solid_capstyle="butt")
    ax.plot([P[0], P[0] + 1.8], [P[1], P[1]], "--", color="0.45", lw=1.4)
    ang = np.linspace(0, PSI, 30)
    ax.plot(P[0] + 1.4 * np.cos(ang), P[1] + 1.4 * np.sin(ang), color="k", lw=1.4)
    ax.text(P[0] + 1.55, P[1] + 0.28, r"$\psi$")
    arrow(ax, P, P + 1.5 * E, color="#c0392b", lw=2.6)
    ax.text(*(P + 0.7 * E + np.array([-1.2, 0.35])), r"$(\dot x, \dot y)$", color="#c0392b")
    ax.plot(*P, "s", color="#7f8c8d", ms=11, zorder=6)
    ax.text(*(P + np.array([0.25, -0.55])), "$m$")
    ax.set_title("from above", fontsize=18)
    ax.set_xlim(-0.5, 4.5)
    ax.set_ylim(-0.6, 3.6)


def main():
    fig, (a, b) = plt.subplots(1, 2, figsize=(11, 4.6),
                               gridspec_kw={"width_ratios": [1.35, 1]})
    for ax in (a, b):
        ax.set_aspect("equal")
        ax.axis("off")
    side(a)
    top(b)
    return _draw.save(fig, __file__)


if __name__ == "__main__":
    print(main())
