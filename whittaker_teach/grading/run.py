"""Grading a class: each notebook run in a sandbox of its own, its answers checked outside.

``python -m whittaker_teach grade --exercise ID --roster ROSTER.csv SUBMISSIONS... --out
grades.csv [--feedback DIR] [--gradebook FILE] [--canvas GRADEBOOK.csv] [--moodle
WORKSHEET.csv]``, or without ``--exercise``/``--roster`` (each notebook graded as the exercise
it names, identified only by its file name: no LMS exports then).

With ``--exercise`` and ``--roster`` (an assignment), :mod:`.roster` first
matches every notebook to exactly one roster entry (or lists it in the
identity report and grades it under no one), and every notebook must be a
notebook of that exercise; the grades are then written into the lecturer's
own Canvas gradebook and Moodle worksheet (:mod:`.exports`).

For each submission:

1. the file is opened once, without following a symbolic link at any level
   of its path, and read (:func:`open_submission`: a link, a hard link,
   something outside the submissions folder, not a regular file, too large,
   not UTF-8, not JSON, JSON nested deeper than ``MAX_JSON_DEPTH``: one row
   saying so); it is then parsed and validated in a child process with at
   most ``VALIDATE_MEMORY_MB`` and ``VALIDATE_SECONDS`` of CPU (truncated,
   not a notebook, a notebook of another exercise than the assignment's: one
   row saying so);
2. those bytes run from top to bottom in a sandbox of their own
   (:mod:`.sandbox`: bubblewrap, a uid of its own, its own process, network,
   IPC and mount namespaces, one memory and process limit over all its
   processes, a size-limited scratch tmpfs, the package without answers),
   ``jobs`` at a time: nbclient and the kernel it starts (:mod:`.worker`)
   both run inside, with a time limit per cell and per notebook; when the
   run ends, every process it started ends;
3. inside, ``check(...)`` only records each answer as text
   (:mod:`whittaker_teach.exercises.recorder`); the grader then checks each
   recorded answer itself, outside the sandbox, with
   :func:`whittaker_teach.exercises.check`.  The last check of each part
   counts; a part never checked is "not answered".

Every message in the CSV and on the feedback pages is the grader's own:
nothing the notebook prints or writes is copied into them (a cell's error is
named only by a built-in exception's name).  The CSV
(``submission,exercise,part,ok,points,max_points,message``) is written as
each submission is graded, so the rows already graded survive whatever
happens later; a cell that begins with ``= + - @``, a tab or a carriage
return gets a leading ``'`` (the OWASP rule against formula injection).

``main`` prints, before anything runs, which limits each sandbox has here and
by what mechanism (:func:`print_limits`).  On Ctrl-C or SIGTERM no new run
starts, the running ones are killed with everything they started, their
cgroups and temporary folders removed, and the rows graded so far, the
identity report and the LMS files are written for the students graded
before the signal (exit status 130).

Without the sandbox (no bubblewrap, no namespaces) :func:`grade` refuses
unless ``unsafe=True`` (``--unsafe``): then each notebook runs as a plain
process of the grader's user, with only per-process limits.
"""

from __future__ import annotations

import csv
import html
import json
import math
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

from .rows import HEADER, Row, cell, num as _num, summary

__all__ = ["Row", "grade", "grade_one", "grade_assignment", "record_line", "read_submission",
           "open_submission", "cell", "main", "summary", "print_limits", "Interrupted",
           "SandboxUnavailable", "HEADER"]

CELL_TIMEOUT = 60          # seconds per cell
NOTEBOOK_TIMEOUT = 300     # seconds per notebook
MEMORY_MB = 3000           # over all the processes of a submission
PROCESSES = 128            # processes and threads of a submission
DISK_MB = 200              # its scratch tmpfs
CPUS = 1.0                 # CPUs' worth of time per period, over all its processes
MAX_NOTEBOOK_BYTES = 20_000_000
MAX_JSON_DEPTH = 64
MAX_LOG_BYTES = 2_000_000
MAX_LOG_LINE = 200_000
MAX_ANSWER_CHARS = 50_000
# exercises whose student notebook uses the library, until the exercises say so themselves
_SOLVERS_FALLBACK = {"chaplygin-sleigh", "turning-point", "work-precision"}


def record_line(feedback, answer):
    """The check-log line for an answer given to ``check`` (see
    :mod:`whittaker_teach.exercises.recorder`)."""
    from whittaker_teach.exercises.recorder import record_line as line
    return line(feedback.exercise, feedback.part,
                None if feedback.status == "unanswered" else answer)


class SandboxUnavailable(RuntimeError):
    """The sandbox cannot be had here; the message says why."""


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


