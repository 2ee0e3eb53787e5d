"""The student edition holds no solution anywhere: every file of its build (pages, search index, page sources,
executed notebooks, the take-home zip's notebooks, its PDFs, Sphinx's own pickles) is searched for the text of
each worked solution and for each answer of the key, as the instructor edition shows them. The instructor edition
has them all, and its answer keys.

The student edition is built by ``python -m scara.course edition student`` (the README's test command does) into
``_build/student``; without it these tests skip with the reason (under ``CI=true`` they fail).
"""
from __future__ import annotations

import html
import io
import json
import os
import re
import shutil
import subprocess
import zipfile
from pathlib import Path

import pytest

from scara.book import format_plain_text, plain_text
from scara.course.edition import SOLUTION_BLOCK, student_notebook
from scara.course.exercises import catalog, solve

ROOT = Path(__file__).resolve().parents[2]
STUDENT = Path(os.environ.get("SCARA_STUDENT_BUILD", ROOT / "_build" / "student"))
INSTRUCTOR = ROOT / "_build" / "html"
#: files that hold no text
BINARY = {".png", ".jpg", ".jpeg", ".gif", ".woff", ".woff2", ".ttf", ".eot", ".ico", ".otf"}
#: the fewest words a phrase of a solution has to be searched for (shorter ones recur in any text)
WORDS = 6


def _unavailable(reason):
    if os.environ.get("CI") == "true":
        pytest.fail(reason)
    pytest.skip(reason)


def _normal(text: str) -> str:
    text = text.replace("\u2019", "'").replace("\u2018", "'").replace("\u201c", '"').replace("\u201d", '"')
    text = text.replace("\u2013", "-").replace("\u2014", "-").replace("\u00a0", " ").replace("\u202f", " ")
    return re.sub(r"\s+", " ", text).strip().lower()


def _html_text(raw: str) -> str:
    raw = re.sub(r"<(script|style)[^>]*>.*?</\1>", " ", raw, flags=re.S)
    return html.unescape(re.sub(r"<[^>]+>", " ", raw))


def _texts(path: Path, data: bytes):
    """The readable texts of one file (a zip: of each member)."""
    if path.suffix in BINARY:
        return
    if path.suffix == ".zip":
        with zipfile.ZipFile(io.BytesIO(data)) as zf:
            for name in zf.namelist():
                yield from _texts(Path(name), zf.read(name))
        return
    if path.suffix == ".pdf":
        if shutil.which("pdftotext"):
            yield subprocess.run(["pdftotext", "-layout", "-", "-"], input=data, capture_output=True).stdout.decode(
                errors="replace")
        return
    text = data.decode("utf-8", errors="replace")
    yield text
    if path.suffix in (".html", ".htm"):
        yield _html_text(text)
    if path.suffix in (".ipynb", ".json", ".js"):
        # the strings of a JSON document as they read (escapes undone)
        yield re.sub(r"\\n", "\n", re.sub(r'\\"', '"', text))


@pytest.fixture(scope="module")
def corpus():
    html_dir = STUDENT / "_build" / "html"
    if not (html_dir / "index.html").is_file():
        _unavailable(f"the student edition is not built ({html_dir}/index.html missing): run "
                     "python -m scara.course edition student first")
    out = {}
    for path in sorted(STUDENT.rglob("*")):
        if path.is_file():
            out[path] = [_normal(t) for t in _texts(path, path.read_bytes())]
    return out


def _instructor_texts() -> tuple[dict, str]:
    """From the instructor edition's pages: the text of each worked solution (its title -> text) and the text of
    everything else (the chapters, their figures' and cells' output, the other pages)."""
    from bs4 import BeautifulSoup

    if not (INSTRUCTOR / "index.html").is_file():
        _unavailable("the instructor edition is not built (_build/html/index.html missing)")
    solutions, rest = {}, []
    for page in sorted((INSTRUCTOR / "book").glob("*.html")):
        soup = BeautifulSoup(page.read_text(encoding="utf-8"), "html.parser")
        for tag in soup(["script", "style"]):
            tag.decompose()
        for box in soup.select("div.solution"):
            title = box.select_one(".admonition-title")
            name = f"{page.stem}: {title.get_text(' ', strip=True) if title else box.get('id')}"
            solutions[name] = _normal(box.get_text(" "))
            box.decompose()
        key = soup.select_one("section#answer-key")  # the instructor edition's answer key: solutions too
        if key is not None:
            solutions[f"{page.stem}: answer key"] = _normal(key.get_text(" "))
            key.decompose()
        rest.append(_normal(soup.get_text(" ")))
    return solutions, " ".join(rest)


