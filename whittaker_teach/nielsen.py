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

from .canonical import mul, sub
from .reading import check_reading, nielsen_forms, total_derivative_form
from .steps import Step, eq, notation, partial, tex, text
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
            e = sub(red._d(dL, qp), mul(2, red._d(Ls, q)))                     # (2.4)
            for P, qs, d in zip(red._Pstar, red._qdstar, dq):
                term = sub(red._d(d, qp), mul(2, red._d(qs, q)))
                if term != 0:       # P*0 would ask whether every factor of P is finite
                    e = sub(e, mul(P, term))
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
    xl = tex(x)
    dform = total_derivative_form(red)
    st = [Step("2.1", r"the total derivative of $L^*$ ($q''$ appears explicitly)",
               lambda: [eq(notation(f"dL*/d{x}", rf"\frac{{d L^{{*}}}}{{d {xl}}}"), dform)],
               check_reading("2.1", rf"the form shown is $dL^*/d{xl}$ along a path", [dform],
                             [dL], red))]

    def claim22(z, f, ft):
        """d/dq'(df/dx) = d/dx(df/dq') + df/dq, in the paper's notation."""
        zt, zl = text(qp[z], use_unicode=True), tex(qp[z])
        lhs = notation(f"∂/∂{zt}(d{f}/d{x})",
                       rf"\frac{{\partial}}{{\partial {zl}}}\frac{{d {ft}}}{{d {xl}}}")
        rhs = (notation(f"d/d{x}(∂{f}/∂{zt})",
                        rf"\frac{{d}}{{d {xl}}}\frac{{\partial {ft}}}{{\partial {zl}}}")
               + partial(f, ft, q[z]))
        return eq(lhs, rhs)
    st.append(Step("2.2", r"$\partial/\partial q'_\nu$ of (2.1)",
                   lambda: [claim22(c, "L*", "L^{*}") for c in nus], check_identity(
        "2.2", r"$\partial(dL^*/dq_\varepsilon)/\partial q'_\nu = d/dq_\varepsilon(\partial L^*/"
        r"\partial q'_\nu) + \partial L^*/\partial q_\nu$",
        [red._d(dL, qp[c]) for c in nus],
        [red._D(red._d(Ls, qp[c])) + red._d(Ls, q[c]) for c in nus], smp)))
    if S.dependent_coordinates:
        lhs = [red._d(red._D(qs), qp[c]) for qs in red._qdstar for c in nus]
        rhs = [red._D(red._d(qs, qp[c])) + red._d(qs, q[c]) for qs in red._qdstar for c in nus]
        def shown():
            return [claim22(c, text(S.qd[d]) + "*", tex(S.qd[d]) + "^{*}")
                    for d in S.dependent_coordinates for c in nus]
        st.append(Step("2.3", r"the same for $\dot q^*$", shown, check_identity(
            "2.3", r"$\partial(d\dot q^*/dq_\varepsilon)/\partial q'_\nu = d/dq_\varepsilon"
            r"(\partial\dot q^*/\partial q'_\nu) + \partial\dot q^*/\partial q_\nu$",
            lhs, rhs, smp)))
    else:
        st.append(Step("2.3", r"no constraints ($g = 0$): nothing to transform", []))
    forms = nielsen_forms(red)
    st.append(Step("2.4", r"the equations in Nielsen form, one per $q_\nu$",
                   lambda: [eq(f, 0) for f in forms], check_reading(
                       "2.4", "(2.4) minus (1.26) vanishes: the Nielsen form is equivalent; the "
                       "form shown is (2.4)", forms, list(n["2.4"]), red,
                       also=(list(n["2.4"]), list(red._eqs)))))
    return st
