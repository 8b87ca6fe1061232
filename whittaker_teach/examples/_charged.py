"""A charge in a uniform magnetic field B (vector potential (0, B x)) and a
harmonic well: L has the term B x ydot, linear in the velocities, so the
reduced Lagrangian L* (1.16) differs for xdot > 0 and xdot < 0.

>>> from whittaker_teach.examples import charged_particle
>>> s = charged_particle()
>>> s.reduce("x", +1).L_star - s.reduce("x", -1).L_star
2*sqrt(m*Derivative(y(x), x)**2 + m)*sqrt(2*h - k*x**2 - k*y(x)**2)
"""

import sympy as sp
from ..coordinates import dynamicsymbols

from ..system import ChaplyginSystem

__all__ = ["charged_particle"]


def charged_particle():
    """L = m/2 (xdot^2 + ydot^2) + B x ydot - k/2 (x^2 + y^2): holonomic, gyroscopic."""
    t = dynamicsymbols._t
    m, B, k = sp.symbols("m B k", positive=True)
    x, y = dynamicsymbols("x y")
    L = m / 2 * (x.diff(t)**2 + y.diff(t)**2) + B * x * y.diff(t) - k / 2 * (x**2 + y**2)
    return ChaplyginSystem(L, [x, y], name="charged_particle")
