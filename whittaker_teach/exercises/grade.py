"""Grading a class: each submitted notebook run in a sandbox of its own, its answers checked outside.

``python -m whittaker_teach grade SUBMISSION.ipynb ... --out grades.csv [--feedback DIR]
[--gradebook FILE] [--canvas FILE] [--moodle FILE]``

For each submission:

1. the file is read once, by the grader (not a regular file, a symbolic
   link, too large, not UTF-8, not JSON, JSON nested deeper than
   ``MAX_JSON_DEPTH``, truncated, not a notebook: one row saying so);
2. those bytes run from top to bottom in a sandbox of their own
   (:mod:`.sandbox`: bubblewrap, a uid of its own, its own process, network,
   IPC and mount namespaces, one memory and process limit over all its
   processes, a size-limited scratch tmpfs, the package without answers),
   ``jobs`` at a time: nbclient and the kernel it starts both run inside,
   with a time limit per cell and per notebook; when the run ends, every
   process it started ends;
3. inside, ``check(...)`` only records each answer as text
   (:mod:`.recorder`); the grader then checks each recorded answer itself,
   outside the sandbox, with :func:`whittaker_teach.exercises.check`.  The
   last check of each part counts; a part never checked is "not answered".

Every message in the CSV and on the feedback pages is the grader's own:
nothing the notebook prints or writes is copied into them (a cell's error is
named only by a built-in exception's name).  The CSV
(``submission,exercise,part,ok,points,max_points,message``) is written as
each submission is graded, so the rows already graded survive whatever
happens later; a cell that begins with ``= + - @``, a tab or a carriage
return gets a leading ``'`` (the OWASP rule against formula injection).

Without the sandbox (not root, no bubblewrap, no namespaces) :func:`grade`
refuses unless ``unsafe=True`` (``--unsafe``): then each notebook runs as a
plain process of the grader's user, with only per-process limits.

>>> row = Row("alice.ipynb", "kepler-orbit", "h", False, "not answered")
>>> row.csv()
['alice.ipynb', 'kepler-orbit', 'h', 'False', '0', '1', 'not answered']
>>> cell("=HYPERLINK(\\"http://x\\")"), cell("-dash.ipynb"), cell("ok")
('\\'=HYPERLINK("http://x")', "'-dash.ipynb", 'ok')
"""

from __future__ import annotations

import csv
import html
import json
import os
import queue
import shutil
import subprocess
import sys
import tempfile
import threading
import time
from concurrent.futures import ThreadPoolExecutor, as_completed
from dataclasses import dataclass
from pathlib import Path

__all__ = ["Row", "grade", "grade_one", "record_line", "read_submission", "cell", "main",
           "SandboxUnavailable", "HEADER"]

CELL_TIMEOUT = 60          # seconds per cell
NOTEBOOK_TIMEOUT = 300     # seconds per notebook
MEMORY_MB = 3000           # over all the processes of a submission
PROCESSES = 128            # processes and threads of a submission
DISK_MB = 200              # its scratch tmpfs
MAX_NOTEBOOK_BYTES = 20_000_000
MAX_JSON_DEPTH = 64
MAX_OUTPUT_CHARS = 1_000_000
MAX_LOG_BYTES = 2_000_000
MAX_LOG_LINE = 200_000
MAX_ANSWER_CHARS = 50_000
HEADER = ["submission", "exercise", "part", "ok", "points", "max_points", "message"]
# exercises whose student notebook uses the library, until the exercises say so themselves
_SOLVERS_FALLBACK = {"chaplygin-sleigh", "turning-point", "work-precision"}


class SandboxUnavailable(RuntimeError):
    """The sandbox cannot be had here; the message says why."""


@dataclass
class Row:
    """One line of the grades: a part of a submission, or (part "") why it could not run."""

    submission: str
    exercise: str
    part: str
    ok: bool
    message: str
    points: float = 0
    max_points: float = 1

    def csv(self):
        return [cell(v) for v in (self.submission, self.exercise, self.part, str(bool(self.ok)),
                                  _num(self.points), _num(self.max_points) if self.part else "",
                                  self.message)]


def _num(x):
    return f"{x:g}" if isinstance(x, float) else str(x)


def cell(text):
    """A CSV cell a spreadsheet never reads as a formula (OWASP: a leading quote)."""
    text = str(text)
    return "'" + text if text[:1] in ("=", "+", "-", "@", "\t", "\r") else text


