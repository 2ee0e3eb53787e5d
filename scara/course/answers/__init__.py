"""The computations that answer the book's exercises, one module per chapter: each function, registered with
``@solves(label)``, takes an exercise's parameters (:mod:`scara.course.chapters`) and returns its answers, in the
units the exercise asks for, with the intermediate numbers its worked solution quotes. It raises the package's
:class:`~scara.errors.ScaraError` for parameters outside the exercise's sense (an unreachable point, an unstable
gain), which is how an assignment's draw is checked.

This package is the key: the student edition of the book leaves it out, with the solutions."""
from __future__ import annotations

import importlib

#: label -> the function that answers it
SOLVERS: dict = {}

MODULES = ("ch1", "ch2", "ch3", "ch4", "ch5", "ch6", "ch7", "appendix")


def solves(label: str):
    """Register the decorated function as the computation answering exercise ``label``."""
    def register(fn):
        if label in SOLVERS and SOLVERS[label] is not fn:
            raise ValueError(f"two computations answer exercise {label!r}")
        SOLVERS[label] = fn
        return fn
    return register


def load() -> None:
    """Import every chapter's answers (each registers its functions)."""
    for name in MODULES:
        importlib.import_module(f"{__name__}.{name}")
