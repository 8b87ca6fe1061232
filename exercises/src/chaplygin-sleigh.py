# %% [markdown]
# # The Chaplygin sleigh with an offset centre of mass
#
# The sledge of section 3 has its centre of mass over the contact point. Move
# the centre of mass a distance $b$ forward along the runner and you have the
# Chaplygin sleigh. The reduction still applies; what changes?

# %% [markdown] statement
# The knife edge at $(x, y)$ cannot slide sideways, $\dot y = \dot x\tan\theta$;
# the centre of mass lies a distance $b$ ahead of it along the runner; $m$ is
# the mass, $J$ the moment of inertia about the centre of mass, and a torsional
# spring $-\tfrac12 k^2\theta^2$ acts as on the sledge. The library has it as
# `wt.examples.offset_sleigh()`; with $b = 0$ it is the sledge.
# Take $q_\varepsilon = x$, $\theta' = d\theta/dx$.
# **Assumptions:** $m, J, k, b > 0$; the sleigh moves with $\dot x > 0$; $|\theta| < \pi/2$.
#
# 1. `L_star`: the reduced Lagrangian (1.16) (you may use the library's reduction).
# 2. `J_eff`: $L^{\ast}$ is the sledge's (3.7) with $J$ replaced by another moment of inertia.
#    Which? What is it physically?
# 3. `P_star`: $(\partial L/\partial\dot y)^{\ast}$ of (1.26), in $\theta'$, $\theta$ and $h$.
# 4. `odd_part`: from $\theta''$ solved from (1.26), the part odd in $\theta'$,
#    $\tfrac12[\theta''(\theta', \theta) - \theta''(-\theta', \theta)]$. What does it say
#    about the mirrored path $\theta(-x)$?

# %% exercise
EXERCISE = {
    "title": "The Chaplygin sleigh with an offset centre of mass",
    "equations": "1.16, 1.26",
    "solvers": True,     # the statement gives the reduction to work with
    "symbols": "x xdot+ y ydot theta thetadot thetaprime thetaprimeprime h m+ J+ k+ b+ Jeff+",
    "domain": {"x": "real", "xdot": "speed", "theta": "angle", "thetadot": "slope",
               "ydot": "slope", "thetaprime": "slope", "h": "energy"},
    "conditions": ["2*h - k^2*theta^2"],
    "parts": {
        "L_star": {
            "what": "L* (1.16) for the offset sleigh, xdot > 0", "points": 1,
            "variables": "theta thetaprime h m J k b",
            "sign_note": "the direction of travel is xdot > 0, so take the root with the + sign",
            "why_not": {"xdot": "put xdot from (1.12)", "thetadot": "use theta'"},
            "success": "L* is the sledge's (3.7) with J replaced by J + m b^2."},
        "J_eff": {
            "what": "the moment of inertia that replaces J in the sledge's L* (3.7)",
            "points": 1, "variables": "m J b",
            "success": "J + m b^2: the moment of inertia about the contact point (parallel "
                       "axes)."},
        "P_star": {
            "what": "(dL/d ydot)* in theta', theta and h", "points": 1,
            "variables": "theta thetaprime h m J k b",
            "sign_note": "the direction of travel is xdot > 0, so take the root with the + sign",
            "why_not": {"xdot": "put xdot from (1.12)", "thetadot": "use theta'",
                        "ydot": "use the constraint"},
            "success": "(dL/d ydot)* carries the offset b: the constraint term of (1.26) is "
                       "where the sleigh differs from a sledge with J + m b^2."},
        "odd_part": {
            "what": "the part of theta'' odd in theta': (theta''(theta') - theta''(-theta'))/2",
            "points": 2, "variables": "theta thetaprime h m J k b",
            "success": "The odd part is proportional to b: theta' -> -theta' is the same as "
                       "b -> -b. The sledge's mirrored path theta(-x) is again a path; the "
                       "sleigh's is the path of a sleigh with its centre of mass behind the "
                       "knife edge."},
    },
}

# %%
from whittaker_teach.notebook import setup; setup()

# %%
import sympy as sp
import whittaker_teach as wt
from whittaker_teach.exercises import check