def read_submission(path, folder=None):
    """(what the grader reads of it, None) or (None, why it is not a gradable notebook)."""
    nb, _, why = _read(path, folder)
    return nb, why


def _read(path, folder=None):
    """(notebook, its bytes, None) or (None, None, why it cannot be graded)."""
    try:
        return _read_checked(path, folder)
    except (Exception, RecursionError) as exc:  # noqa: BLE001 - never stop the batch
        return None, None, f"the grader could not read the file ({type(exc).__name__})"


class _Refused(Exception):
    """A submission path that is not opened; the message says why."""


def open_submission(path, folder=None):
    """A file descriptor of the regular file at ``path``, opened without following a
    symbolic link at any level of the path: every folder on the way is opened with
    ``O_DIRECTORY|O_NOFOLLOW`` relative to the one before (from ``/`` or the working
    folder), the file with ``O_NOFOLLOW``.  Then, as a second check, the file must lie
    in ``folder`` (the submissions folder, default: the file's own folder) and have
    one name only (a hard link is refused).  Raises :class:`_Refused` saying why."""
    import errno
    import stat
    p = os.fspath(path)
    parts = [c for c in p.split("/") if c not in ("", ".")]
    if not parts:
        raise _Refused("not a file")
    step = os.O_RDONLY | os.O_DIRECTORY | os.O_NOFOLLOW | os.O_CLOEXEC
    fd = os.open("/" if p.startswith("/") else ".", step)
    try:
        for i, c in enumerate(parts):
            last = i == len(parts) - 1
            flags = (os.O_RDONLY | os.O_NOFOLLOW | os.O_NONBLOCK | os.O_CLOEXEC) if last \
                else step
            try:
                nfd = os.open(c, flags, dir_fd=fd)
            except OSError as exc:
                try:
                    link = stat.S_ISLNK(os.lstat(c, dir_fd=fd).st_mode)
                except OSError:
                    link = False
                if link or exc.errno == errno.ELOOP:
                    where = "/".join(parts[:i + 1])
                    raise _Refused(("a symbolic link, not a notebook (hand in the .ipynb file "
                                    "itself)") if last else (
                        f"its path goes through a symbolic link ({shown_path(where)}), "
                        "which the grader does not follow")) from None
                if exc.errno in (errno.ENOENT, errno.ENOTDIR):
                    raise _Refused("not found") from None
                raise
            os.close(fd)
            fd = nfd
        st = os.fstat(fd)
        if not stat.S_ISREG(st.st_mode):
            raise _Refused("not a file")
        if st.st_nlink > 1:
            raise _Refused(f"a hard link (the file has {st.st_nlink} names): hand in a copy")
        real = os.readlink(f"/proc/self/fd/{fd}") if os.path.isdir("/proc/self/fd") else None
        top = os.path.realpath(folder if folder is not None else os.path.dirname(p) or ".")
        if real is not None and not real.startswith(top.rstrip("/") + "/"):
            raise _Refused("it lies outside the submissions folder")
    except BaseException:
        os.close(fd)
        raise
    return fd


def _read_checked(path, folder=None):
    import stat
    try:
        fd = open_submission(path, folder)
    except _Refused as exc:
        return None, None, str(exc)
    with os.fdopen(fd, "rb") as f:
        st = os.fstat(f.fileno())
        if not stat.S_ISREG(st.st_mode):
            return None, None, "not a file"
        if st.st_size > MAX_NOTEBOOK_BYTES:
            return None, None, (f"the file is {st.st_size // 1_000_000} MB; a notebook of at "
                                f"most {MAX_NOTEBOOK_BYTES // 1_000_000} MB is expected")
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
    summary, why = _validated(raw)
    if summary is None:
        return None, None, why
    return summary, raw, None


#: what reading and validating one notebook may cost, in a process of its own
VALIDATE_MEMORY_MB = 1024
VALIDATE_SECONDS = 20

