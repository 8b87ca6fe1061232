# %% [markdown]
# # The order of a method, measured
#
# *Level: standard (about 30 minutes). Chapter 15, "A fixed-step order study".*
#
# An adaptive integrator changes its step with the tolerance, so its work-precision
# line does not show its order (chapter 7). With a **fixed** step $\Delta t$, a method
# of order $p$ has a global error close to $c\,\Delta t^p$: halving the step divides
# the error by about $2^p$. Here you measure $p$ for two methods on the sledge,
# against its exact solution.

# %% [markdown] statement
# **Assumptions:** the sledge of section 3: a runner whose contact point moves only
# along it (the non-holonomic constraint $\dot y\cos\theta - \dot x\sin\theta = 0$), a
# torsion spring $k^2$ on the heading $\theta$, no friction; the speed $C$ along the runner
# is then constant.
#
# **Model.** The sledge of section 3 in the form that (3.12)–(3.15) solve: the state
# $u = (\theta, \dot\theta, x, y)$ with
# $\ddot\theta = -(k^2/J)\,\theta$ (3.14), $\dot x = C\cos\theta$ (3.12),
# $\dot y = C\sin\theta$ (3.13), $C$ constant; `fs.sledge_rhs(params, C)` below is this
# right-hand side. $m = J = k = 1$, $C = 1$, from $\theta = 0$, $\dot\theta = 0.5$,
# $x = y = 0$ at $t = 0$, up to $T = 20$. The exact motion is $\theta = 0.5\sin t$,
# with $x$ and $y$ from (3.15): `wt.examples.sledge_exact(params, a=0.5,
# phi=-pi/2, C=1)`.
#
# **Methods.** `fs.integrate(f, (0, T), u0, N, method)`: $N$ equal steps
# $\Delta t = T/N$ of the classical Runge–Kutta method (`"rk4"`, four evaluations a
# step) or of the explicit midpoint rule (`"midpoint"`, two), with no step-size
# control; the result at $T$ is the state after the last step.
#
# **Error measure** (chapter 7's): the largest, over $\theta$, $x$, $y$, of the
# absolute error at $t = T$ divided by the component's scale along the exact motion:
# $s_\theta = 0.5$, and $s_x$, $s_y$ the largest $|x|$, $|y|$ of the exact motion at
# the 401 times $t = 20\,i/400$, $i = 0, \dots, 400$.
#
# 1. `error_rk4`: the error of RK4 with $N = 300$ steps.
# 2. `order_rk4`: the observed order of RK4,
#    $\log_2\big(e(N{=}300)/e(N{=}600)\big)$.
# 3. `order_midpoint`: the observed order of the midpoint rule, from the same two
#    step numbers.
#
# Answers within a relative $10^{-4}$ are accepted.

# %% exercise
EXERCISE = {
    "title": "The order of a method, measured",
    "equations": "3.12, 3.13, 3.14, 3.15",
    "solvers": True,
    "symbols": "",
    "parts": {
        "error_rk4": {
            "what": "the relative error at t = 20 of RK4 with N = 300 fixed steps",
            "points": 1, "rtol": 1e-04,
            "wrong": [["1.409482393466277e-6",
                       "That is an absolute error: the measure divides each component's "
                       "error by its scale before taking the largest."]],
            "success": "That is RK4's error with 300 steps (dt = 1/15)."},
        "order_rk4": {
            "what": "the observed order of RK4 from N = 300 and N = 600 steps",
            "points": 2, "rtol": 1e-04,
            "wrong": [["4", "4 is RK4's order in theory; the question asks for the order "
                            "observed: log2 of the ratio of your two errors."],
                      ["4.080460019163207", "That is the order of theta's error alone: the "
                       "error measure is, at each N, the largest of the three scaled errors "
                       "(it is not the same component at N = 300 and at N = 600)."],
                      ["3.9810556864856346", "That is the order of one component's error "
                       "(or of unscaled errors): the error measure is, at each N, the largest "
                       "of the three scaled errors."]],
            "success": "Close to 4, the order of the classical Runge-Kutta method: halving "
                       "the step divides the error by about 16."},
        "order_midpoint": {
            "what": "the observed order of the midpoint rule from N = 300 and N = 600 steps",
            "points": 1, "rtol": 1e-04,
            "wrong": [["2", "2 is the midpoint rule's order in theory; the question asks "
                            "for the order observed from your two errors."]],
            "success": "Close to 2: the explicit midpoint rule has order 2."},
    },
}

