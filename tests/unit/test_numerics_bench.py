"""The work-precision benchmark: its run set, outputs and summary (tiny studies; no
assertion on timings)."""

import json

import pytest

from whittaker_teach import __main__ as cli
from whittaker_teach.numerics import work_precision as wp

TINY = {"periods": 1, "rtols": (1e-5, 1e-8), "dla_steps": (16,), "repeat": 1,
        "methods": ("DOP853",)}


@pytest.fixture(scope="module")
def tiny():
    return wp.study(quick=True, progress=False, amplitudes=(0.3,), methods=("DOP853", "LSODA"),
                    rtols=TINY["rtols"], dla_steps=TINY["dla_steps"], periods=1, repeat=3)


def test_records(tiny):
    runs = tiny["runs"]
    assert {r["model"] for r in runs} == set(wp.MODELS)
    for r in runs:
        assert r["error"] == max(r["err_theta"], r["err_x"], r["err_y"], r["err_t"])
        assert len(r["times"]) == 3 and r["seconds"] > 0
    full = [r for r in runs if r["model"] == "full" and r["method"] == "DOP853"]
    assert full[1]["error"] < full[0]["error"] < 1e-2         # tighter rtol, smaller error
    hand = [r for r in runs if r["model"] == "numpy+scipy" and r["method"] == "DOP853"]
    assert [r["nfev"] for r in hand] == [r["nfev"] for r in full]   # the same equations
    exact = [r for r in runs if r["model"] == "exact"][0]
    assert exact["err_x_abs"] < 1e-14


def test_run_set_and_picks_do_not_depend_on_speed(tiny):
    again = wp.study(quick=True, progress=False, amplitudes=(0.3,), methods=("DOP853", "LSODA"),
                     rtols=TINY["rtols"], dla_steps=TINY["dla_steps"], periods=1, repeat=1)
    assert wp.run_set(again) == wp.run_set(tiny)
    assert wp.picks(again) == wp.picks(tiny)


def test_budget_in_evaluations(monkeypatch):
    """Over the budget, a ladder that has reached the tightest target stops; one that
    has not goes on (review C, item 4: a cut ladder made a looser run stand in), up
    to the cap, and the summary then says so."""
    monkeypatch.setattr(wp, "NFEV_BUDGET", 250)
    monkeypatch.setattr(wp, "TARGETS", (1e-3,))
    res = wp.study(quick=True, progress=False, amplitudes=(0.3,), methods=("DOP853",),
                   rtols=(1e-3, 1e-6, 1e-9), dla_steps=(), periods=1, repeat=1,
                   alternatives=False)
    full = [r for r in res["runs"] if r["model"] == "full"]
    assert full[-1]["nfev"] > 250 and all(r["nfev"] <= 250 for r in full[:-1])
    assert full[-1]["error"] <= 1e-3 and len(full) < 3
    monkeypatch.setattr(wp, "TARGETS", (1e-14,))      # out of reach: the ladder goes on
    res = wp.study(quick=True, progress=False, amplitudes=(0.3,), methods=("DOP853",),
                   rtols=(1e-3, 1e-6, 1e-9), dla_steps=(), periods=1, repeat=1,
                   alternatives=False)
    full = [r for r in res["runs"] if r["model"] == "full"]
    assert len(full) == 3 and full[1]["nfev"] > 250
    assert "not reached" in wp.summary(res) and "within budget" not in wp.summary(res)
    cap = full[1]["nfev"]                               # ... until the cap, then says so
    monkeypatch.setattr(wp, "NFEV_CAP", cap - 1)
    res = wp.study(quick=True, progress=False, amplitudes=(0.3,), methods=("DOP853",),
                   rtols=(1e-3, 1e-6, 1e-9), dla_steps=(), periods=1, repeat=1,
                   alternatives=False)
    full = [r for r in res["runs"] if r["model"] == "full"]
    assert len(full) == 2 and full[-1]["nfev"] == cap
    assert "not reached within budget" in wp.summary(res)


def test_summary_and_table(tiny):
    best = wp.cheapest(tiny, targets=(1e-3, 1e-12))
    row = best[0.3][1e-3]
    assert row["full"] is not None and row["reduced"] is not None
    assert best[0.3][1e-12]["exact"]["model"] == "exact"
    assert best[0.3]["floor"]["full"]["error"] == min(
        r["error"] for r in tiny["runs"] if r["model"] == "full")
    text = wp.summary(tiny)
    assert "floor" in text and "package / numpy+scipy" in text
    assert max(len(line) for line in text.splitlines()) <= 80
    assert max(len(line) for line in wp.table(tiny).splitlines()) <= 86
    assert "floor by distance from the exact path" in text
    [paired, *_] = tiny["ratios"]["0.3"].values()
    assert paired["ratio"] == pytest.approx(paired["package"] / paired["hand"])
    assert f"{paired['ratio']:.2f}" in text and "full model, timed 15 times alternately" in text