def _windows(text: str) -> set:
    """Every run of :data:`WORDS` words of a text that reads as prose (four words of three letters or more; a
    run of symbols is a formula, which the chapters' text may write the same way)."""
    words = text.split()
    runs = (words[i:i + WORDS] for i in range(len(words) - WORDS + 1))
    return {" ".join(run) for run in runs if sum(w.isalpha() and len(w) >= 3 for w in run) >= 4}


def test_no_solution_text_in_any_file_of_the_student_edition(corpus):
    """Every run of words that the instructor edition prints in a worked solution and nowhere else is searched
    for in every file of the student edition."""
    solutions, rest = _instructor_texts()
    assert len(solutions) == len(catalog()) + len({ex.docname for ex in catalog().values()})
    # what the student edition holds anyway: the instructor edition's other text, the chapters' cells that are
    # not the solutions', the package (docstrings, comments, messages) but for its answers and marking notes
    rest += " ".join(_normal(json.dumps(student_notebook(nb), ensure_ascii=False)) for _, nb in _sources())
    rest += " ".join(_normal(p.read_text(encoding="utf-8")) for p in sorted((ROOT / "scara").rglob("*.py"))
                     if not {"answers", "chapters"} & set(p.relative_to(ROOT / "scara").parts))
    elsewhere = _windows(rest)
    # the marking notes are solutions too
    for ex in catalog().values():
        solutions[f"marking note of {ex.label}"] = _normal(ex.note)
    phrases, bare = {}, []
    for name, text in solutions.items():
        own = _windows(text) - elsewhere
        if not own:
            bare.append(name)
        for window in own:
            phrases.setdefault(window, name)
    # a solution that is all formulas has no run of prose of its own: its numbers are searched for below
    assert len(phrases) > 1500 and len(bare) <= 12, bare
    leaks = []
    for file, texts in corpus.items():
        for t in texts:
            for window in _windows(t) & phrases.keys():
                leaks.append(f"{file.relative_to(STUDENT)}: {phrases[window]}: {window!r}")
    assert not leaks, "solution text in the student edition:\n  " + "\n  ".join(sorted(set(leaks))[:30])


def _sources():
    for path in sorted((ROOT / "book").glob("*.ipynb")):
        yield path, json.loads(path.read_text(encoding="utf-8"))


def _significant(shown: str) -> bool:
    """Whether a printed number is distinctive enough to search for: four digits or more, three of them
    significant (not 2000, 0.50 or 45)."""
    digits = re.sub(r"\D", "", shown)
    return len(digits) >= 4 and len(digits.strip("0")) >= 3


def _key_values(shown: bool = False) -> dict:
    """Each answer of the key as the instructor edition prints it: in its worked solution (with the solution's
    format) and in the answer key (with the answer's): label.name -> strings. Only the answers that the book
    shows by design (``Answer.shown``: a figure to check a prediction on, a table to reason from) with
    ``shown``, only the others without."""
    formats = {}
    for _, nb in _sources():
        text = "\n".join("".join(c["source"]) for c in nb["cells"] if c["cell_type"] == "markdown")
        for m in SOLUTION_BLOCK.finditer(text):
            for key, spec in re.findall(r"\{glue:text\}`([^`:]+):?([^`]*)`", m.group(0)):
                formats.setdefault(key, set()).add(spec)
    out = {}
    for ex in catalog().values():
        if not ex.numeric:
            continue
        result = solve(ex.label)
        for a in ex.answers:
            if bool(a.shown) != shown:
                continue
            key = ex.key(a.name)
            printed = {format(result[a.name], a.fmt)} | {format_plain_text(plain_text(result[a.name]), spec)
                                                        for spec in formats.get(key, ())}
            out[key] = {s for s in printed if _significant(s)}
    return out


