"""Benchmarks that print figures (never timed tests).

``python -m whittaker_teach bench derivation --scale [--n 2..8]``: for the
families of :func:`family` with n coordinates (non-holonomic and holonomic),
the time to reduce (build the system, reduce, the equations (1.26) and q''
solved) and to verify (every step's check), against
sympy.physics.mechanics' LagrangesMethod forming and solving the same
system's equations (the constraints as non-holonomic constraints), and the
peak memory (tracemalloc) of each side.  Each figure comes from a fresh
process forked after the imports (a new interpreter each where there is no
``os.fork``); memory from a separate traced process (tracing slows the run).
Each time is the fastest of ``--repeat`` alternating runs of each side (the
slower runs of a shared machine measure its other load), and the growth per
added coordinate is fitted to them.

``python -m whittaker_teach bench derivation --scale --family chain --n 8,12,24``: a
family of :data:`PEER_FAMILIES`, built by the benchmark with sympy.physics.mechanics,
against both peers: LagrangesMethod (forming and ``rhs``) and KanesMethod
(``kanes_equations`` and ``rhs``), the three in turn in fresh processes, the median of
``--repeat`` rounds each.  The families: ``chain``, spring-coupled Chaplygin sleighs
(:func:`chain`, g = n // 3); ``rotors``, a train of sleighs with their mass centres off
the blades, each carrying a rotor (:func:`rotor_train`, g = n // 4); ``coins``, rolling
coins with off-centre masses, two rolling constraints each (:func:`coin_train`,
g = 2 (n // 4)); ``all``: the three in turn.

``python -m whittaker_teach bench derivation``: in fresh processes, the time
to build the sledge, derive every step of the paper and verify them all,
against the time sympy.physics.mechanics' LagrangesMethod takes to form and
solve the sledge's time-domain equations (with a Lagrange multiplier), and
the time of ``import whittaker_teach``.  Each figure is the median over
``--repeat`` fresh processes, and the compute-only times of the fastest run are
printed beside them.
"""

import json
import math
import os
import statistics
import subprocess
import sys

# Each script prints: total time, success, time after the imports (compute only).
OURS = """
import time; t0 = time.perf_counter()
import whittaker_teach as wt
from whittaker_teach.examples import section3
from whittaker_teach import system, reduction, nielsen, steps, verify, render
t1 = time.perf_counter()
red = wt.examples.sledge().reduce("x", +1)
ok = red.verify().ok and all(s.check is None or s.check.holds for s in section3(reduction=red))
print(time.perf_counter() - t0, ok, time.perf_counter() - t1)
"""

CORE = """
import time; t0 = time.perf_counter()
import whittaker_teach as wt
from whittaker_teach import system, reduction, nielsen, steps, verify, render, examples
t1 = time.perf_counter()
ok = wt.examples.sledge().reduce("x", +1).verify().ok
print(time.perf_counter() - t0, ok, time.perf_counter() - t1)
"""

PEER = """
import time; t0 = time.perf_counter()
import sympy as sp
from sympy.physics.mechanics import dynamicsymbols, LagrangesMethod
t1 = time.perf_counter()
t = dynamicsymbols._t
m, J, k = sp.symbols("m J k", positive=True)
x, th, y = dynamicsymbols("x theta y")
L = m/2*(x.diff(t)**2 + y.diff(t)**2) + J/2*th.diff(t)**2 - k**2*th**2/2
lm = LagrangesMethod(L, [x, th, y], nonhol_coneqs=[y.diff(t) - x.diff(t)*sp.tan(th)])
lm.form_lagranges_equations()
rhs = lm.rhs()
print(time.perf_counter() - t0, True, time.perf_counter() - t1)
"""

IMPORT = """
import time; t0 = time.perf_counter()
import whittaker_teach
print(time.perf_counter() - t0, True, 0)
"""


def _once(code):
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True).stdout.split()
    if out[1] != "True":
        raise RuntimeError("a verification failed during the benchmark")
    return float(out[0]), float(out[2])


def _interleaved(codes, repeat):
    """Median (total, compute-only) time of each code over ``repeat`` rounds, one run of
    each per round, so that a load on the machine falls on all of them alike; and the
    fastest compute-only time of each (the least disturbed run)."""
    times = [[] for _ in codes]
    for _ in range(repeat):
        for i, code in enumerate(codes):
            times[i].append(_once(code))
    return [(statistics.median(a for a, _ in t), statistics.median(b for _, b in t),
             min(b for _, b in t)) for t in times]


def _bytecode():
    """Compile the package's bytecode first, as ``pip install`` does (an editable
    install under PYTHONDONTWRITEBYTECODE=1 would otherwise compile every module
    in every fresh process: about 0.08 s); say what was done."""
    import compileall
    import io
    from contextlib import redirect_stdout
    root = os.path.dirname(os.path.abspath(__file__))
    with redirect_stdout(io.StringIO()):
        ok = compileall.compile_dir(root, quiet=2)
    return "bytecode compiled first, as pip install does" if ok else \
        "bytecode could not be written: every fresh process compiles the package"


