"""A hostile class, graded in one batch: each attack class of issue 24 beside honest and wrong
students.

Every test below reads the same batch (graded once, two at a time, in the sandbox):
the honest students are graded right, the wrong one wrong, each attack is held (its own
rows only, nothing from its kernel in the CSV or the feedback), nothing is left running,
nothing is written outside the sandboxes' scratch.  Needs root and bubblewrap (as CI has);
elsewhere these tests skip and ``grade`` refuses to run without ``--unsafe``.
"""
import csv
import json
import os
import socket
import threading
from pathlib import Path

import nbformat
import pytest

from whittaker_teach.grading import run as grading
from whittaker_teach.grading import sandbox

from .kepler_answers import EX, RIGHT, WRONG

# one xdist worker for every test that grades in the sandbox: the sandbox uids are the
# same in each batch, and a test that looks for processes left running would see
# another batch's (make unit runs with --dist loadgroup)
pytestmark = [pytest.mark.skipif(bool(sandbox.available()), reason=sandbox.available() or "-"),
              pytest.mark.xdist_group("sandbox")]

START = "from whittaker_teach.exercises import check\nimport os, sys, time, signal, json"
SECRET = "TOPSECRET-7f3a"
MEMORY_MB, DISK_MB = 1000, 64


def checks(answers, parts=None):
    return "\n".join(f"check({EX!r}, {answers[p]!r}, part={p!r})" for p in (parts or RIGHT))


def steal(found):
    """Cell: if ``found`` (a Python condition) holds, hand in the right answers, else wrong ones."""
    return f"if {found}:\n    " + checks(RIGHT).replace("\n", "\n    ") + \
        "\nelse:\n    " + checks(WRONG).replace("\n", "\n    ")


SCAN_OTHERS = '''
def others():
    """What this kernel can see of anything but its own sandbox."""
    seen = []
    for pid in os.listdir("/proc"):
        if not pid.isdigit():
            continue
        try:
            cmd = open(f"/proc/{pid}/cmdline", "rb").read().decode(errors="replace")
        except OSError:
            continue
        if ".ipynb" in cmd and "/grade/submission.ipynb" not in cmd:
            seen.append(cmd)
        try:
            for name in os.listdir(f"/proc/{pid}/root/scratch/.grade"):
                if int(pid) > 1 and open(f"/proc/{pid}/root/scratch/.grade/" + name).read() \\
                        != open(os.environ["WHITTAKER_TEACH_CHECK_LOG"]).read():
                    seen.append(name)
        except OSError:
            pass
    return seen


found = []
for _ in range(8):
    found += others()
    time.sleep(0.5)
'''

HUNT_ANSWERS = '''
found = []
for top, dirs, files in os.walk("/"):
    dirs[:] = [d for d in dirs if os.path.join(top, d) not in ("/proc", "/usr", "/dev")]
    for f in files:
        path = os.path.join(top, f)
        if ("whittaker" in path and (f == "catalog.py" or f.endswith(".ipynb")
                                     and path != "/grade/submission.ipynb")) \\
                or "solutions" in path or ("exercises" in path and f.endswith(".json")):
            found.append(path)
'''


KEYRINGS = '''
import ctypes
libc = ctypes.CDLL(None, use_errno=True)
libc.syscall.restype = ctypes.c_long
ADD, REQUEST, KEYCTL = {"x86_64": (248, 249, 250), "aarch64": (217, 218, 219)}[os.uname().machine]
RINGS = (-4, -5, -3)            # the uid's user and user-session keyrings, the session keyring
'''
# one submission stores a key in every keyring it has; the next (the same uid, as soon as
# the first gives it back) looks for it there, and for the session keyring it inherits
KEY_STORE = KEYRINGS + '''
found = [r for r in (libc.syscall(ADD, b"user", b"wt-attack", b"TOPSECRET-7f3a", 14, ring)
                     for ring in RINGS) if r > 0]
'''
KEY_READ = KEYRINGS + '''
found = []
for _ in range(20):
    found += [r for r in (libc.syscall(KEYCTL, 10, ring, b"user", b"wt-attack", 0)
                          for ring in RINGS) if r > 0]                      # KEYCTL_SEARCH
    found += [r for r in [libc.syscall(REQUEST, b"user", b"wt-attack", None, 0)] if r > 0]
    found += [r for r in [libc.syscall(KEYCTL, 0, -3, 0)] if r > 0]   # its session keyring
    if found:
        break
    time.sleep(0.5)
'''


