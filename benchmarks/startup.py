"""How quickly the package and the book start: the cost of ``import scara`` and of *Run All* per chapter.

The budgets of the verification appendix (book/appendix_verification.ipynb, section Speed): ``import scara``
with a warm compile cache costs at most 0.2 s more than importing numpy and numba themselves; *Run All* of any
chapter in a fresh kernel with a warm cache takes at most 8 s; the first chapter on a fresh machine (cold
compile cache) at most 20 s. This script measures, and prints, all three:

* import: ``import numpy, numba`` and ``import scara``, each timed inside ``--repeats`` fresh interpreters
  (``time.perf_counter`` around the import statement, so the interpreter's own start-up is left out), taken in
  turns; the median of each, and their difference. One untimed ``import scara`` runs first, so that anything
  the import compiles is in the cache.
* Run All: each notebook of ``book/`` executed top to bottom by ``nbclient`` in a fresh ``python3`` kernel,
  working directory ``book/``, as *Restart Kernel and Run All* does: the time runs from the kernel's start to
  the reply of the last cell (the kernel's shutdown afterwards is not counted); the "kernel" column is the part
  until the fresh kernel answers. "warm": after one untimed run of the same chapter, with the package's own
  numba cache (or the user's ``NUMBA_CACHE_DIR``). "cold": ``NUMBA_CACHE_DIR`` pointing to a new, empty
  temporary folder, so every kernel the chapter uses is compiled (the user's cache is neither read nor touched).

Both import this checkout's ``scara`` (its root is put first on ``PYTHONPATH``). Times are wall-clock seconds (a
reader waits for the wall clock); they move with the machine's load, and the script asserts nothing about them.

Run: ``python benchmarks/startup.py [--repeats 5] [--runs 1] [--chapters 01_kinematics 05_dynamics] [--no-cold]
[--cells N]``; ``--cells N`` also prints the N slowest cells of each run (where a slow chapter spends its time).

Other scripts call :func:`import_times` and :func:`run_all_times` (both return dicts).
"""
from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import time
from datetime import datetime
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
BOOK = ROOT / "book"

#: the statements compared by :func:`import_times`
IMPORTS = {"numpy+numba": "import numpy, numba", "scara": "import scara"}

_TIMED = "import time; _t = time.perf_counter(); {stmt}; print(time.perf_counter() - _t)"


def _checkout_env() -> dict:
    """Environment additions that make a child process import this checkout's ``scara``."""
    path = os.environ.get("PYTHONPATH")
    return {"PYTHONPATH": str(ROOT) + (os.pathsep + path if path else "")}


def _child_env(extra: dict | None = None) -> dict:
    env = dict(os.environ)
    env.pop("PYTHONPROFILEIMPORTTIME", None)
    env.update(_checkout_env())
    env.update(extra or {})
    return env


def _import_once(stmt: str, python: str, env: dict) -> float:
    out = subprocess.run([python, "-c", _TIMED.format(stmt=stmt)], check=True, capture_output=True, text=True,
                         env=env, cwd=tempfile.gettempdir())
    return float(out.stdout.strip().splitlines()[-1])


def import_times(repeats: int = 5, python: str | None = None, env: dict | None = None) -> dict:
    """Median import times (s) over ``repeats`` fresh interpreters each, warm compile cache.

    Returns ``{"numpy+numba": s, "scara": s, "extra": scara - numpy+numba, "samples": {name: [s, ...]}}``.
    ``python`` is the interpreter (default: this one); ``env`` adds environment variables.
    """
    python = python or sys.executable
    full_env = _child_env(env)
    _import_once(IMPORTS["scara"], python, full_env)  # warm: whatever the import compiles goes to the cache
    samples: dict[str, list[float]] = {name: [] for name in IMPORTS}
    for _ in range(repeats):
        for name, stmt in IMPORTS.items():
            samples[name].append(_import_once(stmt, python, full_env))
    med = {name: statistics.median(v) for name, v in samples.items()}
    return {**med, "extra": med["scara"] - med["numpy+numba"], "samples": samples}


def chapter_paths(chapters=None) -> list[Path]:
    """The notebooks named by ``chapters`` (stems such as ``"01_kinematics"``, or paths); all of ``book/``
    when ``None``."""
    if chapters is None:
        return sorted(BOOK.glob("*.ipynb"))
    out = []
    for c in chapters:
        path = Path(c)
        out.append(BOOK / f"{c}.ipynb" if not path.suffix else path.resolve())
    return out