def main(args):
    if getattr(args, "scale", False):
        return scale_main(args)
    n = args.repeat
    note = _bytecode()
    (ours, ours_c, ours_f), (core, core_c, core_f), (peer, peer_c, peer_f), (imp, _, _) = (
        _interleaved([OURS, CORE, PEER, IMPORT], n))
    print(f"fresh-process medians over {n} runs (Python {sys.version.split()[0]}; {note})")
    print(f"  whittaker_teach, the sledge: every step (1.1)-(2.4), (3.1)-(3.15) derived "
          f"and verified: {ours:6.3f} s")
    print(f"  whittaker_teach, the sledge: the general derivation (1.1)-(2.4) only, "
          f"verified: {core:6.3f} s")
    print(f"  sympy.physics.mechanics LagrangesMethod, the sledge's equations formed and "
          f"solved: {peer:6.3f} s")
    print(f"  ratio (ours / peer): {ours / peer:.2f} with section 3, {core / peer:.2f} without "
          "(target <= 1)")
    print("  compute only (after the imports), s: with section 3, without, peer; ratios "
          "(target <= 1.5)")
    for what, a, b, c in (("median of the runs", ours_c, core_c, peer_c),
                          ("fastest run", ours_f, core_f, peer_f)):
        print(f"    {what:<20} {a:6.3f}  {b:6.3f}  {c:6.3f}   {a / c:.2f} / {b / c:.2f}")
    print(f"  import whittaker_teach: {imp:.3f} s  (target < 0.5 s)")
    return 0


# ----------------------------------------------------------------- scale
def family(n, holonomic=False):
    """The scale family with n coordinates: ``(L, coordinates, dependent)``.

    Non-holonomic: g = (n - 1) // 2 dependent coordinates y_j and p = n - g
    independent q_i; holonomic: g = 0, p = n.  Kinetic energy with the mass
    matrix m_i + c cos^2 q_(i+1) on the diagonal (indices cyclic) and couplings
    (b/8) cos(q_i - q_(i+1)) between neighbours (positive definite for the
    sampled parameters), M/2 ydot_j^2 for each y_j; potential k/2 sum q_i^2;
    constraints ydot_j = sin(q_j) qdot_(j+1) + q_(j+1) qdot_j.

    >>> L, coords, dep = family(3)
    >>> [str(c) for c in coords], len(dep)
    (['q1(t)', 'q2(t)', 'y1(t)'], 1)
    """
    import sympy as sp
    from sympy.physics.mechanics import dynamicsymbols
    t = dynamicsymbols._t
    g = 0 if holonomic else (n - 1) // 2
    p = n - g
    q = [dynamicsymbols(f"q{i}") for i in range(1, p + 1)]
    ys = [dynamicsymbols(f"y{j}") for j in range(1, g + 1)]
    ms = [sp.Symbol(f"m{i}", positive=True) for i in range(1, p + 1)]
    c, b, k, M = sp.symbols("c b k M", positive=True)
    qd = [x.diff(t) for x in q]
    T = sp.S.Zero
    for i in range(p):
        T += (ms[i] + c * sp.cos(q[(i + 1) % p])**2) * qd[i]**2 / 2
        if i + 1 < p:
            T += b / 8 * sp.cos(q[i] - q[i + 1]) * qd[i] * qd[i + 1]
    T += sum((M / 2 * y.diff(t)**2 for y in ys), sp.S.Zero)
    V = k / 2 * sum(x**2 for x in q)
    dep = {ys[j].diff(t): sp.sin(q[j]) * qd[j + 1] + q[j + 1] * qd[j] for j in range(g)}
    return T - V, q + ys, dep


def _frame(q, kane):
    """What every vehicle family starts from: the generalized speeds u_q of the
    coordinates, ``speed`` (a velocity written in them for Kane, as it is otherwise), the
    inertial frame N and its fixed point O."""
    import sympy.physics.mechanics as me
    from sympy.physics.mechanics import dynamicsymbols
    t = dynamicsymbols._t
    u = {c_.diff(t): dynamicsymbols(f"u_{c_.func.__name__}") for c_ in q}
    speed = (lambda e: e.xreplace(u)) if kane else (lambda e: e)
    N = me.ReferenceFrame("N")
    O = me.Point("O")
    O.set_vel(N, 0)
    return u, speed, N, O


