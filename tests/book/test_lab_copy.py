"""The chapters as JupyterLab reads them (``_ext/lab_copy.py``, the take-home copy the book's build writes) and the
kernel side they call (``scara.book``).

* the transform, on a small notebook with a resolver of known labels: glued numbers become inline expressions with
  the book's own results in the cell's metadata, captions become numbered caption cells, references become links
  with the book's text, labelled equations carry their number, hidden checks run under ``%%book_check``; an
  unknown label stops the build with its name;
* ``scara.book``: the formatter prints what myst-nb's ``{glue:text}`` prints (hypothesis, against myst-nb's own
  function), a failing check prints one line and the cell goes on;
* the take-home zip of the built book: no myst-nb role or directive is left in any chapter, every inline
  expression carries the book's result;
* every chapter, with one of its inputs edited (a waypoint's plan, the payload, a configuration, a step), runs to
  the end in a fresh kernel, and every number of its text is computed again (some differ from the book's).

Outside CI a missing build skips with the reason; with ``CI=true`` it fails.
"""
from __future__ import annotations

import json
import os
import re
import sys
import zipfile
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "_ext"))

import lab_copy  # noqa: E402

from scara.book import GLUED, UNDEFINED, UNDEFINED_TEXT, book_check, format_plain_text, glue, glued  # noqa: E402

HTML = Path(os.environ.get("SCARA_BOOK_HTML", ROOT / "_build" / "html"))
ZIP = HTML / "_downloads" / "scara-course.zip"
IN_CI = os.environ.get("CI", "").lower() == "true"
RAW = re.compile(r"\{(glue[:a-z]*|numref|eq|ref|doc|cite[:a-z]*)\}`")


# ------------------------------------------------------------------------------------------------ the transform
def _resolver(docname="book/03_trajectory"):
    known = {("numref", "fig-a"): ("book/03_trajectory", "Fig. 3.1"),
             ("numref", "fig-other"): ("book/01_kinematics", "Fig. 1.2"),
             ("numref", "ex-a"): ("book/03_trajectory", "Exercise 3.4"),
             ("eq", "eq-a"): ("book/03_trajectory", "(3.6)"),
             ("eq", "eq-far"): ("book/01_kinematics", "(1.6)"),
             ("ref", "sec-a"): ("book/06_control", "Side by side")}
    return lab_copy.Resolver(
        docname, lookup=lambda kind, label: known.get((kind, label)),
        titles={"book/notation": "Notation", "book/01_kinematics": "1. Kinematics"},
        files={"book/01_kinematics": "01_kinematics.ipynb", "book/03_trajectory": "03_trajectory.ipynb",
               "book/06_control": "06_control.ipynb", "book/notation": "notation.md",
               "book/references": "references.md"},
        citations={"siciliano2009": "Siciliano et al. 2009", "khatib1987": "Khatib 1987"}, chapter="3")


def _nb(*cells):
    return {"cells": [dict(cell_type=t, source=s, metadata=m, **({"outputs": [{"x": 1}], "execution_count": 3}
                                                                  if t == "code" else {}))
                      for t, s, m in cells], "metadata": {}, "nbformat": 4, "nbformat_minor": 5}