# Run in a child process under those limits (the grader itself never parses a
# submission): the JSON is parsed and validated by nbformat, and only what the
# grader needs comes back, small: the exercise the metadata claims and the
# exercises the code cells' check(...) calls name, in order.
_VALIDATE = r"""
import json, re, sys
text = sys.stdin.buffer.read().decode("utf-8")
def out(**kw):
    sys.stdout.write(json.dumps(kw)); sys.exit(0)
try:
    data = json.loads(text)
except json.JSONDecodeError as exc:
    where = f"line {exc.lineno}, column {exc.colno}"
    if exc.pos >= len(text.rstrip()) - 1:
        out(why=f"not a notebook: the JSON is truncated (it ends at {where})")
    out(why=f"not a notebook: the JSON is damaged at {where}")
if not isinstance(data, dict) or data.get("nbformat") != 4:
    out(why="not a notebook in format 4 (save it from a current Jupyter)")
import nbformat
try:
    nb = nbformat.from_dict(data)
    nbformat.validate(nb)
except Exception as exc:
    out(why=f"not a valid notebook ({type(exc).__name__})")
meta = nb.metadata.get("whittaker_teach", {})
claimed = meta.get("exercise") if isinstance(meta, dict) else None
named = []
for c in nb.cells:
    src = "".join(c.source) if isinstance(c.source, list) else c.source
    if c.cell_type == "code" and isinstance(src, str):
        for m in re.findall(r"check\(\s*[\x22\x27]([\w-]+)[\x22\x27]", src[:100_000]):
            if m not in named and len(named) < 50:
                named.append(m[:100])
out(claimed=claimed[:100] if isinstance(claimed, str) else None, named=named)
"""


class _Summary:
    """What the grader knows of a submitted notebook: the exercise its metadata claims
    and the exercises its check(...) calls name, in order (read by :func:`_validated`)."""

    def __init__(self, claimed, named):
        self.claimed, self.named = claimed, list(named)


def _limit_validation():               # in the child, before exec
    import resource
    limit = VALIDATE_MEMORY_MB * 2**20
    resource.setrlimit(resource.RLIMIT_AS, (limit, limit))
    resource.setrlimit(resource.RLIMIT_CPU, (VALIDATE_SECONDS, VALIDATE_SECONDS + 1))


def _validated(raw):
    """(_Summary, None) or (None, why): the notebook parsed and validated in a child
    process with at most VALIDATE_MEMORY_MB of memory and VALIDATE_SECONDS of CPU."""
    try:
        proc = subprocess.run([sys.executable, "-I", "-c", _VALIDATE], input=raw,
                              capture_output=True, timeout=4 * VALIDATE_SECONDS,
                              preexec_fn=_limit_validation if os.name == "posix" else None)
    except subprocess.TimeoutExpired:
        return None, (f"not gradable: reading the notebook took more than "
                      f"{4 * VALIDATE_SECONDS} s "
                      "(it is far larger or more deeply built than a notebook should be)")
    try:
        result = json.loads(proc.stdout[:100_000].decode("utf-8")) if proc.returncode == 0 \
            else None
    except (UnicodeDecodeError, json.JSONDecodeError):
        result = None
    if not isinstance(result, dict):
        return None, ("not gradable: reading the notebook went beyond the grader's limits "
                      f"({VALIDATE_MEMORY_MB} MB, {VALIDATE_SECONDS} s)")
    if result.get("why"):
        return None, str(result["why"])[:300]
    return _Summary(result.get("claimed"), result.get("named") or []), None


