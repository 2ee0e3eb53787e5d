"""The largest difference met by each independent check, for the closing note of the run.

A test calls ``record(name, err)`` with the difference it is about to assert on; ``record`` keeps the largest
value per test module and check, and returns ``err`` unchanged. Nothing in a test reads these values: the
``pytest_terminal_summary`` hook of ``tests/conftest.py`` prints them at the end of the run.
"""
from __future__ import annotations

import sys

LARGEST: dict[str, dict[str, float]] = {}


def record(name: str, err):
    """Keep ``err`` if it is the largest met so far by check ``name`` of the calling test module; return ``err``."""
    module = sys._getframe(1).f_globals.get("__name__", "?").rpartition(".")[2]
    checks = LARGEST.setdefault(module, {})
    checks[name] = max(checks.get(name, 0.0), float(err))
    return err