sleigh = wt.examples.offset_sleigh()
red = sleigh.reduce("x", direction=+1)
m, J, k, b = sp.symbols("m J k b", positive=True)
x = red.independent
theta, thetaprime, h = sp.symbols("theta thetaprime h")
# the reduction's notation theta(x), d theta(x)/dx -> plain symbols theta, thetaprime
theta_x = sp.Function("theta")(x)
to_plain = {theta_x.diff(x): thetaprime, theta_x: theta}
sleigh.lagrangian

# %%
sleigh.constraints

# %% [markdown]
# The reduction's results are in the notation $\theta(x)$,
# $\frac{d}{dx}\theta(x)$; the check accepts them as they are, or rewritten
# with the plain symbols `theta`, `thetaprime` (`expr.xreplace(to_plain)`).
#
# ## 1. $L^{\ast}$

# %%
### BEGIN SOLUTION
L_star = red.L_star
### END SOLUTION
### PLACEHOLDER: L_star = None  # your answer here
L_star

# %%
check("chaplygin-sleigh", L_star, part="L_star")

# %% [markdown]
# ## 2. The moment of inertia in $L^{\ast}$

# %%
### BEGIN SOLUTION
L_star_squared = sp.expand(L_star.xreplace(to_plain)**2)
J_eff = sp.factor(L_star_squared.coeff(thetaprime, 2)/(2*h - k**2*theta**2))
### END SOLUTION
### PLACEHOLDER: J_eff = None  # your answer here: in m, J and b
J_eff

# %% [markdown] solution
# $L^{\ast}$ has $J\theta'^2 + mb^2\theta'^2$ where the sledge has $J\theta'^2$:
# $J_\text{eff} = J + mb^2$, the moment of inertia about the contact point
# (parallel axes). Along the constraint the term
# $mb\dot\theta(\dot y\cos\theta - \dot x\sin\theta)$ of $L$ vanishes, so $\tilde L$, $\Omega$ and $L^{\ast}$ are
# those of a sledge with $J + mb^2$.

# %%
check("chaplygin-sleigh", J_eff, part="J_eff")

# %% [markdown]
# ## 3. $(\partial L/\partial\dot y)^{\ast}$

# %%
### BEGIN SOLUTION
t = sp.Symbol("t")
xt, thetat, yt = sleigh.coordinates
# dL/dydot, with the constraint (1.3)
P = sleigh.lagrangian.diff(yt.diff(t)).subs(sleigh.constraints)
display(P)
xdot = sp.Symbol("xdot", positive=True)
P = P.subs({thetat.diff(t): xdot*thetaprime, xt.diff(t): xdot})     # (1.5)
P = P.subs(thetat, theta)
P_star = P.subs(xdot, red.velocity.xreplace(to_plain))            # (1.12)
### END SOLUTION
### PLACEHOLDER: P_star = None  # your answer here
P_star

# %%
check("chaplygin-sleigh", P_star, part="P_star")

# %% [markdown]
# ## 4. The part of $\theta''$ odd in $\theta'$

# %%
### BEGIN SOLUTION
theta_pp = list(red.accelerations().values())[0].xreplace(to_plain)
odd_part = sp.factor((theta_pp - theta_pp.subs(thetaprime, -thetaprime))/2)
### END SOLUTION
### PLACEHOLDER: odd_part = None  # your answer here
odd_part

# %% [markdown] solution
# The odd part is proportional to $b$, and the rest of $\theta''$ contains $b$
# only through $J + mb^2$: changing the sign of $\theta'$ is the same as changing
# the sign of $b$. Mirroring a path, $\theta(x) \to \theta(-x)$ (the path turned
# by $180^\circ$, so that the runner's front becomes its back), maps solutions to
# solutions for the sledge ($b = 0$); for the sleigh it gives the path of a sleigh
# whose centre of mass is *behind* the knife edge. The sleigh knows its front
# from its back, and the constraint term of (1.26), through
# $(\partial L/\partial\dot y)^{\ast}$, which carries $b$, is where it does: that is why
# it is not a sledge with $J + mb^2$ although its $L^{\ast}$ is. (It is not a failure
# of time reversal: the library gives the same equation for $\dot x < 0$,
# `sleigh.reduce("x", -1)`.)

# %%
check("chaplygin-sleigh", odd_part, part="odd_part")