def _readable(path: Path, data: bytes):
    """What a reader of a file can read as text: a page's text (not its scripts, whose figure data holds
    thousands of numbers), the search index, a notebook's markdown and text outputs (not its figures), a PDF's
    text; each member of a zip."""
    if path.suffix in BINARY or path.suffix in (".pickle", ".doctree", ".js") and path.name != "searchindex.js":
        return
    if path.suffix == ".zip":
        with zipfile.ZipFile(io.BytesIO(data)) as zf:
            for name in zf.namelist():
                yield from _readable(Path(name), zf.read(name))
        return
    if path.suffix in (".html", ".htm"):
        yield _html_text(data.decode("utf-8", errors="replace"))
    elif path.suffix == ".ipynb":
        nb = json.loads(data)
        for cell in nb.get("cells", []):
            yield "".join(cell.get("source", ""))
            for out in cell.get("outputs", []):
                for mime in ("text/plain", "text/markdown", "text"):
                    value = out.get("data", {}).get(mime, out.get(mime)) if mime != "text" else out.get("text")
                    if value:
                        yield "".join(value) if isinstance(value, list) else str(value)
    elif path.suffix == ".json" and path.name.endswith(".glue.json"):
        yield json.dumps({k: v.get("text/plain") if isinstance(v, dict) else None
                          for k, v in json.loads(data).items()})
    elif path.suffix in (".pdf", ".txt", ".md", ".js", ".csv"):
        yield from _texts(path, data)


@pytest.fixture(scope="module")
def readable(corpus):
    return {p: [_normal(t) for t in _readable(p, p.read_bytes())] for p in corpus}


def test_answers_the_book_shows_by_design_are_where_it_says(readable):
    """The few answers the book shows for its own numbers (a figure to check a prediction on) are declared so,
    and are indeed in the student edition's text: the declaration hides no leak."""
    pages = " ".join(t for p, texts in readable.items() if p.suffix in (".html", ".pdf") for t in texts)
    values = _key_values(shown=True)
    assert values
    for key, shown in values.items():
        assert any(re.search(rf"(?<![\d.]){re.escape(s.lower())}(?!\d)", pages) for s in shown), key


def test_no_answer_of_the_key_in_any_file_of_the_student_edition(readable):
    values = _key_values()
    searched = sum(len(v) for v in values.values())
    assert searched > 40
    owner = {s.lower(): key for key, shown in values.items() for s in shown}
    # one pass over each file: every number it prints, each looked up among the key's
    number = re.compile(r"(?<![\d.])-?\d[\d,]*(?:\.\d+)?(?:e[+-]?\d+)?")
    found = set()
    for file, texts in readable.items():
        for t in texts:
            for m in number.finditer(t):
                if m.group(0) in owner:
                    found.add(f"{file.relative_to(STUDENT)}: {owner[m.group(0)]} = {m.group(0)}")
    assert not found, "answers of the key in the student edition:\n  " + "\n  ".join(sorted(found)[:40])


def test_student_edition_has_no_answers_module_and_no_teachers_page(corpus):
    names = {p.relative_to(STUDENT).as_posix() for p in corpus}
    assert not any("scara/course/answers" in n for n in names)
    assert not any(Path(n).stem == "teaching" for n in names)
    zips = [p for p in corpus if p.suffix == ".zip"]
    assert zips, "the student edition has no take-home download"
    with zipfile.ZipFile(zips[0]) as zf:
        members = zf.namelist()
    assert any(n.endswith("book/04_clik.ipynb") for n in members)
    assert not any("course/answers" in n for n in members)


def test_instructor_edition_has_the_solutions_and_the_keys():
    if not (INSTRUCTOR / "index.html").is_file():
        _unavailable("the book is not built (_build/html/index.html missing)")
    page = _html_text((INSTRUCTOR / "book" / "04_clik.html").read_text(encoding="utf-8"))
    assert "Answer key" in page and "Solution to" in page
    values = _key_values()
    shown = [s for s in values["ex-clik-fragile.kappa_max"]]
    assert shown and all(s in page for s in shown)
