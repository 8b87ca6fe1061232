"""The sledge's exact motion (3.15), for checking the numerics.

``sledge_exact(params, a=..., phi=..., C=...)`` returns a callable t -> {x, y,
theta, xdot, ydot, thetadot}, in closed form through the Jacobi-Anger
expansion (see :mod:`whittaker_teach.numerics.exact`).  NumPy and SciPy are
imported on the first call, not when ``examples`` is imported.

>>> from whittaker_teach.examples import sledge_exact
>>> ex = sledge_exact({"m": 1, "J": 4, "k": 2}, a=0.3, phi=0.0, C=2.0)
>>> ex.omega, ex(0.0)["xdot"] == 2.0 * __import__("math").cos(0.3)
(1.0, True)
"""

__all__ = ["sledge_exact"]


def sledge_exact(params, a=None, phi=0.0, C=1.0, **kw):
    """The exact sledge motion with amplitude ``a`` (or energy ``h=``), phase ``phi``,
    speed ``C``; ``params`` = {m, J, k}.  Keywords: ``h``, ``x0``, ``y0``, ``t0``."""
    from ..numerics.exact import SledgeExact
    return SledgeExact(params, a, phi, C, **kw)
