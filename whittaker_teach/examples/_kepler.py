"""The Kepler problem: a particle in the field -mu m / r.  With the polar angle
phi in place of t, Whittaker's equation (1.27) has the conics r = p/(1 + e cos phi)
among its solutions.

>>> from whittaker_teach.examples import kepler
>>> kepler().reduce("phi").independent
phi
"""

import sympy as sp
from sympy.physics.mechanics import dynamicsymbols

from ..system import ChaplyginSystem

__all__ = ["kepler"]


def kepler():
    """L = m/2 (rdot^2 + r^2 phidot^2) + mu m / r, r > 0: holonomic."""
    t = dynamicsymbols._t
    m, mu = sp.symbols("m mu", positive=True)
    r = dynamicsymbols("r", positive=True)
    phi = dynamicsymbols("phi")
    L = m / 2 * (r.diff(t)**2 + r**2 * phi.diff(t)**2) + mu * m / r
    return ChaplyginSystem(L, [r, phi], name="kepler")
