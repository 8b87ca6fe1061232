"""The steps (3.1)-(3.15) of the sledge, each compared with the paper's printed form.

Kept apart from ``sledge.py`` so that building the sledge does not load it.
"""

import mpmath
import sympy as sp

from ..canonical import power
from ..dag import diff             # SymPy's own rules, each shared piece once
from ..reading import TotalD, cleared_forms
from ..steps import Step, eq, notation
from ..verify import DPS, Check, check_identity, check_zero, largest_value


def _p(red, name):
    return next(p for p in red.system.parameters if p.name == name)


def _refuted(label, claim, expr, sample, points=6):
    """A check that ``expr`` does NOT vanish: used to show a misprint is wrong."""
    worst = largest_value(expr, sample, points)
    return Check(label, claim, worst > 1e-6, "refutation", f"numerically at {points} random "
                 f"admissible points, mpmath at {DPS} digits: the printed form leaves a residual "
                 f"as large as {worst:.2g}", points, worst)


def section3_steps(red):
    S = red.system
    m, J, k = (_p(red, n) for n in "mJk")
    x, th, y = (S.q[c] for c in S.coordinates)
    xd, thd, yd = (S.qd[c] for c in S.coordinates)
    thp, thpp = red._qp[S.coordinates[1]], red._qpp[S.coordinates[1]]
    v, h, s = red._v, red.h, red.direction
    C, a, phi, t = sp.Symbol("C", positive=True), sp.Symbol("a"), sp.Symbol("phi_0"), sp.Symbol("t")
    sec2 = 1 + sp.tan(th)**2
    smp, smp_t = red._sample, S._sample_time

    def smp_c(rng):
        """A point with 2h - m C^2 - k^2 theta^2 > 0, for the first integral (3.11)."""
        pt = red._sample(rng, energy=False)          # h is set here
        with mpmath.workdps(DPS):
            pt[C] = mpmath.mpf(rng.uniform(0.3, 1.5))
            pt[h] = (pt[m] * pt[C]**2 + pt[k]**2 * pt[th]**2) / 2 + rng.uniform(0.1, 1.0)
            pt[a] = rng.uniform(0.1, 1.2)
            pt[phi] = rng.uniform(-3, 3)
            pt[t] = rng.uniform(-3, 3)
        return pt

    st = [Step("3.1", "the Lagrangian", [eq(sp.Symbol("L"), S._L)]),
          Step("3.2", "the constraint: the runner does not slide sideways",
               [eq(yd, S._phi[y])])]
    printed = m / 2 * xd**2 * sec2 + J / 2 * thd**2 - k**2 * th**2 / 2
    st.append(Step("3.3", r"$\tilde L$", [eq(sp.Symbol("Ltilde"), printed)], check_identity(
        "3.3", r"the printed $\tilde L$ equals the derived one", printed, S._Ltilde, smp_t)))
    printed = m / 2 * xd**2 * sec2 + J / 2 * thd**2 + k**2 * th**2 / 2
    st.append(Step("3.4", "the energy integral (1.11)", [eq(printed, h)], check_identity(
        "3.4", "the printed energy equals (1.11)", printed, S._energy(), smp_t)))
    printed = (2 * h - k**2 * th**2) / (m * sec2 + J * thp**2)
    st.append(Step("3.5", r"(1.13) solved: $\dot x^2$, with $\theta' = d\theta/dx$",
                   [eq(v**2, printed)], check_identity(
        "3.5", r"$\dot x^2$ from (1.12) equals the corrected form, with $J\theta'^2$ and "
        r"$\theta' = d\theta/dx$ (the OCR prints $J\dot\theta^2$, which mixes $t$ and $x$: "
        "erratum 3)", red._vstar**2, printed, smp)))
    printed = v**2 / 2 * (m * sec2 + J * thp**2) - k**2 * th**2 / 2
    st.append(Step("3.6", r"$\Omega$ (1.6)", [eq(sp.Symbol("Omega"), printed)], check_identity(
        "3.6", r"the corrected form of $\Omega$, with $J\theta'^2$ (the OCR prints "
        r"$J\dot\theta^2$: erratum 3), equals (1.6)", printed, red._Omega, smp)))
    printed = s * sp.sqrt(2 * h - k**2 * th**2) * sp.sqrt(m * sec2 + J * thp**2)
    st.append(Step("3.7", f"$L^*$ (1.16); the sign is the direction of travel, here ${s:+d}$",
                   [eq(notation("L*", "L^{*}"), printed)], check_identity(
        "3.7", r"the corrected form of $L^*$, with $J\theta'^2$ (the OCR prints "
        r"$J\dot\theta^2$: erratum 3), equals (1.16)", printed, red._Lstar, smp)))
    st.append(Step("3.8", r"$\dot y^*$ (1.23)", [eq(notation("ẏ*", r"\dot{y}^{*}"),
                                                   red._qdstar[0])], check_identity(
        "3.8", r"$\partial(\dot x\tan\theta)/\partial\dot x = \tan\theta$", red._qdstar[0],
        sp.tan(th), smp)))
    A = J * thp**2 + m * sec2
    R = 2 * h - k**2 * th**2
    printed = (red._D(s * sp.sqrt(R) * J * thp / sp.sqrt(A))
               + s * k**2 * th * sp.sqrt(A) / sp.sqrt(R))
    shown = (TotalD(s * sp.sqrt(R) * J * thp / sp.sqrt(A), x)
             + s * k**2 * th * sp.sqrt(A) / sp.sqrt(R))
    st.append(Step("3.9", r"the paper's (3.9), expanded and simplified (a line it prints without a "
                   r"number): (1.26) for the sledge after the $m\tan\theta\,(1 + \tan^2\theta)$ "
                   "terms cancel", [eq(shown, 0)], check_identity(
        "3.9", r"the form shown equals (1.26) (the OCR's last term lacks the root of "
        r"$2h - k^2\theta^2$ and the factor $1 + \tan^2\theta$)", printed, red._eqs[0], smp)))
    qpp = red._tidy_accelerations()[thpp]
    (cleared,) = cleared_forms(red)      # J R theta'' - N, with theta''_[1.26b] = N / (J R)
    printed = J * R * thpp + J * (-R * sp.tan(th) + k**2 * th) * thp**2 + m * k**2 * th * sec2
    st.append(Step("3.10", r"(1.26) cleared of denominators: $J(2h - k^2\theta^2)\,(\theta'' "
                   r"- \theta''_{[1.26b]})$", [eq(cleared, 0)], check_identity(
        "3.10", r"the cleared equation equals the printed (3.10) with "
        r"$mk^2\theta\,(1 + \tan^2\theta)$",
        cleared, printed, smp)))
    ocr = printed - m * k**2 * th * sec2 + m * k * th * sec2
    st.append(Step("3.10 OCR", r"erratum: the OCR's coefficient $mk\theta$", [eq(ocr, 0)],
                   _refuted("3.10 OCR", r"the OCR form with $mk\theta\,(1 + \tan^2\theta)$ is "
                            "not satisfied by the solutions of (1.26)", ocr.xreplace({thpp: qpp}),
                            smp)))
    F = power(-k**2 * th**2 + 2 * h - m * C**2, sp.S.Half) / (sp.sqrt(J) * C * sp.cos(th))
    along = {thp: F, thpp: diff(F, th) * F}
    # shown squared: the paper prints one root, but theta' changes sign at each turning
    # point of theta; (3.10) holds on either root (theta'^2 and theta'' = F'F are the same)
    st.append(Step("3.11", "a first integral of (3.10), $C$ a constant, as a square: the paper "
                   r"prints the root $\theta' = F(\theta)$, but $\theta'$ changes sign at each "
                   r"turning point of $\theta$; the root holds on each half-swing (remark 8 "
                   "of the errata)", [eq(thp**2, F**2)], check_zero(
        "3.11", r"$\theta' = \pm F(\theta)$, $\theta'' = F'(\theta)\,F$ satisfy (3.10) for "
        "every $C$", [printed.xreplace(along), printed.xreplace({thp: -F, thpp: diff(F, th) * F})],
        smp_c)))
    integral = R * power(m + J * thp**2 * sp.cos(th)**2, -1)
    st.append(Step("3.11a", r"equivalently $C^2 = (2h - k^2\theta^2)/(m + J\theta'^2\cos^2"
                   r"\theta)$ is constant along (1.26)", [eq(C**2, integral)], check_zero(
        "3.11a", "$d/dx$ of the integral vanishes on the solutions of (1.26)",
        red._D(integral).xreplace({thpp: qpp}), smp)))
    # (3.12)-(3.14) for the direction s: the equation shown is the one checked (for
    # s = -1, xdot = -C cos theta; the paper, with s = +1, prints C cos theta)
    xdot_c = red._vstar.xreplace({thp: F})
    xdot_shown = s * C * sp.cos(th)
    minus = "" if s > 0 else "-"
    st.append(Step("3.12", "(3.11) in (3.5)" + ("" if s > 0 else r"; $x$ decreases, so the sign "
                   "is minus"), [eq(xd, xdot_shown)], check_identity(
        "3.12", rf"$\dot x$ from (1.12) on the first integral equals ${minus}C\cos\theta$",
        xdot_c, xdot_shown, smp_c)))
    ydot_shown = s * C * sp.sin(th)
    st.append(Step("3.13", "by (3.2)", [eq(yd, ydot_shown)], check_identity(
        "3.13", rf"$\dot x\tan\theta = {minus}C\sin\theta$", xdot_shown * sp.tan(th),
        ydot_shown, smp_c)))
    thdot = F * xdot_shown
    thdd = S.qdd[S.coordinates[1]]
    st.append(Step("3.14", r"$\dot\theta = \theta'\dot x$ (the OCR prints $\theta$ for "
                   r"$\dot\theta$), squared: the root has no one sign (remark 8 of the errata); "
                   "and its derivative",
                   [eq(thd**2, thdot**2), eq(thdd, -k**2 / J * th)],
                   check_identity(
        "3.14", r"$\dot\theta = \theta'\dot x$ on (3.11), so $\dot\theta^2$ is the form shown, "
        r"and $\frac{d\dot\theta}{d\theta}\,\dot\theta = -k^2\theta/J$, as (1.4) gives in time",
        [F * xdot_c, (F * xdot_c)**2, diff(thdot, th) * thdot, S._accelerations()[thdd]],
        [thdot, thdot**2, -k**2 * th / J, -k**2 * th / J], smp_c)))
    sol = a * sp.cos(k / sp.sqrt(J) * t + phi)
    st.append(Step("3.15", "the motion in time; $h = mC^2/2 + k^2a^2/2$",
                   [eq(th, sol), eq(h, m * C**2 / 2 + k**2 * a**2 / 2)], check_zero(
        "3.15", "theta(t) solves (3.14), and thetadot = 0 at theta = a when h = m C^2/2 + "
        "k^2 a^2/2", [diff(diff(sol, t), t) + k**2 / J * sol,
                      (-k**2 * th**2 + 2 * h - m * C**2).xreplace(
                          {th: a, h: m * C**2 / 2 + k**2 * a**2 / 2})], smp_c)))
    return st
