"""The rattleback (celt): a rigid body with a paraboloidal bottom rolling without
slipping on a horizontal plane, its principal axes of inertia turned by an angle delta
about the vertical body axis from the axes of curvature of the bottom.

The model (a standard one; the shape as in the linear analyses of Walker 1896 and
Bondi 1986, the equations as in Borisov and Mamaev's rigid-body-on-a-plane form):
in the body frame, with axes along the principal curvatures at the bottom point, the
bottom is the paraboloid z = x^2/(2 rho_1) + y^2/(2 rho_2); the centre of mass G is at
(0, 0, h) with h < rho_1, rho_2 (so the lowest position is a stable equilibrium at
rest); the central inertia tensor has principal moments A, B, C about axes turned by
delta about z (delta > 0: counterclockwise seen from above, z pointing up; the product
term is the tensor's entry I_12 = (A - B) sin(delta) cos(delta)).  gamma is the upward
vertical in the body frame; the spin is Omega = gamma . omega, positive counterclockwise
seen from above; the contact point
P(gamma) is where the bottom's outward normal is -gamma:
P = (-rho_1 g1/g3, -rho_2 g2/g3, (rho_1 g1^2 + rho_2 g2^2)/(2 g3^2)), and
r = P - G.  Rolling: v_G = r x omega.  Newton-Euler about G, the contact force
eliminated:

    (I + m(|r|^2 E - r r^T)) domega/dt = -omega x I omega
                                         + m r x (dr/dt x omega + omega x (r x omega) + g gamma),
    dgamma/dt = gamma x omega,

with the energy E = omega.I.omega/2 + m|r x omega|^2/2 - m g (r . gamma).

:class:`RattlebackVectors` holds these equations symbolically (SymPy only);
:meth:`RattlebackVectors.linearization` linearises them about the steady spin
omega = (0, 0, Omega) at the lowest point gamma = (0, 0, 1), with sympy directly
(see the chapter: the library's stability room needs the accelerations [1.4a] of the
Euler-angle model, which SymPy does not produce in reasonable time for this body).
:func:`rattleback` builds the same body with ``sympy.physics.mechanics`` and takes it
in through the mechanics input (a Chaplygin system, x and y dependent).

>>> rv = RattlebackVectors()
>>> rv.linearization().shape
(5, 5)
"""

from __future__ import annotations

import sympy as sp

__all__ = ["rattleback", "RattlebackVectors", "contact_point", "spin_rates", "euler_vectors"]


def _symbols():
    m, g, h, r1, r2, A, B, C = sp.symbols("m g h rho_1 rho_2 A B C", positive=True)
    delta = sp.Symbol("delta", real=True)
    return m, g, h, r1, r2, A, B, C, delta


def contact_point(gamma, rho_1, rho_2):
    """The contact point of the paraboloid z = x^2/(2 rho_1) + y^2/(2 rho_2) with the plane
    whose upward normal is ``gamma`` (body components): where the outward normal is -gamma.

    >>> g1, g2, g3, r1, r2 = sp.symbols("g1 g2 g3 r1 r2")
    >>> contact_point([g1, g2, g3], r1, r2).T
    Matrix([[-g1*r1/g3, -g2*r2/g3, (g1**2*r1 + g2**2*r2)/(2*g3**2)]])
    """
    g1, g2, g3 = gamma
    return sp.Matrix([-rho_1 * g1 / g3, -rho_2 * g2 / g3,
                      (rho_1 * g1**2 + rho_2 * g2**2) / (2 * g3**2)])


def _inertia(A, B, C, delta):
    """The central inertia tensor, principal axes turned by delta about z."""
    c, s = sp.cos(delta), sp.sin(delta)
    Rz = sp.Matrix([[c, -s, 0], [s, c, 0], [0, 0, 1]])
    return Rz * sp.diag(A, B, C) * Rz.T


