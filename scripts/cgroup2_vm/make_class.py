"""Write the small hand-made class graded in the cgroup v2 VM (scripts/cgroup2_vm.py).

usage: python make_class.py FOLDER

An honest student, a memory hog (children that together pass the memory limit, each
within its own RLIMIT_AS), a fork bomb (far more processes than pids.max) and a CPU hog
(spinning processes, more than the notebook's cpu.max share).  Each attack first hands
in one right answer, so its row shows the run went on until the limit was reached.
"""
import sys
from pathlib import Path

import nbformat

sys.path.insert(0, str(Path(__file__).resolve().parents[2]))
from tests.integration.kepler_answers import EX, RIGHT  # noqa: E402

START = "from whittaker_teach.exercises import check\nimport os, sys, time, subprocess"


def checks(parts):
    return "\n".join(f"check({EX!r}, {RIGHT[p]!r}, part={p!r})" for p in parts)


CLASS = {
    "honest.ipynb": [START, checks(RIGHT)],
    # 5 children x 300 MB, touched: 1500 MB over a 1000 MB memory.max (each child stays
    # under the per-process RLIMIT_AS): the cgroup's OOM killer ends the group
    "memory-hog.ipynb": [START, checks(["L_star"]),
                         "kids = [subprocess.Popen([sys.executable, '-c', \"b = bytearray("
                         "300_000_000); b[::4096] = b'x' * len(b[::4096]); "
                         "import time; time.sleep(120)\"]) for _ in range(5)]\n"
                         "time.sleep(60)"],
    # 1000 sleeping children: far more than pids.max (128 processes and threads)
    "fork-bomb.ipynb": [START, checks(["L_star"]),
                        "made, refused = 0, 0\n"
                        "for _ in range(1000):\n"
                        "    try:\n"
                        "        if os.fork() == 0:\n"
                        "            time.sleep(600)\n"
                        "            os._exit(0)\n"
                        "        made += 1\n"
                        "    except OSError:\n"
                        "        refused += 1\n"
                        "print('made', made, 'refused', refused)\n"
                        "assert refused == 0, f'fork refused {refused} times'"],
    # 3 spinning processes for 40 s of wall time: 120 s of CPU wanted, cpu.max allows
    # --cpus of it; the children report the CPU time they got
    "cpu-hog.ipynb": [START, checks(["L_star"]),
                      "spin = \"import time, os\\nend = time.time() + 40\\n"
                      "while time.time() < end: pass\\nprint(time.process_time())\"\n"
                      "kids = [subprocess.Popen([sys.executable, '-c', spin], "
                      "stdout=subprocess.PIPE, text=True) for _ in range(3)]\n"
                      "got = [float(k.communicate()[0]) for k in kids]\n"
                      "print('CPU seconds per child in 40 s of wall time:', got)",
                      checks(["r_pp", "h"])],
}


def main(folder):
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    for name, cells in CLASS.items():
        nb = nbformat.v4.new_notebook()
        nb.metadata["whittaker_teach"] = {"exercise": EX}
        nb.cells = [nbformat.v4.new_code_cell(c) for c in cells]
        nbformat.write(nb, folder / name)
    print(f"{len(CLASS)} notebooks in {folder}")


if __name__ == "__main__":
    main(sys.argv[1])
