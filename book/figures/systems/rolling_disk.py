"""The vertical rolling disk of chapters 10 and 11 (``whittaker_teach.forms.examples.rolling_disk()``).

Two 2-D views.  Left, seen from above: the contact point P = (x, y), the heading psi
of the disk's plane from the x direction, the velocity R thetadot of P along the
heading, and the torsional spring k^2 on the heading.  Right, seen in the disk's
plane: the disk of radius R standing on the ground at P, the rolling angle theta
of a marked radius, and the velocity R thetadot of the centre.

Run ``python book/figures/systems/rolling_disk.py``: it writes ``rolling_disk.svg``
beside this file (deterministic output).
"""

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
import _draw  # noqa: E402
import numpy as np  # noqa: E402

_draw.style("rolling_disk")
arrow = _draw.arrow
PSI = np.radians(32.0)
TH = np.radians(55.0)


def top(ax):
    _draw.plane(ax, 4.4, 3.6)
    P = np.array([1.8, 1.3])
    _draw.coordinates(ax, P)
    E = np.array([np.cos(PSI), np.sin(PSI)])
    ax.plot(*zip(P - 1.2 * E, P + 1.2 * E), color="#44546a", lw=9, alpha=0.35,
            solid_capstyle="butt")
    ax.plot([P[0], P[0] + 1.9], [P[1], P[1]], "--", color="0.45", lw=1.4)
    ang = np.linspace(0, PSI, 30)
    ax.plot(P[0] + 1.5 * np.cos(ang), P[1] + 1.5 * np.sin(ang), color="k", lw=1.4)
    ax.text(P[0] + 1.65, P[1] + 0.3, r"$\psi$")
    arrow(ax, P, P + 1.6 * E, color="#c0392b", lw=2.6)
    ax.text(*(P + 1.1 * E + np.array([-0.6, 0.32])), r"$R\dot\theta$", color="#c0392b")
    s = np.linspace(0, 2.6 * np.pi, 120)          # the spiral spring on the heading
    r = 0.12 + 0.055 * s
    ax.plot(P[0] + r * np.cos(s + np.pi), P[1] + r * np.sin(s + np.pi), color="#1f6f43", lw=1.5)
    ax.text(P[0] - 1.0, P[1] + 0.45, "$k^2$", color="#1f6f43")
    ax.plot(*P, "o", color="white", mec="k", mew=2, ms=10, zorder=6)
    ax.text(*(P + np.array([0.3, -0.6])), "$P$")
    ax.set_title("from above", fontsize=18)
    ax.set_xlim(-0.5, 4.9)
    ax.set_ylim(-0.6, 4.0)


def side(ax):
    ax.plot([-2.4, 2.6], [0, 0], color="0.3", lw=2)
    for xh in np.linspace(-2.3, 2.4, 16):
        ax.plot([xh, xh - 0.18], [0, -0.18], color="0.55", lw=1)
    R = 1.5
    C = np.array([0.0, R])
    s = np.linspace(0, 2 * np.pi, 200)
    ax.fill(C[0] + R * np.cos(s), C[1] + R * np.sin(s), color="#44546a", alpha=0.18)
    ax.plot(C[0] + R * np.cos(s), C[1] + R * np.sin(s), color="#44546a", lw=2.4)
    ax.plot([0, 0], [R, 2 * R + 0.35], "--", color="0.45", lw=1.4)
    M = C + R * np.array([np.sin(TH), np.cos(TH)])   # the marked radius, turned by theta
    ax.plot(*zip(C, M), color="#6c3483", lw=2.2)
    ax.plot(*zip(C, C - np.array([0, R])), color="0.3", lw=1.2, ls=":")
    ax.text(-0.42, 0.55 * R, "$R$", color="0.2")
    ang = np.linspace(np.pi / 2 - TH, np.pi / 2, 30)
    ax.plot(C[0] + 0.8 * np.cos(ang), C[1] + 0.8 * np.sin(ang), color="k", lw=1.4)
    ax.text(0.22, C[1] + 0.95, r"$\theta$")
    arrow(ax, C, C + np.array([1.6, 0.0]), color="#c0392b", lw=2.6)
    ax.text(1.6, C[1] + 0.2, r"$R\dot\theta$", color="#c0392b")
    ax.plot(*C, "o", color="k", ms=7, zorder=6)
    ax.plot(0, 0, "o", color="white", mec="k", mew=2, ms=10, zorder=6)
    ax.text(0.18, -0.6, "$P$")
    ax.set_title("in the disk's plane", fontsize=18)
    ax.set_xlim(-2.5, 2.9)
    ax.set_ylim(-0.8, 3.8)


def main():
    return _draw.panels(__file__, (top, side), figsize=(9.6, 4.6),
                        ratios=(1.1, 1))


if __name__ == "__main__":
    print(main())
