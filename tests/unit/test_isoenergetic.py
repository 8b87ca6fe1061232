"""whittaker_teach.isoenergetic: Whittaker's reduction in Hamiltonian form, K = -p_eps.

Each result of the room is compared with a derivation written here by hand in plain
SymPy (the Hamiltonian, the root of H = h, the constraint term), and with the paper where
it has a formula (the sledge's 3.10); the room's own checks are then run, and fed a wrong
K (the other branch) or a dropped constraint term, which they must report as failing."""
import random
from pathlib import Path

import pytest
import sympy as sp

import whittaker_teach as wt
from whittaker_teach.isoenergetic import IsoenergeticForm, isoenergetic
from tests.unit.test_import_graph import _cycles, _graph

ROOT = Path(__file__).resolve().parents[2]


def _same(a, b, sample, points=5):
    """a == b: exactly by ``simplify``, else at random points (``sample(rng)``) to 30
    digits, both values real (the points are chosen inside the energy surface)."""
    d = sp.simplify(a - b)
    if d == 0:
        return True
    rng = random.Random(1)
    for _ in range(points):
        pt = sample(rng)
        va, vb = a.evalf(40, subs=pt), b.evalf(40, subs=pt)
        if not (va.is_real and vb.is_real) or abs(va - vb) > 1e-30 * (1 + abs(va)):
            return False
    return True


def _ok(report, label):
    return [c.holds for c in report if c.label == label]


# ----- the projectile (holonomic) -------------------------------------------------
@pytest.fixture(scope="module")
def projectile():
    return IsoenergeticForm(wt.examples.projectile().reduce("x", +1))


def _projectile_symbols(iso):
    m, g0 = sp.symbols("m g_0", positive=True)
    y, py, px, h = iso.q[iso._nus[0]], iso.p[iso._nus[0]], iso.p[iso._eps], iso.h
    return m, g0, y, py, px, h


def test_projectile_hamiltonian_and_K_by_hand(projectile):
    m, g0, y, py, px, h = _projectile_symbols(projectile)
    H = (px**2 + py**2) / (2 * m) + m * g0 * y
    assert sp.simplify(projectile.hamiltonian - H) == 0
    roots = sp.solve(sp.Eq(H, h), px)
    # the root on which xdot = dH/dp_x = p_x/m > 0 (direction +1)
    (px_plus,) = [r for r in roots if sp.simplify(r.subs({y: 0, py: 0, h: 1, m: 1, g0: 1})) > 0]
    assert sp.simplify(projectile.K - (-px_plus)) == 0
    assert sp.simplify(projectile.K - sp.sqrt(2 * m * (h - m * g0 * y) - py**2) * -1) == 0


def test_projectile_legendre_and_whittaker_by_hand(projectile):
    m, g0, y, py, px, h = _projectile_symbols(projectile)
    W = sp.Symbol("W", positive=True)                      # h - m g_0 y > 0
    yp = projectile.qprime[projectile._nus[0]]
    L_star = sp.sqrt(2 * W) * sp.sqrt(m * (1 + yp**2))     # Jacobi's form, chapter 2
    P = L_star.diff(yp)
    on = {h: W + m * g0 * y}             # after every derivative: K depends on y via h - V
    K = projectile.K
    assert sp.simplify(K.subs(on).subs(py, P) - (P * yp - L_star)) == 0  # K = p y' - L*
    assert sp.simplify(K.diff(py).subs(on).subs(py, P) - yp) == 0        # dK/dp = y'
    # Hamilton's equations of K, by hand: y' = dK/dp_y, p_y' = -dK/dy; then y''
    x = projectile.independent
    ypp = (K.diff(py).diff(y) * K.diff(py) + K.diff(py).diff(py) * -K.diff(y)
           + K.diff(py).diff(x)).subs(on).subs(py, P)
    assert sp.simplify(ypp - (-m * g0 * (1 + yp**2) / (2 * W))) == 0     # chapter 2's y''
    core = projectile.plain(projectile.reduction.accelerations()[
        projectile.reduction.coordinates[0].diff(x, 2)]).subs(h, W + m * g0 * y)
    assert sp.simplify(ypp - core) == 0


