"""whittaker-teach: the generalized Whittaker equations of Mei (1983), derived,
printed and checked step by step with SymPy, for any Chaplygin-type system.

>>> import whittaker_teach as wt
>>> sledge = wt.examples.sledge()
>>> red = sledge.reduce("x", direction=+1)
>>> red.steps["1.16"].status
'verified'

Importing the package is cheap: SymPy and the modules that use it are
loaded on first use of ``ChaplyginSystem``, ``examples`` and the rest.
The classical forms of the equations of motion are in ``whittaker_teach.forms``.
"""

from importlib import import_module

from .errors import ChartError, ModelError, ModelTypeError

__version__ = "0.1.0"

__all__ = [
    "ChaplyginSystem",
    "Reduction",
    "Step",
    "Derivation",
    "Check",
    "Report",
    "ModelError",
    "ModelTypeError",
    "ChartError",
    "examples",
    "exercises",
    "__version__",
]

_LAZY = {
    "ChaplyginSystem": ("system", "ChaplyginSystem"),
    "Reduction": ("reduction", "Reduction"),
    "Step": ("steps", "Step"),
    "Derivation": ("steps", "Derivation"),
    "Report": ("steps", "Report"),
    "Check": ("verify", "Check"),
    "examples": ("examples", None),
    "exercises": ("exercises", None),
}


def __getattr__(name):
    if name in _LAZY:
        module, attr = _LAZY[name]
        mod = import_module(f".{module}", __name__)
        value = mod if attr is None else getattr(mod, attr)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'whittaker_teach' has no attribute {name!r}")


def __dir__():
    return sorted(set(globals()) | set(__all__))
