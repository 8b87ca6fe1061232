"""The exercises: for each, its symbols, its domain (the stated assumptions) and its parts.

Every expected answer that the library computes is taken from it (``L_star``,
``Omega``, ``velocity``, ``accelerations()``, ``constraint_rates``,
``nielsen_equations``); the others (the projectile's path, the Kepler
energy, the paper's misprints) are short closed forms, each verified
against the library's equations by the tests.  A builder runs on the first
check of its exercise only.
"""

from __future__ import annotations

import functools

import sympy as sp

from .compare import Domain
from .specs import Exercise, Names, Part, plain

__all__ = ["EXERCISES"]

# The sampling covers every range the statements allow (compare.Domain spreads
# the points over each range): an angle the statement does not restrict over a
# whole turn, one it restricts to |theta| < pi/2 over all of that interval.
POSITIVE = (0.5, 2.0)       # masses, moments of inertia, lengths, constants
ANGLE = (-1.5707, 1.5707)   # |theta| < pi/2, as the sledge statements say
TURN = (-3.1415, 3.1415)    # an angle the statement does not restrict: a whole turn
SLOPE = (-3.0, 3.0)         # q' = dq/dq_eps
SPEED = (0.05, 3.0)         # qdot_eps > 0: the direction of travel
ENERGY = (0.5, 4.0)


def _syms(spec):
    """'m+ J+ k+ theta' -> symbols, + meaning positive."""
    out = []
    for tok in spec.split():
        pos = tok.endswith("+")
        out.append(sp.Symbol(tok.rstrip("+"), positive=True) if pos else sp.Symbol(tok))
    return out


def _total(f, x, chain):
    """d/dx of f(q', q, x) along a path: chain = [(q, q', q''), ...] (2.1)."""
    out = f.diff(x)
    for q, qp, qpp in chain:
        out += f.diff(qp) * qpp + f.diff(q) * qp
    return out


def _one(d):
    (value,) = d.values()
    return value


XDOT_NOTE = "the direction of travel is xdot > 0, so take the root with the + sign"


# ---------------------------------------------------------------- projectile-path
def _projectile_path():
    import whittaker_teach as wt
    names = Names(_syms("x y yprime yprimeprime h m+ g_0+ v0+ alpha"))   # g_0: gravity
    x, y, yp, ypp, h, m, g, v0, alpha = (names[n] for n in
                                         "x y yprime yprimeprime h m g_0 v0 alpha".split())
    red = wt.examples.projectile().reduce("x", +1)
    dom = Domain({x: (0.0, 3.0), y: (-1.0, 1.0), yp: SLOPE, ypp: (-1.0, 1.0), h: ENERGY,
                  m: POSITIVE, g: POSITIVE, v0: POSITIVE, alpha: (0.001, 1.5707)},
                 conditions=(h - m * g * y,))
    path = x * sp.tan(alpha) - g * x**2 / (2 * v0**2 * sp.cos(alpha)**2)
    parts = [
        Part("L_star", "L* (1.16) for the projectile with x in place of t",
             plain(red.L_star, names), (y, yp, h, m, g), sign_note=XDOT_NOTE,
             why_not={"x": "L does not depend on x", "v0": "L* is written with the energy h",
                      "alpha": "L* is written with the energy h"},
             success="L* = sqrt(2(h - m g_0 y)) sqrt(m (1 + y'^2)), the root for xdot > 0 (1.16)."),
        Part("y_pp", "y'' solved from Whittaker's equation (1.27)",
             plain(_one(red.accelerations()), names), (y, yp, h, m, g),
             why_not={"yprimeprime": "solve the equation for y''"},
             success="y'' from (1.27): the same for either direction of travel."),
        Part("path", "the path y(x) of the projectile launched from the origin with speed v0 "
             "at angle alpha", path, (x, g, v0, alpha),
             why_not={"h": "use h = m v0^2/2", "m": "the path does not depend on the mass",
                      "y": "y(x) is the answer", "yprime": "use y'(0) = tan(alpha)"},
             success="The parabola y = x tan(alpha) - g_0 x^2/(2 v0^2 cos^2(alpha)): it solves "
             "(1.27) with h = m v0^2/2, y(0) = 0, y'(0) = tan(alpha)."),
    ]
    return names, dom, parts


