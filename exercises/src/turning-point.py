# %% [markdown]
# # Where x stops being a coordinate
#
# The reduction uses $x$ as the clock. That works only while $x$ keeps moving
# in one direction: where $\dot x = 0$ the change of variable (1.5),
# $\theta' = \dot\theta/\dot x$, breaks down. Here you find where that happens
# for the sledge, and what the numerical integration of the reduced model does there.

# %% [markdown] statement
# The sledge of section 3, reduced with $q_\varepsilon = x$ and $\dot x > 0$ (1.5), (1.12).
# Its motion in time is $\theta = a\cos(\omega t + \varphi)$ with $\omega = k/\sqrt J$
# (3.15), at the constant speed $C$; the reduced equation has the first integral
# $\theta' = \sqrt{(2h - mC^2 - k^2\theta^2)/J}\,/\,(C\cos\theta)$ (3.11).
# **Assumptions:** $m, J, k, C > 0$; the sledge starts with $\dot x > 0$.
#
# 1. `xdot`: put (3.11) in $\dot x$ from (3.5) and simplify (for $|\theta| < \pi/2$):
#    $\dot x$ along a motion, in $C$ and $\theta$.
# 2. `t_turn`: for the motion $\theta = a\sin(kt/\sqrt J)$ ($\theta = 0$ at $t = 0$) with
#    $a > \pi/2$, the first time $t > 0$ at which $x$ stops being usable.
# 3. `numerics`: for $m = J = k = C = 1$ and $a = 2$, integrate the reduced model with
#    `red.simulate` from $x = 0$ to $x = 5$ (default options). What does it do at that
#    point? Answer with one of `"ChartError"`, `"NaN"`, `"continues"`, `"switches"`.
# 4. `x_turn`: the value of $x$ (6 digits) where the sledge turns back, for those numbers.

# %% exercise
EXERCISE = {
    "title": "Where x stops being a coordinate",
    "equations": "1.5, 1.12, 3.12, 3.15",
    "solvers": True,
    "symbols": "x xdot+ theta thetaprime t h C+ a+ m+ J+ k+",
    "domain": {"x": "real", "xdot": "speed", "theta": "angle", "thetaprime": "slope",
               "t": [0.0, None], "h": "energy", "a": [1.5707963267948966, None]},
    "definitions": {"omega": "k/sqrt(J)"},
    "parts": {
        "xdot": {
            "what": "xdot along a motion of the sledge, in C and theta (from (3.5) and (3.11))",
            "points": 1, "variables": "C theta",
            "sign_note": "the direction of travel is xdot > 0, so take the root with the + sign",
            "why_not": {"thetaprime": "put theta' from the first integral (3.11)",
                        "h": "h drops out on the first integral"},
            "success": "xdot = C cos(theta) (3.12): x stops being usable where cos(theta) = 0."},
        "t_turn": {
            "what": "the first time t > 0 at which x stops being usable, for theta = "
                    "a sin(k t/sqrt(J)) with a > pi/2", "points": 1, "variables": "a J k",
            "why_not": {"C": "the turning point is where theta = pi/2, whatever C",
                        "theta": "give t in terms of a, J and k"},
            "success": "t = sqrt(J)/k asin(pi/(2a)): theta reaches pi/2 there, so xdot = "
                       "C cos theta vanishes and x turns back."},
        "numerics": {
            "what": "what red.simulate does (default options) when the path reaches the "
                    "turning point", "points": 1,
            "choices": {
                "ChartError": [["raises ChartError", "chart error", "raises", "error",
                                "whittaker_teach.ChartError"],
                               "The reduced model watches qdot_x and stops with a ChartError "
                               "that says where x turns back; on_turning_point='switch' "
                               "continues across it, in time."],
                "NaN": [["nan", "returns nan", "nans"],
                        "No: run red.simulate across the turning point and read what happens."],
                "continues": [["continues past it", "wrong values", "silently continues",
                               "nothing"],
                              "No: run red.simulate across the turning point and read what "
                              "happens."],
                "switches": [["switch", "switches chart", "switch to time"],
                             "Only when asked: that is on_turning_point='switch'; with the "
                             "default options, run red.simulate across the turning point and "
                             "read what happens."]}},
        "x_turn": {
            "what": "x where the sledge turns back, for m = J = k = C = 1, a = 2 (to 6 digits)",
            "points": 2, "rtol": 1e-06,
            "success": "x where xdot vanishes: the ChartError reports it, and the exact "
                       "solution sledge_exact agrees."},
    },
}

# %%
from whittaker_teach.notebook import setup; setup()

# %%
import math

import sympy as sp
import whittaker_teach as wt
from whittaker_teach.exercises import check

m, J, k, C, a = sp.symbols("m J k C a", positive=True)
theta, thetaprime, h, t = sp.symbols("theta thetaprime h t")
xdot_35 = (sp.sqrt(2*h - k**2*theta**2)
           / sp.sqrt(m*(1 + sp.tan(theta)**2) + J*thetaprime**2))
F_311 = sp.sqrt((2*h - m*C**2 - k**2*theta**2)/J)/(C*sp.cos(theta))

# the numbers of parts 3 and 4: theta = a sin(t), starting at x = 0 with xdot = C > 0
params = {"m": 1.0, "J": 1.0, "k": 1.0}
exact = wt.examples.sledge_exact(params, a=2.0, phi=-math.pi/2, C=1.0)
red = wt.examples.sledge().reduce("x", direction=+1)
# at x = 0: theta = 0, theta' = 2, h = 2.5
q0, qp0, h0 = exact.reduced_initial()