class RattlebackVectors:
    """The rattleback's equations in the body frame (module docstring).

    ``self.omega``, ``self.gamma``: 3x1 matrices of symbols; ``self.parameters``:
    (m, g, h, rho_1, rho_2, A, B, C, delta); ``self.mass_matrix`` K(gamma) and
    ``self.force`` f(omega, gamma) with K domega/dt = f; ``self.gamma_rate``;
    ``self.energy``.
    """

    def __init__(self, products=False):
        m, g, h, r1, r2, A, B, C, delta = self.parameters = _symbols()
        self.omega = w = sp.Matrix(sp.symbols("omega_1:4", real=True))
        self.gamma = gm = sp.Matrix(sp.symbols("gamma_1:4", real=True))
        self.inertia = I = _inertia(A, B, C, delta)
        #: {I_11: ..., I_12: ..., I_22: ...}: the horizontal block of the inertia tensor in
        #: the curvature axes; with ``products=True`` the tensor is written with these
        #: symbols (I_12, the product of inertia, carries the misalignment)
        I11, I12, I22 = sp.symbols("I_11 I_12 I_22", real=True)
        self.products = {I11: I[0, 0], I12: I[0, 1], I22: I[1, 1]}
        if products:
            self.inertia = I = sp.Matrix([[I11, I12, 0], [I12, I22, 0], [0, 0, C]])
        self.r = r = contact_point(gm, r1, r2) - sp.Matrix([0, 0, h])
        self.gamma_rate = gdot = gm.cross(w)
        rdot = r.jacobian(gm) * gdot
        self.mass_matrix = I + m * (r.dot(r) * sp.eye(3) - r * r.T)
        self.force = (-w.cross(I * w)
                      + m * r.cross(rdot.cross(w) + w.cross(r.cross(w)) + g * gm))
        v = r.cross(w)
        self.energy = (w.dot(I * w) + m * v.dot(v)) / 2 - m * g * r.dot(gm)

    def linearization(self, Omega=None):
        """The matrix A of the linearisation d(delta z)/dt = A delta z about the steady
        spin omega = (0, 0, Omega), gamma = (0, 0, 1), in the state
        z = (omega_1, omega_2, omega_3, gamma_1, gamma_2) (gamma_3 = sqrt(1 - g1^2 - g2^2)
        on the sphere).  The equations vanish at the steady spin (checked: a
        ``ValueError`` otherwise); A = K0^-1 df/dz there."""
        Om = sp.Symbol("Omega", real=True) if Omega is None else Omega
        w1, w2, w3 = self.omega
        g1, g2, g3 = self.gamma
        on_sphere = {g3: sp.sqrt(1 - g1**2 - g2**2)}
        rhs_w = self.force.xreplace(on_sphere)
        rhs_g = self.gamma_rate.xreplace(on_sphere)
        state = [w1, w2, w3, g1, g2]
        point = {w1: 0, w2: 0, w3: Om, g1: 0, g2: 0}
        f0 = [sp.cancel(e.xreplace(point)) for e in (*rhs_w, *rhs_g[:2])]
        if any(e != 0 for e in f0):
            raise ValueError(f"the steady spin is not an equilibrium here: rates {f0}")
        K0 = self.mass_matrix.xreplace(on_sphere).xreplace(point)
        Jw = rhs_w.jacobian(state).xreplace(point)
        Jg = sp.Matrix(rhs_g[:2]).jacobian(state).xreplace(point)
        top = K0.LUsolve(Jw)
        return sp.Matrix.vstack(top, Jg).applyfunc(sp.cancel)

    def charpoly(self, Omega=None, lam=None):
        """det(lam I - A) of :meth:`linearization` as a ``Poly`` in lam (coefficients
        cancelled rational functions; with ``products=True`` they are quick to get)."""
        lam = sp.Symbol("lambda") if lam is None else lam
        A = self.linearization(Omega)
        p = A.charpoly(lam)
        return sp.Poly([sp.factor(c) for c in p.all_coeffs()], lam)

    def values(self, numbers):
        """{parameter symbol: number} from {name: number} (names as printed:
        "m", "g", "h", "rho_1", "rho_2", "A", "B", "C", "delta")."""
        by_name = {str(s): s for s in self.parameters}
        missing = set(by_name) - set(numbers)
        if missing:
            raise ValueError(f"rattleback parameters missing: {sorted(missing)}")
        return {by_name[k]: v for k, v in numbers.items()}


