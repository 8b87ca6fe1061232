#!/usr/bin/env python
"""The slowest single `check` over every answer of tests/unit/test_exercise_checks.py.

    PYTHONPATH=$PWD PYTHONHASHSEED=0 python scripts/time_checks.py

Each exercise is derived first (its first check); then every correct form,
mutation, bad input and denial-of-service answer of the tests is checked once
and timed.  Prints the five slowest checks and the median.
"""
import sys, time
sys.path.insert(0, str(__import__("pathlib").Path(__file__).resolve().parents[1] / "tests" / "unit"))
import test_exercise_checks as T
from whittaker_teach.exercises import check
times = []
def timed(ex, a, part):
    t = time.perf_counter(); check(ex, a, part=part); times.append((time.perf_counter() - t, ex, part, a[:70] if isinstance(a, str) else type(a).__name__))
for (ex, part) in sorted(T.CASES):
    check(ex, None, part=part)          # the exercise is derived first (not a check of an answer)
for (ex, part), (good, bad) in sorted(T.CASES.items()):
    for a in good + T.MORE_GOOD.get((ex, part), []):
        timed(ex, T._answer(a), part)
    for a, _ in bad:
        timed(ex, T._answer(a), part)
    a, _ = T.DOMAIN[(ex, part)]
    timed(ex, T._domain_mutation(a, ex, part) if str(a).startswith("DOM:") else T._answer(a), part)
    for a in T.BAD + T.DOS + T._dos_objects():
        timed(ex, a, part)
times.sort(reverse=True)
print(f"{len(times)} checks; slowest:")
for t in times[:5]:
    print(f"  {t[0]:.2f} s  {t[1]}/{t[2]}: {t[3]}")
print(f"median {sorted(x[0] for x in times)[len(times)//2]*1000:.0f} ms")
