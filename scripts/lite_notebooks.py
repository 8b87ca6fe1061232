"""The notebooks of the in-browser site, made from the book's notebooks.

JupyterLab shows MyST-only syntax as raw text, so each lite copy is the book's
notebook with those constructs turned into plain Markdown/HTML:

==============================  ==================================================
``{exercise}`` (``:label:``)    a bold "Exercise 4.2" paragraph
``{solution} label``            ``<details><summary>Solution …</summary>…</details>``
``{exercise-start}``/``-end``   as ``{exercise}`` / nothing
``{solution-start}``/``-end``   a bold "Solution to …" / "(end of the solution)"
                                (the solution's code cells lie between them)
``{admonition} Title``          a block quote with the title in bold
``{figure} path``               an image with its caption
``{doc}`target```               a link to that notebook (text only for a page that
                                is not a notebook, e.g. the glossary)
``{ref}`label```                "Exercise 4.2" or the section title, linked
``{term}`text <term>```         the text
``{numref}`fig-label```         "the figure" (or its text, without the number)
``{cite:p}`key```               (Author Year), from book/references.bib
``(label)=``                    removed
==============================  ==================================================

Notebooks that run in Pyodide lose their stored outputs (the reader runs
them); a notebook that needs numpy/scipy/matplotlib (not available in the
browser) keeps them and starts with a cell that says so. ``hide-input`` cells
are collapsed. The student exercise notebooks (no solutions) are the lite
exercises. Nothing is written to the source tree: ``build_lite.py`` writes the
copies into the build directory on every build, so they are never stale.
"""
from __future__ import annotations

import copy
import json
import re
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent

#: Python modules that the browser (Pyodide, as served by this site) does not have
NATIVE_ONLY = ("numpy", "scipy", "matplotlib", "tqdm")
#: code that needs them: imports, the numerics package and its entry points
_NEEDS_NATIVE = re.compile(
    r"^\s*(?:import|from)\s+(?:numpy|scipy|matplotlib|tqdm)\b"
    r"|whittaker_teach\.numerics|\bwt\.numerics\b|\.simulate\(|sledge_exact\(",
    re.M)

LITE_KERNELSPEC = {"name": "python", "display_name": "Python (Pyodide)",
                   "language": "python"}

_FENCE = re.compile(r"^(?P<fence>`{3,}|:{3,})\{(?P<name>[\w:-]+)\}[ \t]*(?P<arg>.*)$")
_OPTION = re.compile(r"^:(?P<key>[\w-]+):[ \t]*(?P<value>.*)$")
_ROLE = re.compile(r"\{(?P<role>[\w:-]+)\}`(?P<body>[^`]*)`")
_TARGET = re.compile(r"^\((?P<label>[\w:.-]+)\)=[ \t]*\n?", re.M)
_TITLED = re.compile(r"^(?P<text>.*?)\s*<(?P<target>[^<>]+)>$", re.S)


def needs_native(nb) -> bool:
    """True when a code cell of the notebook needs numpy/scipy/matplotlib/tqdm."""
    return any(c["cell_type"] == "code" and _NEEDS_NATIVE.search(_src(c))
               for c in nb["cells"])


def _src(cell) -> str:
    s = cell.get("source", "")
    return s if isinstance(s, str) else "".join(s)


# ------------------------------------------------------------------ bibliography
def read_bib(path: Path) -> dict:
    """{key: (authors' last names, year)} from a BibTeX file (what a citation shows)."""
    refs = {}
    text = path.read_text(encoding="utf-8") if path.exists() else ""
    for m in re.finditer(r"@\w+\{(?P<key>[^,\s]+),(?P<body>.*?)\n\}", text, re.S):
        body = m.group("body")
        author = re.search(r"\bauthor\s*=\s*\{(.*?)\},?\s*\n", body, re.S)
        year = re.search(r"\byear\s*=\s*\{?(\d{4})", body)
        names = [a.split(",")[0].strip(" {}") for a in
                 re.split(r"\s+and\s+", author.group(1))] if author else ["?"]
        if len(names) > 2:
            who = f"{names[0]} et al."
        else:
            who = " and ".join(names)
        refs[m.group("key")] = (who, year.group(1) if year else "n.d.")
    return refs


