"""The Chaplygin ball: a balanced ball (centre of mass at the geometric centre, unequal
principal moments A, B, C) rolling without slipping on a horizontal plane
(Chaplygin 1903).

Two descriptions, both symbolic (SymPy only):

* :func:`chaplygin_ball` builds the ball with ``sympy.physics.mechanics`` (frames,
  a rigid body, the rolling constraint "the material point at the contact has zero
  velocity") in the coordinates x, y of the contact point and the Euler angles
  (z-x-z) alpha, beta, chi (chi, not gamma: gamma is the vertical below), and
  takes it in through the library's mechanics input
  (:meth:`~whittaker_teach.system.ChaplyginSystem.from_lagranges_method`): a Chaplygin
  system with x, y dependent, as L and the constraints contain neither.
  :func:`contact_momentum` gives the angular momentum about the contact point.
* :class:`BallVectors` writes the same motion in the body frame, in the angular
  momentum about the contact point M and the upward vertical gamma
  (the Chaplygin-Borisov-Mamaev form): dM/dt = M x omega, dgamma/dt = gamma x omega,
  with M = (I + D) omega - D (gamma . omega) gamma, D = m R^2.  It has the integrals
  H = (M . omega)/2, (M, M), (M, gamma), (gamma, gamma) and the invariant measure
  rho dM dgamma with Chaplygin's density rho = (1 - D gamma . (I + D)^-1 gamma)^(-1/2);
  :meth:`BallVectors.check_density` verifies div(rho F) = 0 exactly.

>>> ball = chaplygin_ball()
>>> ball.dependent_coordinates, ball.independent_coordinates
([x(t), y(t)], [alpha(t), beta(t), chi(t)])
>>> BallVectors().check_density()
True
"""

from __future__ import annotations

import sympy as sp

__all__ = ["chaplygin_ball", "contact_momentum", "BallVectors"]


def _ball_model():
    """Frames, points and the body of the ball; returns the pieces the builders need."""
    import sympy.physics.mechanics as me
    x, y, a, b, c = me.dynamicsymbols("x y alpha beta chi")
    m, R, A, B, C = sp.symbols("m R A B C", positive=True)
    N = me.ReferenceFrame("N")
    F = N.orientnew("F", "Body", [a, b, c], "ZXZ")        # body frame, principal axes
    O = me.Point("O")
    O.set_vel(N, 0)
    P = O.locatenew("P", x * N.x + y * N.y)                # the contact point
    G = P.locatenew("G", R * N.z)                          # the centre (= centre of mass)
    G.set_vel(N, G.pos_from(O).dt(N))
    body = me.RigidBody("ball", G, F, m, (me.inertia(F, A, B, C), G))
    return dict(q=[x, y, a, b, c], params=(A, B, C, R, m), N=N, F=F, G=G, P=P, body=body)


def _pythagoras(e):
    """sin(u)**2*X + cos(u)**2*X -> X, term by term (no simplify)."""
    return sp.trigsimp(sp.expand(e))


def chaplygin_ball(name="chaplygin_ball"):
    """The balanced ball (mass m, radius R, principal moments A, B, C about its centre)
    as a :class:`~whittaker_teach.system.ChaplyginSystem`, built with
    ``sympy.physics.mechanics`` and a ``LagrangesMethod`` taken in by
    ``ChaplyginSystem.from_lagranges_method``.  No potential (the centre stays at
    height R).

    >>> chaplygin_ball().parameters
    [A, B, C, R, m]
    """
    import sympy.physics.mechanics as me

    from ..system import ChaplyginSystem
    d = _ball_model()
    N, F, G, body = d["N"], d["F"], d["G"], d["body"]
    R = d["params"][3]
    L = _pythagoras(me.Lagrangian(N, body))
    w = F.ang_vel_in(N)
    slip = G.vel(N) + w.cross(-R * N.z)        # velocity of the material point at P
    cons = [_pythagoras(slip.dot(e)) for e in (N.x, N.y)]
    lm = me.LagrangesMethod(L, d["q"], nonhol_coneqs=cons, frame=N)
    x, y = d["q"][:2]
    return ChaplyginSystem.from_lagranges_method(lm, dependent=[x, y], name=name)


