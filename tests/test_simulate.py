"""The closed-loop engine (scara.simulate): energy conservation and balance, agreement with an independent
integrator, zero-order hold, the PD-plus-gravity steady state against theory, the controller interface with
memory, substeps, errors, and the plain-Python path."""
import json
import os
import subprocess
import sys

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from scara import (
    Controller, PDGravityController, ScaraError, ScaraParams, ShapeError, TorqueController, UnstableError,
    control_law, forward_dynamics, ikine_reference, joint_setpoint, pose, reference_trajectory, simulate,
)
from scara.dynamics import DP_A1, DP_A2, DP_D0, gravity_kernel
from scara.kinematics import jacobian_kernel, pose_kernel
from scara._simulate import closed_loop_kernel  # noqa: F401  (the compiled loop must import)

from _largest import record

P0 = ScaraParams()
P5 = ScaraParams().with_payload(5.0)
# free-motion tests let the quill fall for seconds: a plant with a 1 km stroke (the same dynamics; the stroke only
# decides where the engine stops a run) keeps d3 inside its range
LONG_STROKE = P5.replace(d3_max=1e3)
NOFRICTION = LONG_STROKE.replace(F_m=(0.0, 0.0, 0.0, 0.0))
Q0 = np.array([0.2, -1.0, 0.3, 0.1])


@pytest.fixture(scope="module")
def scenario():
    traj = reference_trajectory()
    return traj, simulate(PDGravityController(), traj, P5)


# --------------------------------------------------------------------------------------------------
# energy
# --------------------------------------------------------------------------------------------------
def test_energy_is_conserved_without_friction_and_torque():
    """RK4 at 1 ms for 10 s of free motion (no friction, no torque, gravity on: the quill falls freely while
    the arm spins). The total energy may only drift by the integrator's error: RK4's local error is O(h^5), so the
    drift must fall ~16x when h halves, and stay below 1e-12 of the largest kinetic energy at h = 1 ms."""
    drift = {}
    for dt in (1e-3, 2e-3):
        r = simulate(TorqueController(), plant=NOFRICTION, duration=10.0, dt=dt, q0=Q0, qd0=[3.0, -6.0, 0.5, 6.0])
        en = r.energy()
        drift[dt] = np.abs(en["total"] - en["total"][0]).max()
        scale = en["kinetic"].max()
        assert np.abs(en["friction_work"]).max() == 0.0 and np.abs(en["input_work"]).max() == 0.0
    record("energy drift (J), 10 s, 1 ms", drift[1e-3])
    record("energy drift relative", drift[1e-3] / scale)
    assert drift[1e-3] / scale < 1e-12
    ratio = drift[2e-3] / drift[1e-3]
    record("drift ratio h=2ms / h=1ms", ratio)
    assert 8 < ratio < 32


def test_friction_work_balances_the_energy_lost():
    """Released with friction and no torque: E(t) - E(0) = -int qd^T F qd dt. Simpson's rule on the 1 ms samples
    of a smooth motion is O(h^4): the balance must close to 1e-12 of the work dissipated."""
    r = simulate(TorqueController(), plant=LONG_STROKE, duration=10.0, q0=Q0, qd0=[3.0, -6.0, 0.5, 6.0])
    en = r.energy()
    assert np.all(np.diff(en["friction_work"]) >= 0)
    err = np.abs(en["balance"]).max() / en["friction_work"][-1]
    record("friction balance (relative), free motion", err)
    assert err < 1e-12


def test_energy_balance_in_closed_loop(scenario):
    """Under zero-order hold the input work over a sample is exactly tau_k^T (q_{k+1} - q_k); with the friction
    work by Simpson's rule (qdd jumps at every sample, so the rule is only O(h^3) per interval there) the balance
    must close to 1e-6 of the energy exchanged along the 70 s reference run."""
    _, r = scenario
    en = r.energy()
    scale = en["friction_work"][-1] + abs(en["input_work"]).max()
    err = np.abs(en["balance"]).max() / scale
    record("closed-loop energy balance (relative)", err)
    assert err < 1e-6


# --------------------------------------------------------------------------------------------------
# against an independent integrator
# --------------------------------------------------------------------------------------------------
def _ivp(q0, qd0, tau, t_end, p, t_eval=None):
    def f(_t, y):
        return np.r_[y[4:], forward_dynamics(y[:4], y[4:], tau, p)]

    return solve_ivp(f, (0.0, t_end), np.r_[q0, qd0], method="DOP853", rtol=1e-13, atol=1e-13, t_eval=t_eval)


def test_free_motion_matches_scipy():
    qd0 = np.array([2.0, -3.0, 0.2, 4.0])
    r = simulate(TorqueController(), plant=LONG_STROKE, duration=2.0, q0=Q0, qd0=qd0)
    sol = _ivp(Q0, qd0, np.zeros(4), 2.0, P5, t_eval=r.t[::100])
    err = max(np.abs(sol.y[:4].T - r.q[::100]).max(), np.abs(sol.y[4:].T - r.qd[::100]).max())
    record("free motion vs DOP853", err)
    assert err < 1e-9  # RK4 at 1 ms: global error ~1e-11 here; DOP853 at rtol 1e-12


