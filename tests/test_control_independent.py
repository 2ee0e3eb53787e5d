"""Tests of scara.control.independent (chapter 6): the independent-joint PID/PD law against steps computed by
hand (unsaturated, saturated, the anti-windup update), the pole placement and the inertia margin, the nominal
model and how far the arm strays from it, saturation over whole runs, the integral against the quill's weight,
windup, the bad settings, and the interface every controller of the chapter shares."""
import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from scara import IndependentJointController, ScaraError, ShapeError, UnstableError, inertia, simulate
from scara.control import (
    B_BAR, ERROR_BOUND, OMEGA, TAU_MAX, TORQUE_BOUND, control_summary, independent_gains, joint_inertia_spread,
    law_cost, nominal_inertia, replay_law,
)
from scara._simulate import _compiled_law

import _largest
from _control_shared import G0, P0, P5, _after, _pos_err, _rest, first_samples, plain_python


def _step(c, q, qd, ref, chi, dt=1e-3):
    """One call of the compiled law: ``(code, tau, signals, chi after the update)``."""
    law = _compiled_law(c.law)
    state = np.array(chi, dtype=float)
    sig = np.zeros(len(c.signal_names))
    tau = np.zeros(4)
    code = law(0, 0.0, dt, np.asarray(q, float), np.asarray(qd, float), np.asarray(ref, float), c.gains_array(),
               c.model_array(), state, np.zeros((1, 4)), sig, tau)
    return code, tau, sig, state


# a state and a reference chosen by hand: q_d - q = (0.002, -0.001, 0.003, -0.004),
# qd_d - qd = (0.1, -0.2, 0.05, 0), qdd_d = (0.5, -0.5, 1, 2), chi = (0.01, -0.02, 0.003, 0)
Q = np.array([0.1, -1.0, 0.5, 0.2])
QD = np.array([0.01, 0.02, -0.03, 0.04])
REF = np.concatenate([Q + [0.002, -0.001, 0.003, -0.004], QD + [0.1, -0.2, 0.05, 0.0], [0.5, -0.5, 1.0, 2.0]])
CHI = np.array([0.01, -0.02, 0.003, 0.0])
HAND = dict(B_bar=(2.0, 3.0, 4.0, 5.0), K_P=(100.0, 200.0, 300.0, 400.0), K_D=(10.0, 20.0, 30.0, 40.0),
            K_I=(500.0, 600.0, 700.0, 800.0))
# F = diag(k_r^2 F_m) of ScaraParams(): (5e-5, 5e-5, 25, 2); qd_d = (0.11, -0.18, 0.02, 0.04)
# v_1 = 100 (0.002) + 10 (0.1) + 500 (0.01) + 2 (0.5) + 5e-5 (0.11)      =   0.2 + 1 + 5 + 1 + 5.5e-6  =   7.2000055
# v_2 = 200 (-0.001) + 20 (-0.2) + 600 (-0.02) + 3 (-0.5) + 5e-5 (-0.18)  = -0.2 - 4 - 12 - 1.5 - 9e-6  = -17.700009
# v_3 = 300 (0.003) + 30 (0.05) + 700 (0.003) + 4 (1) + 25 (0.02)         =   0.9 + 1.5 + 2.1 + 4 + 0.5 =   9.0
# v_4 = 400 (-0.004) + 40 (0) + 800 (0) + 5 (2) + 2 (0.04)                =  -1.6 + 0 + 0 + 10 + 0.08   =   8.48
V_HAND = np.array([7.2000055, -17.700009, 9.0, 8.48])


