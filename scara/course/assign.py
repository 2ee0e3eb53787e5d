"""An assignment for each student of a roster, and the teacher's key.

``python -m scara.course assign --roster roster.csv --secret-file S --out DIR`` writes, for each student of the
roster (a CSV with a column ``id`` and, optionally, ``name``):

* ``DIR/<id>/assignment.ipynb``: the chosen exercises (``--exercises``; default every exercise with a numeric
  answer that can be set with other numbers), each with that student's own parameters, drawn from the student id
  and the course secret (:func:`scara.course.exercises.draw`) and checked by answering them; under each, a cell
  naming the variable that holds each answer and its unit;
* ``DIR/<id>/assignment.html``: the same, to read in a browser (offline: its math is typeset by a copy of MathJax
  in ``DIR/_mathjax``);

and ``DIR/key.json``, for the teacher only: every student's parameters and expected answers with their units and
tolerances, which ``grade`` reads. The same id and secret always give the same assignment; no two students of a
roster share a parameter set; the secret is never written anywhere.
"""
from __future__ import annotations

import csv
import hashlib
import json
import re
import shutil
import time
from pathlib import Path

from scara.course.exercises import Exercise, catalog, draw, exercise
from scara.course.statement import readable, statement
from scara.errors import ScaraError

__all__ = ["exercise_table", "assign", "read_roster", "read_secret", "assignable", "answer_variable", "MIN_SECRET"]

#: the shortest course secret accepted (bytes)
MIN_SECRET = 16
#: what a student id may be made of: it names a folder and a file
ID = re.compile(r"[A-Za-z0-9][A-Za-z0-9._-]{0,63}")


def read_roster(path: Path) -> list[dict]:
    """The students of a roster CSV: ``[{"id": ..., "name": ...}]``; an id missing, repeated or unfit for a
    file name raises :class:`~scara.errors.ScaraError` naming its row."""
    path = Path(path)
    with open(path, newline="", encoding="utf-8-sig") as fh:
        reader = csv.DictReader(fh)
        if not reader.fieldnames or "id" not in [f.strip().lower() for f in reader.fieldnames]:
            raise ScaraError(f"the roster {path} needs a header row with a column 'id' (and optionally 'name'), "
                             f"got {reader.fieldnames}")
        students, seen = [], set()
        for row_number, row in enumerate(reader, 2):
            row = {(k or "").strip().lower(): (v or "").strip() for k, v in row.items()}
            sid = row.get("id", "")
            if not ID.fullmatch(sid):
                raise ScaraError(f"roster {path}, row {row_number}: the id {sid!r} must be 1-64 letters, digits, "
                                 f"'.', '_' or '-', starting with a letter or digit")
            if sid in seen:
                raise ScaraError(f"roster {path}, row {row_number}: the id {sid!r} is given twice")
            seen.add(sid)
            students.append({"id": sid, "name": row.get("name", "") or sid})
    if not students:
        raise ScaraError(f"the roster {path} lists no student")
    return students


def read_secret(path: Path) -> bytes:
    """The course secret from its file (surrounding white space ignored); shorter than :data:`MIN_SECRET` bytes
    raises :class:`~scara.errors.ScaraError`."""
    secret = Path(path).read_bytes().strip()
    if len(secret) < MIN_SECRET:
        raise ScaraError(f"the course secret in {path} has {len(secret)} bytes; use at least {MIN_SECRET} "
                         f"(e.g. python -c \"import secrets; print(secrets.token_hex(16))\" > {path})")
    return secret


def assignable(ex: Exercise) -> bool:
    """Whether an exercise can be set in an assignment: it has a numeric answer and its statement quotes no
    number but its own parameters."""
    if not ex.numeric:
        return False
    try:
        statement(ex.label)
    except ScaraError:
        return False
    return True


BOOK_NUMBERS = "nothing: the book's numbers"


