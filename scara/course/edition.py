"""The two editions of the book, from one source.

The instructor edition is the book as the repository builds it: every exercise with its worked solution folded
under it, and at the end of each chapter the answer key (each numeric answer with its unit and tolerance, the
marking note of each exercise answered by an argument).

The student edition is written from the same sources by :func:`write_student_source` and built like the book:

* every ``{solution}`` block is cut out of the chapters' text (whatever else its cell says stays);
* every cell tagged ``solution`` is left out: the hidden cells that compute a worked solution's numbers, the
  answer key and its heading (so the numbers are never computed, let alone stored in an executed notebook);
* the answers package (:mod:`scara.course.answers`, the key) is left out of the copied package, so the take-home
  download of the student edition cannot compute it either;
* the marking notes of the exercises' declarations are replaced by a line saying where they are;
* the teacher's page (:data:`INSTRUCTOR_PAGES`) is left out, and out of the table of contents.

The chapters keep the outputs of the book's own build (its execution cache, ``_build/.jupyter_cache``), so the
student edition is not executed a second time: each executed chapter passes :func:`student_notebook` as its
source does (a solution's cell leaves with its outputs), and the student edition's configuration runs none of them.
:func:`executed_notebooks` takes a chapter's outputs only from a run of its code as it stands (an older build is
refused, never shown) and only when no cell the student edition keeps reads a name that only a solution's cell
defines (then the kept cells give the same outputs without the solutions). The Markdown pages run as before.

``python -m scara.course edition student`` writes the sources to ``_build/student-source`` and builds them into
``_build/student/_build/html`` (``--execute`` runs the chapters again instead).
"""
from __future__ import annotations

import json
import re
import shutil
import subprocess
import sys
from pathlib import Path

from scara.errors import ScaraError

__all__ = ["INSTRUCTOR_PAGES", "SOLUTION_TAG", "SOLUTION_BLOCK", "strip_solutions", "student_notebook", "write_student_source",
           "build_student", "executed_notebooks", "solution_dependencies", "CACHE", "ROOT"]

#: the pages of the instructor edition only
INSTRUCTOR_PAGES = ("teaching",)
#: the tag of a cell that exists only for the solutions (the instructor edition)
SOLUTION_TAG = "solution"
#: a fenced ``{solution}`` directive, with its fence (three or more backticks or colons) and body
SOLUTION_BLOCK = re.compile(r"^(?P<fence>`{3,}|:{3,})\{solution\}[^\n]*\n.*?^(?P=fence)[ \t]*\n?", re.M | re.S)
#: the repository: the book's sources sit beside the package
ROOT = Path(__file__).resolve().parents[2]
#: where the book's build keeps what it executed (Jupyter Book's jupyter-cache), relative to the repository
CACHE = Path("_build") / ".jupyter_cache"
#: what the student edition's source holds besides the notebooks (copied as they are)
COPIED = ("_config.yml", "_toc.yml", "references.bib", "pyproject.toml", "requirements.txt", "take_home",
          "benchmarks/results.json", "_ext")


def strip_solutions(text: str) -> str:
    """``text`` (a markdown cell) without its ``{solution}`` blocks; an unclosed block raises ``ScaraError``."""
    out = SOLUTION_BLOCK.sub("", text)
    if re.search(r"^(`{3,}|:{3,})\{solution\}", out, re.M):
        raise ScaraError("a {solution} block is not closed by its own fence:\n" + out[:300])
    return out


#: what only the solutions' cells use: dropped from the chapters' imports in the student edition
SOLUTION_NAMES = ("answer_key", "glue_solution")
IMPORT = re.compile(r"^from scara\.course import (?P<names>[\w, ]+)$", re.M)


def _imports(code: str) -> str:
    def keep(m):
        names = [n.strip() for n in m.group("names").split(",") if n.strip() not in SOLUTION_NAMES]
        return f"from scara.course import {', '.join(names)}" if names else ""
    return IMPORT.sub(keep, code)


def student_notebook(nb: dict) -> dict:
    """The student edition of a chapter's notebook (a dict as ``json`` reads it): no cell tagged
    :data:`SOLUTION_TAG`, no ``{solution}`` block, no empty cell left where one was."""
    cells = []
    for cell in nb["cells"]:
        if SOLUTION_TAG in cell.get("metadata", {}).get("tags", []):
            continue
        text = "".join(cell["source"]) if isinstance(cell["source"], list) else cell["source"]
        if cell["cell_type"] == "code" and IMPORT.search(text):
            cell = dict(cell, source=_imports(text).splitlines(keepends=True))
        if cell["cell_type"] == "markdown":
            stripped = strip_solutions(text)
            if stripped != text:
                if not stripped.strip():
                    continue
                cell = dict(cell, source=stripped.splitlines(keepends=True))
        cells.append(cell)
    return dict(nb, cells=cells)