def test_projectile_checks_hold_and_the_other_branch_fails(projectile):
    report = projectile.verify()
    assert report.ok, str(report)
    assert [c.label for c in report] == ["K", "K", "K=L*", "H=1.27"]
    wrong = projectile.verify(K=-projectile.K)             # the root with xdot < 0
    assert not wrong.ok
    # both roots solve H = h; only the sign of xdot = dH/dp_x tells the branches apart
    assert _ok(wrong, "K") == [True, False]
    assert _ok(wrong, "K=L*") == [False]


def test_projectile_the_backward_direction_is_the_other_root():
    back = IsoenergeticForm(wt.examples.projectile().reduce("x", -1))
    fwd = IsoenergeticForm(wt.examples.projectile().reduce("x", +1))
    assert sp.simplify(back.K + fwd.K) == 0
    assert back.verify().ok


# ----- the Kepler problem (holonomic) ----------------------------------------------
@pytest.fixture(scope="module")
def kepler():
    return IsoenergeticForm(wt.examples.kepler().reduce("theta", +1))


def test_kepler_K_is_minus_the_angular_momentum(kepler):
    m, mu = sp.symbols("m mu", positive=True)
    (nu,) = kepler._nus
    r, pr, pth, h = kepler.q[nu], kepler.p[nu], kepler.p[kepler._eps], kepler.h
    H = pr**2 / (2 * m) + pth**2 / (2 * m * r**2) - mu * m / r
    assert sp.simplify(kepler.hamiltonian - H) == 0
    K_hand = -r * sp.sqrt(2 * m * (h + mu * m / r) - pr**2)       # thetadot > 0: p_theta > 0

    def sample(rng):
        vals = {m: rng.uniform(0.5, 2), mu: rng.uniform(0.5, 2), r: rng.uniform(0.2, 1.2),
                pr: rng.uniform(-0.3, 0.3)}
        vals[h] = rng.uniform(0.1, 1.0)                   # h > 0 > V: inside the surface
        return vals
    assert _same(kepler.K, K_hand, sample)
    assert not _same(kepler.K, -K_hand, sample)


def test_kepler_conic_solves_hamiltons_equations_in_theta(kepler):
    """Along r = p/(1 + e cos theta), with p_r = m rdot = m r' thetadot and
    thetadot = sqrt(mu p)/r^2 (the law of areas), Hamilton's equations of K hold."""
    m, mu = sp.symbols("m mu", positive=True)
    p, e = sp.symbols("p e", positive=True)
    (nu,) = kepler._nus
    r, pr, h, th = kepler.q[nu], kepler.p[nu], kepler.h, kepler.independent
    conic = p / (1 + e * sp.cos(th))
    pr_conic = m * conic.diff(th) * sp.sqrt(mu * p) / conic**2
    on = {h: -mu * m * (1 - e**2) / (2 * p)}
    rate_r = kepler.rates[r].subs(on).subs({pr: pr_conic}).subs(r, conic)
    rate_p = kepler.rates[pr].subs(on).subs({pr: pr_conic}).subs(r, conic)

    def sample(rng):
        return {m: rng.uniform(0.5, 2), mu: rng.uniform(0.5, 2), p: rng.uniform(0.5, 2),
                e: rng.uniform(0.1, 0.8), th: rng.uniform(0.1, 3.0)}
    assert _same(rate_r, conic.diff(th), sample)
    assert _same(rate_p, pr_conic.diff(th), sample)
    assert kepler.verify().ok


# ----- the sledge (non-holonomic, Mei's section 3) ---------------------------------
@pytest.fixture(scope="module")
def sledge():
    return IsoenergeticForm(wt.examples.sledge().reduce("x", +1))


def _sledge_symbols(iso):
    m, J, k = sp.symbols("m J k", positive=True)
    (nu,) = iso._nus
    return m, J, k, iso.q[nu], iso.p[nu], iso.p[iso._eps], iso.h, iso.qprime[nu]


def _sledge_sample(m, J, k, th, pth, h):
    def sample(rng):
        vals = {m: rng.uniform(0.5, 2), J: rng.uniform(0.5, 2), k: rng.uniform(0.5, 2),
                th: rng.uniform(0.1, 1.2), pth: rng.uniform(-0.5, 0.5)}
        vals[h] = (vals[k]**2 * vals[th]**2 + vals[pth]**2 / vals[J]) / 2 + rng.uniform(0.2, 1)
        return vals
    return sample


