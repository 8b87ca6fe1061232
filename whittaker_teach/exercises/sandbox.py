"""Moved: :mod:`whittaker_teach.grading.sandbox` (its public names, here for old scripts)."""

from whittaker_teach.grading.sandbox import *  # noqa: F401,F403
from whittaker_teach.grading.sandbox import __all__  # noqa: F401
