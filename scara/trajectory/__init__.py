"""Trajectory planning (chapter 3): in the operational space, path primitives, the trapezoidal timing law, stop
and via points, sampling at ``dt``, and the reference scenario of chapter 3; in the joint space, cubic and
quintic polynomials through a sequence of configurations.

Public names: :class:`Line`, :class:`Arc` (path primitives), :class:`Trapezoidal` and :func:`trapezoidal`
(timing law), :class:`Waypoint`, :func:`plan_path` and the :class:`Trajectory` it returns,
:func:`reference_trajectory` and :func:`reference_plan` (the book's scenario); :func:`cubic`, :func:`quintic`
(one joint-space segment), :func:`joint_trajectory` (a sequence through via points) and the
:class:`JointTrajectory` they return, :func:`joint_counterpart` (the joint-space trajectory through an
operational plan's waypoints), :func:`passage_times`, :func:`path_deviation` and :func:`segment_deviations`
(how far its tool strays from the operational path) and :func:`compare_joint_space` (the two side by side).
"""
from .paths import Arc, Line
from .planner import Trajectory, Waypoint, plan_path, start_orientation
from .reference import (
    REFERENCE_ANTICIPATIONS, REFERENCE_ARC_THROUGH, REFERENCE_DURATIONS, REFERENCE_POINTS, REFERENCE_TOTAL,
    reference_plan, reference_trajectory,
)
from .timing import DEFAULT_BLEND_FRACTION, Trapezoidal, trapezoidal
from .joint import (
    JointTrajectory, compare_joint_space, cubic, joint_counterpart, joint_trajectory, passage_times, path_deviation,
    quintic, segment_deviations,
)

__all__ = [
    "Line", "Arc", "Trapezoidal", "trapezoidal", "DEFAULT_BLEND_FRACTION", "Waypoint", "Trajectory", "plan_path",
    "start_orientation", "reference_plan", "reference_trajectory", "REFERENCE_POINTS", "REFERENCE_ANTICIPATIONS",
    "REFERENCE_DURATIONS", "REFERENCE_ARC_THROUGH", "REFERENCE_TOTAL",
    "JointTrajectory", "cubic", "quintic", "joint_trajectory", "joint_counterpart", "passage_times", "path_deviation",
    "segment_deviations", "compare_joint_space",
]