def chain(n, kane=False):
    """The chain of spring-coupled Chaplygin sleighs with n coordinates: s = n // 3 sleighs
    (x_i, theta_i, y_i: mass m, moment of inertia J about the contact point P_i, which
    has no velocity across the sleigh, P_i.vel(N).dot(B_i.y) = 0), g = s constraints;
    n - 3 s further coordinates z_j (particles of mass M on springs to theta_1).  Springs:
    k/2 theta_i^2, c/2 (theta_(i+1) - theta_i)^2 and kappa/2 (x_(i+1) - x_i)^2.  Built
    with sympy.physics.mechanics (frames, points, bodies).

    Returns a dict: ``L`` (``me.Lagrangian``), ``q`` (every coordinate), ``coneqs`` (the
    constraints, expressions = 0), ``dependent`` (the y_i); with ``kane``, the same
    bodies with their velocities in the speeds u = qdot, and ``kane`` = the keyword
    arguments of KanesMethod, ``bodies`` and ``loads`` (the springs' forces and
    torques, -dV/dq along each point's or frame's partial velocity).

    >>> F = chain(7)
    >>> [str(c) for c in F["q"]], len(F["coneqs"])
    (['x1(t)', 'theta1(t)', 'y1(t)', 'x2(t)', 'theta2(t)', 'y2(t)', 'z1(t)'], 2)
    """
    import sympy as sp
    import sympy.physics.mechanics as me
    from sympy.physics.mechanics import dynamicsymbols
    t = dynamicsymbols._t
    s, r = n // 3, n - 3 * (n // 3)
    m, J, k, c, kappa, M = sp.symbols("m J k c kappa M", positive=True)
    xs = [dynamicsymbols(f"x{i}") for i in range(1, s + 1)]
    ths = [dynamicsymbols(f"theta{i}") for i in range(1, s + 1)]
    ys = [dynamicsymbols(f"y{i}") for i in range(1, s + 1)]
    zs = [dynamicsymbols(f"z{j}") for j in range(1, r + 1)]
    q = [c_ for i in range(s) for c_ in (xs[i], ths[i], ys[i])] + zs
    u, speed, N, O = _frame(q, kane)
    V = sp.S.Zero
    bodies, coneqs, parts = [], [], []
    for i in range(s):
        B = N.orientnew(f"B{i + 1}", "Axis", (ths[i], N.z))
        B.set_ang_vel(N, speed(ths[i].diff(t)) * N.z)
        P = O.locatenew(f"P{i + 1}", xs[i] * N.x + ys[i] * N.y)
        P.set_vel(N, speed(xs[i].diff(t)) * N.x + speed(ys[i].diff(t)) * N.y)
        bodies.append(me.RigidBody(f"S{i + 1}", P, B, m, (me.inertia(B, 0, 0, J), P)))
        coneqs.append(P.vel(N).dot(B.y))
        parts += [(P, xs[i], N.x), (B, ths[i], N.z)]
        V += k / 2 * ths[i]**2
        if i + 1 < s:
            V += kappa / 2 * (xs[i + 1] - xs[i])**2 + c / 2 * (ths[i + 1] - ths[i])**2
    for j in range(r):
        Q = O.locatenew(f"Q{j + 1}", zs[j] * N.z)
        Q.set_vel(N, speed(zs[j].diff(t)) * N.z)
        bodies.append(me.Particle(f"R{j + 1}", Q, M))
        parts.append((Q, zs[j], N.z))
        V += k / 2 * zs[j]**2 + c / 2 * (zs[j] - ths[0])**2
    out = {"q": q, "coneqs": coneqs, "dependent": ys}
    if not kane:
        out["L"] = me.Lagrangian(N, *bodies) - V
        return out
    dep = set(ys)
    out["kane"] = dict(frame=N, q_ind=q, u_ind=[u[c_.diff(t)] for c_ in q if c_ not in dep],
                       u_dependent=[u[y.diff(t)] for y in ys],
                       kd_eqs=[u[c_.diff(t)] - c_.diff(t) for c_ in q],
                       velocity_constraints=coneqs)
    out["bodies"] = bodies
    out["loads"] = [(where, -V.diff(c_) * axis) for where, c_, axis in parts]
    return out