def test_the_copy_reads_as_the_book():
    nb = _nb(("markdown", "# Title\n\nSee {numref}`fig-a`, {numref}`fig-other`, {eq}`eq-a`, {eq}`eq-far`, "
                          "{numref}`ex-a`, {ref}`the table <sec-a>`, {doc}`notation`, {doc}`chapter 1 <01_kinematics>` "
                          "and {cite}`siciliano2009,khatib1987`; [that section](sec-a).", {}),
             ("code", "from scara.book import glue\nglue('v', 0.05625, display=False)", {"tags": ["hide-input"]}),
             ("code", "assert v > 0\nglue('w', 2.5, display=False)", {"tags": ["remove-cell"]}),
             ("markdown", "Speed {glue:text}`v:.4f` m/s and {glue:text}`w`.\n\n$$\nx = 1\n$$ (eq-a)\n", {}),
             ("markdown", "```{glue:figure} fig-a\n:name: fig-a\n\nThe caption, with {eq}`eq-a`.\n```", {}))
    glued = {"v": {"text/plain": "0.05625"}, "w": {"text/plain": "2.5"}}
    out = lab_copy.lab_notebook(nb, _resolver(), glued)
    assert nb["cells"][1]["outputs"] == [{"x": 1}], "the source notebook was changed"
    md = [c["source"] for c in out["cells"] if c["cell_type"] == "markdown"]
    assert md[0].startswith('---\nnumbering:\n  equation: false\n  enumerator: "3.%s"\n---\n# Title')
    assert ("See [Fig. 3.1](#fig-a), [Fig. 1.2](01_kinematics.ipynb#fig-other), [(3.6)](#eq-a), "
            "[(1.6)](01_kinematics.ipynb#eq-far), [Exercise 3.4](#ex-a), [the table](06_control.ipynb#sec-a), "
            "[Notation](notation.md), [chapter 1](01_kinematics.ipynb) and "
            "[\\[Siciliano et al. 2009; Khatib 1987\\]](references.md); [that section](06_control.ipynb#sec-a).") in md[0]
    assert md[1] == ('Speed {eval}`glued("v", ".4f")` m/s and {eval}`glued("w")`.\n\n(eq-a)=\n$$\nx = 1\n'
                     '\\tag{3.6}\n$$\n')
    results = out["cells"][3]["metadata"]["user_expressions"]
    assert results == [
        {"expression": 'glued("v", ".4f")', "result": {"status": "ok", "data": {"text/plain": "'0.0563'"}, "metadata": {}}},
        {"expression": 'glued("w")', "result": {"status": "ok", "data": {"text/plain": "'2.5'"}, "metadata": {}}}]
    assert md[2] == "(fig-a)=\n**Fig. 3.1.** The caption, with [(3.6)](#eq-a)."
    code = [c for c in out["cells"] if c["cell_type"] == "code"]
    assert all(c["outputs"] == [] and c["execution_count"] is None for c in code)
    assert code[0]["source"].startswith(lab_copy.LOAD_MAGIC + "\nfrom scara.book import glue")
    assert code[1]["source"].startswith("%%book_check\nassert v > 0")
    assert all(c["metadata"]["jupyter"]["source_hidden"] for c in code)


def test_a_download_link_becomes_a_link_to_the_file_beside_the_chapter():
    text = ('Files: <a class="reference download" href="../_downloads/scara.urdf" download>scara.urdf</a> and\n'
            '<a class="reference download" href="../_downloads/scara.xml" download>the MJCF</a>.')
    out = lab_copy.lab_notebook(_nb(("markdown", text, {})), _resolver(), {})
    assert out["cells"][0]["source"].endswith("Files: [scara.urdf](scara.urdf) and\n[the MJCF](scara.xml).")


@pytest.mark.parametrize("text, what", [("{numref}`fig-missing`", "fig-missing"), ("{eq}`eq-missing`", "eq-missing"),
                                        ("{cite}`nobody2020`", "nobody2020"), ("{doc}`nowhere`", "book/nowhere")])
def test_an_unknown_label_stops_the_build_with_its_name(text, what):
    with pytest.raises(KeyError, match=re.escape(what)):
        lab_copy.lab_notebook(_nb(("markdown", text, {})), _resolver(), {})


def test_short_citations():
    from pybtex.database import parse_string

    bib = parse_string("""@book{a, author = {Siciliano, Bruno and Sciavicco, Lorenzo and Villani, Luigi}, year = {2009}}
                          @article{b, author = {Khatib, Oussama}, year = {1987}}
                          @article{c, author = {Slotine, J.-J. E. and Li, Weiping}, year = {1987}}""", "bibtex")
    assert [lab_copy.short_citation(bib.entries[k]) for k in "abc"] == [
        "Siciliano et al. 2009", "Khatib 1987", "Slotine and Li 1987"]


# ------------------------------------------------------------------------------------------------ scara.book
_SPECS = st.sampled_from(["", ".0f", ".1f", ".2f", ".4f", ".3g", ".4g", ".2e", ".1%", "+.3f", ",.0f", "d", ".0%"])


@given(value=st.one_of(st.floats(allow_nan=False, allow_infinity=False, min_value=-1e12, max_value=1e12),
                       st.integers(-10**9, 10**9)), spec=_SPECS)
def test_numbers_print_as_myst_nb_prints_them(value, spec):
    from myst_nb.core.variables import format_plain_text as myst_format

    text = repr(value)
    if spec == "d" and isinstance(value, float):
        spec = ".1f"
    assert format_plain_text(text, spec) == myst_format(text, spec)


def test_glued_values_print_as_the_book_prints_them():
    glue("test_speed", 0.05625, display=False)
    glue("test_name", "p1", display=False)
    assert glued("test_speed", ".4f") == "0.0563" and glued("test_name") == "p1"
    with pytest.raises(KeyError, match="'never_glued'.*run the chapter's cells above"):
        glued("never_glued")
    assert GLUED["test_speed"] == 0.05625


