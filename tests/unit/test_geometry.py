"""whittaker_teach.geometry: connection and curvature, the non-holonomic bracket and its
Jacobiator, invariant densities, the momentum equation (chapter 13), on cases with
answers known by hand."""

import pytest
import sympy as sp
from sympy.physics.mechanics import dynamicsymbols

import whittaker_teach as wt
from whittaker_teach import geometry as geo
from whittaker_teach.geometry.momentum import horizontal_combinations
from whittaker_teach.stability import tilting_disk
from tests.unit.test_import_graph import _cycles, _graph

t = dynamicsymbols._t


def _zero(e):
    return sp.simplify(e) == 0


def _in(mod, package):
    return mod == package or mod.startswith(package + ".")


# ----- the import graph -------------------------------------------------------------
def test_the_core_never_imports_geometry_and_geometry_no_numerics():
    edges = _graph()
    assert "whittaker_teach.geometry.connection" in edges     # the graph sees the package
    bad = {m: sorted(w for w in e if _in(w, "whittaker_teach.geometry"))
           for m, e in edges.items() if not _in(m, "whittaker_teach.geometry")}
    assert {m: e for m, e in bad.items() if e} == {}
    geo_edges = {m: {w for w in e if _in(w, "whittaker_teach.geometry")}
                 for m, e in edges.items() if _in(m, "whittaker_teach.geometry")}
    assert _cycles(geo_edges) == []
    assert not any(_in(w, "whittaker_teach.numerics") for m, e in edges.items()
                   if _in(m, "whittaker_teach.geometry") for w in e)


BLOCKED = r"""
import whittaker_teach as wt
from whittaker_teach import geometry as geo
nb = geo.nonholonomic_bracket(wt.examples.sledge())
print(nb.structure.jacobiator(*nb.symbols("x", "p_x", "p_theta")))
"""


def test_geometry_runs_without_numpy(run_without_numerics):
    assert run_without_numerics(BLOCKED).split() == ["tan(theta)"]


# ----- connection and curvature ------------------------------------------------------
def test_sledge_connection_by_hand():
    s = wt.examples.sledge()
    A = geo.connection(s)
    x, th, y = s.coordinates
    X, TH, Y = A.chart.q[x], A.chart.q[th], A.chart.q[y]
    # A = dy - tan(theta) dx; horizontal lifts d/dx + tan(theta) d/dy and d/dtheta
    assert A.one_forms() == {y: {x: -sp.tan(TH), th: 0, y: 1}}
    assert A.horizontal_lift(x) == {x: 1, th: 0, y: sp.tan(TH)}
    assert A.annihilates().holds
    # dA = -sec^2 dtheta ^ dx = sec^2 dx ^ dtheta: (dA)(d/dx, d/dtheta) = sec^2(theta)
    dA = A.exterior_derivative(y)
    assert _zero(dA[0, 1] - sp.sec(TH)**2) and _zero(dA[0, 1] + dA[1, 0])
    B = A.curvature(y)
    assert B.shape == (2, 2) and _zero(B[0, 1] - 1 / sp.cos(TH)**2) and B[0, 0] == 0
    assert A.is_flat().holds is False
    # the Chaplygin term for x: P B_(x theta) thetadot = m xdot tan sec^2 thetadot
    term = A.chaplygin_term()
    m = sp.Symbol("m", positive=True)
    xd, thd = A.chart.v[x], A.chart.v[th]
    assert _zero(term[x] - m * xd * sp.tan(TH) / sp.cos(TH)**2 * thd)
    assert _zero(term[th] + m * xd * sp.tan(TH) / sp.cos(TH)**2 * xd)
    assert not (X in B.free_symbols or Y in B.free_symbols)


@pytest.mark.parametrize("build", [wt.examples.sledge, wt.examples.offset_sleigh,
                                   wt.examples.rolling_disk, tilting_disk],
                         ids=["sledge", "offset_sleigh", "rolling_disk", "tilting_disk"])
def test_curvature_term_is_the_right_side_of_1_4(build):
    assert geo.connection(build()).check_1_4().holds is True


