"""The system model: a Chaplygin-type non-holonomic system, (1.1)-(1.4), (1.10)-(1.11).

A :class:`ChaplyginSystem` is built from a Lagrangian, its coordinates (as
``dynamicsymbols``) and the dependent velocities, ``{qdot_dep: phi}``, where
each ``phi`` is a function of the independent coordinates and velocities
only.  With no dependent velocities it is a holonomic system.

Two steps, as in ``sympy.physics.mechanics.LagrangesMethod``: build the
object (the model is checked once), then ask for what you need.

>>> import sympy as sp
>>> from sympy.physics.mechanics import dynamicsymbols
>>> import whittaker_teach as wt
>>> t = dynamicsymbols._t
>>> m, J, k = sp.symbols("m J k", positive=True)
>>> x, th, y = dynamicsymbols("x theta y")
>>> L = m/2*(x.diff(t)**2 + y.diff(t)**2) + J/2*th.diff(t)**2 - k**2*th**2/2
>>> sledge = wt.ChaplyginSystem(L, [x, th, y], dependent={y.diff(t): x.diff(t)*sp.tan(th)})
>>> sledge.independent_coordinates, sledge.dependent_coordinates
([x(t), theta(t)], [y(t)])
>>> sledge.energy()
J*Derivative(theta(t), t)**2/2 + k**2*theta(t)**2/2 + m*(tan(theta(t))**2 + 1)*Derivative(x(t), t)**2/2
>>> sledge.accelerations()[th.diff(t, 2)]
-k**2*theta(t)/J

The Chaplygin equations (1.4) are derived with the constraints substituted
(L~, "L-tilde"); the dependent coordinates never appear in them.  The model
refuses, with a :class:`~whittaker_teach.errors.ModelError` that names the
condition, a system outside the paper's assumptions: a Lagrangian or a
constraint depending on a dependent coordinate or on t (Chaplygin conditions,
1.3), a constraint that is not homogeneous of degree one (1.10; then the energy
1.11 is not guaranteed to be conserved, and the reduction 1.22-1.26 needs 1.10
anyway), a singular kinetic energy.

Warning: numerical checks sample coordinates in (0.1, 1.2), velocities of
modulus in (0.2, 1.5) and parameters without a sign assumption in (0.5, 2);
an identity that fails only outside that box is not seen by them.
"""

from __future__ import annotations

import random

import mpmath
import sympy as sp
from sympy.core.function import AppliedUndef

from .coordinates import T, name, sign_assumptions
from .canonical import add, mul, negated, power, sub
from .dag import diff, substitute, zeroed
from .errors import ModelError, guarded
from .inputs import check_coordinates, check_values, readable, require_expr, subexpressions
from .linear import lu_solve, solve_with_regular_poles
from .mechanics_input import constraint_expressions, dependent_velocities, exact_rationals
from .reduction import Reduction
from .rewrite import collected, rational
from .steps import Derivation, Report, Step, eq
from .verify import (DPS, EXACT_SIZE_LIMIT, At, Unevaluable, check_zero,
                     shared_points, within_size)

__all__ = ["ChaplyginSystem"]


_name, _sign_assumptions = name, sign_assumptions


#: above this many independent coordinates, (1.4) and the energy (1.11) are solved and
#: checked as derived, and collected (``rewrite.collected``, a rewrite to read: expand,
#: group, factor) only when shown; at or below it, as collected (the examples' forms)
COLLECT_SIGMA_LIMIT = 3

#: a matrix of more nodes than this is solved with its LU pivots chosen by value
PIVOT_BY_VALUE_NODES = 2000