def exercise_table():
    """The book's exercises as a teacher chooses among them, as a Markdown table: number and label, what is asked
    (each answer with its unit and tolerance, or an argument), the numbers an assignment draws for each student
    (with their ranges), and whether it can be set."""
    from IPython.display import Markdown  # noqa: PLC0415

    def cell(text: str) -> str:
        return readable(str(text)).replace("|", "\\|").replace("\n", " ")

    lines = ["| Exercise | Asks for | Drawn for each student | Can be set |", "|---|---|---|---|"]
    for ex in catalog().values():
        asked = "; ".join(f"{a.text} ({a.unit + ', ' if a.unit else ''}{a.tolerance_text()})" for a in ex.answers)
        drawn = "; ".join(f"{p.text}: {p.show(p.values()[0])} to {p.show(p.values()[-1])} {p.unit}".rstrip()
                          if not p.choices else f"{p.text}: one of {', '.join(p.show(v) for v in p.choices)} {p.unit}"
                          for p in ex.params if p.varies)
        lines.append(f"| {ex.number} `{ex.label}` | {cell(asked or 'an argument (see its marking note)')} | "
                     f"{cell(drawn or BOOK_NUMBERS)} | {'yes' if assignable(ex) else 'no'} |")
    return Markdown("\n".join(lines))


def answer_variable(ex: Exercise, name: str) -> str:
    """The variable that holds an answer in the assignment: ``answer_4_3_lag_um``."""
    return f"answer_{ex.number.replace('.', '_')}_{name}"


def _md(text: str) -> dict:
    import nbformat  # noqa: PLC0415

    return nbformat.v4.new_markdown_cell(text)


def _notebook(title: str, student: dict, items: list) -> object:
    import nbformat  # noqa: PLC0415

    nb = nbformat.v4.new_notebook()
    nb.metadata["kernelspec"] = {"name": "python3", "display_name": "Python 3", "language": "python"}
    nb.metadata["scara"] = {"student": student["id"], "exercises": [ex.label for ex, _, _ in items]}
    names = [answer_variable(ex, a.name) for ex, _, _ in items for a in ex.answers]
    nb.cells.append(_md(
        f"# {title}\n\n**{student['name']}** (id `{student['id']}`)\n\n"
        "These exercises are the book's, with numbers of your own: nobody else has the same. Work in this notebook "
        "with the `scara` package, put each answer in the variable named under its exercise, in the unit asked, "
        "then run every cell from the top (Kernel, Restart and run all), save, and hand in this file.\n\n"
        "It is marked by running it from the top in a fresh kernel, offline, with a time limit per cell; "
        f"the answers are read from the variables {', '.join(f'`{n}`' for n in names)} as they stand at the end."))
    nb.cells.append(nbformat.v4.new_code_cell("import numpy as np\n\nimport scara"))
    for ex, params, _ in items:
        head, body = statement(ex.label, params)
        nb.cells.append(_md(f"## Exercise {ex.number}: {head}\n\n{body}"))
        nb.cells.append(nbformat.v4.new_code_cell("# your work\n"))
        asked = "\n".join(f"- `{answer_variable(ex, a.name)}`: {readable(a.text)}, in {a.unit or 'no unit'}"
                          for a in ex.answers)
        nb.cells.append(_md(f"Your answer{'s' if len(ex.answers) > 1 else ''} to Exercise {ex.number}:\n\n{asked}"))
        cell = nbformat.v4.new_code_cell("\n".join(
            f"{answer_variable(ex, a.name)} = None  # {a.unit}".rstrip() for a in ex.answers))
        cell.metadata["scara"] = {"answers": [answer_variable(ex, a.name) for a in ex.answers]}
        nb.cells.append(cell)
    return nb


def _mathjax(out: Path) -> str:
    """Copy MathJax (from the book's offline MathJax package) once into ``out/_mathjax``; its script's URL from a
    student's folder."""
    import importlib.util  # noqa: PLC0415

    spec = importlib.util.find_spec("sphinx-mathjax-offline") or importlib.util.find_spec("sphinx_mathjax_offline")
    if spec is None or not spec.origin:
        return ""
    src = Path(spec.origin).parent / "static" / "mathjax"
    if not (out / "_mathjax").exists() and src.is_dir():
        (out / "_mathjax").mkdir()
        shutil.copy2(src / "tex-chtml.js", out / "_mathjax")
        for part in ("input", "output", "ui"):  # what it loads on demand: TeX extensions, fonts, the menu
            shutil.copytree(src / part, out / "_mathjax" / part)
    return "../_mathjax/tex-chtml.js"