def exercise_of(nb):
    """The exercise id of a student notebook (metadata, else its first check(...))."""
    if nb.claimed:
        return nb.claimed
    return nb.named[0] if nb.named else None


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
    cpus: float = CPUS


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
    rootless = sandbox.rootless()
    lease = None if settings.unsafe or rootless else sandbox.UidLease()
    # private (mkdtemp: 0700, a name no one can guess): the sandbox sees the notebook only
    # through a bind mount, so no other local account can list or copy it
    top = Path(tempfile.mkdtemp(prefix="wt-grade-"))
    nb_file = top / "submission.ipynb"
    fd = os.open(nb_file, os.O_WRONLY | os.O_CREAT | os.O_EXCL | os.O_NOFOLLOW, 0o400)
    with os.fdopen(fd, "wb") as f:
        f.write(raw)
    if lease is not None:               # readable by its sandbox's uid alone
        os.chown(nb_file, lease.uid, lease.uid)
    limits = sandbox.Limits(settings.memory_mb, settings.processes, settings.disk_mb,
                            settings.cpus)
    groups, hit, seccomp = None, set(), None
    log_r, log_w = os.pipe()
    try:
        if settings.unsafe:
            scratch = top / "scratch"
            scratch.mkdir()
            env = sandbox.environment(0, os.getpid(), math.ceil(settings.timeout))
            env.pop("WHITTAKER_TEACH_SANDBOX")
            env = {k: v.replace(sandbox.SCRATCH, str(scratch)) for k, v in env.items()}
            import whittaker_teach
            env["PYTHONPATH"] = str(Path(whittaker_teach.__file__).resolve().parents[1])
            cmd = [sys.executable, "-m", "whittaker_teach.grading.worker", "worker",
                   str(nb_file), str(scratch), f"{settings.cell_timeout:g}",
                   str(settings.memory_mb), str(settings.processes), str(settings.disk_mb),
                   str(log_w)]
            cwd = str(scratch)
        else:
            name = f"wt-grade-{os.getpid()}-{slot}-{time.monotonic_ns()}"
            groups = sandbox.Cgroups.make(name, limits)
            seccomp = sandbox.seccomp_fd()
            cmd = sandbox.command(sandbox.UID_BASE if lease is None else lease.uid,
                                  package.path(solvers), nb_file, limits,
                                  settings.cell_timeout, log_w, groups.procs, seccomp,
                                  run=os.getpid(), cpu_seconds=math.ceil(settings.timeout))
            env, cwd = {"PATH": "/usr/bin:/bin"}, str(top)
        try:
            with _LIVE_LOCK:
                if _STOP.is_set():          # interrupted before this run started
                    if groups is not None:
                        groups.close()
                    return None, "the grader was interrupted before this notebook ran", ""
                proc = subprocess.Popen(cmd, env=env, cwd=cwd, stdin=subprocess.DEVNULL,
                                        stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                        start_new_session=True, pass_fds=(log_w,) + (
                                            () if seccomp is None else (seccomp,)))
                _LIVE.add(proc)
        finally:
            os.close(log_w)
            if seccomp is not None:
                os.close(seccomp)
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
        if lease is not None:
            lease.close()


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
    from whittaker_teach.exercises import check
    kind = rec.get("kind", rec.get("status"))
    if kind == "unanswered":
        return False, "not answered"
    answer = rec.get("answer")
    if not isinstance(answer, str):
        what = _UNRECORDABLE.get(rec.get("what"), "something that is not an answer")
        return False, (f"The answer could not be graded: it is {what}; answer with an "
                       "expression, a number or a string")
    # graded: the hint names the kind of mistake, no quantity to solve for the answer
    f = check(exercise, answer[:MAX_ANSWER_CHARS], part=part, graded=True)
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
            why = _known_exception(f.get("ename")) if f.get("ename") else ""
            why = "" if why == "an exception of its own" else f": {why}"
            text = f"the notebook could not be run (the kernel did not start{why})"
            if settings.memory_mb < MEMORY_MB:     # e.g. --memory 600: too little for a kernel
                text += (f"; the memory limit is {settings.memory_mb} MB, below the default "
                         f"{MEMORY_MB} MB: try a larger --memory")
            parts.append(text)
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
        from whittaker_teach.exercises.catalog import EXERCISES
        return EXERCISES[exercise]
    except (ImportError, KeyError, TypeError):
        return None


def points(exercise):
    """{part: points}: the exercise's own points, else 1 point per part."""
    from whittaker_teach.exercises import parts
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


def _named_exercises(nb):
    """(the exercise of the notebook's metadata or None, the exercises its check(...) name)."""
    return nb.claimed, set(nb.named)


def prepare(path, name=None, assignment=None, folder=None):
    """(name, exercise or None, the notebook's bytes, rows if it cannot be run).

    With ``assignment`` (an exercise id) the notebook must be one of that exercise: its
    metadata ``whittaker_teach.exercise``, if any, names it, and its ``check(...)`` calls
    name no other; it is then graded as that exercise, whatever else it says.
    ``folder``: the submissions folder the file must lie in (:func:`open_submission`)."""
    from whittaker_teach.exercises import exercises
    name = name or Path(path).name
    nb, raw, why = _read(path, folder)
    if nb is None:
        return name, None, None, [Row(name, assignment or "", "", False, why, 0, 0)]
    if assignment is not None:
        claimed, named = _named_exercises(nb)
        other = claimed if claimed not in (None, assignment) else \
            next(iter(sorted(named - {assignment})), None)
        if other is not None:
            return name, None, None, [Row(name, assignment, "", False, OTHER_EXERCISE + (
                f"a notebook of {other[:40]!r}, not of this assignment's {assignment!r}"),
                0, 0)]
        if claimed is None and assignment not in named:
            return name, None, None, [Row(name, assignment, "", False, "not a notebook of "
                                          f"{assignment!r} (no check({assignment!r}, ...) "
                                          "in it)", 0, 0)]
        return name, assignment, raw, None
    exercise = exercise_of(nb)
    if exercise not in exercises():
        return name, None, None, [Row(name, "", "", False, "not a notebook of the exercises "
                                      "(no check(...) of a known exercise in it)", 0, 0)]
    return name, exercise, raw, None


#: how the row of a notebook of another exercise begins (the report counts these)
OTHER_EXERCISE = "refused: "


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
    """A unique name per submission: the file name, or the path where names repeat (bytes
    of a file name that are not UTF-8 shown as \\xNN)."""
    from .roster import shown
    base = [shown(Path(p).name) for p in paths]
    return [b if base.count(b) == 1 else shown(str(p)) for b, p in zip(base, paths)]


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


