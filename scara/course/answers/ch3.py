"""The computations answering chapter 3's exercises (see :mod:`scara.course.answers`)."""
import math
from functools import lru_cache

import numpy as np

from scara import ScaraParams, Trapezoidal, UnreachableError, Waypoint, plan_path, reference_plan, reference_trajectory
from scara.course.answers import solves
from scara.errors import ScaraError
from scara.trajectory import (REFERENCE_DURATIONS, REFERENCE_POINTS, joint_counterpart, passage_times,
                              path_deviation)

DT = 1e-3


@lru_cache(maxsize=1)
def _reference():
    """The reference trajectory of the chapter (planned once per process)."""
    return reference_trajectory()


def _whole_samples(value: float, what: str) -> None:
    if abs(value / DT - round(value / DT)) > 1e-9:
        raise ScaraError(f"{what} = {value} s is not a whole number of 1 ms samples")


def _p4_variant(anticipation: float):
    plan = reference_plan()
    plan["waypoints"][4] = plan["waypoints"][4].replace(anticipation=anticipation)
    return plan_path(**plan)


@solves("ex-traj-corner")
def right_angle_corner(L: float, tf: float, dt: float) -> dict:
    """Two segments of ``L`` at a right angle, each in ``tf`` (blends tf/3), anticipation ``dt`` at the corner:
    the corner distance of the plan, and the closed form a dt^2 / (4 sqrt 2)."""
    _whole_samples(tf, "the duration")
    _whole_samples(dt, "the anticipation")
    if not 0 < dt <= tf / 3 + 1e-12:
        raise ScaraError(f"exercise ex-traj-corner: the anticipation {dt} s must be positive and no longer than "
                         f"the blends t_f/3 = {tf / 3:.4f} s")
    x0, y0, z0 = 0.3, 0.2, 0.5
    wps = [Waypoint([x0, y0, z0]), Waypoint([x0 + L, y0, z0], anticipation=dt), Waypoint([x0 + L, y0 + L, z0])]
    square = plan_path(wps, durations=[tf, tf])
    d, t_pass = square.corner_distances()["p1"]
    a = 4.5 * L / tf**2
    return {"a": a, "d_mm": 1000 * d, "pred_mm": 1000 * a * dt**2 / (4 * math.sqrt(2)),
            "t_into": t_pass - float(square.segment_start[1])}


@solves("ex-traj-fast")
def fastest_segment(v: float, acc: float) -> dict:
    """The fastest trapezoid over p6 -> p7 under a speed limit ``v`` and an acceleration limit ``acc``, its
    duration rounded up to whole milliseconds."""
    if v <= 0 or acc <= 0:
        raise ScaraError("exercise ex-traj-fast: the limits must be positive")
    L = float(np.linalg.norm(REFERENCE_POINTS[7] - REFERENCE_POINTS[6]))
    law = Trapezoidal.minimum_time(L, speed=v, acceleration=acc, dt=DT)
    cruises = L >= v**2 / acc
    exact = L / v + v / acc if cruises else 2 * math.sqrt(L / acc)
    return {"T": float(law.duration), "T_exact": exact, "L": L, "v2_over_a": v**2 / acc,
            "cruises": float(cruises), "ratio": REFERENCE_DURATIONS[6] / float(law.duration)}


@solves("ex-traj-half-circle")
def faster_half_circle(T_arc: float) -> dict:
    """The half circle p10 -> p11 in ``T_arc`` instead of 9.6 s: growth of its accelerations, its peak
    centripetal acceleration, and the rest at p11 within the same 70 s."""
    _whole_samples(T_arc, "the duration")
    ref = _reference()
    T_ref = float(ref.durations[10])
    if not 0 < T_arc < T_ref:
        raise ScaraError(f"exercise ex-traj-half-circle: the half circle must be shortened (0 < T < {T_ref} s)")
    durations = list(REFERENCE_DURATIONS)
    durations[10] = T_arc
    quick = ref.replan(durations=durations)
    rho = float(ref.segments[10].radius)
    slow_law, quick_law = ref.laws[10], quick.laws[10]
    cent_slow = slow_law.cruise_speed**2 / rho
    cent_quick = quick_law.cruise_speed**2 / rho
    return {"growth": quick_law.acceleration / slow_law.acceleration, "cent_growth": cent_quick / cent_slow,
            "cent_slow": cent_slow, "cent_quick": cent_quick, "tan_slow": slow_law.acceleration,
            "tan_quick": quick_law.acceleration, "quick_rest": float(quick.rest), "ref_rest": float(ref.rest),
            "quick_total": float(quick.t[-1])}


@solves("ex-traj-turn")
def turning_gripper(turn: float) -> dict:
    """The reference with p1 given the orientation phi_0 + ``turn`` (degrees): the peak angular speed, and how
    much the positions move (nothing)."""
    ref = _reference()
    plan = reference_plan()
    phi0 = float(ref.x[0, 3])
    plan["waypoints"][1] = plan["waypoints"][1].replace(phi=phi0 + math.radians(turn))
    turning = plan_path(**plan)
    phidot = float(np.abs(turning.xd[:, 3]).max())
    return {"phidot_max": phidot, "phidot_max_deg": math.degrees(phidot), "tf": float(ref.durations[0]),
            "position_change": float(np.abs(turning.x[:, :3] - ref.x[:, :3]).max()),
            "phi_end_deg": math.degrees(float(turning.x[-1, 3]) - phi0)}


