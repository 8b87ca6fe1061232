"""A particle with a nonlinear constraint, positively homogeneous of degree one:
zdot = a sqrt(xdot^2 + ydot^2) (it climbs at a fixed slope a whichever way it
moves), in a uniform field along -y.  phi(-v) = phi(v) here, not -phi(v), so
the reduced constraint qdot* (1.23) changes sign with the direction of travel.

>>> from whittaker_teach.examples import cone_particle
>>> cone_particle().reduce("x", direction=-1).constraint_rates
{z(x): -a*sqrt(Derivative(y(x), x)**2 + 1)}
"""

import sympy as sp
from ..coordinates import dynamicsymbols

from ..system import ChaplyginSystem

__all__ = ["cone_particle"]


def cone_particle():
    """L = m/2 (xdot^2 + ydot^2 + zdot^2) - m g_0 y with zdot = a sqrt(xdot^2 + ydot^2)."""
    t = dynamicsymbols._t
    m, g, a = sp.symbols("m g_0 a", positive=True)   # g_0: gravity (g counts constraints)
    x, y, z = dynamicsymbols("x y z")
    L = m / 2 * (x.diff(t)**2 + y.diff(t)**2 + z.diff(t)**2) - m * g * y
    dep = {z.diff(t): a * sp.sqrt(x.diff(t)**2 + y.diff(t)**2)}
    return ChaplyginSystem(L, [x, y, z], dependent=dep, name="cone_particle")
