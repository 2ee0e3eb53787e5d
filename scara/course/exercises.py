"""The book's exercises as data.

Each exercise of the book is declared once, in the module of its chapter (:mod:`scara.course.chapters`), as an
:class:`Exercise`: its label (the one its ``{exercise}`` directive carries), the parameters its statement uses
(:class:`Param`: a default, the book's value, and a range that keeps the exercise meaningful, for the
assignments drawn for each student), the answers it asks for (:class:`Answer`: a name, a unit, a tolerance) and,
for an exercise whose answer is an argument rather than a number, a marking note.

The computation that answers an exercise is written once too, in :mod:`scara.course.answers` (``@solves(label)``):
it takes the parameters and returns each answer, in the answer's own unit, plus the intermediate numbers its worked
solution quotes. The chapter's statement shows the parameters through glued values (:func:`glue_statement`:
``{glue:text}`ex-clik-lag.A:.1f```), its worked solution the results (:func:`glue_solution`), the instructor
edition's answer key lists them (:func:`answer_key`), and ``python -m scara.course assign`` instantiates the
statement with each student's own parameters and computes their key with the same function.

The student edition of the book leaves :mod:`scara.course.answers` out, with the solutions.
"""
from __future__ import annotations

import hashlib
import hmac
import importlib
import math
import numbers
import re
from dataclasses import dataclass, field

from scara.errors import ScaraError

__all__ = ["Param", "Answer", "Exercise", "EXERCISES", "catalog", "exercise", "chapter_exercises", "chapter_prefix",
           "solve", "glue_statement", "glue_solution", "answer_key", "answer_key_rows", "draw", "draw_params",
           "AnswersMissing", "DOCNAMES"]

#: the chapters that have exercises, in the book's order (docname -> module of :mod:`scara.course.chapters`)
DOCNAMES = {
    "01_kinematics": "ch1",
    "02_manipulability": "ch2",
    "03_trajectory": "ch3",
    "04_clik": "ch4",
    "05_dynamics": "ch5",
    "06_control": "ch6",
    "07_interaction": "ch7",
    "appendix_verification": "appendix",
}


class AnswersMissing(ScaraError):
    """The answers (:mod:`scara.course.answers`) are not installed: this is the student edition."""


@dataclass(frozen=True)
class Param:
    """One number (or choice) an exercise's statement uses.

    ``default`` is the book's value. ``low``, ``high`` and ``step`` give the values an assignment may draw
    (``low + k step``, both ends included); ``choices`` replaces them for a choice among a few values (``"y"``,
    ``"z"``). Without a range the parameter is fixed: every student gets the book's value. ``unit`` is how the
    statement writes the unit, ``fmt`` the format the statement prints the value with (``".1f"``), ``text`` what
    the parameter is, in a few words, for the answer key and the teacher.
    """

    name: str
    default: object
    unit: str = ""
    fmt: str = ""
    text: str = ""
    low: float | None = None
    high: float | None = None
    step: float | None = None
    choices: tuple = ()

    def __post_init__(self):
        if not re.fullmatch(r"[A-Za-z_]\w*", self.name):
            raise ScaraError(f"a parameter's name must be a Python identifier, got {self.name!r}")
        ranged = (self.low, self.high, self.step)
        if any(v is not None for v in ranged) and not all(v is not None for v in ranged):
            raise ScaraError(f"parameter {self.name!r}: give low, high and step together, got {ranged}")
        if self.low is not None:
            if not (self.step > 0 and self.low <= self.default <= self.high):
                raise ScaraError(f"parameter {self.name!r}: needs step > 0 and low <= default <= high, got "
                                 f"low={self.low}, default={self.default}, high={self.high}, step={self.step}")
            k = (self.default - self.low) / self.step
            if abs(k - round(k)) > 1e-9:
                raise ScaraError(f"parameter {self.name!r}: the default {self.default} is not on the grid "
                                 f"{self.low} + k * {self.step}")
        if self.choices and self.default not in self.choices:
            raise ScaraError(f"parameter {self.name!r}: the default {self.default!r} is not among {self.choices}")

    @property
    def varies(self) -> bool:
        """Whether an assignment draws this parameter (it has a range or choices)."""
        return self.low is not None or bool(self.choices)

    def values(self) -> list:
        """Every value an assignment may draw, in increasing order (the default alone for a fixed parameter)."""
        if self.choices:
            return list(self.choices)
        if self.low is None:
            return [self.default]
        n = int(round((self.high - self.low) / self.step))
        # rounded to the step's decimals, so that 0.1 + 3 * 0.05 prints and compares as 0.25
        decimals = max(0, -math.floor(math.log10(self.step)) + 3)
        return [round(self.low + k * self.step, decimals) for k in range(n + 1)]

    def show(self, value) -> str:
        """``value`` as the statement prints it."""
        return format(value, self.fmt) if self.fmt else str(value)


