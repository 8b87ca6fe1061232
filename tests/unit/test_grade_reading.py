"""The grader never parses a submission itself: each notebook is read and validated in a
child process with memory and CPU limits, and only a small summary comes back (issue 37,
item 5: a 4.8 MB notebook of empty JSON objects took the grader to 927 MB)."""
import json
import resource

import pytest

from whittaker_teach.grading import run


def notebook(cells, metadata=None):
    return json.dumps({"nbformat": 4, "nbformat_minor": 5, "metadata": metadata or {},
                       "cells": cells}).encode()


def code(source):
    return {"cell_type": "code", "id": "a" * 8, "metadata": {}, "source": source,
            "outputs": [], "execution_count": None}


def test_a_notebook_is_summarised_not_returned(tmp_path):
    p = tmp_path / "n.ipynb"
    p.write_bytes(notebook([code(["x = 1\n", "check('sledge-L-star', x)"]),
                            code("check(\"kepler-orbit\", 2)")],
                           {"whittaker_teach": {"exercise": "sledge-L-star"}}))
    got, why = run.read_submission(p)
    assert why is None and not hasattr(got, "cells")
    assert got.claimed == "sledge-L-star" and got.named == ["sledge-L-star", "kepler-orbit"]
    assert run.exercise_of(got) == "sledge-L-star"


@pytest.mark.parametrize("raw, why", [
    (b'{"nbformat": 4, "cells": [' + b"{}," * 10 + b"{}]}", "not a valid notebook"),
    (b'{"nbformat": 3}', "format 4"),
    (b'{"nbformat": 4, "cells": [', "truncated"),
])
def test_bad_notebooks_are_refused_with_a_reason(tmp_path, raw, why):
    p = tmp_path / "bad.ipynb"
    p.write_bytes(raw)
    got, reason = run.read_submission(p)
    assert got is None and why in reason


def test_a_huge_notebook_costs_the_grader_no_memory(tmp_path, monkeypatch):
    """1.6 million empty cells (4.8 MB): refused within the child's limits, while the
    grader's own peak memory does not grow by the hundreds of MB parsing would take."""
    monkeypatch.setattr(run, "VALIDATE_SECONDS", 3)
    p = tmp_path / "huge.ipynb"
    p.write_bytes(b'{"nbformat": 4, "metadata": {}, "cells": [' + b"{}," * 1_600_000 + b"{}]}")
    before = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    got, why = run.read_submission(p)
    grown = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss - before     # kB on Linux
    assert got is None and "not gradable" in why, why
    assert grown < 100_000, f"the grader's peak grew by {grown // 1000} MB"