def notebook(path, cells):
    nb = nbformat.v4.new_notebook()
    nb.metadata["whittaker_teach"] = {"exercise": EX}
    nb.cells = [nbformat.v4.new_code_cell(c) for c in cells]
    nbformat.write(nb, path)


def make_class(folder, outside):
    """{file name: {part: expected ok}} (None: not a notebook)."""
    right, wrong, none = dict.fromkeys(RIGHT, True), dict.fromkeys(RIGHT, False), {}
    first = {"L_star": True, "r_pp": False, "h": False}
    plan = {
        # honest and wrong students (names a spreadsheet would read as formulas, too)
        "honest_1.ipynb": ([START, checks(RIGHT)], right),
        "honest~1.ipynb": ([START, checks(RIGHT), "pass"], right),
        "=1+1.ipynb": ([START, checks(RIGHT)], right),
        "-dash.ipynb": ([START, checks(RIGHT)], right),
        "wrong.ipynb": ([START, checks(WRONG)], wrong),
        # one student stops the whole class
        "log-brackets.ipynb": ([START, checks(RIGHT, ["L_star"]),
                                "log = os.fdopen(int(os.environ['WHITTAKER_TEACH_CHECK_FD']), "
                                "'w', closefd=False)\n"
                                "log.write('[' * 100_000 + '\\n')\n"
                                "log.write('{\"a\": \"' + 'x' * 3_000_000 + '\\n')\n"
                                "log.write('{' * 50_000 + '\\n')\nlog.flush()"], first),
        "kill-grader.ipynb": ([START, checks(RIGHT, ["L_star"]),
                               "for pid in range(1, 400):\n    try:\n"
                               "        if pid != os.getpid(): os.kill(pid, 9)\n"
                               "    except OSError: pass\nos.kill(-1, 9)"], first),
        # students reach each other; answers in reach
        "snoop.ipynb": ([START, SCAN_OTHERS, steal("found")], wrong),
        "assassin.ipynb": ([START, "end = time.time() + 4\nwhile time.time() < end:\n"
                            "    for pid in os.listdir('/proc'):\n"
                            "        if pid.isdigit() and int(pid) != os.getpid():\n"
                            "            try:\n"
                            "                c = open(f'/proc/{pid}/cmdline','rb').read()\n"
                            "                if b'ipykernel' in c: os.kill(int(pid), 9)\n"
                            "            except OSError: pass\n    time.sleep(0.2)",
                            checks(WRONG)], wrong),
        "catalog.ipynb": ([START, "from whittaker_teach.exercises.catalog import EXERCISES\n"
                           "check('kepler-orbit', str(EXERCISES['kepler-orbit'].parts['h']"
                           ".expected), part='h')"], none),
        "solver.ipynb": ([START, "import whittaker_teach as wt\nk = wt.examples.kepler()",
                          "import whittaker_teach.reduction"], none),
        "hunt-solutions.ipynb": ([START, HUNT_ANSWERS, steal("found")], wrong),
        # kernel keyrings: a key stored for a later student, an inherited session keyring
        "keyring-a-store.ipynb": ([START, KEY_STORE, steal("found")], wrong),
        "keyring-b-read.ipynb": ([START, KEY_READ, steal("found")], wrong),
        # secrets
        "secrets.ipynb": ([START, checks(RIGHT, ["L_star"]),
                           f"check({EX!r}, os.environ.get('WT_GRADER_SECRET', 'nothing'), "
                           "part='h')",
                           f"s = open({str(outside / 'secret.txt')!r}).read()\n"
                           f"check({EX!r}, s, part='r_pp')"], first),
        "sockets-dev.ipynb": ([START, checks(RIGHT, ["L_star"]),
                               "import socket\ns = socket.socket(socket.AF_UNIX)\n"
                               f"s.connect({str(outside / 'lecturer.sock')!r})\n"
                               "s.sendall(b'hello')",
                               "open('/dev/wt-attack', 'w').write('x')",
                               "open('/proc/sys/kernel/hostname', 'w').write('x')"], first),
        # resources
        "forks-memory.ipynb": ([START, checks(RIGHT, ["L_star"]),
                                "import subprocess\n"
                                "kids = [subprocess.Popen([sys.executable, '-c', \"b = b'x' * "
                                "300_000_000; import time; time.sleep(30)\"]) "
                                "for _ in range(5)]\ntime.sleep(6)"], first),
        "processes.ipynb": ([START, checks(RIGHT, ["L_star"]),
                             "import subprocess\n"
                             "ps = [subprocess.Popen(['sleep', '600']) for _ in range(300)]"],
                            first),
        "daemon.ipynb": ([START, "if os.fork() == 0:\n    os.setsid()\n"
                          "    if os.fork() == 0:\n        time.sleep(600)\n    os._exit(0)",
                          checks(RIGHT)], right),
        # (answers first: the flood may end its own kernel, never the grader or the batch)
        "flood.ipynb": ([START, checks(RIGHT), "from IPython.display import display, HTML\n"
                         "for i in range(100):\n    display(HTML('x' * 1_000_000))",
                         "os.write(1, b'y' * 50_000_000)\nprint('z' * 20_000_000)"], right),
        "disk.ipynb": ([START, checks(RIGHT, ["L_star"]),
                        "for i in range(30):\n"
                        "    open(f'big{i}', 'wb').write(b'x' * 20_000_000)"], first),
        # output the lecturer opens
        "forged.ipynb": ([START, checks(WRONG),
                          "os.write(int(os.environ['WHITTAKER_TEACH_CHECK_FD']), json.dumps("
                          "{'exercise': 'kepler-orbit', 'part': 'h', 'kind': 'answer', "
                          "'answer': 'm*mu', 'status': 'correct', 'ok': True, "
                          "'why': 'Right: FORGED full marks', 'what': 'FORGED', "
                          "'message': 'Right: FORGED full marks'}).encode() + b'\\n')",
                          "class FORGED_full_marks(Exception):\n    pass\n"
                          "raise FORGED_full_marks('=HYPERLINK(\"http://evil\")')"], wrong),
    }
    expected = {}
    for name, (cells, oks) in plan.items():
        notebook(folder / name, cells)
        expected[name] = oks
    deep = '{"cells": ' + "[" * 100_000 + "]" * 100_000 + ', "nbformat": 4}'
    (folder / "deep.ipynb").write_text(deep, encoding="utf-8")
    expected["deep.ipynb"] = None
    # a name that is not UTF-8 (a zip extracted with another encoding): an honest student
    notebook(os.fsdecode(os.fsencode(folder) + b"/caf\xe9.ipynb"), [START, checks(RIGHT)])
    expected["caf\\xe9.ipynb"] = right
    # the solutions, reached through a folder link, a file link or a hard link: each would
    # be graded right if the grader followed it
    solutions = outside / "solutions"
    solutions.mkdir()
    notebook(solutions / "kepler-orbit.ipynb", [START, checks(RIGHT)])
    (folder / "linked").symlink_to(solutions)
    (folder / "link.ipynb").symlink_to(solutions / "kepler-orbit.ipynb")
    os.link(solutions / "kepler-orbit.ipynb", folder / "hard.ipynb")
    for name in ("linked", "link.ipynb", "hard.ipynb", "kepler-orbit.ipynb"):
        expected[name] = None
    return expected


