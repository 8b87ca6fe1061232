"""whittaker_teach.rolling: the rolling disk, the Chaplygin ball and the rattleback
(symbolic parts; the simulations are in tests/integration/test_rolling_simulate.py)."""

import subprocess
import sys
import textwrap

import pytest
import sympy as sp

from whittaker_teach import rolling
from whittaker_teach import stability as st
from whittaker_teach.rolling.rattleback_model import RattlebackVectors, spin_rates

TOY = dict(m=1.0, g=9.81, h=0.01, rho_1=0.5, rho_2=0.02, A=1.6e-4, B=2.08e-3, C=2.08e-3,
           delta=0.05)
LAM = sp.Symbol("lambda")
OMEGA = sp.Symbol("Omega", real=True)


@pytest.fixture(scope="module")
def quartic():
    rv = RattlebackVectors(products=True)
    return rv, rv.charpoly(lam=LAM).all_coeffs()


@pytest.fixture(scope="module")
def linear():
    rv = RattlebackVectors()
    return rv, rv.linearization()


def test_disk_is_the_stability_rooms():
    assert rolling.tilting_disk is st.tilting_disk


def test_rattleback_odd_coefficients(quartic):
    """a3 = -m h (rho_1 - rho_2) I_12 Omega / det and a1 = Omega^2 a3: the odd terms carry
    the misalignment (I_12) times the difference of the curvatures."""
    rv, a = quartic
    m, g, h, r1, r2 = rv.parameters[:5]
    I11, I12, I22 = rv.products
    det = sp.Matrix([[I11 + m * h**2, I12], [I12, I22 + m * h**2]]).det()
    assert a[0] == 1 and a[-1] == 0
    assert sp.cancel(a[1] * det + m * h * (r1 - r2) * I12 * OMEGA) == 0
    assert sp.cancel(a[3] - OMEGA**2 * a[1]) == 0
    assert a[1].subs(I12, 0) == 0


def test_odd_coefficient_in_the_moments_and_the_misalignment(quartic):
    """The horizontal block of I + m h^2 has det (A + m h^2)(B + m h^2), so
    a3 = -m h (rho_1 - rho_2) Omega sin(delta) cos(delta) (1/(B + m h^2) - 1/(A + m h^2))."""
    rv, a = quartic
    m, g, h, r1, r2, A, B, C, delta = rv.parameters
    a3 = a[1].xreplace(rv.products)
    form = (-m * h * (r1 - r2) * OMEGA * sp.sin(delta) * sp.cos(delta)
            * (1 / (B + m * h**2) - 1 / (A + m * h**2)))
    S, Cs = sp.symbols("S Cs")                         # sin(delta), cos(delta)

    def on_circle(e):                                  # numerator mod S^2 + Cs^2 - 1
        e = e.xreplace({sp.sin(delta): S, sp.cos(delta): Cs})
        return sp.expand(sp.rem(sp.expand(sp.numer(sp.together(e))), S**2 + Cs**2 - 1, S))

    assert on_circle(a3 - form) == 0
    assert on_circle(a3 - form.subs(r2, 2 * r2)) != 0  # the identity is not vacuous


def _worst(A, spin, vals):
    return max(z.real for z in spin_rates(A, spin, vals) if abs(z) > 1e-12)


def test_good_direction_stable_only_at_fast_spin(linear):
    """The toy: Omega > 0 is (spectrally) stable above about 38.8 rad/s, unstable below;
    Omega < 0 stays unstable."""
    rv, A = linear
    vals = rv.values(TOY)
    assert _worst(A, 38.5, vals) > 0
    assert _worst(A, 39.0, vals) < 0
    assert _worst(A, 60, vals) < 0
    assert _worst(A, -60, vals) > 1


def test_rattleback_at_rest_rocks_with_the_textbook_frequencies(quartic):
    """Known answer: without misalignment and spin, the body rocks about each axis like a
    rounded rocker, omega_i^2 = m g (rho_i - h) / (I_G + m h^2) (rho_1 about y, rho_2 about x)."""
    rv, a = quartic
    m, g, h, r1, r2 = rv.parameters[:5]
    I11, I12, I22 = rv.products
    p = sp.Poly(a, LAM).as_expr().subs({I12: 0, OMEGA: 0})
    w_pitch = m * g * (r1 - h) / (I22 + m * h**2)
    w_roll = m * g * (r2 - h) / (I11 + m * h**2)
    assert sp.cancel(p - LAM * (LAM**2 + w_pitch) * (LAM**2 + w_roll)) == 0