@dataclass(frozen=True)
class Answer:
    """One number an exercise asks for: ``name`` (an identifier), what it is (``text``), the ``unit`` the
    student gives it in and the ``tolerance`` a given value may be off by: relative (``0.01``: 1 %) unless
    ``absolute`` is set, then in the answer's unit. ``fmt`` is how the key prints it. ``shown`` says where the
    book shows this value for its own numbers, by design (a figure to check a prediction on, a table or a
    text the exercise reasons from); with other numbers, as in an assignment, nothing shows it."""

    name: str
    text: str
    unit: str = ""
    tolerance: float = 0.01
    absolute: bool = False
    fmt: str = ".4g"
    shown: str = ""

    def __post_init__(self):
        if not re.fullmatch(r"[A-Za-z_]\w*", self.name):
            raise ScaraError(f"an answer's name must be a Python identifier, got {self.name!r}")
        if not (self.tolerance > 0 and math.isfinite(self.tolerance)):
            raise ScaraError(f"answer {self.name!r}: the tolerance must be positive and finite, got {self.tolerance}")

    def tolerance_text(self) -> str:
        """The tolerance as a reader reads it: "±1 %" or "±0.05 mm"."""
        if self.absolute:
            return f"±{self.tolerance:g}" + (f" {self.unit}" if self.unit else "")
        return f"±{100 * self.tolerance:g} %"

    def allowed(self, expected: float) -> float:
        """The largest difference from ``expected`` still marked right."""
        return self.tolerance if self.absolute else self.tolerance * abs(expected)

    def matches(self, expected: float, given) -> bool:
        """Whether ``given`` is within the tolerance of ``expected`` (False for anything not a finite real number:
        text, a bool, an array)."""
        if isinstance(given, bool) or not isinstance(given, numbers.Real):
            return False
        try:
            value = float(given)
        except (TypeError, ValueError, OverflowError):
            return False
        return math.isfinite(value) and abs(value - expected) <= self.allowed(expected)


@dataclass(frozen=True)
class Exercise:
    """One exercise of the book. ``label`` is its directive's label, ``docname`` its chapter; ``params`` and
    ``answers`` as above (none for an exercise whose answer is an argument). ``note`` tells the marker what a
    full answer contains (required when there is no numeric answer)."""

    label: str
    docname: str
    params: tuple = ()
    answers: tuple = ()
    note: str = ""
    number: str = field(default="", compare=False)

    def __post_init__(self):
        if self.docname not in DOCNAMES:
            raise ScaraError(f"exercise {self.label!r}: unknown chapter {self.docname!r}; the chapters are "
                             f"{list(DOCNAMES)}")
        if not self.answers and not self.note:
            raise ScaraError(f"exercise {self.label!r} has no numeric answer, so it needs a marking note")
        names = [p.name for p in self.params] + [a.name for a in self.answers]
        if len(set(names)) != len(names):
            raise ScaraError(f"exercise {self.label!r}: a name is used twice among {names}")

    @property
    def numeric(self) -> bool:
        """Whether the exercise asks for numbers (else its answer is an argument, marked by its note)."""
        return bool(self.answers)

    @property
    def defaults(self) -> dict:
        """The book's parameters: name -> value."""
        return {p.name: p.default for p in self.params}

    def param(self, name: str) -> Param:
        for p in self.params:
            if p.name == name:
                return p
        raise KeyError(f"exercise {self.label!r} has no parameter {name!r}; it has {[p.name for p in self.params]}")

    def key(self, name: str) -> str:
        """The glue name of a parameter or result of this exercise: ``label.name``."""
        return f"{self.label}.{name}"