# ---------------------------------------------------------------- kepler-orbit
def _kepler_orbit():
    import whittaker_teach as wt
    names = Names(_syms("r+ rprime rprimeprime theta h m+ mu+ p+ e"))
    r, rp, rpp, theta, h, m, mu, p, e = (names[n] for n in
                                       "r rprime rprimeprime theta h m mu p e".split())
    red = wt.examples.kepler().reduce("theta", +1)
    acc = plain(_one(red.accelerations()), names)
    # the conic at theta = pi/2 (r = p, r' = p e, r'' = 2 p e^2) in (1.27) fixes h
    (h_conic,) = sp.solve(2 * p * e**2 - acc.xreplace({r: p, rp: p * e}), h)
    # e >= 0: ellipses, the parabola and hyperbolas
    dom = Domain({r: (0.5, 3.0), rp: SLOPE, rpp: (-1.0, 1.0), theta: TURN, h: (-1.0, 3.0),
                  m: POSITIVE, mu: POSITIVE, p: POSITIVE, e: (0.0, 3.0)},
                 conditions=(h + m * mu / r,))
    parts = [
        Part("L_star", "L* (1.16) for the Kepler problem with theta in place of t",
             plain(red.L_star, names), (r, rp, h, m, mu),
             sign_note="theta increases along the orbit (thetadot > 0): take the + root",
             why_not={"theta": "L does not depend on theta"},
             success="L* = sqrt(2 h + 2 m mu/r) sqrt(m (r^2 + r'^2)) (1.16)."),
        Part("r_pp", "r'' solved from Whittaker's equation (1.27)", acc, (r, rp, h, m, mu),
             why_not={"rprimeprime": "solve the equation for r''"},
             success="r'' from (1.27)."),
        Part("h", "the energy h for which the conic r = p/(1 + e cos(theta)) solves (1.27)",
             h_conic, (m, mu, p, e),
             why_not={"theta": "h is a constant", "r": "h is a constant of the orbit",
                      "rprime": "h is a constant of the orbit"},
             success="h = -m mu (1 - e^2)/(2 p), for every e >= 0: negative for an ellipse "
             "(e < 1), zero for a parabola (e = 1), positive for a hyperbola (e > 1)."),
    ]
    return names, dom, parts


# ---------------------------------------------------------------- omega-and-energy
def _omega_and_energy():
    import whittaker_teach as wt
    names = Names(_syms("theta thetadot psi psiprime psidot h m+ R+ A+ C+ k+"))
    th, thd, ph, php, phd, h, m, R, A, C, k = (
        names[n] for n in "theta thetadot psi psiprime psidot h m R A C k".split())
    red = wt.examples.rolling_disk().reduce("theta", +1)
    Omega = plain(red.Omega, names)
    dom = Domain({th: TURN, thd: SPEED, ph: TURN, php: SLOPE, phd: SLOPE, h: ENERGY,
                  m: POSITIVE, R: POSITIVE, A: POSITIVE, C: POSITIVE, k: POSITIVE},
                 conditions=(2 * h - k**2 * ph**2,))
    no_psidot = "use (1.5): psidot = thetadot psi'"
    parts = [
        Part("Omega", "Omega (1.6): L~ with psidot = thetadot psi'", Omega,
             (thd, ph, php, m, R, A, C, k), why_not={"psidot": no_psidot,
                                                     "h": "Omega is L~, not the energy"},
             success="Omega = thetadot^2 (A + m R^2 + C psi'^2)/2 - k^2 psi^2/2 (1.6)."),
        Part("energy", "the left-hand side of (1.13), thetadot dOmega/dthetadot - Omega",
             sp.expand(thd * Omega.diff(thd) - Omega), (thd, ph, php, m, R, A, C, k),
             why_not={"psidot": no_psidot, "h": "give the left-hand side of (1.13); its value "
                      "is h"},
             success="The energy (1.13): kinetic plus potential, written with psi'."),
        Part("thetadot", "thetadot (1.12): (1.13) solved for thetadot > 0",
             plain(red.velocity, names), (ph, php, h, m, R, A, C, k),
             sign_note="the disk rolls forward, thetadot > 0: take the + root",
             why_not={"thetadot": "solve (1.13) for thetadot", "psidot": no_psidot},
             success="thetadot = sqrt(2h - k^2 psi^2)/sqrt(A + m R^2 + C psi'^2) (1.12)."),
    ]
    return names, dom, parts


