# %% [markdown]
# # Error against cost for two integrators
#
# Which integrator should you use for the sledge? "The most accurate" is not an
# answer: accuracy costs right-hand-side evaluations. A work-precision
# measurement puts the two side by side: the error each integrator achieves
# against what it cost.

# %% [markdown] statement
# Integrate the sledge of section 3 in time, the full model in its default
# *multiplier* form (chapter 3: the Lagrange-d'Alembert equations with the
# constraint (3.2) and a multiplier, not the paper's form (1.4)), with
# `system.simulate` and `dense=False` (no interpolant: the error is measured at
# the last step, and DOP853's interpolant would cost 3 evaluations a step), for $m = J = k = 1$, from $\theta = 0$,
# $\dot\theta = a\,k/\sqrt J$, $\dot x = C$ with $a = 0.5$, $C = 1$, over $0 \le t \le 20$.
# The exact motion is known, $\theta = a\sin t$ (3.15) with (3.12), (3.13):
# `wt.examples.sledge_exact`.
# **Assumptions:** the set-up of chapter 7: the error of a run is *relative*, the
# largest at $t = 20$ of $|x - x_\text{exact}|/s_x$, $|y - y_\text{exact}|/s_y$,
# $|\theta - \theta_\text{exact}|/s_\theta$, each component divided by its scale
# along the exact motion ($s_\theta = a$, $s_x$ and $s_y$ the largest $|x|$ and
# $|y|$ over $0 \le t \le 20$); its cost is `nfev`, the number of evaluations of the
# right-hand side; the tolerances are `rtol` $= 10^{-4}, 10^{-5}, \dots, 10^{-12}$
# with `atol` $= 10^{-20}$ (tiny, so that the error control is relative in every
# component: not `atol = rtol`).
#
# 1. `nfev`: run `DOP853` and `RK45` on every tolerance (the function `run` below does
#    one run). What is the fewest `nfev` with which DOP853 reaches an error $\le 10^{-8}$?
# 2. `method`: plot error against cost for both. Which would you use for an error of
#    $10^{-8}$: `"DOP853"` or `"RK45"`?
# 3. `why`: why is it cheaper there? One of `"order"`, `"implicit"`, `"symplectic"`,
#    `"tolerance"`.

# %% exercise
EXERCISE = {
    "title": "Error against cost for two integrators",
    "equations": "3.2, 3.15",
    "solvers": True,
    "symbols": "",
    "parts": {
        "nfev": {
            "what": "the fewest right-hand-side evaluations (nfev) with which DOP853 reaches "
                    "a relative error <= 1e-08 on the grid of tolerances", "points": 2,
            "success": "That is the cheapest run of DOP853 below the target."},
        "method": {
            "what": "the integrator you would use for an error of 1e-08", "points": 1,
            "choices": {
                "DOP853": [["dop853"], "DOP853 reaches 1e-08 with fewer evaluations than "
                                       "RK45: the leftmost point below the target line."],
                "RK45": [["rk45"], "Compare the costs (nfev) at which each reaches an error "
                                   "of 1e-08: read them off your table or plot."]}},
        "why": {
            "what": "why that integrator is cheaper at this accuracy", "points": 1,
            "choices": {
                "order": [["higher order", "its order is higher", "8th order", "eighth order",
                           "order 8"],
                          "An error of order 8 falls much faster with the step size than one "
                          "of order 5, so at tight tolerances DOP853 takes far fewer steps, "
                          "although each costs more evaluations."],
                "implicit": [["it is implicit", "implicit method"],
                             "Both are explicit Runge-Kutta methods."],
                "symplectic": [["it is symplectic", "structure preserving"],
                               "Neither is symplectic; the sledge is not even Hamiltonian."],
                "tolerance": [["smaller tolerance", "tighter tolerance", "rtol"],
                              "Both were run on the same tolerances; look at the error each "
                              "achieves for its cost."]}},
    },
}

# %%
from whittaker_teach.notebook import setup; setup()

# %%
import math

import whittaker_teach as wt
from whittaker_teach.exercises import check

params = {"m": 1.0, "J": 1.0, "k": 1.0}
exact = wt.examples.sledge_exact(params, a=0.5, phi=-math.pi/2, C=1.0)
sledge = wt.examples.sledge()
q0, qdot0 = exact.initial()
T = 20.0
RTOLS = [10.0**-n for n in range(4, 13)]
ATOL = 1e-20                 # tiny: the error control is relative in every component
# each component's scale along the exact motion (chapter 7)
grid = [exact(T*i/400) for i in range(401)]
scale = {"theta": 0.5, "x": max(abs(g["x"]) for g in grid),
         "y": max(abs(g["y"]) for g in grid)}