#: what a marking note reads in the student edition
NOTE = "(the marking note is in the instructor edition)"


def without_notes(source: str) -> str:
    """A chapter's module of exercises (Python source) with every marking note (``note=``) replaced by
    :data:`NOTE`: a note says what a full answer contains."""
    import ast  # noqa: PLC0415

    tree = ast.parse(source)
    for node in ast.walk(tree):
        if isinstance(node, ast.Call):
            for kw in node.keywords:
                if kw.arg == "note":
                    kw.value = ast.Constant(NOTE)
    return '"""' + (ast.get_docstring(tree) or "") + '"""\n' + ast.unparse(
        ast.Module(body=tree.body[1:] if ast.get_docstring(tree) else tree.body, type_ignores=[])) + "\n"


def _names(code: str) -> tuple[set, set]:
    """``(bound, read)``: the names a cell's code binds and the names it reads (its IPython magic lines aside)."""
    import ast  # noqa: PLC0415

    tree = ast.parse("\n".join("" if line.lstrip().startswith(("%", "!")) else line for line in code.splitlines()))
    bound, read, local = set(), set(), set()
    for node in ast.walk(tree):
        if isinstance(node, ast.arg):  # a function's or a lambda's own argument
            local.add(node.arg)
        elif isinstance(node, ast.Name):
            (read if isinstance(node.ctx, ast.Load) else bound).add(node.id)
        elif isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
            bound.add(node.name)
        elif isinstance(node, (ast.Import, ast.ImportFrom)):
            bound.update((a.asname or a.name).split(".")[0] for a in node.names)
    return bound, read - local


def solution_dependencies(nb: dict) -> dict[int, set]:
    """The code cells of a chapter that would read what only its solution cells (tagged :data:`SOLUTION_TAG`)
    define: cell index -> those names. Empty when the student edition's cells are independent of the solutions,
    so that their outputs are the same with the solutions' cells as without (the edition keeps those outputs)."""
    code = [(k, SOLUTION_TAG in c.get("metadata", {}).get("tags", []), _names(
        "".join(c["source"]) if isinstance(c["source"], list) else c["source"]))
        for k, c in enumerate(nb["cells"]) if c["cell_type"] == "code"]
    solution_only = set().union(*(b for _, sol, (b, _) in code if sol)) - set().union(
        *(b for _, sol, (b, _) in code if not sol))
    return {k: read & solution_only for k, sol, (_, read) in code if not sol and read & solution_only}


def executed_notebooks(root: Path = ROOT, cache: Path | None = None) -> dict[str, dict]:
    """The chapters as the book's build executed them, from its execution cache (jupyter-cache, :data:`CACHE`):
    file name -> the source notebook (a dict) with the outputs the build stored for it, glued values included,
    one for every ``book/*.ipynb`` of the student edition. Raises :class:`~scara.ScaraError` naming the chapter
    when the cache holds none for its code as it stands (no build, or a build older than the sources), so that no
    output of another version of a chapter reaches the edition."""
    import nbformat  # noqa: PLC0415 - the book's toolchain, as the edition's build needs it
    from jupyter_cache import get_cache  # noqa: PLC0415

    folder = Path(cache) if cache is not None else root / CACHE
    if not (folder / "global.db").is_file():
        raise ScaraError(f"the book's build left no execution cache ({folder} is missing): build the book first "
                         f"(jupyter-book build .), or give --execute to run the chapters again")
    store = get_cache(str(folder))
    out = {}
    for page in sorted((root / "book").glob("*.ipynb")):
        if page.stem in INSTRUCTOR_PAGES:
            continue
        try:
            _, nb = store.merge_match_into_notebook(nbformat.read(page, as_version=4))
        except KeyError:
            raise ScaraError(f"the book's execution cache ({folder}) holds no run of book/{page.name} as it stands "
                             f"(a build older than its code): build the book again, or give --execute to run the "
                             f"chapters again") from None
        nb = json.loads(nbformat.writes(nb))
        needs = solution_dependencies(nb)
        if needs:
            k, names = next(iter(needs.items()))
            raise ScaraError(f"{page.name}: cell {k + 1} reads {', '.join(sorted(names))}, which only a solution's "
                             f"cell defines: the student edition (no solution cells) cannot keep the book's outputs")
        out[page.name] = nb
    return out


