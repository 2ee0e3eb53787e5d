"""Exercises of this chapter as data (see scara.course.exercises)."""
from scara.course.exercises import Answer, Exercise, Param  # noqa: F401

EXERCISES = ()