#: every exercise of the book, by label, in the book's order (filled by :mod:`scara.course.chapters`)
EXERCISES: dict[str, Exercise] = {}


def chapter_prefix(docname: str) -> str:
    """The prefix of a chapter's exercise numbers: ``"4"`` for ``04_clik``, ``"A"`` for the appendix."""
    return docname[:2].lstrip("0") if docname[:2].isdigit() else "A"


def catalog() -> dict[str, Exercise]:
    """Every exercise of the book, by label, in the book's order, each with its number ("4.2")."""
    if not EXERCISES:
        for docname, module in DOCNAMES.items():
            mod = importlib.import_module(f"scara.course.chapters.{module}")
            for k, ex in enumerate(mod.EXERCISES, 1):
                if ex.docname != docname:
                    raise ScaraError(f"exercise {ex.label!r} is declared in {module} but names chapter {ex.docname!r}")
                if ex.label in EXERCISES:
                    raise ScaraError(f"exercise {ex.label!r} is declared twice")
                object.__setattr__(ex, "number", f"{chapter_prefix(docname)}.{k}")
                EXERCISES[ex.label] = ex
    return EXERCISES


def exercise(label: str) -> Exercise:
    """The exercise labelled ``label``; an unknown label raises ``KeyError`` naming it."""
    book = catalog()
    if label not in book:
        raise KeyError(f"no exercise is labelled {label!r}")
    return book[label]


def chapter_exercises(docname: str) -> list[Exercise]:
    """The exercises of one chapter, in order."""
    if docname not in DOCNAMES:
        raise KeyError(f"no chapter {docname!r}; the chapters with exercises are {list(DOCNAMES)}")
    return [ex for ex in catalog().values() if ex.docname == docname]


def _solver(label: str):
    try:
        answers = importlib.import_module("scara.course.answers")
    except ModuleNotFoundError as exc:
        raise AnswersMissing("the answers are not part of this copy of the course (the student edition)") from exc
    if not hasattr(answers, "load"):  # an empty folder where the answers were (the grading sandbox)
        raise AnswersMissing("the answers are not part of this copy of the course")
    answers.load()
    if label not in answers.SOLVERS:
        raise KeyError(f"no computation answers exercise {label!r}")
    return answers.SOLVERS[label]


def solve(label: str, params: dict | None = None) -> dict:
    """The answers of exercise ``label`` for ``params`` (default: the book's), name -> value, with the numbers
    its worked solution quotes. Parameters it does not know raise ``KeyError``; parameters outside the
    exercise's sense (an unreachable point, an unstable gain) raise the package's :class:`~scara.errors.ScaraError`.
    The result holds every answer the exercise declares, each a finite number."""
    ex = exercise(label)
    given = dict(ex.defaults)
    for name, value in (params or {}).items():
        ex.param(name)
        given[name] = value
    out = dict(_solver(label)(**given))
    for a in ex.answers:
        if a.name not in out:
            raise ScaraError(f"the computation of {label!r} returned no answer {a.name!r}")
        value = float(out[a.name])
        if not math.isfinite(value):
            raise ScaraError(f"exercise {label!r}: answer {a.name!r} is {value} for the parameters {given}")
        out[a.name] = value
    return out


def _labels(names) -> list[str]:
    """Exercise labels from labels and chapter docnames (a chapter stands for all its exercises)."""
    out = []
    for name in names:
        out += [ex.label for ex in chapter_exercises(name)] if name in DOCNAMES else [exercise(name).label]
    return out


def glue_statement(*labels: str) -> None:
    """Glue each parameter of the exercises ``labels`` (a chapter's docname: all of its exercises) at its book
    value as ``label.name``, for the statements' ``{glue:text}`` roles."""
    from scara.book import glue  # noqa: PLC0415

    for label in _labels(labels):
        ex = exercise(label)
        for p in ex.params:
            glue(ex.key(p.name), p.default, display=False)


