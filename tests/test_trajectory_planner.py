"""Tests of scara.trajectory.planner (chapter 3, section The reference path).

Each property is checked by a method independent of the planner's own code: closed-form geometry of the
blends, the trapezoidal/Euler rules with their error bounds, the circle's equation, the planar two-link formula
for the manipulability, and hypothesis-generated paths; every bad input is refused with a message naming it."""
from __future__ import annotations

import json
import math
import os
import subprocess
import sys

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from scara import (
    Line, ScaraError, ScaraParams, ShapeError, Trapezoidal, UnreachableError, Waypoint, is_reachable, plan_path,
    pose, reference_plan, trapezoidal,
)
from scara.trajectory import REFERENCE_DURATIONS

from _trajectory_shared import CENTRE, DT, SCENARIO_POINTS, SCENARIO_VIA


def switching_times(traj):
    """Every instant where some segment's acceleration jumps (start, end of each blend)."""
    out = []
    for j, law in enumerate(traj.laws):
        t0 = traj.segment_start[j]
        out += [t0, t0 + law.blend, t0 + law.duration - law.blend, t0 + law.duration]
    return np.unique(out)


def smooth_intervals(traj):
    """Mask over the intervals [t_k, t_k+1): True when no switching instant lies strictly inside."""
    k = np.arange(traj.t.size - 1)
    bad = np.zeros(k.size, dtype=bool)
    for ts in switching_times(traj):
        kk = int(math.floor(ts / traj.dt + 1e-9))
        if abs(ts / traj.dt - round(ts / traj.dt)) > 1e-9 and 0 <= kk < k.size:
            bad[kk] = True
    return ~bad


def jerk_bound(traj):
    """An upper bound of |x'''| over the whole trajectory: zero on lines between switches; on an arc of radius
    rho, d/dt (t sddot + k sdot^2) = 3 k sdot sddot + k' sdot^3 with |k| = 1/rho and |k'| = 1/rho^2."""
    J = 0.0
    for seg, law in zip(traj.segments, traj.laws):
        if seg.kind == "arc":
            v, a, r = law.cruise_speed, law.acceleration, seg.radius
            J += 3 * v * a / r + v ** 3 / r ** 2
    return J


# --------------------------------------------------------------------------------------------------
# stop points and via points
# --------------------------------------------------------------------------------------------------
def test_arm_is_exactly_at_each_stop_point_and_at_rest(ref):
    stops = [i for i in range(12) if not ref.via[i]]
    assert stops == [0, 1, 2, 6, 7, 9, 10, 11]
    for i in stops:
        t_arrive = 0.0 if i == 0 else ref.segment_end[i - 1]
        k = round(t_arrive / DT)
        assert ref.t[k] == pytest.approx(t_arrive, abs=1e-12)
        np.testing.assert_allclose(ref.x[k, :3], SCENARIO_POINTS[i], atol=1e-9, rtol=0)
        np.testing.assert_allclose(ref.xd[k], 0.0, atol=1e-12)


def blend_corner_distance(p_prev, p_via, p_next, T1, T2, dT):
    """Closest approach of the two superposed blends to a via point, in closed form.

    During the overlap (tau in [0, dT], dT <= both blends) the incoming segment still has to cover
    a1 (dT - tau)^2 / 2 and the outgoing one has covered a2 tau^2 / 2, so p - p_via = -u1 A (dT-tau)^2 + u2 B tau^2
    with A = a1/2, B = a2/2. |.|^2 is a quartic in tau; its minimum is at a root of the derivative (a cubic)
    or at an end of the interval. Trapezoid with blend T/3: v = 1.5 L/T, a = 4.5 L/T^2.
    """
    d1, d2 = p_via - p_prev, p_next - p_via
    L1, L2 = np.linalg.norm(d1), np.linalg.norm(d2)
    u1, u2 = d1 / L1, d2 / L2
    A, B = 4.5 * L1 / T1 ** 2 / 2, 4.5 * L2 / T2 ** 2 / 2
    c = float(u1 @ u2)
    tau = np.polynomial.Polynomial([0, 1])
    f = A * A * (dT - tau) ** 4 + B * B * tau ** 4 - 2 * A * B * c * (dT - tau) ** 2 * tau ** 2
    cand = [0.0, dT] + [r.real for r in f.deriv().roots() if abs(r.imag) < 1e-12 and 0 <= r.real <= dT]
    return min(math.sqrt(max(f(x), 0.0)) for x in cand)


