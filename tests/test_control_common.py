"""Tests of scara.control._common (chapter 6): what the three controllers share, on the 70 s reference with the
5 kg payload in the plant, unknown to every controller: the stated bounds, each compiled law against an
independent numpy implementation (replayed on the recorded closed loop), the measures (chattering, summary,
cost), the error cases, the plain-Python path, and the chapter's figures and live panel."""
import math

import numpy as np
import pytest

from scara import (
    AdaptiveController, OperationalSpaceController, RobustController, ScaraError, ShapeError, UnstableError,
    coriolis, gravity, inertia, jacobian, jacobian_dot, pose, simulate,
)
from scara.control import TAU_MAX, chattering, control_summary, law_cost, replay_law

from _control_shared import G0, P0, P5, first_samples, plain_python


# --------------------------------------------------------------------------------------------------
# the tracking targets of chapter 6
# --------------------------------------------------------------------------------------------------
@pytest.mark.parametrize("name", ["robust", "adaptive", "operational", "operational_noint"])
def test_torques_finite_and_within_the_stated_bounds(runs, name):
    c, r = runs[name]
    assert np.all(np.isfinite(r.tau))
    assert np.all(np.abs(r.tau) <= np.asarray(TAU_MAX))
    assert np.array_equal(c.tau_max, np.asarray(TAU_MAX))
    # the quill holds its own weight and the payload: about (m_l3 + m_L) g0
    assert np.abs(r.tau[:, 2]).max() > (P0.m_l3 + 5.0) * G0 * 0.95


# --------------------------------------------------------------------------------------------------
# each law against an independent numpy implementation (replayed on the recorded closed loop)
# --------------------------------------------------------------------------------------------------
def _numpy_robust(c, q, qd, ref):
    qt, qtd = ref[:4] - q, ref[4:8] - qd
    z = c.Q[4:, :4] @ qt + c.Q[4:, 4:] @ qtd
    nz = np.linalg.norm(z)
    w = c.rho * z / nz if nz >= c.epsilon else c.rho * z / c.epsilon
    y = ref[8:] + c.K_D * qtd + c.K_P * qt + w
    n_hat = np.diag(c.model.F) @ qd + gravity(q, c.model)
    return np.diag(c.B_hat) @ y + n_hat


def _numpy_adaptive(c, q, qd, ref, m_hat):
    """Y pi_hat written as the model with the estimated payload: B qdd_r + C qd_r + F qd_r + g (only m3
    adapts); the update m_hat_dot = K_pi^-1 (column m3 of Y)^T sigma with that column taken as dtau/dm_L."""
    qt, qtd = ref[:4] - q, ref[4:8] - qd
    qd_r = ref[4:8] + c.Lambda * qt
    qdd_r = ref[8:] + c.Lambda * qtd
    sigma = qd_r - qd

    def model_tau(m):
        p = c.model.with_payload(m)
        return inertia(q, p) @ qdd_r + coriolis(q, qd, p) @ qd_r + np.diag(p.F) @ qd_r + gravity(q, p)

    tau = model_tau(m_hat) + c.K_D * sigma
    col = model_tau(1.0) - model_tau(0.0)  # linear in the payload: exact column of Y
    return tau, m_hat + 1e-3 * c.K_pi_inv[0] * col @ sigma


def _numpy_operational(c, q, qd, ref, s):
    J = jacobian(q, c.model)
    xt = ref[:4] - pose(q, c.model)
    xtd = ref[4:8] - J @ qd
    y = np.linalg.solve(J, ref[8:] + c.K_D * xtd + c.K_P * xt + c.K_I * s - jacobian_dot(q, qd, c.model) @ qd)
    tau = inertia(q, c.model) @ y + coriolis(q, qd, c.model) @ qd + np.diag(c.model.F) @ qd + gravity(q, c.model)
    return tau, s + 1e-3 * xt