def test_a_numpy_scalar_is_glued_as_a_plain_number():
    """A numpy scalar's text is 'np.float64(2.87...)' wherever the kernel has no formatter for it, which the book's
    build cannot read as a number: glue stores the Python number it holds (an array stays an array)."""
    glue("test_np_float", np.float64(2.5) / np.float64(3.0), display=False)
    glue("test_np_int", np.int64(7), display=False)
    glue("test_np_array", np.array([1.0, 2.0]), display=False)
    assert type(GLUED["test_np_float"]) is float and GLUED["test_np_float"] == 2.5 / 3.0
    assert type(GLUED["test_np_int"]) is int and GLUED["test_np_int"] == 7
    assert isinstance(GLUED["test_np_array"], np.ndarray)


def test_a_failing_check_prints_one_line_and_the_cell_goes_on(capsys):
    ns = {}
    cell = ("a = 1\nassert a == 2, 'the book says 2'\nfor k in range(3):\n    assert k < 1\nc = [][0]\nb = a + 1\n"
            "glue('test_after', b, display=False)\n")
    notes = book_check("", cell, dict(ns, glue=glue))
    assert notes == ["line 2: does not hold", "line 3: does not hold",
                     "line 5: failed (IndexError: list index out of range)"]
    printed = capsys.readouterr().out.strip().splitlines()
    assert len(printed) == 1 and "(line 2: does not hold and 2 more)" in printed[0]
    assert GLUED["test_after"] == 2  # the statements after the failures ran
    # a number the failing statement would have glued reads as not defined, with the reason printed above
    book_check("", "glue('test_never', [][0], display=False)\nfor k in 'ab':\n    glue(f'test_{k}_x', 1 / 0)\n",
               dict(glue=glue))
    capsys.readouterr()
    assert glued("test_never") == UNDEFINED_TEXT and UNDEFINED["test_never"].startswith("line 1: failed (IndexError")
    assert glued("test_b_x") == UNDEFINED_TEXT and UNDEFINED["test_.+_x"].startswith("line 2: failed (ZeroDivision")
    glue("test_never", 1.5, display=False)
    assert glued("test_never") == "1.5"
    with pytest.raises(KeyError):
        glued("test_b_y")
    assert book_check("", "x = 1\nassert x == 1\n", {}) == [] and capsys.readouterr().out == ""


# ------------------------------------------------------------------------------------------------ the built copy
@pytest.fixture(scope="module")
def copies() -> dict:
    if not ZIP.is_file():
        reason = f"the book is not built ({ZIP} missing): run jupyter-book build . first"
        if IN_CI:
            pytest.fail(reason)
        pytest.skip(reason)
    with zipfile.ZipFile(ZIP) as zf:
        return {Path(n).name: json.loads(zf.read(n)) for n in zf.namelist() if n.endswith(".ipynb")}


def test_no_role_of_the_book_is_left_and_every_number_shows_before_a_run(copies):
    for name, nb in copies.items():
        for k, cell in enumerate(nb["cells"]):
            if cell["cell_type"] != "markdown":
                continue
            src = cell["source"]
            assert not RAW.search(src), f"{name} cell {k}: {RAW.search(src).group(0)} left"
            assert "{glue:figure}" not in src and "{glue:" not in src, f"{name} cell {k}: a glue directive left"
            exprs = re.findall(r"\{eval\}`([^`]*)`", src)
            have = {e["expression"] for e in cell["metadata"].get("user_expressions", [])}
            assert set(exprs) == have, f"{name} cell {k}: no book result for {sorted(set(exprs) - have)}"


#: one input of each chapter to edit: (text in the chapter's code, what a learner types instead)
EDITS = {
    "01_kinematics.ipynb": ("p = ScaraParams()  #", "p = ScaraParams(a1=0.45)  #"),
    "02_manipulability.ipynb": ("p = ScaraParams()", "p = ScaraParams(a2=0.45)"),
    "03_trajectory.ipynb": ("traj = reference_trajectory()  #", "traj = reference_trajectory(dt=2e-3)  #"),
    "04_clik.ipynb": ("traj = reference_trajectory()  ", "traj = reference_trajectory(dt=2e-3)  "),
    "05_dynamics.ipynb": ("p5 = p.with_payload(5.0)", "p5 = p.with_payload(3.0)"),
    "06_control.ipynb": ("plant = model.with_payload(5.0)", "plant = model.with_payload(2.0)"),
    "07_interaction.ipynb": ("surface = Surface()  #", "surface = Surface(stiffness=3e4)  #"),
    "appendix_verification.ipynb": ("h = 1e-6", "h = 1e-5"),
}