# ---------------------------------------------------------------- identity-1-19
def _identity_1_19():
    names = Names(_syms("x xdot+ theta thetaprime h m+ J+ b+ k+"))
    x, v, th, thp, h, m, J, b, k = (names[n] for n in
                                    "x xdot theta thetaprime h m J b k".split())
    Om = v**2 / 2 * (m + J * thp**2) + b * v * thp * sp.cos(th) - k**2 * th**2 / 2
    Ov, Ovv, Op = Om.diff(v), Om.diff(v, 2), Om.diff(thp)
    # (1.14): v Ovv dv/dq' + v Ov,q' - Oq' = 0
    dv = sp.Symbol("dv")
    (dv_dqp,) = sp.solve(v * Ovv * dv + v * Ov.diff(thp) - Op, dv)
    dL = Ovv * dv_dqp + Ov.diff(thp)                 # (1.17)
    dom = Domain({x: (0.0, 2.0), v: SPEED, th: TURN, thp: SLOPE, h: ENERGY, m: POSITIVE,
                  J: POSITIVE, b: POSITIVE, k: POSITIVE})
    keep_v = "keep xdot as a symbol: it stands for qdot_eps(q', q, h) of (1.12)"
    parts = [
        Part("dxdot_dthetaprime", "d xdot/d theta' solved from (1.14)", sp.factor(dv_dqp),
             (v, th, thp, m, J, b, k), why_not={"h": keep_v},
             success="From (1.14): d xdot/d theta' = -xdot J theta'/(m + J theta'^2); "
             "b drops out."),
        Part("dLstar_dthetaprime", "dL*/d theta' from (1.17), with (1.14) substituted",
             sp.expand(dL), (v, th, thp, m, J, b, k), why_not={"h": keep_v},
             success="dL*/d theta' = J xdot theta' + b cos(theta) = (1/xdot) dOmega/d theta': "
             "that is (1.19)."),
    ]
    return names, dom, parts


# ---------------------------------------------------------------- sledge symbols
def _sledge_names():
    return Names(_syms("x xdot+ y ydot theta thetadot thetaprime thetaprimeprime h m+ J+ k+"))


def _sledge_domain(names):
    x, v, y, yd, th, thd, thp, thpp, h, m, J, k = (
        names[n] for n in "x xdot y ydot theta thetadot thetaprime thetaprimeprime h m J k"
        .split())
    return Domain({x: (0.0, 2.0), v: SPEED, y: (-1.0, 1.0), yd: SLOPE, th: ANGLE, thd: SLOPE,
                   thp: SLOPE, thpp: (-1.0, 1.0), h: ENERGY, m: POSITIVE, J: POSITIVE,
                   k: POSITIVE}, conditions=(2 * h - k**2 * th**2,))


@functools.lru_cache(maxsize=None)
def _sledge_reduction():
    """The sledge reduced in x (xdot > 0): built once, shared by the sledge exercises."""
    import whittaker_teach as wt
    return wt.examples.sledge().reduce("x", +1)


# ---------------------------------------------------------------- constraint-star
def _constraint_star():
    from sympy.physics.mechanics import dynamicsymbols
    names = _sledge_names()
    x, v, th, thp, thpp = (names[n] for n in "x xdot theta thetaprime thetaprimeprime".split())
    h, m, J, k = (names[n] for n in "h m J k".split())
    red = _sledge_reduction()
    S = red.system
    t = dynamicsymbols._t
    xs, ths, ys = S.coordinates
    phi = plain(S.constraints[ys.diff(t)], names)                        # (3.2)
    omega = phi.xreplace({names["thetadot"]: v * thp})                   # (1.22)
    qstar = plain(_one(red.constraint_rates), names)                     # (1.23)
    bracket = _total(qstar.diff(thp), x, [(th, thp, thpp)]) - qstar.diff(th)
    P = plain(S.lagrangian.diff(ys.diff(t)), names).xreplace({names["ydot"]: phi})
    Pstar = P.xreplace({names["thetadot"]: v * thp}).xreplace({v: plain(red.velocity, names)})
    parts = [
        Part("omega", "omega_y (1.22): the constraint with (1.5) substituted", omega,
             (v, th, thp), why_not={"thetadot": "use (1.5): thetadot = xdot theta'"},
             success="omega = xdot tan(theta): it does not contain theta' at all."),
        Part("ydot_star", "ydot* (1.23) = d omega/d xdot", qstar, (th, thp),
             why_not={"xdot": "ydot* = d omega/d xdot is free of xdot (1.23)"},
             success="ydot* = tan(theta) (3.8): the slope dy/dx of the path."),
        Part("bracket", "the bracket of (1.26): d/dx(d ydot*/d theta') - d ydot*/d theta",
             bracket, (th, thp, thpp),
             success="The bracket is -(1 + tan^2(theta)) = -1/cos^2(theta)."),
        Part("P_star", "(dL/d ydot)* of (1.26): m ydot in theta', theta and h",
             Pstar, (th, thp, h, m, J, k), sign_note=XDOT_NOTE,
             why_not={"xdot": "put xdot from (1.12)", "ydot": "use the constraint (3.2)"},
             success="(dL/d ydot)* = m tan(theta) sqrt(2h - k^2 theta^2)/sqrt(m (1 + "
             "tan^2(theta)) + J theta'^2)."),
    ]
    return names, _sledge_domain(names), parts