# %%
from whittaker_teach.notebook import setup; setup()

# %%
import math

import whittaker_teach as wt
from whittaker_teach.exercises import check
from whittaker_teach.numerics import fixed_step as fs

params = {"m": 1.0, "J": 1.0, "k": 1.0}
T = 20.0
exact = wt.examples.sledge_exact(params, a=0.5, phi=-math.pi/2, C=1.0)
f = fs.sledge_rhs(params, C=1.0)
u0 = [0.0, 0.5, 0.0, 0.0]                 # theta, thetadot, x, y
print(exact(T))                           # the exact state at T, a dict

# %% [markdown]
# ## 1. One run
#
# Write the error measure as a function `error(method, N)` (you will need it three more
# times), then run it once.

# %%
### BEGIN SOLUTION
grid = [exact(T*i/400) for i in range(401)]
scale = {"theta": 0.5, "x": max(abs(g["x"]) for g in grid),
         "y": max(abs(g["y"]) for g in grid)}
end = exact(T)


def error(method, N):
    """The relative error at t = T of N fixed steps of method."""
    t, U, nfev = fs.integrate(f, (0.0, T), u0, N, method)
    last = dict(zip(("theta", "thetadot", "x", "y"), U[-1]))
    return max(abs(last[c] - end[c])/scale[c] for c in ("theta", "x", "y"))


error_rk4 = error("rk4", 300)
### END SOLUTION
### PLACEHOLDER: error = None  # your error measure here: a function error(method, N)
### PLACEHOLDER: error_rk4 = None  # your answer here: a number
error_rk4

# %%
check("fixed-step-order", error_rk4, part="error_rk4")

# %% [markdown]
# ## 2. Halve the step

# %%
### BEGIN SOLUTION
order_rk4 = math.log2(error("rk4", 300)/error("rk4", 600))
### END SOLUTION
### PLACEHOLDER: order_rk4 = None  # your answer here: log2 of the ratio of two errors
order_rk4

# %%
check("fixed-step-order", order_rk4, part="order_rk4")

# %% [markdown]
# ## 3. Another method

# %%
### BEGIN SOLUTION
order_midpoint = math.log2(error("midpoint", 300)/error("midpoint", 600))
### END SOLUTION
### PLACEHOLDER: order_midpoint = None  # your answer here
order_midpoint

# %%
check("fixed-step-order", order_midpoint, part="order_midpoint")

# %% [markdown] solution
# The whole ladder, with Euler too: the observed order settles on the method's order
# once the step is small enough for the leading error term to dominate. Euler, order
# 1, is still far from it at these steps: its heading's amplitude grows by
# $(1 + \Delta t^2)^{N/2} \approx e^{T\Delta t/2}$, an error that is linear in
# $\Delta t$ only once $T\Delta t/2 \ll 1$. Note also that the largest of the three
# scaled errors is $\theta$'s at $N = 300$ and $y$'s at $N = 600$: the observed order
# of the error measure is not that of any one component.

# %% solution
for method in ("euler", "midpoint", "rk4"):
    errs = [error(method, N) for N in (150, 300, 600, 1200)]
    orders = [math.log2(a/b) for a, b in zip(errs, errs[1:])]
    print(f"{method:8s} errors " + " ".join(f"{e:.2e}" for e in errs)
          + "   observed orders " + " ".join(f"{p:.3f}" for p in orders))
