"""The rolling disk in three dimensions (``whittaker_teach.stability.tilting_disk()``).

Two 2-D projections.  Left, seen along the direction of travel: the disk, edge on, tilted
by phi from the vertical, its centre G a distance R above the contact point P along its
plane, gravity g.  Right, seen from above: the contact point P = (x, y), the heading psi
of the disk's plane, the rolling angle theta with the velocity R thetadot of P along
the heading.

Run ``python book/figures/systems/tilting_disk.py``: it writes ``tilting_disk.svg``
beside this file (deterministic output).
"""

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
import _draw  # noqa: E402
import numpy as np  # noqa: E402

_draw.style("tilting_disk")
arrow = _draw.arrow
PHI = np.radians(18.0)
PSI = np.radians(30.0)


def front(ax):
    ax.plot([-2.2, 2.2], [0, 0], color="0.3", lw=2)
    for xh in np.linspace(-2.1, 2.0, 14):
        ax.plot([xh, xh - 0.18], [0, -0.18], color="0.55", lw=1)
    up = np.array([np.sin(PHI), np.cos(PHI)])
    P = np.array([0.0, 0.0])
    G = P + 2.0 * up
    ax.plot(*zip(P - 0.0 * up, P + 4.0 * up), color="#44546a", lw=9, solid_capstyle="butt",
            alpha=0.35)
    ax.plot(*zip(P, G), color="#6c3483", lw=1.6)
    ax.text(*(0.5 * (P + G) + np.array([0.28, -0.2])), "$R$", color="#6c3483")
    ax.plot([0, 0], [0, 3.6], "--", color="0.45", lw=1.4)
    ang = np.linspace(np.pi / 2 - PHI, np.pi / 2, 30)
    ax.plot(3.0 * np.cos(ang), 3.0 * np.sin(ang), color="k", lw=1.4)
    ax.text(0.28, 3.2, r"$\varphi$", ha="center")
    arrow(ax, (1.7, 3.4), (1.7, 2.2), color="#c0392b", lw=2.4)
    ax.text(1.85, 2.6, "$g$", color="#c0392b")
    ax.plot(*G, "o", color="k", ms=10, zorder=6)
    ax.text(*(G + np.array([-0.4, 0.05])), "$G$", ha="center")
    ax.plot(*P, "o", color="white", mec="k", mew=2, ms=10, zorder=6)
    ax.text(0.25, -0.55, "$P$", ha="center")
    ax.set_title("along the motion", fontsize=18)
    ax.set_xlim(-2.3, 2.3)
    ax.set_ylim(-0.8, 4.4)


def top(ax):
    _draw.plane(ax, 4.4, 3.6)
    P = np.array([1.7, 1.3])
    _draw.coordinates(ax, P)
    E = np.array([np.cos(PSI), np.sin(PSI)])
    ax.plot(*zip(P - 1.2 * E, P + 1.2 * E), color="#44546a", lw=9, alpha=0.35,
            solid_capstyle="butt")
    ax.plot([P[0], P[0] + 1.9], [P[1], P[1]], "--", color="0.45", lw=1.4)
    ang = np.linspace(0, PSI, 30)
    ax.plot(P[0] + 1.5 * np.cos(ang), P[1] + 1.5 * np.sin(ang), color="k", lw=1.4)
    ax.text(P[0] + 1.75, P[1] + 0.38, r"$\psi$")
    arrow(ax, P, P + 1.5 * E, color="#c0392b", lw=2.6)
    ax.text(*(P + 1.0 * E + np.array([-0.55, 0.3])), r"$R\dot\theta$", color="#c0392b")
    ax.plot(*P, "o", color="white", mec="k", mew=2, ms=10, zorder=6)
    ax.text(*(P + np.array([0.1, -0.45])), "$P$")
    ax.set_title("from above", fontsize=18)
    ax.set_xlim(-0.5, 4.9)
    ax.set_ylim(-0.6, 4.0)


def main():
    return _draw.panels(__file__, (front, top), figsize=(9.6, 4.6),
                        ratios=(1, 1.1))


if __name__ == "__main__":
    print(main())
