"""Watch the grader's submission groups under a cgroup v2 folder while it runs.

usage: python monitor.py TOP OUT.json   (stops on SIGTERM, then writes OUT.json)

Every 0.5 s it reads, for each wt-grade-* group under TOP, the limits the grader wrote
(memory.max, memory.swap.max, memory.oom.group, pids.max, cpu.max) and what the kernel
counted (memory.events, pids.events, pids.current, cpu.stat, memory.current), and keeps
the last reading of each group and its peaks: the groups are removed when a submission
ends, so this is where their evidence survives.
"""
import json
import os
import signal
import sys
import time

FILES = ("memory.max", "memory.swap.max", "memory.oom.group", "pids.max", "cpu.max",
         "memory.events", "pids.events", "pids.current", "cpu.stat", "memory.current",
         "cgroup.controllers")


def read(path):
    try:
        with open(path, encoding="utf-8") as f:
            return f.read().strip()
    except OSError:
        return None


def main(top, out):
    stop = []
    signal.signal(signal.SIGTERM, lambda *_: stop.append(1))
    seen = {}
    while not stop:
        for d, dirs, _ in os.walk(top):
            for name in dirs:
                if not name.startswith("wt-grade-"):
                    continue
                path = os.path.join(d, name)
                now = {f: read(os.path.join(path, f)) for f in FILES}
                if now["cgroup.controllers"] is None:
                    continue                          # removed meanwhile
                rec = seen.setdefault(path, {"first_seen": time.time(), "peak": {}})
                rec["last"] = now
                rec["last_seen"] = time.time()
                for f in ("pids.current", "memory.current"):
                    try:
                        rec["peak"][f] = max(rec["peak"].get(f, 0), int(now[f]))
                    except (TypeError, ValueError):
                        pass
        time.sleep(0.5)
    with open(out, "w", encoding="utf-8") as f:
        json.dump(seen, f, indent=1)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
