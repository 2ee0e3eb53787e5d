"""The course as a teacher runs it: the exercises as data against the book's text, the student edition's sources,
the assignments and the offline grading of honest and hostile submissions."""
import csv
import json
import math
import re
import shutil
import subprocess
import sys
from pathlib import Path

import nbformat
import pytest

from scara.course import edition
from scara.course.assign import answer_variable, assign, assignable, read_roster, read_secret
from scara.course.exercises import DOCNAMES, Answer, Param, catalog, chapter_exercises, draw, exercise, solve
from scara.course.statement import BLOCK, book_folder, references, statement
from scara.errors import ScaraError

ROOT = Path(__file__).resolve().parents[2]
BOOK = ROOT / "book"
SECRET = b"0123456789abcdef-course-secret-for-tests"


def _markdown(docname):
    nb = json.loads((BOOK / f"{docname}.ipynb").read_text(encoding="utf-8"))
    return nb, "\n\n".join("".join(c["source"]) for c in nb["cells"] if c["cell_type"] == "markdown")


def _glue_keys(text):
    return set(re.findall(r"\{glue:text\}`([^`:]+)(?::[^`]*)?`", text))


# ---- the exercises as data against the book ------------------------------------------------------------------
@pytest.mark.parametrize("docname", list(DOCNAMES))
def test_catalog_lists_every_exercise_in_the_books_order(docname):
    _, text = _markdown(docname)
    labels = [re.search(r"^:label:\s*(\S+)", m.group("options"), re.M).group(1) for m in BLOCK.finditer(text)]
    declared = [ex.label for ex in chapter_exercises(docname)]
    assert declared == labels
    refs = references(str(BOOK))
    for ex in chapter_exercises(docname):  # the number the key and the assignments print is the book's
        assert refs[ex.label] == f"Exercise {ex.number}"


@pytest.mark.parametrize("docname", list(DOCNAMES))
def test_statements_and_solutions_take_their_numbers_from_the_data(docname):
    nb, text = _markdown(docname)
    blocks = {re.search(r"^:label:\s*(\S+)", m.group("options"), re.M).group(1): m.group("body")
              for m in BLOCK.finditer(text)}
    solutions = {m.group(2): m.group(3) for m in re.finditer(
        r"^(`{3,}|:{3,})\{solution\}\s*(\S+)[^\n]*\n(.*?)^\1", text, re.M | re.S)}
    for ex in chapter_exercises(docname):
        shown = _glue_keys(blocks[ex.label])
        for p in ex.params:  # a student must read each of their own numbers in the statement
            if p.varies:
                assert ex.key(p.name) in shown, f"{ex.label}: the statement does not show {p.name}"
        if ex.numeric:
            quoted = _glue_keys(solutions[ex.label])
            for a in ex.answers:  # and the worked solution quotes the computed answer
                assert ex.key(a.name) in quoted, f"{ex.label}: the solution does not quote {a.name}"
    # every number glued under an exercise's name is one it declares or computes
    results = {ex.label: set(solve(ex.label)) | {p.name for p in ex.params}
               for ex in chapter_exercises(docname) if ex.numeric}
    params = {ex.label: {p.name for p in ex.params} for ex in chapter_exercises(docname)}
    for key in _glue_keys(text):
        owner, _, name = key.rpartition(".")
        if owner in params:
            assert name in results.get(owner, params[owner]), f"{key} is glued by nothing"


def test_every_numeric_exercise_answers_its_book_numbers():
    for ex in catalog().values():
        if ex.numeric:
            out = solve(ex.label)
            assert all(isinstance(out[a.name], float) for a in ex.answers)