# ---------------------------------------------------------------- recording (unsafe mode)
def record_line(feedback, answer):
    """The check-log line for an answer given to ``check`` (see :mod:`.recorder`)."""
    from .recorder import record_line as line
    return line(feedback.exercise, feedback.part,
                None if feedback.status == "unanswered" else answer)


# ---------------------------------------------------------------- reading a submission
def _json_depth(text, limit):
    """True if the JSON text nests deeper than ``limit`` (brackets outside strings)."""
    depth, in_str, esc = 0, False, False
    for ch in text:
        if in_str:
            if esc:
                esc = False
            elif ch == "\\":
                esc = True
            elif ch == '"':
                in_str = False
        elif ch == '"':
            in_str = True
        elif ch in "[{":
            depth += 1
            if depth > limit:
                return True
        elif ch in "]}":
            depth -= 1
    return False


def read_submission(path):
    """(notebook, None) or (None, why it is not a notebook)."""
    nb, _, why = _read(path)
    return nb, why


def _read(path):
    """(notebook, its bytes, None) or (None, None, why it cannot be graded)."""
    try:
        return _read_checked(Path(path))
    except (Exception, RecursionError) as exc:  # noqa: BLE001 - never stop the batch
        return None, None, f"the grader could not read the file ({type(exc).__name__})"


def _read_checked(path):
    import stat
    try:
        st = os.lstat(path)
    except OSError:
        return None, None, "not found"
    if stat.S_ISLNK(st.st_mode):
        return None, None, "a symbolic link, not a notebook (hand in the .ipynb file itself)"
    if not stat.S_ISREG(st.st_mode):
        return None, None, "not a file"
    if st.st_size > MAX_NOTEBOOK_BYTES:
        return None, None, (f"the file is {st.st_size // 1_000_000} MB; a notebook of at most "
                            f"{MAX_NOTEBOOK_BYTES // 1_000_000} MB is expected")
    fd = os.open(path, os.O_RDONLY | getattr(os, "O_NOFOLLOW", 0) | getattr(os, "O_NONBLOCK", 0))
    with os.fdopen(fd, "rb") as f:
        if not stat.S_ISREG(os.fstat(f.fileno()).st_mode):
            return None, None, "not a file"
        raw = f.read(MAX_NOTEBOOK_BYTES + 1)
    if len(raw) > MAX_NOTEBOOK_BYTES:
        return None, None, "the file is too large for a notebook"
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError:
        return None, None, "not a notebook (a binary file, not JSON text)"
    if not text.lstrip().startswith("{"):
        return None, None, "not a notebook (not JSON: download the .ipynb file from Jupyter)"
    if _json_depth(text, MAX_JSON_DEPTH):
        return None, None, f"not a notebook (JSON nested more than {MAX_JSON_DEPTH} levels deep)"
    try:
        data = json.loads(text)
    except json.JSONDecodeError as exc:
        where = f"line {exc.lineno}, column {exc.colno}"
        if exc.pos >= len(text.rstrip()) - 1:
            return None, None, f"not a notebook: the JSON is truncated (it ends at {where})"
        return None, None, f"not a notebook: the JSON is damaged at {where}"
    import nbformat
    try:
        if not isinstance(data, dict) or data.get("nbformat") != 4:
            return None, None, "not a notebook in format 4 (save it from a current Jupyter)"
        nb = nbformat.reads(text, as_version=4)
        nbformat.validate(nb)
    except Exception as exc:  # noqa: BLE001 - nbformat raises many kinds
        return None, None, f"not a valid notebook ({type(exc).__name__})"
    return nb, raw, None


def exercise_of(nb):
    """The exercise id of a student notebook (metadata, else its check cells)."""
    import re
    meta = nb.metadata.get("whittaker_teach", {})
    if isinstance(meta, dict) and isinstance(meta.get("exercise"), str):
        return meta["exercise"]
    for c in nb.cells:
        if c.cell_type == "code" and isinstance(c.source, str):
            m = re.search(r"check\(\s*[\"']([\w-]+)[\"']", c.source[:100_000])
            if m:
                return m.group(1)
    return None