# ---------------------------------------------------------------- sledge-L-star
def _sledge_L_star():
    names = _sledge_names()
    v, th, thp, h, m, J, k = (names[n] for n in "xdot theta thetaprime h m J k".split())
    red = _sledge_reduction()
    parts = [
        Part("Omega", "Omega (3.6): L~ (3.3) with thetadot = xdot theta'",
             plain(red.Omega, names), (v, th, thp, m, J, k),
             why_not={"thetadot": "use (1.5): thetadot = xdot theta'", "ydot": "use (3.2)",
                      "h": "Omega is L~, not the energy"},
             success="Omega = xdot^2 (m (1 + tan^2 theta) + J theta'^2)/2 - k^2 theta^2/2 (3.6)."),
        Part("xdot", "xdot (3.5): the root of (1.13) with xdot > 0",
             plain(red.velocity, names), (th, thp, h, m, J, k), sign_note=XDOT_NOTE,
             why_not={"xdot": "solve (1.13) for xdot", "thetadot": "use theta'"},
             wrong=[(sp.sqrt(2 * h - k**2 * th**2) / sp.sqrt(m * (1 + sp.tan(th)**2)
                                                               + J * names["thetadot"]**2),
                     "this is (3.5) as the OCR prints it, with J thetadot^2")],
             success="xdot = sqrt(2h - k^2 theta^2)/sqrt(m (1 + tan^2 theta) + J theta'^2) (3.5)."),
        Part("L_star", "L* (3.7) = dOmega/d xdot with xdot from (3.5)",
             plain(red.L_star, names), (th, thp, h, m, J, k), sign_note=XDOT_NOTE,
             why_not={"xdot": "put xdot from (3.5)", "thetadot": "use theta'"},
             success="L* = sqrt(2h - k^2 theta^2) sqrt(m (1 + tan^2 theta) + J theta'^2) (3.7), "
             "the + sign for xdot > 0."),
    ]
    return names, _sledge_domain(names), parts


# ---------------------------------------------------------------- sledge-reduced-equation
def _sledge_reduced_equation():
    names = _sledge_names()
    th, thp, thpp, h, m, J, k = (names[n] for n in
                                 "theta thetaprime thetaprimeprime h m J k".split())
    red = _sledge_reduction()
    acc = plain(_one(red.accelerations()), names)
    R = 2 * h - k**2 * th**2
    # (3.10) is J R (theta'' - acc) = 0; its term free of theta' and theta''
    last = sp.factor(-J * R * acc.xreplace({thp: 0}))
    printed = m * k * th * (1 + sp.tan(th)**2)
    parts = [
        Part("theta_pp", "theta'' solved from (1.26) for the sledge", acc,
             (th, thp, h, m, J, k), why_not={"thetaprimeprime": "solve (1.26) for theta''"},
             success="theta'' from (1.26); multiplied by J (2h - k^2 theta^2) it gives (3.10)."),
        Part("last_term", "the term of (3.10) free of theta' and theta''", last,
             (th, h, m, J, k),
             wrong=[(printed, "that is the coefficient as the paper prints it, m k theta "
                     "(1 + tan^2 theta): compare it with what (1.26) gives you")],
             why_not={"thetaprime": "take the term free of theta'",
                      "thetaprimeprime": "take the term free of theta''"},
             success="The last term of (3.10) is m k^2 theta (1 + tan^2 theta): the printed "
             "m k theta (1 + tan^2 theta) lacks a factor k (dimensions: k^2 theta is a torque)."),
    ]
    return names, _sledge_domain(names), parts