# --------------------------------------------------------------------------------------------------
# the law, one step computed by hand
# --------------------------------------------------------------------------------------------------
def test_law_step_by_hand_unsaturated():
    c = IndependentJointController(**HAND)
    code, tau, sig, chi = _step(c, Q, QD, REF, CHI)
    assert code == 0
    np.testing.assert_allclose(tau, V_HAND, rtol=1e-13, atol=1e-13)
    # the integral action used at this sample, K_I chi, and no joint clipped
    np.testing.assert_allclose(sig, [5.0, -12.0, 2.1, 0.0, 0.0], rtol=1e-13, atol=1e-15)
    # chi_{k+1} = chi_k + T qt_k for every joint
    np.testing.assert_allclose(chi, CHI + 1e-3 * np.array([0.002, -0.001, 0.003, -0.004]), rtol=1e-13, atol=1e-18)
    # without the feedforward the terms B_bar qdd_d + F qd_d are gone: 7.2000055 - 1 - 5.5e-6 = 6.2
    _, tau_noff, _, _ = _step(IndependentJointController(feedforward=False, **HAND), Q, QD, REF, CHI)
    np.testing.assert_allclose(tau_noff, [6.2, -16.2, 4.5, -1.6], rtol=1e-13, atol=1e-13)


def test_law_step_by_hand_saturated_and_the_anti_windup_update():
    """Bounds (5, 10, 100, 8): joint 1 (v = 7.2, qt > 0) is clipped to +5 with the error pushing further, so its
    integrator holds; joint 2 (v = -17.7, qt < 0) is clipped to -10 and holds too; joint 4 (v = 8.48, qt < 0) is
    clipped to +8 but its error pulls back, so it integrates; joint 3 is inside its bound and integrates."""
    c = IndependentJointController(tau_max=(5.0, 10.0, 100.0, 8.0), **HAND)
    code, tau, sig, chi = _step(c, Q, QD, REF, CHI)
    assert code == 0
    np.testing.assert_array_equal(tau, [5.0, -10.0, 9.0, 8.0])
    assert sig[4] == 3.0  # three joints clipped
    np.testing.assert_allclose(chi, [0.01, -0.02, 0.003 + 1e-3 * 0.003, -1e-3 * 0.004], rtol=1e-13, atol=1e-18)
    # without anti-windup every integrator runs on
    c_w = IndependentJointController(tau_max=(5.0, 10.0, 100.0, 8.0), anti_windup=False, **HAND)
    _, tau_w, _, chi_w = _step(c_w, Q, QD, REF, CHI)
    np.testing.assert_array_equal(tau_w, tau)
    np.testing.assert_allclose(chi_w, CHI + 1e-3 * np.array([0.002, -0.001, 0.003, -0.004]), rtol=1e-13, atol=1e-18)
    # PD: no integrator at all, and no integral action: v - K_I chi = (2.2000055, -5.700009, 6.9, 8.48), only
    # joint 4 beyond its bound
    c_pd = IndependentJointController(integral=False, tau_max=(5.0, 10.0, 100.0, 8.0), **HAND)
    _, tau_pd, sig_pd, chi_pd = _step(c_pd, Q, QD, REF, CHI)
    np.testing.assert_array_equal(chi_pd, CHI)
    np.testing.assert_array_equal(sig_pd[:4], 0.0)
    np.testing.assert_allclose(tau_pd, [2.2000055, -5.700009, 6.9, 8.0], rtol=1e-13)
    assert sig_pd[4] == 1.0


def test_without_saturation_a_command_beyond_its_bound_is_a_failure():
    c = IndependentJointController(saturation=False, tau_max=(5.0, 100.0, 100.0, 100.0), **HAND)
    code, tau, _, _ = _step(c, Q, QD, REF, CHI)
    assert code == TORQUE_BOUND
    np.testing.assert_allclose(tau, V_HAND, rtol=1e-13)  # the command itself, unclipped
    assert "tau_max" in c.explain(code)
    # an error beyond max_error stops the law before any torque
    c_e = IndependentJointController(max_error=0.0025, **HAND)
    code, _, _, chi = _step(c_e, Q, QD, REF, CHI)
    assert code == ERROR_BOUND
    assert "max_error = 0.0025" in c_e.explain(code)


