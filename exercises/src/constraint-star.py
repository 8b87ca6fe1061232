# %% [markdown]
# # The reduced constraint of the sledge
#
# In the generalized Whittaker equations (1.26) the constraints enter through
# $\dot q^{\ast}_{\varepsilon+\beta}$ (1.23) and through the bracket that multiplies
# $(\partial L/\partial\dot q_{\varepsilon+\beta})^{\ast}$. Here you compute both for
# the sledge of section 3.

# %% [markdown] statement
# The sledge of section 3 of Mei (1983):
# $L = \tfrac12 m(\dot x^2 + \dot y^2) + \tfrac12 J\dot\theta^2 - \tfrac12 k^2\theta^2$ (3.1),
# with the constraint $\dot y = \dot x\tan\theta$ (3.2). Take $q_\varepsilon = x$,
# $\theta' = d\theta/dx$; $y$ is the dependent coordinate.
# **Assumptions:** $m, J, k > 0$; the sledge moves with $\dot x > 0$; $|\theta| < \pi/2$.
#
# 1. `omega`: $\omega_y(\theta', \dot x, \theta)$ (1.22): the constraint with (1.5) substituted.
# 2. `ydot_star`: $\dot y^{\ast} = \partial\omega_y/\partial\dot x$ (1.23), (3.8).
# 3. `bracket`: the bracket of (1.26),
#    $\dfrac{d}{dx}\dfrac{\partial\dot y^{\ast}}{\partial\theta'} - \dfrac{\partial\dot y^{\ast}}{\partial\theta}$.
# 4. `P_star`: $(\partial L/\partial\dot y)^{\ast}$: $\partial L/\partial\dot y$ with the
#    constraint and (1.5) substituted and $\dot x$ from (3.5).
#
# Answer with SymPy expressions in the symbols defined below (or strings).

# %% exercise
EXERCISE = {
    "title": "The reduced constraint of the sledge",
    "equations": "1.22, 1.23, 1.26, 3.8",
    "solvers": False,
    "symbols": "x xdot+ y ydot theta thetadot thetaprime thetaprimeprime h m+ J+ k+",
    "domain": {"x": "real", "xdot": "speed", "theta": "angle", "thetadot": "slope",
               "ydot": "slope", "thetaprime": "slope", "h": "energy"},
    "conditions": ["2*h - k^2*theta^2"],
    "parts": {
        "omega": {
            "what": "omega_y (1.22): the constraint with (1.5) substituted", "points": 1,
            "variables": "xdot theta thetaprime",
            "why_not": {"thetadot": "use (1.5): thetadot = xdot theta'"},
            "success": "omega = xdot tan(theta): it does not contain theta' at all."},
        "ydot_star": {
            "what": "ydot* (1.23) = d omega/d xdot", "points": 1,
            "variables": "theta thetaprime",
            "why_not": {"xdot": "ydot* = d omega/d xdot is free of xdot (1.23)"},
            "success": "ydot* = tan(theta) (3.8): the slope dy/dx of the path."},
        "bracket": {
            "what": "the bracket of (1.26): d/dx(d ydot*/d theta') - d ydot*/d theta",
            "points": 1, "variables": "theta thetaprime thetaprimeprime",
            "success": "The bracket is -(1 + tan^2(theta)) = -1/cos^2(theta)."},
        "P_star": {
            "what": "(dL/d ydot)* of (1.26): m ydot in theta', theta and h", "points": 2,
            "variables": "theta thetaprime h m J k",
            "sign_note": "the direction of travel is xdot > 0, so take the root with the + sign",
            "why_not": {"xdot": "put xdot from (1.12)", "ydot": "use the constraint (3.2)"},
            "success": "(dL/d ydot)* = m tan(theta) sqrt(2h - k^2 theta^2)/sqrt(m (1 + "
                       "tan^2(theta)) + J theta'^2)."},
    },
}

# %%
from whittaker_teach.notebook import setup; setup()

# %%
import sympy as sp
from whittaker_teach.exercises import check

m, J, k = sp.symbols("m J k", positive=True)
xdot = sp.Symbol("xdot", positive=True)          # the direction of travel
x, ydot, theta, thetadot, thetaprime, thetaprimeprime, h = sp.symbols(
    "x ydot theta thetadot thetaprime thetaprimeprime h")
L = m/2*(xdot**2 + ydot**2) + J/2*thetadot**2 - k**2*theta**2/2   # (3.1)
ydot_constraint = xdot*sp.tan(theta)                               # (3.2)
xdot_35 = (sp.sqrt(2*h - k**2*theta**2)
           / sp.sqrt(m*(1 + sp.tan(theta)**2) + J*thetaprime**2))


def d_dx(f):
    """d/dx of f(theta', theta, x) along a path (2.1)."""
    return (f.diff(x) + f.diff(thetaprime)*thetaprimeprime
            + f.diff(theta)*thetaprime)

# %% [markdown]
# `xdot_35` is $\dot x$ from (3.5) (the exercise *sledge-L-star* derives it).
#
# ## 1. $\omega_y$ (1.22)

# %%
### BEGIN SOLUTION
omega = ydot_constraint.subs(thetadot, xdot*thetaprime)       # (1.22)
### END SOLUTION
### PLACEHOLDER: omega = None  # your answer here
omega

# %% [markdown] solution
# The sledge's constraint does not contain $\dot\theta$, so (1.5) changes
# nothing: $\omega_y = \dot x\tan\theta$.

# %%
check("constraint-star", omega, part="omega")

# %% [markdown]
# ## 2. $\dot y^{\ast}$ (1.23)

# %%
### BEGIN SOLUTION
ydot_star = omega.diff(xdot)                                  # (1.23)
### END SOLUTION
### PLACEHOLDER: ydot_star = None  # your answer here
ydot_star

# %% [markdown] solution
# $\dot y^{\ast} = \tan\theta = dy/dx$, the slope of the path: by (1.24),
# $\dot y^{\ast} = \dot y/\dot x$ for a constraint homogeneous of degree one.

# %%
check("constraint-star", ydot_star, part="ydot_star")

# %% [markdown]
# ## 3. The bracket of (1.26)

# %%
### BEGIN SOLUTION
bracket = d_dx(ydot_star.diff(thetaprime)) - ydot_star.diff(theta)
### END SOLUTION
### PLACEHOLDER: bracket = None  # your answer here
bracket

# %% [markdown] solution
# $\dot y^{\ast}$ does not depend on $\theta'$, so only $-\partial\dot y^{\ast}/\partial\theta
# = -(1 + \tan^2\theta) = -1/\cos^2\theta$ remains, the paper's value.

# %%
check("constraint-star", bracket, part="bracket")

# %% [markdown]
# ## 4. $(\partial L/\partial\dot y)^{\ast}$

# %%
### BEGIN SOLUTION
P = L.diff(ydot).subs(ydot, ydot_constraint)       # m xdot tan(theta)
P_star = P.subs(xdot, xdot_35)
### END SOLUTION
### PLACEHOLDER: P_star = None  # your answer here: in theta, thetaprime and h
P_star

# %%
check("constraint-star", P_star, part="P_star")
