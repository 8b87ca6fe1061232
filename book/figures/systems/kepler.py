"""The Kepler problem of chapter 2 (``wt.examples.kepler()``).

An elliptic orbit with the centre of attraction F at a focus, the particle of
mass m at distance r from F, the polar angle theta measured from the direction
of the pericentre, and the semi-latus rectum p (the distance from F to the orbit
at theta = pi/2): the orbit is r = p / (1 + e cos(theta)).

Run ``python book/figures/systems/kepler.py``: it writes ``kepler.svg`` beside
this file (deterministic output).
"""

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
import _draw  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

_draw.style("kepler")

P_LR, ECC = 2.0, 0.55                      # the orbit drawn
TH = np.radians(62.0)                      # where the particle is drawn

arrow = _draw.arrow


def orbit(th):
    return P_LR / (1 + ECC * np.cos(th))


def main():
    fig, ax = plt.subplots(figsize=(7.4, 5.4))
    ax.set_aspect("equal")
    ax.axis("off")

    th = np.linspace(0, 2 * np.pi, 400)
    r = orbit(th)
    ax.plot(r * np.cos(th), r * np.sin(th), color="#2c3e50", lw=2.2)

    # the axis through the focus towards the pericentre
    rp = orbit(0.0)
    ax.plot([-orbit(np.pi) - 0.3, rp + 0.9], [0, 0], "--", color="0.45", lw=1.3, zorder=1)
    ax.plot(rp, 0, "o", color="#2c3e50", ms=6)
    ax.text(rp + 0.1, -0.12, "pericentre", fontsize=16, ha="left", va="top", color="#2c3e50")

    # the focus F, the centre of attraction
    ax.plot(0, 0, "*", color="#b9770e", ms=22, zorder=6)
    ax.text(-0.2, -0.22, "$F$", ha="right", va="top")

    # the particle, r and theta
    rr = orbit(TH)
    M = rr * np.array([np.cos(TH), np.sin(TH)])
    ax.plot([0, M[0]], [0, M[1]], color="#c0392b", lw=2.4, zorder=3)
    ax.text(*(0.5 * M + 0.22 * np.array([-np.sin(TH), np.cos(TH)])), "$r$",
            color="#c0392b", ha="right", va="center", fontsize=24)
    ax.plot(*M, "o", color="k", ms=13, zorder=6)
    ax.text(M[0] + 0.2, M[1] + 0.1, "$m$", va="bottom")
    a = np.linspace(0, TH, 50)
    ax.plot(0.75 * np.cos(a), 0.75 * np.sin(a), color="k", lw=1.4)
    ax.text(0.92 * np.cos(TH / 2), 0.92 * np.sin(TH / 2), r"$\theta$", va="center")

    # the semi-latus rectum p, at theta = -pi/2
    arrow(ax, (0, 0), (0, -P_LR), color="#6c3483", lw=1.6, ms=18, style="<|-|>")
    ax.text(0.12, -0.62 * P_LR, "$p$", color="#6c3483", va="center")

    return _draw.save(fig, __file__)


if __name__ == "__main__":
    print(main())