def test_check_1_4_fails_on_a_wrong_curvature():
    A = geo.connection(wt.examples.sledge())
    good = A.curvature
    A.curvature = lambda d: 2 * good(d)      # a wrong curvature must be caught
    assert A.check_1_4().holds is False


def test_rolling_disk_curvature():
    d = wt.examples.rolling_disk()
    A = geo.connection(d)
    psi = A.chart.q[d.coordinates[2]]
    R = sp.Symbol("R", positive=True)
    form = A.curvature_form()
    assert {str(k) for k in form} == {"x", "y"}
    vals = {str(k): v for k, v in form.items()}
    assert _zero(vals["x"] - R * sp.sin(psi)) and _zero(vals["y"] + R * sp.cos(psi))


def _integrable():
    m, J, k = sp.symbols("m J k", positive=True)
    x, th, y = dynamicsymbols("x theta y")
    L = m / 2 * (x.diff(t)**2 + y.diff(t)**2) + J / 2 * th.diff(t)**2 - k**2 * th**2 / 2
    # ydot = x xdot + thetadot: y = x^2/2 + theta + const, a holonomic constraint
    return wt.ChaplyginSystem(L, [x, th, y], dependent={y.diff(t): x * x.diff(t) + th.diff(t)})


def test_holonomic_case_is_flat_and_poisson():
    s = _integrable()
    A = geo.connection(s)
    assert A.is_flat().holds is True
    assert A.check_1_4().holds is True
    nb = geo.nonholonomic_bracket(s)
    assert nb.C == sp.zeros(2, 2)
    assert nb.structure.check_jacobi().holds is True
    assert nb.structure.is_canonical().holds is True
    assert nb.check_equations().holds is True


# ----- the bracket -------------------------------------------------------------------
def test_sledge_bracket_and_jacobiator_by_hand():
    nb = geo.nonholonomic_bracket(wt.examples.sledge())
    x, th, px, pth = nb.coordinates
    b = nb.structure.bracket
    assert b(x, px) == 1 and b(th, pth) == 1 and b(x, pth) == 0 and b(x, th) == 0
    assert b(px, pth) == px * sp.tan(th) and b(pth, px) == -px * sp.tan(th)
    assert nb.structure.jacobiator(x, px, pth) == sp.tan(th)
    table = nb.structure.jacobi_table()
    nonzero = {k: v for k, v in table.items() if v != 0}
    assert nonzero == {(x, px, pth): sp.tan(th)}
    chk = nb.structure.check_jacobi()
    assert chk.holds is False
    assert nb.check_equations().holds is True
    m, J, k = sp.symbols("m J k", positive=True)
    H = px**2 * sp.cos(th)**2 / (2 * m) + pth**2 / (2 * J) + k**2 * th**2 / 2
    assert _zero(nb.hamiltonian - H)


def test_sledge_jacobiator_at_a_point():
    nb = geo.nonholonomic_bracket(wt.examples.sledge())
    x, th, px, pth = nb.coordinates
    val = nb.structure.jacobiator(x, px, pth).subs(th, sp.pi / 4)
    assert val == 1


def test_check_equations_catches_a_wrong_bracket():
    nb = geo.nonholonomic_bracket(wt.examples.sledge())
    x, th, px, pth = nb.coordinates
    S = nb.structure.matrix.copy()
    S[2, 3], S[3, 2] = 0, 0                 # the canonical bracket: the free motion of L~
    nb.structure = geo.AlmostPoisson(nb.coordinates, S)
    assert nb.check_equations().holds is False


def test_rolling_disk_bracket_is_poisson_although_curved():
    nb = geo.nonholonomic_bracket(wt.examples.rolling_disk())
    assert nb.C == sp.zeros(2, 2)
    assert nb.structure.check_jacobi().holds is True
    assert geo.connection(wt.examples.rolling_disk()).is_flat().holds is False


def test_offset_sleigh_jacobiator_not_zero():
    nb = geo.nonholonomic_bracket(wt.examples.offset_sleigh())
    assert nb.structure.check_jacobi().holds is False
    assert nb.check_equations().holds is True


