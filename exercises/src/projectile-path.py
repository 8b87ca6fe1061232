# %% [markdown]
# # The path of a projectile
#
# Whittaker's reduction removes time with the energy integral. For a
# projectile, the horizontal coordinate $x$ takes the place of $t$, and
# Whittaker's equation (1.27) is an equation for the path $y(x)$ itself.

# %% [markdown] statement
# A projectile of mass $m$ moves in a vertical plane under gravity, of acceleration $g_0$ (the
# paper's $g$ counts the constraints):
#
# $$L = \tfrac12 m(\dot x^2 + \dot y^2) - m g_0 y .$$
#
# It is a holonomic system ($g = 0$ constraints in the paper's notation; the
# constraint term of (1.26) is absent). Take $x$ as the independent
# coordinate: $q_\varepsilon = x$, $y' = dy/dx$ (1.5).
# **Assumptions:** $m, g_0 > 0$; the projectile moves with $\dot x > 0$; it is
# launched from the origin with speed $v_0 > 0$ at the angle $\alpha$
# ($0 < \alpha < \pi/2$) above the horizontal.
#
# 1. `L_star`: the reduced Lagrangian $L^{\ast}(y', y)$ (1.5), (1.6), (1.12), (1.16).
# 2. `y_pp`: Whittaker's equation (1.27) for $L^{\ast}$, solved for $y''$.
# 3. `path`: the path $y(x)$ of this projectile (its energy is $h = \tfrac12 m v_0^2$).
#
# Answer with SymPy expressions in the symbols defined below (or strings such
# as `"x*tan(alpha)"`; `y'` stands for $y'$). Gravity is the symbol `g_0`: in a
# string write `g_0`, `g0` or `g₀` (a plain `g` is not gravity here).

# %% exercise
EXERCISE = {
    "title": "The path of a projectile",
    "equations": "1.5, 1.12, 1.16, 1.27",
    "solvers": False,
    "symbols": "x y yprime yprimeprime h m+ g_0+ v0+ alpha",
    "domain": {"x": [0.0, None], "y": "real", "yprime": "slope", "yprimeprime": "real",
               "h": "energy", "alpha": [0.0, 1.5707963267948966]},
    "conditions": ["h - m*g_0*y"],
    "notes": {"g": "gravity is g_0 (also g0 or g₀); the paper's g counts the constraints"},
    "parts": {
        "L_star": {
            "form": "sqrt(2*(h - m*g_0*y))*sqrt(m*(1 + yprime^2))",
            "what": "L* (1.16) for the projectile with x in place of t", "points": 1,
            "variables": "y yprime h m g_0",
            "sign_note": "the direction of travel is xdot > 0, so take the root with the + sign",
            "why_not": {"x": "L does not depend on x", "v0": "L* is written with the energy h",
                        "alpha": "L* is written with the energy h"},
            "success": "L* = sqrt(2(h - m g_0 y)) sqrt(m (1 + y'^2)), the root for xdot > 0 "
                       "(1.16)."},
        "y_pp": {
            "what": "y'' solved from Whittaker's equation (1.27)", "points": 1,
            "variables": "y yprime h m g_0",
            "why_not": {"yprimeprime": "solve the equation for y''"},
            "success": "y'' from (1.27): the same for either direction of travel."},
        "path": {
            "what": "the path y(x) of the projectile launched from the origin with speed v0 "
                    "at angle alpha", "points": 2,
            "variables": "x g_0 v0 alpha",
            "why_not": {"h": "use h = m v0^2/2", "m": "the path does not depend on the mass",
                        "y": "y(x) is the answer", "yprime": "use y'(0) = tan(alpha)"},
            "success": "The parabola y = x tan(alpha) - g_0 x^2/(2 v0^2 cos^2(alpha)): it solves "
                       "(1.27) with h = m v0^2/2, y(0) = 0, y'(0) = tan(alpha)."},
    },
}

# %%
from whittaker_teach.notebook import setup; setup()

