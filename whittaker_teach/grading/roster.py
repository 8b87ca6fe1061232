"""Which student handed in which notebook: LMS file names, read strictly, checked against a roster.

A notebook is graded under a student only when exactly one roster entry
fits it by one of these rules (the report names the rule used):

- **Moodle folder** ("Download submissions in folders", Moodle >= 3.1):
  the notebook lies under a folder ``<Full name>_<participant>_assignsubmission_file``;
  the folder alone says who (the file names inside are the student's own and
  are never read for identity);
- **folder = roster id**: under a folder named exactly as a roster id;
- **Moodle file name** (the same download, not in folders):
  ``<Full name>_<participant>_assignsubmission_file_<file>``;
- **Canvas file name** ("Download Submissions"):
  ``<name>_<user id>_<file id>_<file>`` or ``<name>_LATE_<user id>_<file id>_<file>``;
- **file = roster id**: a file named exactly ``<roster id>.ipynb``.

Moodle writes ``<Full name>`` with every ``_`` made a space
(``mod/assign/classes/local/downloader.php``: ``str_replace('_', ' ',
$fullname)`` then ``clean_filename``); Canvas writes the sortable name
("Smith, John") lower-cased, without anything but letters, digits and ``_``
(``lib/content_zipper.rb``: ``get_filename``, ``sanitize_user_name``).
Every way of reading a file name is tried, and a reading counts only when
its number is a roster id **and** its name part is that student's name
(letters and digits compared, in any order of the name's words; Moodle's
blind marking, ``Participant_<n>``, has no name to compare).  So a student
whose name contains a classmate's number (``eve_111111_222222_...``) is
never read as that classmate: the reading with ``111111`` has the name
part ``eve``, not the classmate's name.

A notebook that fits no entry is **unknown**, one that fits two is
**ambiguous**, and two notebooks that fit one student are **duplicates**:
all are listed in the report and none is graded under anyone.  A file name
that is not UTF-8 (a zip extracted with another encoding) is compared as
UTF-8, CP437 (zip's own) and Windows-1252; it never stops the class.

A roster is a CSV: Canvas's gradebook export (``Student``, ``ID``, ...),
Moodle's grading worksheet (``Identifier`` = ``Participant <n>``,
``Full name``, ...), or any CSV with ``id`` and ``name`` columns.

>>> r = Roster.from_rows([("111111", "Vic Tim"), ("222222", "Eve 111111")])
>>> identify(("eve_111111_222222_9_work.ipynb",), r).student.id
'222222'
>>> identify(("Vic Tim_111111_assignsubmission_file_a.ipynb",), r).rule
'Moodle file name'
"""

from __future__ import annotations

import csv
import itertools
import os
import re
import stat
import unicodedata
from dataclasses import dataclass, field
from pathlib import Path

__all__ = ["Student", "Roster", "RosterError", "Match", "identify", "collect", "assign",
           "shown", "NOTEBOOK_SUFFIX"]

NOTEBOOK_SUFFIX = ".ipynb"
MAX_DEPTH = 6            # folders below a submissions folder that are searched
MAX_FILES = 100_000      # entries looked at, over a whole run

_MOODLE_FOLDER = re.compile(r"^(?P<name>.*?)_(?P<id>\d+)_assignsubmission_file$", re.S)
_MOODLE_FILE = re.compile(r"_(?P<id>\d+)_assignsubmission_file_", re.S)


class RosterError(ValueError):
    """The roster cannot be read; the message says why."""


@dataclass(frozen=True)
class Student:
    """A roster entry: ``id`` is the number the LMS puts in file names."""

    id: str
    name: str


