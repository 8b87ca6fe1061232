"""Models as ``sympy.physics.mechanics`` gives them: constraints as expressions = 0,
``LagrangesMethod`` and ``System`` objects, Float coefficients.

:class:`~whittaker_teach.system.ChaplyginSystem` takes its constraints solved for
the dependent velocities, ``{ydot: phi}``.  A mechanics user has them as
``LagrangesMethod(nonhol_coneqs=...)`` and ``System.add_nonholonomic_constraints``
take them: expressions f(q, qdot) = 0 (or ``Eq``), such as
``P.vel(N).dot(B.y)``.  Here such constraints are solved for the dependent
velocities the user names: a linear one by one linear solve; a nonlinear one by
``sympy.solve``, which must give exactly one solution (``zdot**2 = xdot**2 + ydot**2``
has two, and the error says to pass the branch meant as ``{zdot: phi}``).

>>> import sympy as sp
>>> from sympy.physics.mechanics import dynamicsymbols
>>> x, th, y = dynamicsymbols("x theta y")
>>> t = dynamicsymbols._t
>>> solved_velocities([y.diff(t)*sp.cos(th) - x.diff(t)*sp.sin(th)], [y.diff(t)], t)
{Derivative(y(t), t): sin(theta(t))*Derivative(x(t), t)/cos(theta(t))}

Float coefficients (``0.5*m*xdot**2``) are taken as the exact rationals they
print as (:func:`exact_rationals`: ``Rational(str(f))``, 0.845 -> 169/200), so
that every identity of the derivation is checked exactly or to 40 digits as for
a rational model; the system lists them (``system.rationalized``) and its step
(1.1) says so, with a check that each rational equals its Float to the Float's
precision.

>>> exact_rationals(0.5*x**2 + sp.Float(0.845)*x, {})
x(t)**2/2 + 169*x(t)/200
"""

from __future__ import annotations

import sympy as sp

from . import polywalk
from .dag import diff
from .errors import ModelError, ModelTypeError
from .linear import fraction_free_solve
from .rewrite import FACTOR_LIMIT, _ops_above, factored, pythagoras

__all__ = ["exact_rationals", "constraint_expressions", "solved_velocities",
           "from_lagranges_method", "from_system", "speeds_as_velocities"]


def exact_rationals(expr, record):
    """``expr`` with every Float replaced by the rational it prints as
    (``Rational(str(f))``); each replacement is added to ``record`` {Float: Rational}."""
    floats = expr.atoms(sp.Float)
    if not floats:
        return expr
    sub = {f: sp.Rational(str(f)) for f in floats}
    record.update(sub)
    return expr.xreplace(sub)


def constraint_expressions(items, what="nonhol_coneqs"):
    """A list of expressions f (= 0) from an expression, an ``Eq`` or a list/Matrix of them."""
    if isinstance(items, (sp.Expr, sp.Eq)) or not hasattr(items, "__iter__") \
            or isinstance(items, str):
        items = [items]
    out = []
    for f in items:
        if isinstance(f, sp.Eq):
            f = f.lhs - f.rhs
        if isinstance(f, bool) or not isinstance(f, (sp.Expr, int, float)):
            raise ModelTypeError(f"{what}: each constraint must be a SymPy expression (= 0) or "
                                 f"an Eq, got {type(f).__name__} {f!r:.60}")
        out.append(sp.sympify(f))
    return out


