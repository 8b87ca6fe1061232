# %% [markdown]
# # The Nielsen form
#
# Section 2 of Mei (1983) rewrites the generalized Whittaker equations in
# Nielsen's form (2.4), which needs only the total derivative $dL^{\ast}/dq_\varepsilon$
# (2.1) and partial derivatives. Here you do it for the Kepler problem.

# %% [markdown] statement
# The Kepler problem reduced with the polar angle as independent coordinate
# ($q_\varepsilon = \theta$, $r' = dr/d\theta$; see the exercise *kepler-orbit*)
# has the reduced Lagrangian
#
# $$L^{\ast} = \sqrt{2h + \frac{2m\mu}{r}}\;\sqrt{m(r^2 + r'^2)} .$$
#
# The system is holonomic, so the constraint terms of (1.26) and (2.4) are absent.
# **Assumptions:** $m, \mu > 0$, $r > 0$, $\dot\theta > 0$, $h + m\mu/r > 0$.
#
# 1. `total_derivative`: $dL^{\ast}/d\theta$ (2.1), with $r''$ appearing explicitly.
# 2. `nielsen`: the left-hand side of the Nielsen form (2.4),
#    $\dfrac{\partial}{\partial r'}\Big(\dfrac{dL^{\ast}}{d\theta}\Big) - 2\dfrac{\partial L^{\ast}}{\partial r}$.
#
# Then check that it agrees with the left-hand side of (1.26) (here (1.27)),
# $\dfrac{d}{d\theta}\dfrac{\partial L^{\ast}}{\partial r'} - \dfrac{\partial L^{\ast}}{\partial r}$.

# %% exercise
EXERCISE = {
    "title": "The Nielsen form",
    "equations": "2.1, 2.4, 1.26",
    "solvers": False,
    "symbols": "r+ rprime rprimeprime theta h m+ mu+",
    "domain": {"r": "positive", "rprime": "slope", "rprimeprime": "real", "theta": "turn",
               "h": "energy"},
    "conditions": ["h + m*mu/r"],
    "parts": {
        "total_derivative": {
            "what": "dL*/dtheta (2.1), with r'' in it", "points": 1,
            "variables": "r rprime rprimeprime h m mu",
            "success": "(2.1): dL*/dtheta = dL*/dr' r'' + dL*/dr r' (+ dL*/dtheta = 0 here)."},
        "nielsen": {
            "what": "the left-hand side of (2.4): d/dr'(dL*/dtheta) - 2 dL*/dr", "points": 2,
            "variables": "r rprime rprimeprime h m mu",
            "success": "(2.4) for the Kepler problem; it equals the left-hand side of (1.26)."},
    },
}

# %%
from whittaker_teach.notebook import setup; setup()

# %%
import sympy as sp
from whittaker_teach.exercises import check

m, mu = sp.symbols("m mu", positive=True)
r = sp.Symbol("r", positive=True)
theta, rprime, rprimeprime, h = sp.symbols("theta rprime rprimeprime h")
L_star = sp.sqrt(2*h + 2*m*mu/r)*sp.sqrt(m*(r**2 + rprime**2))
L_star

# %% [markdown]
# ## 1. The total derivative (2.1)
#
# $\dfrac{dL^{\ast}}{d\theta} = \dfrac{\partial L^{\ast}}{\partial r'}r'' + \dfrac{\partial L^{\ast}}{\partial r}r' +
# \dfrac{\partial L^{\ast}}{\partial\theta}$, with $r''$ treated as a separate symbol.

# %%
### BEGIN SOLUTION
total_derivative = (L_star.diff(rprime)*rprimeprime              # (2.1)
                    + L_star.diff(r)*rprime + L_star.diff(theta))
### END SOLUTION
### PLACEHOLDER: total_derivative = None  # your answer here: contains rprimeprime
total_derivative

# %%
check("nielsen-form", total_derivative, part="total_derivative")

# %% [markdown]
# ## 2. The Nielsen form (2.4)

# %%
### BEGIN SOLUTION
nielsen = total_derivative.diff(rprime) - 2*L_star.diff(r)       # (2.4)
### END SOLUTION
### PLACEHOLDER: nielsen = None  # your answer here: the left-hand side of (2.4)
nielsen

# %% [markdown] solution
# By (2.2), $\partial(dL^{\ast}/d\theta)/\partial r' = \dfrac{d}{d\theta}\dfrac{\partial L^{\ast}}{\partial r'} +
# \dfrac{\partial L^{\ast}}{\partial r}$, so (2.4) is (1.26) term for term. Checked:

# %% solution
def d_dtheta(f):
    return f.diff(theta) + f.diff(rprime)*rprimeprime + f.diff(r)*rprime


whittaker = d_dtheta(L_star.diff(rprime)) - L_star.diff(r)   # (1.26), (1.27)
sp.simplify(nielsen - whittaker)

# %%
check("nielsen-form", nielsen, part="nielsen")
