"""How a step's label is printed: Mei's numbers in round brackets, the book's own in square.

Mei (1983) numbers 46 equations: (1.1)-(1.27), (2.1)-(2.4) and (3.1)-(3.15).  The
library also shows forms of its own (the accelerations solved from (1.4), the momenta
used in (1.26), the OCR's printed (3.10), ...).  So that a reader never takes one of
those for an equation of the paper, they are printed in square brackets:

>>> shown_label("1.16"), shown_label("1.26b"), shown_label("from 1.12")
('(1.16)', '[1.26b]', '[from 1.12]')
>>> is_paper_number("3.15"), is_paper_number("3.16"), is_paper_number("1.4a")
(True, False, False)
"""

from __future__ import annotations

__all__ = ["PAPER_NUMBERS", "is_paper_number", "shown_label"]

#: The numbers of Mei's equations, in the paper's order.
PAPER_NUMBERS = tuple([f"1.{i}" for i in range(1, 28)] + [f"2.{i}" for i in range(1, 5)]
                      + [f"3.{i}" for i in range(1, 16)])
_PAPER = frozenset(PAPER_NUMBERS)


def is_paper_number(label: str) -> bool:
    """True when ``label`` is one of the paper's 46 equation numbers."""
    return label in _PAPER


def shown_label(label: str) -> str:
    """``label`` as printed: ``(1.16)`` for the paper's numbers, ``[1.26b]`` otherwise."""
    return f"({label})" if is_paper_number(label) else f"[{label}]"
