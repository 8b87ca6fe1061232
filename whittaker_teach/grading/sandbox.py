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
- **user**: as root, a uid and gid of its own (61000 to 61063, leased with a
  lock: :class:`UidLease`), in no group, no capabilities, ``no_new_privs``;
  rootless (:func:`rootless`), the grader's own uid in a user namespace of its
  own (``bwrap --unshare-user --disable-userns``);
- **system calls**: a seccomp filter (:func:`seccomp_filter`) denies the
  kernel's key management (``add_key``, ``request_key``, ``keyctl``) and every
  call of another ABI: no key survives for a later submission, and no keyring
  its processes inherit can be used;
- **environment**: cleared, then :func:`environment`'s fixed list;
- **limits over all its processes**, where cgroups can be had
  (:class:`Hierarchy`: cgroup v2 for each controller the v2 hierarchy has,
  else cgroup v1): memory (``memory.max``/``memory.limit_in_bytes``), processes
  and threads (``pids.max``), CPU (``cpu.max``/``cpu.cfs_quota_us``: ``cpus``
  CPUs' worth); always: the scratch tmpfs's size (disk), and per process
  ``RLIMIT_AS``, ``RLIMIT_FSIZE``, ``RLIMIT_CPU``, and ``RLIMIT_NPROC`` where it
  counts the sandbox's processes alone (set by the worker before the kernel
  starts); the grader reads at most ``MAX_RESULT_BYTES`` of what it reports,
  and the worker keeps at most ``MAX_OUTPUT_CHARS`` of the kernel's output.
  :func:`enforced` says which of these hold here, and how.

Run as root on Linux (in a container is fine), or as any user where
unprivileged user namespaces are allowed.  :func:`available` says why not
where the sandbox cannot be had.

>>> Limits(memory_mb=3000, pids=128, disk_mb=200).memory_bytes
3145728000
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import tempfile
import threading
from dataclasses import dataclass, field
from pathlib import Path

__all__ = ["available", "rootless", "Limits", "Hierarchy", "Cgroups", "cgroup_limits",
           "hierarchy", "release", "enforced", "seccomp_filter", "seccomp_fd", "PackageCopy",
           "command", "environment", "UID_BASE", "UID_COUNT", "UidLease", "SCRATCH"]

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
    cpus: float = 1.0            # CPUs' worth of time per period, over all its processes

    @property
    def memory_bytes(self):
        return self.memory_mb * 1024 * 1024

    def cpu_quota_us(self, period):
        """The CPU time its processes may use per ``period`` microseconds (at least 1 ms)."""
        return max(1000, int(round(self.cpus * period)))


def rootless():
    """True when the grader is not root: each sandbox is then a user namespace of its own
    (``bwrap --unshare-user``) under the grader's uid, instead of a uid of its own."""
    return os.geteuid() != 0


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
    if not rootless() and shutil.which("setpriv") is None:
        return "setpriv (util-linux) is not installed"
    probe = ["bwrap"] + (["--unshare-user", "--disable-userns"] if rootless() else []) + [
        "--unshare-pid", "--unshare-net", "--unshare-ipc", "--die-with-parent",
        "--ro-bind", "/", "/", "--proc", "/proc", "--dev", "/dev"]
    fd = seccomp_fd()
    if fd is not None:
        probe += ["--seccomp", str(fd)]
    try:
        proc = subprocess.run(probe + ["--", "true"], capture_output=True, timeout=30,
                              pass_fds=(fd,) if fd is not None else ())
    except (OSError, subprocess.SubprocessError) as exc:
        return f"bubblewrap could not be run ({type(exc).__name__})"
    finally:
        if fd is not None:
            os.close(fd)
    if proc.returncode != 0:
        err = proc.stderr.decode("utf-8", "replace").strip().splitlines()
        why = err[-1][:120] if err else f"exit status {proc.returncode}"
        if rootless():
            return (f"the grader is not root and bubblewrap cannot make a user namespace "
                    f"here ({why}): allow unprivileged user namespaces (sysctl "
                    "user.max_user_namespaces, kernel.unprivileged_userns_clone, or "
                    "Ubuntu's kernel.apparmor_restrict_unprivileged_userns), or run grade "
                    "as root")
        return f"bubblewrap cannot make namespaces here ({why}); a container needs to allow them"
    return ""


# ---------------------------------------------------------------- cgroups
#: the controllers a submission's group limits, in the order they are reported
CONTROLLERS = ("memory", "pids", "cpu")
CPU_PERIOD_US = 100_000


