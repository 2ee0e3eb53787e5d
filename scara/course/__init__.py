"""The course as a teacher runs it: the book's exercises as data, the two editions of the book, an assignment for
each student and its offline grading.

* :mod:`scara.course.exercises`: each exercise's parameters, answers (unit, tolerance) or marking note, declared
  once per chapter in :mod:`scara.course.chapters`; the computations that answer them in
  :mod:`scara.course.answers` (the key, left out of the student edition).
* ``python -m scara.course edition student`` writes and builds the student edition of the book: no solution, no
  answer key, no answers module anywhere in it.
* ``python -m scara.course assign`` writes each student's own assignment and the teacher's key;
  ``python -m scara.course grade`` runs the submitted notebooks, each in a sandbox, and marks them.
"""
from scara.course.exercises import (Answer, Exercise, Param, answer_key, catalog, chapter_exercises, exercise,
                                    glue_solution, glue_statement, solve)

__all__ = ["Answer", "Exercise", "Param", "answer_key", "catalog", "chapter_exercises", "exercise",
           "glue_solution", "glue_statement", "solve"]
