# %% [markdown]
# # Is the fast sleigh stiff?
#
# *Level: standard (about 30 minutes). Chapter 8, "A stiff scene", and chapter 15.*
#
# A problem is stiff when a mode that *decays* fast holds an explicit method's step
# down by stability, long after the mode has died out. You diagnose it for the offset
# sleigh at speed, with pencil, numpy and one fixed-step run.

# %% [markdown] statement
# **Assumptions:** the offset sleigh of chapter 3, its equations of motion (1.4) with
# the constraint of a runner whose contact point is a distance $b$ behind the centre of
# mass; no friction.
#
# **Model.** The heading of the offset sleigh, from (1.4) (chapter 7), obeys
# $(J + mb^2)\,\ddot\theta + b\,m\,v\,\dot\theta + k^2\theta = 0$, with $v$ its speed
# along the runner. Take $b = 1$, $m = J = k = 1$ and the speed frozen at its initial
# value $v = 50$ (chapter 8's fast sleigh at half its speed: $\theta_0 = 0.3$,
# $\dot\theta_0 = 0$, $\dot x_0 = 50\cos 0.3$; over $0 \le t \le 300$ the speed changes
# by less than $10^{-4}$ of itself: the heading's energy, 0.045, is all it can gain).
#
# **Method.** The classical Runge–Kutta method RK4 with a fixed step $\Delta t$. On
# $\dot u = \lambda u$ one step multiplies $u$ by $R(\lambda\Delta t)$,
# $R(z) = 1 + z + z^2/2 + z^3/6 + z^4/24$; it is stable on a real $\lambda < 0$ while
# $|R(\lambda\Delta t)| \le 1$, that is while $|\lambda|\Delta t \le \beta$, with
# $\beta$ the real stability interval of RK4 (`fs.stability_interval("rk4")`).
#
# 1. `rate`: the fastest decay rate $r = \max(-\lambda)$ over the two roots $\lambda$ of
#    the characteristic equation of the heading equation.
# 2. `steps`: the fewest equal steps $N$ of RK4 over $0 \le t \le 300$ with
#    $r\,\Delta t \le \beta$ ($\Delta t = 300/N$).
# 3. `method`: for this scene at a tolerance of $10^{-6}$, which class of method do you
#    use? One of `"implicit"` (an implicit or switching method: Radau, BDF, LSODA),
#    `"explicit"` (a high-order explicit method, such as DOP853), `"tighter"` (any
#    method with a tighter tolerance).
#
# `rate` within a relative $10^{-8}$; `steps` exactly.

# %% exercise
EXERCISE = {
    "title": "Is the fast sleigh stiff?",
    "equations": "1.4",
    "solvers": True,
    "symbols": "",
    "parts": {
        "rate": {
            "what": "the fastest decay rate of the heading equation at v = 50",
            "points": 1, "rtol": 1e-08,
            "wrong": [["49.9899979991996", "That is the rate at v = 100, the chapter's fast "
                                           "sleigh; this exercise runs it at v = 50."],
                      ["49.97999199359359", "The heading's inertia about the contact point "
                                            "is J + m b^2, not J: see the characteristic "
                                            "equation."]],
            "success": "The heading is overdamped: one mode dies at this rate, the other "
                       "relaxes a thousand times more slowly."},
        "steps": {
            "what": "the fewest equal RK4 steps over [0, 300] keeping rate * dt within "
                    "RK4's real stability interval",
            "points": 2,
            "wrong": [["2690", "rate * dt must not exceed beta: round the number of steps "
                               "up, not down."],
                      ["5385", "That is the count at v = 100, the chapter's fast sleigh; this "
                               "exercise runs it at v = 50."],
                      ["5384", "Check your rate first (part 1): this count belongs to another "
                               "rate."]],
            "success": "Thousands of steps, whatever the accuracy asked for: that is "
                       "stiffness."},
        "method": {
            "what": "the class of method for this scene", "points": 1,
            "choices": {
                "implicit": [["an implicit method", "switching", "implicit or switching",
                              "radau", "bdf", "lsoda"],
                             "An implicit method is stable on a decaying mode at any step: "
                             "once the fast mode has died, its step follows the slow one."],
                "explicit": [["dop853", "high order", "explicit method"],
                             "An explicit method of any order has a bounded stability "
                             "interval: its step stays below it even after the fast mode "
                             "has died out."],
                "tighter": [["smaller tolerance", "tighter tolerance", "rtol"],
                            "The step is held by stability, not by accuracy: a tighter "
                            "tolerance costs more and changes nothing of that."]}},
    },
}

# %%
from whittaker_teach.notebook import setup; setup()

# %%
import math

import numpy as np

from whittaker_teach.exercises import check
from whittaker_teach.numerics import fixed_step as fs

b, m, J, k, v = 1.0, 1.0, 1.0, 1.0, 50.0
T = 300.0
beta = fs.stability_interval("rk4")
print(f"RK4's real stability interval: beta = {beta:.10f}")

# %% [markdown]
# ## 1. The modes

# %%
### BEGIN SOLUTION
roots = np.roots([J + m*b**2, b*m*v, k**2])         # (J + m b^2) l^2 + b m v l + k^2 = 0
rate = float(max(-roots.real))
### END SOLUTION
### PLACEHOLDER: rate = None  # your answer here: the larger of the two decay rates
rate

# %%
check("stiff-sleigh", rate, part="rate")

# %% [markdown]
# ## 2. What stability costs RK4

# %%
### BEGIN SOLUTION
steps = math.ceil(T*rate/beta)
### END SOLUTION
### PLACEHOLDER: steps = None  # your answer here: an integer
steps

# %%
check("stiff-sleigh", steps, part="steps")

# %% [markdown] solution
# The bound is sharp: RK4 on the heading equation with $N$ steps stays bounded, with
# 2 % fewer steps it blows up, although the fast mode has died out within the first
# time unit (the slow mode, rate about 0.02, is all that is left):

# %% solution
def heading(t, u):
    return np.array([u[1], -(b*m*v*u[1] + k**2*u[0])/(J + m*b**2)])


for N in (steps, int(0.98*steps)):
    t, U, nfev = fs.integrate(heading, (0.0, T), [0.3, 0.0], N, "rk4")
    print(f"N = {N}: rate*dt = {rate*T/N:.4f}, |theta(300)| = {abs(U[-1, 0]):.3e}")

# %% [markdown]
# ## 3. Which method

# %%
### BEGIN SOLUTION
method = "implicit"
### END SOLUTION
### PLACEHOLDER: method = None  # your answer here: "implicit", "explicit" or "tighter"
method

# %%
check("stiff-sleigh", method, part="method")

# %% [markdown] solution
# Chapter 8 measures it on the full model at $v = 100$: DOP853 needs about 28,000
# evaluations at every tolerance from $10^{-3}$ to $10^{-6}$, LSODA a few hundred, and
# `simulate(..., tol=1e-6)` detects the fast mode from the Jacobian at the start and
# picks LSODA. At $v = 50$ the library's test sees the same (the Jacobian of the full
# model at the start, and DOP853's stability floor over the span):

# %% solution
import whittaker_teach as wt
from whittaker_teach.numerics.scene import stiffness

print(stiffness(wt.examples.offset_sleigh(), {"x": 0.0, "theta": 0.3, "y": 0.0},
                {"x": v*math.cos(0.3), "theta": 0.0}, (0.0, T),
                {"m": m, "J": J, "k": k, "b": b}))