def test_params_and_answers_refuse_bad_declarations():
    with pytest.raises(ScaraError, match="not on the grid"):
        Param("m", 0.33, low=0.0, high=1.0, step=0.1)
    with pytest.raises(ScaraError, match="low, high and step together"):
        Param("m", 0.3, low=0.0)
    with pytest.raises(ScaraError, match="tolerance must be positive"):
        Answer("x", "x", tolerance=0.0)
    a = Answer("x", "x", "mm", 0.5, absolute=True)
    assert a.matches(10.0, 10.4) and not a.matches(10.0, 10.6) and not a.matches(10.0, "10")
    assert not a.matches(10.0, float("nan")) and not a.matches(10.0, None)
    r = Answer("y", "y", tolerance=0.01)
    assert r.matches(-200.0, -201.9) and not r.matches(-200.0, -202.1) and not r.matches(-200.0, 200.0)
    assert Param("k", 0.25, low=0.1, high=0.4, step=0.05).values() == [0.1, 0.15, 0.2, 0.25, 0.3, 0.35, 0.4]


def test_draws_are_keyed_by_the_secret_and_checked():
    ex = exercise("ex-clik-lag")
    a = draw(ex, SECRET, "s001")
    assert a == draw(ex, SECRET, "s001")  # the same id and secret: the same numbers
    drawn = {tuple(sorted(draw(ex, SECRET, f"s{i:03d}")[0].items())) for i in range(30)}
    assert len(drawn) > 20  # the draw spreads over the range
    other = {tuple(sorted(draw(ex, b"another-secret-of-the-course", f"s{i:03d}")[0].items())) for i in range(30)}
    assert drawn != other
    for params in drawn:
        p = dict(params)
        assert 0.5 <= p["A"] <= 3.0 and 200 <= p["K"] <= 900


def test_statement_is_the_books_with_the_students_numbers():
    title, text = statement("ex-clik-lag", {"A": 2.3, "K": 650.0})
    assert "2.3 m/s²" in text and "650 s⁻¹" in text and "{" not in text
    _, book_text = statement("ex-clik-lag")
    assert "1.0 m/s²" in book_text and "400 s⁻¹" in book_text


# ---- the student edition's sources ----------------------------------------------------------------------------
def test_student_notebook_has_no_solution():
    nb = {"cells": [
        {"cell_type": "markdown", "metadata": {}, "source": "text\n\n```{solution} ex-a\n:class: dropdown\n\nsecret "
                                                            "words\n```\nafter"},
        {"cell_type": "markdown", "metadata": {}, "source": "````{solution} ex-b\nwith ```code``` inside\n````\n"},
        {"cell_type": "code", "metadata": {"tags": ["remove-cell", "solution"]}, "source": "x = 1", "outputs": []},
        {"cell_type": "code", "metadata": {"tags": ["remove-cell"]}, "source": "y = 2", "outputs": []}]}
    out = edition.student_notebook(nb)
    assert [c["source"] if isinstance(c["source"], str) else "".join(c["source"]) for c in out["cells"]] == [
        "text\n\nafter", "y = 2"]
    with pytest.raises(ScaraError, match="not closed"):
        edition.strip_solutions("```{solution} ex-a\nnever closed\n")


def test_student_source_never_empties_a_folder_it_did_not_write(tmp_path):
    (tmp_path / "mine").mkdir()
    (tmp_path / "mine" / "thesis.tex").write_text("years of work")
    with pytest.raises(ScaraError, match="refusing to empty"):
        edition.write_student_source(tmp_path / "mine")
    assert (tmp_path / "mine" / "thesis.tex").read_text() == "years of work"
    with pytest.raises(ScaraError, match="over the sources"):
        edition.write_student_source(ROOT)


def test_student_source_holds_no_solution_and_no_answers(tmp_path):
    out = edition.write_student_source(tmp_path / "student")
    assert not (out / "scara" / "course" / "answers").exists()
    assert not any(p.stem in edition.INSTRUCTOR_PAGES for p in (out / "book").iterdir())
    assert "teaching" not in (out / "_toc.yml").read_text()
    for nb_path in (out / "book").glob("*.ipynb"):
        nb = json.loads(nb_path.read_text(encoding="utf-8"))
        for cell in nb["cells"]:
            text = "".join(cell["source"])
            assert "{solution}" not in text and "glue_solution" not in text and "answer_key" not in text
            assert "solution" not in cell.get("metadata", {}).get("tags", [])


