"""The rolling disk in three dimensions, built with ``sympy.physics.mechanics`` and
taken in through the library's mechanics input (``nonhol_coneqs``).

Coordinates: the contact point (x, y) (dependent), the heading psi, the tilt phi
from the vertical, the rolling angle theta.  Frames: psi about the vertical,
phi about the horizontal diameter, theta about the disk's axis; the centre G is
R above the contact point along the disk's plane; rolling without slipping: the
material point at the contact has zero velocity.  L and the constraints contain
neither x nor y: a Chaplygin system with x, y dependent.

>>> disk = tilting_disk()
>>> disk.constraints
{Derivative(x(t), t): R*cos(psi(t))*Derivative(theta(t), t), Derivative(y(t), t): R*sin(psi(t))*Derivative(theta(t), t)}
"""

from __future__ import annotations

import sympy as sp

from ..system import ChaplyginSystem

__all__ = ["tilting_disk"]


def tilting_disk(uniform=True):
    """The disk of mass m, radius R under gravity g.  ``uniform=True``: a thin
    uniform disk, moments m R^2/4 about a diameter and m R^2/2 about the axis;
    ``uniform=False``: symbols A (diameter) and C (axis).

    >>> tilting_disk(uniform=False).parameters
    [A, C, R, g, m]
    """
    import sympy.physics.mechanics as me
    t = me.dynamicsymbols._t
    x, y, psi, phi, th = me.dynamicsymbols("x y psi phi theta")
    m, R, g = sp.symbols("m R g", positive=True)
    if uniform:
        A, C = m * R**2 / 4, m * R**2 / 2
    else:
        A, C = sp.symbols("A C", positive=True)
    N = me.ReferenceFrame("N")
    Fa = N.orientnew("Fa", "Axis", [psi, N.z])         # heading
    Fb = Fa.orientnew("Fb", "Axis", [phi, Fa.x])       # tilt
    Fc = Fb.orientnew("Fc", "Axis", [th, Fb.y])        # rolling
    O = me.Point("O")
    O.set_vel(N, 0)
    P = O.locatenew("P", x * N.x + y * N.y)            # the contact point
    G = P.locatenew("G", R * Fb.z)                     # the centre
    G.set_vel(N, G.pos_from(O).dt(N))
    body = me.RigidBody("disk", G, Fc, m, (me.inertia(Fc, A, C, A), G))
    body.potential_energy = m * g * G.pos_from(O).dot(N.z)
    L = sp.trigsimp(sp.expand(me.Lagrangian(N, body)))
    slip = G.vel(N) - Fc.ang_vel_in(N).cross(R * Fb.z)  # velocity of the contact material point
    cons = [sp.trigsimp(sp.expand(slip.dot(e))) for e in (N.x, N.y)]
    return ChaplyginSystem(L, [x, y, psi, phi, th], nonhol_coneqs=cons, dependent=[x, y],
                           name="tilting_disk")
