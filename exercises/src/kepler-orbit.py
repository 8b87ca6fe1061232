# %% [markdown]
# # The Kepler orbit with the polar angle as time
#
# For a planet, the polar angle $\theta$ can take the place of time:
# Whittaker's equation (1.27) then describes the orbit $r(\theta)$ directly,
# and the conics of Kepler's first law must be among its solutions.

# %% [markdown] statement
# A particle of mass $m$ moves in the field of a fixed centre, with potential
# energy $-\mu m/r$:
#
# $$L = \tfrac12 m(\dot r^2 + r^2\dot\theta^2) + \frac{\mu m}{r}.$$
#
# The system is holonomic. Take $\theta$ as the independent coordinate:
# $q_\varepsilon = \theta$, $r' = dr/d\theta$ (1.5).
# **Assumptions:** $m, \mu > 0$, $r > 0$; the particle goes round with
# $\dot\theta > 0$ (the direction of travel).
#
# 1. `L_star`: the reduced Lagrangian $L^{\ast}(r', r)$ (1.6), (1.12), (1.16).
# 2. `r_pp`: Whittaker's equation (1.27) for $L^{\ast}$, solved for $r''$.
# 3. `h`: show that the conic $r = p/(1 + e\cos\theta)$ ($p > 0$, $e \ge 0$: ellipses,
#    the parabola $e = 1$ and hyperbolas $e > 1$)
#    solves (1.27), and find the energy $h$ in terms of $p$ and $e$ (and $m$, $\mu$).
#
# Answer with SymPy expressions in the symbols defined below (or strings; `r'`
# stands for $r'$).

# %% exercise
EXERCISE = {
    "title": "The Kepler orbit with the polar angle as time",
    "equations": "1.16, 1.27",
    "solvers": False,
    "symbols": "r+ rprime rprimeprime theta h m+ mu+ p+ e",
    "domain": {"r": "positive", "rprime": "slope", "rprimeprime": "real", "theta": "turn",
               "h": "energy", "e": [0.0, None]},
    "conditions": ["h + m*mu/r"],
    "parts": {
        "L_star": {
            "form": "sqrt(2*h + 2*m*mu/r)*sqrt(m*(r^2 + rprime^2))",
            "what": "L* (1.16) for the Kepler problem with theta in place of t", "points": 1,
            "variables": "r rprime h m mu",
            "sign_note": "theta increases along the orbit (thetadot > 0): take the + root",
            "why_not": {"theta": "L does not depend on theta"},
            "success": "L* = sqrt(2 h + 2 m mu/r) sqrt(m (r^2 + r'^2)) (1.16)."},
        "r_pp": {
            "what": "r'' solved from Whittaker's equation (1.27)", "points": 1,
            "variables": "r rprime h m mu",
            "why_not": {"rprimeprime": "solve the equation for r''"},
            "success": "r'' from (1.27)."},
        "h": {
            "what": "the energy h for which the conic r = p/(1 + e cos(theta)) solves (1.27)",
            "points": 2, "variables": "m mu p e",
            "why_not": {"theta": "h is a constant", "r": "h is a constant of the orbit",
                        "rprime": "h is a constant of the orbit"},
            "success": "h = -m mu (1 - e^2)/(2 p), for every e >= 0: negative for an ellipse "
                       "(e < 1), zero for a parabola (e = 1), positive for a hyperbola (e > 1)."},
    },
}

# %%
from whittaker_teach.notebook import setup; setup()

# %%
import sympy as sp
from whittaker_teach.exercises import check

m, mu, p = sp.symbols("m mu p", positive=True)
r = sp.Symbol("r", positive=True)
thetadot = sp.Symbol("thetadot", positive=True)   # direction of travel
theta, rprime, rprimeprime, h, e = sp.symbols("theta rprime rprimeprime h e")


def d_dtheta(f):
    """d/dtheta of f(r', r, theta) along a path (2.1)."""
    return f.diff(theta) + f.diff(rprime)*rprimeprime + f.diff(r)*rprime

# %% [markdown]
# ## 1. The reduced Lagrangian $L^{\ast}$
#
# $\Omega$ (1.6) is $L$ with $\dot r = \dot\theta\, r'$; solve
# $\dot\theta\,\partial\Omega/\partial\dot\theta - \Omega = h$ (1.13) for
# $\dot\theta > 0$ and put the root in $L^{\ast} = \partial\Omega/\partial\dot\theta$ (1.16).

# %%
### BEGIN SOLUTION
Omega = m/2*((thetadot*rprime)**2 + r**2*thetadot**2) + mu*m/r   # (1.6)
energy = sp.expand(thetadot*Omega.diff(thetadot) - Omega)        # (1.13)
v = sp.Symbol("v")
roots = sp.solve(sp.Eq(energy.subs(thetadot, v), h), v)
thetadot_sol, = [s for s in roots if not s.could_extract_minus_sign()]
L_star = sp.simplify(Omega.diff(thetadot).subs(thetadot, thetadot_sol))
### END SOLUTION
### PLACEHOLDER: L_star = None  # your answer here: L* in r, rprime and h
L_star

# %%
check("kepler-orbit", L_star, part="L_star")

# %% [markdown]
# ## 2. Whittaker's equation (1.27), solved for $r''$

# %%
### BEGIN SOLUTION
whittaker = d_dtheta(L_star.diff(rprime)) - L_star.diff(r)     # (1.27)
r_pp, = sp.solve(whittaker, rprimeprime)
r_pp = sp.factor(r_pp)
### END SOLUTION
### PLACEHOLDER: r_pp = None  # your answer here: r'' in r, rprime and h
r_pp

# %%
check("kepler-orbit", r_pp, part="r_pp")

# %% [markdown]
# ## 3. The conic, and its energy
#
# Put $r = p/(1 + e\cos\theta)$, with its $r'$ and $r''$, in the equation of
# step 2. For which $h$ does the residual vanish for every $\theta$?

# %%
### BEGIN SOLUTION
conic = p/(1 + e*sp.cos(theta))
on_orbit = {r: conic, rprime: conic.diff(theta)}
residual = sp.factor(sp.together(conic.diff(theta, 2) - r_pp.subs(on_orbit)))
h_conic, = sp.solve(residual, h)
assert sp.simplify(residual.subs(h, h_conic)) == 0     # for every theta
### END SOLUTION
### PLACEHOLDER: h_conic = None  # your answer here: h in terms of p, e, m, mu
h_conic

# %% [markdown] solution
# The residual is linear in $h$ and one value makes it vanish for every
# $\theta$: $h = -\dfrac{m\mu(1 - e^2)}{2p}$. It is negative for an
# ellipse ($e < 1$: a bound orbit), zero for a parabola and positive for a
# hyperbola, as Kepler's problem requires. The reduction never needed $t$.

# %%
check("kepler-orbit", h_conic, part="h")