def solved_velocities(constraints, velocities, t):
    """{velocity: phi} solving the constraints (expressions = 0) for ``velocities``: a
    linear system by one linear solve, otherwise ``sympy.solve`` with a unique solution.
    A clear ModelError when they cannot be solved so."""
    names = ", ".join(str(v.expr.func.__name__) + "dot" for v in velocities)
    if len(constraints) != len(velocities):
        raise ModelError(f"{len(constraints)} constraint(s) for {len(velocities)} dependent "
                         f"velocit{'y' if len(velocities) == 1 else 'ies'} ({names}): give one "
                         "constraint per dependent coordinate (1.1: g constraints, g dependent "
                         "velocities)")
    for f in constraints:
        if not any(f.has(v) for v in velocities):
            raise ModelError(f"the constraint {f} = 0 contains none of the dependent "
                             f"velocities {names}: it cannot be solved for them (1.1)")
    # the velocities as plain symbols while differentiating (SymPy differentiates with
    # respect to a Derivative by substituting a symbol for it at every call)
    as_symbol = {v: sp.Dummy() for v in velocities}
    back = {d: v for v, d in as_symbol.items()}
    plain = [f.xreplace(as_symbol) for f in constraints]
    J = sp.Matrix([[diff(f, as_symbol[v]) for v in velocities] for f in plain])
    if not J.has(*back):                             # linear in the dependent velocities
        zero = {d: 0 for d in back}
        rest = sp.Matrix([f.xreplace(zero) for f in plain])
        g = len(velocities)
        if all(J[i, j] == 0 for i in range(g) for j in range(g) if i != j):   # one each
            if any(J[i, i] == 0 for i in range(g)):
                raise ModelError(f"the constraints cannot be solved for {names}: a "
                                 "constraint does not contain its velocity (1.1)")
            return {v: -rest[i] / J[i, i] for i, v in enumerate(velocities)}
        if J.det() == 0:
            raise ModelError(f"the constraints cannot be solved for {names}: their matrix of "
                             "coefficients of these velocities is singular (1.1)")
        sol = _solved_linear(J, rest)
        return {v: e.xreplace(back) for v, e in zip(velocities, sol)}
    try:
        sols = sp.solve(constraints, velocities, dict=True)
    except (NotImplementedError, ValueError, TypeError) as err:
        raise ModelError(f"the constraints {constraints} = 0 cannot be solved for {names} "
                         f"(sympy.solve: {err}); pass them solved, as dependent={{{names}: "
                         "phi}} (1.1)") from err
    sols = [s for s in sols if all(v in s for v in velocities)]
    if not sols:
        raise ModelError(f"the constraints {constraints} = 0 have no solution for {names} "
                         "that sympy.solve finds; pass them solved, as dependent={ydot: phi} "
                         "(1.1)")
    if len(sols) > 1:
        shown = "; ".join(str({str(k): v for k, v in s.items()}) for s in sols)
        raise ModelError(f"the constraints have {len(sols)} solutions for {names} ({shown}): "
                         "pass the branch you mean solved, as dependent={ydot: phi} (1.1)")
    return {v: sols[0][v] for v in velocities}


def _solved_linear(J, rest):
    """The solution x of J x + rest = 0, each entry one fraction whose denominator divides
    det J (:func:`.linear.fraction_free_solve`): LU's pivots would divide by entries that
    may vanish where J is regular (-sin(theta) for a matrix of determinant sin(phi)),
    giving every solved velocity a pole there.  A fraction is shown factored, any
    sin**2 + cos**2 in it as 1.  Where the entries are not rational functions of their
    symbols, functions and roots, or too large for a gcd, SymPy's ``LUsolve``."""
    velocities = sorted(set().union(*(e.atoms(sp.Derivative) for e in (*J, *rest))),
                        key=sp.default_sort_key)
    plain = {v: sp.Dummy() for v in velocities}
    try:
        parts = fraction_free_solve(J.xreplace(plain), -rest.xreplace(plain))
    except (polywalk.NotPolynomial, polywalk.TooLarge):
        return list(J.LUsolve(-rest))
    except ValueError as err:               # singular as polynomials: det J == 0 missed it
        raise ModelError("the constraints cannot be solved for the dependent velocities: "
                         "their matrix of coefficients of these velocities is singular "
                         "(1.1)") from err
    back = {d: v for v, d in plain.items()}
    out = []
    for num, den in parts:
        if den != 1 and not _ops_above(den, FACTOR_LIMIT):
            den = pythagoras(factored(den))
            if not _ops_above(num, FACTOR_LIMIT):
                num = pythagoras(factored(num))
        out.append((num / den).xreplace(back))
    return out


def _coordinate_of(item, coordinates, t):
    """The coordinate named by ``item``: the coordinate, its velocity or its name."""
    if isinstance(item, str):
        match = [c for c in coordinates if c.func.__name__ == item]
        if match:
            return match[0]
    elif isinstance(item, sp.Derivative) and item.variables == (t,) and item.expr in coordinates:
        return item.expr
    elif item in coordinates:
        return item
    raise ModelError(f"dependent: {item!r} is not one of the coordinates "
                     f"{list(coordinates)} nor its velocity (1.1)")