def test_rattleback_unstable_spin_direction(linear):
    """The toy (A < B, delta > 0: I_12 < 0; rho_1 > rho_2): I_12 (rho_1 - rho_2) Omega > 0,
    i.e. Omega < 0, is the strongly unstable direction (a3 < 0); Omega > 0 is only weakly
    unstable; the mirror body (delta -> -delta) swaps them."""
    rv, A = linear
    vals = rv.values(TOY)
    assert float(rv.products[sp.Symbol("I_12", real=True)].xreplace(vals)) < 0
    bad = max(z.real for z in spin_rates(A, -5, vals))
    good = max(z.real for z in spin_rates(A, 5, vals))
    assert bad == pytest.approx(2.411, abs=2e-3)
    assert 0 < good < 0.2 * bad
    mirror = rv.values({**TOY, "delta": -0.05})
    assert max(z.real for z in spin_rates(A, 5, mirror)) == pytest.approx(bad, rel=1e-9)
    even = rv.values({**TOY, "delta": 0.0})
    plus = sorted(spin_rates(A, 5, even), key=lambda z: (z.real, z.imag))
    minus = sorted(spin_rates(A, -5, even), key=lambda z: (z.real, z.imag))
    assert all(abs(p.real) < 1e-12 for p in plus)          # delta = 0: a centre, no preference
    assert all(abs(p - q) < 1e-9 for p, q in zip(plus, minus))


def test_rattleback_steady_spin_checked():
    rv = RattlebackVectors()
    A = rv.linearization(sp.Integer(3))
    assert A.shape == (5, 5) and not A.has(OMEGA)


def test_ball_vector_form_integrals_and_density():
    bv = rolling.BallVectors()
    assert all(c.holds is True for c in bv.check_integrals().values())
    assert bv.check_density() is True
    assert bv.divergence_of(sp.Integer(1)) != 0          # not Liouville's measure
    from whittaker_teach import geometry as geo           # the geometry room agrees
    assert geo.invariant_density(bv.rhs, bv.state, bv.density).holds is True
    assert geo.invariant_density(bv.rhs, bv.state, 1).holds is False
    A, B, C, D = bv.parameters
    g1, g2, g3 = bv.gamma
    assert sp.simplify(bv.density.subs({g1: 1, g2: 0, g3: 0}) - sp.sqrt((A + D) / A)) == 0


def test_ball_integrals_through_the_library():
    ball = rolling.chaplygin_ball()
    a = ball.independent_coordinates[0]
    t = a.args[0]
    K = rolling.contact_momentum()
    assert st.conserved(ball, ball.energy()).holds is True
    assert st.conserved(ball, K[2]).holds is True
    assert st.conserved(ball, K[0]).holds is True
    assert st.conserved(ball, a.diff(t)).holds is False


def test_ball_constraints_are_rolling():
    """xdot = R omega_y, ydot = -R omega_x (space components)."""
    import sympy.physics.mechanics as me
    ball = rolling.chaplygin_ball()
    x, y, a, b, c = ball.coordinates
    assert [q.func.__name__ for q in (a, b, c)] == ["alpha", "beta", "chi"]   # not gamma
    R = ball.parameters[3]
    N = me.ReferenceFrame("N")
    F = N.orientnew("F", "Body", [a, b, c], "ZXZ")
    w = F.ang_vel_in(N)
    t = x.args[0]
    assert sp.simplify(ball.constraints[x.diff(t)] - R * w.dot(N.y)) == 0
    assert sp.simplify(ball.constraints[y.diff(t)] + R * w.dot(N.x)) == 0


def test_animation_html_is_offline_small_and_deterministic():
    I = [1, 0, 0, 0, 1, 0, 0, 0, 1]
    shape = dict(a=0.1, b=0.02, top=0.03, h=0.01, rho_1=0.5)
    args = ([0.0, 0.01, 0.02], [-5.0, -4.9999, -4.9], [I] * 3,
            [[0, 0, 0.01], [1e-9, -1e-9, 0.01], [0, 0, 0.0100004]], shape)
    html = rolling.rattleback_animation(*args)
    assert html == rolling.rattleback_animation(*args)
    assert "src=" not in html and "http" not in html and "-0.0," not in html
    assert 'id="wt-rattleback-animation"' in html and "<canvas" in html
    with pytest.raises(ValueError, match="same length"):
        rolling.rattleback_animation([0.0], [1.0], [I], [[0, 0, 0]], shape)
    with pytest.raises(ValueError, match="shape needs"):
        rolling.rattleback_animation(*args[:4], dict(a=0.1))


def test_symbolic_builders_run_without_numpy():
    """The builders are SymPy only (the in-browser site has no numpy)."""
    code = textwrap.dedent("""
        import importlib.abc, sys
        class Hide(importlib.abc.MetaPathFinder):
            def find_spec(self, name, path=None, target=None):
                if name.split(".")[0] in ("numpy", "scipy", "matplotlib"):
                    raise ModuleNotFoundError(name)
        sys.meta_path.insert(0, Hide())
        from whittaker_teach import rolling
        rolling.BallVectors(); rolling.chaplygin_ball()
        rolling.RattlebackVectors(products=True).linearization(); rolling.rattleback()
        rolling.rattleback_animation([0, 1], [1, 1], [[1, 0, 0, 0, 1, 0, 0, 0, 1]] * 2,
                                     [[0, 0, 0]] * 2, dict(a=1, b=1, top=1, h=0, rho_1=1))
        assert not any(m.split(".")[0] in ("numpy", "scipy") for m in sys.modules)
        from whittaker_teach.rolling import simulate
        try:
            simulate.simulate_ball(dict(A=1, B=1, C=1, m=1, R=1), [0, 0, 1])
        except ModuleNotFoundError as err:
            assert "[numerics]" in str(err), err
        else:
            raise AssertionError("simulate ran without numpy")
        print("ok")
    """)
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == "ok"