def test_without_saturation_the_tight_bound_stops_the_run(traj, jref):
    c = IndependentJointController(saturation=False, tau_max=(200.0, 200.0, 155.0, 50.0))
    with pytest.raises(UnstableError, match=r"diverged at t = 0\.0\d+ s.*tau_max = \[200\.0, 200\.0, 155\.0, 50\.0\]"):
        c.run(traj, P5, joint_reference=jref)


# --------------------------------------------------------------------------------------------------
# design: pole placement, the inertia margin, the nominal model
# --------------------------------------------------------------------------------------------------
@given(b=st.floats(0.1, 100.0), w=st.floats(1.0, 300.0), frac=st.floats(0.0, 0.99))
def test_pole_placement_gives_a_triple_or_double_pole(b, w, frac):
    """The error polynomial B_bar s^3 + (F + K_D) s^2 + K_P s + K_I must equal B_bar (s + omega)^3, whose
    coefficients are B_bar (1, 3 w, 3 w^2, w^3); PD: B_bar s^2 + (F + K_D) s + K_P = B_bar (s + w)^2. The friction
    F stays below 2 w B_bar, so that K_D > 0 for both."""
    f = frac * 2.0 * w * b
    K_P, K_D, K_I = independent_gains(b, w, f)
    want = b * np.poly([-w, -w, -w])
    got = np.array([b * np.ones(4), f + K_D, K_P, K_I]).T
    assert np.abs(got - want).max() <= 1e-12 * want.max()
    K_P2, K_D2, K_I2 = independent_gains(b, w, f, integral=False)
    want2 = b * np.poly([-w, -w])
    got2 = np.array([b * np.ones(4), f + K_D2, K_P2]).T
    assert np.abs(got2 - want2).max() <= 1e-12 * want2.max()
    assert np.all(K_I2 == 0)


def test_book_gains_and_motor_gains():
    c = IndependentJointController()
    F = P0.F
    w = OMEGA
    np.testing.assert_allclose(c.K_P, 3 * w ** 2 * np.array(B_BAR), rtol=1e-15)
    np.testing.assert_allclose(c.K_D, 3 * w * np.array(B_BAR) - F, rtol=1e-15)
    np.testing.assert_allclose(c.K_I, w ** 3 * np.array(B_BAR), rtol=1e-15)
    assert c.K_P[2] == 60750.0  # 3 * 900 * 22.5 N/m
    m = c.motor_gains()
    # the quill's motor sees K_P3 / k_r3^2 = 60750 / 2500 = 24.3 N m/rad
    assert m["K_P"][2] == pytest.approx(24.3, rel=1e-14)
    np.testing.assert_allclose(m["K_D"] * np.asarray(P0.k_r) ** 2, c.K_D, rtol=1e-15)


@pytest.mark.parametrize("omega", [5.0, 30.0, 120.0])
def test_inertia_margin_is_where_the_loop_loses_stability(omega):
    """Routh: B s^3 + (F + K_D) s^2 + K_P s + K_I is Hurwitz iff B < (F + K_D) K_P / K_I; checked on the roots just
    below and above the margin. With the placed gains F + K_D = 3 w B_bar, so the margin is
    3 w B_bar 3 w^2 B_bar / (w^3 B_bar B_bar) = 9, with or without friction."""
    c = IndependentJointController(omega=omega)
    margin = c.inertia_margin()
    for i in range(4):
        for scale, stable in ((0.99, True), (1.01, False)):
            B = scale * margin[i] * c.B_bar[i]
            roots = np.roots([B, c.F[i] + c.K_D[i], c.K_P[i], c.K_I[i]])
            assert (roots.real.max() < 0) == stable, (i, scale)
    np.testing.assert_allclose(margin, 9.0, rtol=1e-12)
    c0 = IndependentJointController(omega=omega, model=P0.replace(F_m=(0.0, 0.0, 0.0, 0.0)))
    np.testing.assert_allclose(c0.inertia_margin(), 9.0, rtol=1e-14)
    # explicit gains move it: twice the integral gain halves it
    c2 = IndependentJointController(omega=omega, K_I=2 * c.K_I)
    np.testing.assert_allclose(c2.inertia_margin(), 4.5, rtol=1e-12)
    assert np.all(np.isinf(IndependentJointController(integral=False).inertia_margin()))