def _mounts(text=None):
    """[(mount point, the hierarchy's folder mounted there, fstype, super options)]."""
    if text is None:
        try:
            with open("/proc/self/mountinfo", encoding="utf-8") as f:
                text = f.read()
        except OSError:
            return []
    out = []
    for line in text.splitlines():
        left, _, right = line.partition(" - ")
        lf, rf = left.split(), right.split()
        if len(lf) >= 5 and len(rf) >= 3 and rf[0] in ("cgroup", "cgroup2"):
            out.append((lf[4].replace("\\040", " "), lf[3], rf[0], rf[2].split(",")))
    return out


def _memberships(text=None):
    """{controller or '' (cgroup v2): this process's cgroup path}, from /proc/self/cgroup."""
    if text is None:
        try:
            with open("/proc/self/cgroup", encoding="utf-8") as f:
                text = f.read()
        except OSError:
            return {}
    out = {}
    for line in text.splitlines():
        try:
            hid, names, path = line.split(":", 2)
        except ValueError:
            continue
        if hid == "0" and names == "":
            out[""] = path
        for name in names.split(","):
            if name:
                out[name] = path
    return out


def _inside(mount, root, own):
    """The folder of ``own`` (a path of /proc/self/cgroup) under a mount of ``root``."""
    if own is None:
        return None
    if root != "/" and (own == root or own.startswith(root + "/")):
        own = own[len(root):]            # a container that mounts only its own subtree
    return Path(mount) / own.lstrip("/")


def _read(path):
    try:
        return Path(path).read_text(encoding="utf-8")
    except OSError:
        return ""


