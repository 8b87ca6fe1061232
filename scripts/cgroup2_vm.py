"""Test the grader's cgroup v2 path for real: boot a cgroup-v2-only VM and grade in it.

This machine's cgroups are hybrid (v1 controllers, a cgroup2 mount without them), so the
grader's cgroup v2 code (whittaker_teach/grading/sandbox.py, class Hierarchy) is tested
here only against fake trees.  This script boots Debian's kernel in QEMU with virtme-ng,
the host's root file system seen read-only over 9p (the same Python, this repository,
bubblewrap), cgroup2 mounted at /sys/fs/cgroup and no v1 hierarchy (``cgroup_no_v1=all``),
and runs there, as root, in a delegated group of its own (scripts/cgroup2_vm/guest.sh):

- ``env``: proves the VM has cgroup v2 only (mountinfo, /proc/cgroups);
- ``probe``: Hierarchy.prepare/group/release, the limits read back, a real OOM kill,
  forks refused at pids.max, throttling at cpu.max (scripts/cgroup2_vm/probe.py);
- ``class``: ``python -m whittaker_teach grade`` on an honest student, a memory hog, a fork
  bomb and a CPU hog, checked by scripts/cgroup2_vm/check_class.py;
- ``pytest``: tests named by ``--pytest`` (off by default: under emulation a batch of
  notebooks takes long), in a delegated group of their own, with the plugin
  scripts/cgroup2_vm/wt_vm_timescale.py.

Under emulation the grader's timeouts are made for a CPU some 40 times faster, so the
class and pytest steps multiply the time-only limits by ``--time-scale`` (default 20
emulated, 1 with KVM): the CPU for reading a notebook, the kernel's startup wait, and
(pytest) the timeouts tests give ``grade()``; never a memory, process or CPU-share limit.

Exits 0 when every step passed, 1 when one failed, 2 when the VM could not be had.

usage: python scripts/cgroup2_vm.py [--install] [--steps env,probe,class] [--out DIR]
                                    [--pytest 'tests/...::test_x'] [--accel auto|kvm|tcg]

``--install`` installs what is missing: Debian's qemu-system-x86, busybox-static and
linux-image-amd64 (apt-get; the cloud kernel lacks 9p), virtme-ng 1.42 (pip, in a venv
of its own under ~/.cache/wt-cgroup2-vm).  KVM is used where /dev/kvm can run a stock
kernel; under PVM (kvm_pvm, which runs only PVM-enabled guests) the VM is emulated (TCG),
some 40 times slower than the host: on this 2-CPU machine under a load of 7-9, booting and
the env step take about 2 minutes, probe about 4, the class of 4 about 15-20.
"""
import argparse
import glob
import os
import shutil
import subprocess
import sys
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
CACHE = Path(os.environ.get("WT_CGROUP2_VM_CACHE", Path.home() / ".cache" / "wt-cgroup2-vm"))
VENV = CACHE / "venv"
VNG = VENV / "bin" / "vng"
VIRTME_NG = "virtme-ng==1.42"
APT = ["qemu-system-x86", "busybox-static", "linux-image-amd64"]
STEPS = ("env", "probe", "class", "pytest")


def kernel():
    """Debian's generic kernel (it has the 9p modules the cloud kernel lacks), or None."""
    found = sorted(p for p in glob.glob("/boot/vmlinuz-*-amd64") if "cloud" not in p)
    return found[-1] if found else None


def missing():
    out = []
    if shutil.which("qemu-system-x86_64") is None:
        out.append("qemu-system-x86")
    if shutil.which("busybox") is None and not Path("/bin/busybox").exists():
        out.append("busybox-static")
    if kernel() is None:
        out.append("linux-image-amd64")
    return out


def install():
    need = missing()
    if need:
        print(f"cgroup2_vm: apt-get install {' '.join(need)}", flush=True)
        subprocess.run(["apt-get", "install", "-y", "--no-install-recommends", *need],
                       check=True, env={**os.environ, "DEBIAN_FRONTEND": "noninteractive"})
    if not VNG.exists():
        print(f"cgroup2_vm: pip install {VIRTME_NG} into {VENV}", flush=True)
        subprocess.run([sys.executable, "-m", "venv", str(VENV)], check=True)
        subprocess.run([str(VENV / "bin" / "pip"), "install", "-q", VIRTME_NG], check=True)


