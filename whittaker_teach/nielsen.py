"""The Nielsen form (2.1)-(2.4) of the generalized Whittaker equations.

Nielsen's form uses the total derivative dL*/dq_eps (2.1), in which q''_nu
appears explicitly, and differentiates it with respect to q'_nu.  By (2.2)
and (2.3) the result is (1.26) again, written as (2.4).

>>> import whittaker_teach as wt
>>> red = wt.examples.sledge().reduce("x")
>>> eqs = nielsen(red)
>>> sorted(eqs)
['2.1', '2.4']
"""

from __future__ import annotations

import sympy as sp

from .steps import Step, eq, notation
from .verify import check_identity

__all__ = ["nielsen", "nielsen_steps"]


def nielsen(red):
    """{"2.1": dL*/dq_eps, "2.4": [Nielsen equations, one per q_nu]} in internal symbols."""
    if "nielsen" not in red._cache:
        S, Ls = red.system, red._Lstar
        dL = red._D(Ls)                                                          # (2.1)
        dq = [red._D(q) for q in red._qdstar]
        eqs = []
        for c in red._nus:
            qp, q = red._qp[c], S.q[c]
            e = dL.diff(qp) - 2 * Ls.diff(q)                                     # (2.4)
            for P, qs, d in zip(red._Pstar, red._qdstar, dq):
                e -= P * (d.diff(qp) - 2 * qs.diff(q))
            eqs.append(e)
        red._cache["nielsen"] = {"2.1": dL, "2.4": eqs}
    return red._cache["nielsen"]


def nielsen_steps(red):
    """Steps (2.1)-(2.4), each identity checked for this system."""
    S, Ls, smp = red.system, red._Lstar, red._sample
    n = nielsen(red)
    dL, nus = n["2.1"], red._nus
    qp, q = red._qp, S.q
    x = red.independent
    st = [Step("2.1", "the total derivative of L* (q'' appears explicitly)",
               [eq(notation(f"dL*/d{x}", rf"\frac{{d L^{{*}}}}{{d {sp.latex(x)}}}"), dL)])]
    st.append(Step("2.2", "d/dq'_nu of (2.1)", [], check_identity(
        "2.2", "d(dL*/dq_eps)/dq'_nu = d/dq_eps(dL*/dq'_nu) + dL*/dq_nu",
        [dL.diff(qp[c]) for c in nus],
        [red._D(Ls.diff(qp[c])) + Ls.diff(q[c]) for c in nus], smp)))
    if S.dependent_coordinates:
        lhs = [red._D(qs).diff(qp[c]) for qs in red._qdstar for c in nus]
        rhs = [red._D(qs.diff(qp[c])) + qs.diff(q[c]) for qs in red._qdstar for c in nus]
        st.append(Step("2.3", "the same for qdot*", [], check_identity(
            "2.3", "d(dqdot*/dq_eps)/dq'_nu = d/dq_eps(dqdot*/dq'_nu) + dqdot*/dq_nu",
            lhs, rhs, smp)))
    else:
        st.append(Step("2.3", "no constraints (g = 0): nothing to transform", []))
    st.append(Step("2.4", "the equations in Nielsen form, one per q_nu",
                   [eq(e, 0) for e in n["2.4"]], check_identity(
                       "2.4", "(2.4) minus (1.26) vanishes: the Nielsen form is equivalent",
                       n["2.4"], red._eqs, smp)))
    return st