@pytest.mark.parametrize("i", [3, 4, 8])
def test_corner_distance_matches_the_blend_geometry(ref, i):
    T1, T2, dT = REFERENCE_DURATIONS[i - 1], REFERENCE_DURATIONS[i], SCENARIO_VIA[i]
    assert dT <= min(T1, T2) / 3  # the closed form assumes the overlap lies inside both blends
    expected = blend_corner_distance(SCENARIO_POINTS[i - 1], SCENARIO_POINTS[i], SCENARIO_POINTS[i + 1], T1, T2, dT)
    got, when = ref.corner_distances()[f"p{i}"]
    assert got == pytest.approx(expected, abs=1e-9)
    assert got > 1e-3  # passed near, never exactly
    assert ref.segment_start[i] <= when <= ref.segment_end[i - 1]
    # the samples never come closer than the continuous minimum, and the nearest sample is within v dt / 2
    d = np.linalg.norm(ref.x[:, :3] - SCENARIO_POINTS[i], axis=1)
    assert d.min() >= expected - 1e-12
    assert d.min() <= expected + ref.speed().max() * DT / 2


def test_via_points_never_stop_the_arm(ref):
    sp_ = ref.speed()
    for i in (3, 4, 5, 8):
        win = (ref.t >= ref.segment_start[i] - 0.5) & (ref.t <= ref.segment_end[i - 1] + 0.5)
        assert sp_[win].min() > 1e-3


def test_collinear_via_point_only_blends_the_speed(ref):
    # p5 lies on the line p4-p6: during its overlap the arm stays on that line
    a, b = SCENARIO_POINTS[4], SCENARIO_POINTS[6]
    u = (b - a) / np.linalg.norm(b - a)
    win = (ref.t >= ref.segment_start[5]) & (ref.t <= ref.segment_end[4])
    rel = ref.x[win, :3] - a
    np.testing.assert_allclose(np.cross(rel, u), 0.0, atol=1e-15)
    assert ref.corner_distances()["p5"][0] == 0.0


# --------------------------------------------------------------------------------------------------
# continuity and derivatives
# --------------------------------------------------------------------------------------------------
def test_velocity_is_continuous(ref):
    jump = np.abs(np.diff(ref.xd, axis=0))
    bound = np.abs(ref.xdd).max(axis=0) * DT
    # sup |xdd| over an interval may exceed the samples' max only through the arc's smooth variation (jerk)
    slack = jerk_bound(ref) * DT ** 2 + 1e-16
    assert np.all(jump <= bound + slack)


def test_xd_and_xdd_agree_with_finite_differences(ref):
    h, J = DT, jerk_bound(ref)
    smooth = smooth_intervals(ref)
    amax = np.abs(ref.xdd).max()
    # x' = xd: the trapezoidal rule is exact for quadratics; error <= h^3 J / 12 on a smooth interval and
    # <= h^2 |jump of xdd| / 8 <= h^2 amax / 4 across one jump of the acceleration
    e1 = np.abs(np.diff(ref.x, axis=0) - (ref.xd[1:] + ref.xd[:-1]) * h / 2)
    roundoff = 4e-16
    assert e1[smooth].max() <= h ** 3 * J / 12 + roundoff
    assert e1.max() <= h ** 2 * amax / 4 + roundoff
    # xd' = xdd: a forward-Euler step from the right-continuous acceleration; error <= h^2 J / 2 on a smooth
    # interval, <= h |jump| <= 2 h amax across a jump
    e2 = np.abs(np.diff(ref.xd, axis=0) - ref.xdd[:-1] * h)
    assert e2[smooth].max() <= h ** 2 * J / 2 + 1e-17
    assert e2.max() <= 2 * h * amax
    # and the plain central difference agrees away from the jumps to O(h^2 J)
    cd = (ref.x[2:] - ref.x[:-2]) / (2 * h)
    both = smooth[1:] & smooth[:-1]  # centred on sample k = 1 .. N-2: neither neighbour interval has a jump
    on_sample = np.round(switching_times(ref) / h).astype(int)  # ... and no jump at t_k itself
    both[np.clip(on_sample - 1, 0, both.size - 1)] = False
    assert np.abs(cd - ref.xd[1:-1])[both].max() <= h ** 2 * J / 6 + 1e-12