def test_nominal_inertia_and_how_far_the_arm_strays(jref):
    q = jref.q[::100]
    Bbar = nominal_inertia(q)
    # B22, B33, B44 are constant: beta22 + m3 a2^2, m3 + k_r3^2 I_m3, I_l4 + k_r4^2 I_m4
    assert Bbar[2] == pytest.approx(P0.m3 + P0.k_r[2] ** 2 * P0.I_m[2], rel=1e-14)       # 10 + 12.5
    assert Bbar[3] == pytest.approx(P0.I_l4 + P0.k_r[3] ** 2 * P0.I_m[3], rel=1e-14)     # 1 + 0.4
    np.testing.assert_allclose(Bbar, B_BAR, rtol=0.005)          # the stored entries, rounded
    np.testing.assert_allclose(np.round(Bbar, 2)[1:], np.asarray(B_BAR)[1:], atol=1e-9)
    sp = joint_inertia_spread(q, payloads=(0.0, 10.0))
    # the quill: only the payload changes its inertia, (m3 + 10 + 12.5) / 22.5
    assert sp["low"][2] == pytest.approx(1.0, rel=1e-14)
    assert sp["high"][2] == pytest.approx((P0.m_l3 + 10.0 + 12.5) / 22.5, rel=1e-14)
    # ... and its coupling is the rotor terms B13 = B23 = k_r3 I_m3 = 0.25: 0.5 / 22.5
    assert sp["coupling"][2] == pytest.approx(2 * P0.k_r[2] * P0.I_m[2] / 22.5, rel=1e-12)
    np.testing.assert_allclose(sp["rotor"], np.asarray(P0.k_r) ** 2 * np.asarray(P0.I_m) / np.asarray(B_BAR),
                               rtol=1e-15)
    # joint 1: B11 = beta11 + 2 a1 (m_l2 l2 + m3 a2) cos theta2 ranges with the elbow, the motor's own rotor is
    # a thousandth of it
    B11 = np.array([inertia(qk, P0.with_payload(m))[0, 0] for m in (0.0, 10.0) for qk in q])
    assert sp["high"][0] == pytest.approx(B11.max() / B_BAR[0], rel=1e-14)
    assert sp["low"][0] == pytest.approx(B11.min() / B_BAR[0], rel=1e-14)
    assert sp["high"][0] - sp["low"][0] > 0.5 and sp["rotor"][0] < 1e-3
    assert sp["rotor"][2] > 0.5


# --------------------------------------------------------------------------------------------------
# whole runs: saturation, the integral, windup
# --------------------------------------------------------------------------------------------------
@pytest.mark.parametrize("name", ["pid", "pd", "saturated", "windup"])
def test_every_torque_respects_its_bound_over_the_whole_run(independent_runs, name):
    c, r = independent_runs[name]
    assert len(r.t) == 70001  # the whole 70 s
    assert np.all(np.isfinite(r.tau))
    assert np.all(np.abs(r.tau) <= c.tau_max[None, :]), np.abs(r.tau).max(axis=0)
    clipped = r.saturated > 0
    if name in ("saturated", "windup"):
        # the bound is reached (the law clips to it exactly) and only the quill is clipped
        assert clipped.sum() > 100
        assert np.abs(r.tau[:, 2]).max() == c.tau_max[2]
        assert np.all(np.abs(r.tau[clipped, 2]) == c.tau_max[2])
    else:
        assert not clipped.any() and np.all(np.abs(r.tau) < np.asarray(TAU_MAX))


