"""The constraint distribution of a Chaplygin system, its connection and curvature.

Linear constraints qdot_(eps+beta) = sum_sigma b_(beta sigma)(q) qdot_sigma (Chaplygin: the
b free of the dependent coordinates, 1.3) say that the velocity lies in the
**distribution** D, the vectors annulled by the one-forms

    A^beta = dq_(eps+beta) - sum_sigma b_(beta sigma) dq_sigma      (the connection).

The **horizontal lift** of d/dq_sigma is the vector of D over it,
e_sigma = d/dq_sigma + sum_beta b_(beta sigma) d/dq_(eps+beta).  The **curvature** is dA^beta
on horizontal vectors, B^beta_(sigma tau) = dA^beta(e_sigma, e_tau); here

    B^beta_(sigma tau) = d b_(beta sigma)/d q_tau - d b_(beta tau)/d q_sigma.

It is zero for every beta exactly when D is integrable (the constraints are holonomic).
Mei's (1.4) for such a system reads

    d/dt dL~/dqdot_sigma - dL~/dq_sigma = sum_beta P_beta sum_tau B^beta_(sigma tau) qdot_tau,

P_beta = (dL/dqdot_(eps+beta))~: :meth:`Connection.check_1_4` shows it on a system by
computing both sides, the left from the library's (1.4).

>>> import whittaker_teach as wt
>>> from whittaker_teach.geometry import connection
>>> A = connection(wt.examples.sledge())
>>> A.curvature_form()
{y: tan(theta)**2 + 1}
>>> A.check_1_4().holds
True
"""

from __future__ import annotations

import sympy as sp

from ..errors import ModelError
from ._plain import Plain, zero

__all__ = ["Connection", "connection"]