MATHJAX_CONFIG = ("<script>window.MathJax = {tex: {inlineMath: [['$', '$'], ['\\\\(', '\\\\)']], "
                  "displayMath: [['$$', '$$'], ['\\\\[', '\\\\]']], processEscapes: true}};</script>\n")


def _html(nb, mathjax: str) -> str:
    from nbconvert import HTMLExporter  # noqa: PLC0415

    exporter = HTMLExporter(template_name="lab")
    exporter.mathjax_url = mathjax
    exporter.exclude_input_prompt = True
    exporter.exclude_output_prompt = True
    body, _ = exporter.from_notebook_node(nb)
    # nothing from the network: the page works offline (the lab template's require.js is only for widgets)
    body = re.sub(r'<script[^>]+src="https?://[^"]*"[^>]*>\s*</script>', "", body)
    # the template configures MathJax 2; the copy is MathJax 3, which reads $...$ once told so, before it loads
    load = f'<script src="{mathjax}"> </script>'
    if mathjax and load in body:
        body = body.replace(load, MATHJAX_CONFIG + load)
    return body


def assign(roster: Path, secret: bytes, out: Path, labels: list[str] | None = None,
           title: str = "Robot manipulators: your assignment", log=print) -> dict:
    """Write every student's assignment and the key (see the module's docstring); returns the key."""
    import nbformat  # noqa: PLC0415

    students = read_roster(roster)
    if labels:
        chosen = [exercise(label) for label in labels]
        for ex in chosen:
            if not assignable(ex):
                raise ScaraError(f"exercise {ex.label!r} cannot be set: "
                                 + ("its answer is an argument, not a number" if not ex.numeric else
                                    "its statement quotes a number of the chapter that is not one of its parameters"))
    else:
        chosen = [ex for ex in catalog().values() if assignable(ex)]
    if not chosen:
        raise ScaraError("no exercise to set")
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    mathjax = _mathjax(out)
    key = {"title": title, "created": time.strftime("%Y-%m-%d %H:%M:%S"),
           "exercises": [ex.label for ex in chosen], "students": {}}
    taken: dict[tuple, str] = {}
    t0 = time.monotonic()
    for student in students:
        sid = student["id"]
        items, offset = [], 0
        while True:
            items = []
            for k, ex in enumerate(chosen):
                # a repeat of another student's whole set is drawn again, the first varying exercise first
                start = offset if k == 0 else 0
                params, results = draw(ex, secret, f"{sid}#{start}" if start else sid)
                items.append((ex, params, results))
            frozen = tuple((ex.label, tuple(sorted(p.items()))) for ex, p, _ in items)
            if frozen not in taken:
                taken[frozen] = sid
                break
            offset += 1
            if offset > 50:
                raise ScaraError(f"student {sid!r} cannot get a parameter set of their own: the chosen exercises "
                                 f"have too few values for {len(students)} students")
        nb = _notebook(title, student, items)
        folder = out / sid
        folder.mkdir(exist_ok=True)
        nbformat.write(nb, folder / "assignment.ipynb")
        (folder / "assignment.html").write_text(_html(nb, mathjax), encoding="utf-8")
        key["students"][sid] = {"name": student["name"], "params": {ex.label: p for ex, p, _ in items},
                                "answers": {answer_variable(ex, a.name): {
                                    "label": ex.label, "number": ex.number, "answer": a.name,
                                    "text": readable(a.text),
                                    "expected": r[a.name], "unit": a.unit, "tolerance": a.tolerance,
                                    "absolute": a.absolute, "fmt": a.fmt} for ex, _, r in items for a in ex.answers}}
        log(f"{sid}: {len(items)} exercises")
    key["seconds"] = round(time.monotonic() - t0, 2)
    key["fingerprint"] = hashlib.sha256(json.dumps(key["students"], sort_keys=True).encode()).hexdigest()[:16]
    (out / "key.json").write_text(json.dumps(key, indent=1, ensure_ascii=False) + "\n", encoding="utf-8")
    return key