class Interrupted(KeyboardInterrupt):
    """Ctrl-C or SIGTERM while grading: ``rows`` and ``line`` are what was graded before
    (in the CSV too), ``graded`` the number of submissions with rows."""

    def __init__(self, rows, line, graded):
        super().__init__(line)
        self.rows, self.line, self.graded = rows, line, graded


def grade(paths, out, feedback=None, jobs=2, cell_timeout=CELL_TIMEOUT,
          timeout=NOTEBOOK_TIMEOUT, memory=MEMORY_MB, quiet=False, unsafe=False,
          processes=PROCESSES, disk=DISK_MB, gradebook=None, names=None, assignment=None,
          per_submission=None, folders=None, cpus=CPUS):
    """Grade the submissions into the CSV ``out``: (rows, summary line).

    ``names``: what each submission is called in the CSV (default: its file
    name, or its path where file names repeat); ``assignment``: an exercise
    id every notebook must be of (see :func:`prepare`); ``per_submission``: a
    list that receives the rows of each submission, in the order of ``paths``
    (None for one not graded, after an interrupt); ``folders``: the
    submissions folder of each path (default: its own folder).

    The notebooks run ``jobs`` at a time, each in its own sandbox; their
    recorded answers are checked here, in the main thread (where each check
    has its time budget), as each run ends, and its rows written at once.
    Raises :class:`SandboxUnavailable` when the sandbox cannot be had and
    ``unsafe`` is not set.  On Ctrl-C (KeyboardInterrupt) no new run starts, the
    running ones are killed with everything they started, their groups and
    temporary folders removed, the gradebook written with what was graded, and
    :class:`Interrupted` raised.
    """
    from . import sandbox
    from .exports import write_gradebook
    _STOP.clear()                   # (a grader interrupted before, in this process)
    why = sandbox.available()
    if why and not unsafe:
        raise SandboxUnavailable(why)
    for name in ("WHITTAKER_TEACH_CHECK_LOG", "WHITTAKER_TEACH_CHECK_FD",
                 "WHITTAKER_TEACH_COLLECT"):                  # the grader checks, never records
        os.environ.pop(name, None)
    settings = Settings(cell_timeout, timeout, memory, processes, disk, unsafe, cpus)
    paths = [os.fspath(p) for p in paths]
    names = list(names) if names is not None else _names(paths)
    folders = list(folders) if folders is not None else [None] * len(paths)
    writer = _Writer(out)
    package = None
    results = {}
    bar = _progress(len(paths), quiet)
    interrupted = False

    def done(i, rows):
        results[i] = rows
        writer.rows(rows)
        if feedback:
            write_feedback(feedback, [names[i]], {names[i]: rows})
        if bar is not None:
            bar.update(1)

    try:
        package = None if unsafe else sandbox.PackageCopy()
        todo = []
        for i, p in enumerate(paths):
            name, exercise, raw, rows = prepare(p, names[i], assignment, folders[i])
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
        finally:                    # Ctrl-C, say: no new run, the running ones killed (a
            if sys.exc_info()[0] is not None:   # thread about to start one finds _STOP set)
                _stop_runs()
            pool.shutdown(wait=True, cancel_futures=True)   # their sandboxes taken down
    except KeyboardInterrupt:
        interrupted = True
    finally:
        writer.close()
        if bar is not None:
            bar.close()
        if package is not None:
            package.close()
        sandbox.release()
    ordered = [results.get(i) for i in range(len(paths))]
    rows = [r for rs in ordered if rs for r in rs]
    if per_submission is not None:
        per_submission.extend(ordered)
    graded = [rs for rs in ordered if rs is not None]
    if gradebook:
        write_gradebook(gradebook, graded)
    line = summary(rows, len(graded))
    if interrupted:
        raise Interrupted(rows, line + f" (interrupted: {len(paths) - len(graded)} of "
                          f"{len(paths)} not graded)", len(graded))
    return rows, line


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


class UnsafeFolder(ValueError):
    """A feedback folder another account could plant files or links in."""


def _private_folder(folder):
    """``folder``, made 0700 if missing; an existing one must be a real folder of this
    user that no one else can write in (a link planted there would make the grader,
    often root, write through it)."""
    import stat
    folder = Path(folder)
    try:
        st = os.lstat(folder)
    except FileNotFoundError:
        folder.parent.mkdir(parents=True, exist_ok=True)
        os.mkdir(folder, 0o700)
        return folder
    if not stat.S_ISDIR(st.st_mode):
        raise UnsafeFolder(f"{folder} is not a folder (a link or a file): give a new folder "
                           "for the feedback pages")
    if st.st_uid != os.geteuid() or st.st_mode & 0o022:
        raise UnsafeFolder(f"{folder} can be written by other accounts: give a new folder "
                           "for the feedback pages (the grader makes it, mode 0700)")
    return folder


