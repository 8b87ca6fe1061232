"""Chetaev's virtual displacements (Chetaev 1932-33) for the constraints of a system.

A constraint f_beta(q, qdot) = 0 restricts the virtual displacements by Chetaev's
condition

    sum_s df_beta/dqdot_s delta q_s = 0                                       [Ch1]

which for a linear constraint A(q) qdot = 0 is the usual A(q) delta q = 0, and for
a nonlinear one is a definition (Chetaev 1932-33; Appell's example of a weight whose
vertical speed is tied to its horizontal speed, zdot = c sqrt(xdot^2 + ydot^2),
realised as the limit of a mechanism, Appell 1911, Hamel 1949).  Solved, the free
displacements are delta q_beta = sum_sigma B_beta,sigma delta q_sigma with Chetaev's
coefficients B = dphi_beta/dqdot_sigma [Ch2].  The ideal constraint force is
R_s = -sum_beta lambda_beta df_beta/dqdot_s (the multipliers of Routh-Voss); it does
no virtual work on [Ch1] by construction, and for a constraint homogeneous of degree
one in the velocities (the model's assumption) no work on the actual motion either:
sum_s R_s qdot_s = -sum lambda_beta f_beta = 0 by Euler's relation [Ch3], checked
here for the system at hand.

>>> from whittaker_teach.forms import examples
>>> d = chetaev(examples.appell_hamel())
>>> d.labels, d["Ch3"].status
(['Ch1', 'Ch2', 'Ch3'], 'verified')
"""

from __future__ import annotations

import sympy as sp

from ..canonical import add, mul
from ..errors import guarded
from ..steps import Derivation, Step, eq
from ..verify import check_zero, shared_points
from ._print import indexed, tidy
from .routh_voss import RouthVoss

__all__ = ["chetaev"]


@guarded("Chetaev's virtual displacements")
def chetaev(system):
    """The steps [Ch1]-[Ch3] for the constraints of ``system`` (a
    :class:`~whittaker_teach.forms.NonholonomicSystem`)."""
    S = system
    rv = RouthVoss(S)
    J = rv._jacobian()
    # plain symbols (delta_x): variables a reader substitutes into
    delta = {c: sp.Symbol("delta_" + str(S.q[c])) for c in S.coordinates}
    cond = [add(*[mul(J[i][j], delta[c]) for j, c in enumerate(S.coordinates) if J[i][j] != 0])
            for i in range(len(S._f))]
    free = [(delta[b], add(*[mul(S.B(b, s), delta[s]) for s in S.sigma])) for b in S.beta]
    lam = rv._lambdas()
    sol = rv._solution()
    R = [add(*[-mul(l, J[i][j]) for i, l in enumerate(lam) if J[i][j] != 0])
         for j in range(len(S.coordinates))]
    on = {S.qd[c]: phi for c, phi in S._phi.items()}
    power = add(*[mul(r, on.get(S.qd[c], S.qd[c])) for r, c in zip(R, S.coordinates)])
    sig = [S.qd[c] for c in S.sigma]
    with shared_points():
        chk = check_zero("Ch3", "the ideal constraint force does no work on the actual motion "
                         r"($\sum_s R_s\,\dot q_s = 0$, with the multipliers of the motion: "
                         "the constraints are homogeneous of degree one)", power, S.sample,
                         seed=19, at={l: sol[l] for l in lam})
    steps = [
        Step("Ch1", r"Chetaev's conditions $\sum_s \partial f_\beta/\partial\dot q_s\,"
             r"\delta q_s = 0$, one per constraint as given", lambda: [eq(e, 0) for e in cond]),
        Step("Ch2", r"the free virtual displacements, $\delta q_\beta = \sum_\sigma "
             r"B_{\beta\sigma}\,\delta q_\sigma$ (Chetaev's coefficients)",
             lambda: [eq(a, b) for a, b in free]),
        Step("Ch3", r"the ideal constraint force $R_s = -\sum_\beta \lambda_\beta\,"
             r"\partial f_\beta/\partial\dot q_s$ (the multipliers of [RV]) and its power",
             lambda: [eq(indexed("R", [S.q[c]]), r) for c, r in zip(S.coordinates, R)]
             + [eq(l, tidy(sol[l], sig)) for l in lam]
             + [eq(sp.Symbol("P_R"), power)], chk),
    ]
    return Derivation(f"{S.name}: Chetaev's virtual displacements", steps)