@pytest.mark.parametrize("name", ["robust", "adaptive", "operational", "operational_noint"])
def test_compiled_law_matches_numpy(runs, name):
    c, r = runs[name]
    tau, sig, _ = replay_law(c, r, 3000)
    assert np.array_equal(tau, r.tau[:3000])  # the replay is the run's own law
    idx = list(range(0, 40)) + list(range(40, 3000, 97))
    state = 0.0 if name == "adaptive" else np.zeros(4)
    k_prev = -1
    worst = 0.0
    for k in range(3000):
        q, qd, ref = r.q[k], r.qd[k], r.reference[k]
        if name == "robust":
            if k not in idx:
                continue
            t_np = _numpy_robust(c, q, qd, ref)
        elif name == "adaptive":
            t_np, state_next = _numpy_adaptive(c, q, qd, ref, state)
            assert sig[k, 0] == pytest.approx(state, abs=1e-9)
            state = state_next
        else:
            t_np, state_next = _numpy_operational(c, q, qd, ref, state)
            np.testing.assert_allclose(sig[k], c.K_I * state, atol=1e-9)
            state = state_next
        worst = max(worst, np.abs(t_np - tau[k]).max())
        k_prev = k
    assert k_prev > 0
    assert worst < 1e-9 * max(1.0, np.abs(r.tau).max())


# --------------------------------------------------------------------------------------------------
# measures
# --------------------------------------------------------------------------------------------------
def test_chattering_measure_closed_form():
    class R:  # a torque that alternates +-A every sample: second difference 4 A on that joint
        tau = np.zeros((101, 4))
    R.tau[:, 2] = 3.0 * (-1.0) ** np.arange(101)
    assert chattering(R) == pytest.approx(12.0)
    R.tau = np.outer(np.linspace(0, 1, 101), [1, 2, 3, 4])  # a ramp: zero second difference
    assert chattering(R) == pytest.approx(0.0, abs=1e-12)


def test_summary_and_cost(runs):
    c, r = runs["operational"]
    s = control_summary(r, c, repeats=2)
    assert set(s) >= {"max_position_error", "rms_position_error", "max_orientation_error", "final_position_error",
                      "steady_z_error", "peak_tau", "chattering", "step_cost"}
    assert 0 < s["rms_position_error"] <= s["max_position_error"]
    assert np.array_equal(s["peak_tau"], np.abs(r.tau).max(axis=0))
    assert 0 < s["step_cost"] < 1e-4
    assert 0 < law_cost(c, r, repeats=1) < 1e-4
    assert math.isnan(control_summary(r)["step_cost"])
    with pytest.raises(ScaraError, match="settle"):
        control_summary(r, settle=100.0)


# --------------------------------------------------------------------------------------------------
# failures
# --------------------------------------------------------------------------------------------------
@pytest.mark.parametrize("make, match", [
    (lambda: RobustController(K_P=0.0), "K_P"),
    (lambda: RobustController(K_D=[60, 60, -1, 60]), r"K_D\[2\] = -1"),
    (lambda: RobustController(rho=0.0), "rho"),
    (lambda: RobustController(epsilon=0.0), "epsilon"),
    (lambda: RobustController(epsilon=-0.01), "epsilon"),
    (lambda: RobustController(Lambda=0.0), "Lambda"),
    (lambda: RobustController(B_hat=[1, 1, 0, 1]), "B_hat"),
    (lambda: AdaptiveController(Lambda=-1.0), "Lambda"),
    (lambda: AdaptiveController(K_D=0.0), "K_D"),
    (lambda: AdaptiveController(K_pi=0.0), "K_pi"),
    (lambda: AdaptiveController(K_pi={"m3": -1.0}), "K_pi"),
    (lambda: AdaptiveController(K_pi={"payload": 1.0}), "payload"),
    (lambda: AdaptiveController(K_pi=np.full(13, np.inf)), "nothing would adapt"),
    (lambda: OperationalSpaceController(K_P=-5.0), "K_P"),
    (lambda: OperationalSpaceController(K_I=0.0), "K_I"),
    (lambda: OperationalSpaceController(tau_max=[200, 200, 0, 50]), "tau_max"),
    (lambda: OperationalSpaceController(max_error=0.0), "max_error"),
])
def test_bad_settings_raise(make, match):
    with pytest.raises(ScaraError, match=match):
        make()


def test_unstable_settings_raise():
    with pytest.raises(UnstableError, match="Lambda"):
        RobustController(K_D=20.0, Lambda=30.0)
    with pytest.raises(UnstableError, match="Routh"):
        OperationalSpaceController(K_P=100.0, K_D=10.0, K_I=2000.0)
    OperationalSpaceController(integral=False, K_I=0.0)  # K_I unused without the integral
    with pytest.raises(ShapeError):
        RobustController(K_P=[1, 2, 3])


def test_torque_beyond_its_bound_stops_the_run(traj, jref):
    c = AdaptiveController(tau_max=(200.0, 200.0, 90.0, 50.0))  # the quill needs about 98 N to hold itself
    with pytest.raises(UnstableError, match=r"t = 0\.0000 s.*code 2"):
        simulate(c, traj, P5, joint_reference=jref)
    with pytest.raises(UnstableError, match=r"t = 0\.0000 s.*tau_max"):
        c.run(traj, P5, joint_reference=jref)


