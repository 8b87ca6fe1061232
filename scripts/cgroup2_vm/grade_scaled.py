"""``python -m whittaker_teach grade ...`` with the timeouts of an emulated CPU
(wt_vm_timescale.apply: the notebook-reading CPU limit and the kernel startup wait,
x WT_VM_TIME_SCALE).  Nothing else is changed.

usage: python grade_scaled.py grade ARGS...
"""
import os
import runpy
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import wt_vm_timescale  # noqa: E402

wt_vm_timescale.apply()
sys.argv = ["whittaker_teach", *sys.argv[1:]]
runpy.run_module("whittaker_teach", run_name="__main__", alter_sys=True)
