"""The sledge of section 3 of Mei (1983), with a torsional spring.

The projection of the centre on the plane coincides with the contact point;
the runner cannot slide sideways, so ydot = xdot tan(theta) (3.2).

>>> from whittaker_teach.examples import sledge
>>> s = sledge()
>>> s.lagrangian
J*Derivative(theta(t), t)**2/2 - k**2*theta(t)**2/2 + m*(Derivative(x(t), t)**2 + Derivative(y(t), t)**2)/2
"""

import sympy as sp
from ..coordinates import dynamicsymbols

from ..system import ChaplyginSystem

__all__ = ["sledge"]


def sledge():
    """The section 3 system: L (3.1) and the constraint (3.2)."""
    t = dynamicsymbols._t
    m, J, k = sp.symbols("m J k", positive=True)
    x, th, y = dynamicsymbols("x theta y")
    L = m / 2 * (x.diff(t)**2 + y.diff(t)**2) + J / 2 * th.diff(t)**2 - k**2 * th**2 / 2
    return ChaplyginSystem(L, [x, th, y], dependent={y.diff(t): x.diff(t) * sp.tan(th)},
                           name="sledge")


def section3(direction=+1, reduction=None):
    """Section 3 of the paper, (3.1)-(3.15), derived for the sledge and checked.

    Each printed formula of the paper is compared with what the library
    derives; where the OCR text differs from the mathematics (3.5, 3.9, 3.10,
    the line before 3.14) the step shows the correct form and a check that the
    printed one fails.  Pass ``reduction`` (the sledge reduced in x) to reuse it.

    >>> d = section3()
    >>> d["3.10"].status, d["3.11"].status
    ('verified', 'verified')
    """
    from ._section3 import section3_steps
    from ..steps import Derivation
    from ..verify import shared_points
    red = reduction if reduction is not None else sledge().reduce("x", direction)
    with shared_points():       # the checks share their random points and values there
        steps = section3_steps(red)
    return Derivation("Mei (1983), section 3: the sledge", steps)
