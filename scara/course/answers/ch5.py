"""The computations answering this chapter's exercises (see scara.course.answers)."""
from scara.course.answers import solves  # noqa: F401
