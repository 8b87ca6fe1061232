"""An interrupted grader starts no new run: a thread that reaches the start of a run after
the interrupt (Ctrl-C while it was preparing) finds the stop set, starts nothing and says
so, and the next ``grade`` in the same process starts afresh."""

import subprocess

from whittaker_teach.grading import run as grade


def test_no_run_starts_after_an_interrupt(monkeypatch):
    started = []
    monkeypatch.setattr(subprocess, "Popen", lambda *a, **k: started.append(a))
    grade._stop_runs()
    try:
        result, failure, log = grade._run(b"{}", grade.Settings(unsafe=True))
    finally:
        grade._STOP.clear()
    assert (result, failure, log) == (None, "the grader was interrupted before this "
                                      "notebook ran", "")
    assert started == []