def test_sledge_K_and_the_constraint_term_by_hand(sledge):
    m, J, k, th, pth, px, h, thp = _sledge_symbols(sledge)
    sec2 = 1 + sp.tan(th)**2
    H = px**2 / (2 * m * sec2) + pth**2 / (2 * J) + k**2 * th**2 / 2
    assert sp.simplify(sledge.hamiltonian - H) == 0
    K_hand = -sp.sqrt(2 * m * sec2 * (h - pth**2 / (2 * J) - k**2 * th**2 / 2))
    sample = _sledge_sample(m, J, k, th, pth, h)
    assert _same(sledge.K, K_hand, sample)
    # Mei's constraint term of (1.26) with ydot* = tan(theta) (3.8):
    # (dL/dydot)* [d/dx (dydot*/dtheta') - dydot*/dtheta] = m ydot (0 - sec^2 theta),
    # ydot = xdot tan(theta), xdot = p_x / (m sec^2 theta), p_x = -K
    Q_hand = m * (-K_hand / (m * sec2)) * sp.tan(th) * (0 - sec2)
    assert _same(sledge.constraint_term[0], Q_hand, sample)
    assert _same(sledge.constraint_term[0], K_hand * sp.tan(th), sample)


def test_sledge_hamiltons_equations_give_mei_3_10(sledge):
    """theta'' from dtheta/dx = dK/dp, dp/dx = -dK/dtheta + Q, at p = dL*/dtheta' with
    L* of (3.7), satisfies Mei's (3.10) (with the corrected k^2)."""
    m, J, k, th, pth, px, h, thp = _sledge_symbols(sledge)
    x = sledge.independent
    L_star = sp.sqrt(2 * h - k**2 * th**2) * sp.sqrt(m * (1 + sp.tan(th)**2) + J * thp**2)
    P = L_star.diff(thp)
    K, Q = sledge.K, sledge.constraint_term[0]
    f = K.diff(pth)
    R = 2 * h - k**2 * th**2

    def mei_310(q2):
        return (J * R * q2 + J * (-R * sp.tan(th) + k**2 * th) * thp**2
                + m * k**2 * th * (1 + sp.tan(th)**2))

    def hamilton_q2(Q):
        return (f.diff(th) * f + f.diff(pth) * (-K.diff(th) + Q) + f.diff(x)).subs(pth, P)

    def sample(rng):
        vals = {m: rng.uniform(0.5, 2), J: rng.uniform(0.5, 2), k: rng.uniform(0.5, 2),
                th: rng.uniform(0.1, 1.2), thp: rng.uniform(-1, 1)}
        vals[h] = vals[k]**2 * vals[th]**2 / 2 + rng.uniform(0.2, 1)
        return vals
    assert _same(mei_310(hamilton_q2(Q)), sp.S.Zero, sample)
    # without the constraint term, (3.10) fails: the term is needed
    assert not _same(mei_310(hamilton_q2(0)), sp.S.Zero, sample)


def test_sledge_checks_hold_and_fail_without_the_constraint_term(sledge):
    report = sledge.verify()
    assert report.ok, str(report)
    assert [c.label for c in report] == ["K", "K", "K=L*", "H=1.26"]
    dropped = sledge.verify(constraint_term=[0])
    assert _ok(dropped, "H=1.26") == [False]
    assert _ok(dropped, "K=L*") == [True]          # the Legendre transform does not see Q


# ----- the offset sleigh (non-holonomic, a cross term in P_y) ------------------------
@pytest.fixture(scope="module")
def sleigh():
    return IsoenergeticForm(wt.examples.offset_sleigh().reduce("x", +1))