class Hierarchy:
    """Where a grader makes its submissions' groups: for each controller of
    :data:`CONTROLLERS`, cgroup v2 where the v2 hierarchy has it (listed in the
    ``cgroup.controllers`` of the grader's own v2 group), else the cgroup v1
    hierarchy that has it, else none (per-process limits only).

    In v2 a group's children get a controller only when the group enables it in its
    ``cgroup.subtree_control``, and a group that holds processes cannot (the "no
    internal processes" rule).  :meth:`prepare` enables what is missing; where the
    grader's group holds the grader alone (as under ``systemd-run --scope -p
    Delegate=yes``) it first moves the grader into a leaf ``wt-grade-<pid>-grader``;
    :meth:`release` undoes both.  A group shared with other processes is left alone
    (its controllers are then not used).
    """

    def __init__(self, v2=None, v2_controllers=(), v1=None, why=""):
        self.v2, self.v2_controllers = v2, tuple(v2_controllers)
        self.v1 = dict(v1 or {})
        self.why = why                  # why a v2 controller could not be used, if so
        self._leaf, self._enabled = None, []

    @classmethod
    def find(cls, mountinfo=None, cgroup=None):
        """The hierarchies of this process (``mountinfo``, ``cgroup``: the texts of
        /proc/self/mountinfo and /proc/self/cgroup, read if not given)."""
        mounts, own = _mounts(mountinfo), _memberships(cgroup)
        v2, v2c = None, []
        for mount, root, fstype, _ in mounts:
            if fstype == "cgroup2" and v2 is None:
                base = _inside(mount, root, own.get(""))
                if base is not None and base.is_dir():
                    v2 = base
                    have = _read(base / "cgroup.controllers").split()
                    v2c = [c for c in CONTROLLERS if c in have]
        v1 = {}
        for mount, root, fstype, opts in mounts:
            if fstype != "cgroup":
                continue
            for c in CONTROLLERS:
                if c in opts and c not in v2c and c not in v1:
                    base = _inside(mount, root, own.get(c))
                    if base is not None and base.is_dir():
                        v1[c] = base
        return cls(v2 if v2c else None, v2c, v1)

    def prepare(self, pid=None):
        """Enable the v2 controllers in the grader's group (see the class), and keep only
        the hierarchies this grader can make groups in (a v1 hierarchy is root's)."""
        pid = os.getpid() if pid is None else pid
        for c, base in list(self.v1.items()):
            probe = base / f"wt-grade-{pid}-probe"
            try:
                probe.mkdir()
            except OSError:
                del self.v1[c]
                continue
            _rmdir(probe)
        if self.v2 is None:
            return self
        control = self.v2 / "cgroup.subtree_control"
        missing = [c for c in self.v2_controllers if c not in _read(control).split()]
        if missing and not self._enable(control, missing):
            procs = set(_read(self.v2 / "cgroup.procs").split())
            if procs <= {str(pid)}:               # the grader alone: into a leaf of its own
                leaf = self.v2 / f"wt-grade-{pid}-grader"
                try:
                    leaf.mkdir()
                    self._write(leaf / "cgroup.procs", str(pid))
                    self._leaf = leaf
                except OSError:
                    _rmdir(leaf)
                self._enable(control, missing)
        have = _read(control).split()
        probe = self.v2 / f"wt-grade-{pid}-probe"
        try:
            probe.mkdir()
            _rmdir(probe)
        except OSError:
            have = []                           # no group can be made there (not ours)
        lost = [c for c in self.v2_controllers if c not in have]
        if lost:
            self.why = (f"cgroup v2: {', '.join(lost)} cannot be enabled for the grader's "
                        f"children in {self.v2} (the group holds other processes: run grade "
                        "alone in a delegated group, e.g. systemd-run --scope -p Delegate=yes)")
            self.v2_controllers = tuple(c for c in self.v2_controllers if c in have)
            if not self.v2_controllers:
                self.v2 = None
        return self

    @staticmethod
    def _write(path, text):
        """Write a control file (one place, so a test can play the kernel's part)."""
        Path(path).write_text(text)

    def _enable(self, control, controllers):
        try:
            self._write(control, " ".join("+" + c for c in controllers))
        except OSError:
            return False
        self._enabled += [c for c in controllers if c not in self._enabled]
        return True

    def release(self, pid=None):
        """Give back what :meth:`prepare` changed (after every group is closed)."""
        if self.v2 is None or (not self._enabled and self._leaf is None):
            return
        pid = os.getpid() if pid is None else pid
        if self._enabled:
            try:
                self._write(self.v2 / "cgroup.subtree_control",
                            " ".join("-" + c for c in self._enabled))
                self._enabled = []
            except OSError:
                pass
        if self._leaf is not None:
            try:
                self._write(self.v2 / "cgroup.procs", str(pid))
            except OSError:
                return                  # still enabled (a group left?): keep the leaf
            if _rmdir(self._leaf):
                self._leaf = None

    def mechanism(self, controller):
        """'cgroup v2', 'cgroup v1' or '' (none) for a controller."""
        if controller in self.v2_controllers:
            return "cgroup v2"
        return "cgroup v1" if controller in self.v1 else ""

    def group(self, name, limits):
        """A submission's groups, with its limits written (:class:`Cgroups`)."""
        group = Cgroups()
        if self.v2 is not None:
            d = self.v2 / name
            try:
                d.mkdir()
                ok = []
                for c in self.v2_controllers:
                    try:
                        _V2_WRITE[c](d, limits)
                        ok.append(c)
                    except OSError:
                        pass
                group.v2, group.v2_controllers = d, tuple(ok)
            except OSError:
                pass
        for c, base in self.v1.items():
            d = base / name
            try:
                d.mkdir()
            except OSError:
                continue
            try:
                _V1_WRITE[c](d, limits)
            except OSError:
                _rmdir(d)
                continue
            group.dirs[c] = d
        return group


def _v1_memory(d, limits):
    (d / "memory.limit_in_bytes").write_text(str(limits.memory_bytes))
    swap = d / "memory.memsw.limit_in_bytes"
    if swap.exists():
        swap.write_text(str(limits.memory_bytes))


def _v1_cpu(d, limits):
    (d / "cpu.cfs_period_us").write_text(str(CPU_PERIOD_US))
    (d / "cpu.cfs_quota_us").write_text(str(limits.cpu_quota_us(CPU_PERIOD_US)))


def _v2_memory(d, limits):
    (d / "memory.max").write_text(str(limits.memory_bytes))
    for name, value in (("memory.swap.max", "0"), ("memory.oom.group", "1")):
        try:                          # (no swap accounting, an older kernel: not there)
            (d / name).write_text(value)
        except OSError:
            pass


_V1_WRITE = {"memory": _v1_memory,
             "pids": lambda d, limits: (d / "pids.max").write_text(str(limits.pids)),
             "cpu": _v1_cpu}
_V2_WRITE = {"memory": _v2_memory,
             "pids": lambda d, limits: (d / "pids.max").write_text(str(limits.pids)),
             "cpu": lambda d, limits: (d / "cpu.max").write_text(
                 f"{limits.cpu_quota_us(CPU_PERIOD_US)} {CPU_PERIOD_US}")}


