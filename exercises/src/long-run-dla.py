# %% [markdown]
# # A long run: DLA against RK4
#
# *Level: standard (about 45 minutes). Chapter 8, "Long runs", and chapter 15.*
#
# Over many periods what matters is how errors *grow*. A fixed-step Runge–Kutta method
# and the discrete Lagrange–d'Alembert integrator (DLA) of chapter 8, with the same
# step, make different mistakes: one loses energy, the other keeps it and loses the
# phase. Both can be predicted exactly on the sledge, whose heading is a harmonic
# oscillator.

# %% [markdown] statement
# **Assumptions:** the sledge of section 3: a runner whose contact point moves only
# along it (the non-holonomic constraint $\dot y\cos\theta - \dot x\sin\theta = 0$), a
# torsion spring $k^2$ on the heading $\theta$, no friction; the speed $C$ along the runner
# is then constant.
#
# **Model.** The sledge of section 3, $m = J = k = 1$, from $\theta = 0$,
# $\dot\theta = 0.5$, $\dot x = 1$ ($C = 1$, amplitude $a = 0.5$, $\omega = 1$),
# $x = y = 0$, over 100 periods, $0 \le t \le T = 200\pi$. Its energy is
# $E = \tfrac12(mC^2 + J\dot\theta^2 + k^2\theta^2)$, $h = E(0) = 0.625$.
#
# **Methods,** each with 32 equal steps per period, $\Delta t = 2\pi/32$ (3200 steps):
#
# * **RK4**: the classical Runge–Kutta method on the form (3.12)–(3.14) of the
#   equations, $u = (\theta, \dot\theta, x, y)$: `fs.integrate(fs.sledge_rhs(params,
#   C=1), (0, T), u0, 3200, "rk4")`;
# * **DLA**: `sledge.simulate(q0, qdot0, (0, T), params, method="DLA", dt=2*pi/32)`,
#   the midpoint discrete Lagrangian with the constraint at the midpoint (chapter 8):
#   $N = \operatorname{round}(T/\texttt{dt}) = 3200$ steps of $T/N$. The velocities it
#   reports at the points (`trajectory.qdot`) are those of the discrete momenta,
#   $\dot\theta_k = p_k/J$ (the projection on the constraint leaves $\dot\theta$ alone),
#   and on the heading oscillator the sequence $(\theta_k, \dot\theta_k)$ is exactly the
#   implicit midpoint rule's.
#
# **Error measures.** The relative energy error at $T$, $(h - E(T))/h$. The phase
# lag at $T$: the heading of each method is $\theta = A\sin\chi$,
# $\dot\theta = A\cos\chi$ for some amplitude $A$ and phase $\chi$; the lag is the
# exact phase $\omega T$ minus the computed $\chi$ (unwrapped).
#
# 1. `rk4_energy`: RK4's relative energy error at $T$ (within a relative $10^{-6}$).
# 2. `dla_phase`: DLA's phase lag at $T$, in radians (within a relative $10^{-6}$).
# 3. `keeps`: which of the two keeps the energy to rounding over the run? `"DLA"`,
#    `"RK4"`, `"both"` or `"neither"`.
#
# *Hint.* One step of either method multiplies the heading's
# $(\dot\theta/\omega + i\,\theta)$ by a complex number $R(i\omega\Delta t)$, its
# stability function: $|R|$ sets the energy, $\arg R$ the phase.

