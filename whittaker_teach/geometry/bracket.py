"""Almost-Poisson brackets: the non-holonomic bracket of a Chaplygin system and its
Jacobiator.

A bracket on functions of z = (z_1, ..., z_n) is given by its **structure matrix**
Pi_ij = {z_i, z_j} (skew-symmetric): {f, g} = sum_ij Pi_ij df/dz_i dg/dz_j.  It is
**Poisson** when the Jacobi identity holds, the **Jacobiator**
{f, {g, h}} + {g, {h, f}} + {h, {f, g}} being zero; only "almost Poisson" when not.

For a Chaplygin system with linear constraints, reduced to the independent coordinates
q_sigma with the momenta p_sigma = dL~/dqdot_sigma and the energy H(q, p), (1.4) reads
qdot_sigma = {q_sigma, H}, pdot_sigma = {p_sigma, H} for the bracket

    {q_sigma, p_tau} = delta_(sigma tau),   {q_sigma, q_tau} = 0,
    {p_sigma, p_tau} = C_(sigma tau) = sum_beta P_beta B^beta_(sigma tau)

(P_beta = (dL/dqdot_(eps+beta))~ written in (q, p), B the curvature of
:mod:`~whittaker_teach.geometry.connection`).  :meth:`NonholonomicBracket.check_equations`
checks the claim against the library's accelerations [1.4a].

>>> import whittaker_teach as wt
>>> nb = nonholonomic_bracket(wt.examples.sledge())
>>> x, th, px, pth = nb.coordinates
>>> nb.structure.bracket(px, pth)
p_x*tan(theta)
>>> nb.check_equations().holds
True
"""

from __future__ import annotations

from itertools import combinations

import sympy as sp

from ..errors import ModelError, ModelTypeError
from ._plain import zero
from .connection import connection

__all__ = ["AlmostPoisson", "NonholonomicBracket", "nonholonomic_bracket", "rescaled"]


class AlmostPoisson:
    """The bracket with structure matrix ``matrix`` on the symbols ``coordinates``.

    >>> q, p = sp.symbols("q p")
    >>> canonical = AlmostPoisson([q, p], sp.Matrix([[0, 1], [-1, 0]]))
    >>> canonical.bracket(q**2, p)
    2*q
    >>> canonical.check_jacobi().holds
    True
    """

    def __init__(self, coordinates, matrix):
        coords = list(coordinates)
        if not coords or not all(isinstance(z, sp.Symbol) for z in coords):
            raise ModelTypeError("coordinates must be a non-empty list of SymPy Symbols")
        if len(set(coords)) != len(coords):
            raise ModelError("coordinates repeat a symbol")
        M = sp.Matrix(matrix)
        if M.shape != (len(coords), len(coords)):
            raise ModelError(f"the structure matrix is {M.shape[0]}x{M.shape[1]}; it must be "
                             f"{len(coords)}x{len(coords)}, one row and column per coordinate")
        sym = [M[i, j] + M[j, i] for i in range(M.rows) for j in range(i, M.cols)]
        if any(e != 0 for e in sym) and not zero("skew", "Pi + Pi^T = 0", sym).holds:
            raise ModelError("the structure matrix is not skew-symmetric ({z_i, z_j} must be "
                             "-{z_j, z_i}): a bracket must be antisymmetric")
        self.coordinates = coords
        self.matrix = M

    def bracket(self, f, g):
        """{f, g} = sum_ij Pi_ij df/dz_i dg/dz_j."""
        z, M = self.coordinates, self.matrix
        df = [sp.sympify(f).diff(zi) for zi in z]
        dg = [sp.sympify(g).diff(zj) for zj in z]
        return sp.Add(*[M[i, j] * df[i] * dg[j] for i in range(len(z)) for j in range(len(z))
                        if M[i, j] != 0 and df[i] != 0 and dg[j] != 0])

    def jacobiator(self, f, g, h):
        """{f, {g, h}} + {g, {h, f}} + {h, {f, g}} as one fraction (``sp.cancel``, a
        rational normal form: functions such as tan(theta) are treated as symbols; zero for
        a Poisson bracket)."""
        b = self.bracket
        return sp.cancel(b(f, b(g, h)) + b(g, b(h, f)) + b(h, b(f, g)))

    def jacobi_table(self):
        """{(z_i, z_j, z_k): Jacobiator} for i < j < k (it is skew in its arguments, so
        these determine it), the coordinate functions only."""
        return {(a, b, c): self.jacobiator(a, b, c)
                for a, b, c in combinations(self.coordinates, 3)}

    def check_jacobi(self):
        """Check that every entry of :meth:`jacobi_table` vanishes (the bracket is
        Poisson); ``holds`` False when some entry is not zero."""
        vals = list(self.jacobi_table().values())
        return zero("Jacobi", "the Jacobiator vanishes", vals or [sp.S.Zero])

    def vector_field(self, hamiltonian):
        """[zdot_i = {z_i, H}]."""
        return [self.bracket(z, hamiltonian) for z in self.coordinates]

    def is_canonical(self, n=None):
        """Whether the matrix is exactly [[0, I], [-I, 0]] (checked term by term)."""
        k = len(self.coordinates) // 2 if n is None else n
        J = sp.zeros(2 * k, 2 * k)
        for i in range(k):
            J[i, k + i], J[k + i, i] = 1, -1
        return zero("canonical", "Pi = [[0, I], [-I, 0]]", list(self.matrix - J))


