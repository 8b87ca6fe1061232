"""Routh's method for a cyclic coordinate: the Routhian and the effective potential.

Routh's method needs the momentum of the cyclic coordinate, p_c = dL~/dqdot_c, to
be an **integral** of (1.4), and the other equations of (1.4) to be Lagrange's
equations of the Routhian R = (L~ - c qdot_c) at p_c = c.  Both hold for a
holonomic system with a cyclic coordinate; for a non-holonomic one the constraint
terms of (1.4) usually break the first (the sledge's x, the sleigh's x).  The
library checks both (exactly or at 40 digits) and refuses with a ModelError when
either fails.  Then the steady motions with momentum c are the critical points of
the **effective potential** V_eff = -R at zero shape velocities, and a strict
minimum is stable (Routh's theorem: V_eff + the kinetic part of R is an integral).

>>> import whittaker_teach as wt
>>> r = routh(wt.examples.kepler(), "theta")
>>> r.effective_potential
c**2/(2*m*r(t)**2) - m*mu/r(t)
"""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp

from ..errors import ModelError
from ..verify import check_zero
from .steady import _coordinate, _plain, _require_system, cyclic_coordinates, sampler

__all__ = ["Routhian", "routh"]


@dataclass(frozen=True)
class Routhian:
    """``routhian`` R (in the other coordinates and velocities, and ``momentum`` c),
    ``effective_potential`` -R at zero velocities, ``velocity`` qdot_c in terms of c,
    ``cyclic`` the coordinate, ``coordinates`` the others."""

    system: object
    cyclic: object
    momentum: sp.Symbol
    velocity: sp.Expr
    routhian: sp.Expr
    effective_potential: sp.Expr
    coordinates: list

    def critical_points(self, coordinate=None):
        """The values of ``coordinate`` (default: the only other coordinate) where
        dV_eff/dq = 0 (``sympy.solve``: those it finds), each with V_eff''.

        >>> import whittaker_teach as wt
        >>> routh(wt.examples.kepler(), "theta").critical_points()
        [(c**2/(m**2*mu), m**7*mu**4/c**6)]
        """
        if coordinate is None:
            if len(self.coordinates) != 1:
                raise ModelError("name the coordinate: the Routhian has "
                                 f"{len(self.coordinates)} other coordinates")
            q = self.coordinates[0]
        else:
            q = _coordinate(self.system, coordinate)
        s = sp.Dummy(q.func.__name__, real=True)
        V = self.effective_potential.xreplace({q: s})
        d1 = sp.diff(V, s)
        d2 = sp.diff(V, s, 2)
        out = []
        for r in sp.solve(d1, s):
            if r.is_real is False:
                continue
            out.append((r, sp.factor(sp.cancel(d2.subs(s, r)))))
        return out


def _collected(e):
    """e expanded and collected in the coordinates and velocities, coefficients factored."""
    e = sp.expand(e)
    keys = sorted(e.atoms(sp.Derivative) | {a for a in e.atoms(sp.Function)
                                             if isinstance(a, sp.core.function.AppliedUndef)},
                  key=sp.default_sort_key)
    return sp.collect(e, keys, sp.factor) if keys else sp.factor(e)


def routh(system, cyclic, momentum=None):
    """The Routhian of ``system`` for the ``cyclic`` coordinate (a coordinate or its
    name), with the momentum symbol ``momentum`` (default ``c``).

    ModelError when the coordinate is not cyclic in [1.4a], when its momentum
    dL~/dqdot_c is not conserved along (1.4), when dL~/dqdot_c = c cannot be solved
    for qdot_c uniquely, or when the other equations of (1.4) are not Lagrange's
    equations of R.

    >>> import whittaker_teach as wt
    >>> routh(wt.examples.sledge(), "x")
    Traceback (most recent call last):
    ...
    whittaker_teach.errors.ModelError: the momentum of x, m*Derivative(x(t), t)/cos(theta(t))**2, is not conserved along (1.4): the constraint terms of (1.4) act along x, and Routh's method does not apply
    """
    _require_system(system)
    q = _coordinate(system, cyclic)
    if momentum is None:
        momentum = sp.Symbol("c", real=True)
    if not isinstance(momentum, sp.Symbol):
        raise ModelError(f"momentum must be a SymPy Symbol, got {momentum!r}")
    if q not in cyclic_coordinates(system):
        raise ModelError(f"{q.func.__name__} is not cyclic: it appears in the accelerations [1.4a]")
    t = system.coordinates[0].args[0]
    Lt = system.L_tilde
    Q, V, rep = _plain(system)
    if sp.count_ops(Lt) < 400:
        Lt = sp.trigsimp(Lt)             # sin^2 + cos^2 as built by the constraints
    if Q[q] in Lt.xreplace(rep).free_symbols:
        raise ModelError(f"L~ contains {q.func.__name__}: it is not cyclic in L~")
    p = Lt.diff(q.diff(t))
    acc = system.accelerations()
    rate = p.diff(t).subs(acc)
    rate_plain = rate.xreplace(rep)
    if rate_plain != 0:
        chk = check_zero("momentum", "dp/dt = 0", rate_plain, sampler(rate_plain.free_symbols))
        if not chk.holds:
            raise ModelError(f"the momentum of {q.func.__name__}, {sp.factor(p)}, is not conserved "
                             f"along (1.4): the constraint terms of (1.4) act along "
                             f"{q.func.__name__}, and Routh's method does not apply")
    sols = sp.solve(sp.Eq(p, momentum), q.diff(t))
    if len(sols) != 1:
        raise ModelError(f"dL~/d{q.func.__name__}dot = {momentum} has {len(sols)} solutions for "
                         f"{q.func.__name__}dot: Routh's method needs exactly one")
    qd = sp.factor(sols[0])
    R = _collected((Lt - momentum * q.diff(t)).subs(q.diff(t), qd))
    others = [c for c in system.independent_coordinates if c != q]
    # the other equations of (1.4) must be Lagrange's equations of R
    eom = dict(zip(system.independent_coordinates, system.equations_of_motion()))
    for c in others:
        el = R.diff(c.diff(t)).diff(t) - R.diff(c)
        # on the motion p = c: compare with (1.4)'s expression for c, the momentum substituted
        diff = (el - eom[c]).subs(momentum, p)
        diff = diff.subs({a: b for a, b in acc.items() if a.args[0] != q}).subs(acc)
        dp = diff.xreplace(rep)
        if dp != 0 and sp.cancel(dp) != 0:
            chk = check_zero("routh", "Lagrange's equation of R", dp, sampler(dp.free_symbols))
            if not chk.holds:
                raise ModelError(f"the equation of {c.func.__name__} in (1.4) is not Lagrange's "
                                 "equation of the Routhian (constraint terms remain): Routh's "
                                 "method does not apply")
    Veff = _collected(-R.subs({c.diff(t): 0 for c in others}))
    return Routhian(system, q, momentum, qd, R, Veff, others)