def write_student_source(out: Path, root: Path = ROOT, executed: dict[str, dict] | None = None) -> Path:
    """Write the student edition's sources to ``out`` (emptied first): the book's pages, stripped of their
    solutions, its configuration and extensions, and the package without its answers. Returns ``out``.

    ``executed`` (file name -> executed notebook, :func:`executed_notebooks`) gives the chapters with the outputs
    of the book's build: they are written with those outputs and the edition's configuration does not execute
    them. Without it every chapter is executed by the edition's build."""
    out = Path(out)
    if out.resolve() == root.resolve() or root.resolve() in out.resolve().parents and out.name in ("book", "scara"):
        raise ScaraError(f"refusing to write the student edition over the sources: {out}")
    if out.exists() and any(out.iterdir()) and not (out / "EDITION").is_file():
        raise ScaraError(f"refusing to empty {out}: it holds files and is not a student edition this command wrote "
                         f"(no EDITION file); give a new or empty folder")
    if out.exists():
        shutil.rmtree(out)
    (out / "book").mkdir(parents=True)
    for page in sorted((root / "book").iterdir()):
        if page.stem in INSTRUCTOR_PAGES:
            continue
        if page.suffix == ".ipynb":
            nb = executed[page.name] if executed else json.loads(page.read_text(encoding="utf-8"))
            (out / "book" / page.name).write_text(json.dumps(student_notebook(nb), indent=1, ensure_ascii=False) + "\n",
                                                  encoding="utf-8")
        elif page.suffix == ".md":
            (out / "book" / page.name).write_text(strip_solutions(page.read_text(encoding="utf-8")), encoding="utf-8")
    ignore = shutil.ignore_patterns("__pycache__", "*.pyc", "*.nbi", "*.nbc", ".ipynb_checkpoints")
    for name in COPIED:
        src = root / name
        if src.is_dir():
            shutil.copytree(src, out / name, ignore=ignore)
        elif src.is_file():
            (out / name).parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(src, out / name)
    shutil.copytree(root / "scara", out / "scara", ignore=shutil.ignore_patterns(
        "__pycache__", "*.pyc", "*.nbi", "*.nbc", "answers"))
    for module in (out / "scara" / "course" / "chapters").glob("*.py"):
        module.write_text(without_notes(module.read_text(encoding="utf-8")), encoding="utf-8")
    toc = (out / "_toc.yml").read_text(encoding="utf-8")
    for page in INSTRUCTOR_PAGES:
        toc = re.sub(rf"^[ \t]*- file: book/{page}[ \t]*\n", "", toc, flags=re.M)
    (out / "_toc.yml").write_text(toc, encoding="utf-8")
    if executed:
        _keep_outputs(out / "_config.yml")
    (out / "EDITION").write_text("student\n", encoding="utf-8")
    return out


#: the ``execute:`` section of the book's ``_config.yml`` (the section's name and its indented lines)
EXECUTE_SECTION = re.compile(r"^execute:[ \t]*\n(?:[ \t]+.*\n|[ \t]*\n)*", re.M)
#: the line of that section listing the notebooks the build does not execute (none, in the book)
NOT_EXECUTED = re.compile(r"^(?P<indent>[ \t]+)exclude_patterns: \[\].*$", re.M)


def _keep_outputs(config: Path) -> None:
    """Make the edition's configuration execute none of its ``book/*.ipynb`` (they hold the book's outputs)."""
    text = config.read_text(encoding="utf-8")
    section = EXECUTE_SECTION.search(text)
    found = NOT_EXECUTED.search(section.group(0)) if section else None
    if found is None:
        raise ScaraError(f"{config}: its 'execute:' section has no line 'exclude_patterns: []' to list the chapters "
                         f"that keep the book's outputs")
    start, end = section.start() + found.start(), section.start() + found.end()
    line = f"{found.group('indent')}exclude_patterns: [\"book/*.ipynb\"]   # they keep the outputs of the book's build"
    config.write_text(text[:start] + line + text[end:], encoding="utf-8")


def build_student(source: Path, output: Path, extra_args=()) -> int:
    """Build the student edition's ``source`` with Jupyter Book into ``output`` (its ``html`` folder), warnings
    as errors; returns the build's exit status."""
    cmd = [str(Path(sys.executable).with_name("jupyter-book")), "build", str(source), "--path-output", str(output),
           "-W", "-n", "--keep-going", *extra_args]
    return subprocess.call(cmd)
