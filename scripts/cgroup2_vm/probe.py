"""The grader's cgroup v2 code (whittaker_teach.grading.sandbox) against a real kernel.

Run by scripts/cgroup2_vm/guest.sh as root, alone in a delegated group of a
cgroup-v2-only machine.  Prints each check and what the kernel's files said; exits 1
if any check failed.
"""
import os
import subprocess
import sys
import time
from pathlib import Path

from whittaker_teach.grading import sandbox

failed = []


def check(what, ok, detail=""):
    print(("ok   " if ok else "FAIL ") + what + (f"  [{detail}]" if detail else ""))
    if not ok:
        failed.append(what)


def read(p):
    try:
        return Path(p).read_text().strip()
    except OSError as exc:
        return f"<{exc}>"


def own_group():
    return [line.split(":", 2)[2] for line in read("/proc/self/cgroup").splitlines()
            if line.startswith("0::")][0]


def run_in(group, code, timeout=60):
    """Run ``python -c code`` as the group's first process (as the sandbox's sh does)."""
    join = "for f in " + " ".join(f"'{p}'" for p in group.procs) + \
        "; do echo $$ > \"$f\" || exit 97; done; exec \"$@\""
    return subprocess.run(["/bin/sh", "-c", join, "sh", sys.executable, "-c", code],
                          capture_output=True, text=True, timeout=timeout)


start = own_group()
base = Path("/sys/fs/cgroup") / start.lstrip("/")
print(f"the probe runs in {start}; cgroup.controllers: {read(base / 'cgroup.controllers')}; "
      f"subtree_control: {read(base / 'cgroup.subtree_control')!r}")
found = sandbox.Hierarchy.find()
check("find: the v2 group is this process's own, with memory pids cpu",
      found.v2 == base and found.v2_controllers == ("memory", "pids", "cpu") and not found.v1,
      f"v2={found.v2} controllers={found.v2_controllers} v1={found.v1}")

where = sandbox.hierarchy()             # find().prepare(), as grade does
leaf = base / f"wt-grade-{os.getpid()}-grader"
check("prepare: every controller by cgroup v2, no note",
      [where.mechanism(c) for c in ("memory", "pids", "cpu")] == ["cgroup v2"] * 3
      and not where.why, f"why={where.why!r}")
check("prepare: the grader moved into its leaf", own_group() == f"{start}/{leaf.name}",
      own_group())
check("prepare: the delegated group enables memory pids cpu for its children",
      set(read(base / "cgroup.subtree_control").split()) >= {"memory", "pids", "cpu"},
      read(base / "cgroup.subtree_control"))
lines = dict(sandbox.enforced(sandbox.Limits(), 300, where))
for k in ("memory", "processes", "CPU"):
    print(f"     enforced {k}: {lines[k]}")
check("enforced: memory.max, pids.max and cpu.max by cgroup v2",
      "(cgroup v2 memory.max)" in lines["memory"] and "(cgroup v2 pids.max)" in
      lines["processes"] and "(cgroup v2 cpu.max)" in lines["CPU"])

# the limits as written, read back from the kernel
limits = sandbox.Limits(memory_mb=64, pids=12, disk_mb=10, cpus=0.25)
g = sandbox.Cgroups.make(f"wt-grade-{os.getpid()}-limits", limits)
files = {f: read(g.v2 / f) for f in ("memory.max", "memory.swap.max", "memory.oom.group",
                                     "pids.max", "cpu.max")}
print("     the kernel's files:", files)
check("group: the limits are the kernel's",
      files == {"memory.max": str(64 * 1024 * 1024), "memory.swap.max": "0",
                "memory.oom.group": "1", "pids.max": "12", "cpu.max": "25000 100000"}
      and g.v2_controllers == ("memory", "pids", "cpu"), str(g.v2_controllers))

# memory: a process that touches 200 MB in a 64 MB group is killed by the group's OOM
p = run_in(g, "b = bytearray(200_000_000); b[::4096] = b'x' * len(b[::4096]); print('alive')")
events = read(g.v2 / "memory.events").replace("\n", ", ")
check("memory: killed by the OOM killer, memory.events counts it, hit() says memory",
      p.returncode == -9 and "alive" not in p.stdout and "memory" in g.hit(),
      f"exit {p.returncode}; memory.events: {events}; hit={sorted(g.hit())}")

