"""The compiled core of the operational-space planner (chapter 3): a plan's inputs packed as a float vector (the
*spec*), checked and resolved by :func:`build_plan` into the planned path packed as another float vector (the
*plan*: segments, timing laws, schedule, orientations), sampled by :func:`sample_plan` (at ``dt``) or
:func:`evaluate_plan` (at any times), checked against the workspace by :func:`plan_reach`, and summarised by
:func:`plan_extremes` and :func:`corner_distance`.

:func:`~scara.trajectory.plan_path` runs exactly these kernels, and so does the live waypoint editor's page
program (:mod:`scara.programs.trajectory`): the planner is written once. The layouts of both vectors are listed
in :mod:`scara.programs.path`; the offsets below are their single definition.

Every check a plan can fail returns a code (the constants ``DURATION_*`` ... ``WAYPOINT_*``) and writes the
numbers its message needs into ``info`` (the fields of :data:`INFO`); :func:`~scara.trajectory.plan_path` words
them as exceptions, the editor's program as the texts of its refusals.
"""
from __future__ import annotations

import math

import numpy as np

from .._compile import ArrayLayout, kernel
from ..kinematics import IK_OK, IK_OUTSIDE_STROKE, ikine_kernel, reach_kernel
from .paths import (ARC_COLLINEAR, ARC_END_OFF_CIRCLE, ARC_END_OFF_PLANE, ARC_NORMAL_ZERO,  # noqa: F401 - codes
                    ARC_OVERFLOW, ARC_RADIUS_OVERFLOW, ARC_RADIUS_TOO_SMALL, ARC_SAME_ENDS, ARC_START_OFF_CIRCLE,
                    ARC_START_OFF_PLANE, LINE_OVERFLOW)
from .paths import (ARC_LENGTH, ARC_OUT, ARC_RADIUS, ARC_U, ARC_V, GEOMETRY_OK, GEOMETRY_TOL, arc_geometry,
                    arc_through, line_geometry)
from .timing import DEFAULT_BLEND_FRACTION, LAW_BLEND_TOO_LONG, LAW_NOT_FINITE, LAW_OK, trapezoid_at, trapezoid_check

#: largest number of samples of a planned trajectory (``total / dt + 1``), checked before any work: each sample
#: holds ``t``, ``x``, ``xd``, ``xdd`` (104 bytes), so the limit caps a plan at about 200 MB; the reference
#: scenario has 70 001 samples at 1 ms
MAX_SAMPLES = 2_000_000

# --------------------------------------------------------------------------------------------------
# the spec: a plan's inputs (see scara.programs.path for the table)
# --------------------------------------------------------------------------------------------------
S_N, S_DT, S_TOTAL, S_PHI, S_ELBOW, S_CHECK, S_A1, S_A2, S_D0, S_D3_MIN, S_D3_MAX = range(11)
SPEC_HEAD = 11
#: per waypoint: position, anticipation (s), 1 when it has its own phi, that phi (rad)
W_X, W_Y, W_Z, W_ANT, W_HAS_PHI, W_PHI = range(6)
SPEC_WAYPOINT = 6
#: per segment: duration (s), blend (s; NaN: a third of the duration), arc kind, arc data
G_DURATION, G_BLEND, G_ARC, G_DATA = 0, 1, 2, 3
#: arc kinds: a line, the arc through a point (``G_DATA``: the point), a given arc (``G_DATA``: start, end,
#: centre, u, v, radius, angle, length)
ARC_NONE, ARC_THROUGH, ARC_GIVEN = 0, 1, 2
GA_START, GA_END, GA_CENTRE, GA_U, GA_V, GA_RADIUS, GA_ANGLE, GA_LENGTH = 0, 3, 6, 9, 12, 15, 16, 17
SPEC_SEGMENT = 3 + 18

# --------------------------------------------------------------------------------------------------
# the plan: the planned path (see scara.programs.path for the table)
# --------------------------------------------------------------------------------------------------
P_N, P_DT, P_K, P_K_END, P_X0, P_Q0, P_ELBOW, P_A1, P_A2, P_D0, P_D3_MIN, P_D3_MAX = 0, 1, 2, 3, 4, 8, 12, 13, 14, 15, 16, 17
PLAN_HEAD = 18
#: per waypoint: position, phi (rad), anticipation (s, the samples' count times dt), its number of samples
V_X, V_Y, V_Z, V_PHI, V_ANT, V_NA = range(6)
PLAN_WAYPOINT = 6
#: per segment: kind (0 line, 1 arc), first and end sample, length, duration, blend, cruise speed,
#: acceleration, phi change, displacement end - start (3), line tangent (3), radius, arc axes u, v, centre (3 each)
(Q_KIND, Q_K0, Q_K1, Q_L, Q_T, Q_TC, Q_V, Q_A, Q_DPHI, Q_D, Q_TANGENT, Q_RADIUS, Q_U, Q_AV,
 Q_CENTRE) = 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 12, 15, 16, 19, 22
PLAN_SEGMENT = 25

