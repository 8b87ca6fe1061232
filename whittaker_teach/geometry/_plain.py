"""Plain symbols for a :class:`~whittaker_teach.system.ChaplyginSystem` (shared by the
geometry modules): each coordinate q(t) a real Symbol ``q``, its velocity ``qdot``, its
acceleration ``qddot`` (SymPy prints ``thetadot`` as a dotted theta), and the constraint
coefficients b_(beta sigma)(q) of a constraint linear in the velocities."""

from __future__ import annotations

import sympy as sp

from ..errors import ModelError, ModelTypeError
from ..system import ChaplyginSystem
from ..verify import check_zero

__all__ = ["Plain", "require_system", "sampler"]


def require_system(system):
    if not isinstance(system, ChaplyginSystem):
        raise ModelTypeError(f"expected a ChaplyginSystem (whittaker_teach.ChaplyginSystem), "
                             f"got {type(system).__name__}")
    return system


def _value(s, rng):
    if s.is_positive:
        return rng.uniform(0.5, 2.0)
    if s.is_negative:
        return -rng.uniform(0.5, 2.0)
    return rng.uniform(-1.2, 1.2)


def sampler(symbols):
    """``sample(rng)`` for :func:`~whittaker_teach.verify.check_zero`: positive symbols
    in (0.5, 2), negative ones in (-2, -0.5), the others in (-1.2, 1.2)."""
    symbols = sorted(set(symbols), key=str)
    return lambda rng: {s: _value(s, rng) for s in symbols}


def zero(label, claim, exprs):
    """``check_zero`` on ``exprs`` with :func:`sampler` over their free symbols."""
    exprs = list(exprs) if isinstance(exprs, (list, tuple)) else [exprs]
    free = set().union(*(sp.sympify(e).free_symbols for e in exprs)) if exprs else set()
    return check_zero(label, claim, exprs, sampler(free))


def _name(c):
    return c.func.__name__


class Plain:
    """The system's coordinates as plain symbols.

    ``q[c]``, ``v[c]``, ``a[c]`` (coordinate, velocity, acceleration of the dynamicsymbol
    ``c``); :meth:`plain` rewrites an expression of dynamicsymbols in them, :meth:`public`
    back.  ``b[beta][sigma]``: the coefficient of qdot_sigma in the constraint for the
    dependent velocity qdot_(eps+beta) (ModelError when a constraint is not linear in the
    velocities: then there is no distribution, and no connection).
    """

    def __init__(self, system):
        self.system = require_system(system)
        t = system.coordinates[0].args[0]
        self.t = t
        self.coordinates = list(system.coordinates)
        self.independent = list(system.independent_coordinates)
        self.dependent = list(system.dependent_coordinates)
        self.q = {c: sp.Symbol(_name(c), real=True) for c in self.coordinates}
        self.v = {c: sp.Symbol(_name(c) + "dot", real=True) for c in self.coordinates}
        self.a = {c: sp.Symbol(_name(c) + "ddot", real=True) for c in self.coordinates}
        self._to = {}
        for c in self.coordinates:
            self._to[sp.Derivative(c, (t, 2))] = self.a[c]
            self._to[sp.Derivative(c, t)] = self.v[c]
            self._to[c] = self.q[c]
        self._back = {v: k for k, v in self._to.items()}
        self.parameters = list(system.parameters)
        self.phi = {c: self.plain(system.constraints[c.diff(t)]) for c in self.dependent}
        self.b = self._coefficients()

    def plain(self, expr):
        """``expr`` (dynamicsymbols) in the plain symbols."""
        return sp.sympify(expr).xreplace(self._to)

    def public(self, expr):
        """``expr`` (plain symbols) in dynamicsymbols."""
        return sp.sympify(expr).xreplace(self._back)

    def _coefficients(self):
        vs = [self.v[c] for c in self.independent]
        out = {}
        for d in self.dependent:
            phi = self.phi[d]
            row = {c: phi.diff(self.v[c]) for c in self.independent}
            rest = sp.expand(phi - sum(row[c] * self.v[c] for c in self.independent))
            second = [row[c].diff(w) for c in self.independent for w in vs]
            if rest != 0 or any(e != 0 for e in second):
                chk = zero("linear", "", [phi - sum(row[c] * self.v[c] for c in self.independent)]
                           + second)
                if not chk.holds:
                    raise ModelError(
                        f"the constraint {_name(d)}dot = {self.public(phi)} is not linear in the "
                        "velocities: the geometry of this chapter (a distribution, its connection "
                        "and curvature) needs qdot_(eps+beta) = sum b_(beta sigma)(q) qdot_sigma")
            out[d] = row
        return out

    def sample(self, exprs):
        """A sampler for the free symbols of ``exprs``."""
        exprs = exprs if isinstance(exprs, (list, tuple)) else [exprs]
        return sampler(set().union(*(sp.sympify(e).free_symbols for e in exprs)))
