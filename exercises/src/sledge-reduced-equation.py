# %% [markdown]
# # The sledge's reduced equation, and a misprint
#
# Section 3 of Mei (1983) ends with the reduced equation (3.10) of the sledge,
# a second-order equation for its path $\theta(x)$. One coefficient of (3.10),
# as printed, is wrong. Derive the equation and find it.

# %% [markdown] statement
# For the sledge of section 3 ($q_\varepsilon = x$, $\theta' = d\theta/dx$) you
# are given the reduced Lagrangian $L^{\ast}$ (3.7), the reduced constraint
# $\dot y^{\ast} = \tan\theta$ (3.8) and $(\partial L/\partial\dot y)^{\ast} = m\dot y$ in
# $\theta'$, $\theta$ and $h$ (see the exercises *sledge-L-star* and
# *constraint-star*). The paper prints (3.10) as
#
# $$\begin{aligned}
# J(2h - k^2\theta^2)\theta'' &+ J\big[-(2h - k^2\theta^2)\tan\theta + k^2\theta\big]\theta'^2\\
#   &+ m k\,\theta\,(1 + \tan^2\theta) = 0 .
# \end{aligned}$$
#
# **Assumptions:** $m, J, k > 0$; the sledge moves with $\dot x > 0$; $|\theta| < \pi/2$;
# $2h - k^2\theta^2 > 0$.
#
# 1. `theta_pp`: the generalized Whittaker equation (1.26), (3.9), solved for $\theta''$.
# 2. `last_term`: multiply $\theta'' - \theta''(\theta', \theta)$ by $J(2h - k^2\theta^2)$,
#    as (3.10) does, and give the term free of $\theta'$ and $\theta''$. Which printed
#    coefficient is wrong?

# %% exercise
EXERCISE = {
    "title": "The sledge's reduced equation and a misprint",
    "equations": "1.26, 3.9, 3.10",
    "solvers": False,
    "symbols": "x xdot+ y ydot theta thetadot thetaprime thetaprimeprime h m+ J+ k+",
    "domain": {"x": "real", "xdot": "speed", "theta": "angle", "thetadot": "slope",
               "ydot": "slope", "thetaprime": "slope", "h": "energy"},
    "conditions": ["2*h - k^2*theta^2"],
    "parts": {
        "theta_pp": {
            "form": "(J*thetaprime^2*(2*h*tan(theta) - k^2*theta^2*tan(theta) - k^2*theta) "
                    "- k^2*m*theta*(1 + tan(theta)^2))/(J*(2*h - k^2*theta^2))",
            "what": "theta'' solved from (1.26) for the sledge", "points": 2,
            "variables": "theta thetaprime h m J k",
            "why_not": {"thetaprimeprime": "solve (1.26) for theta''"},
            "success": "theta'' from (1.26); multiplied by J (2h - k^2 theta^2) it gives (3.10)."},
        "last_term": {
            "form": "m*k^2*theta*(1 + tan(theta)^2)",
            "what": "the term of (3.10) free of theta' and theta''", "points": 1,
            "variables": "theta h m J k",
            "wrong": [["m*k*theta*(1 + tan(theta)^2)",
                       "that is the coefficient as the paper prints it, m k theta "
                       "(1 + tan^2 theta): compare it with what (1.26) gives you"]],
            "why_not": {"thetaprime": "take the term free of theta'",
                        "thetaprimeprime": "take the term free of theta''"},
            "success": "The last term of (3.10) is m k^2 theta (1 + tan^2 theta): the printed "
                       "m k theta (1 + tan^2 theta) lacks a factor k (dimensions: k^2 theta is a "
                       "torque)."},
    },
}

# %%
from whittaker_teach.notebook import setup; setup()

# %%
import sympy as sp
from whittaker_teach.exercises import check

m, J, k = sp.symbols("m J k", positive=True)
x, theta, thetaprime, thetaprimeprime, h = sp.symbols(
    "x theta thetaprime thetaprimeprime h")
sec2 = 1 + sp.tan(theta)**2
R = 2*h - k**2*theta**2
L_star = sp.sqrt(R)*sp.sqrt(m*sec2 + J*thetaprime**2)              # (3.7)
ydot_star = sp.tan(theta)                                         # (3.8)
P_star = m*sp.tan(theta)*sp.sqrt(R)/sp.sqrt(m*sec2 + J*thetaprime**2)


def d_dx(f):
    """d/dx of f(theta', theta, x) along a path (2.1)."""
    return (f.diff(x) + f.diff(thetaprime)*thetaprimeprime
            + f.diff(theta)*thetaprime)

# %% [markdown]
# ## 1. The reduced equation (1.26), solved for $\theta''$

# %%
### BEGIN SOLUTION
bracket = d_dx(ydot_star.diff(thetaprime)) - ydot_star.diff(theta)
eq_126 = (d_dx(L_star.diff(thetaprime)) - L_star.diff(theta)
          - P_star*bracket)                                     # (1.26)
theta_pp, = sp.solve(eq_126, thetaprimeprime)
theta_pp = sp.factor(theta_pp)
### END SOLUTION
### PLACEHOLDER: theta_pp = None  # your answer here: theta'' in theta, thetaprime and h
theta_pp

# %%
check("sledge-reduced-equation", theta_pp, part="theta_pp")

# %% [markdown]
# ## 2. The cleared equation (3.10) and its last term

# %%
### BEGIN SOLUTION
cleared = sp.expand(sp.cancel(J*R*(thetaprimeprime - theta_pp)))
cleared = sp.collect(cleared, [thetaprimeprime, thetaprime], sp.factor)
display(cleared)
last_term = cleared.subs({thetaprimeprime: 0, thetaprime: 0})
### END SOLUTION
### PLACEHOLDER: last_term = None  # your answer here: the term free of theta' and theta''
last_term

# %% [markdown] solution
# The first two terms agree with the paper; the last is
# $m k^2\theta(1 + \tan^2\theta)$, not the printed $m k\,\theta(1 + \tan^2\theta)$.
# Two quick arguments for $k^2$: the spring's torque is $-\partial U/\partial\theta =
# -k^2\theta$, so $k$ appears only as $k^2$ everywhere else; and the paper's own
# first integral (3.11), $\theta' = \sqrt{(2h - mC^2 - k^2\theta^2)/J}\,/(C\cos\theta)$,
# satisfies the equation with $k^2$ and not the printed one:

# %% solution
C = sp.Symbol("C", positive=True)
F = sp.sqrt((2*h - m*C**2 - k**2*theta**2)/J)/(C*sp.cos(theta))   # (3.11)
along = {thetaprime: F, thetaprimeprime: F.diff(theta)*F}
printed = cleared - last_term + m*k*theta*sec2
sp.simplify(cleared.subs(along)), sp.simplify(printed.subs(along))

# %%
check("sledge-reduced-equation", last_term, part="last_term")
