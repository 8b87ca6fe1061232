"""The non-holonomic momentum equation (Bloch, Krishnaprasad, Marsden and Murray 1996).

Let X_1, ..., X_k be vector fields on the configuration space that are symmetries:
L and the constraints are invariant under their flows.  A symmetry X_i need not lie
in the distribution D (the translation d/dx of the sledge does not): then the reaction
of the constraints has a component along it and the Noether momentum dL/dqdot . X_i is
in general not conserved.  A combination xi = sum_i c_i(q) X_i that does lie in D at
every q gives the momentum J = dL/dqdot . xi, and along the motion

    dJ/dt = sum_i (dc_i/dt) dL/dqdot . X_i          (the momentum equation),

since X_i L = 0 and the reaction does no work on xi (it lies in D).
:meth:`MomentumEquation.check` compares it with the library's (1.4).

>>> import sympy as sp
>>> import whittaker_teach as wt
>>> s = wt.examples.offset_sleigh()
>>> x, th, y = s.coordinates
>>> me = momentum_equation(s, [{x: 1}, {y: 1}], [sp.cos(th), sp.sin(th)])
>>> sp.simplify(me.momentum), sp.simplify(me.rate)
(m*Derivative(x(t), t)/cos(theta(t)), b*m*Derivative(theta(t), t)**2)
>>> me.check.holds
True
"""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp

from ..errors import ModelError, ModelTypeError
from ..verify import Check
from ._plain import Plain, zero

__all__ = ["MomentumEquation", "momentum_equation", "horizontal_combinations"]


@dataclass(frozen=True)
class MomentumEquation:
    """``combination`` [c_i] (dynamicsymbols), ``section`` {q: component of xi},
    ``momentum`` J and ``rate`` (its time derivative by the momentum equation), both with
    the constraints substituted; ``check`` (dJ/dt along (1.4) = rate); ``noether``
    [(X_i in D?, d/dt (dL/dqdot . X_i) along (1.4))] per generator."""

    combination: list
    section: dict
    momentum: sp.Expr
    rate: sp.Expr
    check: Check
    noether: list


def _generators(ch, generators):
    if isinstance(generators, dict) or not hasattr(generators, "__iter__"):
        raise ModelTypeError("generators must be a list of vector fields, each a dict "
                             "{coordinate: component}, e.g. [{x: 1}, {y: 1}]")
    out = []
    names = {c.func.__name__: c for c in ch.coordinates}
    for k, X in enumerate(generators):
        if not isinstance(X, dict) or not X:
            raise ModelTypeError(f"generator {k} must be a non-empty dict {{coordinate: "
                                 f"component}}, got {X!r:.60}")
        vec = {c: sp.S.Zero for c in ch.coordinates}
        for key, comp in X.items():
            c = names.get(key) if isinstance(key, str) else (key if key in ch.coordinates else None)
            if c is None:
                raise ModelError(f"generator {k}: {key!r} is not a coordinate of the system "
                                 f"({', '.join(names)})")
            comp = ch.plain(sp.sympify(comp))
            if comp.has(*ch.v.values(), *ch.a.values()):
                raise ModelError(f"generator {k}: the component along {c.func.__name__} "
                                 "depends on a velocity; a vector field on the configuration "
                                 "space depends on the positions only")
            vec[c] = comp
        out.append(vec)
    return out


def _prolonged(ch, X, f):
    """X^(1) f: the vector field and its first prolongation applied to f(q, qdot)."""
    out = []
    for c in ch.coordinates:
        if X[c] == 0:
            continue
        out.append(X[c] * f.diff(ch.q[c]))
        dX = sp.Add(*[X[c].diff(ch.q[r]) * ch.v[r] for r in ch.coordinates])
        out.append(dX * f.diff(ch.v[c]))
    return sp.Add(*out)


def _defect(ch, X):
    """A^beta(X) for each dependent coordinate: zero iff X lies in D."""
    return [X[d] - sp.Add(*[ch.b[d][s] * X[s] for s in ch.independent]) for d in ch.dependent]


def _check_symmetries(ch, system, gens):
    L = ch.plain(system.lagrangian)
    on = {ch.v[d]: ch.phi[d] for d in ch.dependent}
    for k, X in enumerate(gens):
        XL = _prolonged(ch, X, L)
        if XL != 0 and not zero("symmetry", "", [XL]).holds:
            raise ModelError(f"generator {k} is not a symmetry of L: its prolongation applied "
                             f"to L gives {ch.public(XL)}, not 0")
        for d in ch.dependent:
            Xf = _prolonged(ch, X, ch.v[d] - ch.phi[d]).xreplace(on)
            if Xf != 0 and not zero("symmetry", "", [Xf]).holds:
                raise ModelError(f"generator {k} does not preserve the constraint for "
                                 f"{d.func.__name__}dot: on the constraint its prolongation "
                                 f"gives {ch.public(Xf)}, not 0")