def _write_private(path, text):
    """Write ``path`` without following a link: a new file (O_EXCL|O_NOFOLLOW) renamed
    over the old name."""
    tmp = path.with_name(f".{path.name}.{os.getpid()}.tmp")
    fd = os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_EXCL | getattr(os, "O_NOFOLLOW", 0),
                 0o600)
    with os.fdopen(fd, "w", encoding="utf-8") as f:
        f.write(text)
    os.replace(tmp, path)


def write_feedback(folder, names, results):
    """One HTML page per submission: its parts, right or not, and the grader's messages,
    into a private folder (:func:`_private_folder`), never through a link."""
    folder = _private_folder(folder)
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
        _write_private(folder / page_name(name), page)


class NothingFound(ValueError):
    """No notebook where the submissions were said to be; the message says what was looked at."""


def nothing_found(paths, skipped):
    """Why nothing was graded: what was given, and the layouts ``grade`` reads."""
    given = ", ".join(shown_path(p) for p in list(paths)[:3]) + (" ..." if len(paths) > 3
                                                                  else "")
    missing = [m for m in skipped if m.status == "not-found"]
    return (f"found no notebook in {given or 'nothing'}"
            + (f" ({len(missing)} path{'s' if len(missing) != 1 else ''} not found: a "
               "shell pattern that matched nothing?)" if missing else "")
            + ". Pass the folder the LMS download was extracted into: .ipynb files named "
            "as Canvas or Moodle name them, or Moodle's folders "
            "<Full name>_<participant>_assignsubmission_file/")


def shown_path(p):
    from .roster import shown
    return shown(os.fspath(p))


@dataclass
class Outcome:
    """What :func:`grade_assignment` did: the rows, the summary line, the identity report's
    entries and what the exports wrote."""

    rows: list
    line: str
    report: list            # [(status, submission, student id, name, rule, detail)]
    problems: int           # notebooks not graded under anyone, or refused
    exports: list           # lines for the lecturer


REPORT_HEADER = ["status", "submission", "student_id", "student_name", "rule", "detail"]


def grade_assignment(paths, exercise, roster, out, report=None, gradebook=None, canvas=None,
                     canvas_out=None, canvas_column=None, moodle=None, moodle_out=None,
                     overwrite_feedback=False, **kw):
    """Grade the notebooks under ``paths`` for the assignment ``exercise``, each under the
    roster entry it fits (:mod:`.roster`); write the identity ``report`` and the exports.

    A notebook graded under no one (unknown, ambiguous, duplicate) or refused (another
    exercise, not a notebook) is in the report, never in an export.  Raises
    :class:`NothingFound` when there is no notebook at all."""
    from . import exports as ex
    from . import roster as rs
    notebooks, skipped = rs.assign(paths, roster)
    if not notebooks:
        raise NothingFound(nothing_found(paths, skipped))
    todo = [m for m in notebooks if m.status == "matched"]
    per, stopped = [], None
    try:
        rows, line = grade([m.path for m in todo], out, names=[m.name for m in todo],
                           assignment=exercise, per_submission=per,
                           folders=[m.folder for m in todo], **kw)
    except Interrupted as exc:      # what was graded is still reported and exported
        rows, line, stopped = exc.rows, exc.line, exc
    entries, graded, problems = [], {}, 0
    for m, rs_rows in zip(todo, per):
        if rs_rows is None:
            problems += 1
            entries.append(["not-graded", m.name, m.student.id, m.student.name, m.rule,
                            "the grader was interrupted before this notebook was graded"])
            continue
        parts = [r for r in rs_rows if r.part]
        if parts:
            graded[m.student.id] = (m, rs_rows)
            entries.append(["graded", m.name, m.student.id, m.student.name, m.rule, ""])
        else:
            problems += 1
            why = rs_rows[0].message if rs_rows else ""
            status = "other-exercise" if why.startswith(OTHER_EXERCISE) else "not-graded"
            entries.append([status, m.name, m.student.id, m.student.name, m.rule, why])
    for m in notebooks:
        if m.status != "matched":
            problems += 1
            entries.append([m.status, m.name, m.student.id if m.student else "",
                            m.student.name if m.student else "", m.rule, m.reason])
    for m in skipped:
        entries.append([m.status, m.name, "", "", "", m.reason])
    handed = {m.student.id for m in notebooks if m.student is not None}
    for sid, st in roster.students.items():
        if sid not in handed:
            entries.append(["no-submission", "", sid, st.name, "", ""])
    done = []
    if gradebook:
        ex.write_gradebook(gradebook, [r for _, r in graded.values()],
                           [m.student for m, _ in graded.values()])
        done.append(f"gradebook in {gradebook}")
    pts = {sid: _points_of(r) for sid, (_, r) in graded.items()}
    if canvas:
        dst = canvas_out or ex.default_out(canvas)
        title = getattr(_exercise(exercise), "title", None)
        column, written, missing = ex.fill_canvas(canvas, dst, pts, exercise, title,
                                                  canvas_column)
        done.append(f"Canvas: {len(written)} grades in column {column!r} of {dst}")
        for sid in missing:
            entries.append(["not-in-canvas", graded[sid][0].name, sid,
                            graded[sid][0].student.name, "", "graded, but not a student of "
                            "the Canvas gradebook: not exported"])
    if moodle:
        dst = moodle_out or ex.default_out(moodle)
        fb = {sid: (*pts[sid], ex.feedback_text(r)) for sid, (_, r) in graded.items()}
        written, missing = ex.fill_moodle(moodle, dst, fb, overwrite_feedback)
        done.append(f"Moodle: {len(written)} grades in {dst}")
        for sid in missing:
            entries.append(["not-in-moodle", graded[sid][0].name, sid,
                            graded[sid][0].student.name, "", "graded, but not a participant "
                            "of the Moodle worksheet: not exported"])
    if report:
        with open(report, "w", newline="", encoding="utf-8") as f:
            w = csv.writer(f)
            w.writerow(REPORT_HEADER)
            for e in entries:
                w.writerow([cell(v) for v in e])
    if stopped is not None:
        stopped.outcome = Outcome(rows, line, entries, problems, done)
        raise stopped
    return Outcome(rows, line, entries, problems, done)


