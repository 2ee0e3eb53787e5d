"""Tests of scara.params: the parameter object is frozen, and a payload or a replaced value is checked."""
import numpy as np
import pytest

from scara import ScaraError, ScaraParams


def test_params_object():
    p = ScaraParams()
    with pytest.raises(Exception):
        p.a1 = 2.0  # frozen
    q = p.with_payload(5.0)
    assert q.m_L == 5.0 and q.m3 == 15.0 and p.m_L == 0.0
    assert np.allclose(p.F, [5e-5, 5e-5, 25.0, 2.0])
    assert p.replace(a1=0.6).a1 == 0.6
    with pytest.raises(ScaraError, match="unknown parameter"):
        p.replace(mass=3)
    with pytest.raises(ScaraError, match=r"m_L = -1.0 must be finite and >= 0"):
        p.with_payload(-1.0)
    with pytest.raises(ScaraError, match="k_r must have 4 entries"):
        p.replace(k_r=(1, 2, 3))


def test_booleans_and_strings_are_not_parameters():
    with pytest.raises(ScaraError, match=r"a1 must be a number, got True"):
        ScaraParams(a1=True)
    with pytest.raises(ScaraError, match=r"k_r must be 4 numbers \(one per joint\), got \(1, 2, 'a', 4\)"):
        ScaraParams(k_r=(1, 2, "a", 4))


def test_stroke_limits_are_the_joint_limits():
    p = ScaraParams(d3_min=0.1, d3_max=0.8)
    assert p.q_min[2] == 0.1 and p.q_max[2] == 0.8
    with pytest.raises(ScaraError, match=r"d3_min = 0\.8 m \.\. d3_max = 0\.1 m must be a range"):
        ScaraParams(d3_min=0.8, d3_max=0.1)


@pytest.mark.parametrize("field, value, limit", [
    ("a1", 1e-300, r"a1 = 1e-300 m is below 1e-06 m"), ("a2", 1e-300, r"a2 = 1e-300 m is below 1e-06 m"),
    ("a1", 1e308, r"a1 = 1e\+308 is above 1e\+06"), ("d0", 1e308, r"d0 = 1e\+308 is above 1e\+06"),
    ("l2", 1e300, r"l2 = 1e\+300 is above 1e\+06"),
])
def test_lengths_the_model_cannot_keep_accurate_are_refused(field, value, limit):
    """An arm of 1e-300 m or 1e308 m would end in a wrong inverse kinematics or an overflow: refused at once."""
    with pytest.raises(ScaraError, match=limit):
        ScaraParams(**{field: value})


def test_degenerate_but_accepted_parameters_are_handled():
    """l2 = 0 (link 2's centre of mass on joint 2) and zero link inertias are physical: the model works, and
    where B(q) has no inverse, forward_dynamics says which joint has no inertia and what would give it some."""
    from scara import UnstableError, forward_dynamics, inertia, ikine, manipulability, plan_path, pose
    from scara import dynamic_parameters, params_from_pi

    q = np.array([0.1, 0.5, 0.5, 0.0])
    p = ScaraParams(l2=0.0)
    back = params_from_pi(dynamic_parameters(p), p)
    assert back.m_l2 == p.m_l2 and np.allclose(dynamic_parameters(back), dynamic_parameters(p), rtol=1e-14)
    assert np.isfinite(forward_dynamics(q, np.zeros(4), np.zeros(4), p)).all()
    bare = ScaraParams(I_l1=0, I_l2=0, I_l4=0, m_l1=0, m_l2=0, m_l3=0, I_m=(0, 0, 0, 0))
    assert np.array_equal(inertia(q, bare), np.zeros((4, 4)))
    with pytest.raises(UnstableError, match=r"joint 1 has no inertia of its own .* I_l1, m_l1 l1\^2, k_r1\^2 I_m1 "
                                            r".* must not all be 0"):
        forward_dynamics(q, np.zeros(4), np.zeros(4), bare)
    no_tool = ScaraParams(I_l4=0, I_m=(0.01, 0.01, 0.005, 0.0))
    with pytest.raises(UnstableError, match=r"joint 4 has no inertia of its own \(B44 = 0\).*I_l4, k_r4\^2 I_m4"):
        forward_dynamics(q, np.zeros(4), np.zeros(4), no_tool)
    # the kinematics of such arms are untouched
    assert np.allclose(ikine(pose(q, bare), bare, elbow=+1), q)
    assert manipulability(q, bare) > 0
    assert plan_path([[0.5, 0.2, 0.5], [0.5, 0.3, 0.5]], [1.0], p=bare, dt=0.01).x.shape == (101, 4)


def test_lengths_at_the_ends_of_the_range_work():
    from scara import ikine, is_reachable, pose
    from scara._manipulability import workspace_map

    for p in (ScaraParams(a1=1e-6, a2=1e-6, d0=1e-6, d3_max=1e-6), ScaraParams(a1=1e6, a2=1e6, d0=1e6, d3_max=1e6)):
        q = np.array([0.3, 1.0, 0.5 * p.d3_max, 0.0])
        x = pose(q, p)
        assert bool(is_reachable(x, p))
        assert np.allclose(ikine(x, p, elbow=+1), q, rtol=1e-9, atol=1e-9 * p.a1)
        assert np.isfinite(np.nanmax(workspace_map(p, n=11)[2]))


def test_a_gear_ratio_of_zero_is_refused():
    """A motor with ``k_r = 0`` drives nothing: the parameters refuse it where they are given, naming the field."""
    with pytest.raises(ScaraError, match=r"k_r = \[1\.0, 1\.0, 0\.0, 20\.0\] must be > 0 for every joint"):
        ScaraParams(k_r=(1.0, 1.0, 0.0, 20.0))
