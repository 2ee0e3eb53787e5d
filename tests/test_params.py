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