# ---------------------------------------------------------------- the worker (in the sandbox)
def _private_stdout():
    """Keep fd 1 for the result only; the kernel inherits /dev/null; no one may open ours."""
    private = os.dup(1)                       # not inheritable
    devnull = os.open(os.devnull, os.O_RDWR)
    os.dup2(devnull, 1)
    os.dup2(devnull, 2)
    try:                                      # /proc/<worker>/fd becomes root's
        import ctypes
        ctypes.CDLL(None, use_errno=True).prctl(4, 0, 0, 0, 0)   # PR_SET_DUMPABLE = 0
    except (OSError, AttributeError):
        pass
    return private


def _worker_main(argv):
    """``python -m whittaker_teach.exercises.grade worker NOTEBOOK SCRATCH CELL_TIMEOUT MEMORY_MB
    PROCESSES DISK_MB LOG_FD``: run the notebook, write one JSON object to stdout.

    {"failure": None or {"kind", "cell"}, "errors": [{"cell", "ename"}]}; the
    kernel's check log goes to the pipe LOG_FD (``/dev/fd/LOG_FD``).
    """
    import resource
    private = _private_stdout()
    nb_path, scratch, cell_timeout = argv[0], Path(argv[1]), float(argv[2])
    memory, pids, disk, log_fd = int(argv[3]), int(argv[4]), int(argv[5]), int(argv[6])
    os.environ["WHITTAKER_TEACH_CHECK_FD"] = str(log_fd)              # the sandbox's recorder
    if not os.environ.get("WHITTAKER_TEACH_SANDBOX"):                 # the package's check
        os.environ["WHITTAKER_TEACH_CHECK_LOG"] = f"/dev/fd/{log_fd}"
    limit = memory * 1024 * 1024
    resource.setrlimit(resource.RLIMIT_AS, (limit, limit))
    resource.setrlimit(resource.RLIMIT_FSIZE, (disk * 1024 * 1024,) * 2)
    resource.setrlimit(resource.RLIMIT_CORE, (0, 0))
    if os.environ.get("WHITTAKER_TEACH_SANDBOX"):   # a uid of its own: count its processes
        resource.setrlimit(resource.RLIMIT_NPROC, (pids, pids))
    for d in ("home", "tmp", ".grade", ".jupyter/runtime", ".ipython", ".matplotlib"):
        (scratch / d).mkdir(parents=True, exist_ok=True)
    home = scratch / "home"
    result = {"failure": None, "errors": []}
    try:
        _execute(nb_path, home, cell_timeout, log_fd, result)
    except BaseException as exc:  # noqa: BLE001 - report, never crash silently
        result["failure"] = result["failure"] or {"kind": "start", "cell": 0,
                                                  "ename": type(exc).__name__}
    data = json.dumps(result).encode("utf-8")
    view = memoryview(data)
    while view:
        view = view[os.write(private, view):]
    return 0


def _execute(nb_path, home, cell_timeout, log_fd, result):
    import nbformat
    from jupyter_client.manager import AsyncKernelManager
    from nbclient import NotebookClient
    from nbclient.exceptions import CellTimeoutError, DeadKernelError

    class Client(NotebookClient):
        """Keeps at most MAX_OUTPUT_CHARS of output (streams, displays, errors) in memory."""

        kept = 0

        def output(self, outs, msg, display_id, cell_index):
            content = msg.get("content", {})
            size = sum(len(str(v)) for v in content.values()) if isinstance(content, dict) \
                else MAX_OUTPUT_CHARS
            if msg.get("msg_type") != "error":
                self.kept += size
                if self.kept > MAX_OUTPUT_CHARS:
                    return None
            return super().output(outs, msg, display_id, cell_index)

    nb = nbformat.read(nb_path, as_version=4)
    for c in nb.cells:
        if c.cell_type == "code":
            c.outputs = []
    km = AsyncKernelManager(kernel_name="python3")
    client = Client(nb, km=km, timeout=cell_timeout, allow_errors=True, startup_timeout=60,
                    kernel_name="python3", shutdown_kernel="immediate",
                    resources={"metadata": {"path": str(home)}})
    n = 0
    try:
        with client.setup_kernel(cwd=str(home), pass_fds=(log_fd,)):
            for index, c in enumerate(nb.cells):
                if c.cell_type != "code":
                    continue
                n += 1
                try:
                    client.execute_cell(c, index)
                except CellTimeoutError:
                    result["failure"] = {"kind": "cell-timeout", "cell": n}
                    return
                except DeadKernelError:
                    result["failure"] = {"kind": "dead", "cell": n}
                    return
                for out in c.outputs:
                    if out.get("output_type") == "error" and len(result["errors"]) < 3:
                        result["errors"].append({"cell": n, "ename": str(out.get("ename"))[:80]})
                c.outputs = []
    except DeadKernelError:
        result["failure"] = result["failure"] or {"kind": "dead", "cell": n}