def test_tilting_disk_bracket():
    nb = geo.nonholonomic_bracket(tilting_disk())
    psi, phi, th, ppsi, pphi, pth = nb.coordinates
    # {p_psi, p_theta} = (4/5) p_phi cos(phi) for the uniform disk
    assert _zero(nb.C[0, 2] - sp.Rational(4, 5) * pphi * sp.cos(phi))
    assert _zero(nb.structure.jacobiator(phi, ppsi, pth) - sp.Rational(4, 5) * sp.cos(phi))
    assert nb.check_equations().holds is True


# ----- Chaplygin's multiplier -----------------------------------------------------------
def test_sledge_multiplier_hamiltonises():
    nb = geo.nonholonomic_bracket(wt.examples.sledge())
    x, th = nb.q
    new, H_star = geo.rescaled(nb, sp.cos(th))
    assert new.is_canonical().holds is True
    assert new.check_jacobi().holds is True
    m, J, k = sp.symbols("m J k", positive=True)
    Px, Pth = new.coordinates[2:]
    assert _zero(H_star - (Px**2 / (2 * m) + Pth**2 / (2 * J * sp.cos(th)**2) + k**2 * th**2 / 2))
    # N = 1 is no multiplier: the bracket stays almost Poisson
    same, _ = geo.rescaled(nb, 1)
    assert same.check_jacobi().holds is False
    # the invariant density N^(eps - 1) = cos(theta) in (q, p); 1 is not one
    F = nb.vector_field()
    assert geo.invariant_density(F, nb.coordinates, sp.cos(th)).holds is True
    assert geo.invariant_density(F, nb.coordinates, 1).holds is False
    assert _zero(geo.divergence(F, nb.coordinates) - sp.tan(th) * nb.p[1] / J)


def test_multiplier_density_exponent_is_eps_minus_1_for_eps_3():
    # [13.8] beyond eps = 2: a bracket whose rescaling by an arbitrary N(q) is canonical
    # ({P, P}' = 0 in [13.7]) has C = (p_tau dN/dq_sigma - p_sigma dN/dq_tau)/N; with
    # H = H*(q, N p) its field has the invariant density N^(eps-1) and not N^(eps-2), N^eps
    q, p, P = sp.symbols("q_1:4"), sp.symbols("p_1:4"), sp.symbols("P_1:4")
    N, V = sp.Function("N")(*q), sp.Function("V")(*q)
    a = [sp.Function(f"a_{i}")(*q) for i in (1, 2, 3)]
    Pi = sp.zeros(6, 6)
    for i in range(3):
        Pi[i, 3 + i], Pi[3 + i, i] = 1, -1
        for j in range(3):
            Pi[3 + i, 3 + j] = (p[j] * N.diff(q[i]) - p[i] * N.diff(q[j])) / N
    br = geo.AlmostPoisson(list(q) + list(p), Pi)
    H_star = sum(ai * Pi_**2 for ai, Pi_ in zip(a, P)) / 2 + V
    at = {Pi_: N * pi for Pi_, pi in zip(P, p)}
    F = br.vector_field(H_star.xreplace(at))
    # F is N times Hamilton's equations of H* in (q, P = N p)
    Ndot = sum(N.diff(qi) * F[i] for i, qi in enumerate(q))
    for i in range(3):
        assert _zero(F[i] - N * H_star.diff(P[i]).xreplace(at))
        assert _zero(Ndot * p[i] + N * F[3 + i] + N * H_star.diff(q[i]).xreplace(at))
    div = {k: sp.simplify(geo.divergence([N**k * f for f in F], br.coordinates)) for k in (1, 2, 3)}
    assert div[2] == 0
    assert div[1] != 0 and div[3] != 0


def test_position_density_sledge_and_sleigh():
    s = geo.position_density(geo.nonholonomic_bracket(wt.examples.sledge()))
    th = sp.Symbol("theta", real=True)
    assert s.exists and s.one_form[sp.Symbol("x", real=True)] == 0
    assert _zero(s.one_form[th] + sp.tan(th))            # ln rho = ln cos theta
    o = geo.position_density(geo.nonholonomic_bracket(wt.examples.offset_sleigh()))
    assert o.is_one_form.holds is True and o.closed.holds is False and not o.exists