def test_zero_order_hold_matches_scipy_per_interval():
    """The PD+gravity loop at 1 ms for 0.2 s from a 0.3 rad step: the same discrete law, the plant integrated by
    DOP853 (rtol 1e-13) over each interval with the torque held. The difference is RK4's truncation: it must fall
    ~16x from 1 to 2 substeps (fourth order), and stays below 1e-10 rad in q, 1e-8 rad/s in qd at 1 substep."""
    q_d = np.array([0.5, -1.3, 0.45, 0.6])
    c = PDGravityController()
    g_hat = np.array([0.0, 0.0, -P0.m3 * P0.g0, 0.0])
    worst = {}
    for sub in (1, 2):
        r = simulate(c, plant=P5, joint_reference=joint_setpoint(q_d, 0.2), q0=Q0, substeps=sub)
        q, qd = Q0.copy(), np.zeros(4)
        wq = wv = wt = 0.0
        for k in range(len(r.t) - 1):
            tau = c.K_P * (q_d - q) + c.K_D * (0.0 - qd) + g_hat
            wt = max(wt, np.abs(tau - r.tau[k]).max())
            sol = _ivp(q, qd, tau, 1e-3, P5)
            q, qd = sol.y[:4, -1], sol.y[4:, -1]
            wq = max(wq, np.abs(q - r.q[k + 1]).max())
            wv = max(wv, np.abs(qd - r.qd[k + 1]).max())
        worst[sub] = (wq, wv, wt)
    record("ZOH loop vs DOP853: max |dq| (rad)", worst[1][0])
    record("ZOH loop vs DOP853: max |dqd| (rad/s)", worst[1][1])
    assert worst[1][0] < 1e-10 and worst[1][1] < 1e-8 and worst[1][2] < 1e-5
    assert 8 < worst[1][1] / worst[2][1] < 32


def test_qdd_is_the_plant_acceleration(scenario):
    _, r = scenario
    for k in (0, 1234, 50000, len(r.t) - 1):
        assert np.allclose(r.qdd[k], forward_dynamics(r.q[k], r.qd[k], r.tau[k], P5), rtol=1e-13, atol=1e-12)


def test_substeps_make_no_difference(scenario):
    traj, r1 = scenario
    r4 = simulate(PDGravityController(), traj, P5, substeps=4)
    err = np.abs(r4.q - r1.q).max()
    record("substeps 4 vs 1 (max |dq|)", err)
    assert err < 1e-10
    assert np.abs(r4.tau - r1.tau).max() < 1e-6


# --------------------------------------------------------------------------------------------------
# PD plus gravity: theory
# --------------------------------------------------------------------------------------------------
def test_pd_gravity_steady_state_error_matches_theory():
    """Held at a set point with the 5 kg payload unknown to the controller, the quill settles where
    K_P3 e3 = g3 - g_hat3 = -m_L g0, i.e. e3 = q_d3 - q3 = -m_L g0 / K_P3; the other joints settle exactly."""
    q_d = np.array([0.5, -1.3, 0.45, 0.6])
    c = PDGravityController()
    r = simulate(c, plant=P5, joint_reference=joint_setpoint(q_d, 6.0), q0=Q0)
    e = r.joint_error[-1]
    theory = c.steady_state_error(P5)
    assert theory[2] == pytest.approx(-5.0 * 9.81 / 10000.0, rel=1e-15)
    err = np.abs(e - theory).max()
    record("PD+g steady state vs theory (m)", err)
    assert err < 1e-9
    assert r.e[-1, 2] == pytest.approx(5.0 * 9.81 / 10000.0, abs=1e-9)  # e_z = z_d - z > 0: the quill sags
    # with the model right (the controller knows the payload) the error vanishes
    exact = PDGravityController(model=P5)
    r2 = simulate(exact, plant=P5, joint_reference=joint_setpoint(q_d, 6.0), q0=Q0)
    assert np.abs(r2.joint_error[-1]).max() < 1e-9
    assert r.gravity_compensation[-1] == pytest.approx(-P0.m3 * P0.g0)


def test_reference_scenario_steady_state(scenario):
    """Along the reference scenario of chapter 3 (book/03_trajectory.ipynb), the last 2 s at rest show the same
    vertical error."""
    _, r = scenario
    s = r.summary()
    assert s["steady_state_error_components"][2] == pytest.approx(5.0 * 9.81 / 10000.0, abs=1e-8)
    assert np.abs(s["steady_state_error_components"][[0, 1, 3]]).max() < 1e-8
    assert r.t[-1] == pytest.approx(70.0) and r.q.shape == r.qd.shape == r.qdd.shape == r.tau.shape == (70001, 4)
    assert np.allclose(r.x, pose(r.q, P5)) and np.allclose(r.e, r.x_d - r.x)
    assert r.reference_kind == "joint" and r.q_d.shape == (70001, 4)


