"""The references a run receives (scara._simulate.setpoints): computed for the trajectory's arm and elbow, options
that do not apply refused, and the one singularity rule at the start."""
from __future__ import annotations

import numpy as np
import pytest

from scara import PDGravityController, ScaraError, ScaraParams, UnstableError, plan_path, pose, simulate
from scara._clik import clik2
from scara._simulate.setpoints import _start_velocity, ikine_reference

#: an arm of other link lengths than the course's (a1 = a2 = 0.5 m)
OTHER = ScaraParams(a1=0.6, a2=0.45)
SHORT = [[0.55, 0.20, 0.5], [0.55, 0.30, 0.5]]


def _short(p=None, elbow=-1, dt=1e-3):
    return plan_path(SHORT, [0.5], dt=dt, p=p, elbow=elbow)


def test_joint_reference_is_computed_for_the_plants_arm():
    traj = _short(OTHER)
    res = simulate(PDGravityController(model=OTHER), traj, OTHER)
    want = clik2(traj, p=OTHER)
    assert np.array_equal(res.q_d, want.q)
    # the joints it follows put the tool of this arm on the planned path
    assert np.abs(pose(res.q_d, OTHER)[:, :3] - traj.x[:, :3]).max() < 1e-4


def test_a_trajectory_of_another_arm_is_refused_naming_both():
    traj = _short()                      # planned for a1 = a2 = 0.5 m
    with pytest.raises(ScaraError, match=r"planned for an arm with a1 = 0\.5, a2 = 0\.5, d0 = 1 m.*"
                                         r"a1 = 0\.6, a2 = 0\.45, d0 = 1 m"):
        simulate(PDGravityController(model=OTHER), traj, OTHER)
    with pytest.raises(ScaraError, match=r"a1 = 0\.6, a2 = 0\.45"):
        ikine_reference(traj, OTHER)


def test_a_payload_is_not_another_arm():
    traj = _short()
    res = simulate(PDGravityController(), traj, ScaraParams().with_payload(5.0))
    assert np.array_equal(res.q_d, clik2(traj).q)


@pytest.mark.parametrize("elbow", [+1, -1])
def test_ikine_reference_follows_the_plans_elbow_and_arm(elbow):
    traj = _short(OTHER, elbow=elbow)
    ref = ikine_reference(traj)
    assert np.all(np.sign(ref[:, 1]) == elbow)
    assert np.abs(pose(ref[:, :4], OTHER) - traj.x).max() < 1e-12
    # an explicit elbow is honoured
    assert np.all(np.sign(ikine_reference(traj, elbow=-elbow)[:, 1]) == -elbow)


def test_duration_with_a_reference_is_refused():
    traj = _short()
    with pytest.raises(ScaraError, match=r"duration = 2\.0 applies to an open-loop run without reference only, "
                                         r"but traj is given"):
        simulate(PDGravityController(), traj, duration=2.0)
    jref = np.zeros((11, 12))
    jref[:, :4] = [0.0, 1.0, 0.5, 0.0]
    with pytest.raises(ScaraError, match=r"duration = 0\.01 .* but joint_reference is given"):
        simulate(PDGravityController(), joint_reference=jref, duration=0.01)


def test_start_velocity_uses_the_one_singularity_rule():
    with pytest.raises(UnstableError, match=r"the start configuration q0 q = \[0\.0, 0\.0, 0\.5, 0\.0\] is singular"):
        _start_velocity(np.array([0.0, 0.0, 0.5, 0.0]), np.array([0.01, 0.0, 0.0, 0.0]), ScaraParams())
    qd = _start_velocity(np.array([0.0, 1.0, 0.5, 0.0]), np.array([0.01, 0.0, 0.0, 0.0]), ScaraParams())
    assert np.isfinite(qd).all()


def test_ikine_reference_refuses_a_singular_sample():
    traj = plan_path([[0.3, 0.0, 0.5], [1.0, 0.0, 0.5]], [1.0], dt=0.01)  # ends with the arm stretched
    with pytest.raises(UnstableError, match=r"the reference at sample \d+: .* is singular"):
        ikine_reference(traj)


def test_a_run_owns_its_reference_arrays():
    traj = _short()
    jref = np.ascontiguousarray(ikine_reference(traj))
    keep = jref.copy()
    res = simulate(PDGravityController(), traj, joint_reference=jref)
    assert not np.shares_memory(res.reference, jref) and not np.shares_memory(res.q_d, jref)
    assert not np.shares_memory(res.x_d, traj.x)
    assert np.array_equal(jref, keep) and jref.flags.writeable