def horizontal_combinations(system, generators):
    """A basis of the combinations sum c_i X_i lying in D (each a list [c_i], in the
    dynamicsymbols): the solutions of A^beta(sum c_i X_i) = 0 (``Matrix.nullspace``)."""
    ch = Plain(system)
    gens = _generators(ch, generators)
    K = sp.Matrix([[e for e in _defect(ch, X)] for X in gens]).T
    return [[ch.public(e) for e in v] for v in K.nullspace()]


def _rate(ch, system, f):
    """d f/dt along (1.4) for f(q, qdot) with the dependent velocities substituted."""
    acc = system.accelerations()
    on = {ch.v[d]: ch.phi[d] for d in ch.dependent}
    f = f.xreplace(on)
    terms = [f.diff(ch.q[c]) * ch.v[c] for c in ch.coordinates]
    terms += [f.diff(ch.v[c]) * ch.plain(acc[c.diff(ch.t, 2)]) for c in ch.independent]
    return sp.Add(*terms).xreplace(on)


def momentum_equation(system, generators, combination=None):
    """The momentum equation of the combination ``combination`` ([c_i], functions of the
    coordinates) of the symmetries ``generators`` (see the module).  Without
    ``combination`` the one combination in D is used (ModelError when there are
    none or several).  ModelError when a generator is not a symmetry of L or of the
    constraints, or the combination does not lie in D."""
    ch = Plain(system)
    gens = _generators(ch, generators)
    _check_symmetries(ch, system, gens)
    if combination is None:
        basis = horizontal_combinations(system, generators)
        if len(basis) != 1:
            raise ModelError(f"{len(basis)} independent combinations of the generators lie in "
                             "D; pass combination=[c_1, ...] to choose one"
                             if basis else "no combination of the generators lies in the "
                             "distribution D: there is no momentum equation for them")
        combination = basis[0]
    if isinstance(combination, (str, dict)) or not hasattr(combination, "__iter__"):
        raise ModelTypeError("combination must be a list [c_1, ...], one per generator")
    cs = [ch.plain(sp.sympify(c)) for c in combination]
    if len(cs) != len(gens):
        raise ModelError(f"combination has {len(cs)} entries for {len(gens)} generators")
    if any(c.has(*ch.v.values()) for c in cs):
        raise ModelError("combination may depend on the positions only, not on velocities")
    xi = {c: sp.Add(*[ci * X[c] for ci, X in zip(cs, gens)]) for c in ch.coordinates}
    defect = _defect(ch, xi)
    if any(e != 0 for e in defect) and not zero("in D", "", defect).holds:
        raise ModelError("the combination sum c_i X_i does not lie in the distribution D "
                         f"(A(xi) = {[ch.public(e) for e in defect]}): choose one with "
                         "A(xi) = 0, e.g. from horizontal_combinations")
    L = ch.plain(system.lagrangian)
    on = {ch.v[d]: ch.phi[d] for d in ch.dependent}
    dL = {c: L.diff(ch.v[c]) for c in ch.coordinates}
    J = sp.Add(*[dL[c] * xi[c] for c in ch.coordinates]).xreplace(on)
    cdot = [sp.Add(*[ci.diff(ch.q[r]) * ch.v[r] for r in ch.coordinates]).xreplace(on)
            for ci in cs]
    rate = sp.Add(*[cd * sp.Add(*[dL[c] * X[c] for c in ch.coordinates])
                    for cd, X in zip(cdot, gens)]).xreplace(on)
    chk = zero("momentum", "dJ/dt along (1.4) = sum cdot_i dL/dqdot . X_i",
               [_rate(ch, system, J) - rate])
    noether = []
    for X in gens:
        d = _defect(ch, X)
        in_D = all(e == 0 for e in d) or bool(zero("in D", "", d).holds)
        noether.append((in_D, ch.public(_rate(ch, system, sp.Add(*[dL[c] * X[c]
                                                                    for c in ch.coordinates])))))
    return MomentumEquation([ch.public(c) for c in cs],
                            {c: ch.public(xi[c]) for c in ch.coordinates},
                            ch.public(J), ch.public(rate), chk, noether)