def _points_of(rows):
    parts = [r for r in rows if r.part]
    return sum(r.points for r in parts), sum(r.max_points for r in parts)


def _refuse_sandbox(why):
    print(f"grade: refusing to run students' notebooks without the sandbox: {why}.\n"
          "Run on Linux with bubblewrap (make sysdeps), as root or as a user who may make "
          "user namespaces, or pass --unsafe to run "
          "them as plain processes of your user, with per-process limits only.",
          file=sys.stderr)
    return 2


def main(args):
    """The ``grade`` subcommand: 0 when every notebook was graded under one student (or, without
    a roster, graded), 1 when the identity report lists notebooks graded under no one or
    refused, 2 when nothing could be graded (no notebook found, a bad roster or LMS file)."""
    from . import sandbox
    opt = {k: getattr(args, k, None) for k in (
        "roster", "exercise", "report", "canvas", "canvas_out", "canvas_column", "moodle",
        "moodle_out", "overwrite_feedback", "gradebook", "feedback")}
    paths = [os.fspath(p) for p in args.submissions]
    lms = opt["canvas"] or opt["moodle"]
    if (lms or opt["roster"]) and not opt["exercise"]:
        print("grade: --roster, --canvas and --moodle need --exercise ID (the assignment's "
              "exercise: every notebook is graded as that exercise, or refused)",
              file=sys.stderr)
        return 2
    why = sandbox.available()
    if why and not args.unsafe:
        return _refuse_sandbox(why)
    if opt["feedback"]:
        try:                        # before any notebook runs, not after the class
            _private_folder(opt["feedback"])
        except UnsafeFolder as exc:
            print(f"grade: {exc}", file=sys.stderr)
            return 2
    settings = dict(feedback=opt["feedback"], jobs=args.jobs, cell_timeout=args.cell_timeout,
                    timeout=args.timeout, memory=args.memory, quiet=args.quiet,
                    unsafe=bool(why), gradebook=opt["gradebook"])
    for k in ("cpus", "processes", "disk"):
        if getattr(args, k, None) is not None:
            settings[k] = getattr(args, k)
    if not why:
        print_limits(settings)
    start = time.monotonic()
    restore = _on_signals()
    try:
        if opt["exercise"]:
            out = _main_assignment(paths, args, opt, settings)
            if isinstance(out, int):
                return out
            line, code, extra = out
        else:
            from .roster import assign
            notebooks, skipped = assign(paths, None)
            if not notebooks:
                print(f"grade: {nothing_found(paths, skipped)}", file=sys.stderr)
                return 2
            for m in skipped:
                print(f"grade: passed over {m.name}: {m.reason}", file=sys.stderr)
            files = [m.path for m in notebooks]
            names = _names(files) if all(len(m.parts) <= 1 for m in notebooks) else \
                [m.name for m in notebooks]
            _, line = grade(files, args.out, names=names,
                            folders=[m.folder for m in notebooks], **settings)
            code, extra = 0, []
    except KeyboardInterrupt as exc:
        outcome = getattr(exc, "outcome", None)
        print(f"\ngrade: interrupted; the submissions graded so far are in {args.out}"
              + (f" ({exc.line})" if isinstance(exc, Interrupted) else ""), file=sys.stderr)
        for x in (outcome.exports if outcome is not None else []):
            print(f"grade: {x} (the students graded before the interrupt)", file=sys.stderr)
        return 130
    finally:
        restore()
        sandbox.release()
    took = time.monotonic() - start
    print(f"{line} ({took:.0f} s); grades in {args.out}"
          + (f", feedback in {opt['feedback']}" if opt["feedback"] else ""))
    for x in extra:
        print(x)
    if why:
        print(f"(UNSAFE: the notebooks ran without the sandbox: {why})")
    return code