def contact_momentum():
    """The angular momentum of the ball about the contact point, K_P = H_G + PG x m v_G,
    as its components (along N.x, N.y, N.z) in the coordinates and velocities of
    :func:`chaplygin_ball` (dependent velocities included: substitute the constraints).

    >>> len(contact_momentum())
    3
    """
    d = _ball_model()
    N, G, P, body = d["N"], d["G"], d["P"], d["body"]
    K = body.angular_momentum(G, N) + G.pos_from(P).cross(body.mass * G.vel(N))
    return [_pythagoras(K.dot(e)) for e in (N.x, N.y, N.z)]


class BallVectors:
    """The Chaplygin ball in the body frame: M (angular momentum about the contact point)
    and gamma (the upward unit vertical), both as body components.

    ``self.M``, ``self.gamma``: 3x1 matrices of symbols; ``self.omega``: omega(M, gamma)
    solved from M = J omega - D (gamma . omega) gamma, J = I + D E, D = m R^2;
    ``self.rhs``: (dM/dt, dgamma/dt) = (M x omega, gamma x omega);
    ``self.integrals``: {name: expression}; ``self.density``: Chaplygin's rho.

    >>> bv = BallVectors()
    >>> bv.density
    1/sqrt(-D*(gamma_1**2/(A + D) + gamma_2**2/(B + D) + gamma_3**2/(C + D)) + 1)
    """

    def __init__(self):
        A, B, C, D = sp.symbols("A B C D", positive=True)
        self.parameters = (A, B, C, D)
        self.M = sp.Matrix(sp.symbols("M_1:4", real=True))
        self.gamma = sp.Matrix(sp.symbols("gamma_1:4", real=True))
        J = sp.diag(A + D, B + D, C + D)
        Jinv_M = sp.Matrix([self.M[i] / J[i, i] for i in range(3)])
        Jinv_g = sp.Matrix([self.gamma[i] / J[i, i] for i in range(3)])
        denom = 1 - D * self.gamma.dot(Jinv_g)
        g_dot_w = self.gamma.dot(Jinv_M) / denom              # (gamma . omega)
        self.omega = Jinv_M + D * g_dot_w * Jinv_g
        self.rhs = sp.Matrix([*self.M.cross(self.omega), *self.gamma.cross(self.omega)])
        self.state = [*self.M, *self.gamma]
        self.integrals = {
            "H": self.M.dot(self.omega) / 2,
            "(M, M)": self.M.dot(self.M),
            "(M, gamma)": self.M.dot(self.gamma),
            "(gamma, gamma)": self.gamma.dot(self.gamma),
        }
        self.density = 1 / sp.sqrt(denom)

    def momentum_of(self, omega, gamma):
        """M = (I + D) omega - D (gamma . omega) gamma for given omega, gamma (sequences)."""
        A, B, C, D = self.parameters
        w, g = sp.Matrix(omega), sp.Matrix(gamma)
        return sp.diag(A + D, B + D, C + D) * w - D * g.dot(w) * g

    def check_integrals(self):
        """{name: Check}: d/dt of each integral along ``rhs`` vanishes, checked at random
        points in 40-digit arithmetic (:func:`~whittaker_teach.verify.check_zero`; an exact
        ``cancel`` of the rate of H takes about a minute)."""
        from ..stability.steady import sampler
        from ..verify import check_zero
        out = {}
        for name, f in self.integrals.items():
            rate = sum(sp.diff(f, s) * r for s, r in zip(self.state, self.rhs))
            out[name] = check_zero("integral", f"d/dt {name} = 0 along the ball's equations",
                                   rate, sampler(rate.free_symbols), exact=False)
        return out

    def check_density(self):
        """True when div(rho F) = 0 identically (F = ``rhs`` on R^6), i.e.
        div F + F . grad(log rho) = 0 as a rational function: rho dM dgamma is an
        invariant measure.  False otherwise (e.g. for rho = 1)."""
        return self.divergence_of(self.density) == 0

    def divergence_of(self, rho):
        """div(rho F)/rho, cancelled (a rational function for the densities tried here)."""
        logrho = sp.log(rho)
        total = 0
        for s, f in zip(self.state, self.rhs):
            total += sp.diff(f, s) + f * sp.diff(logrho, s)
        return sp.cancel(sp.together(sp.expand_log(total, force=True)))