def test_integral_removes_the_steady_error_of_gravity_on_the_quill(independent_runs):
    """No gravity model: at rest PD needs K_P3 qt_3 = g_3 = -m3 g0, so the quill sags by m3 g0 / K_P3 (by hand:
    15 * 9.81 / (900 * 22.5) = 7.2667 mm) and the other joints carry no gravity torque; the integral removes it."""
    c_pd, r_pd = independent_runs["pd"]
    sag = (P0.m_l3 + 5.0) * G0 / (OMEGA ** 2 * 22.5)
    assert sag == pytest.approx(7.2667e-3, rel=1e-4)
    e_rest = (r_pd.q_d - r_pd.q)[_rest(r_pd)]
    assert _largest.record("PD sag at rest, relative", abs(e_rest[:, 2].mean() + sag) / sag) < 1e-6
    np.testing.assert_allclose(c_pd.steady_state_error(P5), [0, 0, -sag, 0], rtol=1e-14)
    assert np.abs(e_rest[:, [0, 1, 3]]).max() < 1e-9
    # in the operational error: z_d - z_e = +sag
    assert r_pd.e[_rest(r_pd), 2].mean() == pytest.approx(sag, rel=1e-6)
    c, r = independent_runs["pid"]
    assert _pos_err(r)[_rest(r)].max() < 1e-9
    # the integral action settles at the whole weight, quill and payload: -m3 g0
    assert r.integral_action_3[-1] == pytest.approx(-(P0.m_l3 + 5.0) * G0, rel=1e-6)
    assert np.all(c.steady_state_error(P5) == 0)


def test_pid_tracks_the_path_and_saturation_with_anti_windup_costs_only_the_start(independent_runs):
    _, r = independent_runs["pid"]
    _, rs = independent_runs["saturated"]
    assert _pos_err(r)[_after(r)].max() < 10e-6
    # with the quill's force bounded at 155 N the start transient is longer, but after the first second the torques
    # of the two runs differ by less than a millionth of the quill's force (147 N)
    late = r.t >= 1.0
    assert np.abs(rs.tau[late] - r.tau[late]).max() < 1e-6 * (P0.m_l3 + 5.0) * G0
    assert _pos_err(rs).max() > 1.5 * _pos_err(r).max()
    # conditional integration: no overshoot above the reference (the ideal actuator's quill hardly rises either)
    assert (rs.q_d[:, 2] - rs.q[:, 2]).max() < 1e-5


def test_windup_without_anti_windup(independent_runs, traj, jref):
    """Without anti-windup the integrator keeps growing while the quill's force is clipped, and the quill then
    overshoots: it rises millimetres above its reference, and the clipping lasts several times longer."""
    _, rs = independent_runs["saturated"]
    _, rw = independent_runs["windup"]
    overshoot = (rw.q_d[:, 2] - rw.q[:, 2]).max()
    assert overshoot > 5e-3
    assert rw.integral_action_3.min() < 3 * rs.integral_action_3.min()  # wound up far past the -147 N it needs
    last = lambda r: r.t[np.flatnonzero(r.saturated > 0)[-1]]  # noqa: E731
    assert last(rw) > 2.5 * last(rs)
    assert _pos_err(rw)[_after(rw)].max() > 10 * _pos_err(rs)[_after(rs)].max()
    # at 150 N (2 % above the weight) the wound-up loop oscillates until the error passes its bound
    with pytest.raises(UnstableError, match="max_error"):
        IndependentJointController(tau_max=(200.0, 200.0, 150.0, 50.0), anti_windup=False).run(
            traj, P5, joint_reference=jref)
    IndependentJointController(tau_max=(200.0, 200.0, 150.0, 50.0)).run(traj, P5, joint_reference=jref)


# --------------------------------------------------------------------------------------------------
# the interface every controller of chapter 6 shares
# --------------------------------------------------------------------------------------------------
def _numpy_independent(c, q, qd, ref, chi):
    """The law written again with numpy: v = ff + K_P qt + K_D qt_dot + K_I chi, clipped, and conditional
    integration."""
    qt, qtd = ref[:4] - q, ref[4:8] - qd
    v = c.K_P * qt + c.K_D * qtd + c.K_I * chi + c.B_bar * ref[8:] + c.F * ref[4:8]
    u = np.clip(v, -c.tau_max, c.tau_max) if c.saturation else v
    clipped = u != v
    hold = c.anti_windup & clipped & (qt * v > 0)
    return u, np.where(hold, chi, chi + 1e-3 * qt) if c.integral else chi