def test_evaluate_matches_the_samples_and_accepts_any_order(ref):
    k = np.array([70000, 0, 19467, 22500, 61200, 12345])
    x, xd, xdd = ref.evaluate(ref.t[k])
    np.testing.assert_array_equal(x, ref.x[k])
    np.testing.assert_array_equal(xd, ref.xd[k])
    np.testing.assert_array_equal(xdd, ref.xdd[k])
    x2, _, _ = ref.evaluate([-1.0, 100.0])
    np.testing.assert_allclose(x2[:, :3], SCENARIO_POINTS[[0, 11]], atol=1e-12)


# --------------------------------------------------------------------------------------------------
# the half circle
# --------------------------------------------------------------------------------------------------
def test_arc_samples_lie_on_the_circle_and_pass_the_scenario_point(ref):
    win = (ref.t >= ref.segment_start[10]) & (ref.t <= ref.segment_end[10])
    rel = ref.x[win, :3] - CENTRE
    np.testing.assert_allclose(np.linalg.norm(rel, axis=1), 0.05, atol=1e-9, rtol=0)
    np.testing.assert_allclose(rel[:, 2], 0.0, atol=1e-12)  # in the horizontal plane z = 0.5
    assert rel[:, 1].min() >= -1e-12  # the half through y > 0.20
    # the symmetric timing law puts the scenario's middle point at mid-time, on a sample
    k = round((ref.segment_start[10] + ref.durations[10] / 2) / DT)
    np.testing.assert_allclose(ref.x[k, :3], [0.23, 0.25, 0.5], atol=1e-9, rtol=0)
    # velocity tangent to the circle, and the centripetal acceleration |v|^2 / rho towards the centre
    v, a = ref.xd[win, :3], ref.xdd[win, :3]
    np.testing.assert_allclose(np.einsum("ij,ij->i", v, rel), 0.0, atol=1e-15)
    radial = np.einsum("ij,ij->i", a, rel) / 0.05
    np.testing.assert_allclose(radial, -np.einsum("ij,ij->i", v, v) / 0.05, atol=1e-14)


# --------------------------------------------------------------------------------------------------
# the joint path and the manipulability met along it
# --------------------------------------------------------------------------------------------------
def test_joint_path_and_minimum_manipulability(ref):
    q = ref.joints()
    assert np.all(q[:, 1] <= 0)  # elbow theta2 < 0 all along
    np.testing.assert_allclose(pose(q), ref.x, atol=1e-12)
    # planar two-link arm: cos theta2 = (r^2 - a1^2 - a2^2) / (2 a1 a2), w = a1 a2 |sin theta2|
    p = ScaraParams()
    r2 = ref.x[:, 0] ** 2 + ref.x[:, 1] ** 2
    c2 = (r2 - p.a1 ** 2 - p.a2 ** 2) / (2 * p.a1 * p.a2)
    w = p.a1 * p.a2 * np.sqrt(1 - c2 ** 2)
    s = ref.summary()
    assert s["min_manipulability"] == pytest.approx(w.min(), abs=1e-12)
    assert s["min_manipulability_time"] == pytest.approx(ref.t[np.argmin(w)])
    assert is_reachable(ref.x).all()


# --------------------------------------------------------------------------------------------------
# validation: every bad input is refused with a message naming it
# --------------------------------------------------------------------------------------------------
PTS = [[0.3, 0.2, 0.5], [0.4, 0.2, 0.5], [0.4, 0.3, 0.5]]


def test_fewer_than_two_points():
    with pytest.raises(ScaraError, match="at least two waypoints"):
        plan_path([[0.3, 0.2, 0.5]], durations=[])