# %%
import sympy as sp
from whittaker_teach.exercises import check

m, g_0, v0 = sp.symbols("m g_0 v0", positive=True)
xdot = sp.Symbol("xdot", positive=True)      # direction of travel
x, y, yprime, yprimeprime, h, alpha = sp.symbols(
    "x y yprime yprimeprime h alpha")


def d_dx(f):
    """d/dx of f(y', y, x) along a path (2.1)."""
    return f.diff(x) + f.diff(yprime)*yprimeprime + f.diff(y)*yprime

# %% [markdown]
# ## 1. The reduced Lagrangian $L^{\ast}$
#
# Build $\Omega$ (1.6) with $\dot y = \dot x\,y'$, solve the energy integral
# $\dot x\,\partial\Omega/\partial\dot x - \Omega = h$ (1.13) for $\dot x > 0$,
# and put that root in $L^{\ast} = \partial\Omega/\partial\dot x$ (1.16).

# %%
### BEGIN SOLUTION
Omega = m/2*(xdot**2 + (xdot*yprime)**2) - m*g_0*y       # (1.6)
energy = sp.expand(xdot*Omega.diff(xdot) - Omega)      # (1.13)
v = sp.Symbol("v")                                     # xdot, no sign
roots = sp.solve(sp.Eq(energy.subs(xdot, v), h), v)
# the root with xdot > 0:
xdot_sol, = [r for r in roots if not r.could_extract_minus_sign()]
L_star = sp.simplify(Omega.diff(xdot).subs(xdot, xdot_sol))   # (1.16)
### END SOLUTION
### PLACEHOLDER: L_star = None  # your answer here: L* in y, yprime and h
L_star

# %%
check("projectile-path", L_star, part="L_star")

# %% [markdown]
# ## 2. Whittaker's equation (1.27)
#
# $\dfrac{d}{dx}\dfrac{\partial L^{\ast}}{\partial y'} - \dfrac{\partial L^{\ast}}{\partial y} = 0$:
# solve it for $y''$ (use `d_dx` for the total derivative).

# %%
### BEGIN SOLUTION
whittaker = d_dx(L_star.diff(yprime)) - L_star.diff(y)      # (1.27)
y_pp, = sp.solve(whittaker, yprimeprime)
y_pp = sp.factor(y_pp)
### END SOLUTION
### PLACEHOLDER: y_pp = None  # your answer here: y'' in y, yprime and h
y_pp

# %%
check("projectile-path", y_pp, part="y_pp")

# %% [markdown]
# ## 3. The path $y(x)$
#
# The projectile starts at $y(0) = 0$ with slope $y'(0) = \tan\alpha$ and
# energy $h = \tfrac12 m v_0^2$. Find $y(x)$. (A hint: try a polynomial.)

# %% [markdown] solution
# Try $y = x\tan\alpha + c\,x^2$, which meets both initial conditions, and
# ask what $c$ makes the residual $y'' - y''(y', y)$ of step 2 vanish:

# %%
### BEGIN SOLUTION
c = sp.Symbol("c")
trial = x*sp.tan(alpha) + c*x**2
on_path = {y: trial, yprime: trial.diff(x), h: m*v0**2/2}
residual = sp.factor(sp.together(trial.diff(x, 2) - y_pp.subs(on_path)))
display(residual)
c_sol, = sp.solve(residual, c)
path = trial.subs(c, c_sol)
### END SOLUTION
### PLACEHOLDER: path = None  # your answer here: y as a function of x, g_0, v0, alpha
path

# %% [markdown] solution
# The numerator of the residual, $2 c v_0^2 + g_0(1 + \tan^2\alpha)$, is free of $x$:
# one value of $c$ makes it vanish for every $x$, so the parabola is an exact
# solution, and by uniqueness (an initial value problem for a second-order
# equation) it is *the* path. The mass drops out, as it should.

# %%
check("projectile-path", path, part="path")