# --------------------------------------------------------------------------------------------------
# the interface: a controller with memory written in the test
# --------------------------------------------------------------------------------------------------
@control_law
def _pid_law(k, t, dt, q, qd, ref, gains, model, state, work, signals, tau):
    g = work[0]
    gravity_kernel(q, model, g)
    for i in range(4):
        e = ref[i] - q[i]
        state[i] += dt * e
        tau[i] = gains[i] * e + gains[4 + i] * (ref[4 + i] - qd[i]) + gains[8 + i] * state[i] + g[i]
        signals[i] = state[i]
    return 0


class _PID(Controller):
    law = staticmethod(_pid_law)
    name = "pid_test"
    reference_kind = "joint"
    signal_names = ("i1", "i2", "i3", "i4")
    work_rows = 1

    def gains_array(self):
        return np.r_[PDGravityController().gains_array(), np.full(4, 20000.0), ]

    def initial_state(self):
        return np.zeros(4)


def test_controller_with_memory_removes_the_payload_error():
    """Integral action (state carried by the engine) removes the sag; the integrator settles at
    K_I3 int e3 = m_L g0, i.e. the integral of the error equals -m_L g0 / K_I3."""
    q_d = np.array([0.5, -1.3, 0.45, 0.6])
    r = simulate(_PID(), plant=P5, joint_reference=joint_setpoint(q_d, 15.0), q0=Q0)
    assert abs(r.joint_error[-1, 2]) < 1e-8
    assert r.i3[-1] == pytest.approx(-5.0 * 9.81 / 20000.0, rel=1e-6)
    assert set(r.signals) == {"i1", "i2", "i3", "i4"}
    with pytest.raises(AttributeError, match="signals"):
        r.nonexistent  # noqa: B018


@control_law
def _task_pd_law(k, t, dt, q, qd, ref, gains, model, state, work, signals, tau):
    """Operational-space PD plus gravity: tau = J^T (K_P (x_d - x) - K_D J qd) + g_hat(q)."""
    J = work[0:4]
    x = work[4]
    g = work[5]
    v = work[6]
    pose_kernel(q, model[DP_A1], model[DP_A2], model[DP_D0], x)
    jacobian_kernel(q, model[DP_A1], model[DP_A2], J)
    gravity_kernel(q, model, g)
    for i in range(4):
        s = 0.0
        for j in range(4):
            s += J[i, j] * qd[j]
        v[i] = gains[i] * (ref[i] - x[i]) + gains[4 + i] * (ref[4 + i] - s)
    for j in range(4):
        s = 0.0
        for i in range(4):
            s += J[i, j] * v[i]
        tau[j] = s + g[j]
    for i in range(4):
        signals[i] = ref[i] - x[i]
    return 0


class _TaskPD(Controller):
    law = staticmethod(_task_pd_law)
    name = "task_pd_test"
    reference_kind = "operational"
    signal_names = ("ex", "ey", "ez", "ephi")
    work_rows = 7

    def gains_array(self):
        return np.array([2e4, 2e4, 1e4, 600.0, 2e3, 2e3, 1e3, 60.0])


def test_operational_controller_gets_operational_references(scenario):
    """An operational-space law receives [x_d, xd_d, xdd_d] rows from the trajectory and starts at the
    trajectory's start configuration; its own error signal equals the engine's e. At rest at the end the
    vertical sag is m_L g0 / K_P,z (J's z row is [0, 0, -1, 0])."""
    traj, _ = scenario
    r = simulate(_TaskPD(), traj, P5)
    assert r.reference_kind == "operational" and r.q_d is None
    assert np.array_equal(r.reference[:, :4], traj.x)
    assert np.allclose(r.q[0], traj.q0, atol=1e-12)
    assert np.allclose(np.column_stack([r.ex, r.ey, r.ez, r.ephi]), r.e, rtol=0, atol=1e-12)
    assert r.summary()["steady_state_error_components"][2] == pytest.approx(5.0 * 9.81 / 1e4, abs=1e-8)
    with pytest.raises(ScaraError, match="joint reference"):
        r.joint_error  # noqa: B018


@control_law
def _failing_law(k, t, dt, q, qd, ref, gains, model, state, work, signals, tau):
    for i in range(4):
        tau[i] = 0.0
    return 7 if k == 250 else 0


class _Failing(Controller):
    law = staticmethod(_failing_law)
    name = "failing"
    reference_kind = "none"