# ----- the momentum equation -----------------------------------------------------------
def test_momentum_equation_sledge_and_sleigh():
    s = wt.examples.sledge()
    x, th, y = s.coordinates
    me = geo.momentum_equation(s, [{x: 1}, {y: 1}], [sp.cos(th), sp.sin(th)])
    m = sp.Symbol("m", positive=True)
    assert _zero(me.momentum - m * x.diff(t) / sp.cos(th)) and _zero(me.rate)
    assert me.check.holds is True
    assert [n[0] for n in me.noether] == [False, False]
    assert _zero(me.noether[0][1] + m * sp.tan(th) * th.diff(t) * x.diff(t))
    o = wt.examples.offset_sleigh()
    x, th, y = o.coordinates
    me = geo.momentum_equation(o, [{x: 1}, {y: 1}], [sp.cos(th), sp.sin(th)])
    b = sp.Symbol("b", positive=True)
    assert _zero(me.rate - m * b * th.diff(t)**2) and me.check.holds is True
    basis = horizontal_combinations(s, [{"x": 1}, {"y": 1}])
    assert len(basis) == 1 and _zero(basis[0][0] * sp.tan(s.coordinates[1]) - basis[0][1])


def test_momentum_equation_rolling_disk():
    d = wt.examples.rolling_disk()
    x, y, psi, th = d.coordinates
    me = geo.momentum_equation(d, [{x: 1}, {y: 1}, {th: 1}])
    A, R, m = sp.symbols("A R m", positive=True)
    assert _zero(me.momentum - (A + m * R**2) * th.diff(t)) and me.rate == 0
    assert me.check.holds is True


# ----- bad input ----------------------------------------------------------------------
def test_bad_input_names_what_is_wrong():
    with pytest.raises(wt.ModelError, match="not linear in the velocities"):
        geo.connection(wt.examples.cone_particle())
    with pytest.raises(wt.ModelError, match="no constraint"):
        geo.connection(wt.examples.kepler())
    with pytest.raises(wt.ModelTypeError, match="expected a ChaplyginSystem"):
        geo.connection("sledge")
    q, p = sp.symbols("q p")
    with pytest.raises(wt.ModelError, match="not skew-symmetric"):
        geo.AlmostPoisson([q, p], sp.Matrix([[0, 1], [1, 0]]))
    with pytest.raises(wt.ModelError, match="2x2"):
        geo.AlmostPoisson([q, p], sp.Matrix([[0]]))
    nb = geo.nonholonomic_bracket(wt.examples.sledge())
    with pytest.raises(wt.ModelError, match="positions"):
        geo.rescaled(nb, nb.p[0])
    with pytest.raises(wt.ModelError, match="not a dependent coordinate"):
        geo.connection(wt.examples.sledge()).curvature("x")
    with pytest.raises(wt.ModelError, match="one component per variable"):
        geo.divergence([q], [q, p])
    s = wt.examples.sledge()
    x, th, y = s.coordinates
    with pytest.raises(wt.ModelError, match="not a symmetry of L"):
        geo.momentum_equation(s, [{x: -y, y: x, th: 1}])      # the spring breaks rotations
    with pytest.raises(wt.ModelError, match="does not lie in the distribution"):
        geo.momentum_equation(s, [{x: 1}, {y: 1}], [1, 0])
    with pytest.raises(wt.ModelError, match="not a coordinate"):
        geo.momentum_equation(s, [{"z": 1}])
    m, J, p_x = sp.symbols("m J p_x", positive=True)
    xx, tt, yy = dynamicsymbols("x theta y")
    clash = wt.ChaplyginSystem(m / 2 * (xx.diff(t)**2 + yy.diff(t)**2) + J / 2 * tt.diff(t)**2
                               - p_x * tt**2, [xx, tt, yy],
                               dependent={yy.diff(t): xx.diff(t) * sp.tan(tt)})
    with pytest.raises(wt.ModelError, match="name of a momentum"):
        geo.nonholonomic_bracket(clash)
    with pytest.raises(wt.ModelError, match="does not preserve the constraint"):
        geo.momentum_equation(s, [{x: -y, y: x}])   # turns (x, y) but not the runner