# pids: 30 children in a group of 12 processes and threads
p = run_in(g, "import os, time\nmade = refused = 0\nfor _ in range(30):\n"
           "    try:\n        pid = os.fork()\n    except OSError:\n        refused += 1\n"
           "        continue\n    if pid == 0:\n        os.closerange(0, 3)\n        time.sleep(30)\n        os._exit(0)\n"
           "    made += 1\nprint(made, refused)")
pe = read(g.v2 / "pids.events")
check("pids: forks refused at pids.max, pids.events counts them, hit() says pids",
      p.stdout.split()[-1:] != ["0"] and "pids" in g.hit(),
      f"made, refused: {p.stdout.strip()}; pids.events: {pe}; pids.current "
      f"{read(g.v2 / 'pids.current')}; hit={sorted(g.hit())}")

# close: kills the sleeping children (cgroup.kill) and removes the group
t = time.monotonic()
g.close()
check("close: the group is gone with its processes", not g.v2.exists(),
      f"{time.monotonic() - t:.2f} s")

# cpu: two spinning processes for 4 s in a group of a quarter CPU
g = sandbox.Cgroups.make(f"wt-grade-{os.getpid()}-cpu", limits)
spin = ("import time, subprocess, sys\n"
        "k = subprocess.Popen([sys.executable, '-c', 'import time\\nend = time.time() + 4\\n"
        "while time.time() < end: pass'])\nend = time.time() + 4\n"
        "while time.time() < end: pass\nk.wait()")
t = time.monotonic()
p = run_in(g, spin)
wall = time.monotonic() - t
stat = dict(line.split() for line in read(g.v2 / "cpu.stat").splitlines())
used = int(stat["usage_usec"]) / 1e6
print(f"     cpu.stat: {stat}")
check("cpu: throttled (cpu.stat nr_throttled, throttled_usec), about 0.25 CPU used",
      int(stat.get("nr_throttled", 0)) > 0 and int(stat.get("throttled_usec", 0)) > 0
      and used < 0.25 * wall * 1.5 + 0.3,
      f"{used:.2f} s of CPU in {wall:.2f} s of wall time: {used / wall:.2f} CPU; two "
      "spinning processes unlimited would use up to 2")
g.close()
check("close: the cpu group is gone", not g.v2.exists())

# release: the grader back in its own group, the leaf gone, the controllers given back
sandbox.release()
check("release: back in the delegated group, leaf removed, subtree_control empty",
      own_group() == start and not leaf.exists() and read(base / "cgroup.subtree_control")
      == "", f"group {own_group()}, leaf there: {leaf.exists()}, subtree_control "
      f"{read(base / 'cgroup.subtree_control')!r}")

# cgroup_limits() after release (tests/integration/test_grade_attacks.py calls it after
# grade() has released the hierarchy, then looks for groups left behind)
got = sandbox.cgroup_limits()
left = sorted(p.name for p in base.iterdir() if p.name.startswith("wt-grade-"))
check("cgroup_limits() after release leaves no wt-grade-* group behind", left == [],
      f"cgroup_limits()={got}; left under {base}: {left}; this process in {own_group()}")
sandbox.release()
left = sorted(p.name for p in base.iterdir() if p.name.startswith("wt-grade-"))
check("... and none after a second release()", left == [] and own_group() == start,
      f"left: {left}; in {own_group()}")



def cgroup_limits_patched():
    """sandbox.cgroup_limits with the patch proposed in /tmp/cgroup2_findings.md."""
    with sandbox._HIERARCHY_LOCK:
        prepared = bool(sandbox._HIERARCHY)
    group = sandbox.Cgroups.make(f"wt-grade-probe-{os.getpid()}", sandbox.Limits())
    try:
        return group.enforced
    finally:
        group.close()
        if not prepared:
            sandbox.release()


got = cgroup_limits_patched()
left = sorted(p.name for p in base.iterdir() if p.name.startswith("wt-grade-"))
print(f"     with the proposed patch: cgroup_limits()={got}; left: {left}; in {own_group()}; "
      f"subtree_control {read(base / 'cgroup.subtree_control')!r}")
patched_ok = got == ["cpu", "memory", "pids"] and left == [] and own_group() == start

print("FAILED: " + "; ".join(failed) if failed else "all checks passed")
print("the proposed patch of cgroup_limits: " + ("leaves nothing" if patched_ok else
                                                   "DOES NOT HELP"))
sys.exit(1 if failed else 0)
