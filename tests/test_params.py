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