# ---------------------------------------------------------------- running one submission
class _Reader(threading.Thread):
    """Reads at most ``limit`` bytes of a pipe and drops the rest (the pipe never blocks)."""

    def __init__(self, stream, limit):
        super().__init__(daemon=True)
        self.stream, self.limit, self.data, self.over = stream, limit, bytearray(), False

    def run(self):
        try:
            while True:
                chunk = self.stream.read1(65536)
                if not chunk:
                    break
                if len(self.data) + len(chunk) > self.limit:
                    self.over = True
                else:
                    self.data += chunk
        except (OSError, ValueError):
            pass


@dataclass
class Settings:
    cell_timeout: float = CELL_TIMEOUT
    timeout: float = NOTEBOOK_TIMEOUT
    memory_mb: int = MEMORY_MB
    processes: int = PROCESSES
    disk_mb: int = DISK_MB
    unsafe: bool = False


_LIVE = set()          # the runs going on (killed if the grader is interrupted)
_LIVE_LOCK = threading.Lock()   # a run starts and is recorded in _LIVE under it, and an
_STOP = threading.Event()       # interrupt sets _STOP under it: no run starts after that


def _stop_runs():
    """No new run from now on; kill the running ones (with everything they started)."""
    with _LIVE_LOCK:
        _STOP.set()
        live = list(_LIVE)
    for proc in live:
        _kill(proc)


def _run(raw, settings, package=None, solvers=True, slot=0):
    """Run one notebook (its bytes): (worker result or None, grader-side failure or '', the
    check log as text)."""
    from . import sandbox
    top = Path(tempfile.mkdtemp(prefix="wt-grade-"))
    os.chmod(top, 0o755)
    nb_file = top / "submission.ipynb"
    nb_file.write_bytes(raw)
    os.chmod(nb_file, 0o644)
    limits = sandbox.Limits(settings.memory_mb, settings.processes, settings.disk_mb)
    groups, hit = None, set()
    log_r, log_w = os.pipe()
    try:
        if settings.unsafe:
            scratch = top / "scratch"
            scratch.mkdir()
            env = sandbox.environment(0)
            env.pop("WHITTAKER_TEACH_SANDBOX")
            env = {k: v.replace(sandbox.SCRATCH, str(scratch)) for k, v in env.items()}
            import whittaker_teach
            env["PYTHONPATH"] = str(Path(whittaker_teach.__file__).resolve().parents[1])
            cmd = [sys.executable, "-m", "whittaker_teach.exercises.grade", "worker",
                   str(nb_file), str(scratch), f"{settings.cell_timeout:g}",
                   str(settings.memory_mb), str(settings.processes), str(settings.disk_mb),
                   str(log_w)]
            cwd = str(scratch)
        else:
            name = f"wt-grade-{os.getpid()}-{slot}-{time.monotonic_ns()}"
            groups = sandbox.Cgroups.make(name, limits)
            cmd = sandbox.command(sandbox.UID_BASE + slot, package.path(solvers), nb_file,
                                  limits, settings.cell_timeout, log_w, groups.procs)
            env, cwd = {"PATH": "/usr/bin:/bin"}, str(top)
        try:
            with _LIVE_LOCK:
                if _STOP.is_set():          # interrupted before this run started
                    if groups is not None:
                        groups.close()
                    return None, "the grader was interrupted before this notebook ran", ""
                proc = subprocess.Popen(cmd, env=env, cwd=cwd, stdin=subprocess.DEVNULL,
                                        stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                        start_new_session=True, pass_fds=(log_w,))
                _LIVE.add(proc)
        finally:
            os.close(log_w)
        out, err = _Reader(proc.stdout, sandbox.MAX_RESULT_BYTES), _Reader(proc.stderr, 20_000)
        log = _Reader(os.fdopen(log_r, "rb"), MAX_LOG_BYTES)
        log_r = None
        for reader in (out, err, log):
            reader.start()
        failure = ""
        try:
            proc.wait(timeout=settings.timeout)
        except subprocess.TimeoutExpired:
            failure = f"timeout: the notebook ran longer than {settings.timeout:g} s"
        finally:
            _kill(proc)
            _LIVE.discard(proc)
            if groups is not None:
                hit = groups.hit()
                groups.close()
        for reader in (out, err, log):
            reader.join(10)
        result = None
        if not failure:
            try:
                result = json.loads(bytes(out.data).decode("utf-8"))
                if not isinstance(result, dict):
                    result = None
            except (ValueError, RecursionError, UnicodeDecodeError):
                result = None
        if result is None and not failure:
            failure = "the notebook's run ended without a result (its processes were killed)"
            if b"bwrap:" in bytes(err.data) or proc.returncode == 97:
                failure = "the grader could not start the sandbox"
                print(f"grade: the sandbox did not start: "
                      f"{bytes(err.data).decode('utf-8', 'replace').strip()[:300]}",
                      file=sys.stderr)
        if hit:
            failure = "; ".join(x for x in (failure, "it reached " + " and ".join(
                {"memory": f"the memory limit ({settings.memory_mb} MB over all its processes)",
                 "pids": f"the limit of {settings.processes} processes and threads"}[h]
                for h in sorted(hit))) if x)
        return result, failure, bytes(log.data).decode("utf-8", "replace")
    finally:
        if log_r is not None:
            os.close(log_r)
        shutil.rmtree(top, ignore_errors=True)