def test_repeated_point():
    with pytest.raises(ScaraError, match="repeated point: p1 = p0"):
        plan_path([PTS[0], PTS[0], PTS[1]], durations=[1.0, 1.0])
    with pytest.raises(ScaraError, match="repeated point"):
        Line(PTS[0], PTS[0])


def test_blend_longer_than_half_its_segment():
    with pytest.raises(ScaraError, match=r"segment p0->p1: blend = 0.6 s is longer than half the duration"):
        plan_path(PTS, durations=[1.0, 1.0], blends=[0.6, None])
    with pytest.raises(ScaraError, match="longer than half"):
        Trapezoidal(0.1, 1.0, 0.51)


def test_anticipation_must_be_shorter_than_both_segments():
    wps = [Waypoint(PTS[0]), Waypoint(PTS[1], anticipation=1.0), Waypoint(PTS[2])]
    with pytest.raises(ScaraError, match=r"anticipation at via point p1 = 1 s must be shorter than both"):
        plan_path(wps, durations=[3.0, 1.0])
    with pytest.raises(ScaraError, match="shorter than both"):
        plan_path(wps, durations=[1.0, 3.0])
    plan_path(wps, durations=[1.001, 1.001])  # just shorter: accepted
    with pytest.raises(ScaraError, match="first waypoint and cannot be a via point"):
        plan_path([Waypoint(PTS[0], anticipation=0.5), PTS[1]], durations=[1.0])


def test_unreachable_sample_names_time_point_and_segment():
    with pytest.raises(UnreachableError) as err:
        plan_path([[0.5, 0.2, 0.5], [0.9, 0.6, 0.5]], durations=[2.0])
    msg = str(err.value)
    # independent: the first time the line leaves the disk r <= a1 + a2 = 1 under the trapezoid
    a, b = np.array([0.5, 0.2]), np.array([0.9, 0.6])
    L = np.linalg.norm(b - a)
    u = (b - a) / L
    s_exit = -(a @ u) + math.sqrt((a @ u) ** 2 - (a @ a - 1.0))  # |a + s u| = 1
    tt = np.arange(2001) * DT
    s_t = trapezoidal(tt, L, 2.0)[0]
    k_first = int(np.argmax(s_t > s_exit + 1e-12))
    assert f"t = {tt[k_first]:.3f} s" in msg
    assert "segment p0->p1" in msg and "a1 + a2 = 1 m" in msg and "x = [" in msg
    with pytest.raises(UnreachableError, match="stroke"):
        plan_path([[0.5, 0.2, 0.5], [0.5, 0.2, 1.2]], durations=[2.0])


def test_other_invalid_inputs():
    with pytest.raises(ShapeError, match="one entry per segment"):
        plan_path(PTS, durations=[1.0])
    with pytest.raises(ScaraError, match="whole number of sampling periods"):
        plan_path(PTS, durations=[1.0005, 1.0])
    with pytest.raises(ScaraError, match="shorter than the motion"):
        plan_path(PTS, durations=[1.0, 1.0], total=1.5)
    with pytest.raises(ScaraError, match="segment indices"):
        plan_path(PTS, durations=[1.0, 1.0], arcs={5: [0.3, 0.3, 0.5]})
    with pytest.raises(ScaraError, match="anticipation"):
        Waypoint(PTS[0], anticipation=-1)
    with pytest.raises(ScaraError, match="unknown planning input"):
        plan_path(PTS, durations=[1.0, 1.0]).replan(speed=3)


def test_planned_orientation_follows_the_timing_law():
    wps = [Waypoint(PTS[0], phi=0.0), Waypoint(PTS[1], phi=0.5), Waypoint(PTS[2])]
    tr = plan_path(wps, durations=[2.0, 2.0])
    k1 = round(2.0 / DT)
    assert tr.x[k1, 3] == pytest.approx(0.5, abs=1e-12) and tr.x[-1, 3] == pytest.approx(0.5, abs=1e-12)
    # phi / 0.5 and s / L are the same normalised law
    s = trapezoidal(tr.t[:k1], 0.1, 2.0)[0]
    np.testing.assert_allclose(tr.x[:k1, 3] / 0.5, s / 0.1, atol=1e-12)