def run_notebook(path, env: dict | None = None, timeout: float = 900) -> dict:
    """Execute one notebook in a fresh kernel, as *Restart Kernel and Run All* does.

    Returns ``{"total": s, "kernel": s, "cells": [(index, s, first line), ...]}``: ``total`` from the start of
    the kernel to the reply of the last cell (the kernel's shutdown afterwards is not counted), ``kernel``
    until the kernel answers its first request, and each cell's time from its ``execute_input`` to its
    ``execute_reply`` (as recorded by nbclient).
    """
    import nbformat
    from nbclient import NotebookClient
    from nbclient.util import ensure_async, run_sync

    path = Path(path)
    nb = nbformat.read(path, as_version=4)
    client = NotebookClient(nb, timeout=timeout, kernel_name="python3", allow_errors=False,
                            resources={"metadata": {"path": str(path.parent)}})

    async def run():
        t0 = time.perf_counter()
        # the kernel's own start-up chatter (stdout, stderr) is not shown; its errors reach the cells' replies
        async with client.async_setup_kernel(stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL):
            await client.async_wait_for_reply(await ensure_async(client.kc.kernel_info()))
            ready = time.perf_counter() - t0
            for index, cell in enumerate(nb.cells):
                await client.async_execute_cell(cell, index, execution_count=client.code_cells_executed + 1)
            total = time.perf_counter() - t0
        return ready, total

    saved = dict(os.environ)
    os.environ.update({**_checkout_env(), **(env or {})})  # the kernel inherits this process's environment
    try:
        ready, total = run_sync(run)()
    finally:
        os.environ.clear()
        os.environ.update(saved)
    cells = []
    for i, cell in enumerate(nb.cells):
        ex = cell.get("metadata", {}).get("execution", {})
        if cell.cell_type == "code" and "iopub.execute_input" in ex and "shell.execute_reply" in ex:
            start = datetime.fromisoformat(ex["iopub.execute_input"].replace("Z", "+00:00"))
            end = datetime.fromisoformat(ex["shell.execute_reply"].replace("Z", "+00:00"))
            first = next((line for line in cell.source.splitlines() if line.strip()), "")
            cells.append((i, (end - start).total_seconds(), first[:70]))
    return {"total": total, "kernel": ready, "cells": cells}


def run_all_times(chapters=None, cold: bool = False, warmup: bool = True, repeats: int = 1,
                  detail: bool = False) -> dict:
    """*Run All* time (s) of each chapter in a fresh kernel: ``{chapter stem: s}``.

    ``cold=False``: the package's numba cache (or the user's ``NUMBA_CACHE_DIR``), warmed by one untimed run
    of the chapter when ``warmup``; the median of ``repeats`` timed runs. ``cold=True``: each timed run gets
    its own empty ``NUMBA_CACHE_DIR`` (a temporary folder, removed afterwards). With ``detail`` the values are
    the :func:`run_notebook` dicts of the last run (cells included) with the medians of ``total`` and
    ``kernel``, instead of the seconds.
    """
    results = {}
    for path in chapter_paths(chapters):
        runs = []
        if not cold and warmup:
            run_notebook(path)
        for _ in range(repeats):
            if cold:
                with tempfile.TemporaryDirectory(prefix="scara-numba-cold-") as cache:
                    runs.append(run_notebook(path, env={"NUMBA_CACHE_DIR": cache}))
            else:
                runs.append(run_notebook(path))
        if detail:
            results[path.stem] = {**runs[-1], "total": statistics.median(r["total"] for r in runs),
                                  "kernel": statistics.median(r["kernel"] for r in runs)}
        else:
            results[path.stem] = statistics.median(r["total"] for r in runs)
    return results


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--repeats", type=int, default=5, help="fresh interpreters per import statement")
    ap.add_argument("--runs", type=int, default=1, help="timed Run All per chapter (the median is shown)")
    ap.add_argument("--chapters", nargs="*", default=None, help="notebook stems (default: every book/*.ipynb)")
    ap.add_argument("--cold-chapter", default="01_kinematics", help="the chapter timed with a cold cache")
    ap.add_argument("--no-cold", action="store_true", help="skip the cold-cache run")
    ap.add_argument("--no-import", action="store_true", help="skip the import timing")
    ap.add_argument("--cells", type=int, default=0, help="print the N slowest cells of each run")
    args = ap.parse_args(argv)

    import numba
    import numpy

    print(f"python {sys.version.split()[0]}, numpy {numpy.__version__}, numba {numba.__version__}, "
          f"{os.cpu_count()} cpus, load {os.getloadavg()[0]:.2f}")
    if not args.no_import:
        imp = import_times(args.repeats)
        print(f"\nimport (warm cache), median of {args.repeats} fresh interpreters")
        print(f"{'statement':<28}{'s':>8}")
        print("-" * 36)
        for name, stmt in IMPORTS.items():
            print(f"{stmt:<28}{imp[name]:8.3f}")
        print(f"{'scara - (numpy + numba)':<28}{imp['extra']:8.3f}   (target <= 0.2 s)")

    warm = run_all_times(args.chapters, repeats=args.runs, detail=True)
    cold = {} if args.no_cold else run_all_times([args.cold_chapter], cold=True, repeats=args.runs, detail=True)
    print(f"\nRun All in a fresh kernel (s, from the kernel's start to the last cell's reply; 'kernel': until "
          f"the kernel answers){', median of ' + str(args.runs) + ' runs' if args.runs > 1 else ''}")
    print(f"{'chapter':<26}{'kernel':>8}{'warm':>8}{'cold':>8}")
    print("-" * 50)
    for stem in list(warm) + [c for c in cold if c not in warm]:
        w = warm.get(stem)
        c = cold.get(stem)
        print(f"{stem:<26}{w['kernel'] if w else c['kernel']:8.2f}" + (f"{w['total']:8.1f}" if w else f"{'':8}")
              + (f"{c['total']:8.1f}" if c else ""))
    print("targets: warm <= 8 s for every chapter; cold <= 20 s for the first chapter")
    if args.cells:
        for label, results in (("warm", warm), ("cold", cold)):
            for stem, res in results.items():
                print(f"\n{stem}: slowest cells ({label})")
                for i, sec, first in sorted(res["cells"], key=lambda c: -c[1])[:args.cells]:
                    print(f"  cell {i:3d} {sec:6.2f} s  {first}")


if __name__ == "__main__":
    main()
