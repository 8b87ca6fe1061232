"""Steady motions (relative equilibria) of a Chaplygin system.

A **steady motion** here holds every *shape* coordinate at a constant value
(velocity 0) while every *moving* coordinate turns at a constant velocity.  For
that to be a solution of (1.4) with constant velocities, the accelerations [1.4a]
must not depend on the moving coordinates (they are **cyclic** in [1.4a]: checked
at 40 digits) and must vanish at the point.  The dependent coordinates follow by
the constraints (1.3) and are not part of the state.

>>> import sympy as sp
>>> import whittaker_teach as wt
>>> from whittaker_teach.stability import steady_motion
>>> sleigh = wt.examples.offset_sleigh()
>>> x, th, y = sleigh.coordinates
>>> v = sp.Symbol("v", positive=True)
>>> sm = steady_motion(sleigh, values={th: 0}, velocities={x: v})
>>> sm.family, sm.energy()
((v,), m*v**2/2)
"""

from __future__ import annotations

import random
from dataclasses import dataclass, field

import sympy as sp

from ..errors import ModelError, ModelTypeError
from ..system import ChaplyginSystem
from ..verify import check_zero

__all__ = ["SteadyMotion", "steady_motion", "find_steady_motions", "cyclic_coordinates", "conserved"]


def _require_system(system):
    if not isinstance(system, ChaplyginSystem):
        raise ModelTypeError(f"expected a ChaplyginSystem, got {type(system).__name__}")
    return system


def _coordinate(system, key):
    """An independent coordinate of ``system`` named by itself or by its name."""
    for q in system.independent_coordinates:
        if key == q or key == q.func.__name__ or (isinstance(key, sp.Symbol) and key.name == q.func.__name__):
            return q
    for q in system.dependent_coordinates:
        if key == q or key == q.func.__name__:
            raise ModelError(f"{q.func.__name__} is a dependent coordinate (1.1): its velocity "
                             "follows from the constraints; give the independent ones only")
    raise ModelError(f"{key!r} is not a coordinate of the system; its independent coordinates "
                     f"are {', '.join(q.func.__name__ for q in system.independent_coordinates)}")


def _value(v, what):
    try:
        v = sp.sympify(v, strict=True)
    except (sp.SympifyError, TypeError) as err:
        raise ModelTypeError(f"{what} must be a number or a SymPy expression, got {v!r}") from err
    if not isinstance(v, sp.Expr):
        raise ModelTypeError(f"{what} must be an expression, got {v!r}")
    if v.has(sp.oo, -sp.oo, sp.zoo, sp.nan):
        raise ModelError(f"{what} is not finite ({v})")
    if v.has(sp.I) or any(s.is_real is False for s in v.free_symbols):
        raise ModelError(f"{what} must be real, got {v}")
    if any(isinstance(a, sp.core.function.AppliedUndef) for a in v.atoms(sp.Function)):
        raise ModelError(f"{what} must be a constant (no function of time), got {v}")
    return sp.nsimplify(v, rational=True) if v.has(sp.Float) else v


def _sample_value(s, rng):
    if s.is_positive:
        return rng.uniform(0.5, 2.0)
    if s.is_negative:
        return -rng.uniform(0.5, 2.0)
    if s.is_nonnegative:
        return rng.uniform(0.0, 2.0)
    return rng.uniform(-1.5, 1.5)


def sampler(symbols):
    """A ``sample(rng)`` for :func:`~whittaker_teach.verify.check_zero`: each symbol
    a random value of its sign (positive symbols in (0.5, 2), others in (-1.5, 1.5))."""
    symbols = sorted(set(symbols), key=str)
    return lambda rng: {s: _sample_value(s, rng) for s in symbols}


def _plain(system):
    """{q(t).diff(t): V, q(t): Q} for the independent coordinates, plain symbols."""
    t = system.coordinates[0].args[0]
    Q = {q: sp.Dummy(q.func.__name__, real=True) for q in system.independent_coordinates}
    V = {q: sp.Dummy(q.func.__name__ + "dot", real=True) for q in system.independent_coordinates}
    rep = {q.diff(t): V[q] for q in system.independent_coordinates}
    rep.update({q: Q[q] for q in system.independent_coordinates})
    return Q, V, rep


def _accelerations_plain(system):
    t = system.coordinates[0].args[0]
    Q, V, rep = _plain(system)
    acc = system.accelerations()
    return Q, V, {q: acc[q.diff(t, 2)].xreplace(rep) for q in system.independent_coordinates}