#: the numbers a refused plan's message needs (``info`` of :func:`build_plan` and :func:`plan_reach`): waypoint
#: labels ``w_a``, ``w_b`` (their indices), segments ``s_a``, ``s_b``, ``s_c``, ``s_d`` (the index of each and of
#: its end waypoint ``s_a1`` ...), seconds, the point met (``px, py, pz`` rounded to 4 decimals as the package prints a
#: point, ``phi_deg``, ``z_exact``, its distance ``r`` from the joint-1 axis, ``d3 = d0 - p_z``), the arm's limits,
#: and three points ``a, b, c``
INFO = ArrayLayout(
    ("w_a", 1), ("w_b", 1), ("s_a", 1), ("s_a1", 1), ("s_b", 1), ("s_b1", 1), ("s_c", 1), ("s_c1", 1), ("s_d", 1),
    ("s_d1", 1),
    ("value", 1), ("periods", 1), ("dt", 1), ("ant", 1), ("dur_a", 1), ("dur_b", 1), ("blend", 1), ("half", 1),
    ("speed", 1), ("acc", 1), ("total", 1), ("motion_end_at", 1), ("samples", 1),
    ("px", 1), ("py", 1), ("pz", 1), ("phi_deg", 1), ("z_exact", 1), ("r", 1), ("d3", 1), ("t_out", 1),
    ("sample", 1), ("r_min", 1), ("r_max", 1), ("d3_min", 1), ("d3_max", 1),
    ("ax", 1), ("ay", 1), ("az", 1), ("bx", 1), ("by", 1), ("bz", 1), ("cx", 1), ("cy", 1), ("cz", 1),
)
(I_W_A, I_W_B, I_S_A, I_S_A1, I_S_B, I_S_B1, I_S_C, I_S_C1, I_S_D, I_S_D1, I_VALUE, I_PERIODS, I_DT, I_ANT, I_DUR_A, I_DUR_B,
 I_BLEND, I_HALF, I_SPEED, I_ACC, I_TOTAL, I_MOTION_END, I_SAMPLES, I_PX, I_PY, I_PZ, I_PHI_DEG, I_Z, I_R, I_D3,
 I_T_OUT, I_SAMPLE, I_R_MIN, I_R_MAX, I_D3_MIN, I_D3_MAX, I_AX, I_AY, I_AZ, I_BX, I_BY, I_BZ, I_CX, I_CY,
 I_CZ) = INFO.offsets
INFO_SIZE = INFO.size

__all__ = ["build_plan", "sample_plan", "evaluate_plan", "plan_at", "segment_add", "moving_segments", "plan_reach",
           "plan_extremes", "corner_distance", "whole_samples", "rint", "round4", "spec_size", "plan_size",
           "MAX_SAMPLES", "INFO", "ARC_COLLINEAR", "ARC_END_OFF_CIRCLE", "ARC_END_OFF_PLANE", "ARC_NORMAL_ZERO",
           "ARC_OVERFLOW", "ARC_RADIUS_OVERFLOW", "ARC_RADIUS_TOO_SMALL", "ARC_SAME_ENDS", "ARC_START_OFF_CIRCLE",
           "ARC_START_OFF_PLANE", "LINE_OVERFLOW"]

# the codes (9-19 are those of the geometry kernels, scara.trajectory.paths: LINE_OVERFLOW, ARC_OVERFLOW,
# ARC_COLLINEAR, ARC_NORMAL_ZERO ... ARC_SAME_ENDS; 21-22 those of the timing law, scara.trajectory.timing)
PLAN_OK = 0
DURATION_TOO_MANY = 1
DURATION_NOT_WHOLE = 2
VIA_FIRST = 3
VIA_LAST = 4
ANTICIPATION_TOO_LONG = 5
ANTICIPATION_TOO_MANY = 6
ANTICIPATION_NOT_WHOLE = 7
REPEATED_POINT = 8
#: the trapezoidal law's codes (:func:`~scara.trajectory.timing.trapezoid_check`)
LAW_BLEND = LAW_BLEND_TOO_LONG
LAW_NOT_FINITE = LAW_NOT_FINITE
GIVEN_ARC_START = 23
GIVEN_ARC_END = 24
START_OUTSIDE_ANNULUS = 25
START_OUTSIDE_STROKE = 26
MOTION_TOO_MANY = 27
TOTAL_TOO_MANY = 28
TOTAL_NOT_WHOLE = 29
TOTAL_SAMPLES_TOO_MANY = 30
TOTAL_TOO_SHORT = 31
#: a sample out of reach: ``SAMPLE_OUT + 2 * where + why``, ``where`` 0-4 for one to five or more segments
#: moving (:data:`I_S_A`, :data:`I_S_B`, :data:`I_S_C` the first three, :data:`I_S_D` the last), 5 at rest after
#: the last one; ``why`` 0 outside the annulus, 1 outside the stroke
SAMPLE_OUT = 40
SAMPLE_NOT_FINITE = 55
WAYPOINT_OUTSIDE_ANNULUS = 56
WAYPOINT_OUTSIDE_STROKE = 57


