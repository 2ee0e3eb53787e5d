"""Operational-space trajectory planning (chapter 3): path primitives, the trapezoidal timing law, stop and
via points, sampling at ``dt``, and the reference scenario of chapter 3.

Public names: :class:`Line`, :class:`Arc` (path primitives), :class:`Trapezoidal` and :func:`trapezoidal`
(timing law), :class:`Waypoint`, :func:`plan_path` and the :class:`Trajectory` it returns,
:func:`reference_trajectory` and :func:`reference_plan` (the book's scenario).
"""
from .paths import Arc, Line
from .planner import Trajectory, Waypoint, plan_path, start_orientation
from .reference import (
    REFERENCE_ANTICIPATIONS, REFERENCE_ARC_THROUGH, REFERENCE_DURATIONS, REFERENCE_POINTS, REFERENCE_TOTAL,
    reference_plan, reference_trajectory,
)
from .timing import DEFAULT_BLEND_FRACTION, Trapezoidal, trapezoidal

__all__ = [
    "Line", "Arc", "Trapezoidal", "trapezoidal", "DEFAULT_BLEND_FRACTION", "Waypoint", "Trajectory", "plan_path",
    "start_orientation", "reference_plan", "reference_trajectory", "REFERENCE_POINTS", "REFERENCE_ANTICIPATIONS",
    "REFERENCE_DURATIONS", "REFERENCE_ARC_THROUGH", "REFERENCE_TOTAL",
]
