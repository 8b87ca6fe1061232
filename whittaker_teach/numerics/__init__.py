"""Numerics: the full, reduced and exact models, integrated and compared.

==========================  ====================================================
``codegen``                 the symbolic core's equations as Python functions
``time_model``              the full model (1.4) in t: ``ChaplyginSystem.simulate``
``reduced_model``           the reduced model (1.26) in q_eps: ``Reduction.simulate``
``integrators``             the discrete Lagrange-d'Alembert integrator (``method="DLA"``)
``exact``                   the sledge in closed form (Bessel functions)
``work_precision``          speed against error: ``python -m whittaker_teach bench numerics``
``hard_cases``              the hard cases, each run and judged
``figures``                 regenerates the book's stored results (``make bench``)
==========================  ====================================================

Importing this package imports none of them (nor numpy or scipy).
"""

from importlib import import_module

__all__ = ["codegen", "time_model", "reduced_model", "integrators", "exact",
           "work_precision", "hard_cases", "results", "validate", "figures", "ivp"]


def __getattr__(name):
    if name in __all__:
        mod = import_module(f".{name}", __name__)
        globals()[name] = mod
        return mod
    raise AttributeError(f"module 'whittaker_teach.numerics' has no attribute {name!r}")