def cyclic_coordinates(system):
    """The independent coordinates that do not appear in the accelerations [1.4a].

    Decided at 40 digits: the derivative of every acceleration with respect to the
    coordinate vanishes at random points (:func:`~whittaker_teach.verify.check_zero`),
    so that sin(psi)**2 + cos(psi)**2 left as built counts as free of psi.

    >>> import whittaker_teach as wt
    >>> cyclic_coordinates(wt.examples.sledge())
    [x(t)]
    """
    _require_system(system)
    Q, V, acc = _accelerations_plain(system)
    out = []
    for q in system.independent_coordinates:
        d = [a.diff(Q[q]) for a in acc.values()]
        if all(e == 0 for e in d):
            out.append(q)
            continue
        syms = set().union(*(e.free_symbols for e in d))
        chk = check_zero("cyclic", f"[1.4a] free of {q}", d, sampler(syms))
        if chk.holds:
            out.append(q)
    return out


@dataclass(frozen=True)
class SteadyMotion:
    """A steady motion: shape coordinates at ``values``, moving ones at ``velocities``.

    ``family`` lists the symbols of the motion that are not parameters of the system
    (the speed v of the sleigh's straight motions): the steady motions form a family
    of that dimension through this one.
    """

    system: ChaplyginSystem
    values: dict
    velocities: dict
    family: tuple = field(default=())

    @property
    def moving(self):
        """The moving (cyclic) coordinates, in the system's order."""
        return [q for q in self.system.independent_coordinates if q in self.velocities]

    @property
    def shape(self):
        """The coordinates held fixed, in the system's order."""
        return [q for q in self.system.independent_coordinates if q in self.values]

    def point(self):
        """{q(t): value, q(t).diff(t): velocity} for every independent coordinate (a
        moving coordinate's own value is set to 0: [1.4a] does not contain it)."""
        t = self.system.coordinates[0].args[0]
        out = {}
        for q in self.system.independent_coordinates:
            out[q.diff(t)] = self.velocities.get(q, sp.S.Zero)
            out[q] = self.values.get(q, sp.S.Zero)
        return out

    def energy(self):
        """The energy (1.11) on this motion: the h of its reduction."""
        t = self.system.coordinates[0].args[0]
        E = self.system.energy()
        pt = self.point()
        E = E.xreplace({k: v for k, v in pt.items() if k.is_Derivative})
        return sp.factor(sp.cancel(E.xreplace({k: v for k, v in pt.items() if not k.is_Derivative})))

    def __repr__(self):
        vals = ", ".join(f"{q.func.__name__} = {v}" for q, v in self.values.items())
        vels = ", ".join(f"{q.func.__name__}dot = {v}" for q, v in self.velocities.items())
        return f"SteadyMotion({self.system.name}: {'; '.join(s for s in (vals, vels) if s)})"


def steady_motion(system, values=None, velocities=None):
    """The steady motion with the shape coordinates at ``values`` and the moving ones
    at constant ``velocities``, after checking that it is one.

    Every independent coordinate must appear in exactly one of the two dicts (keys:
    the coordinate or its name).  A moving coordinate must be cyclic in [1.4a]
    (:func:`cyclic_coordinates`), and every acceleration must vanish at the point
    (exactly, else at 40 digits at random values of the parameters and of the
    motion's own symbols); otherwise a ModelError names what fails.

    >>> import sympy as sp
    >>> import whittaker_teach as wt
    >>> sledge = wt.examples.sledge()
    >>> steady_motion(sledge, {"theta": 0}, {"x": 0})
    SteadyMotion(sledge: theta = 0; xdot = 0)
    >>> steady_motion(sledge, {"theta": sp.Rational(1, 2)}, {"x": 1})
    Traceback (most recent call last):
    ...
    whittaker_teach.errors.ModelError: not a steady motion: the acceleration of theta is -k**2/(2*J), not 0 ([1.4a] at the point)
    """
    _require_system(system)
    values = {_coordinate(system, k): _value(v, f"the value of {k}") for k, v in (values or {}).items()}
    velocities = {_coordinate(system, k): _value(v, f"the velocity of {k}")
                  for k, v in (velocities or {}).items()}
    both = set(values) & set(velocities)
    if both:
        raise ModelError(f"{sorted(q.func.__name__ for q in both)} given both a fixed value and "
                         "a velocity: a shape coordinate is held fixed, a moving one turns")
    missing = [q.func.__name__ for q in system.independent_coordinates
               if q not in values and q not in velocities]
    if missing:
        raise ModelError(f"no value or velocity given for {', '.join(missing)}: every independent "
                         "coordinate is either held fixed (values) or moving (velocities)")
    cyc = cyclic_coordinates(system) if velocities else []
    for q in velocities:
        if q not in cyc:
            raise ModelError(f"{q.func.__name__} cannot move at a constant velocity in a steady "
                             f"motion: it appears in the accelerations [1.4a] (it is not cyclic); "
                             "hold it fixed (values) instead")
    order = [q for q in system.independent_coordinates]
    values = {q: values[q] for q in order if q in values}
    velocities = {q: velocities[q] for q in order if q in velocities}
    params = set(system.parameters)
    fam = set()
    for v in list(values.values()) + list(velocities.values()):
        fam |= v.free_symbols - params
    sm = SteadyMotion(system, values, velocities, tuple(sorted(fam, key=str)))
    res = residuals(sm)
    for q, r in res.items():
        if r == 0:
            continue
        rr = sp.cancel(r)
        if rr == 0:
            continue
        chk = check_zero("steady", f"acceleration of {q}", r, sampler(r.free_symbols))
        if not chk.holds:
            raise ModelError(f"not a steady motion: the acceleration of {q.func.__name__} is "
                             f"{sp.factor(rr)}, not 0 ([1.4a] at the point)")
    return sm


