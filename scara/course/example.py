"""The teacher's page's worked example: a class of three, its assignments, three submissions and their marks.

:func:`command` runs ``python -m scara.course ...`` as a teacher types it and returns what it printed;
:func:`example_submissions` writes what three students hand in for exercises 1.1 (direct kinematics) and 4.1 (the
lag of the second-order CLIK): one who did the work, one who slipped on the units, one whose notebook never ends.
"""
from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

__all__ = ["command", "example_submissions", "parameters_table", "quoted", "marks_table", "ROSTER", "EXERCISES"]

#: the worked example's class
ROSTER = "id,name\nada,Ada Lovelace\nalan,Alan Turing\ngrace,Grace Hopper\n"
#: the exercises it sets
EXERCISES = ("ex-kin-direct", "ex-clik-lag")

_WORK = {
    "ex-kin-direct": """\
x = scara.pose([np.radians({t1}), np.radians({t2}), {d3}, np.radians({t4})])
{var[px]}, {var[py]}, {var[pz]} = x[:3]
{var[phi]} = np.degrees(x[3]){phi_slip}
""",
    "ex-clik-lag": """\
from types import SimpleNamespace
A, K, T = {A}, {K}, 1e-3
t = np.arange(301) * T
ramp = SimpleNamespace(t=t, x=np.tile([0.4, -0.3, 0.7, 0.2], (301, 1)), xd=np.zeros((301, 4)),
                       xdd=np.zeros((301, 4)), dt=T)
ramp.x[:, 2] -= 0.5 * A * t**2
ramp.xd[:, 2], ramp.xdd[:, 2] = -A * t, -A
run = scara.clik2(ramp, *scara.second_order_gains(np.array([400.0, 400.0, K, 100.0])))
{var[lag_um]} = abs(run.e[-1, 2]){lag_scale}
""",
}


def command(*args: str, cwd=None) -> str:
    """Run ``python -m scara.course ARGS`` (in folder ``cwd``) and return what it printed (its error line, if
    it failed)."""
    run = subprocess.run([sys.executable, "-m", "scara.course", *args], capture_output=True, text=True, cwd=cwd)
    return (run.stdout + run.stderr).strip()


def parameters_table(key: dict):
    """Each student's numbers, one row per parameter that varies, one column per student (a DataFrame)."""
    import pandas as pd  # noqa: PLC0415

    from scara.course.exercises import exercise  # noqa: PLC0415
    from scara.course.statement import readable  # noqa: PLC0415

    rows = {}
    for sid, student in key["students"].items():
        for label, params in student["params"].items():
            ex = exercise(label)
            for name, value in params.items():
                p = ex.param(name)
                if p.varies:
                    text = readable(p.text)
                    rows.setdefault((f"{ex.number}", f"{text} ({p.unit})" if p.unit else text), {})[
                        student["name"]] = p.show(value)
    table = pd.DataFrame.from_dict(rows, orient="index")
    table.index.names = ["Exercise", "Parameter"]
    return table


def example_submissions(assignments: Path, out: Path, key: dict) -> list[Path]:
    """Write the three example submissions into ``out``: Ada's, right; Alan's, with φ in radians and the lag in
    metres; Grace's, which loops for ever after doing the work. Returns their paths."""
    import nbformat  # noqa: PLC0415

    from scara.course.assign import answer_variable  # noqa: PLC0415
    from scara.course.exercises import exercise  # noqa: PLC0415

    out.mkdir(parents=True, exist_ok=True)
    paths = []
    for sid, slip in (("ada", False), ("alan", True), ("grace", False)):
        nb = nbformat.read(Path(assignments) / sid / "assignment.ipynb", as_version=4)
        params = key["students"][sid]["params"]
        work = []
        for label in EXERCISES:
            ex = exercise(label)
            var = {a.name: answer_variable(ex, a.name) for a in ex.answers}
            slips = {"phi_slip": f"\n{var.get('phi')} = x[3]" if slip else "",
                     "lag_scale": "" if slip else " * 1e6"}
            work.append(_WORK[label].format(**params[label], var=var, **slips))
        # each piece of work goes in the cell that holds its exercise's answers
        cells = [c for c in nb.cells if c.cell_type == "code" and "scara" in c.metadata]
        for cell, code in zip(cells, work):
            cell.source = code
        if sid == "grace":
            nb.cells.append(nbformat.v4.new_code_cell("while True:  # a loop that never ends\n    pass"))
        path = Path(out) / f"{sid}.ipynb"
        nbformat.write(nb, path)
        paths.append(path)
    return paths


def quoted(markdown: str):
    """``markdown`` (a notebook's cells, a feedback file) shown as a quotation within a page: its headings in bold,
    so that they do not become the page's own sections."""
    from IPython.display import Markdown  # noqa: PLC0415

    lines = [re.sub(r"^#+\s+(.*)$", r"**\1**", line) for line in markdown.strip().splitlines()]
    return Markdown("\n".join(f"> {line}".rstrip() for line in lines))


def marks_table(path: Path):
    """``marks.csv`` as a Markdown table: student, score and the run's mark line."""
    import csv  # noqa: PLC0415

    from IPython.display import Markdown  # noqa: PLC0415

    with open(path, newline="", encoding="utf-8") as fh:
        rows = list(csv.DictReader(fh))
    lines = ["| Student | Score | Run |", "|---|---|---|"]
    lines += [f"| {r['student']} | {r['score']} / {r['max_score']} | {r['status']} |" for r in rows]
    return Markdown("\n".join(lines))
