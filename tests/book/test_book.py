"""The book's notebooks follow the conventions checked below (outputs cleared, a hidden assert cell, a live panel,
folded solutions, glued numbers, labels that resolve, citations in references.bib, sources a reader can open):
checked statically, so a chapter that forgets one fails here with a clear message before the build or the browser
test runs."""
import json
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
TOC = (ROOT / "_toc.yml").read_text()
NOTEBOOKS = sorted((ROOT / "book").glob("*.ipynb"))


def _cells(path):
    return json.loads(path.read_text())["cells"]


def _src(cell):
    return "".join(cell.get("source", []))


def _tags(cell):
    return cell.get("metadata", {}).get("tags", [])


def test_there_are_chapters():
    assert len(NOTEBOOKS) >= 2


@pytest.mark.parametrize("nb", NOTEBOOKS, ids=lambda p: p.name)
def test_notebook_is_in_the_toc(nb):
    assert f"book/{nb.stem}" in TOC, f"{nb.name} is not listed in _toc.yml"


@pytest.mark.parametrize("nb", NOTEBOOKS, ids=lambda p: p.name)
def test_outputs_cleared_and_kernel(nb):
    data = json.loads(nb.read_text())
    assert data["metadata"].get("kernelspec", {}).get("name") == "python3"
    stored = [i for i, c in enumerate(data["cells"]) if c["cell_type"] == "code" and (c.get("outputs") or c.get("execution_count"))]
    assert not stored, f"{nb.name}: cells {stored} carry stored outputs; clear them before committing"


@pytest.mark.parametrize("nb", [n for n in NOTEBOOKS if re.match(r"\d\d_", n.name)], ids=lambda p: p.name)
def test_chapter_conventions(nb):
    cells = _cells(nb)
    code = [c for c in cells if c["cell_type"] == "code"]
    md = "\n".join(_src(c) for c in cells if c["cell_type"] == "markdown")
    asserts = [c for c in code if "remove-cell" in _tags(c) and "assert" in _src(c)]
    assert asserts, f"{nb.name}: no hidden assert cell (tag remove-cell) checking the chapter's numbers"
    live = [i for i, c in enumerate(cells) if c["cell_type"] == "code" and "scara.widgets" in _src(c)
            and "remove-cell" not in _tags(c)]
    assert live, f"{nb.name}: no live panel cell from scara.widgets"
    hidden = [i for i in live if "remove-output" in _tags(cells[i])]
    assert not hidden, f"{nb.name}: the panels of cells {hidden} are hidden from the page (their output is the page panel)"
    assert re.search(r"^## Live panels?\b", md, re.M), f"{nb.name}: no section introduces the live panel"
    assert "{dropdown}" in md or ":class: dropdown" in md, f"{nb.name}: no folded exercise solution"
    assert "glue(" in "\n".join(_src(c) for c in code), f"{nb.name}: no glued number"


def _all_text():
    """Markdown of every page: notebook markdown cells plus the .md pages."""
    texts = {}
    for nb in NOTEBOOKS:
        texts[nb.name] = "\n".join(_src(c) for c in _cells(nb) if c["cell_type"] == "markdown")
    for md in (ROOT / "book").glob("*.md"):
        texts[md.name] = md.read_text()
    return texts


def test_every_referenced_label_is_defined():
    """Equation labels ``$$ ... $$ (eq-x)`` / ``(eq-x)=`` and figure names ``:name: fig-x`` that the text
    refers to with {eq}, {numref} or {ref} exist somewhere in the book (the build's -n checks it too, but
    this names the page and the label at once)."""
    texts = _all_text()
    defined = set()
    for t in texts.values():
        defined |= set(re.findall(r"\$\$\s*\((eq-[\w-]+)\)", t))
        defined |= set(re.findall(r"^\((\S+)\)=\s*$", t, re.M))
        defined |= set(re.findall(r":name:\s*(\S+)", t))
        defined |= set(re.findall(r":label:\s*(\S+)", t))
    missing = []
    for page, t in texts.items():
        for role, label in re.findall(r"\{(eq|numref|ref)\}`(?:[^`<]*<)?([\w-]+)>?`", t):
            if label not in defined:
                missing.append(f"{page}: {{{role}}}`{label}`")
    assert not missing, "references to labels that no page defines: " + ", ".join(missing)