def spec_size(n: int) -> int:
    """The length of the spec of a plan of ``n`` waypoints."""
    return SPEC_HEAD + SPEC_WAYPOINT * n + SPEC_SEGMENT * (n - 1)


def plan_size(n: int) -> int:
    """The length of the plan vector of ``n`` waypoints."""
    return PLAN_HEAD + PLAN_WAYPOINT * n + PLAN_SEGMENT * (n - 1)


@kernel(light=True)
def spec_waypoint(n, i):
    """The offset of waypoint ``i``'s block in the spec of ``n`` waypoints."""
    return SPEC_HEAD + SPEC_WAYPOINT * i


@kernel(light=True)
def spec_segment(n, j):
    """The offset of segment ``j``'s block in the spec of ``n`` waypoints."""
    return SPEC_HEAD + SPEC_WAYPOINT * n + SPEC_SEGMENT * j


@kernel(light=True)
def plan_waypoint(n, i):
    """The offset of waypoint ``i``'s block in the plan of ``n`` waypoints."""
    return PLAN_HEAD + PLAN_WAYPOINT * i


@kernel(light=True)
def plan_segment(n, j):
    """The offset of segment ``j``'s block in the plan of ``n`` waypoints."""
    return PLAN_HEAD + PLAN_WAYPOINT * n + PLAN_SEGMENT * j


@kernel(light=True)
def whole_samples(value, dt):
    """``(code, n)``: ``value`` (s) as ``n`` sampling periods ``dt``; the code is 1 when ``value / dt`` exceeds
    :data:`MAX_SAMPLES` (or is NaN), 2 when it is more than 1e-6 periods away from a whole number, 0 otherwise."""
    periods = value / dt
    if not periods <= MAX_SAMPLES:
        return 1, 0.0
    n = math.floor(periods + 0.5)
    if abs(value / dt - n) > 1e-6:
        return 2, n
    return 0, n


@kernel
def rint(v):
    """``v`` rounded to the nearest whole number, a half to the even one (numpy's ``round``)."""
    f = math.floor(v)
    d = v - f
    if d > 0.5 or (d == 0.5 and f % 2 != 0):
        return f + 1.0
    return f


@kernel
def round4(v):
    """``v`` rounded to 4 decimals (a half to the even digit), as the package prints the coordinates of a point in
    a message."""
    return rint(v * 1e4) / 1e4


@kernel
def _point_info(info, px, py, pz, phi, d0):
    """Write the point ``(px, py, pz, phi)`` a message names into ``info``."""
    info[I_PX] = round4(px)
    info[I_PY] = round4(py)
    info[I_PZ] = round4(pz)
    info[I_PHI_DEG] = math.degrees(round4(phi))
    info[I_Z] = pz
    info[I_R] = math.hypot(px, py)
    info[I_D3] = d0 - pz


@kernel
def _limits_info(info, a1, a2, d3_min, d3_max):
    """Write the arm's limits into ``info``: the annulus ``|a1 - a2| <= r <= a1 + a2`` and the stroke."""
    info[I_R_MIN] = abs(a1 - a2)
    info[I_R_MAX] = a1 + a2
    info[I_D3_MIN] = d3_min
    info[I_D3_MAX] = d3_max


@kernel
def _segment_info(info, j):
    info[I_S_A] = j
    info[I_S_A1] = j + 1