@dataclass
class Roster:
    students: dict = field(default_factory=dict)      # {id: Student}
    kind: str = "plain"                               # "canvas", "moodle" or "plain"
    source: str = ""

    @classmethod
    def from_rows(cls, pairs, kind="plain", source=""):
        r = cls(kind=kind, source=source)
        for sid, name in pairs:
            sid = str(sid).strip()
            if not sid:
                continue
            if sid in r.students:
                raise RosterError(f"the roster {source or ''} has the id {sid} twice".replace(
                    "  ", " "))
            r.students[sid] = Student(sid, str(name).strip())
        return r

    @classmethod
    def read(cls, path):
        """A roster from a CSV: Canvas's gradebook export, Moodle's grading worksheet, or
        any CSV with ``id`` and ``name`` columns."""
        try:
            with open(path, newline="", encoding="utf-8-sig") as f:
                table = list(csv.reader(f))
        except (OSError, UnicodeDecodeError) as exc:
            raise RosterError(f"cannot read the roster {path}: {type(exc).__name__}") from exc
        if not table:
            raise RosterError(f"the roster {path} is empty")
        head = [h.strip() for h in table[0]]
        low = [h.lower() for h in head]
        if len(head) >= 2 and head[0].startswith("Student") and head[1] == "ID":
            pairs = [(row[1], row[0]) for row in table[1:] if len(row) > 1
                     and row[1].strip().isdigit()]           # not the Points Possible row
            return cls.from_rows(pairs, "canvas", str(path))
        if "identifier" in low and "full name" in low:
            i, n = low.index("identifier"), low.index("full name")
            pairs = []
            for row in table[1:]:
                if len(row) > max(i, n):
                    m = re.search(r"(\d+)\s*$", row[i])
                    if m:
                        pairs.append((m.group(1), row[n]))
            return cls.from_rows(pairs, "moodle", str(path))
        ids, names = ("id", "student id", "student_id"), ("name", "full name",
                                                          "student name", "student")
        i = next((low.index(k) for k in ids if k in low), None)
        n = next((low.index(k) for k in names if k in low), None)
        if i is not None and n is not None:
            pairs = [(row[i], row[n]) for row in table[1:] if len(row) > max(i, n)]
            return cls.from_rows(pairs, "plain", str(path))
        raise RosterError(f"{path} is not a roster: expected Canvas's gradebook export "
                          "(Student, ID, ...), Moodle's grading worksheet (Identifier, Full "
                          "name, ...) or a CSV with id and name columns")


@dataclass
class Match:
    """What the roster says about one file of the submissions."""

    path: str                 # as found (may hold undecodable bytes as surrogates)
    parts: tuple              # the path's components below the submissions folder
    status: str               # matched, unknown, ambiguous, duplicate, ignored, not-found
    student: Student | None = None
    rule: str = ""
    reason: str = ""

    @property
    def folder(self):
        """The submissions folder it was found in (``path`` without its ``parts``)."""
        p = self.path.rstrip("/") if self.parts else self.path
        for _ in self.parts:
            p = os.path.dirname(p)
        return p or "."

    @property
    def name(self):
        """The path as shown in the grades and the report (always valid UTF-8)."""
        return shown("/".join(self.parts)) if self.parts else shown(self.path)


def shown(text):
    """A file name as text that can be written anywhere: bytes that are not UTF-8 as \\xNN."""
    try:
        text.encode("utf-8")
        return text
    except UnicodeEncodeError:
        return os.fsencode(text).decode("utf-8", "backslashreplace")


# ---------------------------------------------------------------- names
def _spellings(text):
    """The ways a file name's bytes may have been meant (UTF-8, zip's CP437, Windows-1252)."""
    try:
        text.encode("utf-8")
        return [text]
    except UnicodeEncodeError:
        raw = os.fsencode(text)
    out = []
    for enc in ("utf-8", "cp437", "cp1252", "latin-1"):
        try:
            out.append(raw.decode(enc))
        except UnicodeDecodeError:
            pass
    return out


def _words(text):
    text = unicodedata.normalize("NFKC", text).casefold()
    return ["".join(c for c in w if c.isalnum()) for w in re.split(r"[\W_]+", text) if w]