def test_failures_are_reported_with_time_and_cause():
    with pytest.raises(UnstableError, match=r"t = 0\.2500 s .*code 7"):
        simulate(_Failing(), duration=1.0, q0=Q0)
    wild = PDGravityController(K_P=(1e9, 1e9, 1e9, 1e9), K_D=(0, 0, 0, 0))  # far past the 1 ms stability limit
    with pytest.raises(UnstableError, match="diverged at t ="):
        simulate(wild, plant=P5, joint_reference=joint_setpoint(Q0 + 0.1, 2.0), q0=Q0)


def test_bad_inputs_are_refused():
    c = PDGravityController()
    ref = joint_setpoint(Q0, 0.1)
    with pytest.raises(ScaraError, match="substeps"):
        simulate(c, plant=P5, joint_reference=ref, substeps=0)
    with pytest.raises(ShapeError, match="joint_reference"):
        simulate(c, plant=P5, joint_reference=ref[:, :8])
    with pytest.raises(ScaraError, match="needs traj or joint_reference"):
        simulate(c, plant=P5)
    with pytest.raises(ScaraError, match="K_P .* >= 0"):
        PDGravityController(K_P=(-1, 1, 1, 1))
    with pytest.raises(ScaraError, match="no compiled law"):
        simulate(Controller.__new__(type("X", (), {"law": None})), duration=1.0, q0=Q0)
    traj = reference_trajectory()
    with pytest.raises(ScaraError, match="differs from the trajectory"):
        simulate(c, traj, P5, dt=2e-3)


def test_joint_reference_forms_agree():
    """A (N, 12) array, a (q, qd, qdd) tuple and an object with q, qd, qdd give the same run; the closed-form
    ikine reference of the scenario is a valid reference too."""
    ref = joint_setpoint(Q0 + 0.05, 0.3)
    c = PDGravityController()
    a = simulate(c, plant=P5, joint_reference=ref, q0=Q0)
    b = simulate(c, plant=P5, joint_reference=(ref[:, :4], ref[:, 4:8], ref[:, 8:]), q0=Q0)
    obj = type("R", (), {"q": ref[:, :4], "qd": ref[:, 4:8], "qdd": ref[:, 8:]})()
    d = simulate(c, plant=P5, joint_reference=obj, q0=Q0)
    assert np.array_equal(a.q, b.q) and np.array_equal(a.q, d.q)


def test_ikine_reference_is_consistent(scenario):
    traj, _ = scenario
    ref = ikine_reference(traj)
    assert np.abs(pose(ref[::700, :4]) - traj.x[::700]).max() < 1e-12
    # velocities by finite differences of the positions
    fd = np.gradient(ref[:, :4], traj.dt, axis=0)
    assert np.abs(fd[1:-1] - ref[1:-1, 4:8]).max() < 1e-4


# --------------------------------------------------------------------------------------------------
# the plain-Python path
# --------------------------------------------------------------------------------------------------
def test_plain_python_engine_gives_the_same_numbers():
    code = ("import json, numpy as np, scara._compile as c; from scara import *; assert not c.COMPILED;"
            "p=ScaraParams().with_payload(5.0); q0=np.array([0.2,-1.0,0.3,0.1]);"
            "r=simulate(PDGravityController(), plant=p, joint_reference=joint_setpoint(q0+0.1, 0.05), q0=q0);"
            "print(json.dumps(np.r_[r.q.ravel(), r.qd.ravel(), r.tau.ravel(), r.qdd.ravel()].tolist()))")
    env = dict(os.environ, SCARA_NO_NUMBA="1")
    out = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, check=True).stdout
    r = simulate(PDGravityController(), plant=P5, joint_reference=joint_setpoint(Q0 + 0.1, 0.05), q0=Q0)
    ref = np.r_[r.q.ravel(), r.qd.ravel(), r.tau.ravel(), r.qdd.ravel()]
    err = np.abs(np.array(json.loads(out)) - ref).max()
    record("plain Python engine vs compiled", err)
    assert err < 1e-9  # FMA contraction in compiled code: round-off, amplified by the loop gain K_P ~ 1e4


