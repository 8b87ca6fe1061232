"""The grader opens a submission without following a symbolic link at any level of its
path, refuses what lies outside the submissions folder, and gives a file name of any
bytes a row of its own (issue 37, item 5: a directory symlink in a submission path was
followed as root into the solutions; a non-UTF-8 file name stopped the class)."""
import json
import os

import pytest

from whittaker_teach.grading import roster, run

NB = {"nbformat": 4, "nbformat_minor": 5, "metadata": {"whittaker_teach": {
    "exercise": "kepler-orbit"}}, "cells": []}


@pytest.fixture
def tree(tmp_path):
    """subs/ (the submissions), answers/ (what no student may reach)."""
    subs, answers = tmp_path / "subs", tmp_path / "answers"
    subs.mkdir()
    answers.mkdir()
    (answers / "kepler-orbit.ipynb").write_text(json.dumps(NB), encoding="utf-8")
    (subs / "honest.ipynb").write_text(json.dumps(NB), encoding="utf-8")
    return tmp_path


def test_an_ordinary_submission_is_read(tree):
    nb, why = run.read_submission(tree / "subs" / "honest.ipynb", tree / "subs")
    assert why is None and nb.claimed == "kepler-orbit"


def test_a_link_as_the_file_is_refused(tree):
    (tree / "subs" / "link.ipynb").symlink_to(tree / "answers" / "kepler-orbit.ipynb")
    nb, why = run.read_submission(tree / "subs" / "link.ipynb", tree / "subs")
    assert nb is None and why.startswith("a symbolic link")


@pytest.mark.parametrize("relative", [False, True])
def test_a_folder_link_anywhere_in_the_path_is_refused(tree, monkeypatch, relative):
    """subs/alice -> answers: subs/alice/kepler-orbit.ipynb (what `grade subs/*/*.ipynb`
    gives) and a deeper subs/alice/../.. are never opened through the link."""
    (tree / "subs" / "alice").symlink_to(tree / "answers")
    (tree / "answers" / "deeper").mkdir()
    (tree / "answers" / "deeper" / "x.ipynb").write_text(json.dumps(NB), encoding="utf-8")
    if relative:
        monkeypatch.chdir(tree)
        base = "subs"
    else:
        base = str(tree / "subs")
    for path in (f"{base}/alice/kepler-orbit.ipynb", f"{base}/alice/deeper/x.ipynb"):
        nb, why = run.read_submission(path, base)
        assert nb is None and "goes through a symbolic link" in why and "alice" in why, why
        name, exercise, raw, rows = run.prepare(path, "x", None, base)
        assert raw is None and len(rows) == 1 and "symbolic link" in rows[0].message


def test_what_lies_outside_the_submissions_folder_is_refused(tree):
    nb, why = run.read_submission(tree / "answers" / "kepler-orbit.ipynb", tree / "subs")
    assert nb is None and why == "it lies outside the submissions folder"


def test_a_hard_link_is_refused(tree):
    os.link(tree / "answers" / "kepler-orbit.ipynb", tree / "subs" / "hard.ipynb")
    nb, why = run.read_submission(tree / "subs" / "hard.ipynb", tree / "subs")
    assert nb is None and why.startswith("a hard link")


def test_not_found_and_not_a_file(tree):
    assert run.read_submission(tree / "subs" / "missing.ipynb")[1] == "not found"
    os.mkfifo(tree / "subs" / "fifo.ipynb")
    assert run.read_submission(tree / "subs" / "fifo.ipynb")[1] == "not a file"


def test_file_names_of_any_bytes_get_a_row(tree):
    """A zip extracted with another encoding: names that are not UTF-8 are found, read,
    and named in the rows with their bytes shown as \\xNN."""
    subs = os.fsencode(tree / "subs")
    with open(subs + b"/caf\xe9.ipynb", "w", encoding="utf-8") as f:
        json.dump(NB, f)
    with open(subs + b"/\xff\xfe.ipynb", "w", encoding="utf-8") as f:
        f.write("not a notebook")
    notebooks, skipped = roster.assign([str(tree / "subs")], None)
    byname = {m.name: m for m in notebooks}
    assert {"caf\\xe9.ipynb", "\\xff\\xfe.ipynb", "honest.ipynb"} == set(byname)
    nb, why = run.read_submission(byname["caf\\xe9.ipynb"].path, byname["caf\\xe9.ipynb"].folder)
    assert why is None and nb.claimed == "kepler-orbit"
    m = byname["\\xff\\xfe.ipynb"]
    name, exercise, raw, rows = run.prepare(m.path, m.name, None, m.folder)
    assert rows[0].submission == "\\xff\\xfe.ipynb" and "not a notebook" in rows[0].message
    rows[0].csv()                                # writable as UTF-8


def test_the_folder_of_a_match_is_the_submissions_folder(tree):
    folder = tree / "subs" / "Jane Doe_123456_assignsubmission_file"
    folder.mkdir()
    (folder / "k.ipynb").write_text(json.dumps(NB), encoding="utf-8")
    found = {m.name: m for m in roster.assign([str(tree / "subs")], None)[0]}
    assert found["Jane Doe_123456_assignsubmission_file/k.ipynb"].folder == str(tree / "subs")
    given = roster.assign([str(folder / "k.ipynb")], None)[0][0]
    assert given.folder == str(tree / "subs")     # the Moodle folder is kept in its parts