_HIERARCHY = []
_HIERARCHY_LOCK = threading.Lock()


def hierarchy():
    """This process's :class:`Hierarchy`, found and prepared once (until :func:`release`)."""
    with _HIERARCHY_LOCK:
        if not _HIERARCHY:
            _HIERARCHY.append(Hierarchy.find().prepare())
        return _HIERARCHY[0]


def release():
    """Undo what :func:`hierarchy` prepared (the grader back in its own v2 group)."""
    with _HIERARCHY_LOCK:
        if _HIERARCHY:
            _HIERARCHY.pop().release()


@dataclass
class Cgroups:
    """One submission's groups: a cgroup v2 group and/or cgroup v1 groups (one per
    controller), or none where they cannot be made.

    ``procs`` are the ``cgroup.procs`` files the sandbox's first process joins
    before it starts bubblewrap; :meth:`close` kills anything left and removes
    the groups.
    """

    dirs: dict = field(default_factory=dict)        # cgroup v1: {controller: folder}
    v2: Path | None = None
    v2_controllers: tuple = ()

    @classmethod
    def make(cls, name, limits, where=None):
        return (where or hierarchy()).group(name, limits)

    @property
    def procs(self):
        out = [str(self.v2 / "cgroup.procs")] if self.v2 is not None else []
        return out + [str(d / "cgroup.procs") for d in self.dirs.values()]

    @property
    def enforced(self):
        return sorted(set(self.dirs) | set(self.v2_controllers))

    def hit(self):
        """Which limits were reached: a subset of {'memory', 'pids'}."""
        out = set()
        if self.v2 is not None:
            events = _events(self.v2 / "memory.events")
            if "memory" in self.v2_controllers and (events.get("oom_kill", 0) or
                                                    events.get("oom", 0)):
                out.add("memory")
            if "pids" in self.v2_controllers and _events(self.v2 / "pids.events").get("max", 0):
                out.add("pids")
        try:
            if "memory" in self.dirs:
                d = self.dirs["memory"]
                oom = _events(d / "memory.oom_control")
                if int((d / "memory.failcnt").read_text()) > 0 or oom.get("oom_kill", 0):
                    out.add("memory")
        except (OSError, ValueError):
            pass
        if "pids" in self.dirs and _events(self.dirs["pids"] / "pids.events").get("max", 0):
            out.add("pids")
        return out

    def close(self):
        import signal
        import time
        folders = ([self.v2] if self.v2 is not None else []) + list(self.dirs.values())
        if self.v2 is not None and (self.v2 / "cgroup.kill").exists():
            try:
                (self.v2 / "cgroup.kill").write_text("1")
            except OSError:
                pass
        for d in folders:
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


def _events(path):
    """{key: int} of a flat keyed file (memory.events, pids.events, memory.oom_control)."""
    out = {}
    for line in _read(path).splitlines():
        words = line.split()
        if len(words) == 2:
            try:
                out[words[0]] = int(words[1])
            except ValueError:
                pass
    return out


def cgroup_limits():
    """Which limits cgroups enforce over all of a submission's processes here: a subset of
    ['cpu', 'memory', 'pids'] (empty: per-process limits only).

    Where the hierarchy was prepared only to answer this (no grading run holds it), it
    is given back: on a v2 machine the caller returns from its leaf to its own group,
    and the leaf and the enabled controllers go (found on a real v2-only kernel by
    ``scripts/cgroup2_vm.py``: the leaf was left behind)."""
    with _HIERARCHY_LOCK:
        prepared = bool(_HIERARCHY)        # by a caller (grade) that releases it itself
    group = Cgroups.make(f"wt-grade-probe-{os.getpid()}", Limits())
    try:
        return group.enforced
    finally:
        group.close()
        if not prepared:
            release()


def _rmdir(d):
    try:
        d.rmdir()
    except FileNotFoundError:
        return True
    except OSError:
        return False
    return True


# ---------------------------------------------------------------- keyrings
#: the system calls of the kernel's key management, denied in the sandbox (EPERM)
KEY_SYSCALLS = ("add_key", "request_key", "keyctl")
# {machine: (AUDIT_ARCH_*, {syscall: number}, the x32 bit or 0)}, from the kernel's
# arch/x86/entry/syscalls/syscall_64.tbl and include/uapi/asm-generic/unistd.h
_SECCOMP_ARCH = {
    "x86_64": (0xC000003E, {"add_key": 248, "request_key": 249, "keyctl": 250}, 0x40000000),
    "aarch64": (0xC00000B7, {"add_key": 217, "request_key": 218, "keyctl": 219}, 0),
}