@kernel(light=True)
def build_plan(spec, plan, info):
    """Check and resolve a plan's inputs ``spec`` into the planned path ``plan`` (the layouts of
    :mod:`scara.programs.path`), in the planner's order: the segments' numbers of samples, the blends (a third of
    each duration by default), the anticipations (inner waypoints only, shorter than both segments they join),
    the segments' geometry (lines, eq. 4.34; arcs, eq. 4.37), their trapezoidal laws (eqs. 4.8-4.9), the
    orientations (the start configuration's ``theta1 + theta2`` unless given), the schedule (segment ``j + 1``
    starts its anticipation before segment ``j`` ends, eq. 4.56) and the start configuration ``q0``.

    Returns 0, or the code of the first check that fails with the numbers of its message in ``info``
    (:data:`INFO`). Types, shapes and signs are the caller's to check (:func:`~scara.trajectory.plan_path` does)."""
    for i in range(info.shape[0]):
        info[i] = 0.0
    n = int(spec[S_N])
    m = n - 1
    dt = spec[S_DT]
    info[I_DT] = dt
    a1, a2, d0 = spec[S_A1], spec[S_A2], spec[S_D0]
    d3_min, d3_max = spec[S_D3_MIN], spec[S_D3_MAX]
    _limits_info(info, a1, a2, d3_min, d3_max)
    elbow = spec[S_ELBOW]
    nT = np.empty(m)
    nA = np.zeros(n)
    # the durations as whole numbers of samples
    for j in range(m):
        g = spec_segment(n, j)
        value = spec[g + G_DURATION]
        code, k = whole_samples(value, dt)
        if code != 0:
            _segment_info(info, j)
            info[I_VALUE] = value
            info[I_PERIODS] = value / dt
            return DURATION_TOO_MANY if code == 1 else DURATION_NOT_WHOLE
        nT[j] = k
    # the anticipations: inner waypoints only, shorter than both segments they join
    for end in range(2):
        i = 0 if end == 0 else n - 1
        ant = spec[spec_waypoint(n, i) + W_ANT]
        if ant > 0:
            info[I_W_A] = i
            info[I_ANT] = ant
            return VIA_FIRST if i == 0 else VIA_LAST
    for i in range(1, n - 1):
        ant = spec[spec_waypoint(n, i) + W_ANT]
        if ant > 0:
            t_before = nT[i - 1] * dt
            t_after = nT[i] * dt
            if ant >= t_before or ant >= t_after:
                info[I_W_A] = i
                info[I_ANT] = ant
                _segment_info(info, i - 1)
                info[I_S_B] = i
                info[I_S_B1] = i + 1
                info[I_DUR_A] = t_before
                info[I_DUR_B] = t_after
                return ANTICIPATION_TOO_LONG
            code, k = whole_samples(ant, dt)
            if code != 0:
                info[I_W_A] = i
                info[I_VALUE] = ant
                info[I_PERIODS] = ant / dt
                return ANTICIPATION_TOO_MANY if code == 1 else ANTICIPATION_NOT_WHOLE
            nA[i] = k
    # the segments' geometry
    geo = np.zeros(ARC_OUT)
    centre = np.zeros(6)
    for j in range(m):
        wa = spec_waypoint(n, j)
        wb = spec_waypoint(n, j + 1)
        pa = spec[wa:wa + 3]
        pb = spec[wb:wb + 3]
        q = plan_segment(n, j)
        g = spec_segment(n, j)
        for c in range(PLAN_SEGMENT):
            plan[q + c] = 0.0
        dx, dy, dz = pb[0] - pa[0], pb[1] - pa[1], pb[2] - pa[2]
        if math.sqrt(dx * dx + dy * dy + dz * dz) <= GEOMETRY_TOL:
            info[I_W_A] = j
            info[I_W_B] = j + 1
            _segment_info(info, j)
            info[I_AX] = round4(pa[0])
            info[I_AY] = round4(pa[1])
            info[I_AZ] = round4(pa[2])
            return REPEATED_POINT
        kind = spec[g + G_ARC]
        if kind == ARC_NONE:
            code, length, tx, ty, tz = line_geometry(pa, pb)
            if code != GEOMETRY_OK:
                _segment_info(info, j)
                return code
            plan[q + Q_KIND] = 0.0
            plan[q + Q_L] = length
            plan[q + Q_TANGENT] = tx
            plan[q + Q_TANGENT + 1] = ty
            plan[q + Q_TANGENT + 2] = tz
            plan[q + Q_D] = pb[0] - pa[0]
            plan[q + Q_D + 1] = pb[1] - pa[1]
            plan[q + Q_D + 2] = pb[2] - pa[2]
            continue
        plan[q + Q_KIND] = 1.0
        if kind == ARC_THROUGH:
            via = spec[g + G_DATA:g + G_DATA + 3]
            info[I_AX], info[I_AY], info[I_AZ] = round4(pa[0]), round4(pa[1]), round4(pa[2])
            info[I_BX], info[I_BY], info[I_BZ] = round4(via[0]), round4(via[1]), round4(via[2])
            info[I_CX], info[I_CY], info[I_CZ] = round4(pb[0]), round4(pb[1]), round4(pb[2])
            code = arc_through(pa, via, pb, centre)
            if code == GEOMETRY_OK:
                code = arc_geometry(centre[0:3], pa, pb, centre[3:6], math.nan, geo)
            if code != GEOMETRY_OK:
                _segment_info(info, j)
                return code
            for c in range(3):
                plan[q + Q_CENTRE + c] = centre[c]
                plan[q + Q_U + c] = geo[ARC_U + c]
                plan[q + Q_AV + c] = geo[ARC_V + c]
                plan[q + Q_D + c] = pb[c] - pa[c]
            plan[q + Q_RADIUS] = geo[ARC_RADIUS]
            plan[q + Q_L] = geo[ARC_LENGTH]
            continue
        # a given arc: its ends must be the segment's waypoints
        d = g + G_DATA
        for end in range(2):
            pt = pa if end == 0 else pb
            o = d + (GA_START if end == 0 else GA_END)
            ex, ey, ez = spec[o] - pt[0], spec[o + 1] - pt[1], spec[o + 2] - pt[2]
            if math.sqrt(ex * ex + ey * ey + ez * ez) > GEOMETRY_TOL:
                _segment_info(info, j)
                info[I_AX], info[I_AY], info[I_AZ] = round4(spec[o]), round4(spec[o + 1]), round4(spec[o + 2])
                info[I_BX], info[I_BY], info[I_BZ] = round4(pt[0]), round4(pt[1]), round4(pt[2])
                return GIVEN_ARC_START if end == 0 else GIVEN_ARC_END
        for c in range(3):
            plan[q + Q_CENTRE + c] = spec[d + GA_CENTRE + c]
            plan[q + Q_U + c] = spec[d + GA_U + c]
            plan[q + Q_AV + c] = spec[d + GA_V + c]
            plan[q + Q_D + c] = spec[d + GA_END + c] - spec[d + GA_START + c]
        plan[q + Q_RADIUS] = spec[d + GA_RADIUS]
        plan[q + Q_L] = spec[d + GA_LENGTH]
    # the timing laws
    for j in range(m):
        q = plan_segment(n, j)
        g = spec_segment(n, j)
        T = nT[j] * dt
        b = spec[g + G_BLEND]
        tc = DEFAULT_BLEND_FRACTION * T if math.isnan(b) else b
        L = plan[q + Q_L]
        code, blend, v, a = trapezoid_check(L, T, tc)
        if code != LAW_OK:
            _segment_info(info, j)
            info[I_VALUE] = L
            info[I_DUR_A] = T
            info[I_BLEND] = tc if code == LAW_BLEND_TOO_LONG else blend
            info[I_HALF] = T / 2
            info[I_SPEED] = v
            info[I_ACC] = a
            return code
        plan[q + Q_T] = T
        plan[q + Q_TC] = blend
        plan[q + Q_V] = v
        plan[q + Q_A] = a
    # the orientations: each waypoint's own phi, else the one before it; the first is the waypoint's, the
    # plan's phi, or the start configuration's theta1 + theta2 (elbow as given, theta4 = 0)
    w0 = spec_waypoint(n, 0)
    xq = np.empty(4)
    q0 = np.zeros(4)
    if spec[w0 + W_HAS_PHI] != 0:
        phi = spec[w0 + W_PHI]
    elif math.isnan(spec[S_PHI]):
        xq[0], xq[1], xq[2], xq[3] = spec[w0 + W_X], spec[w0 + W_Y], spec[w0 + W_Z], 0.0
        code = ikine_kernel(xq, a1, a2, d0, d3_min, d3_max, elbow, q0)
        if code != IK_OK:
            _point_info(info, xq[0], xq[1], xq[2], 0.0, d0)
            return START_OUTSIDE_STROKE if code == IK_OUTSIDE_STROKE else START_OUTSIDE_ANNULUS
        phi = q0[0] + q0[1]
    else:
        phi = spec[S_PHI]
    for i in range(n):
        w = spec_waypoint(n, i)
        if spec[w + W_HAS_PHI] != 0:
            phi = spec[w + W_PHI]
        v = plan_waypoint(n, i)
        plan[v + V_X] = spec[w + W_X]
        plan[v + V_Y] = spec[w + W_Y]
        plan[v + V_Z] = spec[w + W_Z]
        plan[v + V_PHI] = phi
        plan[v + V_NA] = nA[i]
        plan[v + V_ANT] = nA[i] * dt
    for j in range(m):
        q = plan_segment(n, j)
        plan[q + Q_DPHI] = plan[plan_waypoint(n, j + 1) + V_PHI] - plan[plan_waypoint(n, j) + V_PHI]
    # the schedule
    k0 = 0.0
    k_end = 0.0
    for j in range(m):
        q = plan_segment(n, j)
        if j > 0:
            k0 = k0 + nT[j - 1] - nA[j]
        plan[q + Q_K0] = k0
        plan[q + Q_K1] = k0 + nT[j]
        k_end = max(k_end, k0 + nT[j])
    if k_end + 1 > MAX_SAMPLES:
        info[I_MOTION_END] = k_end * dt
        info[I_SAMPLES] = k_end + 1
        return MOTION_TOO_MANY
    k_total = k_end
    total = spec[S_TOTAL]
    if not math.isnan(total):
        info[I_TOTAL] = total
        code, k = whole_samples(total, dt)
        if code != 0:
            info[I_VALUE] = total
            info[I_PERIODS] = total / dt
            return TOTAL_TOO_MANY if code == 1 else TOTAL_NOT_WHOLE
        if k + 1 > MAX_SAMPLES:
            info[I_SAMPLES] = k + 1
            return TOTAL_SAMPLES_TOO_MANY
        if k < k_end:
            info[I_MOTION_END] = k_end * dt
            return TOTAL_TOO_SHORT
        k_total = k
    # the start configuration
    xq[0], xq[1], xq[2], xq[3] = spec[w0 + W_X], spec[w0 + W_Y], spec[w0 + W_Z], plan[plan_waypoint(n, 0) + V_PHI]
    code = ikine_kernel(xq, a1, a2, d0, d3_min, d3_max, elbow, q0)
    if code != IK_OK:
        _point_info(info, xq[0], xq[1], xq[2], xq[3], d0)
        return START_OUTSIDE_STROKE if code == IK_OUTSIDE_STROKE else START_OUTSIDE_ANNULUS
    plan[P_N] = n
    plan[P_DT] = dt
    plan[P_K] = k_total
    plan[P_K_END] = k_end
    for c in range(4):
        plan[P_X0 + c] = plan[plan_waypoint(n, 0) + c]
        plan[P_Q0 + c] = q0[c]
    plan[P_ELBOW] = elbow
    plan[P_A1] = a1
    plan[P_A2] = a2
    plan[P_D0] = d0
    plan[P_D3_MIN] = d3_min
    plan[P_D3_MAX] = d3_max
    return PLAN_OK