@pytest.mark.parametrize("name", ["pid", "pd", "saturated", "windup"])
def test_compiled_law_matches_numpy(independent_runs, name):
    c, r = independent_runs[name]
    n = 1500  # the start transient, where the saturated runs clip
    tau, sig, state = replay_law(c, r, n)
    assert np.array_equal(tau, r.tau[:n])  # the replay is the run's own law
    chi = np.zeros(4)
    worst = 0.0
    for k in range(n):
        t_np, chi_next = _numpy_independent(c, r.q[k], r.qd[k], r.reference[k], chi)
        np.testing.assert_allclose(sig[k, :4], c.K_I * chi, rtol=1e-12, atol=1e-9)
        worst = max(worst, np.abs(t_np - tau[k]).max())
        chi = chi_next
    np.testing.assert_allclose(state, chi, rtol=1e-12, atol=1e-15)
    assert _largest.record("compiled law against numpy, N m", worst) < 1e-9 * np.abs(r.tau).max()


def test_interface(independent_runs):
    c, r = independent_runs["pid"]
    assert c.name == "independent" and r.controller == "independent"
    assert IndependentJointController(integral=False).name == "independent_pd"
    assert c.reference_kind == "joint" and r.q_d is not None
    assert set(c.signal_names) <= set(r.signals) and len(c.signal_names) == 5
    assert np.array_equal(c.tau_max, np.asarray(TAU_MAX)) and c.max_error == 0.05
    assert c.initial_state().shape == (4,) and not c.initial_state().any()
    s = control_summary(r, c, repeats=2)
    assert s["controller"] == "independent" and s["final_position_error"] < 1e-9
    assert np.array_equal(s["peak_tau"], np.abs(r.tau).max(axis=0))
    assert 0 < law_cost(c, r, repeats=1) < 1e-4
    assert "IndependentJointController(integral=True" in repr(c)


def test_plain_python_path_matches_compiled(traj, jref):
    """The same first 300 samples without numba, with the quill's force bounded at 155 N (the law clips there)."""
    n = 300
    plain = np.array(plain_python(n, (
        "c = IndependentJointController(tau_max=(200, 200, 155, 50))\n"
        "r = simulate(c, sub, p, joint_reference=jr)\n"
        "print(json.dumps(np.r_[r.q.ravel(), r.tau.ravel(), r.saturated].tolist()))\n")))
    sub, jr = first_samples(traj, jref, n)
    r = simulate(IndependentJointController(tau_max=(200, 200, 155, 50)), sub, P5, joint_reference=jr)
    assert r.saturated.sum() > 10
    assert _largest.record("plain Python against compiled", np.abs(plain - np.r_[r.q.ravel(), r.tau.ravel(),
                                                                                    r.saturated]).max()) < 1e-8


