"""The reference scenario of chapter 3 (section The reference path): the 70 s path every later chapter tracks.

Twelve points, straight segments except the half circle ``p10 -> p11`` (centre ``[0.23, 0.20, 0.5]``, radius
0.05 m, through ``[0.23, 0.25, 0.5]``), via points ``p3, p4, p5, p8`` with anticipations 1.5, 2.0, 1.5 and
1.6 s, ``phi`` held at the start configuration's value (elbow ``theta2 < 0``, ``theta4 = 0``).

The segment durations below are our choice (the scenario fixes only the points, the via points and the anticipations). They give every segment a cruise speed
between 1 and 7 cm/s and accelerations under 0.03 m/s^2, leave each anticipation no longer than the blends
it overlaps (so each corner is rounded by two parabolic blends and nothing else), never let three segments
overlap, and end the motion at 66 s, leaving the arm at rest at ``p11`` for the last 4 s of the 70 s.
"""
from __future__ import annotations

import numpy as np

from .planner import Trajectory, Waypoint, plan_path

__all__ = [
    "REFERENCE_POINTS", "REFERENCE_ANTICIPATIONS", "REFERENCE_DURATIONS", "REFERENCE_ARC_THROUGH",
    "REFERENCE_TOTAL", "reference_plan", "reference_trajectory",
]

#: the twelve points p0 ... p11 of the reference scenario (chapter 3; m, base frame)
REFERENCE_POINTS = np.array([
    [0.18, 0.20, 0.5], [0.14, 0.20, 0.5], [0.10, 0.20, 0.2], [0.05, 0.15, 0.5],
    [0.10, 0.10, 0.5], [0.225, 0.10, 0.5], [0.35, 0.10, 0.5], [0.70, 0.15, 0.3],
    [0.35, 0.20, 0.5], [0.30, 0.20, 0.5], [0.28, 0.20, 0.5], [0.18, 0.20, 0.5],
])
REFERENCE_POINTS.flags.writeable = False
#: anticipation (s) at each via point, by waypoint index (chapter 3)
REFERENCE_ANTICIPATIONS = {3: 1.5, 4: 2.0, 5: 1.5, 8: 1.6}
#: duration (s) of segment j = p_j -> p_{j+1}: our choice, shown in the chapter's table
REFERENCE_DURATIONS = (4.0, 8.0, 8.0, 6.0, 6.0, 5.0, 9.0, 9.0, 5.0, 3.0, 9.6)
#: the half circle p10 -> p11 (segment 10) passes through this point (chapter 3)
REFERENCE_ARC_THROUGH = (0.23, 0.25, 0.5)
#: length of the scenario (s)
REFERENCE_TOTAL = 70.0


def reference_plan() -> dict:
    """The keyword arguments of :func:`plan_path` that give the reference scenario of chapter 3 (a fresh copy each
    call, ready to edit): ``plan_path(**reference_plan())`` is :func:`reference_trajectory`."""
    waypoints = [Waypoint(pt, anticipation=REFERENCE_ANTICIPATIONS.get(i, 0.0), label=f"p{i}")
                 for i, pt in enumerate(REFERENCE_POINTS)]
    return dict(waypoints=waypoints, durations=list(REFERENCE_DURATIONS), arcs={10: REFERENCE_ARC_THROUGH},
                total=REFERENCE_TOTAL, elbow=-1)


def reference_trajectory(dt: float = 1e-3, p=None) -> Trajectory:
    """The reference trajectory of chapter 3, sampled every ``dt`` (s): 70 s, ``t`` (N,), ``x``, ``xd``,
    ``xdd`` (N, 4) with ``x = [p_x, p_y, p_z, phi]``.

    ``dt`` must divide the durations and anticipations (1 ms, 10 ms, 0.1 s ... do).

    >>> traj = reference_trajectory()
    >>> traj.t.shape, traj.x.shape, traj.total
    ((70001,), (70001, 4), 70.0)
    """
    return plan_path(**reference_plan(), dt=dt, p=p)
