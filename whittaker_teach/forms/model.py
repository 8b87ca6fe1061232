"""The system model shared by the classical forms: a Lagrangian and non-holonomic
constraints, of Chaplygin type or not.

A :class:`NonholonomicSystem` holds L(q, qdot) and g constraints, each solved for one
dependent velocity, ``qdot_beta = phi_beta(q, qdot_sigma)``: linear ones
A(q) qdot = 0, or nonlinear ones of Chetaev type (homogeneous of degree one in the
velocities, such as zdot = c sqrt(xdot^2 + ydot^2)).  Unlike
:class:`~whittaker_teach.system.ChaplyginSystem`, L and the constraints may depend
on the dependent coordinates q_beta: every form of :mod:`whittaker_teach.forms`
takes such a system; Chaplygin's equations (1.4) only where they apply.

Two steps, as in ``sympy.physics.mechanics.LagrangesMethod``: build the object
(the model is checked once), then hand it to a form and ask.

>>> import sympy as sp
>>> from sympy.physics.mechanics import dynamicsymbols
>>> from whittaker_teach.forms import NonholonomicSystem
>>> t = dynamicsymbols._t
>>> m, J, kappa = sp.symbols("m J kappa", positive=True)
>>> x, th, y = dynamicsymbols("x theta y")
>>> L = m/2*(x.diff(t)**2 + y.diff(t)**2) + J/2*th.diff(t)**2 - kappa/2*(x**2 + y**2)
>>> S = NonholonomicSystem(L, [x, th, y],
...                        constraints=[y.diff(t)*sp.cos(th) - x.diff(t)*sp.sin(th)],
...                        dependent=[y])
>>> S.dependent_coordinates, S.is_linear, S.is_chaplygin
([y(t)], True, False)
>>> S.why_not_chaplygin
'L depends on the dependent coordinate y (Chaplygin condition, 1.3: L must be free of the dependent coordinates)'

The constraints may be given as expressions (= 0, or ``Eq``) with ``dependent``
naming the coordinates whose velocities they are solved for (the last g
coordinates when it is omitted), or solved, ``dependent={y.diff(t): phi}``.
Every bad input is a :class:`~whittaker_teach.errors.ModelError` naming the
condition: a constraint that is not homogeneous of degree one in the velocities,
explicit time, a dependent velocity written with another dependent velocity, a
constraint that cannot be solved for the velocities named.

Warning: numerical checks sample coordinates in (0.1, 1.2), independent
velocities of modulus in (0.2, 1.5) and parameters in (0.5, 2); an identity that
fails only outside that box is not seen by them.
"""

from __future__ import annotations

import random

import mpmath
import sympy as sp
from sympy.core.function import AppliedUndef

from ..canonical import add, mul
from ..coordinates import name as _name, sign_assumptions
from ..dag import along, diff, substitute, zeroed
from ..errors import ModelError, ModelTypeError, guarded
from ..linear import lu_solve
from ..inputs import check_coordinates, check_values, readable, require_expr, subexpressions
from ..verify import DPS, At, Unevaluable, check_zero

__all__ = ["NonholonomicSystem", "from_mechanics"]


def _as_list(x):
    if isinstance(x, (sp.Basic, str)) or not hasattr(x, "__iter__"):
        return [x]
    return list(x)


