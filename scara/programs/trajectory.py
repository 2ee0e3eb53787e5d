"""The page program of chapter 3's waypoint editor: one move of its controls re-planned, checked, sampled,
summarised and thinned for drawing, in one compiled kernel (:func:`editor_program`).

The move applies the controls to the panel's plan: the picked waypoint takes the position ``(x, y, z)`` and
becomes a via point with the anticipation, or a stop point; the picked segment takes the duration. The plan is
then planned by the planner's own kernels (:mod:`scara.trajectory._plan`: :func:`build_plan`, :func:`sample_plan`,
:func:`plan_reach`, :func:`plan_extremes`, :func:`corner_distance`), exactly as
:func:`~scara.trajectory.plan_path` plans it, and every check it fails is a refusal code (the planner's codes).

``data`` (:func:`editor_data`): the number of points of the top view's path and of each time profile, then the
plan's spec (:mod:`scara.programs.path`). ``inputs``: the controls :data:`EDITOR_INPUTS`, in order (a dropdown as
the index of its choice). ``out``: :func:`editor_outputs` (its fields depend on the number of waypoints and of
points drawn): first the numbers of a refusal's message (:data:`scara.trajectory._plan.INFO`), then the summary,
the edited point, and for the figures the corner distances, the segments' bands, the arm at ``t = 0``, the
stop and via points (NaN where a point is of the other kind) and the thinned series (:func:`thin_indices`).
"""
from __future__ import annotations

import math

import numpy as np

from .._compile import ArrayLayout, kernel
from ..kinematics import planar_position, planar_trig, reach_kernel
from ..kinematics import IK_OUTSIDE_STROKE
from ..trajectory._plan import (EXTREMES, I_SAMPLE, INFO, INFO_SIZE, P_N, P_A1, P_A2, P_D0, P_D3_MAX, P_D3_MIN, P_DT, P_K, P_K_END,
                                P_Q0, PLAN_HEAD, PLAN_SEGMENT, PLAN_WAYPOINT, Q_K0, Q_K1, S_CHECK, S_N, V_NA, V_X,
                                V_Y, W_ANT, W_X, W_Y, W_Z, G_DURATION, X_ACC, X_SPEED, X_W, X_W_K, _limits_info,
                                _point_info, build_plan, corner_distance, rint, plan_extremes, plan_reach, plan_segment,
                                plan_waypoint, sample_plan, spec_segment, spec_size, spec_waypoint)

__all__ = ["editor_program", "editor_data", "editor_outputs", "thin_indices", "EDITOR_INPUTS",
           "SUMMARY_OUTSIDE_ANNULUS", "SUMMARY_OUTSIDE_STROKE"]

#: the controls the program reads, in the order of ``inputs``
EDITOR_INPUTS = ("point", "via", "x", "anticipation", "y", "segment", "z", "duration")
IN_POINT, IN_VIA, IN_X, IN_ANTICIPATION, IN_Y, IN_SEGMENT, IN_Z, IN_DURATION = range(8)

#: ``data``: the points drawn per curve (top view, each profile), then the spec
D_TOP, D_PROFILE, D_SPEC = 0, 1, 2

#: the summary's sample out of reach (a plan that is not checked, ``check=False``): no manipulability there
SUMMARY_OUTSIDE_ANNULUS = 58
SUMMARY_OUTSIDE_STROKE = 59

#: the outputs every plan has, after the refusal's numbers: when the motion ends (s), the peak speed (cm/s) and
#: acceleration (cm/s^2), the smallest manipulability (m^2) and when (s), 1 when it is below 0.01 m^2, the
#: waypoint edited and its x, y
_FIXED = (("motion_end", 1), ("peak_speed_cm", 1), ("peak_acc_cm", 1), ("w_min", 1), ("w_min_time", 1),
          ("near_singular", 1), ("edit_point", 1), ("edit_x", 1), ("edit_y", 1))
(E_MOTION_END, E_PEAK_SPEED, E_PEAK_ACC, E_W_MIN, E_W_MIN_TIME, E_NEAR_SINGULAR, E_EDIT_POINT, E_EDIT_X,
 E_EDIT_Y) = range(INFO_SIZE, INFO_SIZE + len(_FIXED))
E_FIXED_END = INFO_SIZE + len(_FIXED)
#: manipulability (m^2) below which the summary notes a nearly singular configuration
NEAR_SINGULAR = 0.01
#: the profiles' series after their times: position, velocity, acceleration of x, y, z, then phi (deg)
PROFILE_SERIES = ("prof_x", "prof_y", "prof_z", "prof_vx", "prof_vy", "prof_vz", "prof_ax", "prof_ay", "prof_az",
                  "prof_phi")


