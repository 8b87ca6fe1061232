"""Rolling bodies in three dimensions (chapter "Rolling bodies in three dimensions").

==========================  ============================================================
``tilting_disk``            the rolling disk (:func:`whittaker_teach.stability.tilting_disk`,
                            sympy.physics.mechanics input), reused here
``chaplygin_ball``          the balanced ball with unequal moments (Chaplygin 1903), built
                            with sympy.physics.mechanics, x and y dependent
``contact_momentum``        its angular momentum about the contact point
``BallVectors``             the ball in (M, gamma): integrals, Chaplygin's density
``rattleback``              the rattleback with a paraboloidal bottom, mechanics input
``RattlebackVectors``       its Newton-Euler equations in (omega, gamma) and their
                            linearisation about the steady spin
``spin_rates``              the eigenvalues of that linearisation at numbers
``euler_vectors``           omega and gamma in the mechanics model's angles
``rattleback_animation``    an offline HTML animation from a simulation
==========================  ============================================================

The builders use SymPy only (they run in the in-browser site); the simulations are in
``whittaker_teach.rolling.simulate`` (numpy, scipy), never imported from here.

>>> from whittaker_teach import rolling
>>> rolling.chaplygin_ball().name
'chaplygin_ball'
"""

from importlib import import_module

__all__ = ["tilting_disk", "chaplygin_ball", "contact_momentum", "BallVectors",
           "rattleback", "RattlebackVectors", "spin_rates", "euler_vectors",
           "rattleback_animation"]

_LAZY = {
    "tilting_disk": ("..stability.models", "tilting_disk"),
    "chaplygin_ball": (".ball", "chaplygin_ball"),
    "contact_momentum": (".ball", "contact_momentum"),
    "BallVectors": (".ball", "BallVectors"),
    "rattleback": (".rattleback_model", "rattleback"),
    "RattlebackVectors": (".rattleback_model", "RattlebackVectors"),
    "spin_rates": (".rattleback_model", "spin_rates"),
    "rattleback_animation": (".animation", "rattleback_animation"),
    "euler_vectors": (".rattleback_model", "euler_vectors"),
}


def __getattr__(name):
    if name in _LAZY:
        module, attr = _LAZY[name]
        value = getattr(import_module(module, __name__), attr)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'whittaker_teach.rolling' has no attribute {name!r}")


def __dir__():
    return sorted(set(globals()) | set(__all__))