# --------------------------------------------------------------------------------------------------
# random waypoint sets: a continuous, reachable path or a clear error
# --------------------------------------------------------------------------------------------------
@st.composite
def random_plans(draw):
    n = draw(st.integers(2, 5))
    pts = []
    for _ in range(n):
        r = draw(st.floats(0.05, 0.98))
        ang = draw(st.floats(-math.pi, math.pi))
        z = draw(st.floats(0.02, 0.98))
        pts.append([r * math.cos(ang), r * math.sin(ang), z])
    durations = [draw(st.integers(5, 40)) / 10 for _ in range(n - 1)]
    wps = [Waypoint(pts[0])]
    for i in range(1, n - 1):
        ant = draw(st.integers(0, 15)) / 10  # often shorter than both segments, sometimes not
        wps.append(Waypoint(pts[i], anticipation=ant))
    wps.append(Waypoint(pts[-1]))
    return wps, durations


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(random_plans())
def test_random_paths_are_continuous_and_reachable_or_refused_clearly(plan):
    wps, durations = plan
    dt = 0.01
    try:
        tr = plan_path(wps, durations, dt=dt)
    except ScaraError as exc:
        msg = str(exc)
        assert len(msg) > 20
        assert any(w in msg for w in ("anticipation", "unreachable", "repeated point", "leaves the workspace"))
        return
    assert is_reachable(tr.x).all()
    assert np.all(np.isfinite(tr.x)) and np.all(np.isfinite(tr.xd)) and np.all(np.isfinite(tr.xdd))
    bound = np.abs(tr.xdd).max(axis=0) * dt
    assert np.all(np.abs(np.diff(tr.xd, axis=0)) <= bound + 1e-12)
    for i, w in enumerate(wps):
        if not w.via:
            k = 0 if i == 0 else round(tr.segment_end[i - 1] / dt)
            np.testing.assert_allclose(tr.x[k, :3], w.position, atol=1e-9)
            np.testing.assert_allclose(tr.xd[k], 0.0, atol=1e-12)


# --------------------------------------------------------------------------------------------------
# plain-Python path (SCARA_NO_NUMBA=1) gives the same trajectory
# --------------------------------------------------------------------------------------------------
def test_plain_python_path_gives_the_same_numbers(ref):
    code = ("import json, scara; from scara._compile import COMPILED; tr = scara.reference_trajectory(dt=0.01); "
            "print(json.dumps([COMPILED, tr.q0.tolist(), tr.x[::50].tolist()]))")
    env = dict(os.environ, SCARA_NO_NUMBA="1")
    out = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, check=True)
    compiled, q0, x = json.loads(out.stdout)
    assert compiled is False
    np.testing.assert_allclose(q0, ref.q0, atol=1e-14)
    np.testing.assert_allclose(x, ref.x[::500], atol=1e-14)


# --------------------------------------------------------------------------------------------------
# the live waypoint editor re-plans on every edit and shows the planner's message for a bad one
# --------------------------------------------------------------------------------------------------
def test_waypoint_editor_replans_and_reports_errors():
    pytest.importorskip("ipywidgets")
    from scara.widgets import waypoint_editor

    ed = waypoint_editor(profiles=False)
    c = ed.panel.controls
    assert ed.panel.last_error is None and ed.trajectory is not None
    c["point"].value = 7  # the sliders now show p7
    assert (c["x"].value, c["y"].value, c["z"].value) == (0.70, 0.15, 0.3) and not c["via"].value
    c["x"].value = 0.99  # r > a1 + a2 somewhere on p6 -> p7
    assert "leaves the workspace" in ed.panel.last_error and "p6->p7" in ed.panel.last_error
    c["x"].value = 0.60
    assert ed.panel.last_error is None
    np.testing.assert_allclose(ed.trajectory.waypoints[7], [0.60, 0.15, 0.3])
    c["point"].value = 0
    c["via"].value = True
    assert "cannot be a via point" in ed.panel.last_error
    c["via"].value = False
    c["point"].value, c["segment"].value = 4, 3
    c["duration"].value = 1.5  # shorter than the 2 s anticipation at p4
    assert "shorter than both" in ed.panel.last_error
    c["duration"].value = 6.0
    assert ed.panel.last_error is None
    # the reference plan itself is untouched by the edits
    assert reference_plan()["waypoints"][7].position == (0.70, 0.15, 0.3)


