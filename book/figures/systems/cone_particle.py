"""The cone particle of chapter 4 (``wt.examples.cone_particle()``).

y is the vertical (gravity -m g_0 y); x and z are horizontal.  The constraint
zdot = a sqrt(xdot^2 + ydot^2) keeps the velocity on a cone whose axis points
along +z: the velocity makes the angle alpha = arctan(a) with the vertical
plane Oxy, whichever way the particle moves in that plane.  The figure shows
the axes, the vertical plane Oxy, the particle P, its path in space and the
path's shadow y(x) in the plane Oxy, gravity, the velocity cone at P, the
velocity v and the angle alpha.

Run ``python book/figures/systems/cone_particle.py``: it writes
``cone_particle.svg`` beside this file (deterministic output).
"""

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
import _draw  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

_draw.style("cone_particle")

A = 0.75                                  # the slope a = tan(alpha)
ALPHA = np.arctan(A)
# view (a right-handed frame): y up; x to the right and away from the viewer,
# z to the right and towards the viewer, so the cone (axis +z) is seen from the side
ELEV, AZIM = np.radians(24.0), np.radians(-53.0)


def proj(x, y, z):
    """Orthographic view of the point (x, y, z) with y vertical."""
    x, y, z = (np.asarray(v, float) for v in (x, y, z))
    # turn about the vertical by AZIM, then look down by ELEV (near is lower)
    u = np.cos(AZIM) * x - np.sin(AZIM) * z
    towards = np.sin(AZIM) * x + np.cos(AZIM) * z
    return u, np.cos(ELEV) * y - np.sin(ELEV) * towards


def path(s):
    """A path obeying the constraint: z grows by a per unit length in Oxy."""
    x = 0.3 + 2.7 * s
    y = 1.7 + 3.6 * s - 3.0 * s**2            # an arc y(x) in the vertical plane
    seg = np.hypot(np.diff(x), np.diff(y))
    z = 0.7 + A * np.concatenate([[0.0], np.cumsum(seg)])
    return x, y, z


def line(ax, P, Q, **kw):
    ax.plot(*zip(proj(*P), proj(*Q)), **kw)


def arrow(ax, P, Q, color="k", lw=2.0, ms=22, ls="-"):
    ax.plot(*zip(proj(*P), proj(*Q)), alpha=0)       # keeps the arrow in the limits
    _draw.arrow(ax, proj(*P), proj(*Q), color=color, lw=lw, ms=ms, ls=ls, zorder=None)


def label(ax, P, text, dx=0.0, dy=0.0, **kw):
    u, v = proj(*P)
    ax.text(u + dx, v + dy, text, **kw)


def main():
    fig, ax = plt.subplots(figsize=(7.6, 6.4))
    ax.set_aspect("equal")
    ax.axis("off")

    # the vertical plane Oxy, shaded
    corners = [(0, 0, 0), (3.3, 0, 0), (3.3, 3.7, 0), (0, 3.7, 0)]
    ax.fill(*zip(*[proj(*c) for c in corners]), color="#e3ebf6", zorder=0)
    label(ax, (0.12, 0.9, 0), "plane $Oxy$", fontsize=16, color="#44546a", va="top")

    # axes
    arrow(ax, (0, 0, 0), (3.7, 0, 0))
    arrow(ax, (0, 0, 0), (0, 4.6, 0))
    arrow(ax, (0, 0, 0), (0, 0, 3.3))
    label(ax, (3.75, 0, 0), "$x$", dx=0.05, dy=-0.05, va="top")
    label(ax, (0, 4.68, 0), "$y$  (up)", dx=-0.1, va="bottom")
    label(ax, (0, 0, 3.4), "$z$", dx=0.05, va="center")
    label(ax, (0, 0, 0), "$O$", dx=-0.12, dy=-0.05, ha="right", va="top")

    # the path and its shadow y(x) in the plane Oxy
    s = np.linspace(0.0, 1.0, 601)
    x, y, z = path(s)
    ax.plot(*proj(x, y, 0 * x), "--", color="#44546a", lw=1.8, zorder=1)
    ax.plot(*proj(x, y, z), color="#c0392b", lw=2.6, zorder=2)
    label(ax, (x[330], y[330], 0), "$y(x)$", dy=0.12, color="#44546a",
          fontsize=18, ha="center", va="bottom")
    for j in (0, 200, 560):
        line(ax, (x[j], y[j], 0), (x[j], y[j], z[j]), ls=":", color="#44546a", lw=1.3)

    # the particle P
    i = 200
    P = np.array([x[i], y[i], z[i]])
    line(ax, (P[0], P[1], 0), P, ls=":", color="#44546a", lw=1.3)

    # gravity
    arrow(ax, P, P + [0, -1.0, 0], color="#1f6f3f", lw=2.6)
    label(ax, P + [0, -0.9, 0], r"$m g_0$", dx=-0.12, ha="right", color="#1f6f3f",
          fontsize=19)

    # the velocity cone at P: axis +z; each generator at alpha to the plane Oxy
    Lg = 1.45                                  # length of a generator drawn
    r, hgt = Lg * np.cos(ALPHA), Lg * np.sin(ALPHA)
    ph = np.linspace(0, 2 * np.pi, 240)
    rim = (P[0] + r * np.cos(ph), P[1] + r * np.sin(ph), np.full_like(ph, P[2] + hgt))
    ax.fill(*proj(*rim), color="#f5cf9f", alpha=0.45, zorder=1, lw=0)
    ax.plot(*proj(*rim), color="#b9770e", lw=1.4, zorder=1)
    # the two outline generators (tangent to the rim as seen)
    ru, rv = proj(*rim)
    pu, pv = proj(*P)
    ang = np.arctan2(rv - pv, ru - pu)
    for k in (np.argmax(ang), np.argmin(ang)):
        ax.plot([pu, ru[k]], [pv, rv[k]], color="#b9770e", lw=1.4, zorder=1)
    arrow(ax, P, P + [0, 0, hgt * 1.9], color="#b9770e", lw=1.3, ms=14, ls="--")

    # the velocity: along the path's tangent, on the cone
    T = np.array([x[i + 1] - x[i - 1], y[i + 1] - y[i - 1], z[i + 1] - z[i - 1]])
    T /= np.linalg.norm(T)
    V = P + Lg * T
    Vxy = np.array([V[0], V[1], P[2]])            # the projection of v on Oxy
    arrow(ax, P, V, color="#c0392b", lw=3.0, ms=24)
    line(ax, P, Vxy, color="#c0392b", lw=1.5, ls="--")
    line(ax, Vxy, V, color="#c0392b", lw=1.1, ls=":")
    label(ax, V, r"$\mathbf{v}$", dx=0.08, dy=0.05, color="#c0392b", fontsize=24)
    # alpha: the arc from the projection of v to v
    t = np.linspace(0, 1, 30)
    arc = [P + 0.62 * Lg * ((1 - tt) * (Vxy - P) / np.linalg.norm(Vxy - P)
                            + tt * T) / np.linalg.norm((1 - tt) * (Vxy - P)
                                                       / np.linalg.norm(Vxy - P) + tt * T)
           for tt in t]
    ax.plot(*proj(*np.array(arc).T), color="k", lw=1.3)
    label(ax, arc[15], r"$\alpha$", dx=0.12, dy=-0.12, fontsize=21)

    u, v = proj(*P)
    ax.plot(u, v, "o", color="k", ms=10, zorder=5)
    ax.text(u - 0.38, v + 0.08, "$P$", fontsize=22)

    return _draw.save(fig, __file__)


if __name__ == "__main__":
    print(main())