def dependent_velocities(dependent, coneqs, coordinates, t):
    """Every accepted form of ``dependent`` (and ``nonhol_coneqs``) as {qdot_dep: phi},
    with the constraints as given (expressions = 0, for the multipliers), or None when
    every constraint was given solved:

    - ``{ydot: phi}``: solved already (phi free of ydot), as before;
    - ``{ydot: f}`` with f containing ydot, or ``{ydot: Eq(...)}``: f = 0 solved for ydot;
    - ``[Eq(ydot, phi), ...]``: equations whose left side is a dependent velocity;
    - ``nonhol_coneqs=[f, ...]`` (expressions = 0 or Eq) with ``dependent=[y, ...]``
      (coordinates, their velocities or names): solved for those velocities."""
    if coneqs is not None:
        fs = constraint_expressions(coneqs)
        if dependent is None or isinstance(dependent, dict):
            raise ModelError("nonhol_coneqs needs the dependent coordinates named, the "
                             "velocities to solve the constraints for: "
                             "ChaplyginSystem(L, qs, nonhol_coneqs=[...], dependent=[y]) (1.1)")
        deps = [_coordinate_of(d, coordinates, t) for d in _as_list(dependent)]
        return solved_velocities(fs, [c.diff(t) for c in deps], t), fs
    if dependent is None:
        return {}, None
    if isinstance(dependent, dict):
        out, implicit = {}, []
        for k, v in dependent.items():
            if isinstance(v, sp.Eq):
                implicit.append((k, v.lhs - v.rhs))
            elif isinstance(v, sp.Basic) and v.has(k):
                implicit.append((k, v))
            else:
                out[k] = v
        if not implicit:
            return out, None
        for k, _ in implicit:
            _coordinate_of(k, coordinates, t)
        out.update(solved_velocities([f for _, f in implicit], [k for k, _ in implicit], t))
        given = dict(implicit)
        return out, [given[k] if k in given else k - v for k, v in out.items()]
    items = _as_list(dependent)
    if items and all(isinstance(e, sp.Eq) for e in items):
        keys = [e.lhs for e in items]
        for k in keys:
            _coordinate_of(k, coordinates, t)
            if not isinstance(k, sp.Derivative):
                raise ModelError(f"dependent: the left side of {k} = ... is not a velocity; "
                                 "write Eq(y.diff(t), phi) (1.1)")
        fs = [e.lhs - e.rhs for e in items]
        return solved_velocities(fs, keys, t), fs
    if items and all(not isinstance(e, sp.Eq) for e in items):
        try:
            [_coordinate_of(d, coordinates, t) for d in items]
        except ModelError:
            pass
        else:
            raise ModelError("dependent=[...] names the dependent coordinates; give their "
                             "constraints with nonhol_coneqs=[f, ...] (expressions = 0), or "
                             "pass dependent={ydot: phi} (1.1)")
    raise ModelTypeError("dependent must be a dict {y.diff(t): phi} (or {y.diff(t): f} with "
                         "f = 0), a list of Eq(y.diff(t), phi), or, with nonhol_coneqs=[f, ...], "
                         "the list of dependent coordinates [y] (1.1); got "
                         f"{type(dependent).__name__} {dependent!r:.60}")


def _as_list(x):
    if isinstance(x, (sp.Basic, str)) or not hasattr(x, "__iter__"):
        return [x]
    return list(x)


def from_lagranges_method(cls, lm, dependent=None, name=None):
    """A ChaplyginSystem from a ``LagrangesMethod`` (its Lagrangian, coordinates and
    ``nonhol_coneqs``); forces and holonomic constraints are refused (no energy integral
    (1.11) / coordinates to eliminate first)."""
    from sympy.physics.mechanics import LagrangesMethod
    if not isinstance(lm, LagrangesMethod):
        raise ModelTypeError(f"from_lagranges_method takes a LagrangesMethod, got "
                             f"{type(lm).__name__}")
    if lm.forcelist:
        raise ModelError("the LagrangesMethod has a forcelist: forces not derived from a "
                         "potential leave no energy integral (1.11), so no Whittaker "
                         "reduction; put a conservative force's potential into L")
    if len(lm._hol_coneqs):
        raise ModelError("the LagrangesMethod has holonomic constraints (hol_coneqs): "
                         "eliminate them by choosing independent coordinates; the paper's "
                         "constraints (1.1) are the nonholonomic ones")
    coneqs = list(lm.coneqs)
    L = lm._L[0]
    if coneqs and dependent is None:
        raise ModelError("name the dependent coordinates: "
                         "ChaplyginSystem.from_lagranges_method(lm, dependent=[y]) (1.1)")
    return cls(L, list(lm.q), dependent, nonhol_coneqs=coneqs or None, name=name)