def run_processes(run=None):
    """Processes on this machine started by the grader run ``run`` (a pid; default: this
    process): their environment holds WHITTAKER_TEACH_RUN=<run>, which the sandbox sets.
    (Not every process of a sandbox uid: another grader may be running at the same time.)"""
    mark = f"WHITTAKER_TEACH_RUN={run or os.getpid()}".encode()
    out = []
    for pid in os.listdir("/proc"):
        if pid.isdigit():
            try:
                with open(f"/proc/{pid}/environ", "rb") as f:
                    env = f.read().split(b"\0")
            except OSError:
                continue
            if mark in env:
                out.append(pid)
    return out


def _settled(find, seconds=10):
    """``find()`` once it is empty, or after ``seconds`` (killed processes take a moment)."""
    import time
    end = time.monotonic() + seconds
    while find() and time.monotonic() < end:
        time.sleep(0.1)
    return find()


def groups_left():
    """The cgroups this process made for its sandboxes that are still there."""
    found = []
    for top in ("/sys/fs/cgroup", ):           # v1 (memory, pids, cpu) and v2 alike
        for d, dirs, _ in os.walk(top):
            found += [x for x in dirs if x.startswith(f"wt-grade-{os.getpid()}-")]
            if d.count("/") > 8:
                dirs[:] = []
    return found