def seccomp_filter(machine=None):
    """The sandbox's seccomp filter (a classic BPF program, as ``bwrap --seccomp`` reads
    it), or None on a machine this does not know: the key management calls
    (:data:`KEY_SYSCALLS`) and every call of another ABI (32-bit, x32) fail with EPERM,
    every other call is allowed.  So no submission can store a key for a later one, nor
    use a keyring its processes inherit (a session keyring).

    >>> len(seccomp_filter("x86_64")) % 8, seccomp_filter("sparc") is None
    (0, True)
    """
    import platform
    import struct
    spec = _SECCOMP_ARCH.get(machine or platform.machine())
    if spec is None:
        return None
    arch, numbers, x32 = spec
    LD_W_ABS, JEQ, JGE, RET = 0x20, 0x15, 0x35, 0x06
    ALLOW, DENY = 0x7FFF0000, 0x00050000 | 1            # SECCOMP_RET_ERRNO | EPERM
    prog = [(LD_W_ABS, 4), (JEQ, arch, "next", "deny"), (LD_W_ABS, 0)]
    if x32:
        prog.append((JGE, x32, "deny", "next"))
    prog += [(JEQ, numbers[n], "deny", "next") for n in KEY_SYSCALLS]
    prog += [(RET, ALLOW), (RET, DENY)]
    deny = len(prog) - 1
    out = b""
    for i, ins in enumerate(prog):
        code, k = ins[0], ins[1]
        jt = jf = 0
        if len(ins) == 4:
            jt, jf = ((deny - i - 1) if x == "deny" else 0 for x in ins[2:])
        out += struct.pack("=HBBI", code, jt, jf, k)
    return out


def seccomp_fd():
    """A file descriptor holding :func:`seccomp_filter` (for ``bwrap --seccomp``), or None."""
    prog = seccomp_filter()
    if prog is None:
        return None
    fd = os.memfd_create("wt-grade-seccomp", 0) if hasattr(os, "memfd_create") else None
    if fd is None:
        return None
    os.write(fd, prog)
    os.lseek(fd, 0, os.SEEK_SET)
    return fd


# ---------------------------------------------------------------- what is enforced
def enforced(limits, timeout, where=None):
    """[(limit, how it is enforced here)]: what ``grade`` prints before it starts."""
    where = where or hierarchy()
    root = not rootless()

    def by(controller, v2_file, v1_file):
        how = where.mechanism(controller)
        return f"{how} {v2_file if how == 'cgroup v2' else v1_file}" if how else ""
    mem = by("memory", "memory.max", "memory.limit_in_bytes")
    pids = by("pids", "pids.max", "pids.max")
    cpu = by("cpu", "cpu.max", "cpu.cfs_quota_us")
    out = [
        ("memory", f"{limits.memory_mb} MB over all its processes ({mem})" if mem else
         f"{limits.memory_mb} MB per process only (RLIMIT_AS; no memory cgroup here)"),
        ("processes", f"{limits.pids} processes and threads ({pids})" if pids else
         (f"{limits.pids} processes (RLIMIT_NPROC of its " + ("uid" if root else
                                                            "user namespace") +
          "; no pids cgroup here)" if nproc_counts_sandbox_alone() else
          "NOT limited (no pids cgroup delegated to this user, and RLIMIT_NPROC would "
          "count all your processes on this kernel)")),
        ("CPU", f"{limits.cpus:g} CPU over all its processes ({cpu}); at most {timeout:g} s "
         "of CPU per process (RLIMIT_CPU)" if cpu else
         f"NOT shared out: no cpu cgroup here; {timeout:g} s of CPU per process "
         "(RLIMIT_CPU)"),
        ("disk", f"{limits.disk_mb} MB (the size of its scratch tmpfs; RLIMIT_FSIZE)"),
        ("network", "none (its own network namespace: loopback only)"),
        ("keyrings", "add_key, request_key and keyctl denied (seccomp filter)"
         if seccomp_filter() is not None else "NOT denied (no seccomp filter for this "
         "machine's architecture)"),
        ("user", f"a uid of its own ({UID_BASE} to {UID_BASE + UID_COUNT - 1}, leased)"
         if root else "rootless: the grader's own uid, in a user namespace of its own"),
    ]
    if where.why:
        out.append(("note", where.why))
    return out


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
        # private (0700): the sandboxes see the copies only through bind mounts
        self.top = Path(tempfile.mkdtemp(prefix="wt-grade-package-"))
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
def environment(uid, run="", cpu_seconds=0, nproc=False):
    """The sandbox's whole environment (``bwrap --clearenv`` then these).

    ``run``: the grader run's mark (its pid), so a test can tell this run's processes
    from another's; ``cpu_seconds``: the CPU time each process may use (RLIMIT_CPU,
    set by the worker; 0: none); ``nproc``: the worker sets RLIMIT_NPROC (only where it
    counts the sandbox's processes alone: see :func:`nproc_counts_sandbox_alone`).
    """
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
            "WHITTAKER_TEACH_SANDBOX": str(uid), "WHITTAKER_TEACH_RUN": str(run),
            "WHITTAKER_TEACH_CPU_SECONDS": str(int(cpu_seconds)),
            "WHITTAKER_TEACH_NPROC": "1" if nproc else "0"}