def rotor_train(n, kane=False):
    """A train of Chaplygin sleighs, each carrying a rotor, with n coordinates: s = n // 4
    cars (x_i, y_i, theta_i, psi_i).  Car i: its blade at P_i = (x_i, y_i) has no velocity
    across the car (P_i.vel(N).dot(B_i.y) = 0, y_i dependent); its mass centre C_i is a
    ahead of the blade (mass m, moment of inertia J about C_i); at C_i a rotor turns by
    psi_i relative to the car (mass m_r, moment of inertia I about its axle, the car's
    vertical).  Springs: k/2 theta_i^2, kappa/2 (x_(i+1) - x_i)^2 (the hitches) and
    c/2 (psi_(i+1) - psi_i)^2 (the rotors' shafts); the n - 4 s remaining coordinates z_j
    are particles of mass M on springs to theta_1, as in :func:`chain`.  Unlike the
    chain, (1.4) has velocity terms from the offset a, and each car's mass matrix couples
    theta_i and psi_i.

    Returns the dict of :func:`chain`; with ``kane``, the rotors' spring torques act on
    the rotor and, reversed, on its car (the generalized force -dV/dpsi_i on psi_i
    only).

    >>> F = rotor_train(9)
    >>> [str(c) for c in F["q"][:4]], [str(y) for y in F["dependent"]], str(F["q"][-1])
    (['x1(t)', 'y1(t)', 'theta1(t)', 'psi1(t)'], ['y1(t)', 'y2(t)'], 'z1(t)')
    """
    import sympy as sp
    import sympy.physics.mechanics as me
    from sympy.physics.mechanics import dynamicsymbols
    t = dynamicsymbols._t
    s, r = n // 4, n - 4 * (n // 4)
    m, J, a, m_r, I, k, c, kappa, M = sp.symbols("m J a m_r I k c kappa M", positive=True)
    xs, ys, ths, psis = ([dynamicsymbols(f"{v}{i}") for i in range(1, s + 1)]
                         for v in ("x", "y", "theta", "psi"))
    zs = [dynamicsymbols(f"z{j}") for j in range(1, r + 1)]
    q = [c_ for i in range(s) for c_ in (xs[i], ys[i], ths[i], psis[i])] + zs
    u, speed, N, O = _frame(q, kane)
    V = sp.S.Zero
    bodies, coneqs, loads = [], [], []
    for i in range(s):
        B = N.orientnew(f"B{i + 1}", "Axis", (ths[i], N.z))
        B.set_ang_vel(N, speed(ths[i].diff(t)) * N.z)
        R = B.orientnew(f"R{i + 1}", "Axis", (psis[i], B.z))
        R.set_ang_vel(B, speed(psis[i].diff(t)) * B.z)
        P = O.locatenew(f"P{i + 1}", xs[i] * N.x + ys[i] * N.y)
        P.set_vel(N, speed(xs[i].diff(t)) * N.x + speed(ys[i].diff(t)) * N.y)
        C = P.locatenew(f"C{i + 1}", a * B.x)
        C.v2pt_theory(P, N, B)
        bodies += [me.RigidBody(f"car{i + 1}", C, B, m, (me.inertia(B, 0, 0, J), C)),
                   me.RigidBody(f"rotor{i + 1}", C, R, m_r, (me.inertia(R, 0, 0, I), C))]
        coneqs.append(P.vel(N).dot(B.y))
        V += k / 2 * ths[i]**2
        if i + 1 < s:
            V += kappa / 2 * (xs[i + 1] - xs[i])**2 + c / 2 * (psis[i + 1] - psis[i])**2
        loads += [(P, xs[i], N.x, None), (B, ths[i], N.z, None), (R, psis[i], N.z, B)]
    V += _extra_particles(me, N, O, zs, M, k, c, ths[0], speed, bodies, loads)
    return _finish(me, N, q, coneqs, ys, bodies, V, loads, u, kane)


