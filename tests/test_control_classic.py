"""Tests of scara.control.classic (chapter 6): PD control with gravity compensation and joint-space inverse dynamics
(computed torque) control. Each law against an independent numpy evaluation at random states; the PD + g torque
shared with chapter 5's law; the closed loops with an exact model (computed torque: the critically damped error
and its sampling correction; PD + g: the Lyapunov function and its derivative); the steady-state errors the
unknown 5 kg payload leaves at the end of the reference run; the sampling limit; bad settings; the interface."""
import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from scara import (ComputedTorqueController, PDGravityController, PDPlusGravityController, ScaraError, ShapeError,
                   UnstableError, coriolis, forward_dynamics, friction, gravity, inertia, simulate)
from scara.control import (ERROR_BOUND, OMEGA, B_BAR, TAU_MAX, TORQUE_BOUND, control_summary, law_cost, replay_law,
                           sampling_limit)
from scara._simulate import _compiled_law

import _largest
from _control_shared import G0, P0, P5, _rest, first_samples, plain_python

T = 1e-3


def _step(c, q, qd, ref, dt=T):
    """One call of the compiled law: ``(code, tau, signals)``."""
    law = _compiled_law(c.law)
    sig = np.zeros(len(c.signal_names))
    tau = np.zeros(4)
    code = law(0, 0.0, dt, np.asarray(q, float), np.asarray(qd, float), np.asarray(ref, float), c.gains_array(),
               c.model_array(), np.zeros(0), np.zeros((c.work_rows, 4)), sig, tau)
    return code, tau, sig


@pytest.fixture(scope="module")
def classic_runs(traj, jref):
    """Both laws along the reference with the unknown 5 kg payload, the book's gains."""
    ctrls = {"pdg": PDPlusGravityController(), "ct": ComputedTorqueController()}
    return {name: (c, simulate(c, traj, P5, joint_reference=jref)) for name, c in ctrls.items()}


# --------------------------------------------------------------------------------------------------
# the laws against numpy
# --------------------------------------------------------------------------------------------------
_angle = st.floats(-3.0, 3.0)
_rate = st.floats(-2.0, 2.0)
_state = st.tuples(st.tuples(_angle, _angle, st.floats(0.05, 0.95), _angle), st.tuples(*[_rate] * 4),
                   st.tuples(*[st.floats(-0.01, 0.01)] * 4), st.tuples(*[_rate] * 4), st.tuples(*[_rate] * 4))


@given(state=_state, omega=st.floats(5.0, 200.0), m_L=st.floats(0.0, 10.0))
def test_pd_plus_gravity_law_matches_numpy(state, omega, m_L):
    q, qd, e, ed, qdd_d = (np.array(v) for v in state)
    model = P0.with_payload(m_L)   # any belief: g_hat comes from it
    c = PDPlusGravityController(omega=omega, model=model, tau_max=[1e9] * 4)
    ref = np.concatenate([q + e, qd + ed, qdd_d])
    e, ed = ref[:4] - q, ref[4:8] - qd   # the errors the law sees (q + e - q is e to a rounding)
    code, tau, sig = _step(c, q, qd, ref)
    want = c.K_P * e + c.K_D * ed + np.array([0.0, 0.0, -(model.m_l3 + m_L) * model.g0, 0.0])
    assert code == 0
    np.testing.assert_allclose(tau, want, rtol=1e-13, atol=1e-12 * np.abs(want).max())
    assert sig[0] == gravity(q, model)[2]