def test_divergence_stops_with_time_and_cause(traj):
    """Past the sampling limit (K_D dt = 2.5 > 2 on the derivative loop) the operational loop grows by a factor
    of order K_D dt - 1 per sample: the run stops within a fraction of a second, at the torque bound, or with
    the bound lifted at the engine's state limit, naming the time; the plain engine call reports the same time."""
    with pytest.raises(UnstableError, match=r"diverged at t = \d+\.\d+ s.*tau_max"):
        OperationalSpaceController(K_P=1e5, K_D=2500.0, K_I=1e5).run(traj, P5)
    c = OperationalSpaceController(K_P=1e5, K_D=2500.0, K_I=1e5, tau_max=1e12)
    with pytest.raises(UnstableError, match=r"diverged at t = (\d+\.\d+) s.*(exceeded|max_error)") as info:
        c.run(traj, P5)
    t_stop = float(info.value.args[0].split("t = ")[1].split(" s")[0])
    assert 0 < t_stop < 0.5
    with pytest.raises(UnstableError, match=f"t = {t_stop:.4f} s"):
        simulate(c, traj, P5)


def test_error_beyond_its_bound_stops_the_run(traj):
    """Without the integral the quill sags by 1.8 mm: with max_error = 1 mm the run stops when the sag passes
    1 mm, in the first tenth of a second, naming the bound."""
    c = OperationalSpaceController(integral=False, max_error=1e-3)
    with pytest.raises(UnstableError, match=r"diverged at t = (\d+\.\d+) s.*max_error = 0\.001") as info:
        c.run(traj, P5)
    t_stop = float(info.value.args[0].split("t = ")[1].split(" s")[0])
    assert 0 < t_stop < 0.1
    full = simulate(OperationalSpaceController(integral=False), traj, P5)
    k = int(round(t_stop / 1e-3))
    assert np.abs(full.e[k]).max() > 1e-3 >= np.abs(full.e[:k]).max()


# --------------------------------------------------------------------------------------------------
# the plain-Python path
# --------------------------------------------------------------------------------------------------
def test_plain_python_path_matches_compiled(traj, jref):
    n = 300
    out = plain_python(n, (
        "out = []\n"
        "for c in (RobustController(), AdaptiveController(), OperationalSpaceController()):\n"
        "    r = simulate(c, sub, p, joint_reference=jr if c.reference_kind == 'joint' else None)\n"
        "    out.append(np.r_[r.q.ravel(), r.tau.ravel()].tolist())\n"
        "print(json.dumps(out))\n"))
    sub, jr = first_samples(traj, jref, n)
    for plain, c in zip(out, (RobustController(), AdaptiveController(), OperationalSpaceController())):
        r = simulate(c, sub, P5, joint_reference=jr if c.reference_kind == "joint" else None)
        ref = np.r_[r.q.ravel(), r.tau.ravel()]
        # round-off only (FMA contraction in compiled code), amplified by loop gains up to ~1e4
        assert np.abs(np.array(plain) - ref).max() < 1e-8, c.name


# --------------------------------------------------------------------------------------------------
# the chapter's figures and live panel
# --------------------------------------------------------------------------------------------------
def _titled(fig):
    lay = fig.to_dict()["layout"]
    assert lay.get("title", {}).get("text"), "figure without a title"
    axes = [k for k in lay if k.startswith(("xaxis", "yaxis")) and not lay[k].get("overlaying")]
    titled = [k for k in axes if lay[k].get("title", {}).get("text")]
    return lay, axes, titled