def coin_train(n, kane=False):
    """A row of vertical rolling coins, each with an off-centre mass, with n coordinates:
    s = n // 4 coins (x_i, y_i, theta_i, phi_i): the centre C_i = (x_i, y_i) of coin i
    (radius R, mass m, moments of inertia I_a about its axle and I_d about a diameter),
    its heading theta_i and its rolling angle phi_i; the coin rolls without slipping,
    C_i.vel(N) = R phi_i' A_i.x (two constraints, x_i and y_i dependent); a point mass
    m_e at distance e from C_i in the coin, under gravity g.  Springs: k/2 theta_i^2,
    c/2 (theta_(i+1) - theta_i)^2, kappa/2 (phi_(i+1) - phi_i)^2; the n - 4 s remaining
    coordinates z_j as in :func:`chain`.  Unlike the sleighs, two constraints per body,
    of the rolling kind, and a mass matrix that couples theta_i and phi_i through the
    off-centre mass.

    Returns the dict of :func:`chain` (``dependent`` the x_i and y_i); with ``kane``,
    gravity is a force on each off-centre mass.

    >>> F = coin_train(4)
    >>> [str(c) for c in F["q"]], len(F["coneqs"])
    (['x1(t)', 'y1(t)', 'theta1(t)', 'phi1(t)'], 2)
    """
    import sympy as sp
    import sympy.physics.mechanics as me
    from sympy.physics.mechanics import dynamicsymbols
    t = dynamicsymbols._t
    s, r = n // 4, n - 4 * (n // 4)
    m, R_, I_a, I_d, m_e, e, g, k, c, kappa, M = sp.symbols(
        "m R I_a I_d m_e e g k c kappa M", positive=True)
    xs, ys, ths, phis = ([dynamicsymbols(f"{v}{i}") for i in range(1, s + 1)]
                         for v in ("x", "y", "theta", "phi"))
    zs = [dynamicsymbols(f"z{j}") for j in range(1, r + 1)]
    q = [c_ for i in range(s) for c_ in (xs[i], ys[i], ths[i], phis[i])] + zs
    u, speed, N, O = _frame(q, kane)
    V, V_gravity = sp.S.Zero, sp.S.Zero
    bodies, coneqs, loads, forces = [], [], [], []
    for i in range(s):
        A = N.orientnew(f"A{i + 1}", "Axis", (ths[i], N.z))
        A.set_ang_vel(N, speed(ths[i].diff(t)) * N.z)
        D = A.orientnew(f"D{i + 1}", "Axis", (phis[i], A.y))
        D.set_ang_vel(A, speed(phis[i].diff(t)) * A.y)
        C = O.locatenew(f"C{i + 1}", xs[i] * N.x + ys[i] * N.y + R_ * N.z)
        C.set_vel(N, speed(xs[i].diff(t)) * N.x + speed(ys[i].diff(t)) * N.y)
        E = C.locatenew(f"E{i + 1}", e * D.x)
        E.v2pt_theory(C, N, D)
        coin = me.RigidBody(f"coin{i + 1}", C, D, m, (me.inertia(A, I_d, I_a, I_d), C))
        bodies += [coin, me.Particle(f"mass{i + 1}", E, m_e)]
        slip = C.vel(N) - R_ * speed(phis[i].diff(t)) * A.x
        coneqs += [slip.dot(N.x), slip.dot(N.y)]
        V += k / 2 * ths[i]**2
        V_gravity += m_e * g * E.pos_from(O).dot(N.z)
        forces.append((E, -m_e * g * N.z))
        if i + 1 < s:
            V += c / 2 * (ths[i + 1] - ths[i])**2 + kappa / 2 * (phis[i + 1] - phis[i])**2
        loads += [(A, ths[i], N.z, None), (D, phis[i], A.y, None)]
    V += _extra_particles(me, N, O, zs, M, k, c, ths[0], speed, bodies, loads)
    return _finish(me, N, q, coneqs, [v for i in range(s) for v in (xs[i], ys[i])], bodies,
                   V, loads, u, kane, forces, V_gravity)


def _extra_particles(me, N, O, zs, M, k, c, ref, speed, bodies, loads):
    """The coordinates z_j left over: particles of mass M on springs k/2 z_j^2 and
    c/2 (z_j - ref)^2 (bodies and loads appended to); their potential."""
    import sympy as sp
    t = me.dynamicsymbols._t
    V = sp.S.Zero
    for j, z in enumerate(zs):
        Q = O.locatenew(f"Q{j + 1}", z * N.z)
        Q.set_vel(N, speed(z.diff(t)) * N.z)
        bodies.append(me.Particle(f"Z{j + 1}", Q, M))
        loads.append((Q, z, N.z, None))
        V += k / 2 * z**2 + c / 2 * (z - ref)**2
    return V


def _finish(me, N, q, coneqs, dependent, bodies, V, loads, u, kane, forces=(), V_forces=0):
    """The family's dict (:func:`chain`'s): L = me.Lagrangian - V - V_forces, or with
    ``kane`` KanesMethod's arguments, the bodies and the loads: the springs' (V's), -dV/dq_r
    along ``axis`` at each (point or frame, q_r, axis, reaction frame or None) -- a point's
    or frame's velocity in q_r' is q_r' axis, so the load's generalized force is -dV/dq_r
    on q_r; a reaction frame takes the opposite torque (a spring between two bodies) --
    then ``forces`` (gravity, whose potential is V_forces)."""
    t = me.dynamicsymbols._t
    out = {"q": q, "coneqs": coneqs, "dependent": dependent}
    if not kane:
        out["L"] = me.Lagrangian(N, *bodies) - V - V_forces
        return out
    dep = set(dependent)
    out["kane"] = dict(frame=N, q_ind=q, u_ind=[u[c_.diff(t)] for c_ in q if c_ not in dep],
                       u_dependent=[u[y.diff(t)] for y in dependent],
                       kd_eqs=[u[c_.diff(t)] - c_.diff(t) for c_ in q],
                       velocity_constraints=coneqs)
    out["bodies"] = bodies
    out["loads"] = [(where, -V.diff(c_) * axis) for where, c_, axis, _ in loads]
    out["loads"] += [(back, V.diff(c_) * axis) for _, c_, axis, back in loads if back]
    out["loads"] += list(forces)
    return out


#: the families compared with both peers (``--family``): name -> (builder, title)
PEER_FAMILIES = {
    "chain": (chain, "chain of spring-coupled Chaplygin sleighs (g = n // 3)"),
    "rotors": (rotor_train, "train of sleighs with rotors, mass centres off the blades "
               "(g = n // 4)"),
    "coins": (coin_train, "row of rolling coins with off-centre masses (g = 2 (n // 4))"),
}


