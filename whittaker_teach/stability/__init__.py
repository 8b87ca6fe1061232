"""Stability of steady motions of a Chaplygin system (chapter "Stability of steady
motions" of the book).

==========================  ============================================================
``cyclic_coordinates``      the coordinates absent from the accelerations [1.4a]
``steady_motion``           a steady motion (shape coordinates fixed, cyclic ones
                            turning at constant velocities), checked to be one
``find_steady_motions``     the steady motions ``sympy.solve`` finds for given unknowns
``linearize``               the linearisation of (1.4) about a steady motion
``linearize_reduced``       the linearisation of (1.26) about its path
``compare``                 the two agree: lambda = v_eps mu, plus one lambda = 0
``classify``                Lyapunov's first method, saying when it decides nothing
``family_dimension``        the dimension of the manifold of steady motions through
                            a point (rank of the equilibrium conditions), when
                            it can be decided
``routh``                   Routh's method for a cyclic coordinate with a conserved
                            momentum: the Routhian and the effective potential
``conserved``               is an expression an integral of (1.4)? (exact or 40 digits)
``tilting_disk``            the rolling disk in 3-D (sympy.physics.mechanics input)
==========================  ============================================================

Only SymPy and mpmath are used; nothing here imports the numerics.

>>> import sympy as sp
>>> import whittaker_teach as wt
>>> from whittaker_teach import stability as st
>>> v = sp.Symbol("v", negative=True)
>>> sm = st.steady_motion(wt.examples.offset_sleigh(), {"theta": 0}, {"x": v})
>>> st.classify(st.linearize(sm)).verdict
'unstable'
"""

from .classify import (Classification, FamilyDimension, classify, family_dimension,
                       hurwitz_conditions)
from .linear import LAMBDA, MU, Linearization, compare, linearize, linearize_reduced
from .routh import Routhian, routh
from .models import tilting_disk
from .steady import (SteadyMotion, conserved, cyclic_coordinates, find_steady_motions,
                     steady_motion)

__all__ = ["SteadyMotion", "steady_motion", "find_steady_motions", "cyclic_coordinates",
           "Linearization", "linearize", "linearize_reduced", "compare", "LAMBDA", "MU",
           "Classification", "classify", "hurwitz_conditions", "FamilyDimension",
           "family_dimension", "Routhian", "routh",
           "conserved", "tilting_disk"]
