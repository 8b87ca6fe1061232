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