def run_ours_family(n, family):
    """{"reduce": s, "verify": s, "ok": bool}: the family (:data:`PEER_FAMILIES`) as a
    mechanics user gives it (``me.Lagrangian``, the constraints = 0 solved for the
    dependent velocities), reduced with q_eps = its first independent coordinate (CPU
    time of the process)."""
    import time
    import whittaker_teach as wt
    F = PEER_FAMILIES[family][0](n)
    t0 = time.process_time()
    sys_ = wt.ChaplyginSystem(F["L"], F["q"], nonhol_coneqs=F["coneqs"],
                              dependent=F["dependent"])
    red = sys_.reduce(sys_.independent_coordinates[0], +1)
    red.equations
    red.accelerations()
    t1 = time.process_time()
    ok = red.verify().ok
    t2 = time.process_time()
    return {"reduce": t1 - t0, "verify": t2 - t1, "ok": ok}


def run_lagrange_family(n, family):
    """{"peer": s}: LagrangesMethod forming and solving (rhs) the family's equations."""
    import time
    from sympy.physics.mechanics import LagrangesMethod
    F = PEER_FAMILIES[family][0](n)
    t0 = time.process_time()
    lm = LagrangesMethod(F["L"], F["q"], nonhol_coneqs=F["coneqs"])
    lm.form_lagranges_equations()
    lm.rhs()
    return {"peer": time.process_time() - t0, "ok": True}


def run_kane_family(n, family):
    """{"peer": s}: KanesMethod (kanes_equations + rhs) of the family: the same bodies,
    the springs and gravity as loads, speeds u = qdot, the dependent coordinates' speeds
    dependent."""
    import time
    from sympy.physics.mechanics import KanesMethod
    F = PEER_FAMILIES[family][0](n, kane=True)
    t0 = time.process_time()
    km = KanesMethod(**F["kane"])
    km.kanes_equations(F["bodies"], F["loads"])
    km.rhs()
    return {"peer": time.process_time() - t0, "ok": True}


def run_ours_chain(n, holonomic=None):
    """:func:`run_ours_family` of the chain (``holonomic`` is unused: the measurer's
    signature)."""
    return run_ours_family(n, "chain")


def run_lagrange_chain(n, holonomic=None):
    """:func:`run_lagrange_family` of the chain."""
    return run_lagrange_family(n, "chain")


def run_kane_chain(n, holonomic=None):
    """:func:`run_kane_family` of the chain."""
    return run_kane_family(n, "chain")


def run_ours(n, holonomic):
    """{"reduce": s, "verify": s, "ok": bool} for the family, in this process (CPU time
    of the process: a load on the machine does not count)."""
    import time
    import whittaker_teach as wt
    L, coords, dep = family(n, holonomic)
    t0 = time.process_time()
    red = wt.ChaplyginSystem(L, coords, dependent=dep).reduce(coords[0], +1)
    red.equations
    red.accelerations()
    t1 = time.process_time()
    ok = red.verify().ok
    t2 = time.process_time()
    return {"reduce": t1 - t0, "verify": t2 - t1, "ok": ok}


def run_peer(n, holonomic):
    """{"peer": s} for LagrangesMethod forming and solving the family's equations."""
    import time
    from sympy.physics.mechanics import LagrangesMethod
    L, coords, dep = family(n, holonomic)
    t0 = time.process_time()
    lm = LagrangesMethod(L, coords, nonhol_coneqs=[k - v for k, v in dep.items()] or None)
    lm.form_lagranges_equations()
    lm.rhs()
    return {"peer": time.process_time() - t0, "ok": True}


def _measured(fn, n, holonomic, traced=False, family=None):
    """``bench.<fn>(n, holonomic)`` in this process, or ``bench.<fn>(n, family)`` for a
    family of :data:`PEER_FAMILIES`; with ``traced``, its peak memory (MiB, tracemalloc
    started here, after the imports) instead of its times."""
    import tracemalloc
    if traced:
        tracemalloc.start()
    out = globals()[fn](n, family) if family else globals()[fn](n, holonomic)
    if traced:
        out = {"peak": tracemalloc.get_traced_memory()[1] / 2**20, "ok": out["ok"]}
        tracemalloc.stop()
    return out


_IMPORTS = """
import gc, json, os, sys
import sympy, sympy.physics.mechanics, mpmath
from whittaker_teach import bench, system, reduction, nielsen, steps, verify
"""

# One process imports everything once; each measurement runs in a process forked
# from it (as fresh as a new process after the imports, without paying the imports
# again: 18 fresh processes spent about 25 s of the 30 s of `--n 2..4` importing).
_SERVER = _IMPORTS + """
gc.collect()
gc.freeze()
for line in sys.stdin:
    r, w = os.pipe()
    pid = os.fork()
    if pid == 0:
        os.close(r)
        try:
            out = bench._measured(**json.loads(line))
        except BaseException as exc:
            out = {"error": f"{type(exc).__name__}: {exc}"}
        with os.fdopen(w, "w") as f:
            f.write(json.dumps(out))
        os._exit(0)
    os.close(w)
    with os.fdopen(r) as f:
        text = f.read()
    os.waitpid(pid, 0)
    print(text or json.dumps({"error": "the measuring process died"}), flush=True)
"""

