"""The scale benchmark runs (n = 2..4) and prints its table; times are printed, not asserted.

The table is recorded with ``record_property("printed", ...)`` and printed at the end
of the run by the root conftest.py (a pytest-xdist worker's own prints are lost)."""

import pytest

from whittaker_teach import bench


def test_scale_benchmark_runs_and_prints(record_property):
    for holonomic in (False, True):
        rows = bench.scale_rows(range(2, 5), holonomic, memory=False)
        assert [r["n"] for r in rows] == [2, 3, 4]
        assert all(r["ok"] for r in rows)          # every check of the derivation held
        table = bench.scale_table(rows, "holonomic family" if holonomic
                                  else "non-holonomic family")
        record_property("printed", "\n" + table)      # the figures go to the CI log
        assert len(table.splitlines()) == 5 and "verify/reduce" in table
        assert all(r["reduce"] > 0 and r["verify"] > 0 and r["peer"] > 0 for r in rows)


def test_peak_memory_is_measured():
    """The traced runs (tracemalloc slows a run about five times: n = 2 only here)."""
    [row] = bench.scale_rows([2], holonomic=True, memory=True)
    assert 0.1 < row["peer_mem"] < row["mem"] < 100       # MiB, after the imports
    assert "MiB" in bench.scale_table([row], "t") and f"{row['mem']:9.1f}" in bench.scale_table([row], "t")


def test_a_failing_measurement_names_the_job():
    measure = bench._Measurer()
    try:
        with pytest.raises(RuntimeError, match=r"run_ours\(n=0"):
            measure("run_ours", 0, False)
        assert measure("run_peer", 2, False)["peer"] > 0      # the server goes on
    finally:
        measure.close()


def test_family_shapes():
    L, coords, dep = bench.family(5)
    assert len(coords) == 5 and len(dep) == 2
    L, coords, dep = bench.family(4, holonomic=True)
    assert len(coords) == 4 and dep == {}


def test_without_fork_each_measurement_is_a_new_interpreter(monkeypatch):
    monkeypatch.delattr(bench.os, "fork")
    measure = bench._Measurer()
    assert measure.server is None
    assert measure("run_peer", 2, True)["peer"] > 0
    assert measure("run_peer", 2, True, traced=True)["peak"] > 0


def test_growth_is_the_fitted_factor_per_coordinate():
    rows = [{"n": n, "t": 0.1 * 1.5 ** n} for n in range(2, 9)]
    assert abs(bench.growth(rows, lambda r: r["t"]) - 1.5) < 1e-12


def test_chain_benchmark_against_both_peers_runs_and_prints(record_property):
    """The chain of sleighs against LagrangesMethod and KanesMethod (issue 26): times
    printed, not asserted; every check of the derivation held."""
    rows = bench.chain_rows(range(4, 6))
    assert [r["n"] for r in rows] == [4, 5] and all(r["ok"] for r in rows)
    assert all(r["peer"] > 0 and r["kane"] > 0 and r["reduce"] > 0 for r in rows)
    table = bench.chain_table(rows)
    record_property("printed", "\n" + table)
    assert len(table.splitlines()) == 4 and "Kane" in table


def test_chain_family_is_the_same_system_for_each_peer():
    """Kane's bodies and loads give the accelerations LagrangesMethod gives (n = 5)."""
    import sympy as sp
    from sympy.physics.mechanics import KanesMethod, LagrangesMethod, dynamicsymbols
    F, K = bench.chain(5), bench.chain(5, kane=True)
    lm = LagrangesMethod(F["L"], F["q"], nonhol_coneqs=F["coneqs"])
    lm.form_lagranges_equations()
    km = KanesMethod(**K["kane"])
    km.kanes_equations(K["bodies"], K["loads"])
    t = dynamicsymbols._t
    q = F["q"]
    pt = dict(zip(q, [0.3, 0.5, 0.1, 0.2, 0.4]))
    pt.update(dict(zip(sp.symbols("m J k c kappa M", positive=True), [1.1, 0.7, 1.3, 0.4, 0.9, 1.2])))
    x1, th1, y1 = q[:3]
    vel = {x1.diff(t): 0.8, th1.diff(t): -0.3, q[3].diff(t): 0.6, q[4].diff(t): 0.2}
    vel[y1.diff(t)] = 0.8 * sp.tan(0.5)
    lag = lm.rhs().xreplace({**pt, **vel})
    us = {u: vel[c.diff(t)] for u, c in zip([*K["kane"]["u_ind"], *K["kane"]["u_dependent"]],
                                            [x1, th1, q[3], q[4], y1])}
    kane = km.rhs().xreplace({**pt, **us})
    n = len(q)
    lag_acc = [float(lag[n + i]) for i in range(n)]
    kane_acc = {u.func.__name__: float(v) for u, v in zip(km.u, kane[n:])}
    for c, a in zip(q, lag_acc):
        assert abs(kane_acc[f"u_{c.func.__name__}"] - a) < 1e-9


