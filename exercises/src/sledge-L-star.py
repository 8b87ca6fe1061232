# %% [markdown]
# # The sledge's reduced Lagrangian
#
# Section 3 of Mei (1983) applies the reduction to a sledge on a horizontal
# plane held by a torsional spring. Here you derive its reduced Lagrangian
# $L^{\ast}$ (3.7) yourself, one step of the paper at a time.

# %% [markdown] statement
# The sledge has mass $m$ and moment of inertia $J$; its contact point is
# $(x, y)$ and its axis makes the angle $\theta$ with $Ox$. With the spring
# $U = -\tfrac12 k^2\theta^2$,
#
# $$L = \tfrac12 m(\dot x^2 + \dot y^2) + \tfrac12 J\dot\theta^2 - \tfrac12 k^2\theta^2
# \qquad (3.1)$$
#
# $$\dot y = \dot x\tan\theta \qquad (3.2)$$
#
# Take $x$ as the independent coordinate ($q_\varepsilon = x$, $\theta' = d\theta/dx$).
# **Assumptions:** $m, J, k > 0$; the sledge moves with $\dot x > 0$; $|\theta| < \pi/2$.
#
# 1. `Omega`: $\Omega$ (1.6), (3.6): $\tilde L$ (3.3) with $\dot\theta = \dot x\,\theta'$ (1.5).
# 2. `xdot`: solve the energy integral (1.13) for $\dot x$ (1.12), (3.5), taking $\dot x > 0$.
# 3. `L_star`: the reduced Lagrangian $L^{\ast} = \partial\Omega/\partial\dot x$ at that $\dot x$ (1.16), (3.7).
#
# Answer with SymPy expressions in the symbols defined below (or with strings
# such as `"sqrt(2*h - k^2*theta^2)"`; `theta'` stands for $\theta'$).

# %% exercise
EXERCISE = {
    "title": "The sledge's reduced Lagrangian",
    "equations": "3.5, 3.6, 3.7",
    "solvers": False,
    "symbols": "x xdot+ y ydot theta thetadot thetaprime thetaprimeprime h m+ J+ k+",
    "domain": {"x": "real", "xdot": "speed", "theta": "angle", "thetadot": "slope",
               "ydot": "slope", "thetaprime": "slope", "h": "energy"},
    "conditions": ["2*h - k^2*theta^2"],
    "parts": {
        "Omega": {
            "what": "Omega (3.6): L~ (3.3) with thetadot = xdot theta'", "points": 1,
            "why_not": {"thetadot": "use (1.5): thetadot = xdot theta'", "ydot": "use (3.2)",
                        "h": "Omega is L~, not the energy"},
            "success": "Omega = xdot^2 (m (1 + tan^2 theta) + J theta'^2)/2 - k^2 theta^2/2 "
                       "(3.6)."},
        "xdot": {
            "form": "sqrt(2*h - k^2*theta^2)/sqrt(m*(1 + tan(theta)^2) + J*thetaprime^2)",
            "what": "xdot (3.5): the root of (1.13) with xdot > 0", "points": 1,
            "sign_note": "the direction of travel is xdot > 0, so take the root with the + sign",
            "why_not": {"xdot": "solve (1.13) for xdot", "thetadot": "use theta'"},
            "wrong": [["sqrt(2*h - k^2*theta^2)/sqrt(m*(1 + tan(theta)^2) + J*thetadot^2)",
                       "this is (3.5) as the OCR prints it, with J thetadot^2"]],
            "success": "xdot = sqrt(2h - k^2 theta^2)/sqrt(m (1 + tan^2 theta) + J theta'^2) "
                       "(3.5)."},
        "L_star": {
            "form": "sqrt(2*h - k^2*theta^2)*sqrt(m*(1 + tan(theta)^2) + J*thetaprime^2)",
            "what": "L* (3.7) = dOmega/d xdot with xdot from (3.5)", "points": 2,
            "sign_note": "the direction of travel is xdot > 0, so take the root with the + sign",
            "why_not": {"xdot": "put xdot from (3.5)", "thetadot": "use theta'"},
            "wrong": [["h - k^2*theta^2",
                       "this is Omega itself at xdot from (3.5); L* (1.16) is its derivative "
                       "dOmega/dxdot, taken first and then evaluated at that xdot"]],
            "success": "L* = sqrt(2h - k^2 theta^2) sqrt(m (1 + tan^2 theta) + J theta'^2) "
                       "(3.7), the + sign for xdot > 0."},
    },
}

# %%
from whittaker_teach.notebook import setup; setup()

# %%
import sympy as sp
from whittaker_teach.exercises import check

m, J, k = sp.symbols("m J k", positive=True)
xdot = sp.Symbol("xdot", positive=True)      # direction of travel
theta, thetadot, thetaprime, h = sp.symbols("theta thetadot thetaprime h")
Ltilde = (m/2*xdot**2*(1 + sp.tan(theta)**2) + J/2*thetadot**2
          - k**2*theta**2/2)                                   # (3.3)
Ltilde

# %% [markdown]
# ## 1. $\Omega$ (1.6)
#
# Substitute (1.5), $\dot\theta = \dot x\,\theta'$, in $\tilde L$.

# %%
### BEGIN SOLUTION
Omega = Ltilde.subs(thetadot, xdot*thetaprime)
### END SOLUTION
### PLACEHOLDER: Omega = None  # your answer here: L~ with thetadot = xdot*thetaprime
Omega

# %%
check("sledge-L-star", Omega, part="Omega")

# %% [markdown]
# ## 2. $\dot x$ from the energy integral (1.13)
#
# The energy integral in the new variables is
# $\dot x\,\partial\Omega/\partial\dot x - \Omega = h$ (1.13). Solve it for
# $\dot x > 0$.

# %%
### BEGIN SOLUTION
energy = sp.expand(xdot*sp.diff(Omega, xdot) - Omega)
v = sp.Symbol("v")                            # xdot, without its sign
roots = sp.solve(sp.Eq(energy.subs(xdot, v), h), v)
display(roots)
# the root with xdot > 0:
xdot_sol, = [r for r in roots if not r.could_extract_minus_sign()]
### END SOLUTION
### PLACEHOLDER: xdot_sol = None  # your answer here: xdot in theta, thetaprime and h
xdot_sol

# %% [markdown] solution
# The energy fixes only $\dot x^2$: (1.13) has the two roots $\pm$. The
# assumption "the sledge moves with $\dot x > 0$" picks the one with the $+$ sign.

# %%
check("sledge-L-star", xdot_sol, part="xdot")

# %% [markdown]
# ## 3. $L^{\ast}$ (1.16)

# %%
### BEGIN SOLUTION
L_star = sp.diff(Omega, xdot).subs(xdot, xdot_sol)   # (1.16)
### END SOLUTION
### PLACEHOLDER: L_star = None  # your answer here: dOmega/dxdot at xdot = xdot_sol
L_star

# %% [markdown] solution
# The library derives the same $L^{\ast}$ (its square roots are written in another
# order, which the check does not mind):

# %% solution
import whittaker_teach as wt
wt.examples.sledge().reduce("x", direction=+1).L_star

# %%
check("sledge-L-star", L_star, part="L_star")
