"""An exercise's statement as the book writes it, instantiated with any parameters, in plain Markdown.

The statement is read from the chapter's notebook (the one place it is written): the ``{exercise}`` block with
the exercise's label. Its MyST markup becomes what a reader of a standalone notebook or page can read:

* ``{glue:text}`label.name:fmt``` (a parameter of this exercise) becomes the given value, formatted as the book
  formats it;
* a reference becomes the text the book prints: ``{eq}`` "(4.17)", ``{numref}`` "Fig. 3.2", "Table 3.1",
  "Exercise 4.2" (numbered as the book numbers them: in each chapter, in order), ``{doc}`` its text or the page's
  title, ``{cite}`` the key in brackets.

A statement that quotes any other glued number cannot be instantiated: :class:`~scara.errors.ScaraError` names it.
"""
from __future__ import annotations

import json
import re
from functools import lru_cache
from pathlib import Path

from scara.course.exercises import DOCNAMES, chapter_prefix, exercise
from scara.errors import ScaraError

__all__ = ["book_folder", "references", "statement", "readable", "BLOCK"]

#: an ``{exercise}`` block: fence, title, options, body
BLOCK = re.compile(r"^(?P<fence>`{3,}|:{3,})\{exercise\}[ \t]*(?P<title>[^\n]*)\n(?P<options>(?::[\w-]+:[^\n]*\n)*)"
                   r"(?P<body>.*?)^(?P=fence)[ \t]*$", re.M | re.S)
ROLE = re.compile(r"\{(glue:text|glue|numref|eq|ref|doc|cite(?::[a-z]+)?)\}`([^`]*)`")
NAMED = re.compile(r"^(?P<fence>`{3,}|:{3,})\{(?P<kind>glue:figure|figure|list-table|table)\}[^\n]*\n"
                   r"(?P<options>(?::[\w-]+:[^\n]*\n)*)", re.M)
EQUATION = re.compile(r"^\$\$[ \t]*\n.*?\n\$\$[ \t]*\((?P<label>[^)\s]+)\)[ \t]*$", re.M | re.S)
FIGURE = re.compile(r"^(?P<fence>`{3,}|:{3,})\{glue:figure\}[^\n]*\n(?P<body>.*?)^(?P=fence)[ \t]*$", re.M | re.S)
EXPLICIT = re.compile(r"^(?P<text>.*?)\s*<(?P<target>[^<>]+)>$", re.S)


def book_folder() -> Path:
    """The folder of the book's chapters, beside the package."""
    return Path(__file__).resolve().parents[2] / "book"


def _markdown(path: Path) -> str:
    if path.suffix == ".ipynb":
        cells = json.loads(path.read_text(encoding="utf-8"))["cells"]
        return "\n\n".join("".join(c["source"]) if isinstance(c["source"], list) else c["source"]
                           for c in cells if c["cell_type"] == "markdown")
    return path.read_text(encoding="utf-8")


@lru_cache(maxsize=4)
def references(folder: str) -> dict:
    """label -> the text the book prints for a reference to it, for the chapters in ``folder``; docname -> its
    title under ``"doc:" + docname``."""
    out = {}
    for path in sorted(Path(folder).iterdir()):
        if path.suffix not in (".ipynb", ".md"):
            continue
        text = _markdown(path)
        heading = re.search(r"^# (.+)$", text, re.M)
        out["doc:" + path.stem] = heading.group(1).strip() if heading else path.stem
        if path.stem not in DOCNAMES:
            continue
        prefix = chapter_prefix(path.stem)
        counts = {"Fig.": 0, "Table": 0}
        for m in NAMED.finditer(text):
            name = re.search(r"^:name:[ \t]*(\S+)", m.group("options"), re.M)
            kind = "Table" if "table" in m.group("kind") else "Fig."
            counts[kind] += 1
            if name:
                out[name.group(1)] = f"{kind} {prefix}.{counts[kind]}"
        for k, m in enumerate(EQUATION.finditer(text), 1):
            out[m.group("label")] = f"({prefix}.{k})"
        for k, m in enumerate(BLOCK.finditer(text), 1):
            label = re.search(r"^:label:[ \t]*(\S+)", m.group("options"), re.M)
            if label:
                out[label.group(1)] = f"Exercise {prefix}.{k}"
    return out


def _block(label: str, folder: Path) -> re.Match:
    ex = exercise(label)
    path = folder / f"{ex.docname}.ipynb"
    for m in BLOCK.finditer(_markdown(path)):
        if re.search(rf"^:label:[ \t]*{re.escape(label)}[ \t]*$", m.group("options"), re.M):
            return m
    raise ScaraError(f"no {{exercise}} block labelled {label!r} in {path}")


def statement(label: str, params: dict | None = None, folder: Path | None = None) -> tuple[str, str]:
    """``(title, text)`` of exercise ``label`` with ``params`` (default: the book's), in plain Markdown with
    ``$...$`` math."""
    from scara.book import format_plain_text, plain_text  # noqa: PLC0415

    folder = Path(folder or book_folder())
    ex = exercise(label)
    values = dict(ex.defaults, **(params or {}))
    refs = references(str(folder))
    m = _block(label, folder)

    def role(r: re.Match) -> str:
        kind, content = r.group(1), r.group(2)
        if kind.startswith("glue"):
            key, _, spec = content.partition(":")
            owner, _, name = key.rpartition(".")
            if owner != label or name not in values:
                raise ScaraError(f"the statement of {label!r} quotes {key!r}, which is not one of its own "
                                 f"parameters ({sorted(values)}): it cannot be set with other numbers")
            return format_plain_text(plain_text(values[name]), spec)
        explicit = EXPLICIT.match(content)
        text, target = (explicit.group("text"), explicit.group("target")) if explicit else (None, content)
        if kind == "doc":
            return text or refs.get("doc:" + Path(target).name, target)
        if kind.startswith("cite"):
            return "[" + ", ".join(k.strip() for k in target.split(",")) + "]"
        if kind == "ref":
            return text or target
        if target not in refs:
            raise ScaraError(f"the statement of {label!r} refers to {target!r}, which the book does not number")
        number = refs[target]
        if text:
            return text.replace("%s", number.split(" ")[-1].strip("()")).replace("{number}", number.split(" ")[-1])
        return number

    def figure(f: re.Match) -> str:  # a figure of the book within the statement: named, not drawn
        name = re.search(r"^:name:[ \t]*(\S+)", f.group("body"), re.M)
        return f"*(The book draws here {refs.get(name.group(1), 'a figure') if name else 'a figure'}.)*"

    body = FIGURE.sub(figure, m.group("body").strip())
    return ROLE.sub(role, m.group("title").strip()), ROLE.sub(role, body)


def readable(text: str, folder: Path | None = None) -> str:
    """``text`` (a marking note, a parameter's description) with each label of the book it names written as the
    book prints a reference to it: "(eq-kin-det)" as "(1.7)", "fig-ch5-inertia-elbow" as "Fig. 5.5"."""
    refs = references(str(Path(folder or book_folder())))

    def name(m: re.Match) -> str:
        label = m.group("label")
        if label not in refs:
            return m.group(0)
        number = refs[label]
        return number if number.startswith("(") else (f"({number})" if m.group("open") else number)

    return re.sub(r"(?P<open>\()?(?P<label>(?:eq|fig|tab|ex)-[\w-]+)(?(open)\))", name, text)