# ---------------------------------------------------------------- nielsen-form
def _nielsen_form():
    import whittaker_teach as wt
    names = Names(_syms("r+ rprime rprimeprime theta h m+ mu+"))
    r, rp, rpp, theta, h, m, mu = (names[n] for n in "r rprime rprimeprime theta h m mu".split())
    red = wt.examples.kepler().reduce("theta", +1)
    Ls = plain(red.L_star, names)
    dL = _total(Ls, theta, [(r, rp, rpp)])                                  # (2.1)
    dom = Domain({r: (0.5, 3.0), rp: SLOPE, rpp: (-1.0, 1.0), theta: TURN, h: (-1.0, 3.0),
                  m: POSITIVE, mu: POSITIVE}, conditions=(h + m * mu / r,))
    parts = [
        Part("total_derivative", "dL*/dtheta (2.1), with r'' in it", dL, (r, rp, rpp, h, m, mu),
             success="(2.1): dL*/dtheta = dL*/dr' r'' + dL*/dr r' (+ dL*/dtheta = 0 here)."),
        Part("nielsen", "the left-hand side of (2.4): d/dr'(dL*/dtheta) - 2 dL*/dr",
             plain(red.nielsen_equations[0], names), (r, rp, rpp, h, m, mu),
             success="(2.4) for the Kepler problem; it equals the left-hand side of (1.26)."),
    ]
    return names, dom, parts


# ---------------------------------------------------------------- chaplygin-sleigh
def _chaplygin_sleigh():
    import whittaker_teach as wt
    from sympy.physics.mechanics import dynamicsymbols
    names = Names(_syms("x xdot+ y ydot theta thetadot thetaprime thetaprimeprime h m+ J+ "
                        "k+ b+ Jeff+"))
    v, th, thd, thp, h, m, J, k, b = (names[n] for n in
                                      "xdot theta thetadot thetaprime h m J k b".split())
    S = wt.examples.offset_sleigh()
    red = S.reduce("x", +1)
    Ls = plain(red.L_star, names)
    Jeff = sp.factor(sp.expand(Ls**2 / (2 * h - k**2 * th**2)).coeff(thp, 2))
    t = dynamicsymbols._t
    ys = S.coordinates[2]
    P = plain(S.lagrangian.diff(ys.diff(t)), names)
    P = P.xreplace({names["ydot"]: plain(S.constraints[ys.diff(t)], names)})
    Pstar = P.xreplace({thd: v * thp}).xreplace({v: plain(red.velocity, names)})
    acc = plain(_one(red.accelerations()), names)
    odd = sp.factor((acc - acc.xreplace({thp: -thp})) / 2)
    dom = _sledge_domain(names)
    dom = Domain({**dom.ranges, b: POSITIVE, names["Jeff"]: POSITIVE}, dom.conditions)
    parts = [
        Part("L_star", "L* (1.16) for the offset sleigh, xdot > 0", Ls,
             (th, thp, h, m, J, k, b), sign_note=XDOT_NOTE,
             why_not={"xdot": "put xdot from (1.12)", "thetadot": "use theta'"},
             success="L* is the sledge's (3.7) with J replaced by J + m b^2."),
        Part("J_eff", "the moment of inertia that replaces J in the sledge's L* (3.7)", Jeff,
             (m, J, b), success="J + m b^2: the moment of inertia about the contact point "
             "(parallel axes)."),
        Part("P_star", "(dL/d ydot)* in theta', theta and h", Pstar,
             (th, thp, h, m, J, k, b), sign_note=XDOT_NOTE,
             why_not={"xdot": "put xdot from (1.12)", "thetadot": "use theta'",
                      "ydot": "use the constraint"},
             success="(dL/d ydot)* carries the offset b: the constraint term of (1.26) "
             "is where the sleigh differs from a sledge with J + m b^2."),
        Part("odd_part", "the part of theta'' odd in theta': (theta''(theta') - "
             "theta''(-theta'))/2", odd, (th, thp, h, m, J, k, b),
             success="The odd part is proportional to b: theta' -> -theta' is the same as "
             "b -> -b. The sledge's mirrored path theta(-x) is again a path; the sleigh's is "
             "the path of a sleigh with its centre of mass behind the knife edge."),
    ]
    return names, dom, parts