def test_via_point_out_of_reach_is_refused_even_when_its_corner_is_not():
    """A via point's corner is cut, so the sampled path can stay in reach while the point itself is not: the
    planner still refuses the point, naming it."""
    from scara import UnreachableError, plan_path, reference_plan

    plan = reference_plan()
    plan["waypoints"][8] = plan["waypoints"][8].replace(position=(0.99, 0.2, 0.5))
    raw = plan_path(**plan, check=False)
    assert np.hypot(raw.x[:, 0], raw.x[:, 1]).max() <= 1.0  # the rounded corner stays inside
    with pytest.raises(UnreachableError, match=r"waypoint p8 x = \[0\.99 +0\.2 +0\.5 *\] is unreachable"):
        plan_path(**plan)


def test_trajectory_evaluate_refuses_nan_times():
    from scara import NonFiniteError
    tr = plan_path([[0.3, 0.2, 0.5], [0.5, 0.2, 0.5]], durations=[2.0])
    with pytest.raises(NonFiniteError, match=r"t\[0\] = nan is not a finite time"):
        tr.evaluate([math.nan])


def test_sample_count_is_bounded_before_any_work():
    import re
    from scara.trajectory.planner import MAX_SAMPLES
    two = [[0.3, 0.2, 0.5], [0.5, 0.2, 0.5]]
    with pytest.raises(ScaraError, match=rf"duration of segment p0->p1 = 2 s is 2e\+09 sampling periods dt = 1e-09 s, "
                                         r"more than a plan may hold \(MAX_SAMPLES = " + re.escape(f"{MAX_SAMPLES:g}") + r" samples\)"):
        plan_path(two, durations=[2.0], dt=1e-9)
    with pytest.raises(ScaraError, match=r"total = 1e\+06 s is 1e\+09 sampling periods .*\(MAX_SAMPLES = "
                                         + re.escape(f"{MAX_SAMPLES:g}")):
        plan_path(two, durations=[2.0], total=1e6)


def test_wrong_types_of_planning_inputs_raise_scara_errors():
    two = [[0.3, 0.2, 0.5], [0.5, 0.2, 0.5]]
    with pytest.raises(ScaraError, match=r"check = 'no' must be True or False"):
        plan_path(two, durations=[2.0], check="no")
    with pytest.raises(ShapeError, match=r"blends must be a sequence with one blend time .* got 0\.5"):
        plan_path(two, durations=[2.0], blends=0.5)
    with pytest.raises(ScaraError, match=r"blends\[0\] must be a number, got 'a'"):
        plan_path(two, durations=[2.0], blends=["a"])
    with pytest.raises(ScaraError, match=r"arcs must be a dict .* got True"):
        plan_path(two, durations=[2.0], arcs=True)
    with pytest.raises(ScaraError, match=r"phi must be a number of radians, got \{'a': 1\.0\}"):
        plan_path(two, durations=[2.0], phi={"a": 1.0})
    with pytest.raises(ScaraError, match=r"phi at a waypoint must be a number of radians, got 'a'"):
        Waypoint([0.3, 0.2, 0.5], phi="a")


def test_plan_honours_the_stroke_of_the_params():
    short = ScaraParams(d3_min=0.0, d3_max=0.4)  # p_z = 0.5 needs d3 = 0.5 m
    with pytest.raises(UnreachableError, match=r"outside the stroke d3_min = 0 m <= d3 <= d3_max = 0\.4 m"):
        plan_path([[0.3, 0.2, 0.5], [0.5, 0.2, 0.5]], durations=[2.0], p=short)


def test_an_arcs_key_must_be_a_segment_index_not_a_bool():
    two = [[0.3, 0.2, 0.5], [0.5, 0.2, 0.5], [0.5, 0.4, 0.5]]
    for key in (True, 0.0, 2, -1):
        with pytest.raises(ScaraError, match=rf"arcs keys are segment indices 0\.\.1 .* got {key!r}"):
            plan_path(two, durations=[2.0, 2.0], arcs={key: (0.45, 0.3, 0.5)})
