"""A projectile in a vertical plane: Whittaker's reduction with x in place of t
gives the path y(x), a parabola.

>>> from whittaker_teach.examples import projectile
>>> red = projectile().reduce("x")
>>> red.accelerations()
{Derivative(y(x), (x, 2)): (g_0*m*Derivative(y(x), x)**2 + g_0*m)/(2*(g_0*m*y(x) - h))}
"""

import sympy as sp
from ..coordinates import dynamicsymbols

from ..system import ChaplyginSystem

__all__ = ["projectile"]


def projectile():
    """L = m/2 (xdot^2 + ydot^2) - m g_0 y: holonomic, two coordinates."""
    t = dynamicsymbols._t
    m, g = sp.symbols("m g_0", positive=True)   # g_0: gravity (g counts constraints)
    x, y = dynamicsymbols("x y")
    L = m / 2 * (x.diff(t)**2 + y.diff(t)**2) - m * g * y
    return ChaplyginSystem(L, [x, y], name="projectile")