def test_figures_have_titles_units_and_legends(runs):
    from scara.plots import (error_norm_figure, joint_motion_figure, operational_error_figure,
                             payload_estimate_figure, payload_sweep_figure, robust_term_figure,
                             steady_state_figure, torque_figure)

    all_runs = [r for _, r in runs.values()]
    figs = [joint_motion_figure(all_runs), operational_error_figure(all_runs), error_norm_figure(all_runs),
            torque_figure(all_runs), payload_estimate_figure(runs["adaptive"][1], 5.0),
            robust_term_figure(runs["robust"][1], 0.05),
            steady_state_figure(runs["operational"][1], runs["operational_noint"][1], 1.8e-3, 2.18),
            payload_sweep_figure([0, 5, 10], {"robust": [1e-5, 1e-4, 2e-4], "adaptive": [1e-7] * 3})]
    for fig in figs:
        lay, axes, titled = _titled(fig)
        assert any(k.startswith("xaxis") for k in titled) and any(k.startswith("yaxis") for k in titled)
        assert all("(" in lay[k]["title"]["text"] or "‖" in lay[k]["title"]["text"] for k in titled)
        assert all(tr.name for tr in fig.data)
        for tr in fig.data:  # thinned for the page
            assert tr.x is None or len(tr.x) <= 2100
    with pytest.raises(ScaraError, match="payload_estimate"):
        payload_estimate_figure(runs["robust"][1], 5.0)
    with pytest.raises(ScaraError, match="values"):
        payload_sweep_figure([0, 5], {"robust": [1.0]})


def test_live_panel_re_simulates_and_reports_errors(traj):
    from scara.widgets import control_panel
    from scara.widgets.control import make_controller

    panel = control_panel(traj)
    assert panel.last_error is None
    for name in ("adaptive (Slotine-Li)", "operational ID + integral", "operational ID, no integral", "robust"):
        panel.controls["controller"].value = name
        assert panel.last_error is None, name
    assert panel.controls["K_pi"].disabled and not panel.controls["epsilon"].disabled
    panel.controls["Lambda"].value = 100.0  # above K_D = 60
    assert "Lambda" in panel.last_error and "K_D" in panel.last_error
    panel.controls["Lambda"].value = 30.0
    assert panel.last_error is None
    panel.controls["controller"].value = "adaptive (Slotine-Li)"
    panel.controls["K_pi"].value = 1e-5  # adaptation far too fast: the run stops, with the time and the cause
    assert "diverged at t =" in panel.last_error
    c = make_controller("operational ID, no integral", 900, 60, 30, 20, 0.05, 1.0, 0.01, 8000)
    assert isinstance(c, OperationalSpaceController) and not c.integral
    c = make_controller("adaptive (Slotine-Li)", 900, 60, 30, 20, 0.05, 2.0, 0.01, 8000)
    assert np.allclose(c.K_D, [1200, 600, 2000, 120]) and c.K_pi_inv[0] == 100.0


def test_counts_and_options_of_the_measures_are_checked_before_any_work(runs):
    c, r = runs["operational"]
    with pytest.raises(ScaraError, match=r"repeats = 1001 .*outside the allowed range 1 <= repeats <= 1000"):
        law_cost(c, r, repeats=1001)
    for bad in (1.5, "3", True, 0):
        with pytest.raises(ScaraError, match=r"repeats = .*(must be a whole number|outside the allowed range "
                                             r"1 <= repeats)"):
            law_cost(c, r, repeats=bad)
    with pytest.raises(ScaraError, match=r"repeats = 5000 .*outside the allowed range 1 <= repeats <= 1000"):
        control_summary(r, c, repeats=5000)
    with pytest.raises(ScaraError, match=rf"n = {len(r.t) + 1} .*outside the allowed range 1 <= n <= {len(r.t)}"):
        replay_law(c, r, n=len(r.t) + 1)
    for name in ("settle", "rest"):
        for bad in (math.nan, math.inf, -1.0):
            with pytest.raises(ScaraError, match=name):
                control_summary(r, **{name: bad})


def test_measures_refuse_a_result_or_controller_they_cannot_read(runs):
    from types import SimpleNamespace

    c, r = runs["operational"]
    bad_tau = r.tau.copy()
    bad_tau[5, 1] = np.nan
    with pytest.raises(ScaraError, match=r"result\.tau\[\(5, 1\)\] = nan is not finite"):
        chattering(SimpleNamespace(tau=bad_tau))
    with pytest.raises(ScaraError, match=r"result\.tau\[\(5, 1\)\] = nan is not finite"):
        control_summary(SimpleNamespace(t=r.t, e=r.e, tau=bad_tau))
    with pytest.raises(ScaraError, match=r"has no attribute 'reference'"):
        replay_law(c, SimpleNamespace(t=r.t, q=r.q, qd=r.qd, dt=r.dt))
    with pytest.raises(ScaraError, match=r"controller = 'abc' is not a controller of scara.simulate's interface"):
        law_cost("abc", r, repeats=1)
    with pytest.raises(ScaraError, match=r"one length"):
        replay_law(c, SimpleNamespace(t=r.t, q=r.q[:10], qd=r.qd, reference=r.reference, dt=r.dt))