def test_every_chapter_has_an_edit(copies):
    chapters = {n for n in copies if n[:2].isdigit() or n.startswith("appendix")}
    assert chapters == set(EDITS)


@pytest.mark.parametrize("name", sorted(EDITS))
def test_an_edited_chapter_runs_to_the_end_and_its_numbers_follow(name, copies, tmp_path):
    import nbformat
    from nbclient import NotebookClient

    nb = json.loads(json.dumps(copies[name]))
    old, new = EDITS[name]
    hits = [c for c in nb["cells"] if c["cell_type"] == "code" and old in c["source"]]
    assert len(hits) == 1, f"{name}: the edit's text {old!r} is in {len(hits)} cells"
    hits[0]["source"] = hits[0]["source"].replace(old, new)
    book = {}
    for cell in nb["cells"]:
        for e in cell["metadata"].get("user_expressions", []):
            book[e["expression"]] = e["result"]["data"]
    # the text's numbers, computed again at the end of the run (as JupyterLab does when each text cell runs)
    nb["cells"].append({"cell_type": "code", "metadata": {}, "outputs": [], "execution_count": None, "source": (
        "import json as _j\n_out = {}\nfor _e in %r:\n    try:\n        _out[_e] = str(eval(_e))\n"
        "    except Exception as _x:\n        _out[_e] = 'ERROR ' + repr(_x)\nprint(_j.dumps(_out))" % sorted(book))})
    node = nbformat.from_dict(nb)
    with zipfile.ZipFile(ZIP) as zf:  # run in the unpacked course, beside the files the chapters read
        zf.extractall(tmp_path)
    client = NotebookClient(node, timeout=600, kernel_name="python3", allow_errors=True,
                            resources={"metadata": {"path": str(tmp_path / "scara-course" / "book")}})
    client.execute()
    errors = [f"cell {k} ({c.source.splitlines()[1 if c.source.startswith('%%') else 0][:60]!r}): "
              f"{o['ename']}: {o['evalue'][:200]}"
              for k, c in enumerate(node.cells) if c.cell_type == "code" for o in c.get("outputs", [])
              if o.get("output_type") == "error"]
    assert not errors, f"{name}: {len(errors)} cells failed after the edit:\n" + "\n".join(errors)
    printed = "".join(o.get("text", "") for o in node.cells[-1].outputs if o.get("output_type") == "stream")
    last = json.loads(printed.strip().splitlines()[-1])
    assert set(last) == set(book)
    failed = {e: v for e, v in last.items() if v.startswith("ERROR")}
    assert not failed, f"{name}: {len(failed)} numbers of the text are not computed after the edit: {failed}"
    undefined = [e for e, v in last.items() if v == UNDEFINED_TEXT]
    print(f"{name}: {len(book)} numbers in the text, {len(undefined)} not defined for the edited input: {undefined}")
    changed = [e for e in book if "text/plain" in book[e] and repr(last[e]) != book[e]["text/plain"]]
    assert changed or not book, f"{name}: no number of the text changed after the edit"


def test_a_chapter_that_opens_with_a_check_loads_the_magic_first():
    nb = _nb(("markdown", "# T", {}), ("code", "assert True", {"tags": ["remove-cell"]}), ("code", "x = 1", {}))
    code = [c["source"] for c in lab_copy.lab_notebook(nb, _resolver(), {})["cells"] if c["cell_type"] == "code"]
    assert code == [lab_copy.LOAD_MAGIC, "%%book_check\nassert True", "x = 1"]
    assert lab_copy.lab_notebook(nb, _resolver(), {})["cells"][1]["id"] == "scara-book-load"


def test_the_first_cell_names_the_panels_the_chapter_builds():
    nb = _nb(("markdown", "# T", {}), ("code", "from scara.widgets import control_panel, clik_panel", {}),
             ("code", "clik_panel(traj)\npanel = control_panel(traj, keep=True)", {}))
    code = [c["source"] for c in lab_copy.lab_notebook(nb, _resolver(), {})["cells"] if c["cell_type"] == "code"]
    assert code[0] == ("import scara.book; scara.book.load_ipython_extension(get_ipython(), "
                       "panels=('clik_panel', 'control_panel'))\nfrom scara.widgets import control_panel, clik_panel")
    # only the builders a cell calls: an import alone, or a name in the text, starts nothing
    nb = _nb(("code", "from scara.widgets import control_panel", {}))
    assert lab_copy.lab_notebook(nb, _resolver(), {})["cells"][0]["source"].startswith(lab_copy.LOAD_MAGIC + "\n")