# ---------------------------------------------------------------- turning-point
TURNING = {"m": 1.0, "J": 1.0, "k": 1.0, "C": 1.0, "a": 2.0}   # the numbers of the exercise


def _turning_point():
    import math

    import whittaker_teach as wt
    names = Names(_syms("x theta thetaprime t h C+ a+ m+ J+ k+"))
    th, C, a, J, k = (names[n] for n in "theta C a J k".split())
    names.definitions["omega"] = k / sp.sqrt(J)          # the statement's omega = k/sqrt(J)
    p = {n: TURNING[n] for n in "mJk"}
    ex = wt.examples.sledge_exact(p, a=TURNING["a"], phi=-math.pi / 2, C=TURNING["C"])
    red = _sledge_reduction()
    q0, qp0, h0 = ex.reduced_initial()
    outcome = "continues"
    try:
        red.simulate(q0, qp0, h0, (0.0, 5.0), p, rtol=1e-10)
    except wt.ChartError:
        outcome = "ChartError"
    omega = math.sqrt(p["k"]**2 / p["J"])
    t_turn = math.asin(math.pi / (2 * TURNING["a"])) / omega
    x_turn = sp.Float(ex(t_turn)["x"], 15)
    dom = Domain({names["x"]: (0.0, 2.0), th: ANGLE, names["thetaprime"]: SLOPE,
                  names["t"]: (0.0, 3.0), names["h"]: ENERGY, C: POSITIVE, a: (1.5709, 6.0),
                  names["m"]: POSITIVE, J: POSITIVE, k: POSITIVE})
    see = "run red.simulate across the turning point and read what happens"
    parts = [
        Part("xdot", "xdot along a motion of the sledge, in C and theta (from (3.5) and "
             "(3.11))", C * sp.cos(th), (C, th), sign_note=XDOT_NOTE,
             why_not={"thetaprime": "put theta' from the first integral (3.11)",
                      "h": "h drops out on the first integral"},
             success="xdot = C cos(theta) (3.12): x stops being usable where cos(theta) = 0."),
        Part("t_turn", "the first time t > 0 at which x stops being usable, for theta = "
             "a sin(k t/sqrt(J)) with a > pi/2", sp.sqrt(J) / k * sp.asin(sp.pi / (2 * a)),
             (a, J, k), why_not={"C": "the turning point is where theta = pi/2, whatever C",
                                 "theta": "give t in terms of a, J and k"},
             success="t = sqrt(J)/k asin(pi/(2a)): theta reaches pi/2 there, so xdot = C cos "
             "theta vanishes and x turns back."),
        Part("numerics", "what red.simulate does (default options) when the path reaches "
             "the turning point", choices={
                 "ChartError": (("raises ChartError", "chart error", "raises", "error",
                                 "whittaker_teach.ChartError"),
                                "The reduced model watches qdot_x and stops with a "
                                "ChartError that says where x turns back; on_turning_point="
                                "'switch' continues across it, in time."),
                 "NaN": (("nan", "returns nan", "nans"), f"No: {see}."),
                 "continues": (("continues past it", "wrong values", "silently continues",
                                "nothing"), f"No: {see}."),
                 "switches": (("switch", "switches chart", "switch to time"),
                              "Only when asked: that is on_turning_point='switch'; with the "
                              "default options, " + see + "."),
             }, answer_key=outcome),
        Part("x_turn", "x where the sledge turns back, for m = J = k = C = 1, a = 2 (to 6 "
             "digits)", x_turn, (), rtol=1e-6,
             success="x where xdot vanishes: the ChartError reports it, and the exact "
             "solution sledge_exact agrees."),
    ]
    return names, dom, parts


# ---------------------------------------------------------------- work-precision
WORK = {"m": 1.0, "J": 1.0, "k": 1.0, "C": 1.0, "a": 0.5, "T": 20.0}
WORK_METHODS = ("DOP853", "RK45")
WORK_RTOLS = tuple(10.0**-n for n in range(4, 13))
WORK_TARGET = 1e-8