def residuals(sm):
    """{q: its acceleration [1.4a] at the steady motion} (all 0 for a steady motion)."""
    system = sm.system
    Q, V, acc = _accelerations_plain(system)
    rep = {}
    for q in system.independent_coordinates:
        rep[V[q]] = sm.velocities.get(q, sp.S.Zero)
        rep[Q[q]] = sm.values.get(q, sp.S.Zero)
    return {q: a.xreplace(rep) for q, a in acc.items()}


def find_steady_motions(system, velocities, values=None, unknowns=None):
    """The steady motions with the moving coordinates at ``velocities``, solved for
    ``unknowns`` by ``sympy.solve`` (what it finds: not necessarily every one).

    By default every coordinate not in ``velocities`` or ``values`` is a shape
    coordinate with an unknown value ``<name>_0``, and those are the unknowns.
    Give ``unknowns`` (symbols used in ``values`` or ``velocities``) to solve for
    others, e.g. the spin rate of a disk rolling in a circle at a given tilt.

    >>> import sympy as sp
    >>> import whittaker_teach as wt
    >>> v = sp.Symbol("v", positive=True)
    >>> find_steady_motions(wt.examples.offset_sleigh(), {"x": v})
    [SteadyMotion(offset_sleigh: theta = 0; xdot = v)]
    """
    _require_system(system)
    if not isinstance(velocities, dict) or not velocities:
        raise ModelError("velocities: a dict {moving coordinate: velocity}, at least one")
    values = dict(values or {})
    given = {_coordinate(system, k) for k in list(values) + list(velocities)}
    auto = []
    for q in system.independent_coordinates:
        if q not in given:
            s = sp.Symbol(q.func.__name__ + "_0", real=True)
            values[q] = s
            auto.append(s)
    unknowns = list(unknowns) if unknowns is not None else auto
    if not unknowns:
        raise ModelError("nothing to solve for: give unknowns, or leave a shape coordinate out "
                         "of values")
    probe = SteadyMotion(system, {_coordinate(system, k): _value(v, str(k)) for k, v in values.items()},
                         {_coordinate(system, k): _value(v, str(k)) for k, v in velocities.items()})
    eqs = [sp.numer(sp.together(r)) for r in residuals(probe).values()]
    eqs = [e for e in eqs if e != 0]
    if not eqs:
        sols = [{}]
    else:
        sols = sp.solve(eqs, unknowns, dict=True)
    out = []
    for sol in sols:
        vals = {k: sp.sympify(v).subs(sol) for k, v in values.items()}
        vels = {k: sp.sympify(v).subs(sol) for k, v in velocities.items()}
        try:
            out.append(steady_motion(system, vals, vels))
        except ModelError:
            continue        # a root of a numerator where the denominator vanishes too
    return out


def conserved(system, expr):
    """Whether ``expr`` (in the coordinates and velocities, dependent velocities allowed)
    is an integral of (1.4): its time derivative along [1.4a] and (1.3) vanishes,
    exactly or at 40 digits at random points.  Returns the ``Check``.

    >>> import sympy as sp
    >>> import whittaker_teach as wt
    >>> s = wt.examples.sledge()
    >>> x, th, y = s.coordinates
    >>> t = x.args[0]
    >>> conserved(s, x.diff(t) / sp.cos(th)).holds, conserved(s, x.diff(t)).holds
    (True, False)
    """
    _require_system(system)
    expr = _value_expr(expr)
    t = system.coordinates[0].args[0]
    rate = expr.subs(system.constraints).diff(t).subs(system.constraints)
    rate = rate.subs(system.accelerations())
    Q, V, rep = _plain(system)
    rate = rate.xreplace(rep)
    return check_zero("integral", "d/dt along (1.4) is 0", rate, sampler(rate.free_symbols))


def _value_expr(e):
    try:
        e = sp.sympify(e, strict=True)
    except (sp.SympifyError, TypeError) as err:
        raise ModelTypeError(f"expected a SymPy expression, got {e!r}") from err
    if not isinstance(e, sp.Expr):
        raise ModelTypeError(f"expected a SymPy expression, got {e!r}")
    return e