def test_sleigh_hamiltonian_and_constraint_term_by_hand(sleigh):
    m, J, k, b = sp.symbols("m J k b", positive=True)
    (nu,) = sleigh._nus
    th, pth, px, h = sleigh.q[nu], sleigh.p[nu], sleigh.p[sleigh._eps], sleigh.h
    I = J + m * b**2
    H = px**2 * sp.cos(th)**2 / (2 * m) + pth**2 / (2 * I) + k**2 * th**2 / 2
    assert sp.simplify(sleigh.hamiltonian - H) == 0
    K_hand = -sp.sqrt(2 * m * (h - pth**2 / (2 * I) - k**2 * th**2 / 2)) / sp.cos(th)
    # P_y = dL/dydot = m ydot + m b thetadot cos(theta), ydot = xdot tan(theta);
    # the bracket of (1.26): -dydot*/dtheta = -sec^2 theta (ydot* = tan theta)
    xdot = -K_hand * sp.cos(th)**2 / m
    thdot = pth / I
    Q_hand = (m * xdot * sp.tan(th) + m * b * thdot * sp.cos(th)) * -(1 / sp.cos(th)**2)

    def sample(rng):
        vals = {s: rng.uniform(0.5, 2) for s in (m, J, k, b)}
        vals.update({th: rng.uniform(0.1, 1.2), pth: rng.uniform(-0.5, 0.5)})
        vals[h] = (vals[k]**2 * vals[th]**2 + vals[pth]**2 / (vals[J] + vals[m] * vals[b]**2)
                   ) / 2 + rng.uniform(0.2, 1)
        return vals
    assert _same(sleigh.K, K_hand, sample)
    assert _same(sleigh.constraint_term[0], Q_hand, sample)


def test_sleigh_checks_hold_and_fail_without_the_constraint_term(sleigh):
    assert sleigh.verify().ok
    assert _ok(sleigh.verify(constraint_term=[0]), "H=1.26") == [False]


# ----- what is refused ---------------------------------------------------------------
def test_a_nonlinear_constraint_is_refused_naming_why():
    with pytest.raises(wt.ModelError, match="not linear in the velocities"):
        IsoenergeticForm(wt.examples.cone_particle().reduce("x"))


def test_not_a_reduction_is_a_type_error():
    with pytest.raises(wt.ModelTypeError, match="expected a Reduction"):
        isoenergetic(wt.examples.projectile())


def test_energy_below_the_surface_and_a_turning_point(projectile):
    vals = {"y": 1, "p_y": 0, "m": 1, "g_0": 2}
    assert float(projectile.p_eps_at({**vals, "h": 4})) == pytest.approx(2.0, rel=1e-12)
    with pytest.raises(wt.ModelError, match="no real root p_x.*below"):
        projectile.p_eps_at({**vals, "h": 1})
    with pytest.raises(wt.ChartError, match="turning point"):
        projectile.p_eps_at({**vals, "h": 2})
    with pytest.raises(wt.ModelError, match="no value for h"):
        projectile.p_eps_at(vals)


def test_a_parameter_named_like_a_momentum_is_refused():
    from whittaker_teach.coordinates import dynamicsymbols
    t = dynamicsymbols._t
    x, y = dynamicsymbols("x y")
    m, c = sp.Symbol("m", positive=True), sp.Symbol("p_y", positive=True)
    S = wt.ChaplyginSystem(m / 2 * (x.diff(t)**2 + y.diff(t)**2) - c * y, [x, y])
    with pytest.raises(wt.ModelError, match="p_y"):
        IsoenergeticForm(S.reduce("x"))


# ----- the import graph ----------------------------------------------------------------
def _in(mod, package):
    return mod == package or mod.startswith(package + ".")


def test_nothing_outside_the_room_imports_it_and_it_imports_no_numerics():
    edges = _graph()
    assert "whittaker_teach.isoenergetic.form" in edges
    room = "whittaker_teach.isoenergetic"
    bad = {m: sorted(w for w in e if _in(w, room)) for m, e in edges.items() if not _in(m, room)}
    assert {m: e for m, e in bad.items() if e} == {}
    assert not any(_in(w, "whittaker_teach.numerics") or _in(w, "whittaker_teach.geometry")
                   for m, e in edges.items() if _in(m, room) for w in e)
    assert _cycles({m: {w for w in e if _in(w, room)} for m, e in edges.items()
                    if _in(m, room)}) == []


BLOCKED = r"""
import whittaker_teach as wt
from whittaker_teach.isoenergetic import isoenergetic
print(isoenergetic(wt.examples.projectile().reduce("x")).verify().ok)
"""


def test_the_room_runs_without_numpy(run_without_numerics):
    assert run_without_numerics(BLOCKED).strip() == "True"
