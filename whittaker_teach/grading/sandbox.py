"""The sandbox a graded notebook runs in: bubblewrap, a dedicated uid, cgroup limits.

One sandbox per submission.  The whole run of the notebook (nbclient and
the kernel it starts) happens inside it, so nothing the notebook starts
outlives it and nothing in it can reach the grader:

- **namespaces** (``bwrap --unshare-pid --unshare-ipc --unshare-net
  --unshare-uts --unshare-cgroup-try``, and a mount namespace): its own
  process tree (the grader, the other submissions and their command lines
  are invisible; when the sandbox's first process ends, the kernel kills
  every process left in it), no network but its own loopback (no host
  sockets: no file system path to one is mounted), its own hostname;
- **files**: a fresh root with only ``/usr`` (and the ``/lib``, ``/bin``
  links), a few files of ``/etc`` (the dynamic linker's cache, fonts, a
  ``passwd`` naming the sandbox's user), the Python environment
  (``sys.prefix``, ``sys.base_prefix``), all read-only; a copy of
  ``whittaker_teach`` **without** its exercises' answers or checker (the
  package's ``exercises`` is :mod:`whittaker_teach.exercises.recorder`, its
  ``grading`` only :mod:`.worker`; where the exercise does not
  allow the library's solvers, the package is only ``check`` and
  ``notebook.setup``); the submission read-only; ``/scratch``, a tmpfs of at
  most ``disk_mb``, the only place it can write; its own ``/proc`` and a
  minimal read-only ``/dev``; no ``/sys``, no ``/tmp`` but ``$TMPDIR`` in
  scratch;
- **user**: a uid and gid of its own (61000 + the job slot, in no group),
  no capabilities, ``no_new_privs``;
- **environment**: cleared, then :func:`environment`'s fixed list;
- **limits over all its processes** (cgroup v1 where the grader can make
  one, see :class:`Limits`): memory (``memory.limit_in_bytes``), processes
  and threads (``pids.max``); always: the scratch tmpfs's size (disk), and
  ``RLIMIT_NPROC`` of its uid, ``RLIMIT_AS`` and ``RLIMIT_FSIZE`` per process
  (set by the worker before the kernel starts); the grader reads at most
  ``MAX_RESULT_BYTES`` of what it reports, and the worker keeps at most
  ``MAX_OUTPUT_CHARS`` of the kernel's output.

Run as root on Linux (in a container is fine): bubblewrap needs root here to
bind the Python environment for another uid and to change to that uid.
:func:`available` says why not where it cannot be had.

>>> Limits(memory_mb=3000, pids=128, disk_mb=200).memory_bytes
3145728000
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import tempfile
from dataclasses import dataclass, field
from pathlib import Path

__all__ = ["available", "Limits", "Cgroups", "cgroup_limits", "PackageCopy", "command",
           "environment",
           "UID_BASE", "UID_COUNT", "UidLease", "SCRATCH"]

UID_BASE = 61000
UID_COUNT = 64
#: where the graders of this machine lease their uids (one lock file per uid)
LEASE_DIR = Path("/run/whittaker-teach-grade")


class UidLease:
    """A sandbox uid (UID_BASE to UID_BASE + UID_COUNT - 1) that no other grader on this
    machine holds: an exclusive ``flock`` on ``LEASE_DIR/<uid>``, kept for one run, so
    two graders running at once never share a uid (and never kill each other's
    students).  Processes left with the uid by a grader that died are killed when
    the lease is taken.  ``close()`` gives the uid back.
    """

    def __init__(self, lease_dir=None, kill_left=True):
        import fcntl
        import stat
        d = Path(lease_dir or LEASE_DIR)
        d.mkdir(mode=0o700, exist_ok=True)
        st = os.lstat(d)
        if not stat.S_ISDIR(st.st_mode) or st.st_uid != os.geteuid() or st.st_mode & 0o077:
            raise RuntimeError(f"{d} is not a private folder of this user (mode 0700)")
        for uid in range(UID_BASE, UID_BASE + UID_COUNT):
            fd = os.open(d / str(uid), os.O_RDWR | os.O_CREAT | os.O_NOFOLLOW | os.O_CLOEXEC,
                         0o600)
            try:
                fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
            except OSError:
                os.close(fd)
                continue
            self.uid, self._fd = uid, fd
            if kill_left:
                _kill_uid(uid)
            return
        raise RuntimeError(f"all {UID_COUNT} sandbox uids are held by other graders")

    def close(self):
        if self._fd is not None:
            os.close(self._fd)
            self._fd = None


def _kill_uid(uid):
    """SIGKILL every process of ``uid`` (a leased uid: no live grader uses it)."""
    import signal
    for d in os.listdir("/proc"):
        if d.isdigit():
            try:
                if os.stat(f"/proc/{d}").st_uid == uid:
                    os.kill(int(d), signal.SIGKILL)
            except OSError:
                pass
SCRATCH = "/scratch"
PACKAGE_ROOT = "/opt/whittaker-teach"
SUBMISSION = "/grade/submission.ipynb"
MAX_RESULT_BYTES = 4_000_000


@dataclass
class Limits:
    """What one submission may use, over all its processes."""

    memory_mb: int = 3000
    pids: int = 128
    disk_mb: int = 200

    @property
    def memory_bytes(self):
        return self.memory_mb * 1024 * 1024


_AVAILABLE = []


def available():
    """'' when submissions can be sandboxed here, else why not (one sentence)."""
    if not _AVAILABLE:
        _AVAILABLE.append(_why_not())
    return _AVAILABLE[0]


def _why_not():
    if not sys.platform.startswith("linux"):
        return "the sandbox needs Linux (bubblewrap)"
    if shutil.which("bwrap") is None:
        return "bubblewrap is not installed (Debian: apt-get install bubblewrap; make sysdeps)"
    if shutil.which("setpriv") is None:
        return "setpriv (util-linux) is not installed"
    if os.geteuid() != 0:
        return ("the grader is not root: the sandbox runs each submission under a uid of its "
                "own, which needs root (run grade as root in a container)")
    try:
        proc = subprocess.run(["bwrap", "--unshare-pid", "--unshare-net", "--unshare-ipc",
                               "--die-with-parent", "--ro-bind", "/", "/", "--proc", "/proc",
                               "--dev", "/dev", "--", "true"],
                              capture_output=True, timeout=30)
    except (OSError, subprocess.SubprocessError) as exc:
        return f"bubblewrap could not be run ({type(exc).__name__})"
    if proc.returncode != 0:
        err = proc.stderr.decode("utf-8", "replace").strip().splitlines()
        return ("bubblewrap cannot make namespaces here (" + (err[-1][:120] if err else
                f"exit status {proc.returncode}") + "); a container needs to allow them")
    return ""


# ---------------------------------------------------------------- cgroups
def _v1_mounts():
    """{controller: (mount point, the hierarchy's folder mounted there)}, cgroup v1."""
    out = {}
    try:
        with open("/proc/self/mountinfo", encoding="utf-8") as f:
            for line in f:
                left, _, right = line.partition(" - ")
                fields = right.split()
                if len(fields) >= 3 and fields[0] == "cgroup":
                    for opt in fields[2].split(","):
                        if opt in ("memory", "pids"):     # (mount point, its root)
                            out[opt] = (left.split()[4], left.split()[3])
    except OSError:
        pass
    return out


def _own_path(controller):
    try:
        with open("/proc/self/cgroup", encoding="utf-8") as f:
            for line in f:
                _, names, path = line.rstrip("\n").split(":", 2)
                if controller in names.split(","):
                    return path
    except (OSError, ValueError):
        pass
    return None


@dataclass
class Cgroups:
    """One submission's memory and pids cgroups (v1), or none where they cannot be made.

    ``paths`` are the ``cgroup.procs`` files the sandbox's first process
    joins before it starts bubblewrap; :meth:`close` kills anything left and
    removes the groups.
    """

    dirs: dict = field(default_factory=dict)

    @classmethod
    def make(cls, name, limits):
        group = cls()
        if os.geteuid() != 0:
            return group
        for controller, (mount, root) in _v1_mounts().items():
            own = _own_path(controller)
            if own is None:
                continue
            if root != "/" and (own == root or own.startswith(root + "/")):
                own = own[len(root):]        # a container that mounts only its own subtree
            d = Path(mount) / own.lstrip("/") / name
            try:
                d.mkdir()
            except OSError:
                continue
            try:
                if controller == "memory":
                    (d / "memory.limit_in_bytes").write_text(str(limits.memory_bytes))
                    swap = d / "memory.memsw.limit_in_bytes"
                    if swap.exists():
                        swap.write_text(str(limits.memory_bytes))
                else:
                    (d / "pids.max").write_text(str(limits.pids))
            except OSError:
                _rmdir(d)
                continue
            group.dirs[controller] = d
        return group

    @property
    def procs(self):
        return [str(d / "cgroup.procs") for d in self.dirs.values()]

    @property
    def enforced(self):
        return sorted(self.dirs)

    def hit(self):
        """Which limits were reached: a subset of {'memory', 'pids'}."""
        out = set()
        try:
            if "memory" in self.dirs:
                d = self.dirs["memory"]
                oom = dict(line.split() for line in (d / "memory.oom_control").read_text()
                           .splitlines() if len(line.split()) == 2)
                if int((d / "memory.failcnt").read_text()) > 0 or int(oom.get("oom_kill", 0)):
                    out.add("memory")
        except (OSError, ValueError):
            pass
        try:
            if "pids" in self.dirs:
                events = (self.dirs["pids"] / "pids.events").read_text().split()
                if len(events) >= 2 and int(events[1]) > 0:
                    out.add("pids")
        except (OSError, ValueError):
            pass
        return out

    def close(self):
        import signal
        import time
        for d in self.dirs.values():
            for _ in range(50):
                try:
                    pids = [int(p) for p in (d / "cgroup.procs").read_text().split()]
                except (OSError, ValueError):
                    break
                if not pids:
                    break
                for pid in pids:
                    try:
                        os.kill(pid, signal.SIGKILL)
                    except OSError:
                        pass
                time.sleep(0.05)
            for _ in range(40):               # a group whose last task is still exiting: busy
                if _rmdir(d):
                    break
                time.sleep(0.05)


def cgroup_limits():
    """Which limits cgroups enforce over all of a submission's processes here: a subset of
    ['memory', 'pids'] (empty: per-process limits only)."""
    group = Cgroups.make(f"wt-grade-probe-{os.getpid()}", Limits())
    try:
        return group.enforced
    finally:
        group.close()


def _rmdir(d):
    try:
        d.rmdir()
    except FileNotFoundError:
        return True
    except OSError:
        return False
    return True


# ---------------------------------------------------------------- the package it sees
# the only modules of a package without solvers; exercises/ is the recorder everywhere
_STUB = '''\
"""whittaker_teach as a graded notebook of this exercise sees it: check and setup only.

The exercise does not allow the library's solvers while it is graded.
"""
import importlib.abc as _abc
import sys as _sys

_ALLOWED = ("whittaker_teach.exercises", "whittaker_teach.exercises.recorder",
            "whittaker_teach.grading", "whittaker_teach.grading.worker",
            "whittaker_teach.notebook")
_WHY = (" is not available while this exercise is graded: the exercise asks you to derive "
        "it yourself (only whittaker_teach.exercises.check and whittaker_teach.notebook.setup "
        "are)")


def _refuse(name):
    from whittaker_teach.exercises.recorder import record_event
    record_event("solver", name)
    return name + _WHY


class _Guard(_abc.MetaPathFinder):
    def find_spec(self, fullname, path, target=None):
        if fullname.startswith("whittaker_teach.") and fullname not in _ALLOWED:
            raise ImportError(_refuse(fullname), name=fullname)
        return None


_sys.meta_path.insert(0, _Guard())


def __getattr__(name):
    if name.startswith("__") or "whittaker_teach." + name in _ALLOWED:
        raise AttributeError(name)
    raise AttributeError(_refuse("whittaker_teach." + name))
'''


class PackageCopy:
    """The copies of ``whittaker_teach`` bound into sandboxes (made once per batch).

    ``path(solvers)`` is a folder holding ``whittaker_teach/``: with
    ``solvers`` the whole package but its ``exercises/``; without, only
    ``__init__`` (a guard that refuses and records any other import),
    ``notebook.py``.  In both ``exercises/`` holds only
    :mod:`whittaker_teach.exercises.recorder` (as ``__init__.py`` too) and
    ``grading/`` only :mod:`.worker` (with an empty ``__init__.py``): never
    the grader, the roster, the exports, the answers or the checker.
    """

    def __init__(self):
        import whittaker_teach
        self.source = Path(whittaker_teach.__file__).resolve().parent
        self.top = Path(tempfile.mkdtemp(prefix="wt-grade-package-"))
        os.chmod(self.top, 0o755)
        self._made = {}
        import threading
        self._lock = threading.Lock()

    def path(self, solvers):
        with self._lock:
            return self._path(solvers)

    def _path(self, solvers):
        if solvers not in self._made:
            root = self.top / ("with-solvers" if solvers else "check-only")
            pkg = root / "whittaker_teach"
            if solvers:
                shutil.copytree(self.source, pkg, ignore=shutil.ignore_patterns(
                    "__pycache__", "*.pyc", "exercises", "grading"))
            else:
                pkg.mkdir(parents=True)
                (pkg / "__init__.py").write_text(_STUB, encoding="utf-8")
                shutil.copy(self.source / "notebook.py", pkg / "notebook.py")
            ex = pkg / "exercises"
            ex.mkdir()
            shutil.copy(self.source / "exercises" / "recorder.py", ex / "__init__.py")
            shutil.copy(self.source / "exercises" / "recorder.py", ex / "recorder.py")
            grading = pkg / "grading"
            grading.mkdir()
            (grading / "__init__.py").write_text('"""The sandbox\'s worker only."""\n',
                                                 encoding="utf-8")
            shutil.copy(self.source / "grading" / "worker.py", grading / "worker.py")
            import compileall           # the sandbox writes no bytecode: compile it once here
            compileall.compile_dir(str(root), quiet=2, workers=1)
            for d, dirs, files in os.walk(root):
                os.chmod(d, 0o755)
                for f in files:
                    os.chmod(os.path.join(d, f), 0o644)
            self._made[solvers] = root
        return self._made[solvers]

    def close(self):
        shutil.rmtree(self.top, ignore_errors=True)


# ---------------------------------------------------------------- the command
def environment(uid):
    """The sandbox's whole environment (``bwrap --clearenv`` then these)."""
    py = str(Path(sys.executable).parent)
    return {"PATH": f"{py}:/usr/local/bin:/usr/bin:/bin", "HOME": f"{SCRATCH}/home",
            "TMPDIR": f"{SCRATCH}/tmp", "USER": "student", "LOGNAME": "student",
            "LANG": "C.UTF-8", "LC_ALL": "C.UTF-8", "PYTHONPATH": PACKAGE_ROOT,
            "PYTHONHASHSEED": "0", "PYTHONDONTWRITEBYTECODE": "1", "MPLBACKEND": "Agg",
            "MPLCONFIGDIR": f"{SCRATCH}/.matplotlib", "JUPYTER_PATH": f"{SCRATCH}/.jupyter",
            "JUPYTER_DATA_DIR": f"{SCRATCH}/.jupyter", "JUPYTER_RUNTIME_DIR":
            f"{SCRATCH}/.jupyter/runtime", "JUPYTER_CONFIG_DIR": f"{SCRATCH}/.jupyter",
            "JUPYTER_PLATFORM_DIRS": "1", "IPYTHONDIR": f"{SCRATCH}/.ipython",
            "OPENBLAS_NUM_THREADS": "1", "OMP_NUM_THREADS": "1", "MKL_NUM_THREADS": "1",
            "WHITTAKER_TEACH_SANDBOX": str(uid)}


def _root_binds():
    """The read-only system part: /usr, the /lib... links or folders, a few files of /etc."""
    args = ["--ro-bind", "/usr", "/usr"]
    for name in ("bin", "sbin", "lib", "lib32", "lib64", "libx32"):
        p = Path("/") / name
        if p.is_symlink():
            args += ["--symlink", os.readlink(p), str(p)]
        elif p.is_dir():
            args += ["--ro-bind", str(p), str(p)]
    for name in ("ld.so.cache", "ld.so.conf", "ld.so.conf.d", "fonts", "localtime",
                 "alternatives", "ssl/openssl.cnf", "mime.types"):
        p = Path("/etc") / name
        if p.exists():
            args += ["--ro-bind", str(p), str(p)]
    return args


def _answer_dirs():
    """Every folder the exercises keep answer data in (their ``answers_dirs()``, if any)."""
    try:
        from whittaker_teach.exercises import answers_dirs
        return [Path(d).resolve() for d in answers_dirs() if Path(d).is_dir()]
    except Exception:  # noqa: BLE001 - an older package without it: nothing more to hide
        return []


def _under(path, roots):
    return any(path == r or r in path.parents for r in roots)


def command(uid, package_root, submission, limits, cell_timeout, log_fd, procs=()):
    """The argv that runs the worker for one submission in its sandbox.

    ``log_fd``: the write end of the pipe the check log goes to (inherited
    by the worker and its kernel: the grader reads the answers as they are
    recorded, so they survive the run's end, however it ends).
    ``procs``: cgroup.procs files the first process joins (``sh`` writes its
    pid, then becomes bubblewrap).
    """
    prefixes = []
    for p in (sys.prefix, sys.base_prefix, str(Path(sys.executable).resolve().parents[1])):
        p = Path(p).resolve()
        if not _under(p, [Path("/usr")] + prefixes) and p not in prefixes:
            prefixes.append(p)
    args = ["bwrap", "--unshare-pid", "--unshare-ipc", "--unshare-net", "--unshare-uts",
            "--unshare-cgroup-try", "--die-with-parent", "--new-session", "--hostname", "grade"]
    made = set()
    for p in [Path("/etc/x"), Path("/opt/x"), Path("/grade/x")] + [p / "x" for p in prefixes]:
        for d in reversed(p.parents[:-1]):      # folders on the way: readable, not 0700
            if d not in made:
                made.add(d)
                args += ["--perms", "0755", "--dir", str(d)]
    args += _root_binds()
    for p in prefixes:
        args += ["--ro-bind", str(p), str(p)]
    # the grader's own package, if it lies inside a bound folder, is hidden under the copy
    import whittaker_teach
    src = Path(whittaker_teach.__file__).resolve().parent
    if _under(src, prefixes + [Path("/usr")]):
        args += ["--ro-bind", str(Path(package_root) / "whittaker_teach"), str(src)]
    for d in _answer_dirs():                # answer data inside a bound folder: hidden
        if _under(d, prefixes + [Path("/usr")]) and not _under(d, [src]):
            args += ["--tmpfs", str(d)]
    passwd = Path(package_root).parent / "passwd"
    if not passwd.exists():
        passwd.write_text("root:x:0:0::/:/usr/sbin/nologin\n" + "".join(
            f"student:x:{UID_BASE + i}:{UID_BASE + i}::{SCRATCH}:/usr/sbin/nologin\n"
            for i in range(64)), encoding="utf-8")
        os.chmod(passwd, 0o644)
    args += ["--ro-bind", str(passwd), "/etc/passwd",
             "--ro-bind", str(package_root), PACKAGE_ROOT,
             "--ro-bind", str(submission), SUBMISSION,
             "--proc", "/proc", "--dev", "/dev", "--remount-ro", "/dev",
             "--size", str(limits.disk_mb * 1024 * 1024), "--perms", "1777",
             "--tmpfs", SCRATCH, "--remount-ro", "/", "--chdir", "/", "--clearenv"]
    for k, v in environment(uid).items():
        args += ["--setenv", k, v]
    args += ["--", shutil.which("setpriv") or "/usr/bin/setpriv", f"--reuid={uid}",
             f"--regid={uid}", "--clear-groups", "--bounding-set=-all", "--inh-caps=-all",
             "--no-new-privs", "--", sys.executable, "-m", "whittaker_teach.grading.worker",
             "worker", SUBMISSION, SCRATCH, f"{cell_timeout:g}", str(limits.memory_mb),
             str(limits.pids), str(limits.disk_mb), str(log_fd)]
    if procs:
        join = "for f in " + " ".join(f"'{p}'" for p in procs) + \
            "; do echo $$ > \"$f\" || exit 97; done; exec \"$@\""
        args = ["/bin/sh", "-c", join, "sh", *args]
    return args