@kernel
def plan_at(plan, time, x, xd, xdd):
    """``x, xd, xdd`` (4,) of the plan at ``time`` (s), by eq. 4.56: the first waypoint, plus the displacement of
    every segment ended by ``time``, plus ``p_j(s_j) - p_j(0)`` of every segment moving (``s_j`` its trapezoidal
    law since its start; a line adds ``t s``, an arc ``rho ((cos(s/rho) - 1) u + sin(s/rho) v)``), with the
    velocities ``t sdot`` and accelerations ``t sddot + k sdot^2``; ``phi`` adds ``dphi_j s_j / L_j``. Before 0
    the arm is at the first waypoint; after the last segment it rests at the last one."""
    n = int(plan[P_N])
    m = n - 1
    dt = plan[P_DT]
    ex, ey, ez, ep = 0.0, 0.0, 0.0, 0.0
    for j in range(m):
        q = plan_segment(n, j)
        if time >= plan[q + Q_K1] * dt:
            ex += plan[q + Q_D]
            ey += plan[q + Q_D + 1]
            ez += plan[q + Q_D + 2]
            ep += plan[q + Q_DPHI]
    x[0] = plan[P_X0] + ex
    x[1] = plan[P_X0 + 1] + ey
    x[2] = plan[P_X0 + 2] + ez
    x[3] = plan[P_X0 + 3] + ep
    for c in range(4):
        xd[c] = 0.0
        xdd[c] = 0.0
    for j in range(m):
        q = plan_segment(n, j)
        if plan[q + Q_K0] * dt <= time < plan[q + Q_K1] * dt:
            segment_add(plan, q, time, x, xd, xdd)


