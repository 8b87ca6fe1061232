"""Appell and Hamel's weight (``whittaker_teach.forms.examples.appell_hamel()``) and the
mechanism of chapter 10 whose limit gives its non-linear constraint: the book's own
version of such a mechanism (Appell's own figure has not been checked).

Left, seen from the side along the wheel's plane, forward to the right: a wheel of
radius a rolls without slipping on the horizontal plane; rolling forward (a phidot > 0,
to the right) turns it clockwise, so the rolling angle phi of a marked radius is
measured clockwise from the vertical.  A drum of radius b is fixed to its axle and
turns with it; the rope leaves the drum's forward side going up, so a clockwise
turn winds it in: over a pulley at the top of the carriage (which the axle carries)
it lifts the weight m, which hangs on the axle's vertical, at height z above the
plane, in gravity g_0 (down).  Rolling forward by dphi moves the weight a dphi
horizontally, with the axle, and winds b dphi of rope: z rises by b dphi, so
zdot = b phidot, xdot = a phidot cos psi, ydot = a phidot sin psi (the model of
chapter 10), and on a straight run (psidot = 0, phidot > 0) the mechanism reproduces
the weight's law zdot = c sqrt(xdot^2 + ydot^2), c = b/a.  Right, seen from above: the weight's
horizontal position (x, y), on the wheel's track, and its velocity (xdot, ydot) along
the wheel's heading psi.

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
    ax.plot([-2.5, 3.4], [0, 0], color="0.3", lw=2)
    for xh in np.linspace(-2.4, 3.2, 19):
        ax.plot([xh, xh - 0.18], [0, -0.18], color="0.55", lw=1)
    a, b = 1.2, 0.5
    C = np.array([0.0, a])
    s = np.linspace(0, 2 * np.pi, 200)
    # the carriage: from the axle up and back, up behind the wheel, forward to the pulley
    H, rp = 4.3, b / 2                       # the pulley's centre is over the drum
    Q = np.array([b - rp, H])
    post = -a - 0.45
    ax.plot([C[0], post, post, Q[0]], [C[1], C[1] - post, H, H], color="0.25", lw=3,
            solid_joinstyle="miter", zorder=1)
    ax.fill(C[0] + a * np.cos(s), C[1] + a * np.sin(s), color="#44546a", alpha=0.15)
    ax.plot(C[0] + a * np.cos(s), C[1] + a * np.sin(s), color="#44546a", lw=2.4)
    ax.fill(C[0] + b * np.cos(s), C[1] + b * np.sin(s), color="#b9770e", alpha=0.35)
    ax.plot(C[0] + b * np.cos(s), C[1] + b * np.sin(s), color="#b9770e", lw=2)
    # phi: a marked radius turned clockwise from the vertical (rolling to the right)
    M = C + a * np.array([np.sin(PHI), np.cos(PHI)])
    ax.plot(*zip(C, M), color="#6c3483", lw=2)
    ax.plot([0, 0], [a, 2 * a], "--", color="0.45", lw=1.2)
    ang = np.linspace(np.pi / 2 - PHI, np.pi / 2, 30)
    ax.plot(C[0] + 0.85 * np.cos(ang), C[1] + 0.85 * np.sin(ang), color="k", lw=1.3)
    arrow(ax, C + 0.85 * np.array([np.cos(ang[1]), np.sin(ang[1])]),
          C + 0.85 * np.array([np.cos(ang[0]), np.sin(ang[0])]), lw=1.3, ms=14)
    ax.text(0.2, C[1] + 0.95, r"$\varphi$")
    ax.plot(*zip(C, C + a * np.array([np.sin(0.75), -np.cos(0.75)])), color="0.2", lw=1.2)
    ax.text(0.72, 0.5, "$a$", color="0.2")
    ax.plot(*zip(C, C - np.array([b, 0.0])), color="#7e5109", lw=1.2)
    ax.text(-0.25, C[1] - 0.1, "$b$", color="#7e5109", ha="center", va="top")
    # the rope: up from the drum's forward side (x = b), over the pulley, down to m
    rope = "#1f6f43"
    W = np.array([0.0, 3.15])                # the weight, on the axle's vertical
    ax.plot([b, b], [C[1], H], color=rope, lw=1.6, zorder=4)
    arc = np.linspace(0, np.pi, 40)
    ax.plot(Q[0] + rp * np.cos(arc), Q[1] + rp * np.sin(arc), color=rope, lw=1.6, zorder=4)
    ax.plot([0, 0], [H, W[1] + 0.25], color=rope, lw=1.6, zorder=4)
    ax.plot(Q[0] + rp * np.cos(s), Q[1] + rp * np.sin(s), color="0.2", lw=1.4)
    ax.plot(*Q, "o", color="0.2", ms=3)
    arrow(ax, (b + 0.17, 3.95), (b + 0.17, 3.35), color=rope, lw=1.4, ms=12)
    ax.text(b + 0.3, 3.45, "rope", color=rope, fontsize=15)
    ax.add_patch(plt.Rectangle((W[0] - 0.3, W[1] - 0.25), 0.6, 0.5, color="#7f8c8d", zorder=5))
    ax.text(W[0] - 0.42, W[1] - 0.1, "$m$", ha="right")
    arrow(ax, (3.0, 4.1), (3.0, 3.1), color="#c0392b", lw=2.2)
    ax.text(3.13, 3.4, "$g_0$", color="#c0392b")
    zx = 2.3
    ax.plot([W[0] + 0.3, zx + 0.15], [W[1], W[1]], ":", color="0.3", lw=1.2)
    arrow(ax, (zx, 0.0), (zx, W[1]), style="<|-|>", lw=1.4, ms=14)
    ax.text(zx + 0.12, 1.9, "$z$")
    arrow(ax, C, C + np.array([1.75, 0.0]), color="#c0392b", lw=2.4)
    ax.text(1.25, C[1] + 0.17, r"$a\dot\varphi$", color="#c0392b")
    ax.plot(*C, "o", color="k", ms=7, zorder=6)
    ax.set_title("the mechanism, from the side", fontsize=18)
    ax.set_xlim(-2.6, 3.6)
    ax.set_ylim(-0.3, 4.9)


def top(ax):
    _draw.plane(ax, 4.0, 3.2)
    P = np.array([1.6, 1.2])
    _draw.coordinates(ax, P)
    E = np.array([np.cos(PSI), np.sin(PSI)])
    Rt = 1.6                                 # the wheel's track so far, ending at P
    h = np.linspace(PSI + 0.65, PSI, 40)
    Ct = P + Rt * np.array([np.sin(PSI), -np.cos(PSI)])
    ax.plot(Ct[0] - Rt * np.sin(h), Ct[1] + Rt * np.cos(h), "--", color="#44546a", lw=1.3)
    ax.text(0.86, 0.45, "track", color="#44546a", fontsize=13, ha="right", va="center")
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
    return _draw.panels(__file__, (side, top), figsize=(11, 4.6),
                        ratios=(1.35, 1))


if __name__ == "__main__":
    print(main())