# --------------------------------------------------------------------------------------------------
# the chapter's figures and live panel (smoke tests: they build, carry titles and units, and the panel
# reports a bad setting instead of raising)
# --------------------------------------------------------------------------------------------------
def test_chapter_figures_and_panel(scenario):
    from scara import torque_breakdown
    from scara.plots import (energy_figure, inertia_figure, payload_slider_figure, payload_torque_figure,
                             torque_share_figure, torque_terms_figure)
    from scara.widgets import dynamics_panel

    traj, r = scenario
    q, qd, qdd = r.reference[:, :4], r.reference[:, 4:8], r.reference[:, 8:12]
    parts = torque_breakdown(q, qd, qdd, P5)
    free = simulate(TorqueController(), plant=P5, duration=0.2, q0=Q0)
    figs = [torque_share_figure(parts), torque_terms_figure(r.t, parts, target=200),
            payload_torque_figure(r.t, {"a": r.tau, "b": 2 * r.tau}, target=200),
            payload_slider_figure(r.t, {0.0: r.tau, 5.0: 2 * r.tau}, target=100),
            energy_figure(free.t, free.energy()), inertia_figure(Q0, P5, "B")]
    for fig in figs:
        assert fig.layout.title.text
        assert any(ax.title.text for ax in fig.select_xaxes())
        assert any(tr.name for tr in fig.data if tr.type != "heatmap")
    slider_fig = figs[3]
    assert len(slider_fig.layout.sliders[0].steps) == 2
    assert len(slider_fig.data[0].x) <= 101 + 1
    panel = dynamics_panel()
    assert panel.last_error is None
    panel.controls["theta2"].value = 30.0
    assert panel.last_error is None
    rows, _notes = panel.declaration.summary(panel.compute(dict(payload=5.0, theta1=0.0, theta2=-90.0, d3=0.5,
                                                                  theta4=0.0, K_P3=1e4)))
    assert "4.905 mm" in str(rows)  # the sag m_L g0 / K_P3 listed in the panel
    with pytest.raises(ScaraError):  # the panel shows this message in place of the plot
        panel.compute(dict(payload=-1.0, theta1=0.0, theta2=-90.0, d3=0.5, theta4=0.0, K_P3=1e4))


# --- the plant's reduced solve (joints 3 and 4 eliminated) against the general forward dynamics ---------
from hypothesis import given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402


@settings(max_examples=300)
@given(seed=st.integers(0, 2**32 - 1))
def test_plant_acceleration_equals_forward_dynamics_for_random_robots(seed):
    """The engine's closed-form elimination of the constant, diagonal quill/wrist block of B gives the same
    acceleration as the general 4x4 solve of scara.forward_dynamics, for random robots and states."""
    import math

    from scara import ScaraParams, forward_dynamics
    from scara.dynamics import dynamic_array
    from scara._simulate import _plant_acceleration, _plant_constants

    rng = np.random.default_rng(seed)
    u = lambda lo, hi, n=None: rng.uniform(lo, hi, n)  # noqa: E731
    p = ScaraParams(a1=u(0.2, 1.0), a2=u(0.2, 1.0), l1=u(0.05, 0.5), l2=u(0.05, 0.5), m_l1=u(1, 40),
                    m_l2=u(1, 40), m_l3=u(1, 20), I_l1=u(0.1, 8), I_l2=u(0.1, 8), I_l4=u(0.1, 2),
                    k_r=tuple(u(1, 60, 4)), I_m=tuple(u(1e-4, 0.02, 4)), F_m=tuple(u(0, 0.02, 4)), m_L=u(0, 10))
    q = np.r_[u(-math.pi, math.pi, 2), u(0, 1), u(-math.pi, math.pi)]
    qd = u(-3, 3, 4)
    tau = u(-50, 50, 4)
    pc = _plant_constants(dynamic_array(p))
    qdd, code = _plant_acceleration(math.cos(q[1]), math.sin(q[1]), tuple(qd), tuple(tau), pc)
    assert code == 0
    ref = forward_dynamics(q, qd, tau, p)
    assert np.allclose(qdd, ref, rtol=1e-10, atol=1e-10 * np.abs(ref).max())


# --------------------------------------------------------------------------------------------------
# the inputs a run is checked against: time base, counts, the start state and the quill's stroke
# --------------------------------------------------------------------------------------------------
class _Traj:
    """A trajectory of N samples at rest at the pose of Q0, with the sample times ``t`` and optionally ``dt``."""

    def __init__(self, t, dt=None):
        self.t = np.asarray(t, dtype=float)
        self.x = np.tile(pose(Q0, P0), (len(self.t), 1))
        self.xd = np.zeros_like(self.x)
        self.xdd = np.zeros_like(self.x)
        if dt is not None:
            self.dt = dt


def test_reference_sampled_at_another_period_is_refused():
    """traj.t every 10 ms with no dt attribute (the run's dt defaults to 1 ms), or with dt = 1e-3 that its t
    contradicts, or not uniform: the message names both spacings."""
    c = PDGravityController()
    t10 = np.arange(51) * 0.01
    with pytest.raises(ScaraError, match=r"traj\.t is sampled every 0\.01 s but the run's dt = 0\.001 s"):
        simulate(c, _Traj(t10), P0, joint_reference=joint_setpoint(Q0, 0.5, dt=0.01))
    with pytest.raises(ScaraError, match=r"traj\.t is sampled every 0\.01 s but the run's dt = 0\.001 s"):
        simulate(c, _Traj(t10, dt=1e-3), P0, joint_reference=joint_setpoint(Q0, 0.5, dt=0.01))
    uneven = np.r_[0.0, np.cumsum(np.r_[np.full(25, 1e-3), np.full(25, 2e-3)])]
    with pytest.raises(ScaraError, match=r"traj\.t is not uniform: its spacing ranges from 0\.001 s to 0\.002 s"):
        simulate(c, _Traj(uneven), P0, joint_reference=joint_setpoint(Q0, 0.05))
    # the same reference with the matching dt runs
    r = simulate(c, _Traj(t10), P0, dt=0.01, joint_reference=joint_setpoint(Q0, 0.5, dt=0.01))
    assert np.allclose(r.t, t10)