def nproc_counts_sandbox_alone():
    """Does RLIMIT_NPROC in a sandbox count its own processes alone?  As root, yes: the
    sandbox has a uid of its own.  Rootless, the sandbox's uid is the lecturer's; since
    Linux 5.14 the count is kept per user namespace, so in the sandbox's own namespace it
    counts the sandbox's processes only; on older kernels it would count every process
    of the lecturer's, and is not set."""
    if not rootless():
        return True
    try:
        major, minor = (int(x) for x in os.uname().release.split(".")[:2])
    except ValueError:
        return False
    return (major, minor) >= (5, 14)


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


def command(uid, package_root, submission, limits, cell_timeout, log_fd, procs=(),
            seccomp=None, run="", cpu_seconds=0):
    """The argv that runs the worker for one submission in its sandbox.

    ``log_fd``: the write end of the pipe the check log goes to (inherited
    by the worker and its kernel: the grader reads the answers as they are
    recorded, so they survive the run's end, however it ends).
    ``procs``: cgroup.procs files the first process joins (``sh`` writes its
    pid, then becomes bubblewrap); ``seccomp``: a file descriptor holding
    :func:`seccomp_filter` (``bwrap --seccomp``).

    As root the sandbox's processes run as ``uid`` (``setpriv``: no groups, no
    capabilities, ``no_new_privs``); rootless (:func:`rootless`) they run as the
    grader's own uid in a user namespace of their own, seen inside as ``uid``
    (``bwrap --unshare-user --disable-userns``: no capabilities outside it, no
    nested namespaces); RLIMIT_NPROC is set only where it counts the sandbox's
    processes alone (:func:`nproc_counts_sandbox_alone`).
    """
    unprivileged = rootless()
    prefixes = []
    for p in (sys.prefix, sys.base_prefix, str(Path(sys.executable).resolve().parents[1])):
        p = Path(p).resolve()
        if not _under(p, [Path("/usr")] + prefixes) and p not in prefixes:
            prefixes.append(p)
    args = ["bwrap"]
    if unprivileged:
        args += ["--unshare-user", "--disable-userns", "--uid", str(uid), "--gid", str(uid)]
    if seccomp is not None:
        args += ["--seccomp", str(seccomp)]
    args += ["--unshare-pid", "--unshare-ipc", "--unshare-net", "--unshare-uts",
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
    env = environment("rootless" if unprivileged else uid, run, cpu_seconds,
                      nproc_counts_sandbox_alone())
    for k, v in env.items():
        args += ["--setenv", k, v]
    args += ["--"]
    if not unprivileged:
        args += [shutil.which("setpriv") or "/usr/bin/setpriv", f"--reuid={uid}",
                 f"--regid={uid}", "--clear-groups", "--bounding-set=-all", "--inh-caps=-all",
                 "--no-new-privs", "--"]
    args += [sys.executable, "-m", "whittaker_teach.grading.worker",
             "worker", SUBMISSION, SCRATCH, f"{cell_timeout:g}", str(limits.memory_mb),
             str(limits.pids), str(limits.disk_mb), str(log_fd)]
    if procs:
        join = "for f in " + " ".join(f"'{p}'" for p in procs) + \
            "; do echo $$ > \"$f\" || exit 97; done; exec \"$@\""
        args = ["/bin/sh", "-c", join, "sh", *args]
    return args
