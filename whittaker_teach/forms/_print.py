"""How the forms name what they show, and one targeted rewrite of their results.

:func:`indexed` names a quantity with coordinates as indices (C_{x psi}, the
y-component of the bracket [X_x, X_theta]): each index printed as the coordinate is, a
Greek name as a Greek letter, in LaTeX and in Unicode (a Symbol named ``"C_x,psi"``
would print ``C_{x,psi}``).  :func:`tidy` reads sin^2 u + cos^2 u as 1 where that
shortens a result.

>>> import sympy as sp
>>> x, th = sp.symbols("x theta")
>>> C = indexed("C", [x, th])
>>> print(sp.latex(C), sp.pretty(C))
C_{x\\theta} C_(x,θ)
>>> K = bracket(x, th, sp.Symbol("y"))
>>> print(sp.latex(K), sp.pretty(K))
{}[X_{x}, X_{\\theta}]^{y} [X_x, X_θ]^y
>>> tidy((-sp.sin(th)**2 - sp.cos(th)**2)/sp.cos(th)**2)
-1/cos(theta)**2
"""

from __future__ import annotations

import re

import sympy as sp

from ..rewrite import rational
from ..steps import notation, tex, text

__all__ = ["indexed", "bracket", "tidy"]

#: an index that needs no separator in LaTeX: one letter or one control word (\theta)
_ONE = re.compile(r"^([A-Za-z0-9]|\\[A-Za-z]+)$")


def _names(i):
    """(Unicode, LaTeX) of an index: a symbol as it prints, anything else as written."""
    if isinstance(i, sp.Basic):
        return text(i, use_unicode=True), tex(i)
    return str(i), str(i)


def indexed(base, subs=(), sup=None, base_tex=None, sep=""):
    """The symbol ``base`` with the subscripts ``subs`` (and superscript ``sup``), each a
    symbol printed as it prints alone (theta as a Greek letter) or a string: a
    :class:`~whittaker_teach.steps.Notation`.  In LaTeX the subscripts are joined by
    ``sep`` (a comma where one of them is longer than a letter); in Unicode
    ``base_i`` for one short index, ``base_(i,j)`` otherwise."""
    su = [_names(s) for s in subs]
    u, t = base, base_tex or base
    if sup is not None:
        a, b = _names(sup)
        u += "^" + a
        t += "^{" + b + "}"
    if su:
        if len(su) == 1 and len(su[0][0]) == 1:
            u += "_" + su[0][0]
        else:
            u += "_(" + ",".join(a for a, _ in su) + ")"
        if not all(_ONE.match(b) for _, b in su):
            sep = ","
        t += "_{" + sep.join(b for _, b in su) + "}"
    return notation(u, t)


def bracket(a, b, c):
    """The ``c``-component of the bracket [X_a, X_b], printed [X_a, X_b]^c (in LaTeX led by
    an empty group: a display row, or an aligned block, must not begin with "[")."""
    (ua, ta), (ub, tb), (uc, tc) = _names(a), _names(b), _names(c)
    return notation(f"[X_{ua}, X_{ub}]^{uc}", f"{{}}[X_{{{ta}}}, X_{{{tb}}}]^{{{tc}}}")


#: above this many operations a result is shown as it is (the rewrite is for reading)
TIDY_OPS_LIMIT = 320


def _trig_args(e):
    """The arguments u of which both sin(u) and cos(u) occur in ``e``."""
    s = {f.args[0] for f in e.atoms(sp.sin)}
    return [u for u in sorted(s & {f.args[0] for f in e.atoms(sp.cos)}, key=sp.default_sort_key)]


def _rewrites(p, u):
    """``p`` with every even power of sin(u) (resp. cos(u)) written in the other:
    sin^2 = 1 - cos^2, expanded."""
    out = []
    for f, g in ((sp.sin(u), sp.cos(u)), (sp.cos(u), sp.sin(u))):
        def lower(w, f=f, g=g):
            return (1 - g**2)**(w.exp // 2) * f**(w.exp % 2)
        r = p.replace(lambda w: w.is_Pow and w.base == f and w.exp.is_Integer and w.exp >= 2,
                      lower)
        if r != p:
            out.append(sp.expand(r))
    return out


def _shortest(p, args):
    best = p
    for u in args:
        for r in _rewrites(best, u):
            if sp.count_ops(r) < sp.count_ops(best):
                best = r
    return best


def tidy(e, symbols=()):
    """``e`` as one fraction (:func:`~whittaker_teach.rewrite.rational`, collected on
    ``symbols``), with sin^2 u + cos^2 u read as 1 where that shortens it: in the
    numerator and the denominator, the even powers of sin(u) are written with cos(u)
    (or the other way) and expanded, and the shorter kept.  A targeted rewrite, exact
    and bounded (above ``TIDY_OPS_LIMIT`` operations only ``rational``)."""
    r = rational(e, symbols)
    args = _trig_args(r)
    if not args or sp.count_ops(r) > TIDY_OPS_LIMIT:
        return r
    num, den = sp.fraction(r)
    n2, d2 = _shortest(num, args), _shortest(den, args)
    if (n2, d2) == (num, den):
        return r
    t = rational(n2 / d2, symbols)
    return t if sp.count_ops(t) < sp.count_ops(r) else r