def glue_solution(*labels: str) -> dict:
    """Glue every number :func:`solve` gives for the book's parameters as ``label.name``, for the worked
    solutions' ``{glue:text}`` roles (labels or a chapter's docname, as :func:`glue_statement`); returns the
    results, label -> name -> value."""
    from scara.book import glue  # noqa: PLC0415

    results = {}
    for label in _labels(labels):
        ex = exercise(label)
        if not ex.numeric:
            continue
        results[label] = solve(label)
        for name, value in results[label].items():
            if isinstance(value, numbers.Real) and not isinstance(value, (bool, int)):
                value = float(value)  # a numpy number glues as its repr ("np.float64(...)"), not as a number
            glue(ex.key(name), value, display=False)
    return results


def answer_key_rows(docname: str, params: dict | None = None) -> list[dict]:
    """The answer key of one chapter for the book's parameters (or ``params``: label -> name -> value): one row
    per answer (exercise number and label, what is asked, value, unit, tolerance) and one per exercise marked by
    its note."""
    rows = []
    for ex in chapter_exercises(docname):
        if not ex.numeric:
            rows.append({"number": ex.number, "label": ex.label, "answer": "", "text": ex.note, "value": None,
                         "unit": "", "tolerance": ""})
            continue
        result = solve(ex.label, (params or {}).get(ex.label))
        for a in ex.answers:
            rows.append({"number": ex.number, "label": ex.label, "answer": a.name, "text": a.text,
                         "value": result[a.name], "shown": format(result[a.name], a.fmt), "unit": a.unit,
                         "tolerance": a.tolerance_text()})
        if ex.note:  # what a full answer argues besides its numbers
            rows.append({"number": ex.number, "label": ex.label, "answer": "", "text": ex.note, "value": None,
                         "unit": "", "tolerance": ""})
    return rows


def answer_key(docname: str):
    """The instructor edition's answer key of a chapter, as Markdown: each numeric answer with its unit and
    tolerance, and the marking note of each exercise answered by an argument."""
    from IPython.display import Markdown  # noqa: PLC0415

    from scara.course.statement import readable  # noqa: PLC0415

    lines = ["| Exercise | Asked | Answer | Unit | Tolerance |", "|---|---|---|---|---|"]
    for r in answer_key_rows(docname):
        cell = lambda s: readable(str(s)).replace("|", "\\|").replace("\n", " ")  # noqa: E731
        if r["value"] is None:
            lines.append(f"| {r['number']} | marking note | {cell(r['text'])} | | |")
        else:
            lines.append(f"| {r['number']} | {cell(r['text'])} | {r['shown']} | {cell(r['unit'])} | "
                         f"{r['tolerance']} |")
    return Markdown("\n".join(lines))


def draw_params(ex: Exercise, secret: bytes, student: str, attempt: int = 0) -> dict:
    """A parameter set of exercise ``ex`` for one student: each varying parameter drawn uniformly among its
    values by a keyed hash (HMAC-SHA256) of the course secret, the student id, the exercise and ``attempt``;
    the same inputs always give the same set, and the set reveals nothing of the secret."""
    out = {}
    for p in ex.params:
        values = p.values()
        msg = f"{student}\x1f{ex.label}\x1f{p.name}\x1f{attempt}".encode()
        digest = hmac.new(secret, msg, hashlib.sha256).digest()
        out[p.name] = values[int.from_bytes(digest[:8], "big") % len(values)]
    return out


def draw(ex: Exercise, secret: bytes, student: str, attempts: int = 50):
    """A meaningful parameter set of ``ex`` for one student and its answers: sets are drawn (:func:`draw_params`)
    until one is answered by the package without error (a reachable point, a stable gain, a payload the arm
    carries). Returns ``(params, results)``; raises :class:`~scara.errors.ScaraError` when no such set turns up in
    ``attempts`` draws (the ranges are too narrow, or mostly meaningless). That no two students of a roster share
    a set is :func:`scara.course.assign.assign`'s to ensure."""
    reasons = []
    for attempt in range(attempts):
        params = draw_params(ex, secret, student, attempt)
        try:
            return params, solve(ex.label, params)
        except ScaraError as exc:
            reasons.append(str(exc).split("\n")[0])
    raise ScaraError(f"exercise {ex.label!r}: no meaningful parameter set for student {student!r} in {attempts} "
                     f"draws; the last refusals: {reasons[-3:]}")