@kernel
def segment_add(plan, q, time, x, xd, xdd):
    """Add the motion at ``time`` of the segment whose block starts at ``q`` (moving at ``time``) to ``x, xd,
    xdd`` (4,): ``p_j(s_j) - p_j(0)``, ``t sdot`` and ``t sddot + k sdot^2`` (a line: ``t`` constant, ``k = 0``; an
    arc: ``rho ((cos(s/rho) - 1) u + sin(s/rho) v)``, eq. 4.37), and ``dphi_j s_j / L_j`` to ``phi``, with
    ``s_j`` the segment's trapezoidal law since its start."""
    dt = plan[P_DT]
    t0 = plan[q + Q_K0] * dt
    L = plan[q + Q_L]
    s, sd, sdd = trapezoid_at(time - t0, L, plan[q + Q_T], plan[q + Q_TC], plan[q + Q_V], plan[q + Q_A])
    if plan[q + Q_KIND] == 0.0:
        for c in range(3):
            tc = plan[q + Q_TANGENT + c]
            if tc != 0.0:
                x[c] += tc * s
                xd[c] += tc * sd
                xdd[c] += tc * sdd
    else:
        rho = plan[q + Q_RADIUS]
        th = s / rho
        co = math.cos(th)
        sn = math.sin(th)
        cm1 = co - 1.0
        sd2 = sd * sd / rho
        for c in range(3):
            u = plan[q + Q_U + c]
            v = plan[q + Q_AV + c]
            if u == 0.0 and v == 0.0:
                continue
            tk = -sn * u + co * v
            x[c] += rho * (cm1 * u + sn * v)
            xd[c] += tk * sd
            xdd[c] += tk * sdd - (co * u + sn * v) * sd2
    dphi = plan[q + Q_DPHI]
    if dphi != 0.0:
        g = dphi / L
        x[3] += g * s
        xd[3] += g * sd
        xdd[3] += g * sdd


@kernel
def evaluate_plan(plan, t, x, xd, xdd):
    """:func:`plan_at` at every time of ``t`` (N,), in any order, written into the rows of ``x, xd, xdd``
    (N, 4). Returns 0, or 1 when the arrays' sizes disagree."""
    N = t.shape[0]
    if x.shape[0] != N or xd.shape[0] != N or xdd.shape[0] != N:
        return 1
    for k in range(N):
        plan_at(plan, t[k], x[k], xd[k], xdd[k])
    return 0