# %% exercise
EXERCISE = {
    "title": "A long run: DLA against RK4",
    "equations": "3.12, 3.13, 3.14, 3.15",
    "solvers": True,
    "symbols": "",
    "parts": {
        "rk4_energy": {
            "what": "RK4's relative energy error (h - E(T))/h after 100 periods",
            "points": 2, "rtol": 1e-06,
            "wrong": [["0.0025313299390408165",
                       "That is relative to the heading's energy alone; the statement's h "
                       "includes the translation, m C^2/2."]],
            "success": "RK4 damps the oscillator a little at every step: |R(i w dt)| < 1, "
                       "so the energy falls steadily, about in proportion to the time."},
        "dla_phase": {
            "what": "DLA's phase lag after 100 periods, in radians",
            "points": 2, "rtol": 1e-06,
            "wrong": [["2.0186378047070193",
                       "That is the leading term of the lag per step, summed; the question "
                       "asks for the lag itself (measured, or from the exact argument of R)."]],
            "success": "The implicit midpoint rule turns by 2 arctan(w dt/2) a step "
                       "instead of w dt: a lag that grows linearly with time."},
        "keeps": {
            "what": "which method keeps the energy to rounding", "points": 1,
            "choices": {
                "DLA": [["the dla", "dla integrator", "variational"],
                        "|R| = 1 exactly for the implicit midpoint rule: it keeps the "
                        "heading's energy, and the constraint force keeps C."],
                "RK4": [["rk", "runge-kutta"],
                        "Compare the energy errors you computed in part 1 and in the DLA "
                        "run."],
                "both": [["all"], "One of the two loses energy at every step: look at "
                                  "|R| for each."],
                "neither": [["none"], "Look at the DLA run's energy error."]}},
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
T, steps = 200*math.pi, 3200
dt = 2*math.pi/32
h = 0.5*(1.0 + 0.5**2)
sledge = wt.examples.sledge()

# %% [markdown]
# ## 1. RK4's energy

# %%
### BEGIN SOLUTION
rk4 = fs.integrate(fs.sledge_rhs(params, C=1.0), (0.0, T), [0.0, 0.5, 0.0, 0.0], steps,
                   "rk4")[1]


def energy(theta, thetadot):
    return 0.5*(1.0 + thetadot**2 + theta**2)


rk4_energy = (h - energy(rk4[-1, 0], rk4[-1, 1]))/h
### END SOLUTION
### PLACEHOLDER: rk4_energy = None  # your answer here: a number
rk4_energy

# %%
check("long-run-dla", rk4_energy, part="rk4_energy")

# %% [markdown]
# ## 2. DLA's phase

# %%
### BEGIN SOLUTION
dla = sledge.simulate({"x": 0.0, "theta": 0.0, "y": 0.0}, {"x": 1.0, "theta": 0.5},
                      (0.0, T), params, method="DLA", dt=dt)


def lag(theta, thetadot):
    """omega T minus the computed phase, unwrapped to the nearest turn of omega T."""
    chi = math.atan2(theta, thetadot)
    return T - (chi + 2*math.pi*round((T - chi)/(2*math.pi)))


dla_phase = lag(dla.q["theta"][-1], dla.qdot["theta"][-1])
### END SOLUTION
### PLACEHOLDER: dla_phase = None  # your answer here: radians
dla_phase

# %%
check("long-run-dla", dla_phase, part="dla_phase")

# %% [markdown] solution
# Both numbers follow from the stability functions, with $z = \omega\Delta t$:
# RK4's $|R(iz)|^2 = 1 - z^6/72 + z^8/576$ per step on the heading's energy, and the
# implicit midpoint rule's $\arg R(iz) = 2\arctan(z/2)$ against the exact $z$:

# %% solution
z = dt
R4 = abs(fs.stability_function("rk4", 1j*z))
head = 0.5*0.5**2                                  # the heading's share of h
print(f"RK4 energy error, predicted {head*(1 - R4**(2*steps))/h:.8e}")
print(f"DLA phase lag, predicted    {steps*(z - 2*math.atan(z/2)):.8f}")
print(f"the other two: RK4 phase lag {lag(rk4[-1, 0], rk4[-1, 1]):.1e} rad, DLA energy "
      f"error {abs(h - energy(dla.q['theta'][-1], dla.qdot['theta'][-1]))/h:.0e}")

# %% [markdown]
# ## 3. Which keeps the energy

# %%
### BEGIN SOLUTION
keeps = "DLA"
### END SOLUTION
### PLACEHOLDER: keeps = None  # your answer here: "DLA", "RK4", "both" or "neither"
keeps

# %%
check("long-run-dla", keeps, part="keeps")
