"""The systems of the course's chapters on the classical forms, built on demand.

==========================  ==============================================================
``sledge()``                Mei's sledge: ydot = xdot tan(theta), a torsional spring
``sleigh()``                the Chaplygin sleigh, centre of mass a distance b ahead of the
                            knife edge (the constraint given as ydot cos - xdot sin = 0)
``rolling_disk()``          a vertical disk rolling without slipping (g = 2)
``appell_hamel()``          a weight with zdot = c sqrt(xdot^2 + ydot^2) (Chetaev, nonlinear;
                            gravity makes it not of Chaplygin type)
``sledge_in_a_well()``      the sledge with a potential kappa/2 (x^2 + y^2): L depends on the
                            dependent coordinate y (not of Chaplygin type)
``chain(n)``                the benchmark's chain of spring-coupled sleighs, n coordinates
==========================  ==============================================================

>>> from whittaker_teach.forms import examples
>>> [examples.sleigh().is_chaplygin, examples.sledge_in_a_well().is_chaplygin]
[True, False]
>>> examples.appell_hamel().is_linear
False
"""

from __future__ import annotations

import sympy as sp
from sympy.physics.mechanics import dynamicsymbols

from .model import NonholonomicSystem

__all__ = ["sledge", "sleigh", "rolling_disk", "appell_hamel", "sledge_in_a_well", "chain",
           "catalogue"]

t = dynamicsymbols._t


def sledge():
    """Mei's section 3: L = m/2 (xdot^2 + ydot^2) + J/2 thetadot^2 - k^2 theta^2/2,
    ydot = xdot tan(theta)."""
    m, J, k = sp.symbols("m J k", positive=True)
    x, th, y = dynamicsymbols("x theta y")
    L = m / 2 * (x.diff(t)**2 + y.diff(t)**2) + J / 2 * th.diff(t)**2 - k**2 * th**2 / 2
    return NonholonomicSystem(L, [x, th, y], dependent={y.diff(t): x.diff(t) * sp.tan(th)},
                              name="sledge")


def sleigh():
    """The Chaplygin sleigh: mass m, moment of inertia J about the centre of mass, which
    lies a distance b ahead of the knife edge (x, y); a torsional spring k.  The
    constraint, the edge does not slide sideways, is given as LagrangesMethod takes it:
    ydot cos(theta) - xdot sin(theta) = 0."""
    m, J, k, b = sp.symbols("m J k b", positive=True)
    x, th, y = dynamicsymbols("x theta y")
    xd, yd, thd = x.diff(t), y.diff(t), th.diff(t)
    L = (m / 2 * (xd**2 + yd**2) + m * b * thd * (yd * sp.cos(th) - xd * sp.sin(th))
         + (J + m * b**2) / 2 * thd**2 - k**2 * th**2 / 2)
    return NonholonomicSystem(L, [x, th, y], constraints=[yd * sp.cos(th) - xd * sp.sin(th)],
                              dependent=[y], name="sleigh")


def rolling_disk():
    """A vertical disk of radius R rolling without slipping, heading psi with a spring:
    xdot = R thetadot cos(psi), ydot = R thetadot sin(psi) (g = 2)."""
    m, R, A, C, k = sp.symbols("m R A C k", positive=True)
    x, y, psi, th = dynamicsymbols("x y psi theta")
    L = (m / 2 * (x.diff(t)**2 + y.diff(t)**2) + A / 2 * th.diff(t)**2
         + C / 2 * psi.diff(t)**2 - k**2 * psi**2 / 2)
    dep = {x.diff(t): R * th.diff(t) * sp.cos(psi), y.diff(t): R * th.diff(t) * sp.sin(psi)}
    return NonholonomicSystem(L, [x, y, psi, th], dependent=dep, name="rolling_disk")


def appell_hamel():
    """Appell and Hamel's weight: a particle of mass m whose vertical velocity is tied to
    its horizontal speed, zdot = c sqrt(xdot^2 + ydot^2) (the limit of a mechanism of
    wheels and a rope, Appell 1911), in gravity g0.  The constraint is nonlinear and
    homogeneous of degree one (Chetaev); L depends on z, so it is not of Chaplygin type."""
    m, c, g0 = sp.symbols("m c g_0", positive=True)
    x, y, z = dynamicsymbols("x y z")
    L = m / 2 * (x.diff(t)**2 + y.diff(t)**2 + z.diff(t)**2) - m * g0 * z
    return NonholonomicSystem(L, [x, y, z], dependent={
        z.diff(t): c * sp.sqrt(x.diff(t)**2 + y.diff(t)**2)}, name="appell_hamel")


def sledge_in_a_well():
    """The sledge in the potential kappa/2 (x^2 + y^2): L depends on y, the dependent
    coordinate, so Chaplygin's equations (1.4) do not apply; Voronets' do."""
    m, J, kappa = sp.symbols("m J kappa", positive=True)
    x, th, y = dynamicsymbols("x theta y")
    L = (m / 2 * (x.diff(t)**2 + y.diff(t)**2) + J / 2 * th.diff(t)**2
         - kappa / 2 * (x**2 + y**2))
    return NonholonomicSystem(L, [x, th, y], dependent={y.diff(t): x.diff(t) * sp.tan(th)},
                              name="sledge_in_a_well")


def chain(n):
    """The chain of spring-coupled Chaplygin sleighs of the benchmarks
    (:func:`whittaker_teach.bench.chain`), n coordinates, built with
    sympy.physics.mechanics; the constraints given as P.vel(N).dot(B.y) = 0."""
    from ..bench import chain as _chain
    F = _chain(n)
    return NonholonomicSystem(F["L"], F["q"], constraints=F["coneqs"],
                              dependent=F["dependent"], name=f"chain({n})")


def catalogue():
    """The book's systems of these chapters, by name (each built when called)."""
    return {"sledge": sledge, "sleigh": sleigh, "rolling_disk": rolling_disk,
            "appell_hamel": appell_hamel, "sledge_in_a_well": sledge_in_a_well}
