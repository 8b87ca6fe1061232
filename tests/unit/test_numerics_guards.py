"""Issue 13's guards: extreme parameters end in a ModelError naming the condition, quickly;
zeros of xdot and poles inside one step are found; long runs keep only their output."""

import math
import time

import numpy as np
import pytest

import whittaker_teach as wt
from whittaker_teach.numerics.scene import scene

P = {"m": 1.0, "J": 1.0, "k": 1.0}


def _exact_turns(ex, T):
    """Zeros of xdot = C cos(a cos psi): a cos psi = +-pi/2, counted over [0, T]."""
    psi0, psi1 = ex.phase(0.0), ex.phase(T)
    c = (math.pi / 2) / ex.a
    n = 0
    base = math.acos(c), math.acos(-c)
    for b in base:
        for r in (b, -b):
            k0 = math.ceil((psi0 - r) / (2 * math.pi))
            k1 = math.floor((psi1 - r) / (2 * math.pi))
            n += max(0, k1 - k0 + 1)
    return n


@pytest.mark.parametrize("d", [1e-6, 1e-9])
def test_turning_points_inside_a_step_are_found(red, d):
    ex = wt.examples.sledge_exact(P, a=math.pi / 2 + d, phi=math.pi / 2, C=1.0)
    T = 5 * ex.period
    q0, qp0, h = ex.reduced_initial()
    path = red.simulate(q0, qp0, h, (0.0, ex(T)["x"]), P, rtol=1e-10, atol=1e-14,
                        on_turning_point="switch")
    assert len(path.turning_points) == _exact_turns(ex, path.t[-1]) == 20
    for s, t in path.turning_points:
        assert abs(ex(t)["xdot"]) < 1e-8 and abs(ex(t)["x"] - s) < 1e-8
    with pytest.raises(wt.ChartError) as info:
        red.simulate(q0, qp0, h, (0.0, ex(T)["x"]), P, rtol=1e-10, atol=1e-14)
    first = min(t for _, t in path.turning_points)
    assert "vanishes" in str(info.value) and abs(info.value.t - first) < 1e-7


@pytest.mark.parametrize("d", [1e-6, 1e-9])
def test_paper_form_does_not_step_over_a_pole(S, d):
    ex = wt.examples.sledge_exact(P, a=math.pi / 2 + d, phi=0.3, C=1.0)
    with pytest.raises(wt.ModelError, match=r"pole, cos\(theta\) = 0, at t = "):
        S.simulate(*ex.initial(), (0, 3 * ex.period), P, formulation="chaplygin")
    tr = S.simulate(*ex.initial(), (0, 3 * ex.period), P)        # the default is regular
    assert tr.formulation == "multiplier"


def _quick(fn):
    t0 = time.process_time()
    with pytest.raises(wt.ModelError) as info:
        fn()
    assert time.process_time() - t0 < 5
    return str(info.value)


def test_exact_refuses_a_huge_amplitude():
    msg = _quick(lambda: wt.examples.sledge_exact({"m": 1, "J": 1, "k": 1e-7}, h=1.0, C=1.0))
    assert "amplitude a = 1e+07" in msg and "Bessel terms" in msg


def test_exact_arithmetic_out_of_range():
    _quick(lambda: wt.examples.sledge_exact({"m": 1, "J": 1, "k": 1e300}, a=1e10, C=1.0))


@pytest.mark.parametrize("C", [1e-160, 1e-300])
def test_tiny_speed_in_the_reduced_model(red, C):
    ex = wt.examples.sledge_exact(P, a=0.5, phi=0.3, C=C)
    q0, qp0, h = ex.reduced_initial()
    msg = _quick(lambda: red.simulate(q0, qp0, h, (0.0, 1.0), P))
    assert "qdot_x is (nearly) zero at the start" in msg


def test_energy_at_a_turning_point(red):
    msg = _quick(lambda: red.simulate({"x": 0, "theta": 0, "y": 0}, {"theta": 0.0}, 0.0,
                                      (0.0, 1.0), P))
    assert "turning point of x" in msg and "step size" not in msg


def test_huge_values_in_the_full_model(S):
    _quick(lambda: S.simulate({"x": 0, "theta": 1e300, "y": 0}, {"x": 1e300, "theta": 1e300},
                              (0, 1), P))


def test_t_eval_checked(S):
    with pytest.raises(wt.ModelError, match="within t_span"):
        S.simulate({"x": 0, "theta": 0.1, "y": 0}, {"x": 1, "theta": 0}, (0, 1), P,
                   t_eval=[0.5, 2.0])