def test_path_error_leaves_out_only_the_clock(tiny):
    """Every run: the distance from the path is at most the state error (up to the
    factor 2 of four components against the largest one), never zero."""
    for r in tiny["runs"]:
        if "failed" not in r and r["model"] != "exact":
            assert 0 < r["err_path"] <= 2 * r["error"], r
    assert wp.to_csv(tiny).splitlines()[0].startswith("amplitude,model,method")


def test_plot_is_deterministic(tiny, tmp_path):
    pytest.importorskip("matplotlib")
    a, b = tmp_path / "a.svg", tmp_path / "b.svg"
    wp.plot(tiny, a)
    wp.plot(tiny, b)
    assert a.read_bytes() == b.read_bytes() and b"<svg" in a.read_bytes()


def test_command_line(monkeypatch, tmp_path, capsys):
    monkeypatch.setattr(wp, "QUICK", TINY)
    out, csv = tmp_path / "wp.json", tmp_path / "wp.csv"
    real = wp.study
    monkeypatch.setattr(wp, "study", lambda quick, progress: real(
        quick=quick, progress=progress, amplitudes=(0.3,)))
    assert cli.main(["bench", "numerics", "--quick", "--quiet", "--json", str(out),
                     "--csv", str(csv)]) == 0
    printed = capsys.readouterr().out
    assert "cheapest run (by evaluations)" in printed and "error 1e-06" in printed
    assert json.loads(out.read_text())["meta"]["periods"] == 1
    assert csv.read_text().count("\n") == len(json.loads(out.read_text())["runs"]) + 1


@pytest.mark.slow
def test_quick_study_is_reproducible():
    """`bench numerics --quick` twice: the same run set, the same picks by evaluations."""
    a = wp.study(quick=True, progress=False, repeat=1)
    b = wp.study(quick=True, progress=False, repeat=1)
    assert wp.run_set(a) == wp.run_set(b) and wp.picks(a) == wp.picks(b)


def test_failed_run_is_recorded_not_raised():
    res = {"meta": {"amplitudes": [1.5], "periods": 1, "repeat": 1},
           "runs": [{"amplitude": 1.5, "model": "reduced", "method": "RK45", "setting": 1e-3,
                     "failed": "ChartError: qdot_x vanishes at x = 1"}],
           "exact_cost": {}}
    assert "failed: ChartError" in wp.table(res)
    assert wp.cheapest(res)[1.5][1e-6]["reduced"] is None


def test_stored_study_ladders_not_cut_short():
    """The book's stored study follows the ladder rule: a ladder ends over its budget
    only once it has reached the tightest target, or at the cap (review C, item 4:
    the stored reduced DOP853 ladder at a = 1.5 once ended at 31 106 evaluations and
    6.7e-12, and a DOP853-tight run stood in for it)."""
    import json
    from pathlib import Path
    res = json.loads((Path(__file__).resolve().parents[2] / "book" / "figures" / "numerics"
                      / "work_precision.json").read_text())
    meta, tight = res["meta"], min(wp.TARGETS)
    ladders = {}
    for r in res["runs"]:
        if "failed" not in r and r["method"] not in (wp.TIGHT, "DLA") and r["model"] != "exact":
            ladders.setdefault((r["amplitude"], r["model"], r["method"]), []).append(r)
    assert len(ladders) > 10
    for key, runs in ladders.items():
        for r in runs[:-1]:                  # no ladder went on past a legitimate end
            assert not (r["nfev"] > meta["nfev_cap"]
                        or (r["nfev"] > meta["nfev_budget"] and r["error"] <= tight)), key
        last = runs[-1]
        ended_early = last["setting"] != meta["rtols"][-1]
        if ended_early:
            assert last["nfev"] > meta["nfev_cap"] or (
                last["nfev"] > meta["nfev_budget"] and last["error"] <= tight), key
    reduced = wp.cheapest(res)[1.5][1e-12]["reduced"]
    assert reduced["method"] == "DOP853" and reduced["nfev"] < meta["nfev_cap"]
