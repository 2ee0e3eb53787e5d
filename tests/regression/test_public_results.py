"""The refactored package gives the book what the recorded version gave it: every whole run of the book's
scenarios and every number and figure of every executed chapter, bit-identical or equal to 1e-15 relative
(``tests/regression/public_results.py`` holds the fingerprints, the record and the rule).

The record was made from the code before the package's internals were reorganised; a change that is meant to
alter a result re-records it (``python tests/regression/public_results.py record`` after a build) in a commit
that says why.
"""
from __future__ import annotations

import gzip
import json
import os
import pathlib
import sys

import pytest

HERE = pathlib.Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
import public_results as pr  # noqa: E402

def _recorded(prefix: str) -> dict:
    with gzip.open(pr.DEFAULT_OUT, "rt") as fh:
        return {k: v for k, v in json.load(fh).items() if k.startswith(prefix)}


def _check(recorded: dict, current: dict):
    problems = pr.compare(recorded, current)
    shown = "\n".join(problems[:40])
    assert not problems, f"{len(problems)} of {len(recorded)} recorded results changed:\n{shown}"


def test_the_book_runs_give_the_recorded_results():
    """Each CLIK method, clik2, every chapter-6 controller with the unknown 5 kg payload and the PD + gravity
    loop: every array of the result, its signals and its summary."""
    recorded = _recorded("run/")
    assert len(recorded) > 100
    _check(recorded, pr.run_results())


def test_the_executed_chapters_give_the_recorded_numbers_and_figures():
    """Every glued number and every figure's data of every chapter, as the book build executed them."""
    build = pr.ROOT / "_build"
    if not (build / "jupyter_execute").is_dir():
        if os.environ.get("CI", "").lower() == "true":
            pytest.fail("the book is not built: the README's test command builds it before running the tests")
        pytest.skip("the book is not built (jupyter-book build .)")
    recorded = _recorded("book/")
    assert len(recorded) > 1000
    _check(recorded, pr.book_results(build))
