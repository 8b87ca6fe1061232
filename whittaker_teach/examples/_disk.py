"""A vertical disk of radius R rolling without slipping on a horizontal plane,
with a torsional spring on its heading psi.  The contact point (x, y) moves
with xdot = R thetadot cos(psi), ydot = R thetadot sin(psi); the rolling
angle theta takes the place of time.

>>> from whittaker_teach.examples import rolling_disk
>>> rolling_disk().independent_coordinates
[psi(t), theta(t)]
"""

import sympy as sp
from ..coordinates import dynamicsymbols

from ..system import ChaplyginSystem

__all__ = ["rolling_disk"]


def rolling_disk():
    """Mass m, radius R, moments of inertia A (rolling axis) and C (vertical), spring k."""
    t = dynamicsymbols._t
    m, R, A, C, k = sp.symbols("m R A C k", positive=True)
    x, y, psi, th = dynamicsymbols("x y psi theta")
    L = (m / 2 * (x.diff(t)**2 + y.diff(t)**2) + A / 2 * th.diff(t)**2
         + C / 2 * psi.diff(t)**2 - k**2 * psi**2 / 2)
    dep = {x.diff(t): R * th.diff(t) * sp.cos(psi), y.diff(t): R * th.diff(t) * sp.sin(psi)}
    return ChaplyginSystem(L, [x, y, psi, th], dependent=dep, name="rolling_disk")
