# %% [markdown]
# # The identity (1.19)
#
# The heart of the reduction is that $L^{\ast}$ (1.16), though built from
# $\partial\Omega/\partial\dot q_\varepsilon$, has the derivatives (1.19)-(1.21)
# that make (1.4) turn into (1.26). Here you follow the paper's route to (1.19)
# for one concrete $\Omega$, with a term linear in the velocity.

# %% [markdown] statement
# Take $q_\varepsilon = x$, one remaining coordinate $\theta$ with
# $\theta' = d\theta/dx$, and
#
# $$\Omega = \tfrac12\dot x^2\,(m + J\theta'^2) + b\,\dot x\,\theta'\cos\theta - \tfrac12 k^2\theta^2 .$$
#
# In (1.14)-(1.19), $\dot x$ stands for the root $\dot x(\theta', \theta, h)$ of
# the energy integral (1.13); keep it as the symbol `xdot`.
# **Assumptions:** $m, J, b, k > 0$; $\dot x > 0$; $\theta$ is any angle and
# $\theta'$ any real number (your answers must hold all round the circle).
#
# 1. `dxdot_dthetaprime`: solve (1.14) for $\partial\dot x/\partial\theta'$:
#    $\dot x\,\Omega_{\dot x\dot x}\,\dfrac{\partial\dot x}{\partial\theta'} +
#    \dot x\,\Omega_{\dot x\theta'} - \Omega_{\theta'} = 0$.
# 2. `dLstar_dthetaprime`: $\partial L^{\ast}/\partial\theta'$ from (1.17),
#    $\Omega_{\dot x\dot x}\,\dfrac{\partial\dot x}{\partial\theta'} + \Omega_{\dot x\theta'}$,
#    with step 1 substituted, and simplified.
#
# Which of the paper's identities have you just proved for this $\Omega$? (Not
# checked: the solution says.)

# %% exercise
EXERCISE = {
    "title": "The identity (1.19)",
    "equations": "1.14, 1.17, 1.19",
    "solvers": False,
    "symbols": "x xdot+ theta thetaprime h m+ J+ b+ k+",
    "domain": {"x": "real", "xdot": "speed", "theta": "real", "thetaprime": "slope",
               "h": "energy"},
    "parts": {
        "dxdot_dthetaprime": {
            "what": "d xdot/d theta' solved from (1.14)", "points": 2,
            "variables": "xdot theta thetaprime m J b k",
            "why_not": {"h": "keep xdot as a symbol: it stands for qdot_eps(q', q, h) of (1.12)"},
            "success": "From (1.14): d xdot/d theta' = -xdot J theta'/(m + J theta'^2); "
                       "b drops out."},
        "dLstar_dthetaprime": {
            "what": "dL*/d theta' from (1.17), with (1.14) substituted", "points": 1,
            "variables": "xdot theta thetaprime m J b k",
            "why_not": {"h": "keep xdot as a symbol: it stands for qdot_eps(q', q, h) of (1.12)"},
            "success": "dL*/d theta' = J xdot theta' + b cos(theta) = (1/xdot) dOmega/d theta': "
                       "that is (1.19)."},
    },
}

# %%
from whittaker_teach.notebook import setup; setup()

# %%
import sympy as sp
from whittaker_teach.exercises import check

m, J, b, k = sp.symbols("m J b k", positive=True)
xdot = sp.Symbol("xdot", positive=True)
theta, thetaprime, h = sp.symbols("theta thetaprime h")
Omega = (xdot**2/2*(m + J*thetaprime**2) + b*xdot*thetaprime*sp.cos(theta)
         - k**2*theta**2/2)
Omega

# %% [markdown]
# ## 1. $\partial\dot x/\partial\theta'$ from (1.14)
#
# Write the unknown derivative as a symbol, e.g. `dv = sp.Symbol("dv")`, and solve.

# %%
### BEGIN SOLUTION
dv = sp.Symbol("dv")
eq_114 = (xdot*Omega.diff(xdot, 2)*dv + xdot*Omega.diff(xdot, thetaprime)
          - Omega.diff(thetaprime))                             # (1.14)
dxdot_dthetaprime, = sp.solve(eq_114, dv)
### END SOLUTION
### PLACEHOLDER: dxdot_dthetaprime = None  # your answer here: in xdot, theta, thetaprime
dxdot_dthetaprime

# %% [markdown] solution
# The term $b\,\dot x\,\theta'\cos\theta$ drops out: being linear in $\dot x$, it
# contributes $b\cos\theta$ to $\dot x\,\Omega_{\dot x\theta'}$ and the same to
# $\Omega_{\theta'}$.

# %%
check("identity-1-19", dxdot_dthetaprime, part="dxdot_dthetaprime")

# %% [markdown]
# ## 2. $\partial L^{\ast}/\partial\theta'$ from (1.17), and (1.19)

# %%
### BEGIN SOLUTION
dLstar_dthetaprime = sp.expand(Omega.diff(xdot, 2)*dxdot_dthetaprime
                               + Omega.diff(xdot, thetaprime))     # (1.17)
# (1.19):
assert sp.simplify(dLstar_dthetaprime - Omega.diff(thetaprime)/xdot) == 0
### END SOLUTION
### PLACEHOLDER: dLstar_dthetaprime = None  # your answer here: in xdot, theta, thetaprime
dLstar_dthetaprime

# %% [markdown] solution
# It equals $\dfrac{1}{\dot x}\dfrac{\partial\Omega}{\partial\theta'}
# = J\dot x\theta' + b\cos\theta$: that is (1.19). As a cross-check, build $L^{\ast}$
# itself: the energy (1.13) is $\tfrac12\dot x^2(m + J\theta'^2) + \tfrac12 k^2\theta^2 = h$
# (the linear term cancels), and $L^{\ast} = \partial\Omega/\partial\dot x$ at its root;
# differentiating $L^{\ast}$ directly gives the same thing once $\dot x$ is put back.

# %% solution
v = sp.Symbol("v")
energy = sp.expand(xdot*Omega.diff(xdot) - Omega)
xdot_root, = [s for s in sp.solve(sp.Eq(energy.subs(xdot, v), h), v)
              if not s.could_extract_minus_sign()]
L_star = Omega.diff(xdot).subs(xdot, xdot_root)               # (1.16)
direct = L_star.diff(thetaprime)
sp.simplify(direct - dLstar_dthetaprime.subs(xdot, xdot_root))

# %%
check("identity-1-19", dLstar_dthetaprime, part="dLstar_dthetaprime")