def test_duration_must_be_a_whole_number_of_samples():
    with pytest.raises(ScaraError, match=r"duration = 1 s is not a whole number of samples of dt = 0\.3 s.*"
                                         r"nearest valid durations are 0\.9 s and 1\.2 s"):
        joint_setpoint(Q0, 1.0, dt=0.3)
    with pytest.raises(ScaraError, match=r"duration = 0\.0105 s .* 0\.01 s and 0\.011 s"):
        simulate(TorqueController(), duration=0.0105, q0=Q0)
    assert len(joint_setpoint(Q0, 0.9, dt=0.3)) == 4


def test_counts_are_bounded_before_any_work():
    c = PDGravityController()
    ref = joint_setpoint(Q0, 0.1)
    with pytest.raises(ScaraError, match=r"substeps = 1001 .*outside the allowed range 1 <= substeps <= 1000"):
        simulate(c, plant=P5, joint_reference=ref, substeps=1001)
    for bad in (1.5, "3", True, 2.0):
        with pytest.raises(ScaraError, match=r"substeps = .* must be a whole number \(an int\) of .*between 1 and "
                                             r"1000"):
            simulate(c, plant=P5, joint_reference=ref, substeps=bad)
    with pytest.raises(ScaraError, match=r"duration = 1e\+07 s at dt = 0\.001 s asks for 1e\+10 samples, past the "
                                         r"limit of 5000000 samples"):
        simulate(TorqueController(), duration=1e7, q0=Q0)
    with pytest.raises(ScaraError, match=r"duration = 1e\+300 s .* past the limit"):
        joint_setpoint(Q0, 1e300)
    with pytest.raises(ScaraError, match="limit"):
        simulate(c, plant=P5, joint_reference=ref, limit=float("nan"))


def test_start_outside_the_quill_stroke_is_refused():
    from scara import UnreachableError

    for d3 in (-0.01, 1.2):
        q0 = Q0.copy()
        q0[2] = d3
        with pytest.raises(UnreachableError, match=rf"q0: joint 3 \(d3\) = {d3:g} m is outside the quill's stroke "
                                                   r"\[0, 1\] m"):
            simulate(TorqueController(), duration=0.1, q0=q0)


def test_falling_quill_stops_the_run_at_the_end_of_its_stroke():
    """Open loop, motors off: from d3 = 0.3 m at 0.5 m/s down (and the 5 kg payload) the quill falls and passes
    d3_max = 1 m after about 0.45 s; the run stops there, naming joint 3, the time and the value."""
    with pytest.raises(UnstableError, match=r"t = 0\.4\d+ s \(sample 4\d\d\): joint 3 \(d3\) = 1\.00\d* m .* past "
                                            r"d3_max of the quill's stroke \[0, 1\] m; the engine models no end stop"):
        simulate(TorqueController(), plant=P5, duration=2.0, q0=Q0, qd0=[0.0, 0.0, 0.5, 0.0])
    # the same fall, pushed up instead: past d3_min
    with pytest.raises(UnstableError, match=r"joint 3 \(d3\) = -0\.\d+ m .* past d3_min"):
        simulate(TorqueController(tau=(0.0, 0.0, -1000.0, 0.0)), plant=P5, duration=2.0, q0=Q0)


def test_overloaded_quill_stops_the_run():
    """A 1e6 kg payload under PD + gravity compensation (which believes in no payload): K_P3 = 1e4 N/m cannot hold
    it (the sag would be 981 m), the quill runs out of its stroke and the run stops with the time and the value."""
    with pytest.raises(UnstableError, match=r"the run of pd_gravity left the joint range at t = .* joint 3 \(d3\) = "
                                            r"1\.\d+ m .* past d3_max"):
        simulate(PDGravityController(), plant=P0.with_payload(1e6), joint_reference=joint_setpoint(Q0, 2.0), q0=Q0)


def test_result_options_must_be_finite_and_positive(scenario):
    _, r = scenario
    for bad in (float("nan"), float("inf"), 0.0, -1.0):
        with pytest.raises(ScaraError, match=r"window"):
            r.summary(window=bad)


def test_overflowing_steady_state_error_is_refused():
    # the heaviest payload the parameters accept, on a vanishing quill gain: the error overflows
    with pytest.raises(ScaraError, match=r"m_L = 1\.e\+09 gives a non-finite steady-state error"):
        PDGravityController(K_P=(1e4, 4e3, 1e-300, 600.0)).steady_state_error(P0.with_payload(1e9))


