"""Compile, into numba's cache (``NUMBA_CACHE_DIR``), the kernels the assignment's exercises use: by answering
each of them once for the book's numbers, as a student's notebook will with its own. ``python -m
scara.course.warm LABEL...`` (every numeric exercise when none is named)."""
from __future__ import annotations

import sys

from scara.course.exercises import catalog, solve


def warm(labels=()) -> None:
    for label in labels or [ex.label for ex in catalog().values() if ex.numeric]:
        solve(label)


if __name__ == "__main__":
    warm(sys.argv[1:])
