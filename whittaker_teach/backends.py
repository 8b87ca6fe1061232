"""Numerical back-ends of the symbolic core: registered by the package that provides them.

The symbolic core (every module of ``whittaker_teach`` outside ``numerics/``)
imports nothing of :mod:`whittaker_teach.numerics`: numerics builds on the
core, never the other way round (``tests/unit/test_import_graph.py`` checks
the import graph).  ``ChaplyginSystem.simulate`` and ``Reduction.simulate``
call the function registered here under their name; the numerics package
registers its entries when it is imported (``numerics/__init__.py``).  When
nothing is registered yet, the provider is loaded by its name, ``PROVIDER``
(as a plug-in is: the core knows a name, not a module), so that
``sledge.simulate(...)`` works without a prior ``import whittaker_teach.numerics``;
without numpy and scipy that load raises the numerics package's
``MissingExtraError``, which names the ``[numerics]`` extra.

>>> register("example", lambda: "ran")
>>> provided("example")()
'ran'
>>> del _REGISTRY["example"]
"""

from __future__ import annotations

from importlib import import_module

__all__ = ["PROVIDER", "register", "provided"]

#: the package that registers the numerical back-ends (loaded by name on first use)
PROVIDER = "whittaker_teach.numerics"

_REGISTRY = {}


def register(name, function):
    """Make ``function`` the back-end called ``name`` (a provider calls this on import)."""
    _REGISTRY[name] = function


def provided(name):
    """The back-end called ``name``, loading ``PROVIDER`` first if it is not registered."""
    if name not in _REGISTRY:
        import_module(PROVIDER)
    try:
        return _REGISTRY[name]
    except KeyError:
        raise LookupError(f"no numerical back-end {name!r}: {PROVIDER} did not register "
                          "one") from None