# --------------------------------------------------------------------------------------------------
# bad settings
# --------------------------------------------------------------------------------------------------
@pytest.mark.parametrize("make, error, match", [
    (lambda: IndependentJointController(omega=0.0), ScaraError, r"omega must be positive definite: omega\[0\] = 0"),
    (lambda: IndependentJointController(omega=[30, 30, -1, 30]), ScaraError, r"omega\[2\] = -1"),
    (lambda: IndependentJointController(omega=math.nan), ScaraError, r"omega must be finite"),
    (lambda: IndependentJointController(B_bar=[14, 8, 0, 1]), ScaraError, r"B_bar\[2\] = 0"),
    (lambda: IndependentJointController(K_P=-1.0), ScaraError, r"K_P must be positive definite"),
    (lambda: IndependentJointController(K_D=[1, 1, 1, 0]), ScaraError, r"K_D\[3\] = 0"),
    (lambda: IndependentJointController(K_I=0.0), ScaraError, r"K_I must be positive definite"),
    (lambda: IndependentJointController(tau_max=[200, 200, 0, 50]), ScaraError, r"tau_max\[2\] = 0"),
    (lambda: IndependentJointController(tau_max=-5.0), ScaraError, r"tau_max"),
    (lambda: IndependentJointController(max_error=0.0), ScaraError, r"max_error"),
    (lambda: IndependentJointController(omega=[30, 30, 30]), ShapeError, r"omega must be"),
    (lambda: IndependentJointController(integral="yes"), ScaraError, r"integral = 'yes' must be True or False"),
    (lambda: IndependentJointController(saturation=1), ScaraError, r"saturation = 1 must be True or False"),
    (lambda: IndependentJointController(anti_windup=None), ScaraError, r"anti_windup = None must be True or False"),
    (lambda: IndependentJointController(feedforward="no"), ScaraError, r"feedforward = 'no' must be True or False"),
    (lambda: IndependentJointController(model="plant"), ScaraError, r"ScaraParams"),
    # the friction of the quill (25 N s/m) alone exceeds 3 omega B_bar = 16.9 at omega = 0.25
    (lambda: IndependentJointController(omega=0.25), ScaraError,
     r"omega\[2\] = 0\.25 rad/s is too slow for joint 3: its friction F\[2\] = 25 alone reaches .* "
     r"choose omega\[2\] > 0\.37"),
    # Routh on the nominal model: K_I >= (F + K_D) K_P / B_bar
    (lambda: IndependentJointController(K_I=1e9), UnstableError, r"K_I\[0\] = 1e\+09 must be < .*Routh"),
])
def test_bad_settings_raise(make, error, match):
    with pytest.raises(error, match=match):
        make()


def test_bad_design_inputs_raise(jref):
    for bad in ([], np.zeros((0, 4))):
        with pytest.raises(ShapeError):
            nominal_inertia(bad)
    with pytest.raises(ScaraError, match="payloads"):
        joint_inertia_spread(jref.q[:3], payloads=-1.0)
    with pytest.raises(ScaraError, match=r"B_bar\[1\] = -2"):
        joint_inertia_spread(jref.q[:3], B_bar=[1, -2, 1, 1])
    with pytest.raises(ScaraError, match=r"F must be positive semi-definite: F\[0\] = -1"):
        independent_gains(F=[-1, 0, 0, 0])
    with pytest.raises(ScaraError, match=r"B_bar = \[1\.e\+300 .* gives a non-finite K_P"):
        independent_gains(B_bar=1e300, omega=1e10)
    assert independent_gains(integral=False)[2].tolist() == [0.0] * 4
    with pytest.raises(ScaraError, match="integral"):
        independent_gains(integral=1)


# --------------------------------------------------------------------------------------------------
# the live panel
# --------------------------------------------------------------------------------------------------
def test_live_panel_offers_the_independent_joint_controller(traj):
    from scara.programs.control import SHOWN
    from scara.widgets import control_panel
    from scara.widgets.control import make_controller

    c = make_controller("independent joint PID", 900, 60, 30, 20, 0.05, 1.0, 0.01, 8000, 50.0)
    assert isinstance(c, IndependentJointController) and np.all(c.omega == 50.0)
    panel = control_panel(traj)
    panel.controls["controller"].value = "independent joint PID"
    assert panel.last_error is None
    assert not panel.controls["omega"].disabled and panel.controls["K_pi"].disabled
    assert panel.state["independent_shown"] == 1.0 and sum(panel.state[f] for f in SHOWN) == 1.0  # its run, alone
    assert panel.figures[0].layout.title.text.startswith("independent joint PID: ")
    panel.controls["omega"].value = 1.0   # too slow for the quill's weight: the sag passes max_error
    assert "max_error" in panel.last_error
    panel.controls["omega"].value = 30.0
    assert panel.last_error is None
    panel.controls["controller"].value = "robust"
    assert panel.controls["omega"].disabled