class NonholonomicBracket:
    """The reduced system of a Chaplygin system in (q, p): see the module.

    ``coordinates`` [q..., p...] (plain symbols), ``momenta`` {q: p_sigma as a function of
    the velocities}, ``velocities`` {qdot symbol: function of (q, p)}, ``hamiltonian``,
    ``C`` (the matrix {p_sigma, p_tau}), ``structure`` (:class:`AlmostPoisson`).
    """

    def __init__(self, system):
        self.connection = connection(system)
        ch = self.chart = self.connection.chart
        self.system = system
        ind = ch.independent
        self.q = [ch.q[c] for c in ind]
        self.p = [sp.Symbol("p_" + c.func.__name__, real=True) for c in ind]
        clash = sorted({str(s) for s in ch.parameters} & {p.name for p in self.p})
        if clash:
            raise ModelError(f"the parameter {clash[0]} has the name of a momentum of the "
                             "reduced system; rename it (the momenta are p_<coordinate>)")
        vs = [ch.v[c] for c in ind]
        Lt = ch.plain(system.L_tilde)
        mom = [Lt.diff(v) for v in vs]
        M = sp.Matrix([[m.diff(v) for v in vs] for m in mom])
        if any(e.has(*vs) for e in M):
            chk = zero("quadratic", "", [e.diff(v) for e in M for v in vs])
            if not chk.holds:
                raise ModelError("L~ is not quadratic in the velocities (its Hessian depends "
                                 "on them): the Legendre transform to (q, p) is not linear")
        p0 = [m.xreplace({v: 0 for v in vs}) for m in mom]
        try:
            sol = M.LUsolve(sp.Matrix([pi - a for pi, a in zip(self.p, p0)]))
        except ValueError as err:
            raise ModelError("the kinetic energy of L~ is singular (its Hessian in the "
                             "velocities is not invertible): no Legendre transform") from err
        self.momenta = dict(zip(ind, mom))
        self.velocities = dict(zip(vs, [sp.cancel(e) for e in sol]))
        self.hamiltonian = (sp.Add(*[pi * s for pi, s in zip(self.p, sol)])
                            - Lt.xreplace(self.velocities))
        P = {d: e.xreplace(self.velocities)
             for d, e in self.connection.dependent_momenta().items()}
        Bs = {d: self.connection.curvature(d) for d in ch.dependent}
        n = len(ind)
        self.C = sp.Matrix(n, n, lambda i, j: sp.cancel(sp.Add(*[P[d] * Bs[d][i, j]
                                                                for d in ch.dependent])))
        S = sp.zeros(2 * n, 2 * n)
        for i in range(n):
            S[i, n + i], S[n + i, i] = 1, -1
            for j in range(n):
                S[n + i, n + j] = self.C[i, j]
        self.coordinates = self.q + self.p
        self.structure = AlmostPoisson(self.coordinates, S)

    def symbols(self, *names):
        """The plain symbols called ``names`` (coordinates and momenta), in order."""
        table = {s.name: s for s in self.coordinates}
        try:
            return [table[n] for n in names]
        except KeyError as err:
            raise ModelError(f"no symbol {err.args[0]!r}; the variables are "
                             f"{sorted(table)}") from None

    def vector_field(self):
        """[{z, H}] for z in ``coordinates``: the reduced equations of motion."""
        return self.structure.vector_field(self.hamiltonian)

    def check_equations(self):
        """Check that {z, H} is the motion of (1.4): qdot from the Legendre transform and
        pdot = d/dt dL~/dqdot along the library's accelerations [1.4a]."""
        ch = self.chart
        acc = {ch.a[c]: ch.plain(e) for c in ch.independent
               for e in [self.system.accelerations()[c.diff(ch.t, 2)]]}
        rates = []
        for c in ch.independent:
            m = self.momenta[c]
            rates.append(sp.Add(*[m.diff(ch.q[d]) * ch.v[d] + m.diff(ch.v[d]) * acc[ch.a[d]]
                                  for d in ch.independent]).xreplace(self.velocities))
        motion = [self.velocities[ch.v[c]] for c in ch.independent] + rates
        F = self.vector_field()
        return zero("bracket", "zdot = {z, H} along (1.4)", [a - b for a, b in zip(F, motion)])


