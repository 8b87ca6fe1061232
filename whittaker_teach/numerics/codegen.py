"""Code generation: the symbolic core's equations as plain Python functions.

Every right-hand side the numerics integrate comes from here: SymPy's
``lambdify`` with common-subexpression elimination (``cse=True``) prints each
model once as a Python function of floats (``math`` module: no array
overhead on the scalar calls an integrator makes); a ``numpy`` version serves
the vectorised evaluations (energy along a whole trajectory).  Each model is
built on first use and cached on the system or reduction object, so a figure
or a benchmark builds only the model it shows.

>>> import whittaker_teach as wt
>>> from whittaker_teach.numerics import codegen
>>> fm = codegen.time_model(wt.examples.sledge(), "chaplygin")
>>> fm.state
['x', 'theta', 'y', 'xdot', 'thetadot']
>>> fm.rhs([0.0, 0.0, 0.0, 1.0, 0.0], [1.0, 1.0, 1.0])   # (J, k, m) = 1
[1.0, 0.0, 0.0, -0.0, -0.0]
>>> S = wt.examples.sledge()
>>> codegen.time_model(S, "multiplier") is codegen.time_model(S, "multiplier")  # cached
True

Three formulations of the time-domain model exist (see :func:`time_model`):
``"chaplygin"`` is (1.4) as the paper writes it; ``"multiplier"`` is the
Lagrange-d'Alembert form with the constraints multiplied through by their
denominators, regular where (1.4) has a pole (the sledge at cos(theta) = 0).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import sympy as sp

from ..errors import ModelError

__all__ = ["time_model", "reduced_model", "dla_model", "constraint_rows", "pole_factors",
           "constraint_poles", "formulation_of", "check_poles", "POLE_TOL",
           "TimeModel", "ReducedModel", "DLAModel", "cache_of"]


def cache_of(obj):
    """The numerics cache of a system or reduction (a dict stored on the object)."""
    return obj.__dict__.setdefault("_numerics", {})


def _lambdify(args, exprs, module="math"):
    """``lambdify`` with CSE; ``args`` a flat list of symbols, ``exprs`` a list (or matrix).

    ``"math"``: a function of floats.  ``"numpy"``: a function of arrays, printed by
    :func:`_portable_printer`, whose values are the same on every processor."""
    if module == "numpy":
        from .portable import numpy_functions
        return sp.lambdify(args, exprs, modules=[numpy_functions(), "numpy"], cse=True,
                           printer=_portable_printer())
    return sp.lambdify(args, exprs, modules=module, cse=True)


def _portable_printer():
    """numpy's printer with the functions whose numpy versions depend on the processor
    (numpy's AVX-512 code for exp, log, tan, powers ...) taken from
    :func:`.portable.numpy_functions` instead: ``_pt_tan(x)``, ``_pt_power(x, 3.0)``;
    square roots and reciprocals stay numpy's (exactly rounded everywhere)."""
    from sympy.printing.numpy import NumPyPrinter

    from .portable import FUNCTIONS

    class PortablePrinter(NumPyPrinter):
        _kf = {**NumPyPrinter._kf, **{f: f"_pt_{f}" for f in FUNCTIONS + ("atan2",)}}

        def _print_Pow(self, expr, rational=False):
            if expr.exp == sp.S.Half:
                return super()._print_Pow(expr, rational)
            if expr.exp == -1:
                return f"(1/({self._print(expr.base)}))"
            return f"_pt_power({self._print(expr.base)}, {float(expr.exp)!r})"
    return PortablePrinter({"fully_qualified_modules": False, "inline": True,
                            "allow_unknown_functions": True, "user_functions": {}})


def trig_as_sin_cos(expr):
    """tan, cot, sec, csc written with sin and cos, so that poles show as denominators.

    >>> th = sp.Symbol("theta")
    >>> trig_as_sin_cos(sp.tan(th))
    sin(theta)/cos(theta)
    """
    return expr.replace(sp.tan, lambda a: sp.sin(a) / sp.cos(a)).replace(
        sp.cot, lambda a: sp.cos(a) / sp.sin(a)).replace(
        sp.sec, lambda a: 1 / sp.cos(a)).replace(sp.csc, lambda a: 1 / sp.sin(a))


def pole_factors(exprs, symbols):
    """The distinct factors of the denominators of ``exprs`` that depend on ``symbols``.

    >>> th, xd = sp.symbols("theta xdot")
    >>> pole_factors([xd*sp.tan(th), -th], [th])
    [cos(theta)]
    """
    found = []
    for e in exprs:
        den = sp.fraction(sp.together(trig_as_sin_cos(sp.sympify(e))))[1]
        for f in sp.Mul.make_args(den):
            base = f.base if f.is_Pow and f.exp.is_positive else f
            if base.free_symbols & set(symbols) and base not in found:
                found.append(base)
    return found


def constraint_rows(system):
    """The constraints as A(q) qdot = 0, each multiplied through by its denominator.

    One row per dependent coordinate, over all coordinates (in
    ``system.coordinates`` order).  ModelError if a constraint is not linear in
    the velocities (the multiplier form and the DLA integrator need linear ones).

    >>> import whittaker_teach as wt
    >>> constraint_rows(wt.examples.sledge())
    Matrix([[-sin(theta), 0, cos(theta)]])
    """
    S = system
    qd = [S.qd[c] for c in S.coordinates]
    rows = []
    for c in S.dependent_coordinates:
        num, den = sp.fraction(sp.together(trig_as_sin_cos(S._phi[S.q[c]])))
        e = sp.expand(den * S.qd[c] - num)
        row = [e.diff(v) for v in qd]
        if any(r.has(*qd) for r in row) or sp.expand(e - sum(
                r * v for r, v in zip(row, qd))) != 0:
            raise ModelError(f"the constraint for {c.func.__name__}dot is not linear in the "
                             "velocities: the multiplier form and the discrete "
                             "Lagrange-d'Alembert integrator need A(q) qdot = 0")
        rows.append(row)
    return sp.Matrix(rows) if rows else sp.zeros(0, len(qd))


# ----------------------------------------------------------------- poles of (1.3)
#: An initial state where a denominator of the constraints is smaller than this
#: is refused (the dependent velocities would be round-off divided by round-off).
POLE_TOL = 1e-12


def check_poles(system, qv, p):
    """ModelError if the coordinates ``qv`` are (nearly) at a pole of the constraints."""
    for text, fn in constraint_poles(system):
        if abs(fn(*qv, *p)) < POLE_TOL:
            raise ModelError(f"the initial state is (nearly) at a pole of the constraints "
                             f"(1.3), {text} = {fn(*qv, *p):.1e}: the independent velocities "
                             "do not determine the dependent ones there; start elsewhere")


def _all_velocities(system, from_independent, qv, vs, p):
    """Every velocity from the independent ones (1.3), as floats; ModelError if one is
    not finite (a pole of a constraint)."""
    import numpy as np
    check_poles(system, qv, p)
    with np.errstate(all="ignore"):
        allv = [float(w) for w in from_independent(*qv, *vs, *p)]
    if not all(np.isfinite(allv)):
        bad = [c.func.__name__ for c, w in zip(system.coordinates, allv) if not np.isfinite(w)]
        raise ModelError(f"the constraint for {', '.join(bad)}dot cannot be evaluated at the "
                         "initial state (a pole of the constraint, 1.3): start elsewhere")
    return allv


# ----------------------------------------------------------------- time model
def formulation_of(system, formulation="auto"):
    """``formulation`` with ``"auto"`` resolved: ``"multiplier"`` when the constraints
    are linear in the velocities and have a pole, otherwise ``"chaplygin"`` (cached).

    >>> import whittaker_teach as wt
    >>> formulation_of(wt.examples.sledge())
    'multiplier'
    """
    if formulation != "auto":
        if formulation not in ("chaplygin", "multiplier"):
            raise ModelError(f"unknown formulation {formulation!r}: use 'auto', "
                             "'chaplygin' (1.4) or 'multiplier' (Lagrange-d'Alembert)")
        if formulation == "multiplier":
            constraint_rows(system)          # linear constraints, or ModelError
        return formulation
    cache = cache_of(system)
    if "auto" not in cache:
        S = system
        q = [S.q[c] for c in S.coordinates]
        choice = "chaplygin"
        if pole_factors(list(S._phi.values()), q):
            try:
                constraint_rows(S)
                choice = "multiplier"
            except ModelError:
                pass
        cache["auto"] = choice
    return cache["auto"]


@dataclass
class TimeModel:
    """A compiled time-domain model: ``rhs(y, p)`` with ``y`` laid out as ``state``."""

    formulation: str
    state: list                 # names, in order
    n: int                      # number of coordinates
    rhs: object                 # (y list, p list) -> list
    jac: object                 # (y list, p list) -> nested list
    energy: object              # numpy: (y arrays..., p...) -> array
    velocities: object          # numpy: (y..., p...) -> list of all n velocities
    from_independent: object    # numpy: (q..., qdot_sigma..., p...) -> all n velocities
    poles: list = field(default_factory=list)    # [(expr text, function(y, p))]
    poles_np: list = field(default_factory=list)  # [(expr text, numpy f(*y, *p))]
    system: object = field(default=None, repr=False)

    def initial_state(self, q, v, p):
        """The state vector from {coordinate: value} ``q`` (all) and ``v`` (the independent
        velocities); ModelError at a pole of the constraints or of (1.4)."""
        import numpy as np
        S = self.system
        qv = [q[c] for c in S.coordinates]
        vs = [v[c] for c in S.independent_coordinates]
        allv = _all_velocities(S, self.from_independent, qv, vs, p)
        y0 = qv + (vs if self.formulation == "chaplygin" else allv)
        for text, fn in (self.poles_np if self.formulation == "chaplygin" else ()):
            if fn(*y0, *p) == 0:
                raise ModelError(f"the Chaplygin form (1.4) has a pole at the initial state "
                                 f"({text} = 0); use formulation='multiplier'")
        return np.array(y0)


def _time_exprs_chaplygin(S):
    coords, sig = S.coordinates, S.independent_coordinates
    q = [S.q[c] for c in coords]
    v = [S.qd[c] for c in sig]
    acc = S._accelerations()
    vel = [S.qd[c] if c in sig else S._phi[S.q[c]] for c in coords]
    f = vel + [acc[S.qdd[c]] for c in sig]
    E = S._energy()
    return q + v, f, E, vel


#: Above this operation count the multiplier form's linear system is solved numerically.
SYMBOLIC_SOLVE_LIMIT = 400


def _multiplier_parts(S):
    """M(q), A(q), r(q, v) and Adot(q, v) v of M qddot + r = A^T lambda, A qddot + Adot v = 0."""
    coords = S.coordinates
    q = [S.q[c] for c in coords]
    v = [S.qd[c] for c in coords]
    A = constraint_rows(S)
    L = S._L
    M = sp.hessian(L, v)
    p = sp.Matrix([L.diff(w) for w in v])
    r = p.jacobian(q) * sp.Matrix(v) - sp.Matrix([L.diff(x) for x in q])
    n, g = len(q), A.rows
    Adot_v = sp.Matrix([sum((A[i, j].diff(q[k]) * v[k] * v[j]
                             for j in range(n) for k in range(n)), sp.S.Zero)
                        for i in range(g)])
    E = sum((w * L.diff(w) for w in v), sp.S.Zero) - L
    return q, v, M, A, r, Adot_v, E


def _time_exprs_multiplier(S):
    """The multiplier form solved symbolically; ``None`` for the accelerations if the
    solution is too large (then :func:`_numeric_multiplier` solves it per call)."""
    q, v, M, A, r, Adot_v, E = _multiplier_parts(S)
    n, g = len(q), A.rows
    K = sp.zeros(n + g)
    K[:n, :n], K[:n, n:], K[n:, :n] = M, -A.T, A
    sol = K.LUsolve(sp.Matrix.vstack(-r, -Adot_v))
    acc = [sol[i] for i in range(n)]
    if sum(sp.count_ops(a) for a in acc) > SYMBOLIC_SOLVE_LIMIT:
        acc = None
    return q + v, (v + acc if acc else None), E, v


def _numeric_multiplier(S, P):
    """rhs(y, p) for the multiplier form, with the (n+g) linear system solved in Python
    floats (:func:`.portable.solve`: the same bits on every processor)."""
    from .portable import solve
    q, v, M, A, r, Adot_v, _E = _multiplier_parts(S)
    n, g = len(q), A.rows
    parts = _lambdify(q + v + P, [M.tolist(), A.tolist(), list(r), list(Adot_v)])

    def rhs(y, p):
        Mv, Av, rv, cv = parts(*y, *p)
        K = [list(Mv[i]) + [-Av[j][i] for j in range(g)] for i in range(n)]
        K += [list(Av[j]) + [0.0] * g for j in range(g)]
        return list(y[n:]) + solve(K, [-float(v) for v in list(rv) + list(cv)])[:n]
    return rhs


def _params(system):
    return list(system.parameters)


def _build_time(S, formulation):
    if formulation == "chaplygin":
        y, f, E, vel = _time_exprs_chaplygin(S)
    else:
        y, f, E, vel = _time_exprs_multiplier(S)
    P = _params(S)
    args = y + P
    q = [S.q[c] for c in S.coordinates]
    sig = [S.qd[c] for c in S.independent_coordinates]
    vel_sig = [S.qd[c] if c in S.independent_coordinates else S._phi[S.q[c]]
               for c in S.coordinates]
    poles, poles_np = [], []
    if formulation == "chaplygin":
        for d in pole_factors(f, q):
            poles.append((str(d), _unpack(_lambdify(args, d), len(y))))
            poles_np.append((str(d), _lambdify(args, d, "numpy")))
    if f is None:                           # large: solved numerically per call
        rhs, jac = _numeric_multiplier(S, P), None
    else:
        rhs = _unpack(_lambdify(args, f), len(y))
        jac = _unpack(_lambdify(args, sp.Matrix(f).jacobian(y).tolist()), len(y))
    return TimeModel(formulation, [s.name for s in y], len(S.coordinates), rhs, jac,
                     _lambdify(args, E, "numpy"), _lambdify(args, vel, "numpy"),
                     _lambdify(q + sig + P, vel_sig, "numpy"), poles, poles_np, S)


def _unpack(fn, n):
    """(y, p) -> fn(*y, *p): the calling convention of every compiled function here."""
    def call(y, p):
        return fn(*y, *p)
    call.raw = fn
    return call


def time_model(system, formulation="auto"):
    """The compiled time-domain model of ``system`` (cached on it).

    ``formulation``: ``"auto"`` (see :func:`formulation_of`), ``"chaplygin"``, state (q_s, qdot_sigma), right-hand side
    from (1.4) and the constraints (1.3); or ``"multiplier"``, state (q_s,
    qdot_s), from the Lagrange-d'Alembert equations with a multiplier and the
    constraints in the cleared form A(q) qdot = 0 (:func:`constraint_rows`).
    """
    formulation = formulation_of(system, formulation)
    cache = cache_of(system)
    key = ("time", formulation)
    if key not in cache:
        cache[key] = _build_time(system, formulation)
    return cache[key]


def constraint_poles(system):
    """[(text, f(q..., params...))]: the factors of the constraints' denominators (cached)."""
    cache = cache_of(system)
    if "cpoles" not in cache:
        S = system
        q = [S.q[c] for c in S.coordinates]
        cache["cpoles"] = [(str(d), _lambdify(q + _params(S), d))
                           for d in pole_factors(list(S._phi.values()), q)]
    return cache["cpoles"]


# ----------------------------------------------------------------- reduced model
@dataclass
class ReducedModel:
    """A compiled reduced model: state (q_nu, q'_nu, t, q_dep) as functions of q_eps.

    ``core(z, s, h, p)`` returns ``[q''_nu..., dq_dep/dq_eps..., R, D]`` where R =
    2(h + A0) and D = 2 A2 are the radicands of (1.12), qdot_eps = s sqrt(R/D);
    square roots of R inside the other outputs are taken by the caller (the
    clipped value ``sqrtR``), so that round-off never reaches ``math.sqrt``.
    """

    state: list
    nu: int
    g: int
    core: object
    jac: object
    radicands: object           # (z, s, h, p) -> (R, D, scale of R)
    poles: object = None        # (z, s, h, p) -> values of the denominators' factors
    pole_names: list = field(default_factory=list)


def _build_reduced(red):
    S = red.system
    eps, nus = red._eps, red._nus
    s = S.q[eps]
    qn = [S.q[c] for c in nus]
    qp = [red._qp[c] for c in nus]
    tsym = sp.Symbol("t_")
    deps = [S.q[c] for c in S.dependent_coordinates]
    z = qn + qp + [tsym] + deps
    A2, _A1, A0 = red._A
    R = sp.expand(2 * (red.h + A0))
    D = sp.expand(2 * A2)
    sqrtR, sqrtD = sp.Symbol("sqrtR_"), sp.Symbol("sqrtD_")
    acc = red._accelerations()
    out = [_swap_roots(acc[red._qpp[c]], {R: sqrtR, D: sqrtD}) for c in nus]
    out += [_swap_roots(q, {R: sqrtR, D: sqrtD}) for q in red._qdstar]
    args = z + [s, red.h, sqrtR, sqrtD] + _params(S)
    full = [acc[red._qpp[c]] for c in nus] + [1 / red._vstar] + list(red._qdstar)
    dz = qp + full
    jac = sp.Matrix(dz).jacobian(z)
    jargs = z + [s, red.h] + _params(S)
    scale = sp.Abs(2 * red.h) + sp.Abs(2 * A0)
    poles = pole_factors(full + [D], [S.q[c] for c in S.coordinates])
    return ReducedModel([v.name for v in z], len(nus), len(deps),
                        _lambdify(args, out), _lambdify(jargs, jac.tolist()),
                        _lambdify(jargs, [R, D, scale]),
                        _lambdify(jargs, poles) if poles else None, [str(d) for d in poles])


def _swap_roots(expr, roots):
    """Every power R**(k/2) (k odd) of a radicand R in ``roots`` written as s**k, with s
    the symbol standing for sqrt(R): the caller computes the roots (clipping round-off).

    >>> R, s, x = sp.symbols("R s x")
    >>> _swap_roots(x*sp.sqrt(R) + 1/sp.sqrt(R) + R**sp.Rational(3, 2), {R: s})
    s**3 + s*x + 1/s
    """
    def half(e):
        return (e.is_Pow and e.base in roots and e.exp.is_Rational
                and not e.exp.is_integer and (2 * e.exp).is_integer)
    return expr.replace(half, lambda e: roots[e.base] ** (2 * e.exp))


def reduced_model(red):
    """The compiled reduced model of a :class:`~whittaker_teach.reduction.Reduction`
    (cached on it): the generalized Whittaker equations (1.26) solved for q''_nu,
    with dt/dq_eps = 1/qdot_eps (1.12) and dq_dep/dq_eps = qdot* (1.23)."""
    cache = cache_of(red)
    if "reduced" not in cache:
        cache["reduced"] = _build_reduced(red)
    return cache["reduced"]


# ----------------------------------------------------------------- DLA
@dataclass
class DLAModel:
    """The discrete Lagrange-d'Alembert equations (midpoint rule), compiled.

    ``residual(qa, d, lam, p, dt, P)`` and ``jacobian(...)`` (with respect to
    (d, lam)) of  p + D1 Ld(qa, qa + d) - A(qa)^T lam = 0,  A(qa + d/2) d = 0;
    ``momentum_next(qa, d, dt, P)`` = D2 Ld(qa, qa + d); ``legendre(q, P)`` = (M, b)
    with p = M qdot + b; ``rows(q, P)`` = A(q).
    """

    n: int
    g: int
    residual: object
    jacobian: object
    momentum_next: object
    legendre: object
    rows: object
    energy: object
    from_independent: object     # numpy: (q..., qdot_sigma..., P...) -> all velocities
    system: object = field(default=None, repr=False)

    def initial_state(self, q, v, P):
        """(q0 array, p0 = M qdot + b): positions and momenta from {coordinate: value}
        ``q`` (all) and ``v`` (the independent velocities); ModelError at a pole of (1.3)."""
        import numpy as np

        from .portable import dot
        S = self.system
        qv = [q[c] for c in S.coordinates]
        allv = np.array(_all_velocities(S, self.from_independent, qv,
                                        [v[c] for c in S.independent_coordinates], P))
        M, b = self.legendre(*qv, *P)
        return np.array(qv), np.array([dot(row, allv) + float(bi) for row, bi in zip(M, b)])


def _build_dla(S):
    """The DLA equations in the increments d = q_{k+1} - q_k (not q_{k+1}): the velocity
    d/dt is then formed without subtracting two large positions (no lost digits as
    x grows along a long run)."""
    coords = S.coordinates
    n = len(coords)
    q = [S.q[c] for c in coords]
    v = [S.qd[c] for c in coords]
    qa = [sp.Symbol(f"{s.name}_a") for s in q]
    dd = [sp.Symbol(f"d_{s.name}") for s in q]
    pp = [sp.Symbol(f"p_{s.name}") for s in q]
    A = constraint_rows(S)
    g = A.rows
    lam = [sp.Symbol(f"lambda_{i}") for i in range(g)]
    dt = sp.Symbol("dt_")
    P = _params(S)
    mid = {qi: a + d / 2 for qi, a, d in zip(q, qa, dd)}
    mid.update({vi: d / dt for vi, d in zip(v, dd)})
    Lam = dt * S._L.xreplace(mid)                 # L_d(q_a, q_a + d)
    D2 = [Lam.diff(d) for d in dd]
    D1 = [Lam.diff(a) - d2 for a, d2 in zip(qa, D2)]
    Aa = A.xreplace(dict(zip(q, qa)))
    Am = A.xreplace({qi: a + d / 2 for qi, a, d in zip(q, qa, dd)})
    F = [pp[i] + D1[i] - sum((Aa[j, i] * lam[j] for j in range(g)), sp.S.Zero)
         for i in range(n)]
    F += [sum((Am[j, i] * dd[i] for i in range(n)), sp.S.Zero) for j in range(g)]
    JF = sp.Matrix(F).jacobian(dd + lam)
    args = qa + dd + lam + pp + [dt] + P
    L = S._L
    M = sp.hessian(L, v)
    b = sp.Matrix([L.diff(w) for w in v]) - M * sp.Matrix(v)
    E = sum((w * L.diff(w) for w in v), sp.S.Zero) - L
    return DLAModel(n, g, _lambdify(args, F), _lambdify(args, JF.tolist()),
                    _lambdify(qa + dd + [dt] + P, D2),
                    _lambdify(q + P, [M.tolist(), sp.expand(b).T.tolist()[0]], "numpy"),
                    _lambdify(q + P, A.tolist(), "numpy"),
                    _lambdify(q + v + P, E, "numpy"),
                    _lambdify(q + [S.qd[c] for c in S.independent_coordinates] + P,
                              [S.qd[c] if c in S.independent_coordinates
                               else S._phi[S.q[c]] for c in coords], "numpy"), S)


def dla_model(system):
    """The compiled discrete Lagrange-d'Alembert model of ``system`` (cached on it)."""
    cache = cache_of(system)
    if "dla" not in cache:
        cache["dla"] = _build_dla(system)
    return cache["dla"]