def test_a_trajectory_without_its_fields_is_refused():
    from types import SimpleNamespace

    x = np.tile(pose(Q0, P0), (11, 1))
    with pytest.raises(ScaraError, match=r"traj = SimpleNamespace has no attribute 'xd': a trajectory needs t, x, xd, "
                                         r"xdd"):
        ikine_reference(SimpleNamespace(x=x))
    with pytest.raises(ScaraError, match=r"has no attribute 'x'"):
        simulate(PDGravityController(), SimpleNamespace(t=np.arange(11) * 1e-3), P0,
                 joint_reference=joint_setpoint(Q0, 0.01))


# --------------------------------------------------------------------------------------------------
# the contract enforced: a law stays inside the arrays its layouts declare, and the process never dies
# --------------------------------------------------------------------------------------------------
from scara._compile import ArrayLayout  # noqa: E402
from scara.dynamics import inverse_dynamics_kernel  # noqa: E402


@control_law
def _undeclared_rows_law(k, t, dt, q, qd, ref, gains, model, state, work, signals, tau):
    for r in range(6):  # six rows, the controller declares two
        for i in range(4):
            work[r, i] = 1.0
    return 0


@control_law
def _kernel_overflow_law(k, t, dt, q, qd, ref, gains, model, state, work, signals, tau):
    inverse_dynamics_kernel(q, qd, ref[8:12], model, work, tau)  # the kernel's B takes four rows of work
    return 0


@control_law
def _past_signals_law(k, t, dt, q, qd, ref, gains, model, state, work, signals, tau):
    signals[2] = 1.0
    return 0


@control_law
def _past_gains_law(k, t, dt, q, qd, ref, gains, model, state, work, signals, tau):
    for i in range(4):
        tau[i] = gains[4 + i]
    return 0


@control_law
def _kernel_reads_past_gains_law(k, t, dt, q, qd, ref, gains, model, state, work, signals, tau):
    from scara.control._common import torque_code  # noqa: PLC0415

    return torque_code(tau, gains, 8)


def _open_loop(law, work_rows=0, signals=(), gains=np.zeros(4)):
    class _C(Controller):
        name = "user_law"
        reference_kind = "none"
        work_layout = ArrayLayout(("rows", work_rows), width=4) if work_rows else ArrayLayout(width=4)
        signals_layout = ArrayLayout.of_names(signals)

        def gains_array(self):
            return gains

    _C.law = staticmethod(law)
    return _C()


@pytest.mark.parametrize("law, rows, signals, match", [
    (_undeclared_rows_law, 2, (), r"indexes work\[.*2.*past its declared size: work holds 2 rows of 4"),
    # compiled, the kernel's writes land in the guard rows; in plain Python its own slicing is checked
    (_kernel_overflow_law, 2, (), r"(writes work\[2\]|indexes work\[0:4\] on axis 0 of size 2), past its declared "
                                  r"size: work holds 2 rows of 4"),
    (_past_signals_law, 0, ("a", "b"), r"indexes signals\[2\].*past its declared size: signals holds 2 entries"),
    (_past_gains_law, 0, (), r"indexes gains\[4\].*past its declared size: gains holds 4 entries"),
    (_kernel_reads_past_gains_law, 0, (), r"(reads past gains|indexes gains\[8\].*, past its declared size): gains "
                                          r"holds 4 entries"),
])
def test_a_law_outside_its_arrays_is_refused_before_the_compiled_run(law, rows, signals, match):
    """Without bounds checks a compiled law writing rows it did not declare corrupts the heap (the process dies
    with ``free(): invalid pointer``); the trial call on guarded copies refuses it with the array and its size."""
    c = _open_loop(law, rows, signals)
    with pytest.raises(ScaraError, match=match):
        simulate(c, duration=0.01, q0=Q0)
    # the controller's own arrays were never touched: a fresh run is refused the same way
    with pytest.raises(ScaraError, match=match):
        simulate(c, duration=0.01, q0=Q0)


def test_arrays_of_another_size_than_declared_are_refused():
    class _Short(PDGravityController):
        def gains_array(self):
            return super().gains_array()[:6]

    with pytest.raises(ScaraError, match=r"gains array of controller pd_gravity holds 6 numbers, but its gains_layout "
                                         r"declares 8"):
        simulate(_Short(), plant=P5, joint_reference=joint_setpoint(Q0, 0.01), q0=Q0)
    from scara import AdaptiveController

    class _NoState(AdaptiveController):
        def initial_state(self):
            return np.zeros(3)

    with pytest.raises(ScaraError, match=r"state array of controller adaptive holds 3 numbers, but its state_layout "
                                         r"declares 13"):
        simulate(_NoState(), plant=P5, joint_reference=joint_setpoint(Q0, 0.01), q0=Q0)


