"""Tests of scara.trajectory.reference (chapter 3): the reference scenario, its plan and its trajectory."""
from __future__ import annotations

import numpy as np
import pytest

from scara import ScaraError, ikine, plan_path, pose, reference_plan, reference_trajectory
from scara.trajectory import REFERENCE_DURATIONS, REFERENCE_POINTS

from _trajectory_shared import DT, SCENARIO_POINTS, SCENARIO_VIA


# --------------------------------------------------------------------------------------------------
# the reference scenario (chapter 3)
# --------------------------------------------------------------------------------------------------
def test_reference_meets_the_scenario_of_chapter_3(ref):
    assert ref.dt == DT and ref.total == 70.0
    assert ref.t.shape == (70001,) and ref.x.shape == ref.xd.shape == ref.xdd.shape == (70001, 4)
    np.testing.assert_array_equal(ref.t, np.arange(70001) * DT)
    np.testing.assert_array_equal(ref.waypoints, SCENARIO_POINTS)
    np.testing.assert_array_equal(REFERENCE_POINTS, SCENARIO_POINTS)
    assert [i for i in range(12) if ref.via[i]] == [3, 4, 5, 8]
    assert {i: ref.anticipations[i] for i in range(12) if ref.via[i]} == SCENARIO_VIA
    assert ref.segment_kinds == ["line"] * 10 + ["arc"]
    # durations, anticipations and every stop instant are whole numbers of samples
    for v in [*ref.durations, *ref.anticipations, *ref.segment_start, *ref.segment_end]:
        assert abs(v / DT - round(v / DT)) < 1e-9
    # an anticipation is shorter than both segments it joins
    for i in np.flatnonzero(ref.via):
        assert ref.anticipations[i] < min(ref.durations[i - 1], ref.durations[i])
    # the last >= 2 s: at rest at p11
    assert ref.rest >= 2.0 and ref.motion_end <= 68.0
    tail = ref.t >= ref.motion_end
    np.testing.assert_allclose(ref.x[tail, :3], np.broadcast_to(SCENARIO_POINTS[11], (tail.sum(), 3)), atol=1e-12, rtol=0)
    assert np.all(ref.xd[tail] == 0) and np.all(ref.xdd[tail] == 0)


def test_reference_orientation_is_the_start_configurations(ref):
    q0 = ikine(np.r_[SCENARIO_POINTS[0], 0.0], elbow=-1)  # theta4 = 0 when phi = 0 - ... is solved below
    phi0 = q0[0] + q0[1]  # with phi = theta1 + theta2 the same ikine gives theta4 = 0
    assert q0[1] < 0
    np.testing.assert_allclose(ref.x[:, 3], phi0, atol=0, rtol=0)
    assert np.all(ref.xd[:, 3] == 0) and np.all(ref.xdd[:, 3] == 0)
    np.testing.assert_allclose(ref.q0, [q0[0], q0[1], q0[2], 0.0], atol=1e-12)
    np.testing.assert_allclose(pose(ref.q0), ref.x[0], atol=1e-12)


def test_reference_speeds_and_accelerations_are_gentle(ref):
    s = ref.summary()
    assert 0.01 < s["max_speed"] < 0.1  # m/s: a few cm/s, well inside what a SCARA does
    assert s["max_acceleration"] < 0.05  # m/s^2
    assert max(s["max_joint_speed"]) < 0.5  # rad/s or m/s


def test_reference_dt_must_divide_the_scenario():
    assert reference_trajectory(dt=0.01).t.size == 7001
    with pytest.raises(ScaraError, match="whole number of sampling periods"):
        reference_trajectory(dt=0.003)


# --------------------------------------------------------------------------------------------------
# re-planning: the reference plan is a fresh copy on every call
# --------------------------------------------------------------------------------------------------
def test_replan_and_reference_plan_are_independent_copies(ref):
    plan = reference_plan()
    plan["waypoints"][4] = plan["waypoints"][4].replace(anticipation=0.0)
    assert reference_plan()["waypoints"][4].anticipation == 2.0
    stopped = plan_path(**plan)
    k = round(stopped.segment_end[3] / DT)
    np.testing.assert_allclose(stopped.x[k, :3], SCENARIO_POINTS[4], atol=1e-9)
    assert stopped.total == 70.0 and stopped.rest == pytest.approx(ref.rest - 2.0)
    again = ref.replan(durations=list(REFERENCE_DURATIONS))
    np.testing.assert_array_equal(again.x, ref.x)
