"""Tests of scara.control.robust (chapter 6): the tracking target, the theory the design rests on (Lyapunov
equation, sliding variable, inertia uncertainty alpha, rho, boundary-layer sampling limit, steady-state error)."""

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from scara import RobustController, ScaraError, UnstableError, inertia, simulate
from scara.control import (
    B_HAT, TAU_MAX, chattering, design_inertia_estimate, inertia_eigenvalues, inertia_uncertainty, lyapunov_matrix,
    rho_bound, sliding_weight,
)

from _control_shared import G0, P0, P5, _after, _pos_err, _rest


# --------------------------------------------------------------------------------------------------
# the tracking targets of chapter 6
# --------------------------------------------------------------------------------------------------
def test_robust_keeps_the_error_below_half_a_millimetre(runs):
    c, r = runs["robust"]
    assert c.reference_kind == "joint" and r.q_d is not None
    assert _pos_err(r)[_after(r)].max() <= 0.5e-3


# --------------------------------------------------------------------------------------------------
# robust control: the Lyapunov equation, the sliding variable, alpha, rho, the boundary layer
# --------------------------------------------------------------------------------------------------
@given(kp=st.floats(1.0, 1e4), kd=st.floats(1.0, 500.0), frac=st.floats(0.01, 0.99))
def test_sliding_weight_gives_the_sliding_variable(kp, kd, frac):
    """Closed form (by hand, one joint): H^T Q + Q H = -diag(p1, p2) gives Q12 = p1 / (2 k_p) and
    Q22 = (Q12 + p2 / 2) / k_d, so P = diag(2 k_p lambda, 2 (k_d - lambda)) makes D^T Q xi = qt_dot + lambda qt."""
    lam = frac * kd
    P = sliding_weight(kp, kd, lam)
    Q = lyapunov_matrix(kp, kd, P)
    H = np.block([[np.zeros((4, 4)), np.eye(4)], [-kp * np.eye(4), -kd * np.eye(4)]])
    assert np.abs(H.T @ Q + Q @ H + P).max() <= 1e-9 * np.abs(P).max()
    assert np.linalg.eigvalsh(Q).min() > 0
    Z = Q[4:, :]
    np.testing.assert_allclose(Z, np.hstack([lam * np.eye(4), np.eye(4)]), atol=1e-9 * max(1.0, lam))
    # the remaining entry: Q11 = k_p + k_d lambda
    assert Q[0, 0] == pytest.approx(kp + kd * lam, rel=1e-9)


@given(seed=st.integers(0, 2 ** 31 - 1))
def test_lyapunov_matrix_general_weight(seed):
    rng = np.random.default_rng(seed)
    kp, kd = rng.uniform(10, 2000, 4), rng.uniform(5, 200, 4)
    A = rng.normal(size=(8, 8))
    P = A @ A.T + 0.1 * np.eye(8)
    Q = lyapunov_matrix(kp, kd, P)
    H = np.block([[np.zeros((4, 4)), np.eye(4)], [-np.diag(kp), -np.diag(kd)]])
    assert np.abs(H.T @ Q + Q @ H + P).max() <= 1e-8 * np.abs(P).max()
    assert np.linalg.eigvalsh(Q).min() > 0
    c = RobustController(K_P=kp, K_D=kd, P=P)
    np.testing.assert_allclose(c.sliding, Q[4:, :], atol=1e-12 * np.abs(Q).max())


def test_default_robust_design(jref):
    c = RobustController()
    np.testing.assert_allclose(c.sliding, np.hstack([30 * np.eye(4), np.eye(4)]), atol=1e-9)
    q = jref.q[::1000]
    alpha = inertia_uncertainty(B_HAT, q, payloads=(0.0, 5.0, 10.0))
    assert 0.75 < alpha < 0.85
    # the plain diagonal of B breaks the condition alpha < 1
    assert inertia_uncertainty(np.diag(inertia(q.mean(axis=0))), q) > 1.0
    # the search reproduces the stored entries' alpha (joint 3's entry is free over a wide range)
    bh, a_opt = design_inertia_estimate(q[::5])
    assert a_opt <= inertia_uncertainty(B_HAT, q[::5]) + 1e-9
    assert inertia_uncertainty(B_HAT, q[::5]) - a_opt < 0.01
    np.testing.assert_allclose(bh[[0, 1]], np.asarray(B_HAT)[[0, 1]], rtol=0.03)
    # rho covers a 10 kg payload by the Lyapunov bound
    eta0 = max(np.linalg.norm(np.linalg.solve(inertia(qk, P0.with_payload(10.0)), [0, 0, 10.0 * G0, 0])) for qk in q)
    qdd_max = np.linalg.norm(jref.qdd, axis=1).max()
    assert rho_bound(alpha, qdd_max, eta0) < c.rho
    with pytest.raises(UnstableError, match="alpha"):
        rho_bound(1.2, qdd_max, eta0)