def _glued(words):
    return "".join(w for w in words if w)


def names_agree(in_file, on_roster):
    """Is ``in_file`` (a file name's name part) the roster's name, up to case, accents kept,
    punctuation and spaces dropped, and the order of the name's words?"""
    roster_words = [w for w in _words(on_roster) if w]
    if not roster_words:
        return False
    orders = (itertools.permutations(roster_words) if len(roster_words) <= 6
              else (roster_words, roster_words[::-1]))
    wanted = {_glued(o) for o in orders}
    return any(_glued(_words(s)) in wanted for s in _spellings(in_file))


# ---------------------------------------------------------------- readings of a name
def _canvas_readings(filename):
    """(name part, user id, rest) for every way a Canvas file name can be cut."""
    tokens = filename.split("_")
    out = []
    for k in range(1, len(tokens) - 2):
        uid, fid = tokens[k], tokens[k + 1]
        if not (uid.isascii() and uid.isdigit() and fid.isascii() and fid.isdigit()):
            continue
        head = tokens[:k]
        if head and head[-1] == "LATE":
            head = head[:-1]
        if head and head[-1] == "anon":
            continue
        if head:
            out.append(("_".join(head), uid, "_".join(tokens[k + 2:])))
    return out


def _moodle_readings(filename):
    """(name part, participant, rest) for every way a Moodle file name can be cut."""
    out = []
    for m in _MOODLE_FILE.finditer(filename):
        name = filename[:m.start()]
        if name and "_" not in name:        # Moodle writes every _ of a name as a space
            out.append((name, m.group("id"), filename[m.end():]))
    return out


def _blind(name):
    return name.strip().casefold() == "participant"


def identify(parts, roster):
    """The :class:`Match` of a file at ``parts`` (its path below the submissions folder)."""
    parts = tuple(parts)
    path = "/".join(parts)
    folders, filename = parts[:-1], parts[-1]
    # a folder decides, where one does: the names inside it are the student's own
    for folder in folders:
        m = _MOODLE_FOLDER.match(folder)
        if m:
            return _decide(path, parts, roster, [("Moodle folder", m.group("name"),
                                                  m.group("id"), True)], folder)
        if folder in roster.students:
            return _decide(path, parts, roster, [("folder = roster id", None, folder, False)],
                           folder)
    readings = [("Moodle file name", n, i, True) for n, i, _ in _moodle_readings(filename)]
    readings += [("Canvas file name", n, i, False) for n, i, _ in _canvas_readings(filename)]
    stem = filename[:-len(NOTEBOOK_SUFFIX)] if filename.lower().endswith(NOTEBOOK_SUFFIX) \
        else filename
    if stem in roster.students:
        readings.append(("file = roster id", None, stem, False))
    if re.match(r"^(LATE_)?anon_", filename):
        return Match(path, parts, "unknown", reason="Canvas anonymous grading: the file name "
                     "names no student (grade it by hand, or turn anonymity off)")
    return _decide(path, parts, roster, readings, filename)


def _decide(path, parts, roster, readings, what):
    fits, tried = {}, []
    for rule, name, sid, moodle in readings:
        student = roster.students.get(sid)
        if student is None:
            tried.append(f"{rule}: no roster entry {sid}")
        elif name is None or names_agree(name, student.name) or (moodle and _blind(name)):
            fits.setdefault(student.id, (student, rule))
        else:
            tried.append(f"{rule}: {sid} is {student.name!r} on the roster, not "
                         f"{shown(name)!r}")
    if len(fits) == 1:
        student, rule = next(iter(fits.values()))
        return Match(path, parts, "matched", student, rule)
    if len(fits) > 1:
        who = ", ".join(f"{s.id} ({s.name}, {rule})" for s, rule in fits.values())
        return Match(path, parts, "ambiguous", reason=f"fits several roster entries: {who}")
    if not readings:
        why = ("not a Canvas or Moodle download name, and no roster id is its name "
               f"({shown(what)!r})")
    else:
        why = "; ".join(tried[:4])
    return Match(path, parts, "unknown", reason=why)