# ------------------------------------------------------------------ the index
class Index:
    """What cross-references resolve to: notebook titles, labels, citations.

    ``docs`` maps a document path relative to the root without suffix
    ("book/06-sledge") to its title when it is a lite notebook; ``labels`` maps a
    label to (document, text).
    """

    def __init__(self, docs=None, labels=None, bib=None):
        self.docs = dict(docs or {})
        self.labels = dict(labels or {})
        self.bib = dict(bib or {})

    @classmethod
    def from_notebooks(cls, paths, root: Path = ROOT, bib: Path | None = None):
        index = cls(bib=read_bib(bib or root / "book" / "references.bib"))
        for path in paths:
            nb = json.loads(Path(path).read_text(encoding="utf-8"))
            doc = Path(path).resolve().relative_to(root).with_suffix("").as_posix()
            index.add(doc, nb)
        return index

    def add(self, doc: str, nb) -> None:
        title, n = doc, 0
        chapter = _chapter(doc)
        for cell in nb["cells"]:
            if cell["cell_type"] != "markdown":
                continue
            src = _src(cell)
            h1 = re.search(r"^# (.+)$", src, re.M)
            if h1 and title == doc:
                title = h1.group(1).strip()
            for m in re.finditer(r"^(`{3,}|:{3,})\{exercise(?:-start)?\}.*\n((?::[\w-]+:.*\n)*)",
                                 src, re.M):
                n += 1
                label = re.search(r"^:label:\s*(\S+)", m.group(2), re.M)
                if label:
                    self.labels[label.group(1)] = (doc, _exercise_name(chapter, n))
            for m in re.finditer(r"^\(([\w:.-]+)\)=[ \t]*\n#+\s+(.+)$", src, re.M):
                self.labels[m.group(1)] = (doc, m.group(2).strip())
        self.docs[doc] = title

    def link(self, from_doc: str, to_doc: str, text: str) -> str:
        if to_doc not in self.docs:
            return text
        rel = _relpath(to_doc + ".ipynb", from_doc)
        return f"[{text}]({rel})"


def _chapter(doc: str):
    m = re.match(r"(?:.*/)?(\d+)-", doc)
    return int(m.group(1)) if m else None


def _exercise_name(chapter, n):
    return f"Exercise {chapter}.{n}" if chapter else f"Exercise {n}"


def _relpath(target: str, from_doc: str) -> str:
    """``target`` (root-relative) as seen from the folder of ``from_doc``."""
    src = Path(from_doc).parent.parts
    dst = Path(target).parts
    i = 0
    while i < min(len(src), len(dst) - 1) and src[i] == dst[i]:
        i += 1
    return "/".join([".."] * (len(src) - i) + list(dst[i:]))


# ------------------------------------------------------------------ markdown
def convert_markdown(text: str, doc: str, index: Index, state=None) -> str:
    """MyST-only syntax of one Markdown cell → plain Markdown/HTML."""
    state = state if state is not None else {"exercise": 0}
    text = _TARGET.sub("", text)
    text = _convert_blocks(text, doc, index, state)
    return _convert_roles(text, doc, index)


def _convert_blocks(text, doc, index, state):
    lines = text.split("\n")
    out, i = [], 0
    while i < len(lines):
        m = _FENCE.match(lines[i])
        if not m:
            out.append(lines[i])
            i += 1
            continue
        fence = m.group("fence")
        j = i + 1
        while j < len(lines) and not _closes(lines[j], fence):
            j += 1
        body = lines[i + 1:j]
        options = {}
        while body and _OPTION.match(body[0]):
            o = _OPTION.match(body[0])
            options[o.group("key")] = o.group("value").strip()
            body = body[1:]
        inner = _convert_blocks("\n".join(body).strip("\n"), doc, index, state)
        out.extend(_directive(m.group("name"), m.group("arg").strip(), options,
                              inner, doc, index, state).split("\n"))
        i = j + 1
    return "\n".join(out)


def _closes(line, fence):
    s = line.rstrip()
    return bool(s) and set(s) == {fence[0]} and len(s) >= len(fence)


def _directive(name, arg, options, body, doc, index, state):
    if name in ("exercise-end", "solution-end"):      # gated directives: the end marker
        return "*(end of the solution)*" if name == "solution-end" else ""
    if name == "solution-start":       # its code cells follow: no <details> across cells
        target = index.labels.get(arg, (doc, None))[1] if arg else None
        return f"**Solution to {target}.**" if target else "**Solution.**"
    if name in ("exercise", "exercise-start"):
        state["exercise"] += 1
        label = options.get("label")
        title = (index.labels.get(label, (doc, None))[1] if label else None) \
            or _exercise_name(_chapter(doc), state["exercise"])
        extra = f" ({arg})" if arg else ""
        return f"**{title}{extra}.** {body}" if body else f"**{title}{extra}.**"
    if name == "solution":
        target = index.labels.get(arg, (doc, None))[1] if arg else None
        summary = f"Solution to {target}" if target else "Solution"
        return f"<details>\n<summary>{summary}</summary>\n\n{body}\n\n</details>"
    if name in ("admonition", "note", "warning", "tip", "important", "hint"):
        title = arg or name.capitalize()
        quoted = "\n".join(("> " + line) if line else ">" for line in body.split("\n"))
        return f"> **{title}**\n>\n{quoted}"
    if name in ("figure", "image"):
        caption = body.strip()
        alt = (options.get("alt") or caption.split("\n\n")[0].replace("\n", " ")
               or Path(arg).stem)
        alt = re.sub(r"[\[\]]", "", alt)
        return f"![{alt[:120]}]({arg})" + (f"\n\n*{caption}*" if caption and name == "figure" else "")
    if name in ("math",):
        return f"$$\n{body}\n$$"
    # any other directive: its body as plain Markdown, titled with its name
    return f"**{arg or name}**\n\n{body}" if body else f"**{arg or name}**"


