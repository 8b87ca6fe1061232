"""The Kepler problem: a particle in the field -mu m / r.  With the polar angle
theta in place of t, Whittaker's equation (1.27) has the conics r = p/(1 + e cos theta)
among its solutions.

>>> from whittaker_teach.examples import kepler
>>> kepler().reduce("theta").independent
theta
"""

import sympy as sp
from ..coordinates import dynamicsymbols

from ..system import ChaplyginSystem

__all__ = ["kepler"]


def kepler():
    """L = m/2 (rdot^2 + r^2 thetadot^2) + mu m / r, r > 0: holonomic (theta: the polar
    angle, as the book writes it; phi is kept for the constraint functions)."""
    t = dynamicsymbols._t
    m, mu = sp.symbols("m mu", positive=True)
    r = dynamicsymbols("r", positive=True)
    theta = dynamicsymbols("theta")
    L = m / 2 * (r.diff(t)**2 + r**2 * theta.diff(t)**2) + mu * m / r
    return ChaplyginSystem(L, [r, theta], name="kepler")