class Connection:
    """The connection of a Chaplygin system with linear constraints (see the module).

    Attributes: ``chart`` (the plain symbols, :class:`~._plain.Plain`), ``b``
    ({dependent: {independent: b}}, plain symbols).
    """

    def __init__(self, system):
        self.chart = Plain(system)
        self.system = system
        self.b = self.chart.b

    # ----- the forms -----------------------------------------------------
    def one_forms(self):
        """{dependent coordinate: {coordinate: coefficient}}: A^beta = sum a_s dq_s."""
        ch = self.chart
        out = {}
        for d in ch.dependent:
            a = {c: sp.S.Zero for c in ch.coordinates}
            a[d] = sp.S.One
            for s in ch.independent:
                a[s] = -self.b[d][s]
            out[d] = a
        return out

    def horizontal_lift(self, coordinate):
        """{coordinate: component}: the horizontal lift e_sigma of d/dq_sigma."""
        ch = self.chart
        if coordinate not in ch.independent:
            raise ModelError(f"{coordinate} is not an independent coordinate; the horizontal "
                             f"lifts are of d/dq for {ch.independent}")
        e = {c: sp.S.Zero for c in ch.coordinates}
        e[coordinate] = sp.S.One
        for d in ch.dependent:
            e[d] = self.b[d][coordinate]
        return e

    def annihilates(self):
        """Check that A^beta(e_sigma) = 0 for every beta, sigma (the lifts lie in D)."""
        vals = [sum(a[c] * self.horizontal_lift(s)[c] for c in self.chart.coordinates)
                for a in self.one_forms().values() for s in self.chart.independent]
        return zero("D", "A^beta(e_sigma) = 0", vals)

    def exterior_derivative(self, dependent):
        """dA^beta as the matrix (dA(d/dq_i, d/dq_j)) = (d a_j/d q_i - d a_i/d q_j) over all
        coordinates, in the order of ``system.coordinates``."""
        ch = self.chart
        a = self.one_forms()[self._dependent(dependent)]
        cs = ch.coordinates
        return sp.Matrix(len(cs), len(cs),
                         lambda i, j: a[cs[j]].diff(ch.q[cs[i]]) - a[cs[i]].diff(ch.q[cs[j]]))

    def curvature(self, dependent):
        """B^beta: the matrix (dA^beta(e_sigma, e_tau)) over the independent coordinates,
        computed from :meth:`exterior_derivative` and :meth:`horizontal_lift`."""
        ch = self.chart
        dA = self.exterior_derivative(dependent)
        E = [sp.Matrix([self.horizontal_lift(s)[c] for c in ch.coordinates])
             for s in ch.independent]
        n = len(E)
        return sp.Matrix(n, n, lambda i, j: (E[i].T * dA * E[j])[0, 0])

    def curvature_form(self):
        """For one or two independent coordinates: {dependent q (plain): B^beta_(12)}
        (for one, 0): the curvature as the coefficient of dq_1 ^ dq_2."""
        ch = self.chart
        if len(ch.independent) > 2:
            raise ModelError("curvature_form is for eps <= 2 independent coordinates; use "
                             "curvature(dependent) for the matrix B^beta_(sigma tau)")
        out = {}
        for d in ch.dependent:
            B = self.curvature(d)
            out[ch.q[d]] = B[0, 1] if B.shape[0] == 2 else sp.S.Zero
        return out

    def is_flat(self):
        """Check that every curvature component vanishes (D integrable: holonomic)."""
        comps = [e for d in self.chart.dependent for e in self.curvature(d)]
        return zero("flat", "B = 0", comps)

    def _dependent(self, d):
        ch = self.chart
        for c in ch.dependent:
            if d == c or d == ch.q[c] or d == c.func.__name__:
                return c
        raise ModelError(f"{d!r} is not a dependent coordinate; they are "
                         f"{[c.func.__name__ for c in ch.dependent]}")

    # ----- (1.4) ---------------------------------------------------------
    def dependent_momenta(self):
        """{dependent q: P_beta}: dL/dqdot_(eps+beta) with the constraints substituted."""
        ch = self.chart
        L = ch.plain(self.system.lagrangian)
        sub = {ch.v[d]: ch.phi[d] for d in ch.dependent}
        return {d: L.diff(ch.v[d]).xreplace(sub) for d in ch.dependent}

    def chaplygin_term(self):
        """{independent q: sum_beta P_beta sum_tau B^beta_(sigma tau) qdot_tau} (plain)."""
        ch = self.chart
        P = self.dependent_momenta()
        out = {}
        Bs = {d: self.curvature(d) for d in ch.dependent}
        for i, s in enumerate(ch.independent):
            out[s] = sp.Add(*[P[d] * Bs[d][i, j] * ch.v[tau] for d in ch.dependent
                              for j, tau in enumerate(ch.independent)])
        return out

    def lagrange_part(self):
        """{independent q: d/dt dL~/dqdot_sigma - dL~/dq_sigma} (plain, with accelerations)."""
        ch = self.chart
        Lt = ch.plain(self.system.L_tilde)
        out = {}
        for s in ch.independent:
            p = Lt.diff(ch.v[s])
            dt = sp.Add(*[p.diff(ch.q[c]) * ch.v[c] + p.diff(ch.v[c]) * ch.a[c]
                          for c in ch.independent])
            out[s] = dt - Lt.diff(ch.q[s])
        return out

    def check_1_4(self):
        """Check that the library's (1.4) is (Lagrange's expression of L~) minus the
        curvature term, for each independent coordinate (exact, or 40 digits)."""
        ch = self.chart
        eom = [ch.plain(e) for e in self.system.equations_of_motion()]
        lag, term = self.lagrange_part(), self.chaplygin_term()
        diffs = [lag[s] - term[s] - e for s, e in zip(ch.independent, eom)]
        return zero("1.4", "equals Lagrange's expression of L~ minus sum P B qdot", diffs)


def connection(system):
    """The :class:`Connection` of ``system`` (a ChaplyginSystem with constraints linear in
    the velocities; ModelError otherwise, and for a holonomic system with no constraint)."""
    c = Connection(system)
    if not c.chart.dependent:
        raise ModelError("the system has no constraint (no dependent velocity): there is no "
                         "distribution to give a connection")
    return c