def print_limits(settings, file=None):
    """Print what limits each sandbox will have here, and by what mechanism."""
    from . import sandbox
    limits = sandbox.Limits(settings.get("memory", MEMORY_MB),
                            settings.get("processes", PROCESSES), settings.get("disk", DISK_MB),
                            settings.get("cpus", CPUS))
    lines = sandbox.enforced(limits, settings.get("timeout", NOTEBOOK_TIMEOUT))
    width = max(len(k) for k, _ in lines)
    print("grade: each notebook runs in a sandbox of its own with these limits:",
          file=file or sys.stdout)
    for k, v in lines:
        print(f"  {k + ':':<{width + 1}} {v}", file=file or sys.stdout)
    (file or sys.stdout).flush()


def _on_signals():
    """SIGTERM (and SIGINT) raise KeyboardInterrupt in the main thread, once: a second
    signal while the grader writes what it has and takes the sandboxes down is ignored.
    Returns a function that puts the old handlers back."""
    import signal
    if threading.current_thread() is not threading.main_thread():
        return lambda: None
    fired = []

    def handler(signum, frame):
        if not fired:
            fired.append(signum)
            raise KeyboardInterrupt
        print("grade: still writing the grades and stopping the sandboxes ...",
              file=sys.stderr)
    old = {sig: signal.signal(sig, handler) for sig in (signal.SIGINT, signal.SIGTERM)}

    def restore():
        for sig, h in old.items():
            signal.signal(sig, h)
    return restore


def _main_assignment(paths, args, opt, settings):
    from whittaker_teach.exercises import exercises
    from .exports import ExportError
    from .roster import Roster, RosterError
    exercise = opt["exercise"]
    if exercise not in exercises():
        print(f"grade: no exercise {exercise!r} (known: {', '.join(sorted(exercises()))})",
              file=sys.stderr)
        return 2
    source = opt["roster"] or opt["canvas"] or opt["moodle"]
    if not source:
        print("grade: --exercise needs a roster: --roster FILE (or --canvas/--moodle, whose "
              "downloaded file is then the roster)", file=sys.stderr)
        return 2
    try:
        roster = Roster.read(source)
    except RosterError as exc:
        print(f"grade: {exc}", file=sys.stderr)
        return 2
    report = opt["report"] or str(Path(args.out).with_name(Path(args.out).stem +
                                                          "-identities.csv"))
    try:
        res = grade_assignment(paths, exercise, roster, args.out, report=report,
                               canvas=opt["canvas"], canvas_out=opt["canvas_out"],
                               canvas_column=opt["canvas_column"], moodle=opt["moodle"],
                               moodle_out=opt["moodle_out"],
                               overwrite_feedback=bool(opt["overwrite_feedback"]), **settings)
    except NothingFound as exc:
        print(f"grade: {exc}", file=sys.stderr)
        return 2
    except ExportError as exc:
        print(f"grade: the grades are in {args.out}, but not exported: {exc}",
              file=sys.stderr)
        return 2
    extra = list(res.exports) + [f"identities in {report} (roster {source}: "
                                 f"{len(roster.students)} students)"]
    if res.problems:
        extra.append(f"{res.problems} notebook{'s' if res.problems != 1 else ''} graded "
                     f"under no one or refused: see {report}")
        for status, name, sid, sname, rule, detail in res.report:
            if status not in ("graded", "no-submission"):
                print(f"grade: {status}: {name}: {detail}", file=sys.stderr)
    return res.line, (1 if res.problems else 0), extra


if __name__ == "__main__":
    sys.exit("usage: python -m whittaker_teach grade --exercise ID --roster ROSTER.csv "
             "SUBMISSIONS... --out grades.csv")
