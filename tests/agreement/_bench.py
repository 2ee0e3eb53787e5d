"""The benchmarks' modules (``benchmarks/agreement.py``, ``libraries.py``, ``run.py``) for the agreement tests, each
imported only after the optional extras it needs (``requirements-bench.txt``) import; otherwise the test is
skipped with the reason."""
from __future__ import annotations

import importlib
import os
import sys

import pytest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
BENCH = os.path.join(ROOT, "benchmarks")


def bench_module(name: str, *extras: str):
    """``benchmarks/<name>.py`` as a module, after ``pytest.importorskip`` of every module in ``extras``."""
    for extra in extras:
        pytest.importorskip(extra, reason=f"needs the optional extras: pip install -r requirements-bench.txt ({extra})")
    if BENCH not in sys.path:
        sys.path.insert(0, BENCH)
    return importlib.import_module(name)