def _model_by_hand(q, qd, p):
    """``B(q)``, ``C(q, qd) qd``, ``F qd`` and ``g`` written out from the arm's parameters (rotors on the links
    before them, the payload on the quill's axis), apart from scara.dynamics."""
    m3 = p.m_l3 + p.m_L
    a1, a2, l1, l2 = p.a1, p.a2, p.l1, p.l2
    kr, Im = np.asarray(p.k_r), np.asarray(p.I_m)
    c2, s2 = math.cos(q[1]), math.sin(q[1])
    B = np.zeros((4, 4))
    B[0, 0] = (p.I_l1 + p.m_l1 * l1 ** 2 + kr[0] ** 2 * Im[0] + p.I_l2 + p.m_l2 * (a1 ** 2 + l2 ** 2 + 2 * a1 * l2 * c2)
               + m3 * (a1 ** 2 + a2 ** 2 + 2 * a1 * a2 * c2) + p.I_l4 + Im[1] + Im[2] + Im[3])
    B[0, 1] = p.I_l2 + p.m_l2 * (l2 ** 2 + a1 * l2 * c2) + m3 * (a2 ** 2 + a1 * a2 * c2) + p.I_l4 + kr[1] * Im[1] + Im[2] + Im[3]
    B[1, 1] = p.I_l2 + p.m_l2 * l2 ** 2 + m3 * a2 ** 2 + p.I_l4 + kr[1] ** 2 * Im[1] + Im[2] + Im[3]
    B[0, 2] = B[1, 2] = kr[2] * Im[2]
    B[2, 2] = m3 + kr[2] ** 2 * Im[2]
    B[0, 3] = B[1, 3] = p.I_l4 + kr[3] * Im[3]
    B[3, 3] = p.I_l4 + kr[3] ** 2 * Im[3]
    B = np.triu(B) + np.triu(B, 1).T
    h = a1 * (p.m_l2 * l2 + m3 * a2) * s2                  # the Christoffel symbols of B: only B11, B12 vary
    Cqd = np.array([-h * (2 * qd[0] * qd[1] + qd[1] ** 2), h * qd[0] ** 2, 0.0, 0.0])
    F = kr ** 2 * np.asarray(p.F_m)
    g = np.array([0.0, 0.0, -m3 * p.g0, 0.0])
    return B, Cqd, F * qd, g