@solves("ex-traj-reach")
def out_of_reach(x7: float, y7: float, z7: float) -> dict:
    """The reference with p7 moved to (x7, y7, z7) out of reach: the planner's refusal, the point's distance
    from the joint-1 axis and the first sample of the path outside the workspace."""
    p = ScaraParams()
    r7 = math.hypot(x7, y7)
    plan = reference_plan()
    plan["waypoints"][7] = plan["waypoints"][7].replace(position=(x7, y7, z7))
    try:
        plan_path(**plan)
    except UnreachableError as exc:
        message = str(exc)
    else:
        raise ScaraError(f"exercise ex-traj-reach: p7 = ({x7}, {y7}, {z7}) is reachable, the planner accepts it")
    raw = plan_path(**plan, check=False)
    r = np.hypot(raw.x[:, 0], raw.x[:, 1])
    d3 = p.d0 - raw.x[:, 2]
    out = (r > p.a1 + p.a2) | (r < abs(p.a1 - p.a2)) | (d3 < p.d3_min) | (d3 > p.d3_max)
    k = int(np.argmax(out))
    if not out[k] or raw.segments_at(raw.t[k]) != [6]:
        raise ScaraError(f"exercise ex-traj-reach: the path does not leave the workspace on p6 -> p7 ({message})")
    return {"r7": r7, "t_out": float(raw.t[k]), "k_out": k, "r_out": float(r[k]),
            "x_out": float(raw.x[k, 0]), "y_out": float(raw.x[k, 1]), "z_out": float(raw.x[k, 2]),
            "phi_out": float(raw.x[k, 3]), "early": float(raw.segment_end[6] - raw.t[k])}


@solves("ex-traj-stop")
def stop_at_p4() -> dict:
    """The reference with p4 a stop point: end of the motion, remaining corner distances, smallest
    manipulability, against the reference."""
    ref = _reference()
    stop = _p4_variant(0.0)
    corners = stop.corner_distances()
    return {"end_stop": float(stop.motion_end), "end_ref": float(ref.motion_end),
            "p3_mm": 1000 * corners["p3"][0], "p8_mm": 1000 * corners["p8"][0],
            "w_stop": float(stop.manipulability().min()), "w_ref": float(ref.manipulability().min())}


@solves("ex-traj-half-anticipation")
def shorter_anticipation(antic: float) -> dict:
    """The reference with an anticipation ``antic`` at p4 (within the 2 s blends): how far the arm misses p4,
    and when the motion ends."""
    _whole_samples(antic, "the anticipation")
    ref = _reference()
    blend = min(ref.blends[3], ref.blends[4])
    if not 0 < antic <= blend + 1e-12:
        raise ScaraError(f"exercise ex-traj-half-anticipation: the anticipation {antic} s must be positive and "
                         f"within the blends ({blend} s)")
    variant = _p4_variant(antic)
    d_ref = ref.corner_distances()["p4"][0]
    return {"d_mm": 1000 * variant.corner_distances()["p4"][0], "end": float(variant.motion_end),
            "d_ref_mm": 1000 * d_ref, "antic_ref": float(ref.anticipations[4]),
            "end_ref": float(ref.motion_end), "later": float(variant.motion_end - ref.motion_end)}


@solves("ex-traj-rest-to-rest")
def rest_to_rest() -> dict:
    """Peaks of theta2's speed on the rest-to-rest segment p6 -> p7 of the joint-space trajectories through the
    reference's knots, cubic and quintic (degrees)."""
    ref = _reference()
    cub, qui = joint_counterpart(ref, "cubic"), joint_counterpart(ref, "quintic")
    if not (6 in cub.stops and 7 in cub.stops):
        raise ScaraError("exercise ex-traj-rest-to-rest: p6 -> p7 is not from rest to rest")
    j = cub.segment_labels.index("p6->p7")
    T = float(cub.durations[j])
    dth2 = float(cub.points[7, 1] - cub.points[6, 1])
    tp = passage_times(ref)
    w = (cub.t >= tp[6]) & (cub.t <= tp[7])
    return {"T": T, "dth2": math.degrees(dth2),
            "cubic_peak": math.degrees(float(np.abs(cub.qd[w, 1]).max())),
            "quintic_peak": math.degrees(float(np.abs(qui.qd[w, 1]).max())),
            "acc_cubic": math.degrees(float(np.abs(cub.qdd[w, 1]).max())),
            "acc_quintic": math.degrees(10 / math.sqrt(3) * abs(dth2) / T**2)}


_DEVIATIONS: dict = {}
MAX_EXTRA = 15   # the slider of fig-ch3-joint-space goes up to 15 extra knots per segment


def _deviation(n: int) -> float:
    """Largest distance (m) of the gripper from the reference path with ``n`` extra cubic knots per segment."""
    if n not in _DEVIATIONS:
        ref = _reference()
        _DEVIATIONS[n] = float(path_deviation(joint_counterpart(ref, "cubic", extra=n), ref).max())
    return _DEVIATIONS[n]


@solves("ex-traj-knots")
def knots_for_tolerance(tol_mm: float) -> dict:
    """The smallest number of extra knots per segment (cubics) that keeps the gripper within ``tol_mm`` of the
    reference path."""
    if not _deviation(MAX_EXTRA) * 1000 < tol_mm < _deviation(0) * 1000:
        raise ScaraError(f"exercise ex-traj-knots: the tolerance {tol_mm} mm is not between the slider's ends")
    n = next(n for n in range(MAX_EXTRA + 1) if _deviation(n) * 1000 <= tol_mm)
    return {"n": n, "dev_mm": 1000 * _deviation(n), "knots": 12 + 11 * n, "prev_mm": 1000 * _deviation(n - 1)}