def test_robust_static_error_matches_the_boundary_layer_theory(runs):
    """Inside the layer at rest: B33_hat (K_P3 qt3 + (rho / epsilon) Lambda_3 qt3) = g3_hat - g3, so
    e_z = -qt3 = m_L g0 / (B33_hat (K_P3 + rho Lambda_3 / epsilon))."""
    c, r = runs["robust"]
    expect = 5.0 * G0 / (c.B_hat[2] * (c.K_P[2] + c.rho * c.Lambda[2] / c.epsilon))
    assert r.z_norm[_rest(r)].max() < c.epsilon  # inside the layer
    assert r.e[_rest(r), 2].mean() == pytest.approx(expect, rel=1e-3)


def test_robust_term_covers_the_uncertainty(runs):
    c, r = runs["robust"]
    eta = np.linalg.norm(c.uncertainty(r), axis=1)
    assert eta.max() < c.rho
    # the arm moves slowly, so qdd is small and eta = y - qdd is mostly the acceleration y that makes
    # B_hat y cover the missing weight: ||eta|| near m_L g0 / B33_hat
    assert np.median(eta) == pytest.approx(5.0 * G0 / c.B_hat[2], rel=0.02)


def test_boundary_layer_chatters_below_the_sampling_bound(traj, jref):
    """epsilon_bound predicts where the sampled layer loses stability; 20 % below it the torque switches
    every sample (second difference of hundreds of N), 20 % above it stays smooth."""
    c = RobustController()
    lo, hi = inertia_eigenvalues(c.B_hat, jref.q[::500], payloads=(5.0,))
    assert 0 < lo < 1 < hi < 1 + inertia_uncertainty(c.B_hat, jref.q[::500], payloads=(5.0,)) + 1e-9
    bound = c.epsilon_bound(hi)
    assert bound == pytest.approx(hi * c.rho * 1e-3 / (2 - hi * c.K_D.max() * 1e-3))
    assert c.epsilon > 2 * bound  # the book's default has margin
    smooth = simulate(RobustController(epsilon=1.2 * bound), traj, P5, joint_reference=jref)
    rough = simulate(RobustController(epsilon=0.8 * bound), traj, P5, joint_reference=jref)
    assert chattering(rough) > 100 * chattering(smooth)
    assert chattering(rough) > 10.0
    assert np.all(np.abs(rough.tau) <= np.asarray(TAU_MAX))
    with pytest.raises(UnstableError, match="K_D"):
        RobustController(K_D=3000.0, Lambda=30.0).epsilon_bound(1.0)


def test_robust_error_grows_linearly_with_the_payload(traj, jref):
    e = {}
    for m in (2.5, 10.0):
        r = simulate(RobustController(), traj, P0.with_payload(m), joint_reference=jref)
        e[m] = r.e[_rest(r), 2].mean()
    assert e[10.0] == pytest.approx(4 * e[2.5], rel=1e-3)


# --------------------------------------------------------------------------------------------------
# the chapter's figures and live panel
# --------------------------------------------------------------------------------------------------
def test_boundary_layer_slider_steps_switch_runs(traj, jref):
    from scara.plots import boundary_layer_slider_figure

    eps = (0.01, 0.05)
    fig = boundary_layer_slider_figure({e: simulate(RobustController(epsilon=e), traj, P5, joint_reference=jref)
                                        for e in eps}, bound=0.0159)
    steps = fig.layout.sliders[0].steps
    assert len(steps) == len(eps)
    per = len(fig.data) // len(eps)
    for n, step in enumerate(steps):
        vis = step.args[0]["visible"]
        assert vis == [per * n <= i < per * (n + 1) for i in range(len(fig.data))]
        assert ("chatters" in step.args[1]["title.text"]) == (eps[n] <= 0.0159)


def test_rho_bound_refuses_non_finite_bounds():
    for args, name in [((np.nan, 1.0, 1.0), "alpha"), ((0.5, np.inf, 1.0), "qdd_max"), ((0.5, 1.0, np.nan), "eta0_max"),
                       ((0.5, -1.0, 1.0), "qdd_max")]:
        with pytest.raises(ScaraError, match=rf"{name} = "):
            rho_bound(*args)
    with pytest.raises(ScaraError, match=r"qdd_max = 1\.e\+308 gives a non-finite rho"):
        rho_bound(0.5, 1e308, 1e308)


def test_overflowing_designs_are_refused():
    with pytest.raises(ScaraError, match=r"K_P = \[1\.e\+308 .* gives a non-finite "
                                         r"P = diag\(2 K_P Lambda, 2 \(K_D - Lambda\)\)"):
        sliding_weight(1e308, 1e308, 30.0)


def test_payloads_must_be_masses():
    q = np.array([[0.1, 1.0, 0.3, 0.0]])
    for bad in ("abc", True, [[1.0, 2.0]]):
        with pytest.raises(ScaraError, match=r"payloads"):
            inertia_uncertainty(1.0, q, payloads=bad)
        with pytest.raises(ScaraError, match=r"payloads"):
            inertia_eigenvalues(1.0, q, payloads=bad)
