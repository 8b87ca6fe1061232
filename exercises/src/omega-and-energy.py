# %% [markdown]
# # Ω and the energy integral for the rolling disk
#
# The first two steps of every reduction: rewrite $\tilde L$ with the new
# independent coordinate (1.5), (1.6), and solve the energy integral (1.13)
# for the velocity of that coordinate (1.12).

# %% [markdown] statement
# A vertical disk of mass $m$ and radius $R$ rolls without slipping on a
# horizontal plane: $(x, y)$ is its contact point, $\psi$ its heading and
# $\theta$ its rolling angle; $A$ and $C$ are its moments of inertia about
# the rolling axis and the vertical, and a spring of stiffness $k^2$ acts on
# the heading:
#
# $$L = \tfrac12 m(\dot x^2 + \dot y^2) + \tfrac12 A\dot\theta^2 + \tfrac12 C\dot\psi^2 -
#   \tfrac12 k^2\psi^2,$$
#
# $$\dot x = R\dot\theta\cos\psi,\qquad \dot y = R\dot\theta\sin\psi .$$
#
# The constraints are of Chaplygin type (1.3) and homogeneous of degree one
# (1.10). Take the rolling angle as the independent coordinate:
# $q_\varepsilon = \theta$, $\psi' = d\psi/d\theta$ (1.5).
# **Assumptions:** $m, R, A, C, k > 0$; the disk rolls forward, $\dot\theta > 0$;
# $\theta$ and $\psi$ are any angles (with $2h - k^2\psi^2 > 0$), $\psi'$ any real number.
#
# 1. `Omega`: $\Omega(\psi', \dot\theta, \psi)$ (1.6): $\tilde L$ with $\dot\psi = \dot\theta\,\psi'$.
# 2. `energy`: the left-hand side of the energy integral (1.13),
#    $\dot\theta\,\partial\Omega/\partial\dot\theta - \Omega$.
# 3. `thetadot`: (1.13) $= h$ solved for $\dot\theta > 0$ (1.12).
#
# Answer with SymPy expressions in the symbols defined below (or strings; `psi'`
# stands for $\psi'$).

# %% exercise
EXERCISE = {
    "title": "Omega and the energy integral for the rolling disk",
    "equations": "1.5, 1.6, 1.12, 1.13",
    "solvers": False,
    "symbols": "theta thetadot+ psi psiprime psidot h m+ R+ A+ C+ k+",
    "domain": {"theta": "real", "thetadot": "speed", "psi": "real", "psiprime": "slope",
               "psidot": "slope", "h": "energy"},
    "conditions": ["2*h - k^2*psi^2"],
    "parts": {
        "Omega": {
            "what": "Omega (1.6): L~ with psidot = thetadot psi'", "points": 1,
            "variables": "thetadot psi psiprime m R A C k",
            "why_not": {"psidot": "use (1.5): psidot = thetadot psi'",
                        "h": "Omega is L~, not the energy"},
            "success": "Omega = thetadot^2 (A + m R^2 + C psi'^2)/2 - k^2 psi^2/2 (1.6)."},
        "energy": {
            "what": "the left-hand side of (1.13), thetadot dOmega/dthetadot - Omega",
            "points": 1, "variables": "thetadot psi psiprime m R A C k",
            "why_not": {"psidot": "use (1.5): psidot = thetadot psi'",
                        "h": "give the left-hand side of (1.13); its value is h"},
            "success": "The energy (1.13): kinetic plus potential, written with psi'."},
        "thetadot": {
            "form": "sqrt(2*h - k^2*psi^2)/sqrt(A + m*R^2 + C*psiprime^2)",
            "what": "thetadot (1.12): (1.13) solved for thetadot > 0", "points": 1,
            "variables": "psi psiprime h m R A C k",
            "sign_note": "the disk rolls forward, thetadot > 0: take the + root",
            "why_not": {"thetadot": "solve (1.13) for thetadot",
                        "psidot": "use (1.5): psidot = thetadot psi'"},
            "success": "thetadot = sqrt(2h - k^2 psi^2)/sqrt(A + m R^2 + C psi'^2) (1.12)."},
    },
}

# %%
from whittaker_teach.notebook import setup; setup()

# %%
import sympy as sp
from whittaker_teach.exercises import check

m, R, A, C, k = sp.symbols("m R A C k", positive=True)
thetadot = sp.Symbol("thetadot", positive=True)   # direction of travel
xdot, ydot, psi, psidot, psiprime, h = sp.symbols(
    "xdot ydot psi psidot psiprime h")
L = (m/2*(xdot**2 + ydot**2) + A/2*thetadot**2 + C/2*psidot**2
     - k**2*psi**2/2)
constraints = {xdot: R*thetadot*sp.cos(psi), ydot: R*thetadot*sp.sin(psi)}
L

# %% [markdown]
# ## 1. $\Omega$ (1.6)
#
# First $\tilde L$: $L$ with the constraints substituted; then (1.5).

# %%
### BEGIN SOLUTION
Ltilde = sp.simplify(L.subs(constraints))
Omega = Ltilde.subs(psidot, thetadot*psiprime)               # (1.6)
### END SOLUTION
### PLACEHOLDER: Omega = None  # your answer here: in thetadot, psi and psiprime
Omega

# %%
check("omega-and-energy", Omega, part="Omega")

# %% [markdown]
# ## 2. The energy integral (1.13)

# %%
### BEGIN SOLUTION
energy = sp.expand(thetadot*Omega.diff(thetadot) - Omega)    # (1.13)
### END SOLUTION
### PLACEHOLDER: energy = None  # your answer here: thetadot*dOmega/dthetadot - Omega
energy

# %% [markdown] solution
# $\Omega$ is a quadratic polynomial $A_2\dot\theta^2 + A_0$ in $\dot\theta$,
# so (1.13) is $A_2\dot\theta^2 - A_0$: the kinetic energy plus the potential
# energy, as it must be.

# %%
check("omega-and-energy", energy, part="energy")

# %% [markdown]
# ## 3. $\dot\theta$ from (1.13) (1.12)

# %%
### BEGIN SOLUTION
v = sp.Symbol("v")                            # thetadot without its sign
roots = sp.solve(sp.Eq(energy.subs(thetadot, v), h), v)
thetadot_sol, = [s for s in roots if not s.could_extract_minus_sign()]
### END SOLUTION
### PLACEHOLDER: thetadot_sol = None  # your answer here: in psi, psiprime and h
thetadot_sol

# %% [markdown] solution
# The energy fixes only $\dot\theta^2$; rolling forward picks the $+$ root.
# The library's reduction gives the same (`velocity` is (1.12)):

# %% solution
import whittaker_teach as wt
wt.examples.rolling_disk().reduce("theta", direction=+1).velocity

# %%
check("omega-and-energy", thetadot_sol, part="thetadot")
