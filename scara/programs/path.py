"""An operational-space plan (chapter 3) packed as a float vector, and the kernels that plan and sample it.

:func:`plan_vector` packs a planned trajectory (a :class:`~scara.trajectory.Trajectory`, or the keyword arguments
of :func:`~scara.trajectory.plan_path`) as the *plan* below; :func:`sample_plan` samples it every ``dt`` and
:func:`evaluate_plan` at any times, by eq. 4.56 (a segment ``j`` moves its trapezoidal law ``s_j`` from its
start ``k0_j dt`` to its end ``k1_j dt``, the displacements of the segments add up). They are the kernels of
:mod:`scara.trajectory._plan` that :func:`~scara.trajectory.plan_path` itself runs, so that
``sample_plan(plan_vector(reference_trajectory()), t, x, xd, xdd)`` gives the reference trajectory's ``t, x,
xd, xdd`` exactly. :func:`build_plan` makes a plan from a *spec* (a plan's inputs, :func:`plan_spec`), with every
check of :func:`~scara.trajectory.plan_path` returned as a code (see :mod:`scara.trajectory._plan`).

The spec (inputs of a plan of ``n`` waypoints and ``m = n - 1`` segments), ``spec_size(n)`` floats::

    0  n            1  dt (s)         2  total (s; NaN: the end of the motion)   3  phi (rad; NaN: none)
    4  elbow (+1/-1) 5  check (0/1)   6  a1   7  a2   8  d0   9  d3_min   10  d3_max  (m)
    11 + 6 i        waypoint i: x, y, z (m), anticipation (s), 1 if it has its own phi, that phi (rad)
    11 + 6 n + 21 j segment j: duration (s), blend (s; NaN: a third of the duration), arc kind (0 a line,
                    1 the arc through a point, 2 a given arc), then 18 numbers: the point (kind 1), or the
                    arc's start, end, centre, u, v (3 each), radius, angle, length (kind 2)

The plan (the planned path), ``plan_size(n)`` floats::

    0  n      1  dt (s)      2  K, the last sample (N = K + 1 samples)    3  the last sample of the motion
    4  x0 = [p_x, p_y, p_z, phi] at the start (4)    8  q0, the start configuration (4)    12  elbow
    13 a1  14 a2  15 d0  16 d3_min  17 d3_max (m): the arm the plan is checked against
    18 + 6 i        waypoint i: x, y, z (m), phi (rad), anticipation (s), its number of samples
    18 + 6 n + 25 j segment j: kind (0 line, 1 arc), k0 and k1 (first and end sample), length L (m),
                    duration T (s), blend t_c (s), cruise speed v_c (m/s), acceleration a (m/s^2), phi change
                    (rad), displacement end - start (3, m), line tangent (3), radius (m), arc axes u and v
                    (3 each), centre (3, m)

The offsets are the constants of :mod:`scara.trajectory._plan` (``S_*``, ``W_*``, ``G_*`` for the spec,
``P_*``, ``V_*``, ``Q_*`` for the plan).
"""
from __future__ import annotations

import numpy as np

from ..trajectory._plan import (build_plan, evaluate_plan, plan_at, plan_extremes, plan_reach, plan_size,
                                sample_plan, spec_size)

__all__ = ["plan_vector", "plan_spec", "sample_plan", "evaluate_plan", "build_plan", "plan_at", "plan_reach",
           "plan_extremes", "plan_size", "spec_size"]


def plan_vector(traj_or_plan_args) -> np.ndarray:
    """The plan (layout of the module's docstring) of a :class:`~scara.trajectory.Trajectory`, or of the keyword
    arguments of :func:`~scara.trajectory.plan_path` (planned, checked and sampled by it): a new float vector.

    >>> from scara import reference_plan
    >>> v = plan_vector(reference_plan())
    >>> int(v[0]), int(v[2]) + 1          # 12 waypoints, 70 001 samples
    (12, 70001)
    """
    from ..trajectory import Trajectory, plan_path  # noqa: PLC0415

    traj = traj_or_plan_args
    if not isinstance(traj, Trajectory):
        traj = plan_path(**dict(traj_or_plan_args))
    return np.array(traj.plan_vector, dtype=float)


def plan_spec(plan_args: dict) -> np.ndarray:
    """The spec (layout of the module's docstring) of the keyword arguments of
    :func:`~scara.trajectory.plan_path`, their types, shapes and signs checked: what :func:`build_plan` plans."""
    from ..trajectory.planner import plan_spec as _spec  # noqa: PLC0415

    return _spec(**dict(plan_args))
