"""The answer to a check: :class:`Feedback`, with ``.ok`` and ``.message``.

It shows as a short coloured box in a notebook (``_repr_html_``), as
Markdown where HTML is not wanted (``_repr_markdown_``) and as one line of
text elsewhere.  Nothing here imports SymPy.

>>> f = Feedback(True, "L* is right.", "sledge-L-star", "L_star")
>>> f.ok, str(f)
(True, '[sledge-L-star, L_star] Correct. L* is right.')
>>> print(Feedback(False, "not answered yet: replace None by your answer", "kepler-orbit", "h",
...                status="unanswered"))
[kepler-orbit, h] not answered yet: replace None by your answer
"""

from __future__ import annotations

import html
from dataclasses import dataclass

__all__ = ["Feedback"]

_STYLE = {
    # status: (label, border colour, background colour)
    "correct": ("Correct", "#2e7d32", "#e8f5e9"),
    "wrong": ("Not yet right", "#c62828", "#ffebee"),
    "unanswered": ("Not answered yet", "#616161", "#f5f5f5"),
    "invalid": ("Cannot check this answer", "#ef6c00", "#fff3e0"),
    "graded": ("Recorded as read", "#1565c0", "#e3f2fd"),
}


@dataclass(frozen=True)
class Feedback:
    """The result of :func:`whittaker_teach.exercises.check`.

    ``ok`` is True only for a correct answer; ``message`` says why, or what
    kind of difference the checker sees.  ``status`` is one of
    ``"correct"``, ``"wrong"``, ``"unanswered"`` (the answer is still None),
    ``"invalid"`` (not something the checker can read) and ``"graded"`` (the
    student edition of a graded exercise: the answer as read, no verdict).
    """

    ok: bool
    message: str
    exercise: str = ""
    part: str | None = None
    status: str = ""
    read: str = ""          # a typed answer as the checker read it, shown before the verdict

    def __post_init__(self):
        if not self.status:
            object.__setattr__(self, "status", "correct" if self.ok else "wrong")

    def __bool__(self):
        return bool(self.ok)

    @property
    def _where(self):
        bits = [b for b in (self.exercise, self.part) if b]
        return f"[{', '.join(bits)}] " if bits else ""

    @property
    def _read(self):
        return f"Read as {self.read}. " if self.read else ""

    def __str__(self):
        if self.status == "unanswered":
            return f"{self._where}{self.message}"
        return f"{self._where}{self._read}{_STYLE[self.status][0]}. {self.message}"

    def __repr__(self):
        return f"Feedback(ok={self.ok}, {str(self)!r})"

    def _repr_html_(self):
        label, border, background = _STYLE[self.status]
        where = html.escape(self._where.strip())
        msg = html.escape(self.message)
        if self.status == "unanswered":
            text = msg
        else:
            text = f"<strong>{label}.</strong> {msg}"
        if self.read:
            text = (f'Read as <code class="wt-read">{html.escape(self.read)}</code>. ' + text)
        return (f'<div class="wt-feedback wt-feedback-{self.status}" style="border-left: 4px '
                f'solid {border}; background: {background}; padding: 0.4em 0.8em; '
                f'margin: 0.2em 0; color: #212121;"><span style="color: {border};">{where}</span> '
                f"{text}</div>")

    def _repr_markdown_(self):
        label = _STYLE[self.status][0]
        msg = self.message.replace("*", r"\*").replace("_", r"\_")
        if self.status == "unanswered":
            return f"{self._where}{msg}"
        read = f"Read as `{self.read}`. " if self.read else ""
        return f"{self._where}{read}**{label}.** {msg}"