@control_law
def _nan_signal_law(k, t, dt, q, qd, ref, gains, model, state, work, signals, tau):
    signals[0] = 0.0
    signals[1] = np.nan if k == 30 else 1.0
    return 0


@control_law
def _inf_torque_law(k, t, dt, q, qd, ref, gains, model, state, work, signals, tau):
    tau[2] = np.inf if k == 40 else 0.0
    return 0


def test_non_finite_signals_and_torques_stop_the_run_naming_time_signal_and_value():
    with pytest.raises(UnstableError, match=r"diverged at t = 0\.0300 s \(sample 30\): the controller's law returned "
                                            r"the signal 'b' = nan, which is not finite"):
        simulate(_open_loop(_nan_signal_law, signals=("a", "b")), duration=0.1, q0=Q0)
    with pytest.raises(UnstableError, match=r"diverged at t = 0\.0400 s \(sample 40\): the controller's law returned "
                                            r"the torque tau_3 = inf, which is not finite"):
        simulate(_open_loop(_inf_torque_law), duration=0.1, q0=Q0)


def test_helpers_given_another_kind_of_run_name_what_they_need():
    from scara import AdaptiveController, OperationalSpaceController, RobustController
    from scara.control import control_summary, replay_law

    pd = simulate(PDGravityController(), plant=P5, joint_reference=joint_setpoint(Q0, 0.05), q0=Q0)
    with pytest.raises(ScaraError, match=r"final_estimate needs a run whose law keeps a state of 13 numbers; the run "
                                         r"of 'pd_gravity' kept 0 numbers"):
        AdaptiveController.final_estimate(pd)
    with pytest.raises(ScaraError, match=r"uncertainty needs a run that records the signals \['w_1', 'w_2', 'w_3', "
                                         r"'w_4'\]; the run of 'pd_gravity' records \['gravity_compensation'\]"):
        RobustController().uncertainty(pd)
    with pytest.raises(ScaraError, match=r"no attribute or signal 'payload_estimate'.*'pd_gravity'"):
        pd.payload_estimate  # noqa: B018
    assert not hasattr(pd, "payload_estimate")  # still an AttributeError for getattr and hasattr
    with pytest.raises(ScaraError, match=r"reads a 'operational' reference, but the run of pd_gravity recorded a "
                                         r"'joint' one"):
        replay_law(OperationalSpaceController(), pd)
    with pytest.raises(ScaraError, match=r"result is a run of 'pd_gravity', controller = 'robust'"):
        control_summary(pd, RobustController(), repeats=1)


def test_design_sweeps_are_bounded_or_compiled():
    """The sweeps over configurations run in one compiled loop (70,001 configurations in well under a second, the
    same matrices as one call of ``inertia`` each); the optimiser, which evaluates them thousands of times, is
    bounded."""
    import time

    from scara import inertia
    from scara.control import design_inertia_estimate, inertia_uncertainty, joint_inertia_spread

    q = np.tile(Q0, (70_001, 1))
    q[:, 1] += np.linspace(-1.0, 1.0, len(q))
    t0 = time.perf_counter()
    inertia_uncertainty((8.6, 6.0, 22.5, 1.4), q)
    joint_inertia_spread(q)
    assert time.perf_counter() - t0 < 20.0
    sub = q[::7000]
    Bh = np.diag([8.6, 6.0, 22.5, 1.4])
    expected = max(np.linalg.norm(np.eye(4) - np.linalg.solve(inertia(qk, P0.with_payload(m)), Bh), 2)
                   for m in (0.0, 10.0) for qk in sub)
    assert inertia_uncertainty((8.6, 6.0, 22.5, 1.4), sub) == pytest.approx(expected, rel=1e-13)
    with pytest.raises(ScaraError, match=r"len\(q\) \* len\(payloads\) = 140002 inertia matrices is outside the "
                                         r"allowed range 1 <= len\(q\) \* len\(payloads\) <= 5000"):
        design_inertia_estimate(q)


def test_the_result_shares_no_memory_with_the_callers_arrays():
    ref = joint_setpoint(Q0, 0.05)
    r = simulate(PDGravityController(), plant=P5, joint_reference=ref, q0=Q0)
    assert not np.shares_memory(r.reference, ref) and not np.shares_memory(r.q_d, ref)
    assert np.array_equal(r.reference, ref)
    traj = reference_trajectory()
    from scara import OperationalSpaceController

    short = type("T", (), dict(t=traj.t[:50], x=traj.x[:50], xd=traj.xd[:50], xdd=traj.xdd[:50], dt=traj.dt))()
    r = simulate(OperationalSpaceController(), short, P5)
    assert not np.shares_memory(r.x_d, traj.x) and np.array_equal(r.x_d, traj.x[:50])


def test_an_empty_reference_is_refused():
    with pytest.raises(ShapeError, match=r"the reference holds 0 samples: a run needs at least one"):
        simulate(PDGravityController(), joint_reference=np.zeros((0, 12)), q0=Q0)