@kernel
def sample_plan(plan, t, x, xd, xdd):
    """Sample the plan every ``dt`` from 0 to its total: ``t[k] = k dt`` (N,) and :func:`plan_at` into the rows of
    ``x, xd, xdd`` (N, 4), ``N = K + 1`` with ``K = plan[P_K]``. Returns 0, or 1 when an array does not hold
    ``N`` rows."""
    N = int(plan[P_K]) + 1
    if t.shape[0] != N or x.shape[0] != N or xd.shape[0] != N or xdd.shape[0] != N:
        return 1
    n = int(plan[P_N])
    m = n - 1
    dt = plan[P_DT]
    # the same sums as plan_at, walking the segments forwards: those ended form a prefix (their ends increase)
    done = 0
    ex, ey, ez, ep = 0.0, 0.0, 0.0, 0.0
    for k in range(N):
        time = k * dt
        t[k] = time
        while done < m and time >= plan[plan_segment(n, done) + Q_K1] * dt:
            q = plan_segment(n, done)
            ex += plan[q + Q_D]
            ey += plan[q + Q_D + 1]
            ez += plan[q + Q_D + 2]
            ep += plan[q + Q_DPHI]
            done += 1
        row, rowd, rowdd = x[k], xd[k], xdd[k]
        row[0] = plan[P_X0] + ex
        row[1] = plan[P_X0 + 1] + ey
        row[2] = plan[P_X0 + 2] + ez
        row[3] = plan[P_X0 + 3] + ep
        for c in range(4):
            rowd[c] = 0.0
            rowdd[c] = 0.0
        j = done
        while j < m:
            q = plan_segment(n, j)
            if plan[q + Q_K0] * dt > time:
                break
            segment_add(plan, q, time, row, rowd, rowdd)
            j += 1
    return 0


@kernel
def moving_segments(plan, time):
    """``(first, last)``: the segments moving at ``time`` (``first <= j <= last``; ``start_j <= time <
    end_j``), or ``(-1, -1)`` when none is."""
    n = int(plan[P_N])
    dt = plan[P_DT]
    first = -1
    last = -1
    for j in range(n - 1):
        q = plan_segment(n, j)
        if plan[q + Q_K0] * dt <= time < plan[q + Q_K1] * dt:
            if first < 0:
                first = j
            last = j
    return first, last


@kernel
def plan_reach(plan, x, info):
    """The in-reach check of a sampled plan: every sample ``x`` (N, 4) in the workspace (:func:`reach_kernel`,
    finite), then every waypoint (a via point's corner is rounded, so the path may stay in reach while the point
    itself is not). Returns 0, or ``SAMPLE_OUT + 2 * where + why`` for the first sample out (with its time, point
    and moving segments in ``info``), :data:`SAMPLE_NOT_FINITE`, or ``WAYPOINT_OUTSIDE_*`` for the first waypoint
    out of reach (``info``'s ``w_a`` and point)."""
    n = int(plan[P_N])
    dt = plan[P_DT]
    a1, a2, d0 = plan[P_A1], plan[P_A2], plan[P_D0]
    d3_min, d3_max = plan[P_D3_MIN], plan[P_D3_MAX]
    for k in range(x.shape[0]):
        row = x[k]
        code = reach_kernel(row, a1, a2, d0, d3_min, d3_max)[0]
        finite = (math.isfinite(row[0]) and math.isfinite(row[1]) and math.isfinite(row[2])
                  and math.isfinite(row[3]))
        if code == IK_OK and finite:
            continue
        for i in range(info.shape[0]):
            info[i] = 0.0
        _limits_info(info, a1, a2, d3_min, d3_max)
        tk = k * dt
        info[I_SAMPLE] = k
        info[I_T_OUT] = tk
        info[I_DT] = dt
        _point_info(info, row[0], row[1], row[2], row[3], d0)
        if code == IK_OK:
            return SAMPLE_NOT_FINITE
        first, last = moving_segments(plan, tk)
        if first < 0:
            where = 5
            first = n - 2
            last = n - 2
        else:
            where = min(last - first, 4)
        info[I_S_A] = first
        info[I_S_A1] = first + 1
        info[I_S_B] = first + 1
        info[I_S_B1] = first + 2
        info[I_S_C] = first + 2
        info[I_S_C1] = first + 3
        info[I_S_D] = last
        info[I_S_D1] = last + 1
        return SAMPLE_OUT + 2 * where + (1 if code == IK_OUTSIDE_STROKE else 0)
    for i in range(n):
        w = plan_waypoint(n, i)
        code = reach_kernel(plan[w:w + 3], a1, a2, d0, d3_min, d3_max)[0]
        if code != IK_OK:
            for c in range(info.shape[0]):
                info[c] = 0.0
            _limits_info(info, a1, a2, d3_min, d3_max)
            info[I_W_A] = i
            _point_info(info, plan[w + V_X], plan[w + V_Y], plan[w + V_Z], 0.0, d0)
            return WAYPOINT_OUTSIDE_STROKE if code == IK_OUTSIDE_STROKE else WAYPOINT_OUTSIDE_ANNULUS
    return 0


#: the fields of :func:`plan_extremes`' ``out``: the largest linear speed ``|pdot|`` (m/s) and its sample, the
#: largest ``|pddot|`` (m/s^2) and its sample, the smallest manipulability ``w`` (m^2) and its sample
X_SPEED, X_SPEED_K, X_ACC, X_ACC_K, X_W, X_W_K = range(6)
EXTREMES = 6