def _peak(S, periods, method="RK23", rtol=1e-2):
    import tracemalloc
    ex = wt.examples.sledge_exact(P, a=0.5, phi=0.3, C=1.0)
    T = periods * ex.period
    t_eval = np.linspace(0, T, 1000)
    S.simulate(*ex.initial(), (0, 1.0), P, method=method, rtol=rtol)      # compiled
    tracemalloc.start()
    tr = S.simulate(*ex.initial(), (0, T), P, method=method, rtol=rtol, t_eval=t_eval)
    _, peak = tracemalloc.get_traced_memory()
    tracemalloc.stop()
    assert len(tr.t) == 1000 and tr.nfev > 5 * periods
    return peak


def test_memory_does_not_grow_with_the_run(S):
    """With t_eval, a run keeps its output only: 10 times longer, the same peak memory."""
    short, long = _peak(S, 200), _peak(S, 2000)
    assert long < 1.2 * short + 1e6 and long < 20e6, (short, long)


@pytest.mark.slow
def test_long_run_memory(S):
    """1e5 periods of the full model with 1000 output points: under 200 MB (several
    minutes under tracemalloc: ``make slow``)."""
    assert _peak(S, 100_000, "DOP853", 1e-3) < 200e6


def test_scene_picks_exact_for_the_sledge(S):
    sc = scene(S, {"x": 0, "theta": 0.3, "y": 0}, {"x": 1, "theta": 0.1}, (0, 30), P,
               tol=1e-9)
    ex = wt.examples.sledge_exact(P, a=math.hypot(0.3, 0.1), phi=math.atan2(-0.1, 0.3),
                                  C=1 / math.cos(0.3))
    assert sc.model == "exact" and "closed form" in sc.why
    assert abs(sc(30.0)["x"] - ex(30.0)["x"]) < 1e-12


def test_scene_full_model_meets_its_tolerance():
    T = wt.examples.offset_sleigh()
    Ps = {"m": 1, "J": 1, "k": 1, "b": 0.1}
    q0, qd0 = {"x": 0, "theta": 0.3, "y": 0}, {"x": 1, "theta": 0}
    sc = scene(T, q0, qd0, (0, 20), Ps, tol=1e-8)
    ref = T.simulate(q0, qd0, (0, 20), Ps, rtol=2.3e-14, atol=1e-20, t_eval=sc.t)
    for c in ("x", "theta", "y"):
        scale = np.max(np.abs(ref.q[c]))
        assert np.max(np.abs(sc.q[c] - ref.q[c])) / scale <= 1e-8
    assert sc.model == "full" and "DOP853" in sc.why
    with pytest.raises(wt.ModelError, match="no model reaches the relative error 1e-15"):
        scene(T, q0, qd0, (0, 20), Ps, tol=1e-15)


def test_numerics_imports_have_no_circles():
    import ast
    import pathlib
    root = pathlib.Path(wt.__file__).parent / "numerics"
    graph = {}
    for f in root.glob("*.py"):
        deps = set()
        for node in ast.walk(ast.parse(f.read_text())):
            if isinstance(node, ast.ImportFrom) and node.level == 1:
                if node.module:
                    deps.add(node.module.split(".")[0])
                else:
                    deps.update(a.name for a in node.names)
        graph[f.stem] = deps & {g.stem for g in root.glob("*.py")}
    seen, stack = set(), []

    def visit(n):
        assert n not in stack, f"import circle: {' -> '.join(stack + [n])}"
        if n in seen:
            return
        stack.append(n)
        for m in graph.get(n, ()):
            visit(m)
        stack.pop()
        seen.add(n)
    for n in graph:
        visit(n)


def test_a_simulate_call_crosses_modules_a_few_times():
    """One entry per model, the input checked once, the generated code behind it: a call of
    simulate goes entry -> validate -> codegen -> ivp, never back and forth
    (``scripts/trace_numerics.py``; before the rework: 14, 13 and 14 crossings)."""
    import importlib.util
    import pathlib
    path = pathlib.Path(__file__).parents[2] / "scripts" / "trace_numerics.py"
    spec = importlib.util.spec_from_file_location("trace_numerics", path)
    tracer = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(tracer)
    for name, fn in tracer.cases():
        fn()                                              # code generated
        seq = tracer.transitions(fn)
        # the core finds the numerics entry in the registry (backends.provided) and calls
        # it (numerics.__init__.simulate, which dispatches to the model): that dispatch
        # replaced an import and is not a crossing of the work; count from the model on
        seq = [t for t in seq if t[1] != "backends"]
        if seq and seq[0][1] == "numerics.__init__":
            seq = seq[1:]
        callees = [b.split(".")[-1] for _a, b, _f in seq]
        assert len(seq) <= 5, (name, seq)
        assert callees.count("validate") == 1, (name, seq)     # checked once,
        assert callees[1] == "validate", (name, seq)            # up front