def owned_by_sandbox(*roots):
    found = []
    for root in roots:
        for top, dirs, files in os.walk(root):
            for name in dirs + files:
                try:
                    uid = os.lstat(os.path.join(top, name)).st_uid
                except OSError:
                    continue
                if sandbox.UID_BASE <= uid < sandbox.UID_BASE + 64:
                    found.append(os.path.join(top, name))
    return found


@pytest.fixture(scope="module")
def batch(tmp_path_factory):
    """The graded batch, graded once even when pytest-xdist spreads these tests over workers
    (the first worker grades it under a lock; the others read its result)."""
    import fcntl
    base = tmp_path_factory.getbasetemp()
    shared = base.parent if os.environ.get("PYTEST_XDIST_WORKER") else base   # this session
    with open(shared / "hostile-class.lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        done = shared / "hostile-class.json"
        if not done.exists():
            result = _grade_the_class(tmp_path_factory.mktemp("hostile"))
            done.write_text(json.dumps(result), encoding="utf-8")
    result = json.loads(done.read_text(encoding="utf-8"))
    for key in ("out", "tmp", "outside", "feedback"):
        result[key] = Path(result[key])
    return result


def _grade_the_class(tmp):
    folder, outside = tmp / "submissions", tmp / "lecturer"
    folder.mkdir()
    outside.mkdir()
    (outside / "secret.txt").write_text(SECRET, encoding="utf-8")
    server = socket.socket(socket.AF_UNIX)
    server.bind(str(outside / "lecturer.sock"))
    server.listen(5)
    server.settimeout(0.5)
    accepted, stop = [], threading.Event()

    def serve():
        while not stop.is_set():
            try:
                conn, _ = server.accept()
                accepted.append(conn.recv(100))
            except OSError:
                pass
    thread = threading.Thread(target=serve, daemon=True)
    thread.start()
    expected = make_class(folder, outside)
    before_dev = set(os.listdir("/dev"))
    os.environ["WT_GRADER_SECRET"] = SECRET
    # variables that make check() record instead of check: the grader must not obey them
    os.environ["WHITTAKER_TEACH_COLLECT"] = str(tmp / "collected.json")
    os.environ["WHITTAKER_TEACH_CHECK_LOG"] = str(tmp / "check-log.jsonl")
    try:
        paths = sorted(str(p) for p in folder.iterdir()) + [str(folder / "linked" /
                                                               "kepler-orbit.ipynb")]
        out = tmp / "grades.csv"
        rows, line = grading.grade(paths, str(out), feedback=str(tmp / "feedback"), jobs=2,
                                   cell_timeout=20, timeout=60, memory=MEMORY_MB, disk=DISK_MB,
                                   quiet=True, gradebook=str(tmp / "gradebook.csv"))
    finally:
        for name in ("WT_GRADER_SECRET", "WHITTAKER_TEACH_COLLECT", "WHITTAKER_TEACH_CHECK_LOG"):
            os.environ.pop(name, None)
        stop.set()
        thread.join(5)
        server.close()
    with open(out, newline="", encoding="utf-8") as f:
        table = list(csv.reader(f))
    got = {}
    for sub, ex, part, ok, pts, mx, message in table[1:]:
        got.setdefault(sub.lstrip("'") if sub[:2] in ("'=", "'-") else sub, []).append(
            [part, ok == "True", message])
    return {"expected": expected, "got": got, "table": table, "out": str(out), "tmp": str(tmp),
            "outside": str(outside), "accepted": [a.decode() for a in accepted],
            "before_dev": sorted(before_dev), "feedback": str(tmp / "feedback"),
            "left": _settled(run_processes), "line": line,
            "cgroups": sandbox.cgroup_limits(),
            "groups_left": groups_left()}


def parts_of(batch, name):
    return {p: ok for p, ok, _ in batch["got"][name] if p}


def failure_of(batch, name):
    return " ".join(m for p, _, m in batch["got"][name] if not p)


def test_honest_and_wrong_students_are_graded_right(batch):
    assert not (batch["tmp"] / "collected.json").exists()
    assert not (batch["tmp"] / "check-log.jsonl").exists()
    for name in ("honest_1.ipynb", "honest~1.ipynb", "=1+1.ipynb", "-dash.ipynb",
                 "wrong.ipynb"):
        assert parts_of(batch, name) == batch["expected"][name], batch["got"][name]
    assert sorted(batch["got"]) == sorted(batch["expected"])


def test_no_student_stops_the_class(batch):
    for name in ("log-brackets.ipynb", "kill-grader.ipynb"):
        assert parts_of(batch, name) == batch["expected"][name], batch["got"][name]
    assert failure_of(batch, "kill-grader.ipynb")        # its own run ended without a result
    assert "nested more than" in failure_of(batch, "deep.ipynb")


def test_students_cannot_reach_each_other(batch):
    for name in ("snoop.ipynb", "assassin.ipynb"):
        assert parts_of(batch, name) == batch["expected"][name], batch["got"][name]


def test_no_answers_in_reach(batch):
    assert not any(parts_of(batch, "catalog.ipynb").values())
    assert "whittaker_teach.exercises.catalog" in failure_of(batch, "catalog.ipynb")
    assert not any(parts_of(batch, "solver.ipynb").values())
    note = failure_of(batch, "solver.ipynb")
    assert "whittaker_teach.examples" in note and "does not allow" in note
    assert parts_of(batch, "hunt-solutions.ipynb") == batch["expected"]["hunt-solutions.ipynb"]


def test_no_secret_leaks(batch):
    assert parts_of(batch, "secrets.ipynb") == batch["expected"]["secrets.ipynb"]
    assert parts_of(batch, "sockets-dev.ipynb") == batch["expected"]["sockets-dev.ipynb"]
    assert batch["accepted"] == []                        # the host socket was never reached
    assert SECRET not in batch["out"].read_text(encoding="utf-8")
    for page in batch["feedback"].iterdir():
        assert SECRET not in page.read_text(encoding="utf-8")
    assert sorted(os.listdir("/dev")) == batch["before_dev"]


def test_resources_are_bounded_and_nothing_outlives_its_run(batch):
    for name in ("forks-memory.ipynb", "processes.ipynb", "daemon.ipynb", "flood.ipynb",
                 "disk.ipynb"):
        assert parts_of(batch, name) == batch["expected"][name], (name, batch["got"][name])
    if "memory" in batch["cgroups"]:          # one limit over all its processes
        assert "memory limit" in failure_of(batch, "forks-memory.ipynb") or \
            "died" in failure_of(batch, "forks-memory.ipynb")
    assert "error in code cell 3" in failure_of(batch, "processes.ipynb")   # pids or NPROC
    assert "error in code cell 3: OSError" in failure_of(batch, "disk.ipynb")
    assert batch["left"] == []                            # no process of any sandbox is left
    assert batch["groups_left"] == []                     # nor any of their cgroups
    assert owned_by_sandbox(batch["tmp"], "/tmp", "/dev/shm") == []


def test_output_a_lecturer_opens_safely(batch):
    for row in batch["table"][1:]:
        for value in row:
            assert value[:1] not in ("=", "+", "-", "@", "\t", "\r"), row
    assert parts_of(batch, "forged.ipynb") == batch["expected"]["forged.ipynb"]
    text = batch["out"].read_text(encoding="utf-8")
    assert "FORGED" not in text and "HYPERLINK" not in text
    assert failure_of(batch, "forged.ipynb") == "error in code cell 4: an exception of its own"
    assert failure_of(batch, "log-brackets.ipynb") == ""
    pages = {p.name: p.read_text(encoding="utf-8") for p in batch["feedback"].iterdir()}
    assert len(pages) == len(batch["expected"])
    assert not any("FORGED" in page for page in pages.values())
    one = [p for p in pages.values() if "Feedback on honest_1.ipynb" in p]
    other = [p for p in pages.values() if "Feedback on honest~1.ipynb" in p]
    assert len(one) == 1 and len(other) == 1


def test_the_gradebook_has_points_and_totals(batch):
    with open(batch["tmp"] / "gradebook.csv", newline="", encoding="utf-8") as f:
        book = {r["submission"].lstrip("'"): r for r in csv.DictReader(f)}
    pts = grading.points(EX)                      # the exercise's own points, 1 by default
    full = f"{sum(pts.values()):g}"
    assert book["honest_1.ipynb"]["total"] == full and book["honest_1.ipynb"]["max_points"] == full
    assert book["wrong.ipynb"]["total"] == "0"
    assert book["log-brackets.ipynb"]["kepler-orbit:L_star"] == f"{pts['L_star']:g}"
    assert book["log-brackets.ipynb"]["total"] == f"{pts['L_star']:g}"
    assert json.dumps(batch["line"]).startswith(f'"{len(batch["expected"])} submissions')


def test_keyrings_are_out_of_reach(batch):
    """add_key, request_key and keyctl are denied in the sandbox (seccomp): the key the
    first stores is never there for the second, nor is any session keyring it inherits."""
    for name in ("keyring-a-store.ipynb", "keyring-b-read.ipynb"):
        assert parts_of(batch, name) == batch["expected"][name], batch["got"][name]
        assert failure_of(batch, name) == "", batch["got"][name]


def test_links_and_names_of_any_bytes(batch):
    """The solutions behind a folder link, a file link or a hard link are never opened;
    a name that is not UTF-8 is graded like any other."""
    assert parts_of(batch, "caf\\xe9.ipynb") == batch["expected"]["caf\\xe9.ipynb"]
    why = {name: failure_of(batch, name) for name in ("linked", "link.ipynb", "hard.ipynb",
                                                      "kepler-orbit.ipynb")}
    assert why["linked"].startswith("a symbolic link") and why["link.ipynb"].startswith(
        "a symbolic link"), why
    assert why["hard.ipynb"].startswith("a hard link"), why
    assert "goes through a symbolic link (" in why["kepler-orbit.ipynb"], why
    for name in why:
        assert parts_of(batch, name) == {}, batch["got"][name]
