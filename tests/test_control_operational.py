"""Tests of scara.control.operational (chapter 6): the steady-state errors with and without the integral term
and the singular Jacobian."""

import numpy as np
import pytest

from scara import OperationalSpaceController, ScaraError, UnstableError, inertia, pose
from scara.control import replay_law

from _control_shared import G0, P0, P5, _pos_err, _rest


# --------------------------------------------------------------------------------------------------
# the tracking targets of chapter 6
# --------------------------------------------------------------------------------------------------
def test_operational_integral_removes_the_steady_state_error(runs):
    _, ri = runs["operational"]
    _, rn = runs["operational_noint"]
    final_i = _pos_err(ri)[_rest(ri)].max()
    assert final_i <= 0.01e-3
    final_n = _pos_err(rn)[_rest(rn)].max()
    assert final_n >= 100 * final_i


def test_vertical_error_without_integral_matches_the_books_formula(runs):
    """Chapter 6: e_z = m_L g0 / (B33_hat K_P,z), B33_hat = m_l3 + k_r3^2 I_m3 (payload-free). Binding
    tolerance 5 %; the full prediction K_P^-1 J_A B_hat^-1 (g - g_hat) (which keeps the rotor coupling
    B13 = B23, 3e-4 relative) must hold to 1e-3: the rest window starts 2 s after the stop, when the transient
    (slowest pole near 26 rad/s) is below 1e-20 of its start."""
    c, r = runs["operational_noint"]
    B33_hat = inertia([0, -1.0, 0.5, 0], P0)[2, 2]
    assert B33_hat == pytest.approx(P0.m_l3 + P0.k_r[2] ** 2 * P0.I_m[2])
    formula = P5.m_L * G0 / (B33_hat * c.K_P[2])
    ez = r.e[_rest(r), 2]
    assert np.ptp(ez) < 1e-3 * formula  # the arm is still
    assert ez.mean() == pytest.approx(formula, rel=0.05)
    q_end = r.q[-1]
    assert ez.mean() == pytest.approx(c.steady_state_error(P5, q_end)[2], rel=1e-3)
    # x, y and phi carry only what the coupling B13 = B23 of motor 3's rotor brings (about 1 % of e_z)
    pred = c.steady_state_error(P5, q_end)
    np.testing.assert_allclose(r.e[_rest(r)].mean(axis=0), pred, rtol=0, atol=1e-3 * formula)
    assert np.abs(pred[[0, 1, 3]]).max() < 0.02 * formula


# --------------------------------------------------------------------------------------------------
# failures
# --------------------------------------------------------------------------------------------------
def test_operational_law_refuses_a_singular_jacobian():
    """At theta2 = 0 (arm stretched) J_A is singular: the law returns code 4 instead of dividing by zero."""
    from types import SimpleNamespace as NS

    from scara.control import SINGULAR_JACOBIAN

    c = OperationalSpaceController()
    q = np.array([[0.3, 0.0, 0.5, 0.0]])
    x = pose(q[0])
    res = NS(t=np.zeros(1), q=q, qd=np.zeros((1, 4)), reference=np.concatenate([x, np.zeros(8)])[None, :], dt=1e-3)
    with pytest.raises(UnstableError, match="sample 0"):
        replay_law(c, res)
    assert "singular" in c.explain(SINGULAR_JACOBIAN)
    res.q = np.array([[0.3, 1e-3, 0.5, 0.0]])  # slightly bent: fine
    res.reference = np.concatenate([pose(res.q[0]), np.zeros(8)])[None, :]
    tau, _, _ = replay_law(c, res)
    assert np.all(np.isfinite(tau))


def test_integral_flag_must_be_a_bool():
    for bad in ("no", "False", 0, 1, None):
        with pytest.raises(ScaraError, match=r"integral = .* must be True or False \(a bool\)"):
            OperationalSpaceController(integral=bad)
    assert OperationalSpaceController(integral=np.False_).integral is False


def test_overflowing_steady_state_error_is_refused():
    # the heaviest payload the parameters accept, on a vanishing vertical gain: the error overflows
    c = OperationalSpaceController(integral=False, K_P=(1200.0, 1200.0, 1e-305, 1200.0))
    with pytest.raises(ScaraError, match=r"m_L = 1\.e\+09 gives a non-finite steady-state error"):
        c.steady_state_error(P0.with_payload(1e9))
