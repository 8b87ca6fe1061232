"""The charged particle of chapter 4 (``wt.examples.charged_particle()``).

A particle of mass m in the plane Oxy, in a harmonic well centred at O (force
-k r) and in a uniform magnetic field B along +z (out of the page; B stands
for the charge times the field).  The magnetic force B (ydot, -xdot) bends
the path to the right of the direction of motion.  The figure shows the axes,
the level circles of the well (k), the field symbols, the particle P with its
velocity v and the magnetic force (below the arrow's tip, clear of the path).

Run ``python book/figures/systems/charged_particle.py``: it writes
``charged_particle.svg`` beside this file (deterministic output).
"""

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
import _draw  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

_draw.style("charged_particle")


def arrow(ax, p, q, color="k", lw=2.0, ms=22):
    _draw.arrow(ax, p, q, color=color, lw=lw, ms=ms, zorder=None)


def path():
    """A stretch of a true motion: m xdd = B yd - k x, m ydd = -B xd - k y (RK4)."""
    m, B, k = 1.0, 1.6, 1.0
    s = np.array([-2.9, 0.2, 1.1, 1.6])            # x, y, xdot, ydot
    dt, out = 0.004, [s.copy()]

    def f(s):
        x, y, u, v = s
        return np.array([u, v, (B * v - k * x) / m, (-B * u - k * y) / m])

    for _ in range(420):
        k1 = f(s)
        k2 = f(s + dt / 2 * k1)
        k3 = f(s + dt / 2 * k2)
        k4 = f(s + dt * k3)
        s = s + dt / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
        out.append(s.copy())
    return np.array(out), B, k


def main():
    fig, ax = plt.subplots(figsize=(6.4, 6.0))
    ax.set_aspect("equal")
    ax.axis("off")

    # the well: level circles of k r^2 / 2
    for r in (0.9, 1.8, 2.7):
        ax.add_patch(plt.Circle((0, 0), r, fill=False, color="#9aa7b8", lw=1.2,
                                ls=(0, (4, 3))))
    # the field, out of the page
    for gx in (-2.6, -1.3, 1.3, 2.6):
        for gy in (-2.6, 2.6):
            ax.add_patch(plt.Circle((gx, gy), 0.16, fill=False, color="#7d3c98", lw=1.5))
            ax.plot(gx, gy, "o", color="#7d3c98", ms=3.5)
    ax.text(2.95, 2.6, "$B$", color="#7d3c98", va="center")

    # axes
    arrow(ax, (-3.2, 0), (3.4, 0))
    arrow(ax, (0, -3.2), (0, 3.4))
    ax.text(3.45, -0.1, "$x$", va="top")
    ax.text(0.12, 3.4, "$y$", va="top")
    ax.text(-0.1, -0.1, "$O$", ha="right", va="top")

    # a stretch of path, the particle and its forces
    traj, B, k = path()
    ax.plot(traj[:, 0], traj[:, 1], color="#c0392b", lw=2.6)
    i = 110
    x, y, u, v = traj[i]
    P = np.array([x, y])
    speed = np.hypot(u, v)
    vdir = np.array([u, v]) / speed
    arrow(ax, P, P + 1.2 * vdir, color="#c0392b", lw=2.8)
    ax.text(*(P + 1.25 * vdir + [0.05, 0.0]), r"$\mathbf{v}$", color="#c0392b",
            fontsize=24, va="bottom")
    fmag = np.array([v, -u]) / speed                 # B (ydot, -xdot): to the right
    arrow(ax, P, P + 1.0 * fmag, color="#7d3c98", lw=2.4)
    ax.text(*(P + 1.0 * fmag + [0.15, -0.15]), r"$B\,(\dot y,-\dot x)$",   # below the tip,
            color="#7d3c98", fontsize=20, ha="center", va="top")         # clear of the path
    ax.text(2.05, -1.95, "$k$", color="#5d6d7e", fontsize=20)
    ax.plot(*P, "o", color="k", ms=10, zorder=5)
    ax.text(P[0] - 0.5, P[1] + 0.05, "$P$")

    ax.set_xlim(-3.3, 3.6)
    ax.set_ylim(-3.2, 3.5)
    return _draw.save(fig, __file__)


if __name__ == "__main__":
    print(main())