# A new interpreter for each measurement (where there is no os.fork).
_CHILD = _IMPORTS + """
print(json.dumps(bench._measured({fn!r}, {n}, {hol}, {traced}, {family!r})))
"""


class _Measurer:
    """Runs ``bench.<fn>(n, holonomic)`` in a fresh process after the imports: forked
    from one server process where ``os.fork`` exists, else a new interpreter each."""

    def __init__(self):
        self.server = None
        if hasattr(os, "fork"):
            self.server = subprocess.Popen([sys.executable, "-c", _SERVER], text=True,
                                           stdin=subprocess.PIPE, stdout=subprocess.PIPE)

    def __call__(self, fn, n, holonomic, traced=False, family=None):
        if self.server is None:
            code = _CHILD.format(fn=fn, n=n, hol=holonomic, traced=traced, family=family)
            out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                                 check=True).stdout.strip().splitlines()[-1]
            return json.loads(out)
        job = {"fn": fn, "n": n, "holonomic": holonomic, "traced": traced,  # _measured's
               "family": family}
        self.server.stdin.write(json.dumps(job) + "\n")
        self.server.stdin.flush()
        line = self.server.stdout.readline()
        out = json.loads(line) if line else {"error": "the benchmark's server process died"}
        if "error" in out:
            what = f"family={family!r}" if family else f"holonomic={holonomic}"
            raise RuntimeError(f"bench {fn}(n={n}, {what}): {out['error']}")
        return out

    def close(self):
        if self.server is not None:
            self.server.stdin.close()
            self.server.wait()
            self.server = None


def chain_rows(ns, repeat=1, family="chain"):
    """One dict per n of a family of :data:`PEER_FAMILIES` (the chain by default): ours
    (reduce, verify), LagrangesMethod (``peer``) and KanesMethod (``kane``), each the
    median of ``repeat`` runs, the three in turn in each round (interleaved: a load on
    the machine falls on all of them alike), each in a fresh process; the ratios of the
    medians to each peer, and ``kane_ratios``, ours / Kane of each round."""
    rows = []
    measure = _Measurer()
    try:
        for n in ns:
            runs = [(measure("run_ours_family", n, None, family=family),
                     measure("run_lagrange_family", n, None, family=family),
                     measure("run_kane_family", n, None, family=family))
                    for _ in range(repeat)]
            med = statistics.median
            row = {"n": n, "family": family,
                   "reduce": med(o["reduce"] for o, _, _ in runs),
                   "verify": med(o["verify"] for o, _, _ in runs),
                   "ours": med(o["reduce"] + o["verify"] for o, _, _ in runs),
                   "ok": all(o["ok"] for o, _, _ in runs),
                   "peer": med(p["peer"] for _, p, _ in runs),
                   "kane": med(k["peer"] for _, _, k in runs),
                   "kane_ratios": [(o["reduce"] + o["verify"]) / k["peer"] for o, _, k in runs]}
            row["ratio"] = row["ours"] / row["peer"]
            row["kane_ratio"] = row["ours"] / row["kane"]
            rows.append(row)
    finally:
        measure.close()
    return rows


def chain_table(rows, title=None):
    """The rows of :func:`chain_rows` as a text table (at most 100 columns): the medians,
    and the range of ours / Kane over the rounds; the title is the family's unless given."""
    title = title or PEER_FAMILIES[rows[0].get("family", "chain") if rows else "chain"][1]
    lines = [f"{title}\n{'n':>3} {'reduce s':>9} {'verify s':>9} {'ours s':>8} "
             f"{'Lagrange s':>10} {'Kane s':>8} {'/Lagrange':>9} {'/Kane':>6} "
             f"{'rounds /Kane':>12}  checks"]
    for r in rows:
        each = r.get("kane_ratios") or [r["kane_ratio"]]
        lines.append(f"{r['n']:>3} {r['reduce']:9.3f} {r['verify']:9.3f} {r['ours']:8.3f} "
                     f"{r['peer']:10.3f} {r['kane']:8.3f} {r['ratio']:9.2f} "
                     f"{r['kane_ratio']:6.2f} {f'{min(each):.2f}-{max(each):.2f}':>12}  "
                     f"{'held' if r['ok'] else 'FAILED'}")
    return "\n".join(lines)


