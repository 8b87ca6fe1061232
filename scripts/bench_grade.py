"""Grade a class of 30 with and without the sandbox and print the times (issue 24).

    python scripts/bench_grade.py [--repeat 2] [--jobs 2] [--n 30]

A generated class of kepler-orbit notebooks (right answers as strings and as
SymPy objects, wrong, partly answered, blank), graded ``--repeat`` times in
each mode, the modes alternating (sandbox, unsafe, unsafe, sandbox, ...) so
that a busy machine disturbs both alike; prints every run and the medians.  Needs
root and bubblewrap for the sandboxed runs.  A benchmark, not a test: it
asserts only that both modes give the same grades.
"""
import argparse
import statistics
import sys
import tempfile
import time
from pathlib import Path

import nbformat

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from tests.integration.kepler_answers import EX, RIGHT, WRONG  # noqa: E402
from whittaker_teach.grading import run as grading  # noqa: E402

SYMPY = ("import sympy as sp\nm, mu, p, r = sp.symbols('m mu p r', positive=True)\n"
         "h, e, rp = sp.symbols('h e rprime')\n"
         f"check({EX!r}, sp.sqrt(2*h + 2*m*mu/r)*sp.sqrt(m*(r**2 + rp**2)), part='L_star')\n"
         f"check({EX!r}, m*mu*(e**2 - 1)/(2*p), part='h')")


def student(kind, i):
    cells = ["from whittaker_teach.notebook import setup; setup()",
             "from whittaker_teach.exercises import check"]
    answers = {"right": RIGHT, "wrong": WRONG, "blank": dict.fromkeys(RIGHT)}.get(kind)
    if kind == "sympy":
        cells.append(SYMPY)
    elif kind == "partly":
        answers = {**WRONG, "L_star": RIGHT["L_star"], "h": None}
    for part, text in (answers or {}).items():
        cells.append(f"check({EX!r}, {text!r}, part={part!r})")
    nb = nbformat.v4.new_notebook()
    nb.metadata["whittaker_teach"] = {"exercise": EX}
    nb.cells = [nbformat.v4.new_code_cell(c) for c in cells]
    return nb


def make_class(folder, n):
    kinds = ["right"] * 10 + ["sympy"] * 5 + ["wrong"] * 8 + ["partly"] * 4 + ["blank"] * 3
    paths = []
    for i in range(n):
        path = folder / f"student{i:02d}.ipynb"
        nbformat.write(student(kinds[i % len(kinds)], i), path)
        paths.append(str(path))
    return paths


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=2)
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--n", type=int, default=30)
    args = ap.parse_args(argv)
    from whittaker_teach.exercises import sandbox
    why = sandbox.available()
    if why:
        sys.exit(f"bench_grade: no sandbox here ({why})")
    with tempfile.TemporaryDirectory() as tmp:
        paths = make_class(Path(tmp), args.n)
        times, grades = {"sandbox": [], "unsafe": []}, {}
        for r in range(args.repeat):
            for mode in (("sandbox", "unsafe") if r % 2 == 0 else ("unsafe", "sandbox")):
                start = time.monotonic()
                rows, line = grading.grade(paths, str(Path(tmp) / f"{mode}.csv"),
                                           jobs=args.jobs, quiet=True,
                                           unsafe=(mode == "unsafe"))
                took = time.monotonic() - start
                times[mode].append(took)
                grades.setdefault(mode, [(x.submission, x.part, x.ok) for x in rows])
                print(f"run {r + 1} {mode:8s} {took:6.1f} s  {line}", flush=True)
        assert grades["sandbox"] == grades["unsafe"], "the two modes graded differently"
    s, u = statistics.median(times["sandbox"]), statistics.median(times["unsafe"])
    print(f"class of {args.n}, {args.jobs} at a time: median {s:.1f} s with the sandbox, "
          f"{u:.1f} s without: {100 * (s / u - 1):+.0f}% for the sandbox")


if __name__ == "__main__":
    main()