def run(method, rtol):
    """One run: (nfev, relative error at t = T)."""
    traj = sledge.simulate(q0, qdot0, (0.0, T), params, method=method,
                           rtol=rtol, atol=ATOL, dense=False)
    end = exact(T)
    error = max(abs(float(traj.q[c][-1]) - end[c])/scale[c]
                for c in ("x", "y", "theta"))
    return traj.nfev, error

# %% [markdown]
# ## 1. The measurements

# %%
### BEGIN SOLUTION
table = {method: [(rtol, *run(method, rtol)) for rtol in RTOLS]
         for method in ("DOP853", "RK45")}
for method, rows in table.items():
    print(method)
    for rtol, nfev, error in rows:
        print(f"  rtol {rtol:7.0e}   nfev {nfev:5d}   error {error:8.1e}")
nfev = min(n for _, n, e in table["DOP853"] if e <= 1e-8)
### END SOLUTION
### PLACEHOLDER: nfev = None  # your answer here: an integer
nfev

# %%
check("work-precision", nfev, part="nfev")

# %% [markdown]
# ## 2. The work-precision diagram

# %% solution alt="Work-precision diagram on log-log axes: the relative error at t = 20 against the number of right-hand-side evaluations for DOP853 (circles) and RK45 (squares), with a dashed line at the target 1e-8; DOP853 reaches the target with fewer evaluations."
import matplotlib.pyplot as plt
from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter

fig, ax = plt.subplots(figsize=(6, 4))
for method, marker in (("DOP853", "o"), ("RK45", "s")):
    rows = table[method]
    ax.loglog([n for _, n, _ in rows], [e for _, _, e in rows],
              marker=marker, label=method)
ax.axhline(1e-8, color="0.5", lw=0.8, ls="--", label="target $10^{-8}$")
# labels on 1, 2, 5 x 10^k only: the minor ticks of a short log axis would overlap
ax.xaxis.set_major_locator(LogLocator(base=10, subs=(1.0, 2.0, 5.0)))
ax.xaxis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:,.0f}"))
ax.xaxis.set_minor_formatter(NullFormatter())
ax.set_xlabel("cost: nfev (evaluations of the right-hand side)")
ax.set_ylabel("relative error at $t = 20$")
ax.legend()
fig.tight_layout()
plt.show()

# %%
### BEGIN SOLUTION
cost = {method: min(n for _, n, e in rows if e <= 1e-8)
        for method, rows in table.items()}
print(cost)
method = min(cost, key=cost.get)
### END SOLUTION
### PLACEHOLDER: method = None  # your answer here: "DOP853" or "RK45"
method

# %% [markdown] solution
# Wall-clock time tells the same story here, but it depends on the machine (this
# cell's output is not checked):

# %% solution tag=nbval-ignore-output
import time

for name in ("DOP853", "RK45"):
    rtol = max(r for r, _, e in table[name] if e <= 1e-8)
    start = time.perf_counter()
    for _ in range(20):
        run(name, rtol)
    ms = (time.perf_counter() - start)/20*1e3
    print(f"{name}: {ms:.1f} ms per run at rtol {rtol:.0e}")

# %%
check("work-precision", method, part="method")

# %% [markdown]
# ## 3. Why

# %%
### BEGIN SOLUTION
why = "order"
### END SOLUTION
### PLACEHOLDER: why = None  # your answer here: "order", "implicit", "symplectic" or "tolerance"
why

# %% [markdown] solution
# DOP853 is a Runge-Kutta method of order 8, RK45 of order 5 (both explicit, both
# Dormand-Prince). Halving the step divides DOP853's error by about $2^8$ and
# RK45's by about $2^5$: on the diagram DOP853's line is much steeper, so below
# about $10^{-6}$ it needs far fewer evaluations for the same error, although
# each of its steps costs 12 evaluations against 6; at loose tolerances the two
# are close. Note also that `rtol` is not the error (compare the two columns of
# the table above): the error at $t = 20$ is the accumulation of every step's,
# so the tolerance must be chosen from a measurement like this one.

# %%
check("work-precision", why, part="why")
