"""Check what the VM recorded of the hand-made class (scripts/cgroup2_vm/make_class.py).

usage: python check_class.py OUT    (OUT: the folder guest.sh wrote; exit 1 on a failure)

(a) grade printed, at its start, that memory, processes and CPU are limited by cgroup v2;
(b) the honest student is graded right, each attack is held and reported as the grader
    documents it, and the kernel's own counters (recorded by monitor.py) show it:
    memory.events oom_kill, pids.events max, cpu.stat nr_throttled/throttled_usec;
(c) no wt-grade-* group, no process of the run and no temporary folder is left.
"""
import csv
import json
import sys
from pathlib import Path

out = Path(sys.argv[1])
failed = []


def check(what, ok, detail=""):
    print(("ok   " if ok else "FAIL ") + what + (f"  [{detail}]" if detail else ""))
    if not ok:
        failed.append(what)


stdout = (out / "class.stdout").read_text(errors="replace")
print("## grade's first lines:\n" + "\n".join(stdout.splitlines()[:10]) + "\n")
check("(a) memory by cgroup v2", "MB over all its processes (cgroup v2 memory.max)" in stdout)
check("(a) processes by cgroup v2", "processes and threads (cgroup v2 pids.max)" in stdout)
check("(a) CPU by cgroup v2", "CPU over all its processes (cgroup v2 cpu.max)" in stdout)
check("(a) no note that a controller could not be had", "\n  note:" not in stdout)

rows = {}
with open(out / "class.csv", newline="", encoding="utf-8") as f:
    for r in csv.DictReader(f):
        rows.setdefault(r["submission"], []).append(r)


def parts(name):
    return {r["part"]: r["ok"] == "True" for r in rows.get(name, []) if r["part"]}


def failure(name):
    return " ".join(r["message"] for r in rows.get(name, []) if not r["part"])


for name in sorted(rows):
    print(f"## {name}: parts {parts(name)}; failure: {failure(name)!r}")
check("(b) honest: every part right, no failure",
      parts("honest.ipynb") == {"L_star": True, "r_pp": True, "h": True}
      and not failure("honest.ipynb"))
check("(b) memory hog: its answer before the hog kept, 'reached the memory limit'",
      parts("memory-hog.ipynb").get("L_star") is True
      and "the memory limit (1000 MB over all its processes)" in failure("memory-hog.ipynb"))
check("(b) fork bomb: its answer kept, 'reached the limit of 128 processes and threads'",
      parts("fork-bomb.ipynb").get("L_star") is True
      and "the limit of 128 processes and threads" in failure("fork-bomb.ipynb"))
check("(b) CPU hog: slowed, not stopped: every part right",
      parts("cpu-hog.ipynb") == {"L_star": True, "r_pp": True, "h": True},
      failure("cpu-hog.ipynb"))

groups = json.loads((out / "class-groups.json").read_text())
subs = {k: v for k, v in groups.items() if not k.endswith("-grader")}
leaves = [k for k in groups if k.endswith("-grader")]
print(f"## {len(subs)} submission groups seen, grader leaf: {leaves}")


def flat(text):
    out = {}
    for line in (text or "").splitlines():
        k, _, v = line.partition(" ")
        try:
            out[k] = int(v)
        except ValueError:
            out[k] = v
    return out


oom = pids = throttled = 0
for path, rec in sorted(subs.items(), key=lambda kv: kv[1]["first_seen"]):
    last = rec["last"]
    me, pe, cs = flat(last["memory.events"]), flat(last["pids.events"]), flat(last["cpu.stat"])
    print(f"{Path(path).name}: memory.max={last['memory.max']} pids.max={last['pids.max']} "
          f"cpu.max={last['cpu.max']!r} memory.swap.max={last['memory.swap.max']} "
          f"memory.oom.group={last['memory.oom.group']} | oom_kill={me.get('oom_kill')} "
          f"pids.events max={pe.get('max')} peak pids={rec['peak'].get('pids.current')} "
          f"peak memory={rec['peak'].get('memory.current', 0) / 2**20:.0f} MB | "
          f"usage_usec={cs.get('usage_usec')} nr_periods={cs.get('nr_periods')} "
          f"nr_throttled={cs.get('nr_throttled')} throttled_usec={cs.get('throttled_usec')}")
    check("  its limits as the grader wrote them",
          last["memory.max"] == str(1000 * 2**20) and last["pids.max"] == "128"
          and last["cpu.max"] == "100000 100000" and last["memory.swap.max"] == "0"
          and last["memory.oom.group"] == "1")
    oom += bool(me.get("oom_kill"))
    pids += bool(pe.get("max"))
    throttled = max(throttled, cs.get("throttled_usec", 0) or 0)
check("(b) one group's memory.events counted an OOM kill (the memory hog)", oom == 1, oom)
check("(b) one group's pids.events counted forks refused at pids.max (the fork bomb)",
      pids == 1, pids)
check("(b) cpu.stat shows throttling at cpu.max (more than 1 s throttled in one group)",
      throttled > 1_000_000, f"{throttled / 1e6:.1f} s")

after = (out / "class-after.txt").read_text()
print("## after the run:\n" + after)
sections = after.split("## ")[1:]
left = {s.splitlines()[0]: [x for x in s.splitlines()[1:] if x.strip()] for s in sections}
check("(c) no wt-grade-* group left", not left[next(k for k in left if "groups left" in k)])
check("(c) no process of the run left",
      not left[next(k for k in left if "WHITTAKER_TEACH_RUN" in k)]
      and not left[next(k for k in left if "sandbox uids" in k)])
check("(c) the delegated group given back: no process, subtree_control empty",
      not left[next(k for k in left if "given back" in k)])
check("(c) no temporary folder left", not left[next(k for k in left if "temporary" in k)])
check("grade exit status 0", "grade exit status 0 " in stdout)
print("FAILED: " + "; ".join(failed) if failed else "all checks passed")
sys.exit(1 if failed else 0)