# ---------------------------------------------------------------- finding the notebooks
def collect(paths):
    """[(path, parts below the folder given)] of every file under ``paths``, and [Match] of
    what was passed over (symbolic links, special files, paths not found).

    A folder is searched without following symbolic links, at most ``MAX_DEPTH`` deep; a
    file given by name whose folder is a Moodle submission folder keeps that folder in its
    parts (``grade subs/*/*.ipynb``)."""
    found, skipped, seen = [], [], [0]
    for p in paths:
        p = os.fspath(p)
        try:
            st = os.lstat(p)
        except OSError:
            skipped.append(Match(p, (), "not-found", reason="no such file or folder"))
            continue
        if stat.S_ISLNK(st.st_mode):
            skipped.append(Match(p, (), "ignored", reason="a symbolic link (not followed)"))
        elif stat.S_ISDIR(st.st_mode):
            _walk(p, (), found, skipped, seen)
        elif stat.S_ISREG(st.st_mode):
            parent = Path(p).parent.name
            parts = (parent, Path(p).name) if _MOODLE_FOLDER.match(parent) else (Path(p).name,)
            found.append((p, parts))
        else:
            skipped.append(Match(p, (), "ignored", reason="not a file"))
    return found, skipped


def _walk(folder, parts, found, skipped, seen):
    if len(parts) >= MAX_DEPTH:
        skipped.append(Match(folder, parts, "ignored", reason="too deep (not searched)"))
        return
    try:
        entries = sorted(os.scandir(folder), key=lambda e: e.name)
    except OSError as exc:
        skipped.append(Match(folder, parts, "ignored", reason=f"cannot be read "
                             f"({type(exc).__name__})"))
        return
    for e in entries:
        seen[0] += 1
        if seen[0] > MAX_FILES:
            skipped.append(Match(e.path, parts + (e.name,), "ignored", reason="too many files"))
            return
        sub = parts + (e.name,)
        if e.is_symlink():
            skipped.append(Match(e.path, sub, "ignored", reason="a symbolic link (not "
                                 "followed)"))
        elif e.is_dir(follow_symlinks=False):
            _walk(e.path, sub, found, skipped, seen)
        elif e.is_file(follow_symlinks=False):
            found.append((e.path, sub))
        else:
            skipped.append(Match(e.path, sub, "ignored", reason="not a file"))


def assign(paths, roster, explicit=()):
    """Every file under ``paths`` matched against ``roster``: [Match] (notebooks), [Match]
    (the rest: files that are not notebooks, links, paths not found).

    Files found inside folders count only if they end in ``.ipynb``; a file named on the
    command line counts whatever its name (it is then graded, or refused, as a notebook).
    Two notebooks that fit one student are both marked ``duplicate``."""
    found, skipped = collect(paths)
    given = {os.fspath(p) for p in paths}
    notebooks = []
    for path, parts in found:
        if path not in given and not parts[-1].lower().endswith(NOTEBOOK_SUFFIX):
            skipped.append(Match(path, parts, "ignored", reason="not a notebook (.ipynb)"))
            continue
        notebooks.append(identify(parts, roster) if roster is not None else
                         Match(path, parts, "matched", None, "file name"))
        notebooks[-1].path = path
    by_student = {}
    for m in notebooks:
        if m.status == "matched" and m.student is not None:
            by_student.setdefault(m.student.id, []).append(m)
    for sid, ms in by_student.items():
        if len(ms) > 1:
            names = ", ".join(x.name for x in ms)
            for x in ms:
                x.status, x.reason = "duplicate", (f"{len(ms)} notebooks for {sid} "
                                                   f"({x.student.name}): {names}; keep one "
                                                   "and grade again")
    return notebooks, skipped