def editor_outputs(n: int, top_points: int, profile_points: int) -> ArrayLayout:
    """The output fields of :func:`editor_program` for a plan of ``n`` waypoints drawn with ``top_points`` and
    ``profile_points`` per curve (each curve also keeps every segment's start and end: ``2 (n - 1)`` more)."""
    m = n - 1
    inner = range(1, n - 1)
    fields = [(name, 1) for name in INFO.names] + list(_FIXED)
    fields += [(f"corner_{i}", 1) for i in inner]
    for g in range((m + 1) // 2):
        fields += [(f"band_{g}_x0", 1), (f"band_{g}_x1", 1)]
    for i in inner:
        fields += [(f"overlap_{i}_x0", 1), (f"overlap_{i}_x1", 1), (f"overlap_{i}_on", 1)]
    fields += [("arm_x", 3), ("arm_y", 3), ("stop_x", n), ("stop_y", n), ("via_x", n), ("via_y", n),
               ("path_x", top_points + 2 * m), ("path_y", top_points + 2 * m), ("prof_t", profile_points + 2 * m)]
    fields += [(name, profile_points + 2 * m) for name in PROFILE_SERIES]
    fields += [("spec_out", spec_size(n))]  # the edited spec, which the panel carries to its next move
    return ArrayLayout(*fields)


@kernel
def editor_offsets(n, tp, pp):
    """The offsets of the variable fields of :func:`editor_outputs` (``tp``, ``pp``: the lengths of the top view's
    and of the profiles' series): corners, bands, overlaps, arm, stop, via, path, profiles, and the end."""
    m = n - 1
    o_corner = E_FIXED_END
    o_band = o_corner + (n - 2)
    o_overlap = o_band + 2 * ((m + 1) // 2)
    o_arm = o_overlap + 3 * (n - 2)
    o_stop = o_arm + 6
    o_via = o_stop + 2 * n
    o_path = o_via + 2 * n
    o_prof = o_path + 2 * tp
    o_end = o_prof + 11 * pp
    return o_corner, o_band, o_overlap, o_arm, o_stop, o_via, o_path, o_prof, o_end


def editor_data(spec, top_points: int, profile_points: int) -> np.ndarray:
    """The program's ``data``: the points drawn per curve, then the plan's ``spec`` (:mod:`scara.programs.path`)."""
    return np.r_[float(top_points), float(profile_points), np.asarray(spec, dtype=float)]


@kernel
def thin_indices(plan, points, idx):
    """The samples drawn of a plan of ``N`` samples: ``points`` evenly spaced (``round(linspace(0, N - 1,
    points))``) and every segment's first and end sample, sorted, each once, written into ``idx`` (``points + 2
    (n - 1)``,) and padded with the last sample (which a curve then repeats). Returns the number of distinct
    samples."""
    n = int(plan[P_N])
    m = n - 1
    last = plan[P_K]
    marks = np.empty(2 * m)
    for j in range(m):
        q = plan_segment(n, j)
        marks[2 * j] = plan[q + Q_K0]
        marks[2 * j + 1] = plan[q + Q_K1]
    for a in range(1, 2 * m):  # insertion sort: a few marks, nearly in order
        v = marks[a]
        b = a - 1
        while b >= 0 and marks[b] > v:
            marks[b + 1] = marks[b]
            b -= 1
        marks[b + 1] = v
    step = last / (points - 1) if points > 1 else 0.0
    count = 0
    ib = 0
    im = 0
    prev = -1.0
    while ib < points or im < 2 * m:
        if ib < points:
            vb = last if ib == points - 1 else rint(ib * step + 0.0)
        else:
            vb = math.inf
        vm = marks[im] if im < 2 * m else math.inf
        if vb <= vm:
            v = vb
            ib += 1
        else:
            v = vm
            im += 1
        if v != prev:
            idx[count] = v
            count += 1
            prev = v
    for c in range(count, idx.shape[0]):
        idx[c] = last
    return count



@kernel
def editor_program(inputs, data, out):
    """One move of the waypoint editor (see the module's docstring): the picked waypoint and segment edited,
    the plan planned, checked and sampled at ``dt`` by the planner's kernels, its summary (when the motion ends,
    the peak speed and acceleration, the smallest manipulability, the closest approach to each via point), and
    its figures' series (the arm at ``t = 0``, the stop and via points, the path seen from above and the time
    profiles thinned by :func:`thin_indices`, the segments' bands). Returns 0, or the planner's code of what it
    refuses (the numbers of its message in ``out``'s first fields)."""
    tp_points = int(data[D_TOP])
    pp_points = int(data[D_PROFILE])
    base = data[D_SPEC:]
    n = int(base[S_N])
    m = n - 1
    spec = np.empty(base.shape[0])
    for c in range(base.shape[0]):
        spec[c] = base[c]
    i = int(inputs[IN_POINT])
    w = spec_waypoint(n, i)
    spec[w + W_X] = inputs[IN_X]
    spec[w + W_Y] = inputs[IN_Y]
    spec[w + W_Z] = inputs[IN_Z]
    spec[w + W_ANT] = inputs[IN_ANTICIPATION] if inputs[IN_VIA] != 0 else 0.0
    spec[spec_segment(n, int(inputs[IN_SEGMENT])) + G_DURATION] = inputs[IN_DURATION]
    out[E_EDIT_POINT] = i
    out[E_EDIT_X] = inputs[IN_X]
    out[E_EDIT_Y] = inputs[IN_Y]
    info = out[0:INFO_SIZE]
    plan = np.empty(PLAN_HEAD + PLAN_WAYPOINT * n + PLAN_SEGMENT * m)
    code = build_plan(spec, plan, info)
    if code != 0:
        return code
    N = int(plan[P_K]) + 1
    dt = plan[P_DT]
    t = np.empty(N)
    x = np.empty((N, 4))
    xd = np.empty((N, 4))
    xdd = np.empty((N, 4))
    sample_plan(plan, t, x, xd, xdd)
    if spec[S_CHECK] != 0:
        code = plan_reach(plan, x, info)
        if code != 0:
            return code
    # the summary
    ext = np.empty(EXTREMES)
    k = plan_extremes(plan, x, xd, xdd, ext)
    if k != 0:
        row = x[k - 1]
        for c in range(INFO_SIZE):
            info[c] = 0.0
        _limits_info(info, plan[P_A1], plan[P_A2], plan[P_D3_MIN], plan[P_D3_MAX])
        info[I_SAMPLE] = k - 1
        _point_info(info, row[0], row[1], row[2], row[3], plan[P_D0])
        why = reach_kernel(row, plan[P_A1], plan[P_A2], plan[P_D0], plan[P_D3_MIN], plan[P_D3_MAX])[0]
        return SUMMARY_OUTSIDE_STROKE if why == IK_OUTSIDE_STROKE else SUMMARY_OUTSIDE_ANNULUS
    out[E_MOTION_END] = plan[P_K_END] * dt
    out[E_PEAK_SPEED] = 100 * ext[X_SPEED]
    out[E_PEAK_ACC] = 100 * ext[X_ACC]
    out[E_W_MIN] = ext[X_W]
    out[E_W_MIN_TIME] = t[int(ext[X_W_K])]
    out[E_NEAR_SINGULAR] = 1.0 if ext[X_W] < NEAR_SINGULAR else 0.0
    tp = tp_points + 2 * m
    pp = pp_points + 2 * m
    o_corner, o_band, o_overlap, o_arm, o_stop, o_via, o_path, o_prof, o_end = editor_offsets(n, tp, pp)
    # the closest approach to each via point (mm; 0 at a stop point, which the path passes through)
    for v in range(1, n - 1):
        d = 0.0
        if plan[plan_waypoint(n, v) + V_NA] > 0:
            d = 1000 * corner_distance(plan, x, v)[0]
        out[o_corner + v - 1] = d
    # the segments' bands: every other segment, and the overlap at each via point
    for g in range((m + 1) // 2):
        q = plan_segment(n, 2 * g)
        out[o_band + 2 * g] = max(plan[q + Q_K0] * dt, 0.0)
        out[o_band + 2 * g + 1] = min(plan[q + Q_K1] * dt, t[N - 1])
    for v in range(1, n - 1):
        a = max(plan[plan_segment(n, v) + Q_K0] * dt, 0.0)
        b = min(plan[plan_segment(n, v - 1) + Q_K1] * dt, t[N - 1])
        o = o_overlap + 3 * (v - 1)
        out[o] = a
        out[o + 1] = b
        out[o + 2] = 1.0 if plan[plan_waypoint(n, v) + V_NA] > 0 and b > a else 0.0
    # the arm at t = 0, from above: the base axis, the elbow, the wrist (1.5)
    sc = planar_trig(plan[P_Q0], plan[P_Q0 + 1])
    a1 = plan[P_A1]
    out[o_arm] = 0.0
    out[o_arm + 1] = a1 * sc[1]
    out[o_arm + 3] = 0.0
    out[o_arm + 4] = -a1 * sc[0]
    out[o_arm + 2], out[o_arm + 5] = planar_position(sc, a1, plan[P_A2])
    # the stop and via points
    for v in range(n):
        pw = plan_waypoint(n, v)
        via = plan[pw + V_NA] > 0
        out[o_stop + v] = math.nan if via else plan[pw + V_X]
        out[o_stop + n + v] = math.nan if via else plan[pw + V_Y]
        out[o_via + v] = plan[pw + V_X] if via else math.nan
        out[o_via + n + v] = plan[pw + V_Y] if via else math.nan
    # the path seen from above and the time profiles, thinned
    idx = np.empty(max(tp, pp))
    thin_indices(plan, tp_points, idx[0:tp])
    for c in range(tp):
        kk = int(idx[c])
        out[o_path + c] = x[kk, 0]
        out[o_path + tp + c] = x[kk, 1]
    thin_indices(plan, pp_points, idx[0:pp])
    for c in range(pp):
        kk = int(idx[c])
        out[o_prof + c] = t[kk]
        for comp in range(3):
            out[o_prof + (1 + comp) * pp + c] = x[kk, comp]
            out[o_prof + (4 + comp) * pp + c] = xd[kk, comp]
            out[o_prof + (7 + comp) * pp + c] = xdd[kk, comp]
        out[o_prof + 10 * pp + c] = math.degrees(x[kk, 3])
    # the edited spec: the plan the next move starts from (the panel's carry)
    for c in range(spec.shape[0]):
        out[o_end + c] = spec[c]
    return 0
