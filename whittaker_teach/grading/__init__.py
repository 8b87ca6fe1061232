"""Grading a class: the grader's own room, apart from checking an answer and from authoring.

- :mod:`.run`: ``python -m whittaker_teach grade``; runs each notebook in
  its sandbox and checks the recorded answers with
  :func:`whittaker_teach.exercises.check`;
- :mod:`.worker`: what runs inside the sandbox (nbclient and the kernel);
- :mod:`.sandbox`: bubblewrap, a uid of its own, cgroup limits, the copy
  of the package a graded notebook sees;
- :mod:`.roster`: which student handed in which notebook (LMS file names
  checked against the roster);
- :mod:`.exports`: the gradebook CSV, and the grades written into the
  lecturer's own Canvas gradebook and Moodle grading worksheet;
- :mod:`.rows`: the rows of the grades and their CSV cells.

The imports run one way: grading uses :mod:`whittaker_teach.exercises`
(``check``, the catalogue, the recorder); nothing in ``exercises`` imports
the grader (``exercises.grade`` and ``exercises.sandbox`` are only
aliases kept for old scripts).  This ``__init__`` imports nothing, so the
sandbox's worker can run from a copy holding only ``worker.py``.
"""