def work_precision_table():
    """{method: [(rtol, nfev, error at t = T), ...]}: the exercise's measurements.

    The error is the largest of |x - x_exact|, |y - y_exact|, |theta - theta_exact|
    at t = T, the exact motion being the library's sledge_exact.
    """
    import math

    import whittaker_teach as wt
    p = {n: WORK[n] for n in "mJk"}
    ex = wt.examples.sledge_exact(p, a=WORK["a"], phi=-math.pi / 2, C=WORK["C"])
    system = wt.examples.sledge()
    q0, qdot0 = ex.initial()
    T = WORK["T"]
    exact = ex(T)
    table = {}
    for method in WORK_METHODS:
        rows = []
        for rtol in WORK_RTOLS:
            traj = system.simulate(q0, qdot0, (0.0, T), p, method=method, rtol=rtol)
            err = max(abs(float(traj.q[c][-1]) - exact[c]) for c in ("x", "y", "theta"))
            rows.append((rtol, int(traj.nfev), err))
        table[method] = rows
    return table


def cheapest(rows, target=WORK_TARGET):
    """The smallest nfev among the runs with error <= target (None if none)."""
    costs = [n for _, n, e in rows if e <= target]
    return min(costs) if costs else None


def _work_precision():
    names = Names([])
    table = work_precision_table()
    cost = {m: cheapest(rows) for m, rows in table.items()}
    best = min((c, m) for m, c in cost.items() if c is not None)[1]
    dom = Domain({})
    other = [m for m in WORK_METHODS if m != best][0]
    parts = [
        Part("nfev", "the fewest right-hand-side evaluations (nfev) with which DOP853 reaches "
             f"an error <= {WORK_TARGET:g} on the grid of tolerances", sp.Integer(cost["DOP853"]),
             (), success=f"DOP853 needs {cost['DOP853']} evaluations; RK45 needs "
             f"{cost['RK45']}."),
        Part("method", f"the integrator you would use for an error of {WORK_TARGET:g}", choices={
            best: ((best.lower(),), f"{best} reaches {WORK_TARGET:g} with "
                   f"{cost[best]} evaluations, {other} needs {cost[other]}."),
            other: ((other.lower(),), f"Compare the costs (nfev) at which each reaches an "
                    f"error of {WORK_TARGET:g}: read them off your table or plot."),
        }, answer_key=best),
        Part("why", "why that integrator is cheaper at this accuracy", choices={
            "order": (("higher order", "its order is higher", "8th order", "eighth order",
                       "order 8"), "An error of order 8 falls much faster with the "
                      "step size than one of order 5, so at tight tolerances DOP853 takes "
                      "far fewer steps, although each costs more evaluations."),
            "implicit": (("it is implicit", "implicit method"), "Both are explicit "
                         "Runge-Kutta methods."),
            "symplectic": (("it is symplectic", "structure preserving"), "Neither is "
                           "symplectic; the sledge is not even Hamiltonian."),
            "tolerance": (("smaller tolerance", "tighter tolerance", "rtol"), "Both were "
                          "run on the same tolerances; look at the error each achieves "
                          "for its cost."),
        }, answer_key="order"),
    ]
    return names, dom, parts


EXERCISES = {e.id: e for e in [
    Exercise("projectile-path", "The path of a projectile", "1.5, 1.12, 1.16, 1.27",
             _projectile_path),
    Exercise("kepler-orbit", "The Kepler orbit with the polar angle as time", "1.16, 1.27",
             _kepler_orbit),
    Exercise("omega-and-energy", "Omega and the energy integral for the rolling disk",
             "1.5, 1.6, 1.12, 1.13", _omega_and_energy),
    Exercise("identity-1-19", "The identity (1.19)", "1.14, 1.17, 1.19", _identity_1_19),
    Exercise("constraint-star", "The reduced constraint of the sledge", "1.22, 1.23, 1.26, 3.8",
             _constraint_star),
    Exercise("sledge-L-star", "The sledge's reduced Lagrangian", "3.5, 3.6, 3.7",
             _sledge_L_star),
    Exercise("sledge-reduced-equation", "The sledge's reduced equation and a misprint",
             "1.26, 3.9, 3.10", _sledge_reduced_equation),
    Exercise("nielsen-form", "The Nielsen form", "2.1, 2.4, 1.26", _nielsen_form),
    Exercise("chaplygin-sleigh", "The Chaplygin sleigh with an offset centre of mass",
             "1.16, 1.26", _chaplygin_sleigh),
    Exercise("turning-point", "Where x stops being a coordinate", "1.5, 1.12, 3.12, 3.15",
             _turning_point),
    Exercise("work-precision", "Error against cost for two integrators", "1.4, 3.15",
             _work_precision),
]}