def _kill(proc):
    """Kill the run's whole session (in the sandbox: bubblewrap, whose namespace goes with it)."""
    import signal
    try:
        os.killpg(proc.pid, signal.SIGKILL)
    except (ProcessLookupError, PermissionError):
        pass
    try:
        proc.wait(timeout=10)
    except subprocess.TimeoutExpired:  # pragma: no cover
        pass


# ---------------------------------------------------------------- scoring, in the grader
def _records(log):
    """The records of a check log that look like records (never parsing anything deep)."""
    out = []
    if not isinstance(log, str):
        return out
    for line in log.splitlines():
        line = line.strip()
        if not line.startswith("{") or len(line) > MAX_LOG_LINE:
            continue
        if line.count("{") + line.count("[") > 4:        # a record is one flat object
            continue
        try:
            rec = json.loads(line)
        except (ValueError, RecursionError):
            continue
        if isinstance(rec, dict):
            out.append(rec)
    return out


def _last_checks(records, exercise):
    """{part: record} of the last check of each part of this exercise."""
    out = {}
    for rec in records:
        if rec.get("exercise") == exercise and isinstance(rec.get("part"), str):
            out[rec["part"]] = rec
    return out


_UNRECORDABLE = {
    "list": "a list", "tuple": "a tuple", "dict": "a dict", "set": "a set",
    "bool": "True or False", "complex": "a complex number", "function": "a function",
    "too-large": "an answer too large to grade (simplify it)"}


def _recheck(exercise, part, rec):
    """(ok, message) of a recorded answer, checked again here, in the grader's own words."""
    from . import check
    kind = rec.get("kind", rec.get("status"))
    if kind == "unanswered":
        return False, "not answered"
    answer = rec.get("answer")
    if not isinstance(answer, str):
        what = _UNRECORDABLE.get(rec.get("what"), "something that is not an answer")
        return False, (f"The answer could not be graded: it is {what}; answer with an "
                       "expression, a number or a string")
    f = check(exercise, answer[:MAX_ANSWER_CHARS], part=part)
    if f.status == "unanswered":
        return False, "not answered"
    return bool(f.ok), str(f.message)


def _known_exception(name):
    import builtins
    obj = getattr(builtins, name, None) if isinstance(name, str) and name.isidentifier() else None
    if isinstance(obj, type) and issubclass(obj, BaseException):
        return name
    return "an exception of its own"


def _failure_text(result, settings):
    """The grader's own words for what the worker reported (numbers and known names only)."""
    def n(v):
        return v if isinstance(v, int) and 0 <= v < 1_000_000 else 0
    parts = []
    f = result.get("failure")
    if isinstance(f, dict):
        kind, c = f.get("kind"), n(f.get("cell"))
        if kind == "cell-timeout":
            parts.append(f"timeout: code cell {c} ran longer than {settings.cell_timeout:g} s")
        elif kind == "dead":
            parts.append(f"the kernel died in code cell {c} (it exited, or it was killed: "
                         "out of memory?)")
        elif kind == "start":
            parts.append("the notebook could not be run (the kernel did not start)")
    errors = result.get("errors")
    if isinstance(errors, list) and not parts:
        for e in errors[:3]:
            if isinstance(e, dict):
                parts.append(f"error in code cell {n(e.get('cell'))}: "
                             f"{_known_exception(e.get('ename'))}")
    return "; ".join(parts)


