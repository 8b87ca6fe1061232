"""Invariant measures: the divergence of a vector field and Liouville's condition.

A measure rho(z) dz is invariant under the flow of zdot = F(z) when div(rho F) = 0.
For the reduced system of a Chaplygin system in (q, p) (:func:`~.bracket.nonholonomic_bracket`)
a density of the positions alone, rho(q), needs -div F = d ln(rho)/dt = sum_sigma
(d ln rho/d q_sigma) qdot_sigma along the motion: -div F, written in the velocities,
must be a one-form sum c_sigma(q) qdot_sigma whose coefficients are a gradient, hence
closed, dc_sigma/dq_tau = dc_tau/dq_sigma (:func:`position_density`).

>>> import whittaker_teach as wt
>>> from whittaker_teach.geometry import nonholonomic_bracket
>>> nb = nonholonomic_bracket(wt.examples.sledge())
>>> x, th = nb.q
>>> invariant_density(nb.vector_field(), nb.coordinates, sp.cos(th)).holds
True
"""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp

from ..errors import ModelError, ModelTypeError
from ..verify import Check
from ._plain import zero

__all__ = ["divergence", "invariant_density", "position_density", "PositionDensity"]


def _field(F, z):
    F, z = list(F), list(z)
    if len(F) != len(z):
        raise ModelError(f"the vector field has {len(F)} components and there are {len(z)} "
                         "variables: one component per variable")
    if not all(isinstance(s, sp.Symbol) for s in z):
        raise ModelTypeError("the variables must be SymPy Symbols")
    return [sp.sympify(f) for f in F], z


def divergence(F, z):
    """sum_i dF_i/dz_i.

    >>> q, p = sp.symbols("q p")
    >>> divergence([p, -q - p], [q, p])
    -1
    """
    F, z = _field(F, z)
    return sp.Add(*[f.diff(s) for f, s in zip(F, z)])


def invariant_density(F, z, rho):
    """Check Liouville's condition div(rho F) = 0 (exact, or 40 digits)."""
    F, z = _field(F, z)
    rho = sp.sympify(rho)
    if rho == 0:
        raise ModelError("the density rho is 0: an invariant measure needs rho > 0")
    return zero("Liouville", "div(rho F) = 0", [divergence([rho * f for f in F], z)])


@dataclass(frozen=True)
class PositionDensity:
    """-div F = sum c_sigma qdot_sigma: ``one_form`` {q: c_sigma}, ``is_one_form`` (the
    Check that -div F is that sum, with nothing left over), ``curl`` {(q_sigma, q_tau):
    dc_tau/dq_sigma - dc_sigma/dq_tau} and ``closed`` (the Check that the curl vanishes:
    then rho = exp(integral of c) is a density of the positions alone, locally)."""

    minus_div: sp.Expr
    one_form: dict
    is_one_form: Check
    curl: dict
    closed: Check

    @property
    def exists(self):
        """True when both checks hold (a density rho(q) exists locally)."""
        return bool(self.is_one_form.holds and self.closed.holds)


def position_density(nb):
    """The condition for an invariant density of the positions alone (see the module)
    for the reduced system ``nb`` (a NonholonomicBracket), worked in the velocities."""
    from .bracket import NonholonomicBracket
    if not isinstance(nb, NonholonomicBracket):
        raise ModelTypeError(f"expected a NonholonomicBracket, got {type(nb).__name__}")
    ch = nb.chart
    vs = [ch.v[c] for c in ch.independent]
    to_v = {p: nb.momenta[c] for p, c in zip(nb.p, ch.independent)}
    md = (-divergence(nb.vector_field(), nb.coordinates)).xreplace(to_v)
    c = {q: md.diff(v) for q, v in zip(nb.q, vs)}
    rest = md - sp.Add(*[c[q] * v for q, v in zip(nb.q, vs)])
    is_form = zero("one-form", "-div F = sum c qdot", [rest] + [e.diff(v) for e in c.values()
                                                               for v in vs])
    curl = {(a, b): c[b].diff(a) - c[a].diff(b) for i, a in enumerate(nb.q)
            for b in nb.q[i + 1:]}
    closed = zero("closed", "dc = 0", list(curl.values()) or [sp.S.Zero])
    return PositionDensity(md, c, is_form, curl, closed)