def test_cited_keys_are_in_the_bibliography():
    bib = set(re.findall(r"@\w+\{([\w-]+),", (ROOT / "references.bib").read_text()))
    cited = set()
    for t in _all_text().values():
        for group in re.findall(r"\{cite(?::\w+)?\}`([^`]+)`", t):
            cited |= {k.strip() for k in group.split(",")}
    assert cited <= bib, f"cited but not in references.bib: {sorted(cited - bib)}"


#: wording that points at a document outside the repository (a reader of the book cannot open it)
_OUTSIDE = re.compile(r"\bSPEC\b|DESIGN\.md|\bthe issue\b|\bissues? \d|\bthe (?:project's )?specification\b", re.I)


def test_sources_are_in_the_repository():
    """Text and code of every page cite the book's own sections and equations, the textbook, or the page that
    states the data, never a document outside the repository."""
    pages = {nb.name: "\n".join(_src(c) for c in _cells(nb)) for nb in NOTEBOOKS}
    pages.update({md.name: md.read_text() for md in (ROOT / "book").glob("*.md")})
    found = [f"{name}: {m.group(0)!r}" for name, text in pages.items() for m in _OUTSIDE.finditer(text)]
    assert not found, "pointers outside the repository: " + ", ".join(found)


_EXERCISE = re.compile(r"```+\{exercise\}[^\n]*\n:label:\s*(\S+)")
_SOLUTION = re.compile(r"```+\{solution\}\s*(\S+)\s*\n(?::[\w-]+:[^\n]*\n)*")


@pytest.mark.parametrize("nb", [n for n in NOTEBOOKS if re.match(r"\d\d_|appendix", n.name)], ids=lambda p: p.name)
def test_exercises_are_numbered_with_folded_solutions(nb):
    """Each chapter's exercises are sphinx-exercise directives (numbered "Exercise 3.4", referable by label),
    at least four, and each has a solution folded below it (``:class: dropdown``); none is numbered by hand."""
    md = "\n".join(_src(c) for c in _cells(nb) if c["cell_type"] == "markdown")
    labels = _EXERCISE.findall(md)
    assert len(labels) >= 4, f"{nb.name}: {len(labels)} exercises written as {{exercise}} directives (at least 4)"
    solutions = {m.group(1): m.group(0) for m in _SOLUTION.finditer(md)}
    unsolved = [lab for lab in labels if lab not in solutions]
    assert not unsolved, f"{nb.name}: exercises without a solution: {unsolved}"
    unfolded = [lab for lab, head in solutions.items() if ":class: dropdown" not in head]
    assert not unfolded, f"{nb.name}: solutions not folded (:class: dropdown): {unfolded}"
    by_hand = re.findall(r"^\*\*\d+\.", md, re.M)
    assert not by_hand, f"{nb.name}: exercises numbered by hand ({by_hand[:3]}): use {{exercise}}"


def test_appendix_numbers_its_equations_and_figures_with_a_letter():
    """In the built book the appendix's equations and figures read (A.1), Fig. A.2, not (1) and Fig. 2."""
    page = ROOT / "_build" / "html" / "book" / "appendix_verification.html"
    if not page.exists():
        pytest.skip("the book is not built")
    html = page.read_text()
    eqnos = re.findall(r'class="eqno">\(([^)<]*)\)', html)
    figs = re.findall(r'class="caption-number">Fig\. ([^ <]+)', html)
    assert eqnos and figs, "the appendix has no numbered equation or figure"
    assert all(n.startswith("A.") for n in eqnos + figs), f"appendix numbers without the letter A: {eqnos + figs}"
