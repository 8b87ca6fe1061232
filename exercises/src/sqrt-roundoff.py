# %% [markdown]
# # Round-off under a square root
#
# *Level: warm-up (about 20 minutes). Chapter 8, "Round-off under square roots", and
# chapter 15.*
#
# Near a turning point the first integral (3.11) takes the square root of a
# difference of nearly equal numbers. In floating point the difference loses digits
# (**catastrophic cancellation**), and a rewritten form does not.

# %% [markdown] statement
# **Assumptions:** the sledge of section 3: a runner whose contact point moves only
# along it (the non-holonomic constraint $\dot y\cos\theta - \dot x\sin\theta = 0$), a
# torsion spring $k^2$ on the heading $\theta$, no friction; the speed $C$ along the runner
# is then constant. The arithmetic: IEEE double precision, rounding to nearest ($u = 2^{-53}$).
#
# **Model.** The sledge with $m = J = k = C = 1$ and amplitude $a = 0.6$, so
# $h = \tfrac12 mC^2 + \tfrac12 k^2a^2$. Squared, (3.11) gives
# $J\dot\theta^2 = R(\theta) = 2h - mC^2 - k^2\theta^2$, which vanishes at the turning
# point $\theta = a$; mathematically $R = k^2(a - \theta)(a + \theta)$.
#
# **Arithmetic.** IEEE double precision (Python floats), evaluated left to right
# exactly as written: `a = 0.6`, `theta = a - 1e-9`,
# `h = 0.5*m*C*C + 0.5*k*k*a*a`, and the *naive* radicand
# `R_naive = 2*h - m*C*C - k*k*theta*theta`.
#
# **Error measure.** The exact radicand $R = k^2(a - \theta)(a + \theta)$ of the two
# floating-point numbers `a` and `theta` (computed without rounding, e.g. with
# `fractions.Fraction`); the relative error of `R_naive` is $|R_\text{naive} - R|/R$.
#
# 1. `digits`: the number of decimal digits the subtraction can lose,
#    $\lfloor\log_{10}\kappa\rfloor$ with the condition number
#    $\kappa = (|2h| + |mC^2| + |k^2\theta^2|)/|R|$.
# 2. `rel_error`: the relative error of `R_naive` (within a relative $10^{-6}$).
# 3. `form`: which form of the radicand keeps full relative accuracy near the
#    turning point? `"factored"` ($k^2(a - \theta)(a + \theta)$), `"expanded"`
#    ($2h - mC^2 - k^2\theta^2$) or `"clip"` (the expanded form with negative values
#    set to zero).

# %% exercise
EXERCISE = {
    "title": "Round-off under a square root",
    "equations": "3.11",
    "solvers": True,
    "symbols": "",
    "parts": {
        "digits": {
            "what": "floor(log10) of the condition number of the naive radicand",
            "points": 1,
            "wrong": [["10", "Take the floor of log10(kappa), not the next integer up."]],
            "success": "About that many of the 16 digits of a double can be lost in the "
                       "subtraction."},
        "rel_error": {
            "what": "the relative error of the naive radicand at theta = a - 1e-9",
            "points": 2, "rtol": 1e-06,
            "wrong": [["1.014634665229886e-7",
                       "You measured against the radicand at a distance of exactly 1e-9 from "
                       "0.6; the float theta = a - 1e-9 is not that far from the float a. "
                       "The statement's reference is the exact radicand of the two "
                       "floating-point numbers a and theta: Fraction(a), Fraction(theta)."]],
            "success": "Far above the 1e-16 of one rounding, as the condition number "
                       "warned."},
        "form": {
            "what": "the form of the radicand that keeps full relative accuracy",
            "points": 1,
            "choices": {
                "factored": [["k^2*(a - theta)*(a + theta)", "product", "factorised"],
                             "a - theta is computed exactly here (Sterbenz: the two are "
                             "within a factor 2), and products and sums of positive "
                             "numbers lose no relative accuracy."],
                "expanded": [["naive", "2h - m C^2 - k^2 theta^2"],
                             "That is the form whose error you measured in part 2."],
                "clip": [["clipped", "max(0, R)"],
                         "Clipping turns a negative round-off into 0 (no NaN), but the "
                         "digits lost in the subtraction stay lost."]}},
    },
}

# %%
from whittaker_teach.notebook import setup; setup()

# %%
import math
from fractions import Fraction

from whittaker_teach.exercises import check

m = J = k = C = 1.0
a = 0.6
theta = a - 1e-9
h = 0.5*m*C*C + 0.5*k*k*a*a
R_naive = 2*h - m*C*C - k*k*theta*theta
A, TH, K = Fraction(a), Fraction(theta), Fraction(k)
R = K*K*(A - TH)*(A + TH)                    # exact, in rational arithmetic
print(f"R_naive = {R_naive!r}\nR       = {float(R)!r}")

# %% [markdown]
# ## 1. How many digits can go

# %%
### BEGIN SOLUTION
kappa = (abs(2*h) + abs(m*C*C) + abs(k*k*theta*theta))/float(R)
digits = math.floor(math.log10(kappa))
### END SOLUTION
### PLACEHOLDER: digits = None  # your answer here: an integer
digits

# %%
check("sqrt-roundoff", digits, part="digits")

# %% [markdown]
# ## 2. How many went

# %%
### BEGIN SOLUTION
rel_error = float(abs(Fraction(R_naive) - R)/R)
### END SOLUTION
### PLACEHOLDER: rel_error = None  # your answer here: a number
rel_error

# %%
check("sqrt-roundoff", rel_error, part="rel_error")

# %% [markdown] solution
# The factored form, in the same floating point, against the exact value; and what
# the error does to $\dot\theta = \sqrt{R/J}$: a square root halves a relative error,
# which saves $\log_{10}2 \approx 0.3$ of a digit, so $\dot\theta$ loses about as many
# digits as $R$:

# %% solution
R_factored = k*k*(a - theta)*(a + theta)
print(f"factored: relative error {float(abs(Fraction(R_factored) - R)/R):.1e}")
print(f"thetadot: naive {math.sqrt(R_naive/J):.12e}, factored "
      f"{math.sqrt(R_factored/J):.12e}")
exact_thetadot = math.sqrt(float(R)/J)   # R/J rounded once: within 1e-16 of the exact root
print(f"relative error of the naive thetadot: "
      f"{abs(math.sqrt(R_naive/J) - exact_thetadot)/exact_thetadot:.2e}")

# %% [markdown]
# ## 3. Which form

# %%
### BEGIN SOLUTION
form = "factored"
### END SOLUTION
### PLACEHOLDER: form = None  # your answer here: "factored", "expanded" or "clip"
form

# %%
check("sqrt-roundoff", form, part="form")
