"""Geometry and symmetry of a Chaplygin system (chapter 13 of the book).

==========================  ============================================================
``connection``              the constraint one-forms A, the horizontal lifts, the
                            curvature B = dA on horizontal vectors, and the check that
                            Mei's (1.4) is Lagrange's equation of L~ plus the curvature
                            term
``nonholonomic_bracket``    the almost-Poisson bracket of the reduced system in (q, p)
``AlmostPoisson``           a bracket given by its structure matrix: brackets,
                            Jacobiator, the Hamiltonian vector field
``rescaled``                the bracket after Chaplygin's change of time d tau = N dt,
                            in the momenta N p
``divergence``,             the divergence of a vector field, the Liouville condition
``invariant_density``       div(rho F) = 0 for a density rho
``position_density``        the condition for a density of the positions alone
``momentum_equation``       the non-holonomic momentum equation of a symmetry
``horizontal_combinations`` the combinations of symmetries that lie in the distribution
==========================  ============================================================

Only SymPy and mpmath are used; the core never imports this package.

>>> import whittaker_teach as wt
>>> from whittaker_teach import geometry as geo
>>> nb = geo.nonholonomic_bracket(wt.examples.sledge())
>>> nb.structure.jacobiator(*nb.symbols("x", "p_x", "p_theta"))
tan(theta)
"""

from .bracket import AlmostPoisson, NonholonomicBracket, nonholonomic_bracket, rescaled
from .connection import Connection, connection
from .measure import divergence, invariant_density, position_density
from .momentum import MomentumEquation, horizontal_combinations, momentum_equation

__all__ = ["Connection", "connection", "AlmostPoisson", "NonholonomicBracket",
           "nonholonomic_bracket", "rescaled", "divergence", "invariant_density",
           "position_density", "MomentumEquation", "momentum_equation", "horizontal_combinations"]