def test_every_panel_builder_names_its_page_program_for_the_compile_ahead():
    import importlib

    import scara.widgets as widgets
    from scara.book import AHEAD_BUILDERS

    builders = {n for n in dir(widgets) if n.endswith("_panel") or n == "waypoint_editor"}
    assert set(AHEAD_BUILDERS) == builders
    for name, kernels in AHEAD_BUILDERS.items():
        module = importlib.import_module(getattr(widgets, name).__module__)
        declaration = getattr(module, re.sub(r"(_panel)?$", "_declaration", name, count=1))()
        page = declaration.page
        assert kernels[0] is page.kernel, name                  # the program first
        assert page.prepare is None or page.prepare in kernels, name


def test_compile_ahead_compiles_a_panel_into_the_cache_in_the_background(tmp_path, monkeypatch):
    from scara import book
    from scara.programs.dynamics import dynamics_program

    monkeypatch.setenv("NUMBA_CACHE_DIR", str(tmp_path / "cache"))
    monkeypatch.delenv(book.AHEAD_CHILD, raising=False)
    assert not book.compile_ahead(())
    with pytest.raises(ValueError, match="not_a_panel"):
        book.compile_ahead(["not_a_panel"])
    try:
        assert book.compile_ahead(["dynamics_panel", "dynamics_panel"])
        assert not book.compile_ahead(["clik_panel"])           # one process at a time
        assert book._AHEAD["kernels"] == ("scara.programs.dynamics.dynamics_program",)
        folder = book._AHEAD["folder"]
        book.wait_compiled(book.wait_compiled, timeout=0.0)     # not asked for: no wait
        book.wait_compiled(dynamics_program, timeout=120.0)
        assert (folder / "scara.programs.dynamics.dynamics_program").exists()
        assert book._AHEAD["process"].wait(timeout=60) == 0
        assert list((tmp_path / "cache").rglob("*dynamics_program*.nbi"))
    finally:
        book._stop_ahead()
    assert not folder.exists() and "process" not in book._AHEAD


def test_compile_ahead_steps_aside_without_the_panels_packages(monkeypatch):
    import scara
    from scara import book

    monkeypatch.delenv(book.AHEAD_CHILD, raising=False)
    monkeypatch.setitem(sys.modules, "scara.widgets", None)   # import scara.widgets raises ImportError
    monkeypatch.delattr(scara, "widgets", raising=False)
    assert not book.compile_ahead(["control_panel"])
    assert "process" not in book._AHEAD


def test_a_markdown_page_reads_as_the_book():
    entries = {"siciliano2009": ("Siciliano et al. 2009", "book", "Bruno Siciliano\\. *Robotics*\\. 2009\\."),
               "khatib1987": ("Khatib 1987", "article", "Oussama Khatib\\. A unified approach\\. 1987\\.")}
    text = ("# References\n\n```{bibliography}\n:filter: type == \"book\"\n```\n\nPapers:\n\n"
            "```{bibliography}\n:filter: type != \"book\"\n```\n\nSee {cite}`siciliano2009` and {eq}`eq-far`.\n")
    out = lab_copy.lab_markdown(text, _resolver("book/references"), entries)
    assert out == ("# References\n\n- **[Siciliano et al. 2009]** Bruno Siciliano\\. *Robotics*\\. 2009\\.\n\nPapers:\n\n"
                   "- **[Khatib 1987]** Oussama Khatib\\. A unified approach\\. 1987\\.\n\n"
                   "See [\\[Siciliano et al. 2009\\]](#) and [(1.6)](01_kinematics.ipynb#eq-far).\n")


def test_the_markdown_pages_of_the_copy_carry_no_role_or_directive(copies):
    with zipfile.ZipFile(ZIP) as zf:
        pages = {Path(n).name: zf.read(n).decode() for n in zf.namelist() if n.endswith(".md") and "/book/" in n}
    assert set(pages) == {"notation.md", "references.md"}, "the introduction is a notebook in the copy"
    for name, text in pages.items():
        assert not RAW.search(text), f"{name}: {RAW.search(text).group(0)} left"
        assert "{bibliography}" not in text and "```{" not in text, f"{name}: a directive left"
    bib = len(re.findall(r"^@", (ROOT / "references.bib").read_text(), re.M))
    assert pages["references.md"].count("- **[") == bib, "every entry of the bibliography is listed once"