def scale_rows(ns, holonomic, memory=True, repeat=1):
    """One dict per n: times (s, the fastest of ``repeat`` runs of each side, alternating:
    on a shared machine the slower runs measure the other load, not the code), ratio
    (reduce + verify) / peer, peak memory (MiB)."""
    rows = []
    measure = _Measurer()
    try:
        for n in ns:
            runs = [(measure("run_ours", n, holonomic), measure("run_peer", n, holonomic))
                    for _ in range(repeat)]
            fastest = min((o for o, _ in runs), key=lambda o: o["reduce"] + o["verify"])
            ours = {k: fastest[k] for k in ("reduce", "verify")}
            ours["ok"] = all(o["ok"] for o, _ in runs)
            peer = {"peer": min(p["peer"] for _, p in runs)}
            row = {"n": n, **ours, **peer}
            row["ratio"] = (row["reduce"] + row["verify"]) / row["peer"]
            if memory:
                row["mem"] = measure("run_ours", n, holonomic, True)["peak"]
                row["peer_mem"] = measure("run_peer", n, holonomic, True)["peak"]
            rows.append(row)
    finally:
        measure.close()
    return rows


def scale_table(rows, title):
    """The rows as a text table (at most 100 columns)."""
    head = (f"{title}\n{'n':>3} {'reduce s':>9} {'verify s':>9} {'peer s':>8} {'ratio':>6} "
            f"{'verify/reduce':>13} {'peak MiB':>9} {'peer MiB':>9}  checks")
    lines = [head]
    for r in rows:
        mem = f"{r['mem']:9.1f} {r['peer_mem']:9.1f}" if "mem" in r else f"{'-':>9} {'-':>9}"
        lines.append(f"{r['n']:>3} {r['reduce']:9.2f} {r['verify']:9.2f} {r['peer']:8.2f} "
                     f"{r['ratio']:6.1f} {r['verify'] / r['reduce']:13.2f} {mem}  "
                     f"{'held' if r['ok'] else 'FAILED'}")
    return "\n".join(lines)


def growth(rows, key):
    """Growth per added coordinate: exp of the least-squares slope of log(time) on n,
    ``key`` a function of a row."""
    ns = [r["n"] for r in rows]
    if len(ns) < 2:
        return float("nan")
    ys = [math.log(key(r)) for r in rows]
    mn, my = sum(ns) / len(ns), sum(ys) / len(ys)
    slope = (sum((n - mn) * (y - my) for n, y in zip(ns, ys))
             / sum((n - mn) ** 2 for n in ns))
    return math.exp(slope)


def scale_main(args):
    if "," in args.n:                   # a list: --n 8,12,24
        ns = [int(v) for v in args.n.split(",")]
    else:
        lo, _, hi = args.n.partition("..")
        ns = range(int(lo), int(hi or lo) + 1)
    repeat = max(1, getattr(args, "repeat", 1))
    print("CPU seconds. reduce: build, reduce, (1.26) and q'' solved; verify: every check;")
    ok = True
    family = getattr(args, "family", "both")
    if family in PEER_FAMILIES or family == "all":
        names = list(PEER_FAMILIES) if family == "all" else [family]
        print("ours = reduce + verify; beside KanesMethod (kanes_equations + rhs) and\n"
              "LagrangesMethod (forming + rhs); /Lagrange, /Kane: ours over each; the medians\n"
              f"of {repeat} rounds (each round: ours, Lagrange, Kane in turn, each in a fresh\n"
              "process forked after the imports); no memory columns", flush=True)
        for name in names:
            rows = chain_rows(ns, repeat=repeat, family=name)
            print(chain_table(rows), flush=True)
            if len(rows) > 1:
                print(f"growth per added coordinate (least squares on log time): ours "
                      f"x{growth(rows, lambda r: r['ours']):.3f}, Lagrange "
                      f"x{growth(rows, lambda r: r['peer']):.3f}, Kane "
                      f"x{growth(rows, lambda r: r['kane']):.3f}", flush=True)
            ok = ok and all(r["ok"] for r in rows)
        return 0 if ok else 1
    print("peer: LagrangesMethod forming and solving; ratio = (reduce + verify) / peer;\n"
          f"the fastest of {repeat} alternating runs of each side, each in a fresh process\n"
          "(forked after the imports);\n"
          "peak memory (MiB, after the imports) by tracemalloc")
    kinds = {"both": (False, True), "nonholonomic": (False,), "holonomic": (True,)}
    for holonomic in kinds[family]:
        rows = scale_rows(ns, holonomic, memory=not args.no_memory, repeat=repeat)
        title = ("holonomic family" if holonomic else
                 "non-holonomic family (g = (n - 1) // 2 constraints)")
        print(scale_table(rows, title), flush=True)
        if len(rows) > 1:
            print(f"growth per added coordinate (least squares on log time): ours "
                  f"x{growth(rows, lambda r: r['reduce'] + r['verify']):.2f}, peer "
                  f"x{growth(rows, lambda r: r['peer']):.2f}", flush=True)
        ok = ok and all(r["ok"] for r in rows)
    return 0 if ok else 1