def _modules():
    """The dotted names of the grader's own whittaker_teach modules and packages."""
    import whittaker_teach
    root = Path(whittaker_teach.__file__).resolve().parent
    names = {"whittaker_teach"}
    for path in root.rglob("*.py"):
        parts = path.relative_to(root).with_suffix("").parts
        if parts[-1] == "__init__":
            parts = parts[:-1]
        names.add(".".join(("whittaker_teach",) + parts))
    return names


def _solver_note(records):
    known, names = _modules(), []
    for rec in records:
        if rec.get("kind") == "solver":
            what = rec.get("what")
            name = what if isinstance(what, str) and what in known else "a part of " \
                "whittaker_teach"
            if name not in names:
                names.append(name)
    if not names:
        return ""
    return ("the notebook imported parts of the library (" + ", ".join(names[:3]) + ") that "
            "this exercise does not allow while graded: only check and setup are available")


def _exercise(exercise):
    try:
        from .catalog import EXERCISES
        return EXERCISES[exercise]
    except (ImportError, KeyError, TypeError):
        return None


def points(exercise):
    """{part: points}: the exercise's own points, else 1 point per part."""
    from . import parts
    ex = _exercise(exercise)
    out = {}
    for part in parts(exercise):
        p = getattr(getattr(ex, "parts", {}).get(part), "points", None) if ex else None
        out[part] = p if isinstance(p, (int, float)) and not isinstance(p, bool) and p >= 0 else 1
    return out


def solvers_allowed(exercise):
    """May a graded notebook of this exercise use the library's solvers?"""
    flag = getattr(_exercise(exercise), "solvers", None)
    return bool(flag) if isinstance(flag, bool) else exercise in _SOLVERS_FALLBACK


def score(name, exercise, result, failure, log, settings=None):
    """The rows of a submission that ran: one per part, and one for a failure."""
    settings = settings or Settings()
    records = _records(log)
    checks = _last_checks(records, exercise)
    rows = []
    for part, pts in points(exercise).items():
        rec = checks.get(part)
        if rec is None:
            ok, message = False, "not answered"
        else:
            try:
                ok, message = _recheck(exercise, part, rec)
            except (Exception, RecursionError) as exc:  # noqa: BLE001
                ok, message = False, f"the grader could not check this answer " \
                    f"({type(exc).__name__}); please report it"
        rows.append(Row(name, exercise, part, ok, message, pts if ok else 0, pts))
    failure = "; ".join(x for x in (failure, _failure_text(result or {}, settings),
                                    _solver_note(records)) if x)
    if failure:
        rows.append(Row(name, exercise, "", False, failure, 0, 0))
    return rows


def prepare(path, name=None):
    """(name, exercise or None, the notebook's bytes, rows if it cannot be run)."""
    from . import exercises
    name = name or Path(path).name
    nb, raw, why = _read(path)
    if nb is None:
        return name, None, None, [Row(name, "", "", False, why, 0, 0)]
    exercise = exercise_of(nb)
    if exercise not in exercises():
        return name, None, None, [Row(name, "", "", False, "not a notebook of the exercises "
                                      "(no check(...) of a known exercise in it)", 0, 0)]
    return name, exercise, raw, None


def grade_one(path, cell_timeout=CELL_TIMEOUT, timeout=NOTEBOOK_TIMEOUT, memory=MEMORY_MB,
              unsafe=False):
    """The rows of one submission (runs it; see the module docstring)."""
    rows, _ = grade([path], None, cell_timeout=cell_timeout, timeout=timeout, memory=memory,
                    quiet=True, unsafe=unsafe)
    return rows


def _progress(total, quiet):
    """A progress bar on a terminal (tqdm if installed, else a counter); None otherwise."""
    if quiet or not sys.stderr.isatty():
        return None
    try:
        from tqdm import tqdm
        return tqdm(total=total, unit="notebook", file=sys.stderr, ncols=100)
    except ImportError:
        class Counter:
            n = 0

            def update(self, k=1):
                self.n += k
                print(f"\rgraded {self.n}/{total}", end="", file=sys.stderr, flush=True)

            def close(self):
                print(file=sys.stderr)
        return Counter()


def _names(paths):
    """A unique name per submission: the file name, or the path where names repeat."""
    base = [Path(p).name for p in paths]
    return [b if base.count(b) == 1 else str(p) for b, p in zip(base, paths)]