def _executed_cache(folder, change=None):
    """An execution cache as the book's build leaves it (jupyter-cache): each chapter run, each code cell given an
    output; ``change`` (a file name) is cached with its last code cell's source changed (an older version)."""
    from jupyter_cache import get_cache
    from jupyter_cache.base import CacheBundleIn

    cache = get_cache(str(folder))
    for page in BOOK.glob("*.ipynb"):
        nb = nbformat.read(page, as_version=4)
        code = [c for c in nb.cells if c.cell_type == "code"]
        for k, cell in enumerate(code):
            cell.outputs = [nbformat.v4.new_output("stream", name="stdout", text=f"ran {page.stem} {k}\n")]
        if page.name == change:
            code[-1].source = "an older version"
        cache.cache_notebook_bundle(CacheBundleIn(nb, str(page)), check_validity=False, overwrite=True)
    return folder


def test_student_source_keeps_the_outputs_of_the_books_build(tmp_path):
    """The chapters keep the build's outputs (a solution's cell leaves with its own), and the edition's configuration
    executes none of them, only the Markdown pages."""
    executed = edition.executed_notebooks(cache=_executed_cache(tmp_path / "cache"))
    assert sorted(executed) == sorted(p.name for p in BOOK.glob("*.ipynb") if p.stem not in edition.INSTRUCTOR_PAGES)
    out = edition.write_student_source(tmp_path / "student", executed=executed)
    for name, nb in executed.items():
        source = json.loads((BOOK / name).read_text(encoding="utf-8"))
        assert [(c["cell_type"], c["source"]) for c in nbformat.reads(json.dumps(nb), 4).cells] == [
            (c["cell_type"], "".join(c["source"])) for c in source["cells"]]     # the source's own cells
        kept = json.loads((out / "book" / name).read_text(encoding="utf-8"))
        assert kept["cells"] == edition.student_notebook(nb)["cells"]
        ran = ["".join(o["text"]) for c in kept["cells"] if c["cell_type"] == "code" for o in c["outputs"]]
        assert ran and all(t.startswith(f"ran {Path(name).stem} ") for t in ran)
    config = (out / "_config.yml").read_text()
    assert 'exclude_patterns: ["book/*.ipynb"]' in config.split("\nexecute:", 1)[1].split("\n\n", 1)[0]
    assert (ROOT / "_config.yml").read_text().count("exclude_patterns: []") == 1   # the book executes every chapter
    # without outputs given, the edition's build executes the chapters as the book's does
    plain = edition.write_student_source(tmp_path / "plain")
    assert (plain / "_config.yml").read_text() == (ROOT / "_config.yml").read_text()


def test_student_source_refuses_outputs_of_another_version(tmp_path):
    with pytest.raises(ScaraError, match="left no execution cache"):
        edition.executed_notebooks(cache=tmp_path / "none")
    cache = _executed_cache(tmp_path / "cache", change="03_trajectory.ipynb")
    with pytest.raises(ScaraError, match="holds no run of book/03_trajectory.ipynb as it stands"):
        edition.executed_notebooks(cache=cache)


def test_a_cell_that_reads_a_solutions_name_stops_the_reuse_of_outputs():
    def cell(source, solution=False):
        return {"cell_type": "code", "source": source, "outputs": [],
                "metadata": {"tags": ["remove-cell", "solution"] if solution else []}}

    nb = {"cells": [cell("import numpy as np\np = 1"), cell("ex = p + 1\nf = lambda d: d", solution=True),
                    cell("%%book_check\nprint(np.pi, p, [k for k in range(3)])"), cell("def g(ex):\n    return ex"),
                    cell("y = ex * 2")]}
    assert edition.solution_dependencies(nb) == {4: {"ex"}}
    nb["cells"][3]["source"] = "ex = 0"   # defined outside the solutions too: the student's cells have it
    assert edition.solution_dependencies(nb) == {}
    for page in BOOK.glob("*.ipynb"):     # the book's chapters: none
        assert edition.solution_dependencies(json.loads(page.read_text(encoding="utf-8"))) == {}, page.name


