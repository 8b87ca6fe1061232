"""The Chaplygin sleigh: the knife edge at the contact point (x, y) cannot slide
sideways, ydot = xdot tan(theta), and the centre of mass lies a distance b
ahead of it along the runner.  With b = 0 it is the sledge of section 3.

>>> from whittaker_teach.examples import offset_sleigh
>>> s = offset_sleigh()
>>> s.dependent_coordinates
[y(t)]
"""

import sympy as sp
from ..coordinates import dynamicsymbols

from ..system import ChaplyginSystem

__all__ = ["offset_sleigh"]


def offset_sleigh():
    """Mass m, moment of inertia J about the centre of mass, offset b, torsional spring k.

    The centre of mass moves with (xdot - b thetadot sin(theta), ydot + b thetadot
    cos(theta)); its kinetic energy is expanded by hand (sin^2 + cos^2 = 1), and
    the constraint is written ydot = xdot sin(theta)/cos(theta), so that SymPy's
    automatic cancellation keeps the results short.
    """
    t = dynamicsymbols._t
    m, J, k, b = sp.symbols("m J k b", positive=True)
    x, th, y = dynamicsymbols("x theta y")
    xd, yd, thd = x.diff(t), y.diff(t), th.diff(t)
    L = (m / 2 * (xd**2 + yd**2) + m * b * thd * (yd * sp.cos(th) - xd * sp.sin(th))
         + (J + m * b**2) / 2 * thd**2 - k**2 * th**2 / 2)
    return ChaplyginSystem(L, [x, th, y], dependent={yd: xd * sp.sin(th) / sp.cos(th)},
                           name="offset_sleigh")
