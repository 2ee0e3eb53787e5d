"""The exercises of each chapter, as data (:class:`scara.course.exercises.Exercise`), one module per chapter,
each listing its chapter's exercises in the book's order (``EXERCISES``). The statements and worked solutions in
the chapters' notebooks take their numbers from here and from :mod:`scara.course.answers`."""