# ---- assignments ----------------------------------------------------------------------------------------------
def _roster(path, n):
    with open(path, "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["id", "name"])
        for i in range(n):
            w.writerow([f"stu-{i:03d}", f"Student {i}"])
    return path


def test_roster_and_secret_are_checked(tmp_path):
    (tmp_path / "bad.csv").write_text("name\nAda\n")
    with pytest.raises(ScaraError, match="column 'id'"):
        read_roster(tmp_path / "bad.csv")
    (tmp_path / "dup.csv").write_text("id\na1\na1\n")
    with pytest.raises(ScaraError, match="row 3.*given twice"):
        read_roster(tmp_path / "dup.csv")
    (tmp_path / "path.csv").write_text("id\n../etc\n")
    with pytest.raises(ScaraError, match="row 2"):
        read_roster(tmp_path / "path.csv")
    (tmp_path / "short").write_text("abc\n")
    with pytest.raises(ScaraError, match="at least 16"):
        read_secret(tmp_path / "short")
    # the command says so in one line, with no traceback
    (tmp_path / "secret").write_bytes(SECRET)
    for roster, secret, said in (("bad.csv", "secret", "column 'id'"), ("dup.csv", "short", "at least 16")):
        run = subprocess.run([sys.executable, "-m", "scara.course", "assign", "--roster", str(tmp_path / roster),
                              "--secret-file", str(tmp_path / secret), "--out", str(tmp_path / "o")],
                             capture_output=True, text=True)
        assert run.returncode == 2 and "Traceback" not in run.stderr and said in run.stderr, run.stderr


def test_assignments_are_personal_reproducible_and_keep_the_secret(tmp_path):
    roster = _roster(tmp_path / "roster.csv", 30)
    labels = ["ex-clik-lag"]
    key = assign(roster, SECRET, tmp_path / "a", labels, log=lambda *a: None)
    again = assign(roster, SECRET, tmp_path / "b", labels, log=lambda *a: None)
    assert key["students"] == again["students"]
    sets = {json.dumps(s["params"], sort_keys=True) for s in key["students"].values()}
    assert len(sets) == 30  # no two students share a parameter set
    for sid, s in key["students"].items():
        nb = nbformat.read(tmp_path / "a" / sid / "assignment.ipynb", as_version=4)
        assert nb.metadata["scara"]["student"] == sid
        text = "\n".join(c.source for c in nb.cells)
        p = s["params"]["ex-clik-lag"]
        assert f"{p['A']:.1f} m/s²" in text and f"{p['K']:.0f} s⁻¹" in text
        var = answer_variable(exercise("ex-clik-lag"), "lag_um")
        assert f"{var} = None" in text
        expected = s["answers"][var]["expected"]
        assert expected == pytest.approx(1e-3 * p["A"] / p["K"] * 1e6, rel=1e-6)  # T A / K, in µm
    for f in (tmp_path / "a").rglob("*"):
        if f.is_file() and "_mathjax" not in f.parts:
            assert SECRET not in f.read_bytes(), f
    html = (tmp_path / "a" / "stu-000" / "assignment.html").read_text()
    assert '<script src="../_mathjax/tex-chtml.js' in html or 'src="../_mathjax/tex-chtml.js' in html
    assert not re.search(r'<script[^>]+src="https?:', html)
    # MathJax 3 (the offline copy) is told to read $...$ before it loads
    assert html.index("inlineMath: [['$', '$']") < html.index('src="../_mathjax/tex-chtml.js"')
    assert (tmp_path / "a" / "_mathjax" / "tex-chtml.js").is_file()


def test_only_numeric_exercises_with_their_own_numbers_can_be_set(tmp_path):
    arguments = [ex for ex in catalog().values() if not ex.numeric]
    for ex in arguments:
        assert not assignable(ex)
    if arguments:
        with pytest.raises(ScaraError, match="argument"):
            assign(_roster(tmp_path / "r.csv", 1), SECRET, tmp_path / "o", [arguments[0].label], log=lambda *a: None)


@pytest.mark.parametrize("docname", list(DOCNAMES))
def test_every_numeric_exercise_draws_thirty_meaningful_sets(docname):
    for ex in chapter_exercises(docname):
        if ex.numeric:
            for i in range(30):
                params, results = draw(ex, SECRET, f"s{i:03d}")
                assert all(math.isfinite(results[a.name]) for a in ex.answers), (ex.label, params)
                for p in ex.params:
                    assert params[p.name] in p.values(), (ex.label, p.name)


def test_every_settable_exercise_draws_for_a_class(tmp_path):
    settable = [ex for ex in catalog().values() if assignable(ex)]
    assert settable
    key = assign(_roster(tmp_path / "roster.csv", 3), SECRET, tmp_path / "a", None, log=lambda *a: None)
    assert key["exercises"] == [ex.label for ex in settable]
    for sid in key["students"]:
        nb = nbformat.read(tmp_path / "a" / sid / "assignment.ipynb", as_version=4)
        assert "{glue" not in "\n".join(c.source for c in nb.cells)


# ---- grading, with hostile submissions --------------------------------------------------------------------------
HONEST = """
from types import SimpleNamespace
A, K = {A}, {K}
dt, n = 1e-3, 301
t = np.arange(n) * dt
ramp = SimpleNamespace(t=t, x=np.tile([0.4, -0.3, 0.7, 0.2], (n, 1)), xd=np.zeros((n, 4)), xdd=np.zeros((n, 4)), dt=dt)
ramp.x[:, 2] -= 0.5 * A * t**2
ramp.xd[:, 2] = -A * t
ramp.xdd[:, 2] = -A
run = scara.clik2(ramp, *scara.second_order_gains(np.array([400.0, 400.0, K, 100.0])))
{var} = abs(run.e[-1, 2]) * 1e6
"""

SNOOP = """
import os, glob
found = []
markers = {markers!r}
for path in {paths!r}:
    if os.path.exists(path):
        found.append("exists " + path)
for name, value in os.environ.items():
    if any(m in name or m in value for m in markers):
        found.append("env " + name)
for pid in os.listdir("/proc"):
    if pid.isdigit():
        for part in ("environ", "cmdline"):
            try:
                data = open(f"/proc/{{pid}}/{{part}}", "rb").read().decode(errors="replace")
            except OSError:
                continue
            if any(m in data for m in markers):
                found.append(f"proc {{pid}} {{part}}")
for root, dirs, files in os.walk("/"):
    dirs[:] = [d for d in dirs if not (root == "/" and d in ("proc", "sys", "dev"))]
    for f in files + dirs:
        if any(m in f for m in markers) or f == "key.json":
            found.append("file " + os.path.join(root, f))
print(found)
{var} = float(len(found))
"""

WRITE = """
import os
done = []
for path in {paths!r}:
    try:
        with open(path, "w") as fh:
            fh.write("overwritten")
        done.append(path)
    except OSError:
        pass
os.system("touch {paths[0]}-by-shell 2>/dev/null")
{var} = float(len([p for p in done if p != "/tmp/scara-escaped"]))  # its own /tmp is private: that write is allowed
"""

HOSTILE = {
    "loop": "while True:\n    pass",
    "memory": "blocks = []\nwhile True:\n    blocks.append(bytearray(10**8))",
    "kill": "import os, signal\nos.kill(os.getpid(), signal.SIGKILL)",
    "flood": "for i in range(10**6):\n    print(i)\n",
    "steal": "from scara.course import solve\n{var} = solve('ex-clik-lag', {params!r})['lag_um']",
}


@pytest.fixture(scope="module")
def graded(tmp_path_factory):
    if shutil.which("bwrap") is None:
        import os
        if os.environ.get("CI") == "true":
            pytest.fail("bubblewrap (bwrap) is missing: CI installs it to grade in a sandbox")
        pytest.skip("bubblewrap (bwrap) is not installed: grading runs each submission in it")
    from scara.course.grade import grade

    tmp = tmp_path_factory.mktemp("grading")
    roster = tmp / "roster.csv"
    kinds = ["right", "wrong", "loop", "memory", "kill", "flood", "snoop", "write", "steal", "garbage", "stranger"]
    with open(roster, "w") as fh:
        fh.write("id,name\n" + "".join(f"{k}-x7q,{k.title()}\n" for k in kinds[:-1]))
    key_dir = tmp / "teacher"
    key = assign(roster, SECRET, key_dir, ["ex-clik-lag"], log=lambda *a: None)
    subs = tmp / "submissions"
    subs.mkdir()
    var = answer_variable(exercise("ex-clik-lag"), "lag_um")
    key_path = key_dir / "key.json"
    before = {p: p.read_bytes() for p in [key_path]}
    for kind in kinds:
        sid = f"{kind}-x7q"
        if kind == "garbage":
            (subs / f"{sid}.ipynb").write_text("{ this is not a notebook")
            continue
        src = "right-x7q" if kind == "stranger" else sid
        nb = nbformat.read(key_dir / src / "assignment.ipynb", as_version=4)
        p = key["students"][src]["params"]["ex-clik-lag"]
        if kind in ("right", "flood", "stranger"):
            code = HONEST.format(A=p["A"], K=p["K"], var=var)
            if kind == "flood":
                code = HOSTILE["flood"] + code
        elif kind == "wrong":
            code = HONEST.format(A=p["A"], K=p["K"], var=var) + f"\n{var} = {var} / 1e6  # metres, not µm"
        elif kind == "snoop":
            code = SNOOP.format(markers=["right-x7q", "wrong-x7q", "teacher", SECRET.decode()[:16],
                                         repr(key["students"]["right-x7q"]["answers"][var]["expected"])[:8]],
                                paths=[str(key_path), str(subs), str(key_dir), str(subs / "right-x7q.ipynb")],
                                var=var)
        elif kind == "write":
            code = WRITE.format(paths=[str(tmp / "escaped"), str(key_path), str(subs / "right-x7q.ipynb"),
                                       "/tmp/scara-escaped"], var=var)
        elif kind == "steal":
            steal = HOSTILE["steal"].format(var=var, params=p).replace("\n", "\n    ")
            code = f"try:\n    {steal}\nexcept Exception:\n    {var} = -1.0"
        else:
            code = HOSTILE[kind]
        nb.cells.append(nbformat.v4.new_code_cell(code))
        if kind == "stranger":
            nb.metadata["scara"]["student"] = "nobody-on-the-roster"
        name = "stranger.ipynb" if kind == "stranger" else f"{sid}.ipynb"
        nbformat.write(nb, subs / name)
    subs_before = {p: p.read_bytes() for p in subs.iterdir()}
    rows = grade(key_path, subs, tmp / "marks", timeout=20, memory_mb=2048, jobs=2, log=lambda *a: None)
    return {"rows": {r["student"]: r for r in rows}, "tmp": tmp, "key": key, "var": var, "key_before": before,
            "subs_before": subs_before, "subs": subs, "out": tmp / "marks"}


def test_honest_submissions_are_marked_right_and_wrong(graded):
    rows = graded["rows"]
    assert rows["right-x7q"]["score"] == 1 and rows["right-x7q"]["status"] == "ran to the end"
    assert rows["wrong-x7q"]["score"] == 0 and rows["wrong-x7q"]["status"] == "ran to the end"
    assert rows["flood-x7q"]["score"] == 1  # a million lines printed first change nothing
    feedback = (graded["out"] / "feedback" / "wrong-x7q.md").read_text()
    assert "wrong: Exercise 4." in feedback and "expected" in feedback and "off by" in feedback
    results = json.loads((graded["out"] / "gradescope" / "right-x7q" / "results.json").read_text())
    assert results["score"] == 1 and results["tests"][0]["max_score"] == 1


def test_hostile_submissions_get_a_clear_mark_line(graded):
    rows = graded["rows"]
    assert rows["loop-x7q"]["status"] == "timed out after 20 s" and rows["loop-x7q"]["score"] == 0
    assert rows["memory-x7q"]["status"] == "ran out of memory (limit 2048 MB)"
    assert rows["kill-x7q"]["status"] == "kernel died"
    assert rows["garbage-x7q"]["status"] == "not a readable notebook"
    assert rows["stranger"]["status"] == "no student of the key has this id"
    assert all(r["score"] == 0 for k, r in rows.items() if k not in ("right-x7q", "flood-x7q"))


def test_nothing_leaks_into_or_out_of_a_sandbox(graded):
    feedback = {p.stem: p.read_text() for p in (graded["out"] / "feedback").glob("*.md")}
    assert "given 0, off by" in feedback["snoop-x7q"]  # it found nothing: no key, no other work, no secret
    assert "given 0, off by" in feedback["write-x7q"]  # it wrote nothing outside its own folder
    assert "given -1, off by" in feedback["steal-x7q"]  # the answers' code is not there
    assert not (graded["tmp"] / "escaped").exists() and not Path("/tmp/scara-escaped").exists()
    assert not Path(str(graded["tmp"] / "escaped") + "-by-shell").exists()
    for path, data in graded["key_before"].items():
        assert path.read_bytes() == data
    for path, data in graded["subs_before"].items():
        assert path.read_bytes() == data
    assert sorted(graded["subs"].iterdir()) == sorted(graded["subs_before"])


def test_the_grade_command_reads_its_inputs(tmp_path):
    run = subprocess.run([sys.executable, "-m", "scara.course", "grade", "--key", str(tmp_path / "none.json"),
                          "--submissions", str(tmp_path), "--out", str(tmp_path / "o")],
                         capture_output=True, text=True)
    assert run.returncode == 2 and "Traceback" not in run.stderr and "none.json" in run.stderr


def test_book_folder_is_the_books():
    assert book_folder() == BOOK


def test_the_runner_caps_a_flood_of_output_and_still_reads_the_answers(tmp_path):
    """A notebook that prints three times :data:`OUTPUT_CAP` characters to each stream, then points ``sys.stdout``
    elsewhere, still has its answers read; the kernel sends at most the cap of each stream (the cells' outputs, as
    the runner holds them, are counted by a spy on nbclient's output hook)."""
    import nbclient

    from scara.course import _runner

    nb = nbformat.v4.new_notebook()
    flood = f"import sys\nfor _ in range({3 * _runner.OUTPUT_CAP // 100}):\n    print('x' * 99)\n    " \
            f"print('y' * 99, file=sys.stderr)\n"
    nb.cells = [nbformat.v4.new_code_cell(flood), nbformat.v4.new_code_cell("import io\nsys.stdout = io.StringIO()"),
                nbformat.v4.new_code_cell("answer = 2.5")]
    path = tmp_path / "flood.ipynb"
    nbformat.write(nb, path)
    sent = {"stdout": 0, "stderr": 0}
    hook = nbclient.NotebookClient.output

    def spy(self, outs, msg, display_id, cell_index):
        if msg["msg_type"] == "stream":
            sent[msg["content"]["name"]] += len(msg["content"]["text"])
        return hook(self, outs, msg, display_id, cell_index)

    nbclient.NotebookClient.output = spy
    try:
        out = _runner.run(str(path), str(tmp_path / "result.json"), 60.0, ["answer"])
    finally:
        nbclient.NotebookClient.output = hook
    assert out["status"] == "ok" and out["answers"] == {"answer": 2.5} and out["error"] is None
    assert 0 < sent["stderr"] <= _runner.OUTPUT_CAP
    assert 0 < sent["stdout"] <= _runner.OUTPUT_CAP + 200          # the cap, and the collecting cell's line