def _zero_at(point):
    """An ``iszerofunc`` for SymPy's LU: True for 0 and for an entry whose value at
    ``point`` (a :class:`.verify.At`, 40 digits) is 0 to half the digits, False
    otherwise."""
    def iszero(x):
        if x.is_Number:
            return x == 0
        try:
            with mpmath.workdps(DPS):
                return not abs(point(x)) > mpmath.mpf(10) ** (-DPS // 2)
        except (ZeroDivisionError, ValueError, OverflowError, TypeError):
            return True              # not a usable pivot at this point
    return iszero


class ChaplyginSystem:
    """A Chaplygin-type system: L(q, qdot) and qdot_dep = phi(q_sigma, qdot_sigma).

    Parameters
    ==========
    lagrangian : Expr
        L in the coordinates (``dynamicsymbols``) and their time derivatives.
    coordinates : list
        All coordinates q_s, independent and dependent, in the order to use.
    dependent : dict or list, optional
        ``{q_dep.diff(t): phi}``: the dependent velocities (1.1), (1.3).
        Linear constraints and positively homogeneous ones of degree one
        (``a*sqrt(xdot**2 + ydot**2)``) both work.  None or {}: holonomic.
        Also accepted: ``{q_dep.diff(t): f}`` with f (= 0, or an ``Eq``) containing
        q_dep.diff(t), a list of ``Eq(q_dep.diff(t), phi)``, and, with
        ``nonhol_coneqs``, the list of the dependent coordinates ``[y]``.
    nonhol_coneqs : list, optional
        The constraints as ``LagrangesMethod`` takes them: expressions f(q, qdot)
        (= 0) or ``Eq``, linear or nonlinear in the velocities, solved for the
        velocities of the coordinates named in ``dependent``
        (:func:`~whittaker_teach.mechanics_input.solved_velocities`; a ModelError
        when they cannot be solved, or have several solutions).  Kept for
        :meth:`multipliers`, which uses them as written.
    name : str, optional
        A name for printing.

    Float coefficients (``0.5*m*xdot**2``) are taken as the exact rationals they
    print as (``Rational(str(f))``: 0.845 is 169/200), listed in ``rationalized``
    ({Float: Rational}); step (1.1) says so, and its check, in ``verify()``, that each
    rational equals its Float to the Float's precision.  Every other check is then
    exact or to 40 digits as for any rational model.  The coordinates may be functions
    of a time symbol declared ``real=True`` (the results use the same symbol).
    """

    @guarded("building the system")
    def __init__(self, lagrangian, coordinates, dependent=None, *, nonhol_coneqs=None,
                 name=None):
        self.name = name or "system"
        self.coordinates = check_coordinates(coordinates)
        self._t = self.coordinates[0].args[0]       # dynamicsymbols._t, or t real=True
        self._make_symbols()
        self.rationalized = {}
        if nonhol_coneqs is not None:
            nonhol_coneqs = [self._exact(f) for f in constraint_expressions(nonhol_coneqs)]
        if isinstance(dependent, dict):
            dependent = {k: self._exact(v) if isinstance(v, sp.Basic) else v
                         for k, v in dependent.items()}
        elif isinstance(dependent, (list, tuple)):
            dependent = [self._exact(v) if isinstance(v, sp.Basic) else v for v in dependent]
        dependent, self._coneqs = dependent_velocities(dependent, nonhol_coneqs,
                                                       self.coordinates, self._t)
        dep_coords = [self._velocity_owner(key) for key in dependent]
        self.dependent_coordinates = [c for c in self.coordinates if c in dep_coords]
        self.independent_coordinates = [c for c in self.coordinates if c not in dep_coords]
        if not self.independent_coordinates:
            raise ModelError("every velocity is dependent: at least one independent "
                             "coordinate q_sigma is needed (1.1: eps = n - g >= 1)")
        L = self._exact(require_expr(lagrangian, "the Lagrangian L"))
        self.lagrangian = L
        self.constraints = {k.expr.diff(self._t): self._exact(
            require_expr(v, f"the constraint for {k}")) for k, v in dependent.items()}
        self._L = self._internal(L, "the Lagrangian L")
        self._phi = {self.q[c]: self._internal(self.constraints[c.diff(self._t)],
                                               f"the constraint {_name(c)}dot = phi")
                     for c in self.dependent_coordinates}
        self._dmemo = {}     # dag.diff's memo: shared subexpressions differentiated once
        self._rewritten = []     # (what, q_dep, as given, rewritten free of q_dep): 1.3
        self.parameters = self._parameters()        # (sampled by the checks of 1.3)
        self._check_chaplygin()
        self.parameters = self._parameters()
        for p in self.parameters:
            if p.is_real is False or (p.is_real is None and p.is_complex):
                raise ModelError(f"parameter {p} is declared complex (not real): the "
                                 "parameters of L and of the constraints must be real (1.1); "
                                 f"declare it with sp.Symbol({p.name!r}, real=True) or "
                                 "positive=True")
        clash = [p for p in self.parameters if p.name in self._names]
        if clash:
            raise ModelError(f"parameter {clash[0]} has the name of a coordinate or velocity; "
                             "rename it (the derivation uses plain symbols for q and qdot)")
        self._cache = {}

    def _parameters(self):
        return sorted(set().union(self._L.free_symbols,
                                  *(p.free_symbols for p in self._phi.values()))
                      - set(self._all_symbols), key=str)

    @classmethod
    def from_lagranges_method(cls, lm, dependent=None, name=None):
        """The system of a ``sympy.physics.mechanics.LagrangesMethod``: its Lagrangian,
        coordinates and ``nonhol_coneqs``, solved for the velocities of ``dependent``
        (a list of coordinates).  A forcelist or holonomic constraints are refused."""
        from .mechanics_input import from_lagranges_method
        return from_lagranges_method(cls, lm, dependent, name)

    @classmethod
    def from_system(cls, system, dependent=None, name=None):
        """The system of a ``sympy.physics.mechanics.System`` (SymPy >= 1.13) whose
        kinematic equations are u = qdot: L = ``Lagrangian(frame, *bodies)`` (with each
        body's ``potential_energy``), its nonholonomic constraints solved for the
        velocities of ``system.u_dep`` (or of ``dependent``).  Loads and holonomic
        constraints are refused."""
        from .mechanics_input import from_system
        return from_system(cls, system, dependent, name)

    def _exact(self, expr):
        """``expr`` with its Floats as the exact rationals they print as (recorded)."""
        return exact_rationals(expr, self.rationalized) if isinstance(expr, sp.Basic) else expr

    # ----- notation -------------------------------------------------------
    def _make_symbols(self):
        self.q, self.qd, self.qdd = {}, {}, {}
        for c in self.coordinates:
            n = _name(c)
            self.q[c] = sp.Symbol(n, **_sign_assumptions(c))
            self.qd[c] = sp.Symbol(n + "dot")
            self.qdd[c] = sp.Symbol(n + "ddot")
        self._all_symbols = [*self.q.values(), *self.qd.values(), *self.qdd.values()]
        self._names = {s.name for s in self._all_symbols}
        self._to_internal = {}
        for c in self.coordinates:      # (Derivative(c, t) is c.diff(t), without diff's walk)
            self._to_internal[sp.Derivative(c, (self._t, 2))] = self.qdd[c]
            self._to_internal[sp.Derivative(c, self._t)] = self.qd[c]
            self._to_internal[c] = self.q[c]
        self._to_public = {v: k for k, v in self._to_internal.items()}

    def _velocity_owner(self, key):
        if not (isinstance(key, sp.Derivative) and key.variables == (self._t,)
                and key.expr in self.coordinates):
            raise ModelError(f"dependent: key {key!r} is not the velocity of one of the "
                             f"coordinates {self.coordinates}; write it as y.diff(t) (1.1)")
        return key.expr

    def _internal(self, expr, what):
        clash = sorted(str(s) for s in expr.free_symbols if s.name in self._names)
        if clash:
            raise ModelError(f"{what} contains the symbol {clash[0]}, which has the name of a "
                             "coordinate or velocity; rename it (the derivation uses plain "
                             "symbols for q and qdot)")
        check_values(expr, what)
        e = substitute(expr, self._to_internal)        # xreplace, each shared node once
        nodes = subexpressions(e)                  # one walk for the tests below, not one each
        for d in sorted((n for n in nodes if isinstance(n, sp.Derivative)), key=sp.default_sort_key):
            raise ModelError(f"{what} contains {d.xreplace(self._to_public)}, which is not "
                             "a velocity or acceleration of a listed coordinate")
        for f in sorted((n for n in nodes if isinstance(n, AppliedUndef)), key=sp.default_sort_key):
            raise ModelError(f"{what} depends on {f}, which is not among the coordinates "
                             f"{self.coordinates}")
        free = e.free_symbols
        if self._t in free or T in free:
            raise ModelError(f"{what} depends explicitly on t: the Chaplygin conditions (1.3) "
                             "require L and the constraints to be free of t")
        if any(self.qdd[c] in free for c in self.coordinates):
            raise ModelError(f"{what} contains an acceleration; L and the constraints (1.1) "
                             "depend on coordinates and velocities only")
        # |u| = sqrt(u**2) for the real quantities here: a form SymPy differentiates
        # (the derivative of Abs of a symbol without assumptions is not evaluated)
        if any(isinstance(n, sp.Abs) for n in nodes):
            return e.replace(sp.Abs, lambda u: sp.sqrt(u**2))
        return e

    def _check_chaplygin(self):
        """The Chaplygin conditions (1.3), decided on what L and the constraints are, not on
        how they are written: an expression that contains a dependent coordinate s but
        whose derivative in s is zero (by the checks' exact-or-numeric zero test:
        A sin(psi)**2 + A cos(psi)**2 from ``me.Lagrangian`` of a symmetric disk) is
        rewritten free of s (:meth:`_free_of`); one whose derivative is not zero is refused."""
        dep_q = [self.q[c] for c in self.dependent_coordinates]
        dep_qd = [self.qd[c] for c in self.dependent_coordinates]
        for s in dep_q:
            if self._L.has(s):
                L = self._free_of(self._L, s, "L")
                if L is None:
                    raise ModelError(f"L depends on the dependent coordinate {readable(s)} "
                                     "(Chaplygin condition, 1.3: L must be free of the "
                                     "dependent coordinates q_(ε+β))")
                self._L = L
        for c in list(self._phi):
            for s in dep_q:
                if self._phi[c].has(s):
                    phi = self._free_of(self._phi[c], s, f"the constraint for {c}dot")
                    if phi is None:
                        raise ModelError(f"the constraint for {c}dot depends on the dependent "
                                         f"coordinate {s} (Chaplygin condition, 1.3)")
                    self._phi[c] = phi
            for s in dep_qd:
                if self._phi[c].has(s):
                    raise ModelError(f"the constraint for {c}dot is written with another "
                                     f"dependent velocity {s}: write each dependent velocity "
                                     "in the independent velocities only (1.1)")

    def _free_of(self, expr, s, what):
        """``expr`` rewritten without the dependent coordinate ``s`` when d expr/ds is zero
        (``check_zero``), else None.  Only the terms that contain s are rewritten: first
        collected on the velocities (expand, group, factor each coefficient, sin**2 + cos**2
        as 1: ``rewrite.collected``), else with s set to a fixed value at which they are
        finite; either is kept only when the zero test shows it equal to the terms as
        given, and recorded for step (1.3), whose check repeats that test."""
        if not check_zero("1.3", "", self._d(expr, s), self._sample_time, seed=3).holds:
            return None
        terms = sp.Add.make_args(expr)
        affected = add(*[t for t in terms if t.has(s)])
        kept = [t for t in terms if not t.has(s)]
        tries = [collected(affected, list(self.qd.values()))]
        tries += [substitute(affected, {s: v}) for v in (sp.S.Zero, sp.S.Half, sp.S.One)]
        for new in tries:
            if new.has(s) or new.has(sp.nan, sp.zoo, sp.oo, -sp.oo):
                continue
            if check_zero("1.3", "", sub(affected, new), self._sample_time, seed=3).holds:
                self._rewritten.append((what, s, affected, new))
                return add(*kept, new)
        return None

    def to_public(self, expr):
        """Rewrite an expression of the internal symbols (x, xdot, xddot) in dynamicsymbols
        (one memo for the system: the public results share most of their pieces)."""
        return substitute(expr, self._to_public, self._cache.setdefault("public", {}))

    # ----- properties -----------------------------------------------------
    def _d(self, f, z):
        """df/dz, as ``f.diff(z)`` builds it, each shared subexpression differentiated once."""
        return diff(f, z, self._dmemo)

    @property
    def is_holonomic(self):
        """True when there are no dependent velocities (g = 0)."""
        return not self.dependent_coordinates

    @property
    def _sig(self):
        return self.independent_coordinates

    @property
    def _Ltilde(self):
        if "Lt" not in self._cache:
            self._cache["Lt"] = self._L.xreplace(
                {self.qd[c]: phi for c, phi in zip(self.dependent_coordinates, self._phi.values())})
        return self._cache["Lt"]

    @property
    def L_tilde(self):
        """L~: the Lagrangian with the dependent velocities substituted (after 1.2)."""
        return self.to_public(self._Ltilde)

    def _dLdqdep_tilde(self):
        """(dL/d qdot_(eps+beta)) with the constraints substituted, per dependent coordinate."""
        sub = {self.qd[c]: phi for c, phi in zip(self.dependent_coordinates, self._phi.values())}
        return [self._d(self._L, self.qd[c]).xreplace(sub) for c in self.dependent_coordinates]

    def _velocity_symbols(self):
        return [self.qdd[c] for c in self._sig] + [self.qd[c] for c in self._sig]

    def _dt(self, f):
        """Total time derivative of f(q_sigma, qdot_sigma) along a motion."""
        return add(*[t for c in self._sig for t in (mul(self._d(f, self.q[c]), self.qd[c]),
                                                     mul(self._d(f, self.qd[c]), self.qdd[c]))])

    # ----- (1.4) ----------------------------------------------------------
    def _eom(self):
        if "eom" not in self._cache:
            Lt = self._Ltilde
            P = self._dLdqdep_tilde()
            eqs = []
            for c in self._sig:
                qd, q = self.qd[c], self.q[c]
                e = self._dt(self._d(Lt, qd)) - self._d(Lt, q)
                for Pb, phi in zip(P, self._phi.values()):
                    term = self._dt(self._d(phi, qd)) - self._d(phi, q)
                    if term != 0:       # Pb*0 would ask whether every factor of Pb is finite
                        e -= mul(Pb, term)
                eqs.append(e if self._large else collected(e, self._velocity_symbols()))
            self._cache["eom"] = eqs
        return self._cache["eom"]

    @property
    def _large(self):
        """More than ``COLLECT_SIGMA_LIMIT`` independent coordinates: (1.4) and (1.11) are
        solved and checked as derived, and collected (a rewrite to read) only to show."""
        return len(self._sig) > COLLECT_SIGMA_LIMIT

    def _eom_shown(self):
        """(1.4) to read: collected on the accelerations and velocities."""
        if not self._large:
            return self._eom()
        if "eom_shown" not in self._cache:
            self._cache["eom_shown"] = [collected(e, self._velocity_symbols())
                                        for e in self._eom()]
        return self._cache["eom_shown"]

    @guarded("deriving (1.4)")
    def equations_of_motion(self):
        """The generalized Chaplygin equations (1.4), one expression (= 0) per q_sigma."""
        return [self.to_public(e) for e in self._eom_shown()]

    def _accelerations(self):
        if "acc" not in self._cache:
            qdd = [self.qdd[c] for c in self._sig]
            eqs = sp.Matrix(self._eom())
            M = sp.Matrix([[self._d(e, a) for a in qdd] for e in eqs])
            memo = {}
            rest = sp.Matrix([zeroed(e, qdd, memo) for e in eqs])
            sol = self._solve(M, rest, "the mass matrix d(1.4)/d(qddot_sigma)",
                              self._sample_time)
            self._cache["acc"] = dict(zip(qdd, sol))
        return self._cache["acc"]

    def _tidy_accelerations(self):
        """The accelerations as one fraction each, to read (``rewrite.rational``)."""
        if "acc_tidy" not in self._cache:
            vel = [self.qd[c] for c in self._sig]
            self._cache["acc_tidy"] = {a: rational(x, vel)
                                       for a, x in self._accelerations().items()}
        return self._cache["acc_tidy"]

    @guarded("solving (1.4) for the accelerations")
    def accelerations(self, dependent=False):
        """The accelerations solved from (1.4): {q_sigma.diff(t, 2): expression}; with
        ``dependent=True`` also the dependent coordinates', d/dt of the constraints (1.3)
        with these accelerations (as ``LagrangesMethod.rhs()`` gives every coordinate's)."""
        out = {self.to_public(k): self.to_public(v)
               for k, v in self._tidy_accelerations().items()}
        if dependent:
            acc, memo = self._accelerations(), {}
            for c, phi in zip(self.dependent_coordinates, self._phi.values()):
                out[c.diff(self._t, 2)] = self.to_public(substitute(self._dt(phi), acc, memo))
        return out

    @guarded("the constraint multipliers")
    def multipliers(self):
        """The Lagrange multipliers of the constraints along the motion, one per
        constraint, in ``LagrangesMethod``'s convention: d/dt dL/dqdot_s - dL/dq_s +
        sum_i lambda_i df_i/dqdot_s = 0 for every coordinate, f_i the constraints as given
        (``nonhol_coneqs`` in their order, or f of ``{ydot: f}``, or ``lhs - rhs`` of an
        ``Eq``) or f = ydot - phi (given solved, ``{ydot: phi}``); each a
        function of q and the independent velocities (the constraint force is
        -lambda df/dqdot).  Empty for a holonomic system."""
        deps = self.dependent_coordinates
        if not deps:
            return []
        sub = dict(zip([self.qd[c] for c in deps], self._phi.values()))
        if self._coneqs is not None:
            fs = [self._internal(f, "a constraint of nonhol_coneqs") for f in self._coneqs]
        else:
            fs = [self.qd[c] - phi for c, phi in zip(deps, self._phi.values())]
        C = sp.Matrix([[self._d(f, self.qd[c]).xreplace(sub) for c in deps] for f in fs])
        acc, memo = self._accelerations(), {}
        E = sp.Matrix([substitute(self._dt(P), acc, memo) for P in self._dLdqdep_tilde()])
        lam = solve_with_regular_poles(C.T, -E)   # poles only where C.T is singular
        return [self.to_public(v) for v in lam]

    @guarded("generating the numeric right-hand side")
    def lambdify_rhs(self, modules="math"):
        """``f(t, state, params)``, the full model as one numeric function (``lambdify``
        with common subexpressions): state = [every coordinate, then the independent
        velocities], result = its time derivative; see :mod:`.numeric_rhs`."""
        from .numeric_rhs import system_rhs
        return system_rhs(self, modules)

    def _solve(self, M, rest, what, sample):
        """The solution x of M x + rest = 0, once ``M`` is shown regular at a sampled
        point.  A large matrix (more than ``PIVOT_BY_VALUE_NODES`` nodes) takes as LU
        pivot the first entry whose value at that point is not 0: an entry nonzero at a
        point is not identically zero, and the point's matrix is regular, so a pivot is
        always found.  SymPy's default asks ``is_zero`` of every candidate, which on a
        large entry is a long walk of assumption queries (a seventh of the holonomic
        family's reduce at n = 8); small matrices keep SymPy's own choice."""
        point = self._require_regular(M, what, sample)
        n = M.rows
        if all(M[i, j] is sp.S.Zero for i in range(n) for j in range(n) if i != j):
            return [mul(-rest[i], power(M[i, i], -1)) for i in range(n)]
        small = within_size(list(M), PIVOT_BY_VALUE_NODES)
        try:
            return lu_solve(M, -rest) if small else lu_solve(M, -rest, _zero_at(point))
        except ValueError as err:
            raise ModelError(f"singular kinetic energy: {what} is singular (1.4)") from err

    def _require_regular(self, M, what, sample):
        """The values at a sampled point where ``M`` is regular (det far from 0), as a
        :class:`.verify.At`, or ModelError (a singular kinetic energy, 1.4)."""
        rng = random.Random(7)
        rows = M.tolist()
        diagonal = all(e is sp.S.Zero for i, row in enumerate(rows) for j, e in enumerate(row)
                       if i != j)
        with mpmath.workdps(DPS):
            for _ in range(3):
                at = At(sample(rng))
                try:
                    if diagonal:            # the determinant is the product of the diagonal
                        d = mpmath.fprod(at(row[i]) for i, row in enumerate(rows))
                    else:
                        d = mpmath.det(mpmath.matrix([[at(e) for e in row] for row in rows]))
                except (ZeroDivisionError, ValueError, OverflowError, TypeError):
                    continue
                except (Unevaluable, KeyError) as err:
                    raise ModelError(f"{what} cannot be evaluated numerically to check that "
                                     f"it is regular (1.4): {err}") from err
                if abs(d) > mpmath.mpf(10) ** (-DPS // 2):
                    return at
        raise ModelError(f"singular kinetic energy: {what} is singular, so the accelerations "
                         "cannot be solved (1.4); is the kinetic energy positive definite in "
                         "the independent velocities?")

    # ----- (1.10), (1.11) -------------------------------------------------
    def _euler_residuals(self):
        return [sp.Add(*[self._d(phi, self.qd[c]) * self.qd[c] for c in self._sig], -phi)
                for phi in self._phi.values()]

    @guarded("checking (1.10)")
    def check_homogeneity(self):
        """Check (1.10): every constraint is homogeneous of degree one in the independent
        velocities.  Raises ModelError if not: the energy (1.11) is then not guaranteed
        to be conserved (for some constraints it still is), and (1.22)-(1.26) need (1.10)."""
        if "1.10" not in self._cache:
            res = []
            for c, r in zip(self.dependent_coordinates, self._euler_residuals()):
                phi = f"${sp.latex(self.qd[c])} = \\varphi_{{{sp.latex(self.q[c])}}}$"
                chk = check_zero("1.10", phi + " is homogeneous of degree one in the "
                                 "independent velocities (Euler's relation)",
                                 r, self._sample_time, seed=10)
                if not chk.holds:
                    raise ModelError(
                        f"the constraint {_name(c)}' = {readable(self.constraints[c.diff(self._t)])}"
                        " (a prime: d/dt) is not "
                        "homogeneous of degree one in the independent velocities: (1.10) fails: "
                        "the energy (1.11) is not guaranteed to be conserved, and the "
                        "reduction (1.22)-(1.26) needs (1.10)")
                res.append(chk)
            self._cache["1.10"] = res
        return self._cache["1.10"]

    def _energy(self):
        if "E" not in self._cache:
            Lt = self._Ltilde
            E = add(*[mul(self.qd[c], self._d(Lt, self.qd[c])) for c in self._sig], negated(Lt))
            self._cache["E"] = E if self._large else collected(E, self._velocity_symbols())
        return self._cache["E"]

    def _energy_shown(self):
        """(1.11) to read: collected on the velocities."""
        if not self._large:
            return self._energy()
        if "E_shown" not in self._cache:
            self._cache["E_shown"] = collected(self._energy(), self._velocity_symbols())
        return self._cache["E_shown"]

    @guarded("deriving the energy integral (1.11)")
    def energy(self):
        """The energy integral (1.11): sum qdot_sigma dL~/dqdot_sigma - L~ (its value is h)."""
        self.check_homogeneity()
        return self.to_public(self._energy_shown())

    def _energy_rate(self):
        """dE/dt along the solutions of (1.4): zero when (1.11) is an integral."""
        E = self._energy()
        return substitute(self._dt(E), self._accelerations())

    def _check_energy_rate(self):
        """The check of (1.11): dE/dt = 0 along (1.4).  When dE/dt and the accelerations are
        small enough for an exact attempt, the accelerations are substituted; otherwise
        they are replaced at evaluation (``check_zero``'s ``at``), the substituted
        expression, often large, never built."""
        claim = "$dE/dt = 0$ along the solutions of (1.4)"
        rate, acc = self._dt(self._energy()), self._accelerations()
        if within_size([rate, *acc.values()], EXACT_SIZE_LIMIT):
            return check_zero("1.11", claim, self._energy_rate(), self._sample_time, seed=11)
        return check_zero("1.11", claim, rate, self._sample_time, seed=11, at=acc)

    # ----- random admissible points --------------------------------------
    def _sample_params(self, rng, pt):
        for p in self.parameters:
            val = rng.uniform(0.5, 2.0)
            pt[p] = -val if p.is_negative else val
        return pt

    def _sample_time(self, rng):
        """A random point in (parameters, q, qdot, qddot)."""
        pt = self._sample_params(rng, {})
        for c in self.coordinates:
            pt[self.q[c]] = rng.uniform(0.1, 1.2) * (-1 if self.q[c].is_negative else 1)
            pt[self.qd[c]] = rng.choice((-1, 1)) * rng.uniform(0.2, 1.5)
            pt[self.qdd[c]] = rng.uniform(-1, 1)
        return pt

    # ----- steps ----------------------------------------------------------
    def _steps(self):
        """The time-domain steps (1.1)-(1.4), (1.10), (1.11) for this system."""
        steps = []
        dep_q = [self.q[c] for c in self.dependent_coordinates]
        floats = self._floats_check()
        note = floats and floats.claim.replace("$", "")
        if self.is_holonomic:
            steps.append(Step("1.1", "constraints: none ($g = 0$, a holonomic system)", [],
                              floats, note=note or ""))
        else:
            steps.append(Step("1.1", "the dependent velocities, solved for (Chetaev-type ideal "
                              "constraints)",
                              lambda: [eq(self.qd[c], phi) for c, phi in
                                       zip(self.dependent_coordinates, self._phi.values())], floats,
                              note=note or ""))
        steps.append(Step("1.2", r"the Lagrangian with the constraints substituted, "
                          r"$\tilde L$ of (1.2)",
                          lambda: [eq(sp.Symbol("Ltilde"), self._Ltilde)], dep_q and check_zero(
            "1.2", r"the terms of (1.2) in $\partial\varphi/\partial q_{\varepsilon+\beta}$ and "
            r"$\partial\tilde L/\partial q_{\varepsilon+\beta}$ vanish (Chaplygin type)",
            [self._d(phi, s) for phi in self._phi.values() for s in dep_q]
            + [self._d(self._Ltilde, s) for s in dep_q], self._sample_time) or None,
            tag=r"[$\tilde L$]"))
        if not self.is_holonomic:
            free = ", ".join(f"${sp.latex(self.q[c])}$" for c in self.independent_coordinates)
            steps.append(Step("1.3", f"Chaplygin type: each constraint depends on {free} and "
                              "their velocities only (checked when the model was built)",
                              lambda: [eq(self.qd[c], sp.Function("phi_" + _name(c))(
                                  *[self.q[i] for i in self._sig], *[self.qd[i] for i in self._sig]))
                                  for c in self.dependent_coordinates]
                              + [eq(old, new) for _, _, old, new in self._rewritten],
                              self._rewritten_check(), note=self._rewritten_note()))
        at = {}
        chk = check_zero("1.4", "the solved accelerations satisfy (1.4)",
                         [substitute(e, self._accelerations(), at) for e in self._eom()],
                         self._sample_time, seed=4)
        steps.append(Step("1.4", r"the generalized Chaplygin equations, one per $q_\sigma$",
                          lambda: [eq(e, 0) for e in self._eom_shown()], chk))
        steps.append(Step("1.4a", "the accelerations solved from (1.4)",
                          lambda: [eq(k, v) for k, v in self._tidy_accelerations().items()]))
        if not self.is_holonomic:
            h = self.check_homogeneity()
            worst = max(h, key=lambda c: (c.method == "numeric", c.max_residual))
            steps.append(Step("1.10", "the constraints are homogeneous of degree one: "
                              r"Euler's relation $\sum_\sigma (\partial\varphi/\partial"
                              r"\dot q_\sigma)\,\dot q_\sigma = \varphi$, with the partial "
                              "derivatives of this system", lambda: self._euler_shown(), worst,
                              note="(1.10) and (1.11) belong to the system in time: they are "
                              "shown with it, before the change of variable (1.5)-(1.9)"))
        chk = self._check_energy_rate()
        steps.append(Step("1.11", "the energy integral",
                          lambda: [eq(self._energy_shown(), sp.Symbol("h"))], chk))
        return steps

    def _rewritten_check(self):
        """None, or the check that each part of L or of a constraint written with a
        dependent coordinate equals its rewriting free of it (:meth:`_free_of`)."""
        if not self._rewritten:
            return None
        names = ", ".join(f"{what} (${sp.latex(s)}$)" for what, s, _, _ in self._rewritten)
        return check_zero("1.3", "the terms written with a dependent coordinate do not depend "
                          f"on it: {names}, each equal to its rewriting free of it",
                          [sub(old, new) for _, _, old, new in self._rewritten],
                          self._sample_time, seed=3)

    def _rewritten_note(self):
        if not self._rewritten:
            return ""
        return ("; ".join(f"{what} is written with the dependent coordinate {readable(s)} "
                          "but does not depend on it: those terms are rewritten free of it "
                          "(shown as given = rewritten, equal by the check)" for what, s, _, _ in
                          self._rewritten))

    def _floats_check(self):
        """None, or the check that each Float of the input was taken as the rational it
        prints as, equal to it to the Float's precision (a relative difference below
        10**(1 - digits), digits the Float's decimal precision)."""
        if not self.rationalized:
            return None
        worst, ok = 0.0, True
        for f, r in self.rationalized.items():
            digits = mpmath.libmp.prec_to_dps(f._prec)
            with mpmath.workprec(f._prec + 64):
                d = abs(mpmath.mpf(f._mpf_) - mpmath.mpf(r.p) / r.q)
                rel = d / max(abs(mpmath.mpf(r.p) / r.q), mpmath.mpf(10) ** -digits)
            worst = max(worst, float(rel))
            ok = ok and rel < mpmath.mpf(10) ** (1 - digits)
        pairs = ", ".join(f"{float(f)!r} = {r}" if f._prec == 53 else f"{f} = {r}"
                          for f, r in sorted(self.rationalized.items(), key=lambda i: i[1]))
        from .verify import Check
        return Check("1.1", "the Float coefficients are taken as the exact rationals they "
                     f"print as ({pairs}); the model derived and checked is the rational one",
                     ok, "exact", "Rational(str(Float)), equal to each Float to its "
                     f"precision: largest relative difference {worst:.1e}")

    def _euler_shown(self):
        """(1.10) as the paper writes it, and the partial derivatives it is made of."""
        from .steps import partial
        out = []
        for c, phi in zip(self.dependent_coordinates, self._phi.values()):
            name = "φ_" + _name(c)
            tex = r"\varphi_{" + sp.latex(self.q[c]) + "}"
            sym = sp.Symbol("phi_" + _name(c))     # φ_y in Unicode, \varphi_{y} in LaTeX
            sig = [self.qd[i] for i in self._sig]
            out.append(eq(sp.Add(*[partial(name, tex, v) * v for v in sig]), sym))
            out += [eq(partial(name, tex, v), phi.diff(v)) for v in sig]
            out.append(eq(sym, phi))
        return out

    @property
    @guarded("deriving the time-domain steps")
    def steps(self):
        """The time-domain steps as a :class:`~whittaker_teach.steps.Derivation`."""
        if "steps" not in self._cache:
            with shared_points():
                self._cache["steps"] = Derivation(f"{self.name}: Chaplygin equations",
                                                  self._steps())
        return self._cache["steps"]

    @guarded("verifying the time-domain steps")
    def verify(self):
        """Re-run the time-domain checks; a :class:`~whittaker_teach.steps.Report`."""
        self._cache.pop("steps", None)
        self._cache.pop("1.10", None)
        return Report(s.check for s in self.steps if s.check)

    @guarded("showing the steps")
    def show(self, latex=False):
        """Show the time-domain steps (notebook: rendered maths; terminal: Unicode)."""
        return self.steps.show(latex=latex)

    # ----- reduction ------------------------------------------------------
    @guarded("the Whittaker reduction")
    def reduce(self, coordinate, direction=+1):
        """The Whittaker reduction with ``coordinate`` as q_eps, travelled with
        sign(qdot_eps) = ``direction``: a :class:`~whittaker_teach.reduction.Reduction`."""
        return Reduction(self, coordinate, direction)

    def __repr__(self):
        kind = "holonomic" if self.is_holonomic else "non-holonomic"
        floats = (f", {len(self.rationalized)} Float coefficient(s) taken as exact rationals"
                  if self.rationalized else "")
        return (f"<ChaplyginSystem {self.name!r}: {kind}, coordinates "
                f"{[_name(c) for c in self.coordinates]}{floats}>")

    # ----- numerics (whittaker_teach.numerics) -----------------------------
    def simulate(self, q0, qdot0, t_span, params, method="DOP853", rtol=1e-9, atol=None,
                 **options):
        """Integrate the full model in time: (1.4) and the constraints (1.3).

        ``q0``: {coordinate: value} for every coordinate; ``qdot0``: {coordinate:
        value} for the independent ones; ``params``: {parameter: value}.
        ``method``: a scipy method (``"DOP853"``, ``"RK45"``, ``"Radau"``,
        ``"LSODA"``, ...) or ``"DLA"`` (fixed step ``dt=``, structure preserving);
        ``atol=None`` means atol = rtol.  Options: ``formulation`` (``"auto"``,
        ``"chaplygin"``, ``"multiplier"``), ``t_eval``, ``dense``, and for DLA
        ``max_energy_error`` (a guard against a too coarse step).  Returns a
        :class:`~whittaker_teach.numerics.results.Trajectory`.  With ``tol=`` (a
        relative error) instead of method/rtol, the package picks the model and
        the method (the closed form where one exists, else the full model with a
        checked rtol); ``traj.explain()`` says which and why
        (:mod:`whittaker_teach.numerics.scene`).
        """
        from .backends import provided      # numerics registers it: the core imports none
        return provided("simulate")(self, q0, qdot0, t_span, params, method, rtol, atol,
                                    **options)