@given(state=_state, omega=st.floats(5.0, 200.0), zeta=st.floats(0.5, 2.0), m_L=st.floats(0.0, 10.0))
def test_computed_torque_law_matches_numpy(state, omega, zeta, m_L):
    q, qd, e, ed, qdd_d = (np.array(v) for v in state)
    model = P0.with_payload(m_L)
    c = ComputedTorqueController(omega=omega, zeta=zeta, model=model, tau_max=[1e9] * 4)
    ref = np.concatenate([q + e, qd + ed, qdd_d])
    e, ed = ref[:4] - q, ref[4:8] - qd   # the errors the law sees (q + e - q is e to a rounding)
    code, tau, sig = _step(c, q, qd, ref)
    y = qdd_d + 2 * zeta * omega * ed + omega ** 2 * e
    B, Cqd, Fqd, g = _model_by_hand(q, qd, model)
    want = B @ y + Cqd + Fqd + g
    # the package's public model gives the same (its own checks are chapter 5's)
    np.testing.assert_allclose(inertia(q, model) @ y + coriolis(q, qd, model) @ qd + friction(model) @ qd
                               + gravity(q, model), want, rtol=1e-12, atol=1e-11 * np.abs(want).max())
    assert code == 0
    np.testing.assert_allclose(sig, y, rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(tau, want, rtol=1e-12, atol=1e-11 * np.abs(want).max())


def test_bounds_stop_the_laws():
    q = np.array([0.1, -1.0, 0.5, 0.2])
    ref = np.concatenate([q + [0.0, 0.0, 0.002, 0.0], np.zeros(8)])
    for c in (PDPlusGravityController(max_error=0.001), ComputedTorqueController(max_error=0.001)):
        assert _step(c, q, np.zeros(4), ref)[0] == ERROR_BOUND
        assert "max_error = 0.001" in c.explain(ERROR_BOUND)
    # the quill's command: 98.1 N of weight less K_P3 e_3; a 50 N bound on it stops both laws
    for c in (PDPlusGravityController(tau_max=[200, 200, 50, 50]), ComputedTorqueController(tau_max=[200, 200, 50, 50])):
        code, tau, _ = _step(c, q, np.zeros(4), ref)
        assert code == TORQUE_BOUND and abs(tau[2]) > 50
        assert "tau_max = [200.0, 200.0, 50.0, 50.0]" in c.explain(code)


def test_pd_plus_gravity_is_chapter_5s_torque(classic_runs):
    """The same gains in chapter 5's unbounded law give the same torques, bit for bit (one kernel computes both)."""
    c, r = classic_runs["pdg"]
    tau5, _, _ = replay_law(PDGravityController(K_P=c.K_P, K_D=c.K_D), r)
    assert np.array_equal(tau5, r.tau)
    tau6, _, _ = replay_law(c, r)
    assert np.array_equal(tau6, r.tau)


# --------------------------------------------------------------------------------------------------
# closed loops with an exact model
# --------------------------------------------------------------------------------------------------
Q_SET = np.array([0.3, -1.2, 0.4, 0.1])
E0 = np.array([0.01, -0.02, 0.005, 0.03])


def _regulation(c, plant, n):
    """A run of ``c`` from ``Q_SET - E0`` at rest toward the constant set point ``Q_SET``, ``n`` samples."""
    ref = np.zeros((n, 12))
    ref[:, :4] = Q_SET
    return simulate(c, None, plant, joint_reference=ref, q0=Q_SET - E0, qd0=np.zeros(4))


@pytest.mark.parametrize("friction_free", [False, True])
def test_computed_torque_error_is_critically_damped(friction_free):
    """With an exact model qdd = y, so each joint's error obeys e'' + 2 omega e' + omega^2 e = 0: from rest at
    e0, e(t) = e0 (1 + omega t) exp(-omega t). Sampled, y is held over each period: to first order in T it lags
    by T/2 on average, e'' + K_D e'(t - T/2) + K_P e(t - T/2) = 0, and the correction Delta e solves
    Delta e'' + K_D Delta e' + K_P Delta e = (T/2) (K_D e'' + K_P e'), whose Laplace transform is
    -(T/2) e0 omega^2 (2 omega s + omega^2) / (s + omega)^4: Delta e = -(T/2) omega e0 exp(-u) (u^2 - u^3/6),
    u = omega t (largest 0.38 (omega T / 2) |e0|, at u = 1.7). What is left is of second order, (omega T)^2 |e0|."""
    plant = P0.replace(F_m=(0.0, 0.0, 0.0, 0.0)) if friction_free else P0
    c = ComputedTorqueController(model=plant)
    w = float(c.omega[0])
    r = _regulation(c, plant, 501)
    e = r.q_d - r.q
    u = w * r.t[:, None]
    closed = E0 * (1 + u) * np.exp(-u)
    zoh = -(T / 2) * w * E0 * np.exp(-u) * (u ** 2 - u ** 3 / 6)
    first = np.abs(e - closed).max(axis=0) / np.abs(E0)
    # the first-order correction is what separates the run from the continuous closed form ...
    np.testing.assert_allclose(first, 0.38 * w * T / 2, rtol=0.02)
    # ... and what is left after it is of second order in omega T
    left = np.abs(e - closed - zoh).max(axis=0) / np.abs(E0)
    assert _largest.record("computed torque against the sampled closed form, / |e0|", left.max()) < (w * T) ** 2


def test_sampling_limit_of_computed_torque():
    """Jury: the held double integrator under y = -K_P e - K_D e' has the characteristic polynomial z^2 + a1 z + a0,
    a1 = K_P T^2/2 + K_D T - 2, a0 = 1 - K_D T + K_P T^2/2; its roots cross the unit circle at omega T = min(4 zeta,
    1 / zeta). Checked on the roots of the sampled loop's own matrix, just below and above the limit."""
    for zeta in (0.3, 0.5, 1.0, 2.0):
        w_max = sampling_limit(zeta, T)
        assert w_max == pytest.approx(min(4 * zeta, 1 / zeta) / T, rel=1e-15)
        for scale, stable in ((0.99, True), (1.01, False)):
            w = scale * w_max
            kp, kd = w * w, 2 * zeta * w
            phi = np.array([[1 - kp * T * T / 2, T - kd * T * T / 2], [-kp * T, 1 - kd * T]])
            assert (np.abs(np.linalg.eigvals(phi)).max() < 1) == stable, (zeta, scale)
        ComputedTorqueController(omega=0.99 * w_max, zeta=zeta)
        with pytest.raises(UnstableError, match=rf"omega < min\(4 zeta, 1 / zeta\) / dt = {w_max:g} rad/s"):
            ComputedTorqueController(omega=1.01 * w_max, zeta=zeta)
    # a coarser sampling lowers the limit: 100 rad/s at 10 ms
    with pytest.raises(UnstableError, match="dt = 0.01 s"):
        ComputedTorqueController(omega=120.0, dt=0.01)


def test_pd_plus_gravity_lyapunov_function_along_a_regulation_run():
    """V = qd^T B qd / 2 + e^T K_P e / 2 with an exact g_hat and a constant q_d. Held over a sample, the law's
    torque differs from the continuous one by K_P (q - q_k) + K_D (qd - qd_k): along a sample
    Vdot = -qd^T (K_D + F) qd + qd^T [K_P (q - q_k) + K_D (qd - qd_k)], and |q - q_k| <= T |qd|,
    |qd - qd_k| <= T |qdd|, so V_{k+1} - V_k is at most the remainder
    R_k = (T^2 / 2) sum_i |qd_i| (K_D,i |qdd_i| + K_P,i |qd_i|) (maxima over the sample's two ends), of order T^2
    beside the O(T) dissipation; V itself is rounded to about 1e-14 V(0). La Salle: the only rest is e = 0."""
    c = PDPlusGravityController()
    r = _regulation(c, P0, 3001)
    e = r.q_d - r.q
    V = 0.5 * np.einsum("ni,nij,nj->n", r.qd, inertia(r.q, P0), r.qd) + 0.5 * (e ** 2) @ c.K_P
    dV = np.diff(V)
    m = np.maximum(np.abs(r.qd[1:]), np.abs(r.qd[:-1]))
    a = np.maximum(np.abs(r.qdd[1:]), np.abs(r.qdd[:-1]))
    R = 0.5 * T ** 2 * (m * (c.K_D * a + c.K_P * m)).sum(axis=1)
    roundoff = 1e-14 * V[0]
    assert np.all(dV <= R + roundoff), (dV - R).max()
    assert (dV < 0).sum() > 0.9 * len(dV)
    assert V[-1] < 1e-12 * V[0] and np.abs(e[-1]).max() < 1e-6 * np.abs(E0).max()


@given(q=st.tuples(st.floats(-3, 3), st.floats(-3, 3), st.floats(0.05, 0.95), st.floats(-3, 3)),
       qd=st.tuples(*[st.floats(-1, 1)] * 4).filter(lambda v: np.linalg.norm(v) > 0.1),
       e=st.tuples(*[st.floats(-0.05, 0.05)] * 4))
def test_pd_plus_gravity_vdot_by_finite_differences(q, qd, e):
    """Vdot = -qd^T (K_D + F) qd along the continuous closed loop (exact g_hat, constant q_d = q + e): the
    derivative of V along the flow (qd, qdd) by central differences against the formula; it relies on
    Bdot - 2C being skew-symmetric. With h = 1e-6 the truncation is O(h^2) (about 1e-9 relative) and the
    rounding about 1e-16 V / h (V below 100 J here, |Vdot| above 0.8 W for ||qd|| > 0.1): both far below 1e-6."""
    q, qd, e = (np.array(v) for v in (q, qd, e))
    q_d = q + e
    c = PDPlusGravityController()

    def V(qq, vv):
        return 0.5 * vv @ inertia(qq) @ vv + 0.5 * (q_d - qq) @ (c.K_P * (q_d - qq))

    qdd = forward_dynamics(q, qd, c.K_P * (q_d - q) - c.K_D * qd + gravity(q))
    h = 1e-6
    fd = (V(q + h * qd, qd + h * qdd) - V(q - h * qd, qd - h * qdd)) / (2 * h)
    want = -qd @ ((c.K_D + P0.F) * qd)
    assert _largest.record("PD + g: Vdot by finite differences, relative", abs(fd - want) / abs(want)) < 1e-6


# --------------------------------------------------------------------------------------------------
# the unknown 5 kg payload at the end of the reference run
# --------------------------------------------------------------------------------------------------
def test_steady_state_errors_with_the_unknown_payload(classic_runs):
    c, r = classic_runs["pdg"]
    rest = _rest(r)
    e = (r.q_d - r.q)[rest]
    # PD + g: K_P e = g - g_hat, the quill alone: -m_L g0 / K_P3 (by hand: 49.05 / 20250 = 2.4222 mm)
    sag = -5.0 * G0 / c.K_P[2]
    assert sag == pytest.approx(-2.4222e-3, rel=1e-4)
    np.testing.assert_allclose(c.steady_state_error(P5), [0, 0, sag, 0], rtol=1e-14)
    assert _largest.record("PD + g sag at rest, relative", np.abs(e[:, 2] / sag - 1).max()) < 1e-9
    assert np.abs(e[:, [0, 1, 3]]).max() < 1e-12
    # computed torque: B_hat K_P e = g - g_hat, solved at the rest configuration ...
    c, r = classic_runs["ct"]
    e = (r.q_d - r.q)[_rest(r)]
    ss = c.steady_state_error(P5, r.q[-1])
    assert _largest.record("computed torque error at rest, relative", np.abs(e - ss).max() / abs(ss[2])) < 1e-9
    # ... by hand: B_hat y = [0, 0, -m_L g0, 0], y = K_P e
    B = inertia(r.q[-1], P0)
    np.testing.assert_allclose(ss, np.linalg.solve(B, [0, 0, -5.0 * G0, 0]) / c.K_P, rtol=1e-12)
    # ... within the rotor coupling B13 = B23 = k_r3 I_m3 of -m_L g0 / (B33_hat K_P3)
    approx = -5.0 * G0 / (B[2, 2] * c.K_P[2])
    coupling = np.linalg.inv(B)[2, 2] * B[2, 2] - 1
    assert ss[2] / approx - 1 == pytest.approx(coupling, rel=1e-9) and 0 < coupling < 1e-3


def test_both_track_the_path_with_the_payload(classic_runs):
    """The sag dominates both; computed torque, which also feeds the reference acceleration forward, tracks the
    orientation ten times better than PD + g, which has to err to accelerate the arm."""
    s = {name: control_summary(r) for name, (c, r) in classic_runs.items()}
    for name in s:
        assert 2.4e-3 < s[name]["final_position_error"] < 2.45e-3
        assert np.all(s[name]["peak_tau"] < np.asarray(TAU_MAX))
    assert s["ct"]["max_orientation_error"] < 0.2 * s["pdg"]["max_orientation_error"]
    assert s["ct"]["max_position_error"] < s["pdg"]["max_position_error"]


# --------------------------------------------------------------------------------------------------
# the interface, the plain-Python path, bad settings
# --------------------------------------------------------------------------------------------------
def test_interface(classic_runs):
    for name, (c, r) in classic_runs.items():
        assert r.controller == c.name and c.reference_kind == "joint"
        assert np.array_equal(replay_law(c, r)[0], r.tau)
        s = control_summary(r, c, repeats=1)
        assert s["controller"] == c.name and 0 < s["step_cost"] < 1e-4
        assert 0 < law_cost(c, r, repeats=1) < 1e-4
        assert np.array_equal(c.tau_max, np.asarray(TAU_MAX)) and c.max_error == 0.05
    c, r = classic_runs["ct"]
    # the recorded y is the commanded acceleration: y - qdd is the model error eta of the chapter
    assert set(c.signal_names) == {"y_1", "y_2", "y_3", "y_4"}
    assert abs(r.y_3[_rest(r)].mean() - c.K_P[2] * c.steady_state_error(P5, r.q[-1])[2]) < 1e-9
    pdg = PDPlusGravityController()
    np.testing.assert_allclose(pdg.K_P, OMEGA ** 2 * np.asarray(B_BAR), rtol=1e-15)
    np.testing.assert_allclose(pdg.K_D, 2 * OMEGA * np.asarray(B_BAR) - P0.F, rtol=1e-15)
    assert "PDPlusGravityController(K_P=" in repr(pdg) and "ComputedTorqueController(omega=" in repr(c)


def test_plain_python_path_matches_compiled(traj, jref):
    n = 300
    plain = np.array(plain_python(n, (
        "out = []\n"
        "for c in (PDPlusGravityController(), ComputedTorqueController()):\n"
        "    r = simulate(c, sub, p, joint_reference=jr)\n"
        "    out += np.r_[r.q.ravel(), r.tau.ravel()].tolist()\n"
        "print(json.dumps(out))\n")))
    sub, jr = first_samples(traj, jref, n)
    mine = []
    for c in (PDPlusGravityController(), ComputedTorqueController()):
        r = simulate(c, sub, P5, joint_reference=jr)
        mine += np.r_[r.q.ravel(), r.tau.ravel()].tolist()
    assert _largest.record("plain Python against compiled", np.abs(plain - np.array(mine)).max()) < 1e-8


@pytest.mark.parametrize("make, error, match", [
    (lambda: PDPlusGravityController(omega=0.0), ScaraError, r"omega must be positive definite: omega\[0\] = 0"),
    (lambda: PDPlusGravityController(omega=math.nan), ScaraError, r"omega must be finite"),
    (lambda: PDPlusGravityController(K_P=[1, 1, -1, 1]), ScaraError, r"K_P\[2\] = -1"),
    (lambda: PDPlusGravityController(K_D=[1, 1, 1]), ShapeError, r"K_D must be"),
    (lambda: PDPlusGravityController(B_bar=[1, 0, 1, 1]), ScaraError, r"B_bar\[1\] = 0"),
    (lambda: PDPlusGravityController(tau_max=[200, 200, 0, 50]), ScaraError, r"tau_max\[2\] = 0"),
    (lambda: PDPlusGravityController(model="plant"), ScaraError, r"ScaraParams"),
    (lambda: ComputedTorqueController(omega=-30.0), ScaraError, r"omega must be positive definite"),
    (lambda: ComputedTorqueController(zeta=0.0), ScaraError, r"zeta must be positive definite: zeta\[0\] = 0"),
    (lambda: ComputedTorqueController(zeta=[1, 1, math.nan, 1]), ScaraError, r"zeta must be finite"),
    (lambda: ComputedTorqueController(omega=np.ones((3, 3))), ShapeError, r"omega must be"),
    (lambda: ComputedTorqueController(K_P=math.inf), ScaraError, r"K_P must be finite"),
    (lambda: ComputedTorqueController(K_D=[60, 60, 0, 60]), ScaraError, r"K_D\[2\] = 0"),
    (lambda: ComputedTorqueController(dt=0.0), ScaraError, r"dt"),
    (lambda: ComputedTorqueController(omega=1e200), ScaraError, r"K_P = omega\^2 must be finite"),
    (lambda: ComputedTorqueController(omega=1500.0), UnstableError,
     r"K_P\[0\] = 2\.25e\+06, K_D\[0\] = 3000 make the sampled computed-torque loop unstable at dt = 0\.001 s"),
    (lambda: ComputedTorqueController(K_P=900.0, K_D=2500.0), UnstableError, r"K_D\[0\] = 2500"),
    (lambda: ComputedTorqueController(max_error=-1.0), ScaraError, r"max_error"),
])
def test_bad_settings_raise(make, error, match):
    with pytest.raises(error, match=match):
        make()


def test_steady_state_error_inputs():
    c = ComputedTorqueController()
    with pytest.raises(ShapeError):
        c.steady_state_error(P5, q=[0, 0, 0])
    with pytest.raises(ScaraError):
        c.steady_state_error(P5, q=[0, math.nan, 0.5, 0])
    with pytest.raises(ScaraError, match="ScaraParams"):
        c.steady_state_error("plant")
    assert np.all(c.steady_state_error(P0) == 0)


# --------------------------------------------------------------------------------------------------
# the live panel
# --------------------------------------------------------------------------------------------------
def test_live_panel_offers_both_laws(traj):
    from scara.plots._common import CONTROLLER_LABELS
    from scara.programs.control import SHOWN
    from scara.widgets import control_panel
    from scara.widgets.control import make_controller

    for key, cls in (("pd_plus_gravity", PDPlusGravityController), ("computed_torque", ComputedTorqueController)):
        c = make_controller(CONTROLLER_LABELS[key], 900, 60, 30, 20, 0.05, 1.0, 0.01, 8000, 50.0)
        assert isinstance(c, cls) and np.all(c.omega == 50.0)
    panel = control_panel(traj)
    for key in ("pd_plus_gravity", "computed_torque"):
        panel.controls["controller"].value = CONTROLLER_LABELS[key]
        assert panel.last_error is None
        assert not panel.controls["omega"].disabled and panel.controls["K_P"].disabled
        assert panel.state[f"{key}_shown"] == 1.0 and sum(panel.state[f] for f in SHOWN) == 1.0
        # the note: the quill's sag at rest against the law's own formula (e_z = m_L g0 / K_P3 here)
        assert panel.state["theory_mm"] == pytest.approx(1e3 * 5.0 * G0 / (30.0 ** 2 * 22.5), rel=1e-3)
        assert panel.state["steady_z_error_mm"] == pytest.approx(panel.state["theory_mm"], rel=1e-9)
    panel.controls["omega"].value = 1.0   # the sag m_L g0 / (B33 omega^2) passes max_error
    assert "max_error" in panel.last_error
