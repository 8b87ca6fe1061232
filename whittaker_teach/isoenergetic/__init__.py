"""Whittaker's reduction in Hamiltonian form: the isoenergetic reduction.

Solve the energy integral H(q, p) = h for the momentum p_eps of the coordinate
q_eps that replaces time; then K = -p_eps(q_nu, p_nu; q_eps, h) is a Hamiltonian
with q_eps as the time:

    dq_nu/dq_eps = dK/dp_nu,     dp_nu/dq_eps = -dK/dq_nu + Q_nu,

where Q_nu = 0 for a holonomic system (Whittaker's Treatise; Arnold's reduction
of order by the energy integral) and, for a Chaplygin system with constraints
linear in the velocities, Q_nu is Mei's constraint term of (1.26) written in the
momenta (derived in :mod:`.form`).

==========================  ==========================================================
``IsoenergeticForm``        built from a :class:`~whittaker_teach.reduction.Reduction`:
                            the momenta, H, the branch of p_eps, K, Hamilton's
                            equations in q_eps, the constraint term; ``verify()``
                            checks K against the Legendre transform of L* (1.16)
                            and the equations against the core's (1.27) / (1.26)
``isoenergetic``            the same, as a function
==========================  ==========================================================

Only SymPy and mpmath are used; the core never imports this package.

>>> import whittaker_teach as wt
>>> from whittaker_teach.isoenergetic import IsoenergeticForm
>>> iso = IsoenergeticForm(wt.examples.projectile().reduce("x"))
>>> iso.K
-sqrt(-2*g_0*m**2*y + 2*h*m - p_y**2)
>>> iso.verify().ok
True
"""

from .form import IsoenergeticForm, isoenergetic

__all__ = ["IsoenergeticForm", "isoenergetic"]