def spin_rates(linear_A, Omega_value, values):
    """The eigenvalues (complex floats, SymPy ``nroots`` at 30 digits) of the
    linearisation ``linear_A`` (from :meth:`RattlebackVectors.linearization`) at
    Omega = ``Omega_value`` and the parameter ``values`` {symbol: number}."""
    lam = sp.Symbol("lambda")
    Om = sp.Symbol("Omega", real=True)
    A = linear_A.xreplace({**values, Om: Omega_value})
    p = sp.Poly(A.charpoly(lam).as_expr(), lam)
    return [complex(z) for z in p.nroots(n=30)]


def euler_vectors():
    """(omega, gamma): the body components of the angular velocity and of the upward
    vertical in the coordinates of :func:`rattleback` (psi, theta_1, theta_2 and their
    rates), to compare the two descriptions.

    >>> omega, gamma = euler_vectors()
    >>> gamma.T
    Matrix([[-sin(theta_2(t))*cos(theta_1(t)), sin(theta_1(t)), cos(theta_1(t))*cos(theta_2(t))]])
    """
    import sympy.physics.mechanics as me
    psi, th1, th2 = me.dynamicsymbols("psi theta_1 theta_2")
    N = me.ReferenceFrame("N")
    F = N.orientnew("F", "Body", [psi, th1, th2], "ZXY")
    w = F.ang_vel_in(N)
    return (sp.Matrix([sp.trigsimp(w.dot(e)) for e in (F.x, F.y, F.z)]),
            sp.Matrix([sp.trigsimp(N.z.dot(e)) for e in (F.x, F.y, F.z)]))


def rattleback(name="rattleback"):
    """The rattleback built with ``sympy.physics.mechanics`` (frames: heading psi about the
    vertical, then theta_1 about x, theta_2 about y; the body with its inertia dyadic
    turned by delta; G at P(gamma)-relative position; gravity as potential energy) and
    taken in by ``ChaplyginSystem.from_lagranges_method`` with the contact point's x, y
    dependent.  Building it is quick; deriving its accelerations (1.4) symbolically is
    not (the chapter measures it).

    >>> rattleback().independent_coordinates
    [psi(t), theta_1(t), theta_2(t)]
    """
    import sympy.physics.mechanics as me

    from ..system import ChaplyginSystem
    m, g, h, r1, r2, A, B, C, delta = _symbols()
    x, y, psi, th1, th2 = me.dynamicsymbols("x y psi theta_1 theta_2")
    N = me.ReferenceFrame("N")
    F = N.orientnew("F", "Body", [psi, th1, th2], "ZXY")
    gm = [sp.trigsimp(N.z.dot(e)) for e in (F.x, F.y, F.z)]
    p = contact_point(gm, r1, r2)
    rP = p[0] * F.x + p[1] * F.y + p[2] * F.z
    O = me.Point("O")
    O.set_vel(N, 0)
    P = O.locatenew("P", x * N.x + y * N.y)
    G = P.locatenew("G", h * F.z - rP)
    G.set_vel(N, G.pos_from(O).dt(N))
    D = F.orientnew("D", "Axis", [delta, F.z])
    body = me.RigidBody("rattleback", G, F, m, (me.inertia(D, A, B, C), G))
    body.potential_energy = m * g * G.pos_from(O).dot(N.z)
    L = me.Lagrangian(N, body)
    slip = G.vel(N) + F.ang_vel_in(N).cross(rP - h * F.z)
    cons = [slip.dot(e) for e in (N.x, N.y)]
    lm = me.LagrangesMethod(L, [x, y, psi, th1, th2], nonhol_coneqs=cons, frame=N)
    return ChaplyginSystem.from_lagranges_method(lm, dependent=[x, y], name=name)