def from_system(cls, system, dependent=None, name=None):
    """A ChaplyginSystem from a ``sympy.physics.mechanics.System``: L =
    Lagrangian(frame, *bodies) (each body's ``potential_energy`` counts) and the
    nonholonomic constraints, both with each speed u replaced by its expression in the
    velocities, read from the kinematic equations solved for u (:func:`speeds_as_velocities`:
    u_i = q_j' in any order, as joints give them and ``System.u`` reorders them once
    some are dependent, or any invertible u = f(q, q')); the dependent coordinates are
    those whose velocities the speeds of ``system.u_dep`` are, unless ``dependent`` names
    them.  Loads and holonomic constraints are refused."""
    from sympy.physics.mechanics import Lagrangian, dynamicsymbols
    t = dynamicsymbols._t
    if len(system.loads) or len(getattr(system, "actuators", ())):
        raise ModelError("the System has loads (forces or torques): the reduction needs a "
                         "conservative system (1.11); set each body's potential_energy "
                         "instead (e.g. body.potential_energy = m*g_0*z)")
    if len(system.holonomic_constraints):
        raise ModelError("the System has holonomic constraints: eliminate them by choosing "
                         "independent coordinates (the paper's constraints (1.1) are "
                         "nonholonomic)")
    q, u = list(system.q), list(system.u)
    u_to_qd = speeds_as_velocities(list(system.kdes), q, u, t)
    L = Lagrangian(system.frame, *system.bodies).xreplace(u_to_qd)
    coneqs = [f.xreplace(u_to_qd) for f in system.nonholonomic_constraints]
    if dependent is None and coneqs:
        by_velocity = {qi.diff(t): qi for qi in q}
        dependent = []
        for ud in system.u_dep:
            c = by_velocity.get(u_to_qd[ud])
            if c is None:
                raise ModelError(f"the dependent speed {ud} is {u_to_qd[ud]} by the kinematic "
                                 "equations, not the velocity of one coordinate: name the "
                                 "dependent coordinates, ChaplyginSystem.from_system(system, "
                                 "dependent=[y]) (1.1)")
            dependent.append(c)
        if len(dependent) != len(coneqs):
            raise ModelError("name the dependent coordinates: "
                             "ChaplyginSystem.from_system(system, dependent=[y]) (1.1)")
    return cls(L, q, dependent, nonhol_coneqs=coneqs or None, name=name)


def speeds_as_velocities(kdes, q, u, t):
    """{u_i: its expression in q and q'}, the kinematic equations (expressions = 0, one per
    speed) solved for the speeds: the map is read from the equations, never from the
    positions of u and q in their lists (``System.u`` lists the independent speeds first).

    >>> from sympy.physics.mechanics import dynamicsymbols
    >>> th, x = dynamicsymbols("theta x")
    >>> u1, u2 = dynamicsymbols("u1 u2")
    >>> t = dynamicsymbols._t
    >>> speeds_as_velocities([u2 - th.diff(t), u1 - x.diff(t)], [th, x], [u1, u2], t)
    {u1(t): Derivative(x(t), t), u2(t): Derivative(theta(t), t)}
    """
    if len(kdes) != len(u) or len(u) != len(q):
        raise ModelError("the System needs one kinematic equation per speed and one speed per "
                         f"coordinate ({len(q)} coordinates, {len(u)} speeds, {len(kdes)} "
                         "kinematic equations; add them with system.add_kdes(u - q.diff(t)))")
    qd = [qi.diff(t) for qi in q]
    as_symbol = {v: sp.Dummy() for v in qd}
    plain = [sp.sympify(f).xreplace(as_symbol) for f in kdes]
    try:
        sol = sp.solve(plain, u, dict=True)
    except (NotImplementedError, ValueError) as err:
        raise ModelError(f"the System's kinematic equations cannot be solved for u: {err}") \
            from err
    if len(sol) != 1 or set(sol[0]) != set(u):
        raise ModelError("the System's kinematic equations do not give each speed u as one "
                         "expression in the coordinates and their velocities (u = f(q, q')); "
                         "other kinematic equations are not supported")
    back = {d: v for v, d in as_symbol.items()}
    out = {ui: sol[0][ui].xreplace(back) for ui in u}
    for ui, e in out.items():
        if e.has(*u) or not e.has(*qd):
            raise ModelError(f"the System's kinematic equations give {ui} = {e}, not an "
                             "expression in the velocities q': other kinematic equations "
                             "are not supported")
    return out
