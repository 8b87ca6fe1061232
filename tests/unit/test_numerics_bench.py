"""The work-precision benchmark: its command line, outputs and summary (a tiny study;
no assertion on timings)."""

import json

import pytest

from whittaker_teach import __main__ as cli
from whittaker_teach.numerics import work_precision as wp

TINY = {"periods": 1, "rtols": (1e-5, 1e-8), "dla_steps": (16,), "repeat": 1}


@pytest.fixture(scope="module")
def tiny():
    return wp.study(quick=True, progress=False, amplitudes=(0.3,), methods=("DOP853", "Radau"),
                    rtols=TINY["rtols"], dla_steps=TINY["dla_steps"], periods=1)


def test_records(tiny):
    runs = tiny["runs"]
    assert {r["model"] for r in runs} == {"full", "reduced", "DLA", "exact"}
    for r in runs:
        assert r["error"] == max(r["err_theta"], r["err_x"], r["err_y"])
        assert r["seconds"] > 0
    full = [r for r in runs if r["model"] == "full" and r["method"] == "DOP853"]
    assert full[1]["error"] < full[0]["error"] < 1e-2         # tighter rtol, smaller error
    assert all(r["err_energy"] is None for r in runs if r["model"] == "reduced")
    exact = [r for r in runs if r["model"] == "exact"][0]
    assert exact["error"] < 1e-14
    assert tiny["exact_cost"]["0.3"]["scalar"] > 0


def test_summary_and_table(tiny):
    best = wp.cheapest(tiny, targets=(1e-3, 1e-12))
    row = best[0.3][1e-3]
    assert row["full"] is not None and row["reduced"] is not None
    assert row["ratio"] == pytest.approx(row["reduced"]["seconds"] / row["full"]["seconds"])
    assert best[0.3][1e-12]["exact"]["model"] == "exact"
    text = wp.summary(tiny)
    assert "reduced / full" in text and "one exact evaluation" in text
    assert "err theta" in wp.table(tiny)


def test_plot_is_deterministic(tiny, tmp_path):
    pytest.importorskip("matplotlib")
    a, b = tmp_path / "a.svg", tmp_path / "b.svg"
    wp.plot(tiny, a)
    wp.plot(tiny, b)
    assert a.read_bytes() == b.read_bytes() and b"<svg" in a.read_bytes()


def test_command_line(monkeypatch, tmp_path, capsys):
    monkeypatch.setattr(wp, "QUICK", TINY)
    monkeypatch.setattr(wp, "AMPLITUDES", (0.3,))
    out = tmp_path / "wp.json"
    real = wp.study
    monkeypatch.setattr(wp, "study", lambda quick, progress: real(
        quick=quick, progress=progress, amplitudes=(0.3,), methods=("DOP853",)))
    assert cli.main(["bench", "numerics", "--quick", "--quiet", "--json", str(out)]) == 0
    printed = capsys.readouterr().out
    assert "cheapest run with error <= target" in printed and "error 1e-06" in printed
    assert json.loads(out.read_text())["meta"]["periods"] == 1


def test_failed_run_is_recorded_not_raised():
    res = {"meta": {"amplitudes": [1.5], "periods": 1, "repeat": 1},
           "runs": [{"amplitude": 1.5, "model": "reduced", "method": "RK45", "setting": 1e-3,
                     "failed": "ChartError: qdot_x vanishes at x = 1"}],
           "exact_cost": {}}
    assert "failed: ChartError" in wp.table(res)
    assert wp.cheapest(res)[1.5][1e-6]["reduced"] is None