class _Writer:
    """The CSV, written and flushed submission by submission."""

    def __init__(self, out):
        self.f = open(out, "w", newline="", encoding="utf-8") if out else None
        if self.f:
            self.w = csv.writer(self.f)
            self.w.writerow(HEADER)
            self.f.flush()

    def rows(self, rows):
        if self.f:
            for r in rows:
                self.w.writerow(r.csv())
            self.f.flush()
            os.fsync(self.f.fileno())

    def close(self):
        if self.f:
            self.f.close()


def grade(paths, out, feedback=None, jobs=2, cell_timeout=CELL_TIMEOUT,
          timeout=NOTEBOOK_TIMEOUT, memory=MEMORY_MB, quiet=False, unsafe=False,
          processes=PROCESSES, disk=DISK_MB, gradebook=None, canvas=None, moodle=None):
    """Grade the submissions into the CSV ``out``: (rows, summary line).

    The notebooks run ``jobs`` at a time, each in its own sandbox; their
    recorded answers are checked here, in the main thread (where each check
    has its time budget), as each run ends, and its rows written at once.
    Raises :class:`SandboxUnavailable` when the sandbox cannot be had and
    ``unsafe`` is not set.
    """
    from . import sandbox
    from .gradebook import write_exports
    _STOP.clear()                   # (a grader interrupted before, in this process)
    why = sandbox.available()
    if why and not unsafe:
        raise SandboxUnavailable(why)
    for name in ("WHITTAKER_TEACH_CHECK_LOG", "WHITTAKER_TEACH_CHECK_FD",
                 "WHITTAKER_TEACH_COLLECT"):                  # the grader checks, never records
        os.environ.pop(name, None)
    settings = Settings(cell_timeout, timeout, memory, processes, disk, unsafe)
    paths = [str(p) for p in paths]
    names = _names(paths)
    writer = _Writer(out)
    package = None if unsafe else sandbox.PackageCopy()
    results = {}
    bar = _progress(len(paths), quiet)

    def done(i, rows):
        results[i] = rows
        writer.rows(rows)
        if feedback:
            write_feedback(feedback, [names[i]], {names[i]: rows})
        if bar is not None:
            bar.update(1)

    try:
        todo = []
        for i, p in enumerate(paths):
            name, exercise, raw, rows = prepare(p, names[i])
            if rows is not None:
                done(i, rows)
            else:
                todo.append((i, name, exercise, raw))
        for exercise in {t[2] for t in todo}:
            ex = _exercise(exercise)
            if ex is not None and hasattr(ex, "build"):
                ex.build()                     # once, before the notebooks run
        slots = queue.Queue()
        for s in range(max(1, jobs)):
            slots.put(s)

        def run(raw, solvers):
            slot = slots.get()
            try:
                return _run(raw, settings, package, solvers, slot)
            except Exception as exc:  # noqa: BLE001 - one submission never stops the batch
                return None, f"the grader could not run it ({type(exc).__name__})", ""
            finally:
                slots.put(slot)

        pool = ThreadPoolExecutor(max_workers=max(1, jobs))
        try:
            futures = {pool.submit(run, raw, solvers_allowed(ex)): (i, name, ex)
                       for i, name, ex, raw in todo}
            for fut in as_completed(futures):
                i, name, ex = futures[fut]
                try:
                    rows = score(name, ex, *fut.result(), settings)
                except (Exception, RecursionError) as exc:  # noqa: BLE001
                    rows = [Row(name, ex, "", False, "the grader could not grade it "
                                f"({type(exc).__name__}); please report it", 0, 0)]
                done(i, rows)
        except BaseException:       # Ctrl-C, say: no new run, and the running ones killed
            _stop_runs()            # (a thread about to start one finds _STOP set)
            pool.shutdown(wait=False, cancel_futures=True)
            raise
        pool.shutdown()
    finally:
        writer.close()
        if bar is not None:
            bar.close()
        if package is not None:
            package.close()
    ordered = [results[i] for i in sorted(results)]
    rows = [r for rs in ordered for r in rs]
    write_exports(ordered, gradebook=gradebook, canvas=canvas, moodle=moodle)
    return rows, summary(rows, len(paths))


