"""Numerics: the full, reduced and exact models, integrated and compared.

One entry per model.  An entry checks its input once, up front
(``validate``), then asks ``codegen`` for the compiled model (generated on
first use, cached), which gives the initial state and the right-hand side,
and ``ivp`` integrates; nothing calls back into an entry:

==========================  ====================================================
``time_model``              entry: the full model in t, ``ChaplyginSystem.simulate``
``reduced_model``           entry: the reduced model (1.26) in q_eps, ``Reduction.simulate``
``integrators``             entry: the discrete Lagrange-d'Alembert integrator (``method="DLA"``)
``fixed_step``               Euler, midpoint and RK4 with a fixed step: orders, stability (chapter 15)
``exact``                   entry: the sledge in closed form (Bessel functions)
``scene``                   ``simulate(..., tol=...)``: picks the model and the method
``validate``                every check of the numerical input (ModelError naming the mistake)
``codegen``                 the compiled models: equations as Python functions, initial states
``ivp``                     one call of scipy's ``solve_ivp``; zeros inside steps
``portable``                arithmetic with the same bits on every processor: RK steps, solves
``results``                 what a simulation returns: ``Trajectory``, ``Path``, ``Choice``
``work_precision``          speed against error: ``python -m whittaker_teach bench numerics``
``hard_cases``              the hard cases, each run and judged
``figures``                 regenerates the book's stored results (``make bench``)
==========================  ====================================================

Imports run one way: ``scene`` -> (``exact``, ``validate``, ``results``);
entries -> (``validate``, ``codegen``, ``ivp``, ``results``); ``time_model`` ->
``integrators`` for ``method="DLA"``; ``portable`` is a leaf (it imports nothing of
the package) used by ``ivp``, ``codegen``, ``integrators`` and ``exact``.  No circles
(tested).  Numerics builds on the symbolic core and the core imports none of it:
``simulate`` below is registered with :mod:`whittaker_teach.backends`, where
``ChaplyginSystem.simulate`` and ``Reduction.simulate`` find it
(``tests/unit/test_import_graph.py``).  A call of ``system.simulate`` crosses from one module to another five times
(``scripts/trace_numerics.py`` counts them; tested).  Importing this package imports
none of them (nor numpy or scipy), but it checks that they are installed: they are the ``[numerics]`` extra
(``pip install "whittaker-teach[numerics]"``), which the symbolic core does not
need and the in-browser site (Pyodide) does not have. Without them every
numerics entry point (``simulate``, ``examples.sledge_exact``,
``bench numerics``) raises :class:`MissingExtraError`, an ``ImportError``
that names the extra.
"""

from importlib import import_module
from importlib.util import find_spec

#: the modules of the ``[numerics]`` extra (tqdm only for ``bench numerics``)
EXTRA_MODULES = ("numpy", "scipy")


class MissingExtraError(ImportError):
    """A numerics entry point was used without the ``[numerics]`` extra."""


def require_extra(modules=EXTRA_MODULES, what="whittaker_teach.numerics"):
    """Raise :class:`MissingExtraError` naming the extra if a module is missing.

    >>> require_extra(())          # nothing to check: returns None
    """
    missing = [m for m in modules if find_spec(m) is None]
    if missing:
        raise MissingExtraError(
            f"{what} needs {', '.join(missing)}, which are not installed: they are "
            f"the [numerics] extra of whittaker-teach (pip install "
            f"\"whittaker-teach[numerics]\"; `make setup` installs it). The "
            f"symbolic core (derivations, checks, exercises) works without them; "
            f"in the browser (Pyodide) numerics run only in a local install "
            f"(`make book`).",
            name=missing[0])


require_extra()


def simulate(obj, *args, **options):
    """``ChaplyginSystem.simulate`` and ``Reduction.simulate``: the full model in t
    (``time_model``), the reduced model (1.26) in q_eps (``reduced_model``), or with
    ``tol=`` the model and method the package picks (``scene``).  Registered with the
    core (:mod:`whittaker_teach.backends`), which imports nothing of numerics."""
    from ..reduction import Reduction
    if options.get("tol") is not None:      # the package picks the model and method
        from .scene import simulate_within
        *head, method, rtol, atol = args
        return simulate_within(obj, *head, method=method, rtol=rtol, atol=atol, **options)
    options.pop("tol", None)
    if isinstance(obj, Reduction):
        from .reduced_model import simulate as entry
    else:
        from .time_model import simulate as entry
    return entry(obj, *args, **options)


def _register():
    from ..backends import register
    register("simulate", simulate)


_register()

__all__ = ["MissingExtraError", "require_extra", "simulate", "codegen", "time_model", "reduced_model",
           "integrators", "exact", "scene",
           "work_precision", "hard_cases", "results", "validate", "figures", "ivp",
           "fixed_step"]


def __getattr__(name):
    if name in __all__:
        mod = import_module(f".{name}", __name__)
        globals()[name] = mod
        return mod
    raise AttributeError(f"module 'whittaker_teach.numerics' has no attribute {name!r}")
