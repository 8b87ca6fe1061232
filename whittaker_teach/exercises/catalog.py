"""The exercises that can be checked: one per answer data file (``whittaker_teach/exercises/data/<id>.json``).

No expected answer is written here: each exercise's answers are taken from
its solution by ``make exercises`` and stored as package data
(:mod:`.authoring`, :mod:`.answers`).  :data:`EXERCISES` maps an exercise id
to its :class:`~whittaker_teach.exercises.specs.Exercise`, read on first use.
"""

from __future__ import annotations

from collections.abc import Mapping

__all__ = ["EXERCISES", "load"]

_LOADED = {}


def load(exercise_id):
    """The exercise ``exercise_id`` (KeyError if it has no answer data)."""
    from .answers import answers_path, read_data
    from .authoring import exercise_from_data
    path = answers_path(exercise_id)
    if path is None:
        raise KeyError(exercise_id)
    key = (exercise_id, str(path), path.stat().st_mtime_ns)
    if key not in _LOADED:
        _LOADED[key] = exercise_from_data(read_data(path))
    return _LOADED[key]


class _Exercises(Mapping):
    """{exercise id: Exercise} over the answer data found (see :func:`.answers.answers_dirs`)."""

    def __getitem__(self, exercise_id):
        return load(exercise_id)

    def __iter__(self):
        from .answers import available
        return iter(sorted(available()))

    def __len__(self):
        from .answers import available
        return len(available())

    def __contains__(self, exercise_id):
        from .answers import answers_path
        return answers_path(exercise_id) is not None


EXERCISES = _Exercises()
