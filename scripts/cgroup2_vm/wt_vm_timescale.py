"""Timeouts for the emulated VM (scripts/cgroup2_vm.py), multiplied by WT_VM_TIME_SCALE.

Under emulation (TCG, no usable KVM) the VM's CPU is some 40 times slower than the
host's: reading a notebook (importing nbformat) takes longer than the grader's 20 s of
CPU for it, and a kernel takes longer than a minute to start.  The limits under test
(memory, processes, CPU share) do not depend on time, so only these are scaled:

- ``run.VALIDATE_SECONDS`` (the CPU the grader gives reading one notebook);
- the worker's ``startup_timeout=60`` (nbclient's wait for the kernel), in the copy of
  the package bound into each sandbox (:class:`sandbox.PackageCopy`), not in the source;
- as a pytest plugin (``-p wt_vm_timescale``), the ``cell_timeout`` and ``timeout`` that
  tests pass to ``whittaker_teach.grading.run.grade``.

The scale is printed (stderr, and in pytest's report header).
"""
import compileall
import functools
import os
import sys

SCALE = float(os.environ.get("WT_VM_TIME_SCALE", "1"))


def apply():
    """Scale the grader's reading limit and the sandboxed worker's kernel startup wait."""
    if SCALE == 1:
        return
    from whittaker_teach.grading import run, sandbox
    run.VALIDATE_SECONDS = int(run.VALIDATE_SECONDS * SCALE)
    made = sandbox.PackageCopy._path

    @functools.wraps(made)
    def path(self, solvers):
        fresh = solvers not in self._made
        root = made(self, solvers)
        if fresh:
            worker = root / "whittaker_teach" / "grading" / "worker.py"
            text = worker.read_text(encoding="utf-8")
            if "startup_timeout=60" not in text:
                raise RuntimeError("wt_vm_timescale: worker.py has no startup_timeout=60")
            worker.write_text(text.replace("startup_timeout=60",
                                           f"startup_timeout={60 * SCALE:g}"), encoding="utf-8")
            os.chmod(worker, 0o644)
            compileall.compile_file(str(worker), quiet=2, force=True)
        return root
    sandbox.PackageCopy._path = path
    print(f"wt_vm_timescale: VALIDATE_SECONDS {run.VALIDATE_SECONDS}, kernel startup "
          f"timeout {60 * SCALE:g} s (x {SCALE:g}, emulated CPU)", file=sys.stderr)


def pytest_report_header(config):
    return (f"wt_vm_timescale: grade()'s cell_timeout and timeout, VALIDATE_SECONDS and the "
            f"kernel startup timeout x {SCALE:g} (emulated CPU)")


def pytest_configure(config):
    if SCALE == 1:
        return
    apply()
    from whittaker_teach.grading import run
    grade = run.grade

    @functools.wraps(grade)
    def scaled(*args, **kwargs):
        for k in ("cell_timeout", "timeout"):
            if kwargs.get(k):
                kwargs[k] = kwargs[k] * SCALE
        return grade(*args, **kwargs)
    run.grade = scaled