def _kane_accelerations_agree(name, n, seed):
    """The largest difference between our accelerations (every coordinate's, the
    dependent ones' from d/dt of the constraints) and KanesMethod's (its mass matrix and
    forcing at the same point, solved numerically), at a random admissible point."""
    import random
    import sympy as sp
    from sympy.physics.mechanics import KanesMethod, dynamicsymbols
    import whittaker_teach as wt
    t = dynamicsymbols._t
    build = bench.PEER_FAMILIES[name][0]
    F, K = build(n), build(n, kane=True)
    system = wt.ChaplyginSystem(F["L"], F["q"], nonhol_coneqs=F["coneqs"],
                                dependent=F["dependent"])
    ours = system.accelerations(dependent=True)
    km = KanesMethod(**K["kane"])
    km.kanes_equations(K["bodies"], K["loads"])
    rng = random.Random(seed)
    point = {p: rng.uniform(0.5, 2) for p in sorted(F["L"].free_symbols - {t}, key=str)}
    point.update({c: rng.uniform(0.1, 1.2) for c in F["q"]})
    vel = {c.diff(t): rng.choice((-1, 1)) * rng.uniform(0.2, 1.5)
           for c in system.independent_coordinates}
    for key, phi in system.constraints.items():        # the dependent velocities
        vel[key] = float(phi.xreplace({**vel, **point}))
    speeds = {dynamicsymbols(f"u_{c.func.__name__}"): vel[c.diff(t)] for c in F["q"]}
    M = km.mass_matrix_full.xreplace({**point, **speeds})
    f = km.forcing_full.xreplace({**point, **speeds})
    kane = dict(zip(km.u, M.LUsolve(f)[len(F["q"]):]))
    assert set(kane) == set(speeds)                   # one acceleration per coordinate
    return max(abs(float(ours[c.diff(t, 2)].xreplace({**vel, **point}))
                   - float(kane[dynamicsymbols(f"u_{c.func.__name__}")])) for c in F["q"])


@pytest.mark.parametrize("name, n", [("chain", 7), ("rotors", 9), ("coins", 8)])
def test_each_peer_family_is_the_same_system_for_us_and_kane(name, n):
    """Each family of the Kane comparison (issue 34), two bodies coupled and (chain,
    rotors) a particle z_1: our accelerations are KanesMethod's at random points, so
    both sides solve the same system (a wrong load or a constraint on one side only
    changes them: the coins' gravity counted twice gave 0.2)."""
    for seed in (1, 2):
        assert _kane_accelerations_agree(name, n, seed) < 1e-9


def test_every_peer_family_benchmark_runs_and_prints(record_property):
    """``--family all`` at n = 4: each family's table against both peers; times printed,
    not asserted; every check of the derivation held."""
    import contextlib
    import io
    from whittaker_teach.__main__ import main
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        code = main(["bench", "derivation", "--scale", "--family", "all", "--n", "4",
                     "--repeat", "1"])
    text = out.getvalue()
    record_property("printed", "\n" + text)
    assert code == 0
    for name, (build, title) in bench.PEER_FAMILIES.items():
        assert title in text
        assert len(build(4)["coneqs"]) >= 1
    rows = [line.split() for line in text.splitlines() if line.startswith("  4 ")]
    assert len(rows) == 3 and all(r[-1] == "held" for r in rows)
    assert all(float(v) > 0 for r in rows for v in r[1:6])


def test_family_option_lists_each_peer_family():
    from whittaker_teach.__main__ import main
    import contextlib
    import io
    out = io.StringIO()
    with contextlib.redirect_stdout(out), pytest.raises(SystemExit):
        main(["bench", "derivation", "--help"])
    listed = out.getvalue().replace("\n", " ")
    assert all(name in listed for name in [*bench.PEER_FAMILIES, "all"])
    with contextlib.redirect_stderr(io.StringIO()), pytest.raises(SystemExit):
        main(["bench", "derivation", "--scale", "--family", "lattice"])