def nonholonomic_bracket(system):
    """The :class:`NonholonomicBracket` of a ChaplyginSystem with linear constraints."""
    return NonholonomicBracket(system)


def rescaled(nb, N):
    """Chaplygin's change of time d tau = N(q) dt applied to the bracket ``nb``: returns
    (bracket, H*) in the variables (q, P), P_sigma = N p_sigma, with
    {f, g}' = (1/N) {f, g} (so that df/dtau = {f, H*}') and H*(q, P) = H(q, P/N).

    >>> import whittaker_teach as wt
    >>> nb = nonholonomic_bracket(wt.examples.sledge())
    >>> x, th = nb.q
    >>> new, H_star = rescaled(nb, sp.cos(th))
    >>> new.is_canonical().holds
    True
    """
    if not isinstance(nb, NonholonomicBracket):
        raise ModelTypeError(f"expected a NonholonomicBracket, got {type(nb).__name__}")
    N = sp.sympify(N)
    if not isinstance(N, sp.Expr):
        raise ModelTypeError(f"N must be a SymPy expression in the coordinates, got {N!r}")
    stray = N.free_symbols - set(nb.q) - set(nb.chart.parameters)
    if stray:
        raise ModelError(f"the multiplier N may depend on the positions {nb.q} (and the "
                         f"parameters) only; it contains {sorted(map(str, stray))}")
    if N == 0:
        raise ModelError("the multiplier N is 0: d tau = N dt needs N > 0")
    big_p = [sp.Symbol("P_" + c.func.__name__, real=True) for c in nb.chart.independent]
    clash = sorted({str(s) for s in nb.chart.parameters} & {P.name for P in big_p})
    if clash:
        raise ModelError(f"the parameter {clash[0]} has the name of a new momentum "
                         "P_<coordinate>; rename it")
    Z = nb.q + [N * p for p in nb.p]
    back = {p: P / N for p, P in zip(nb.p, big_p)}
    b = nb.structure.bracket
    n = len(Z)
    S = sp.Matrix(n, n, lambda i, j: (b(Z[i], Z[j]) / N).xreplace(back))
    return AlmostPoisson(nb.q + big_p, S), nb.hamiltonian.xreplace(back)