# %% [markdown]
# ## 1. $\dot x$ along a motion

# %%
### BEGIN SOLUTION
xdot_squared = sp.simplify((xdot_35**2).subs(thetaprime, F_311))
display(xdot_squared)
# the root with xdot > 0 while |theta| < pi/2:
xdot_motion = C*sp.cos(theta)
### END SOLUTION
### PLACEHOLDER: xdot_motion = None  # your answer here: in C and theta
xdot_motion

# %% [markdown] solution
# $\dot x = C\cos\theta$ (3.12), and with (3.2) $\dot y = C\sin\theta$ (3.13): the sledge
# moves at the constant speed $C$ along its axis. So $x$ is a good clock while
# $\cos\theta > 0$, and stops being one where $\theta$ reaches $\pm\pi/2$: the sledge
# then points along $Oy$ and $x$ turns back. That happens on a motion exactly when
# the amplitude $a \ge \pi/2$ (with $a = \pi/2$ only touching it).

# %%
check("turning-point", xdot_motion, part="xdot")

# %% [markdown]
# ## 2. When the sledge gets there

# %%
### BEGIN SOLUTION
roots = sp.solve(sp.Eq(a*sp.sin(k*t/sp.sqrt(J)), sp.pi/2), t)
display(roots)
# the first of them:
t_turn = min(roots, key=lambda r: float(r.subs({J: 1, k: 1, a: 2})))
### END SOLUTION
### PLACEHOLDER: t_turn = None  # your answer here: in a, J and k
t_turn

# %% [markdown] solution
# The first root is $t = \frac{\sqrt J}{k}\arcsin\frac{\pi}{2a}$ (the other is where
# $\theta$ comes back down through $\pi/2$); it is real only for $a \ge \pi/2$.
# For $m = J = k = 1$, $a = 2$:

# %% solution
float(t_turn.subs({J: 1, k: 1, a: 2}))

# %%
check("turning-point", t_turn, part="t_turn")

# %% [markdown]
# ## 3. What the numerics do there
#
# Run `red.simulate(q0, qp0, h0, (0.0, 5.0), params)` and see what happens.

# %%
### BEGIN SOLUTION
try:
    red.simulate(q0, qp0, h0, (0.0, 5.0), params, rtol=1e-10)
    outcome = "continues"
except wt.ChartError as err:
    print(err)
    outcome = "ChartError"
    x_stop = err.value
### END SOLUTION
### PLACEHOLDER: outcome = None  # your answer here: "ChartError", "NaN", "continues" or "switches"
outcome

# %% [markdown] solution
# The integrator does not step blindly into the singularity: the reduced model
# watches how much of the velocity is still along $x$ and, when $\dot x$ is about
# to vanish, stops with a `ChartError` that says where. Asked to, it continues
# across the turning point in time and then goes on in $x$, now running backwards
# (`on_turning_point="switch"`). In time, the full model in its default
# *multiplier* form (chapter 3) has no trouble: $x(t)$ simply turns back. The
# paper's form (1.4) does have trouble there: it divides by $\cos\theta$, which
# vanishes where $x$ turns back, and `formulation="chaplygin"` stops at that pole
# with a `ModelError` (chapter 8); the run plotted below is the multiplier form
# (`traj.formulation`):

# %% solution alt="x against t for the sledge whose amplitude exceeds pi/2: the exact solution (thick grey), the full model in t (dots) and the reduced model in x that switches to time at each turning point of x (thin line) agree; dotted vertical lines mark the turning points, where x runs back."
import matplotlib.pyplot as plt
import numpy as np

path = red.simulate(q0, qp0, h0, (0.0, 1.0), params, rtol=1e-10,
                    on_turning_point="switch")
q0_t, qdot0_t = exact.initial()
traj = wt.examples.sledge().simulate(q0_t, qdot0_t, (0.0, 6.0), params,
                                     rtol=1e-10)
ts = np.linspace(0.0, 6.0, 400)
fig, ax = plt.subplots(figsize=(6, 3))
ax.plot(ts, exact(ts)["x"], color="0.7", lw=4, label="exact (sledge_exact)")
ax.plot(traj.t, traj.q["x"], ".", ms=4, label="full model in $t$")
ax.plot(path.t, path.q["x"], "-", lw=1,
        label="reduced model in $x$, switching")
for s_tp, t_tp in path.turning_points:
    ax.axvline(t_tp, color="C3", lw=0.8, ls=":")
ax.set_xlabel("$t$")
ax.set_ylabel("$x$")
ax.legend(fontsize=8)
plt.show()
print("full model:", traj.formulation, "form")
print(f"{len(path.switches)} chart switches; turning points at x =",
      [round(s_tp, 6) for s_tp, _ in path.turning_points])

# %%
check("turning-point", outcome, part="numerics")

# %% [markdown]
# ## 4. Where the sledge turns back

# %%
### BEGIN SOLUTION
# the exact motion at that time
x_turn = exact(float(t_turn.subs({J: 1, k: 1, a: 2})))["x"]
print(f"exact: {x_turn:.10f}   ChartError: {x_stop:.10f}")
### END SOLUTION
### PLACEHOLDER: x_turn = None  # your answer here: a number
x_turn

# %%
check("turning-point", x_turn, part="x_turn")