@kernel
def plan_extremes(plan, x, xd, xdd, out):
    """The peaks of a sampled plan (rows ``x, xd, xdd`` (N, 4)) written into ``out`` (:data:`EXTREMES`,): the
    largest ``|pdot|`` and ``|pddot|`` and the smallest manipulability ``w = a1 a2 |sin theta2|`` (2.4) met,
    ``|sin theta2| = sqrt(1 - c2^2)`` with ``c2 = cos theta2`` of (1.9) at each sample (:func:`reach_kernel`), each
    with its first sample. Returns 0, or ``k + 1`` for the first sample ``k`` out of reach (no ``w`` there)."""
    a1, a2, d0 = plan[P_A1], plan[P_A2], plan[P_D0]
    d3_min, d3_max = plan[P_D3_MIN], plan[P_D3_MAX]
    best_v, best_a, best_w = -1.0, -1.0, math.inf
    kv, ka, kw = 0, 0, 0
    for k in range(x.shape[0]):
        v = math.sqrt(xd[k, 0] * xd[k, 0] + xd[k, 1] * xd[k, 1] + xd[k, 2] * xd[k, 2])
        if v > best_v:
            best_v, kv = v, k
        a = math.sqrt(xdd[k, 0] * xdd[k, 0] + xdd[k, 1] * xdd[k, 1] + xdd[k, 2] * xdd[k, 2])
        if a > best_a:
            best_a, ka = a, k
        code, c2 = reach_kernel(x[k], a1, a2, d0, d3_min, d3_max)
        if code != IK_OK:
            return k + 1
        c2 = min(max(c2, -1.0), 1.0)
        w = a1 * a2 * math.sqrt(1.0 - c2 * c2)
        if w < best_w:
            best_w, kw = w, k
    out[X_SPEED] = best_v
    out[X_SPEED_K] = kv
    out[X_ACC] = best_a
    out[X_ACC_K] = ka
    out[X_W] = best_w
    out[X_W_K] = kw
    return 0


@kernel
def _distance(x, k, px, py, pz):
    dx = x[k, 0] - px
    dy = x[k, 1] - py
    dz = x[k, 2] - pz
    return math.sqrt(dx * dx + dy * dy + dz * dz)


@kernel
def corner_distance(plan, x, i):
    """``(distance, time)``: the closest approach of the path to the via point ``i`` (m, s), the minimum of
    ``|p_e(t) - p_i|`` over the overlap of the two segments it joins, found on the samples ``x`` (N, 4) and
    refined between the neighbouring samples with :func:`plan_at` (four passes of 65 times, each narrowing the
    bracket 32-fold). Zero for a via point on a straight continuation (only the speed blends there)."""
    n = int(plan[P_N])
    dt = plan[P_DT]
    w = plan_waypoint(n, i)
    px, py, pz = plan[w + V_X], plan[w + V_Y], plan[w + V_Z]
    qb = plan_segment(n, i - 1)
    qa = plan_segment(n, i)
    straight = False
    if plan[qb + Q_KIND] == 0.0 and plan[qa + Q_KIND] == 0.0:
        ux, uy, uz = plan[qb + Q_TANGENT], plan[qb + Q_TANGENT + 1], plan[qb + Q_TANGENT + 2]
        vx, vy, vz = plan[qa + Q_TANGENT], plan[qa + Q_TANGENT + 1], plan[qa + Q_TANGENT + 2]
        cx, cy, cz = uy * vz - uz * vy, uz * vx - ux * vz, ux * vy - uy * vx
        straight = math.sqrt(cx * cx + cy * cy + cz * cz) < 1e-12 and ux * vx + uy * vy + uz * vz > 0
    a = plan[qa + Q_K0] * dt
    b = plan[qb + Q_K1] * dt
    k0 = int(math.floor(a / dt + 0.5))
    k1 = int(math.floor(b / dt + 0.5))
    k = k0
    fun = _distance(x, k0, px, py, pz)
    for kk in range(k0 + 1, k1 + 1):
        d = _distance(x, kk, px, py, pz)
        if d < fun:
            fun, k = d, kk
    tk = k * dt
    lo, hi = max(a, tk - dt), min(b, tk + dt)
    arg = tk
    xs = np.empty(4)
    xds = np.empty(4)
    xdds = np.empty(4)
    for _ in range(4):
        step = (hi - lo) / 64
        best, sbest = math.inf, lo
        for c in range(65):
            s = hi if c == 64 else c * step + lo
            plan_at(plan, s, xs, xds, xdds)
            dx, dy, dz = xs[0] - px, xs[1] - py, xs[2] - pz
            d = math.sqrt(dx * dx + dy * dy + dz * dz)
            if d < best:
                best, sbest = d, s
        if best < fun:
            fun, arg = best, sbest
        lo, hi = max(lo, sbest - step), min(hi, sbest + step)
    if straight:
        fun = 0.0
    return fun, arg