def accel(choice):
    """'kvm' or 'tcg'.  PVM's /dev/kvm (kvm_pvm) runs only PVM-enabled guest kernels: a
    stock kernel hangs at its first instruction there, so it counts as no KVM."""
    if choice != "auto":
        return choice
    if not os.access("/dev/kvm", os.R_OK | os.W_OK) or Path("/sys/module/kvm_pvm").exists():
        return "tcg"
    return "kvm"


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--install", action="store_true", help="install what is missing")
    ap.add_argument("--steps", default="env,probe,class",
                    help=f"comma-separated, of {', '.join(STEPS)} (default env,probe,class)")
    ap.add_argument("--pytest", default="", help="the tests the pytest step runs "
                    "(node ids or -k ...; default tests/integration/test_grade.py); "
                    "adds the pytest step")
    ap.add_argument("--out", help="where the VM writes its evidence (default: a new folder "
                    f"under {CACHE}/runs)")
    ap.add_argument("--accel", choices=("auto", "kvm", "tcg"), default="auto")
    ap.add_argument("--memory", default="4G")
    ap.add_argument("--cpus", type=int, default=2)
    ap.add_argument("--timeout", type=int, default=1500,
                    help="seconds per notebook and per cell in the class step")
    ap.add_argument("--time-scale", type=float, default=0,
                    help="the pytest step multiplies the timeouts tests give grade() by this "
                    "(default: 1 with KVM, 20 emulated)")
    ap.add_argument("--vm-timeout", type=int, default=7200, help="seconds for the whole VM")
    args = ap.parse_args(argv)
    steps = [s for s in args.steps.split(",") if s]
    if args.pytest and "pytest" not in steps:
        steps.append("pytest")
    bad = [s for s in steps if s not in STEPS]
    if bad:
        ap.error(f"unknown steps {bad}")
    if args.install:
        install()
    need = missing() + ([] if VNG.exists() else [VIRTME_NG])
    if need:
        print(f"cgroup2_vm: missing {', '.join(need)} (run with --install, as root)",
              file=sys.stderr)
        return 2
    if os.geteuid() != 0:
        print("cgroup2_vm: run as root (the VM's root user must be root on the 9p root)",
              file=sys.stderr)
        return 2
    out = Path(args.out or CACHE / "runs" / time.strftime("%Y%m%d-%H%M%S")).resolve()
    if out == Path("/tmp") or Path("/tmp") in out.parents:
        print("cgroup2_vm: --out must be outside /tmp (the VM mounts its own /tmp over "
              "it, so nothing written there would come back)", file=sys.stderr)
        return 2
    out.mkdir(parents=True, exist_ok=True)
    for old in out.glob("*.rc"):
        old.unlink()
    py = Path(sys.executable).resolve()
    prefix = Path(sys.prefix).resolve()
    how = accel(args.accel)
    scale = args.time_scale or (1 if how == "kvm" else 20)
    env = f"WT_VM_TIMEOUT={args.timeout} WT_VM_TIME_SCALE={scale:g}"
    if args.pytest:
        env += " WT_VM_PYTEST='" + args.pytest.replace("'", "'\\''") + "'"
    guest = REPO / "scripts" / "cgroup2_vm" / "guest.sh"
    cmd = [str(VNG), "--run", kernel(), "--memory", args.memory, "--cpus", str(args.cpus),
           "--append", "cgroup_no_v1=all", "--rwdir", str(out),
           # the Python prefix and the repository again, to be mounted with a page cache
           f"--qemu-opts=-fsdev local,id=wtpy,path={prefix},security_model=none,"
           "readonly=on,multidevs=remap -device virtio-9p-pci,fsdev=wtpy,mount_tag=wtpy "
           f"-fsdev local,id=wtrepo,path={REPO},security_model=none,readonly=on,"
           "multidevs=remap -device virtio-9p-pci,fsdev=wtrepo,mount_tag=wtrepo",
           "--exec", f"env {env} sh {guest} {out} {py} {REPO} {' '.join(steps)}"]
    if how == "tcg":
        cmd.insert(1, "--disable-kvm")
    print(f"cgroup2_vm: {kernel()}, {how.upper()}, steps {' '.join(steps)}; evidence in {out}",
          flush=True)
    start = time.monotonic()
    with open(out / "vm.log", "wb") as log:
        try:
            vm = subprocess.run(cmd, stdout=log, stderr=subprocess.STDOUT,
                                stdin=subprocess.DEVNULL, timeout=args.vm_timeout, cwd="/tmp",
                                env={**os.environ, "PATH": f"{VENV / 'bin'}:{os.environ['PATH']}"})
            code = vm.returncode
        except subprocess.TimeoutExpired:
            code = "timeout"
    took = time.monotonic() - start
    results = {s: (out / f"{s}.rc").read_text().strip() if (out / f"{s}.rc").exists()
               else "not run" for s in steps}
    print(f"cgroup2_vm: the VM ran {took:.0f} s (exit {code}); " +
          ", ".join(f"{s}: {'passed' if r == '0' else 'FAILED' if r.isdigit() else r}"
                    for s, r in results.items()))
    for s in steps:
        for name in (f"{s}.txt", f"{s}-check.txt"):
            if (out / name).exists() and results[s] != "0":
                print(f"---- {name} (tail)\n" + "\n".join(
                    (out / name).read_text(errors="replace").splitlines()[-40:]))
    if all(r == "not run" for r in results.values()):
        print((out / "vm.log").read_text(errors="replace")[-3000:])
        return 2
    return 0 if all(r == "0" for r in results.values()) else 1


if __name__ == "__main__":
    sys.exit(main())