def summary(rows, n):
    """'30 submissions: 41 parts right, 49 parts wrong, 6 failures'."""
    right = sum(1 for r in rows if r.part and r.ok)
    wrong = sum(1 for r in rows if r.part and not r.ok)
    failures = len({r.submission for r in rows if not r.part})
    return (f"{n} submission{'s' if n != 1 else ''}: {right} part{'s' if right != 1 else ''} "
            f"right, {wrong} part{'s' if wrong != 1 else ''} wrong, {failures} "
            f"failure{'s' if failures != 1 else ''}")


_FEEDBACK_CSS = ("<style>body{font-family:sans-serif;max-width:60em;margin:2em auto;"
                 "padding:0 1em;line-height:1.4}table{border-collapse:collapse}"
                 "td,th{padding:.4em .6em;border-bottom:1px solid #ddd;text-align:left;"
                 "vertical-align:top}td:nth-child(2){white-space:nowrap}</style>")


def page_name(name):
    """The feedback page of a submission: its name if that is a plain lower-case file name,
    else the name made plain and a hash of the exact name (two names never share a page)."""
    import hashlib
    stem = "".join(c if c.isascii() and (c.isalnum() or c in "-_.") else "_" for c in name)
    if stem != name or stem != stem.lower() or stem.startswith((".", "-")) or not stem \
            or len(stem) > 100:       # (upper case too: file systems that ignore case)
        digest = hashlib.sha256(name.encode("utf-8", "surrogatepass")).hexdigest()[:10]
        stem = stem.lstrip(".-")[:80] + "-" + digest
    return f"{stem}.html"


def write_feedback(folder, names, results):
    """One HTML page per submission: its parts, right or not, and the grader's messages."""
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    for name in names:
        rows = results[name]
        items = []
        for r in rows:
            colour = "#2e7d32" if r.ok else "#c62828"
            label = "right" if r.ok else ("could not run" if not r.part else "not yet right")
            pts = f"{_num(r.points)} / {_num(r.max_points)}" if r.part else ""
            items.append(f'<tr><td>{html.escape(r.part or "(notebook)")}</td>'
                         f'<td style="color:{colour}">{label}</td><td>{pts}</td>'
                         f"<td>{html.escape(r.message)}</td></tr>")
        exercise = html.escape(rows[0].exercise) if rows else ""
        right = sum(1 for r in rows if r.part and r.ok)
        total = sum(1 for r in rows if r.part)
        got = sum(r.points for r in rows if r.part)
        most = sum(r.max_points for r in rows if r.part)
        page = ("<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
                "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">"
                f"<title>Feedback: {html.escape(name)}</title>" + _FEEDBACK_CSS +
                f"</head><body><h1>Feedback on {html.escape(name)}</h1>"
                f"<p>Exercise: {exercise}. {right} of {total} parts right: "
                f"{_num(got)} of {_num(most)} points.</p>"
                "<table><tr><th>part</th><th>result</th><th>points</th><th>message</th></tr>"
                + "".join(items) + "</table></body></html>\n")
        (folder / page_name(name)).write_text(page, encoding="utf-8")


def main(args):
    """The ``grade`` subcommand."""
    from . import sandbox
    paths = [str(p) for p in args.submissions]
    why = sandbox.available()
    if why and not args.unsafe:
        print(f"grade: refusing to run students' notebooks without the sandbox: {why}.\n"
              "Run as root on Linux with bubblewrap (make sysdeps), or pass --unsafe to run "
              "them as plain processes of your user, with per-process limits only.",
              file=sys.stderr)
        return 2
    start = time.monotonic()
    try:
        rows, line = grade(paths, args.out, args.feedback, args.jobs, args.cell_timeout,
                           args.timeout, args.memory, args.quiet, unsafe=bool(why),
                           gradebook=args.gradebook, canvas=args.canvas, moodle=args.moodle)
    except KeyboardInterrupt:
        print(f"\ngrade: interrupted; the submissions graded so far are in {args.out}",
              file=sys.stderr)
        return 130
    took = time.monotonic() - start
    print(f"{line} ({took:.0f} s); grades in {args.out}"
          + (f", feedback in {args.feedback}" if args.feedback else ""))
    if why:
        print(f"(UNSAFE: the notebooks ran without the sandbox: {why})")
    return 0


if __name__ == "__main__":
    if len(sys.argv) > 1 and sys.argv[1] == "worker":
        sys.exit(_worker_main(sys.argv[2:]))
    sys.exit("usage: python -m whittaker_teach grade SUBMISSION.ipynb ... --out grades.csv")