class NonholonomicSystem:
    """L(q, qdot) and constraints qdot_beta = phi_beta(q, qdot_sigma), not necessarily
    of Chaplygin type.

    Parameters
    ==========
    lagrangian : Expr
        L in the coordinates (``dynamicsymbols``) and their velocities; t must not
        appear explicitly.
    coordinates : list
        Every coordinate q_s, independent and dependent.
    constraints : list, optional
        The constraints f_beta(q, qdot) = 0 as expressions or ``Eq``: linear in the
        velocities (A(q) qdot = 0) or nonlinear and homogeneous of degree one.
        Solved for the velocities of ``dependent``.  Kept as given: the Routh-Voss
        multipliers belong to them.
    dependent : list or dict, optional
        With ``constraints``: the dependent coordinates (default: the last g).
        Without: ``{q_beta.diff(t): phi_beta}``, the constraints solved.
    name : str, optional
    """

    @guarded("building the non-holonomic system")
    def __init__(self, lagrangian, coordinates, constraints=None, dependent=None, *,
                 nonhol_coneqs=None, name=None):
        from ..mechanics_input import constraint_expressions, dependent_velocities, exact_rationals
        if nonhol_coneqs is not None:           # the keyword of LagrangesMethod
            if constraints is not None:
                raise ModelError("give the constraints once: constraints= or nonhol_coneqs=")
            constraints = nonhol_coneqs
        self.name = name or "system"
        self.coordinates = check_coordinates(coordinates)
        self._t = self.coordinates[0].args[0]
        self.rationalized = {}
        ex = (lambda e: exact_rationals(e, self.rationalized) if isinstance(e, sp.Basic) else e)
        if constraints is not None:
            fs = [ex(f) for f in constraint_expressions(constraints, "constraints")]
            if dependent is None:
                if len(fs) > len(self.coordinates) - 1:
                    raise ModelError(f"{len(fs)} constraints for {len(self.coordinates)} "
                                     "coordinates: at least one velocity must stay independent")
                dependent = self.coordinates[len(self.coordinates) - len(fs):]
            elif isinstance(dependent, dict):
                raise ModelError("with constraints=[...], dependent names the dependent "
                                 "coordinates, [y, ...]; a dict {ydot: phi} is the constraints "
                                 "solved, given without constraints=")
            solved, given = dependent_velocities(list(_as_list(dependent)), fs,
                                                 self.coordinates, self._t)
        else:
            if isinstance(dependent, dict):
                dependent = {k: ex(v) for k, v in dependent.items()}
            solved, given = dependent_velocities(dependent, None, self.coordinates, self._t)
        self._make_symbols()
        deps = []
        for key in solved:
            if not (isinstance(key, sp.Derivative) and key.variables == (self._t,)
                    and key.expr in self.coordinates):
                raise ModelError(f"dependent: key {key!r} is not the velocity of one of the "
                                 f"coordinates; write it as y.diff(t)")
            deps.append(key.expr)
        self.dependent_coordinates = [c for c in self.coordinates if c in deps]
        self.independent_coordinates = [c for c in self.coordinates if c not in deps]
        if not self.independent_coordinates:
            raise ModelError("every velocity is dependent: at least one independent velocity "
                             "is needed (n - g >= 1)")
        self.lagrangian = ex(require_expr(lagrangian, "the Lagrangian L"))
        self._L = self._internal(self.lagrangian, "the Lagrangian L")
        self.constraints = {c.diff(self._t): ex(require_expr(solved[c.diff(self._t)],
                                                              f"the constraint for {_name(c)}dot"))
                            for c in self.dependent_coordinates}
        self._phi = {c: self._internal(self.constraints[c.diff(self._t)],
                                       f"the constraint {_name(c)}dot = phi")
                     for c in self.dependent_coordinates}
        dep_qd = {self.qd[c] for c in self.dependent_coordinates}
        for c, phi in self._phi.items():
            bad = sorted(str(s) for s in phi.free_symbols & dep_qd)
            if bad:
                raise ModelError(f"the constraint for {_name(c)}dot is written with the "
                                 f"dependent velocity {bad[0]}: each dependent velocity must "
                                 "be given in the coordinates and the independent velocities")
        if given is not None:
            self._f = [self._internal(f, "a constraint") for f in given]
        else:
            self._f = [self.qd[c] - self._phi[c] for c in self.dependent_coordinates]
        self.parameters = sorted(
            set().union(self._L.free_symbols, *(p.free_symbols for p in self._phi.values()),
                        *(f.free_symbols for f in self._f)) - set(self._all_symbols), key=str)
        for p in self.parameters:
            if p.is_real is False or (p.is_real is None and p.is_complex):
                raise ModelError(f"parameter {p} is declared complex: the parameters must be real")
        self._memo = {}
        self._cache = {}
        self._check_homogeneous()
        self.source = None          # the sympy.physics.mechanics object, when built from one

    # ----- notation -------------------------------------------------------
    def _make_symbols(self):
        self.q, self.qd, self.qdd, self.qddd = {}, {}, {}, {}
        for c in self.coordinates:
            n = _name(c)
            self.q[c] = sp.Symbol(n, **sign_assumptions(c))
            self.qd[c] = sp.Symbol(n + "dot")
            self.qdd[c] = sp.Symbol(n + "ddot")
            self.qddd[c] = sp.Symbol(n + "dddot")
        self._all_symbols = [*self.q.values(), *self.qd.values(), *self.qdd.values(),
                             *self.qddd.values()]
        self._names = {s.name for s in self._all_symbols}
        self._to_internal = {}
        for c in self.coordinates:
            self._to_internal[sp.Derivative(c, (self._t, 3))] = self.qddd[c]
            self._to_internal[sp.Derivative(c, (self._t, 2))] = self.qdd[c]
            self._to_internal[sp.Derivative(c, self._t)] = self.qd[c]
            self._to_internal[c] = self.q[c]
        self._to_public = {v: k for k, v in self._to_internal.items()}

    def _internal(self, expr, what):
        clash = sorted(str(s) for s in expr.free_symbols if s.name in self._names)
        if clash:
            raise ModelError(f"{what} contains the symbol {clash[0]}, which has the name of a "
                             "coordinate or velocity; rename it")
        check_values(expr, what)
        e = substitute(expr, self._to_internal)
        nodes = subexpressions(e)
        for d in sorted((n for n in nodes if isinstance(n, sp.Derivative)), key=sp.default_sort_key):
            raise ModelError(f"{what} contains {d.xreplace(self._to_public)}, which is not a "
                             "velocity of a listed coordinate")
        for f in sorted((n for n in nodes if isinstance(n, AppliedUndef)), key=sp.default_sort_key):
            raise ModelError(f"{what} depends on {f}, which is not among the coordinates "
                             f"{self.coordinates}")
        free = e.free_symbols
        if self._t in free:
            raise ModelError(f"{what} depends explicitly on t: the forms here are derived for "
                             "scleronomic systems (L and the constraints free of t)")
        if any(s in free for s in (*self.qdd.values(), *self.qddd.values())):
            raise ModelError(f"{what} contains an acceleration; L and the constraints depend on "
                             "coordinates and velocities only")
        if any(isinstance(n, sp.Abs) for n in nodes):
            e = e.replace(sp.Abs, lambda u: sp.sqrt(u**2))
        return e

    def to_public(self, expr):
        """An expression of the internal symbols (x, xdot, xddot) in dynamicsymbols."""
        return substitute(expr, self._to_public, self._cache.setdefault("public", {}))

    def to_internal(self, expr):
        """An expression in dynamicsymbols rewritten in the internal symbols."""
        return substitute(sp.sympify(expr), self._to_internal)

    # ----- structure ------------------------------------------------------
    @property
    def sigma(self):
        """The independent coordinates q_sigma."""
        return self.independent_coordinates

    @property
    def beta(self):
        """The dependent coordinates q_beta."""
        return self.dependent_coordinates

    def _d(self, f, z):
        return diff(f, z, self._memo)

    def _check_homogeneous(self):
        """Every constraint homogeneous of degree one in the independent velocities (Euler's
        relation), else ModelError; and whether each is linear in them."""
        sig = [self.qd[c] for c in self.sigma]
        linear = True
        for c, phi in self._phi.items():
            grads = [self._d(phi, v) for v in sig]
            res = add(*[mul(g, v) for g, v in zip(grads, sig)], -phi)
            chk = check_zero("model", "Euler's relation", res, self.sample, seed=3)
            if not chk.holds:
                raise ModelError(
                    f"the constraint {_name(c)}' = {readable(self.constraints[c.diff(self._t)])}"
                    " is not homogeneous of degree one in the velocities (Euler's relation "
                    "fails): the model takes linear constraints A(q) qdot = 0 and Chetaev "
                    "constraints homogeneous of degree one")
            for g in grads:
                if any(self._d(g, v) != 0 for v in sig):
                    linear = False
        self.is_linear = linear

    @property
    def is_holonomic(self):
        """No constraints (g = 0)."""
        return not self.dependent_coordinates

    @property
    def why_not_chaplygin(self):
        """None for a system of Chaplygin type; else the condition (1.3) that fails.

        Decided on what L and the constraints are, not on how they are written: an
        expression that contains a dependent coordinate s but whose derivative in s is
        zero (the checks' exact-or-numeric zero test, as ``ChaplyginSystem`` decides it:
        A sin(psi)**2 + A cos(psi)**2) does not depend on s."""
        if "why_not" not in self._cache:
            self._cache["why_not"] = self._why_not_chaplygin()
        return self._cache["why_not"]

    def _depends_on(self, expr, s):
        return expr.has(s) and not check_zero("1.3", "", self._d(expr, s), self.sample,
                                              seed=3).holds

    def _why_not_chaplygin(self):
        dep_q = [self.q[c] for c in self.beta]
        for c in self.beta:
            if self._depends_on(self._L, self.q[c]):
                return (f"L depends on the dependent coordinate {_name(c)} (Chaplygin "
                        "condition, 1.3: L must be free of the dependent coordinates)")
        for c, phi in self._phi.items():
            for s in dep_q:
                if self._depends_on(phi, s):
                    return (f"the constraint for {_name(c)}dot depends on the dependent "
                            f"coordinate {s} (Chaplygin condition, 1.3)")
        return None

    @property
    def is_chaplygin(self):
        """True when L and every phi_beta are free of the dependent coordinates (1.3)."""
        return self.why_not_chaplygin is None

    def B(self, c_dep, c_ind):
        """d phi_beta / d qdot_sigma: the coefficient of the linear constraint (Chetaev's
        coefficient for a nonlinear one), in the internal symbols."""
        return self._d(self._phi[c_dep], self.qd[c_ind])

    def C(self, c, c_ind):
        """d qdot_s / d qdot_sigma on the constraints: 1 or 0 for an independent q_s, B
        for a dependent one (the partial velocities of the natural speeds)."""
        if c in self._phi:
            return self.B(c, c_ind)
        return sp.S.One if c == c_ind else sp.S.Zero

    # ----- the constraints at velocity and acceleration level ---------------
    @property
    def on_constraints(self):
        """{qdot_beta: phi_beta, qddot_beta: d phi_beta/dt}: what the forms substitute,
        the dependent accelerations in the independent ones (linear in them)."""
        if "on" not in self._cache:
            on = {self.qd[c]: phi for c, phi in self._phi.items()}
            acc = {}
            for c, phi in self._phi.items():
                acc[self.qdd[c]] = substitute(self.rate(phi), on)
            on.update(acc)
            self._cache["on"] = on
        return self._cache["on"]

    def constrained(self, expr):
        """``expr`` with the dependent velocities and accelerations substituted."""
        return substitute(expr, self.on_constraints, self._cache.setdefault("onmemo", {}))

    def rate(self, f):
        """The total time derivative of f(q, qdot[, qddot]) over every coordinate (in
        qdot_s, qddot_s[, qdddot_s]): ``dag.along`` in one pass."""
        rates = {}
        for c in self.coordinates:
            rates[self.q[c]] = self.qd[c]
            rates[self.qd[c]] = self.qdd[c]
            rates[self.qdd[c]] = self.qddd[c]
        return along(f, rates, self._cache.setdefault("alongmemo", {}))

    def lagrange_expressions(self):
        """E_s(L) = d/dt dL/dqdot_s - dL/dq_s for every coordinate (unconstrained)."""
        if "E" not in self._cache:
            self._cache["E"] = [add(self.rate(self._d(self._L, self.qd[c])),
                                    -self._d(self._L, self.q[c])) for c in self.coordinates]
        return self._cache["E"]

    @property
    def kinetic(self):
        """T = L - L(qdot = 0) (internal symbols): the part of L with the velocities."""
        if "T" not in self._cache:
            V = substitute(self._L, {self.qd[c]: sp.S.Zero for c in self.coordinates})
            self._cache["T"] = add(self._L, -V)
            self._cache["V"] = -V
        return self._cache["T"]

    @property
    def potential(self):
        """V = -L(qdot = 0) (internal symbols)."""
        self.kinetic
        return self._cache["V"]

    def forces(self):
        """Q_s = -dV/dq_s, the generalized forces of the potential, per coordinate."""
        return [-self._d(self.potential, self.q[c]) for c in self.coordinates]

    # ----- random admissible points ---------------------------------------
    def sample(self, rng):
        """A random point: parameters in (0.5, 2), every coordinate in (0.1, 1.2), the
        independent velocities of modulus in (0.2, 1.5), accelerations in (-1, 1)."""
        pt = {}
        for p in self.parameters:
            v = rng.uniform(0.5, 2.0)
            pt[p] = -v if p.is_negative else v
        for c in self.coordinates:
            pt[self.q[c]] = rng.uniform(0.1, 1.2) * (-1 if self.q[c].is_negative else 1)
            pt[self.qd[c]] = rng.choice((-1, 1)) * rng.uniform(0.2, 1.5)
            pt[self.qdd[c]] = rng.uniform(-1, 1)
            pt[self.qddd[c]] = rng.uniform(-1, 1)
        return pt

    def solve_linear(self, eqs, unknowns, what):
        """The solution (a list) of the equations ``eqs`` (= 0), linear in the symbols
        ``unknowns``: its matrix is first shown regular at a sampled point (else a
        ModelError naming ``what``), then solved by LU with pivots chosen by value there
        (an entry non-zero at a point is not identically zero)."""
        M = sp.Matrix([[self._d(e, u) for u in unknowns] for e in eqs])
        memo = {}
        rest = sp.Matrix([zeroed(e, unknowns, memo) for e in eqs])
        n = len(unknowns)
        if n == 0:
            return []
        rng = random.Random(11)
        with mpmath.workdps(DPS):
            for _ in range(4):
                at = At(self.sample(rng))
                try:
                    d = mpmath.det(mpmath.matrix([[at(M[i, j]) for j in range(n)]
                                                  for i in range(n)]))
                except (ZeroDivisionError, ValueError, OverflowError, TypeError):
                    continue
                except (Unevaluable, KeyError) as err:
                    raise ModelError(f"{what} cannot be evaluated numerically: {err}") from err
                if abs(d) > mpmath.mpf(10) ** (-DPS // 2):
                    break
            else:
                raise ModelError(f"{what} is singular: the equations cannot be solved for "
                                 "the accelerations (is the kinetic energy positive definite "
                                 "on the constraints?)")

        def iszero(x):
            if x.is_Number:
                return x == 0
            try:
                with mpmath.workdps(DPS):
                    return not abs(at(x)) > mpmath.mpf(10) ** (-DPS // 2)
            except (ZeroDivisionError, ValueError, OverflowError, TypeError):
                return True
        try:
            return lu_solve(M, -rest, iszero)
        except ValueError as err:
            raise ModelError(f"{what} is singular") from err

    @classmethod
    def from_mechanics(cls, obj, dependent=None, name=None):
        """See :func:`from_mechanics`."""
        return from_mechanics(obj, dependent, name)

    def __repr__(self):
        kind = ("holonomic" if self.is_holonomic else
                ("linear" if self.is_linear else "nonlinear (Chetaev)") + " constraints, "
                + ("Chaplygin type" if self.is_chaplygin else "not of Chaplygin type"))
        return (f"<NonholonomicSystem {self.name!r}: {kind}, coordinates "
                f"{[_name(c) for c in self.coordinates]}, dependent "
                f"{[_name(c) for c in self.beta]}>")


def _build(L, q, dependent=None, nonhol_coneqs=None, name=None):
    """The constructor with ChaplyginSystem's call signature (for mechanics_input)."""
    return NonholonomicSystem(L, q, constraints=nonhol_coneqs, dependent=dependent, name=name)


@guarded("reading the sympy.physics.mechanics model")
def from_mechanics(obj, dependent=None, name=None):
    """A :class:`NonholonomicSystem` from a ``LagrangesMethod`` (its Lagrangian,
    coordinates and ``nonhol_coneqs``), a ``System`` or a ``KanesMethod`` (bodies with
    their ``potential_energy``, kinematic equations u = qdot, the velocity constraints,
    no loads), the constraints solved for the velocities of ``dependent`` (default: the
    dependent speeds of Kane's model, else the last g coordinates).

    >>> import sympy as sp
    >>> from sympy.physics.mechanics import LagrangesMethod, dynamicsymbols
    >>> x, th, y = dynamicsymbols("x theta y")
    >>> t = dynamicsymbols._t
    >>> L = (x.diff(t)**2 + y.diff(t)**2 + th.diff(t)**2)/2
    >>> lm = LagrangesMethod(L, [x, th, y],
    ...                      nonhol_coneqs=[y.diff(t)*sp.cos(th) - x.diff(t)*sp.sin(th)])
    >>> from_mechanics(lm, dependent=[y]).dependent_coordinates
    [y(t)]
    """
    from sympy.physics.mechanics import KanesMethod, LagrangesMethod

    from ..mechanics_input import from_lagranges_method, from_system
    if isinstance(obj, LagrangesMethod):
        if obj.coneqs and dependent is None:
            dependent = list(obj.q)[len(obj.q) - len(obj.coneqs):]
        S = from_lagranges_method(_build, obj, dependent, name)
    elif isinstance(obj, KanesMethod):
        S = _from_kanes_method(obj, dependent, name)
    elif type(obj).__name__ == "System":
        S = from_system(_build, obj, dependent, name)
    else:
        raise ModelTypeError("from_mechanics takes a LagrangesMethod, a KanesMethod or a "
                             f"System, got {type(obj).__name__}")
    S.source = obj
    return S


def _from_kanes_method(km, dependent, name):
    from sympy.physics.mechanics import Lagrangian, dynamicsymbols
    t = dynamicsymbols._t
    if km.bodies is None:
        raise ModelError("the KanesMethod has no bodies: pass bodies=[...] (with their "
                         "potential_energy) to KanesMethod, the Lagrangian is built from them")
    if km.forcelist:
        raise ModelError("the KanesMethod has loads: the forms here take a Lagrangian; put a "
                         "conservative force's potential into body.potential_energy")
    q, u = list(km.q), list(km.u)
    if len(q) != len(u):
        raise ModelError("the KanesMethod's speeds must be u = qdot, one per coordinate")
    kd = km.kindiffdict()
    u_to_qd = {}
    for qi, ui in zip(q, u):
        if sp.expand(kd.get(qi.diff(t), sp.nan) - ui) != 0:
            raise ModelError("the KanesMethod's kinematic equations must be u = qdot (u_i = "
                             "q_i', in the order of q and u); other speeds are not supported")
        u_to_qd[ui] = qi.diff(t)
    L = Lagrangian(km._inertial, *km.bodies).xreplace(u_to_qd)
    fs = []
    if km._udep:    # the velocity constraints as KanesMethod keeps them: k_nh u + f_nh = 0
        fs = [f.xreplace(u_to_qd) for f in (km._k_nh * sp.Matrix(km.u) + km._f_nh)]
    if dependent is None and fs:
        dependent = [q[u.index(ud)] for ud in km._udep]
    return NonholonomicSystem(L, q, constraints=fs or None, dependent=dependent, name=name)