def _convert_roles(text, doc, index):
    def role(m):
        name, body = m.group("role"), m.group("body")
        titled = _TITLED.match(body)
        text_, target = (titled.group("text"), titled.group("target")) if titled else (None, body)
        if name == "doc":
            to = _resolve_doc(doc, target)
            return index.link(doc, to, text_ or index.docs.get(to, Path(target).name))
        if name == "ref":
            to, label_text = index.labels.get(target, (None, None))
            if to is None:
                return text_ or target
            return index.link(doc, to, text_ or label_text)
        if name in ("term", "abbr", "index"):
            return text_ or target
        if name == "numref":        # figures are not numbered in the lite copies
            return (text_ or "the figure").replace("{number}", "").replace("  ", " ").strip()
        if name.startswith("cite"):
            parts = [index.bib.get(k.strip(), (k.strip(), "")) for k in target.split(",")]
            if name == "cite:t":
                return "; ".join(f"{who} ({year})" for who, year in parts)
            return "(" + "; ".join(f"{who} {year}".strip() for who, year in parts) + ")"
        if name in ("math", "eq"):
            return f"${target}$" if name == "math" else f"({target})"
        return text_ or target
    return _ROLE.sub(role, text)


def _resolve_doc(doc, target):
    if target.startswith("/"):
        return target.lstrip("/").removesuffix(".md").removesuffix(".ipynb")
    base = Path(doc).parent
    parts = []
    for p in (base / target).parts:
        if p == "..":
            parts.pop()
        elif p != ".":
            parts.append(p)
    return "/".join(parts).removesuffix(".md").removesuffix(".ipynb")


# ------------------------------------------------------------------ notebooks
def native_banner(doc: str) -> dict:
    return _markdown_cell(
        "> **This notebook runs locally, not in the browser.** It uses numpy, scipy "
        "or matplotlib (the `[numerics]` extra of `whittaker-teach`), and the "
        "in-browser Python (Pyodide) of this site has only the symbolic core "
        "(SymPy, mpmath, `whittaker_teach`): Pyodide's numpy/scipy/matplotlib builds "
        "are not served here. The outputs below are the stored ones from the book. "
        "To run it, install the course locally (`make book` in a clone of the "
        "repository) and open `" + doc + ".ipynb` in Jupyter. The symbolic "
        "chapters and exercises run here.")


def _markdown_cell(text):
    return {"cell_type": "markdown", "metadata": {}, "source": text}


def lite_notebook(nb, doc: str, index: Index):
    """The lite copy of one notebook (a new dict; ``nb`` is not changed)."""
    nb = copy.deepcopy(nb)
    native = needs_native(nb)
    state = {"exercise": 0}
    cells = []
    for cell in nb["cells"]:
        if cell["cell_type"] == "markdown":
            cell["source"] = convert_markdown(_src(cell), doc, index, state)
        elif cell["cell_type"] == "code":
            tags = cell.get("metadata", {}).get("tags", [])
            if "hide-input" in tags or "remove-input" in tags:
                cell["metadata"].setdefault("jupyter", {})["source_hidden"] = True
            if "hide-output" in tags:
                cell["metadata"].setdefault("jupyter", {})["outputs_hidden"] = True
            cell["metadata"].pop("execution", None)
            if not native:
                cell["outputs"] = []
                cell["execution_count"] = None
            cell["source"] = _src(cell)
        cells.append(cell)
    if native:
        cells.insert(0, native_banner(doc))
    nb["cells"] = cells
    nb["metadata"]["kernelspec"] = dict(LITE_KERNELSPEC)
    nb["metadata"].setdefault("language_info", {})["name"] = "python"
    nb["metadata"]["whittaker_teach"] = {"source": doc + ".ipynb",
                                         "runs_in_browser": not native}
    return nb


def figure_paths(nb):
    """Relative image paths named by {figure}/{image} directives of a notebook."""
    out = []
    for cell in nb["cells"]:
        if cell["cell_type"] == "markdown":
            out += re.findall(r"^(?:`{3,}|:{3,})\{(?:figure|image)\}\s*(\S+)", _src(cell), re.M)
    return out
