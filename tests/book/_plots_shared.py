"""Helpers shared by the tests of several scara.plots modules (tests/book/test_plots_*.py): the book's robot and a
configuration, plot-data readers, the forward kinematics written out independently of scara, a quiet call for the
widget panels, the message of a refused call, the sample counts every run figure refuses, and the figures that
more than one test file checks, built once per session (no test modifies them; the builders that take the
reference ``ref``, the session fixture of tests/conftest.py, build once per reference)."""
from __future__ import annotations

import contextlib
import functools
import io
import json
import math
from pathlib import Path

import numpy as np
import pytest

import scara
from scara import ScaraError, ScaraParams, ikine, jacobian, plots
from scara._clik import SEED_K, clik, transpose_stability
from scara.dynamics import torque_breakdown
from scara.plots.clik import gain_slider_figure, gain_steps_figure, relaxed_figure
from scara.plots.control import CONTROLLER_LABELS, figure_slider, saturation_figure

ROOT = Path(__file__).resolve().parents[2]
P = ScaraParams()
P5 = P.with_payload(5.0)
Q = np.array([0.3, -1.2, 0.4, 0.1])


def xy(trace):
    """The x and y data of a plotly trace as float arrays, ``None`` (a break in the line) as NaN."""
    return np.array([np.nan if v is None else v for v in trace.x], float), \
        np.array([np.nan if v is None else v for v in trace.y], float)


def closed_form_position(q):
    """Independent of scara: equation (eq-kin-xe) of chapter 1 written out."""
    t1, t2, d3 = q[0], q[1], q[2]
    return np.array([P.a1 * math.cos(t1) + P.a2 * math.cos(t1 + t2),
                     -(P.a1 * math.sin(t1) + P.a2 * math.sin(t1 + t2)), P.d0 - d3])


def quiet(fn, *a, **kw):
    """``fn(*a, **kw)`` with what it prints swallowed (a panel prints its figure and its messages)."""
    with contextlib.redirect_stdout(io.StringIO()):
        return fn(*a, **kw)


def refusal(build, *args, **kwargs) -> str:
    """The message of the :class:`ScaraError` that ``build(*args, **kwargs)`` raises (the test fails without one)."""
    with pytest.raises(ScaraError) as info:
        build(*args, **kwargs)
    return str(info.value)


def titles_by_state(fig) -> dict:
    """Label of each slider step or dropdown entry -> the title it sets."""
    controls = ([s for sl in fig.layout.sliders for s in sl.steps]
                + [b for m in fig.layout.updatemenus for b in m.buttons])
    return {c.label: c.args[1]["title.text"] for c in controls}


#: sample counts every figure of the CLIK, dynamics, control and verification runs refuses, and what the message names
SAMPLE_COUNTS = [
    (10**6, ("= 1000000", "<= 10000")),
    (1, ("= 1", "2 <= ")),
    (500.5, ("= 500.5", "whole number")),
    ("500", ("= '500'", "whole number")),
]


def check_sample_count_refused(build, args, count, value, names):
    """The count is checked first: the (here absent) runs are never looked at."""
    message = refusal(getattr(plots, build), *args, **{count: value})
    assert message.startswith(f"{count} = ")
    for text in names:
        assert text in message


@functools.cache
def gain_figure(ref):
    """The gain slider of chapter 4 on the reference ``ref`` at 0.5, 1 and 4.5 times the seed gains."""
    return gain_slider_figure(ref, scales=[0.5, 1.0, 4.5])


@functools.cache
def uniform_gains(ref):
    """The transpose with K = k I around its limit on the reference, k_lim = 2 / (T sigma_max(J_A)^2)."""
    st = transpose_stability(ref, np.ones(4))
    sigma_max = max(np.linalg.svd(jacobian(q), compute_uv=False).max() for q in ikine(ref.x[::5], elbow=-1))
    k_lim = 2.0 / ref.dt / sigma_max**2
    ks = {"below": 0.97 * k_lim, "above": 1.03 * k_lim}
    fig = gain_steps_figure(ref, {name: k * np.ones(4) for name, k in ks.items()}, "transpose", prefix="k: ")
    return st, k_lim, ks, fig


@functools.cache
def relaxed_runs(ref):
    """The pseudo-inverse runs on ``ref`` relaxing x, y and z, the inverse run and their figure."""
    runs = [clik(ref, "pseudoinverse", relaxed=c) for c in ("x", "y", "z")]
    inv = clik(ref, "inverse")
    return runs, inv, relaxed_figure(runs, inv)


@functools.cache
def run_figures() -> dict:
    """Every figure of chapters 4, 5, 6 and of the verification appendix, built as the chapters build them."""
    tr = scara.reference_trajectory()
    runs = {m: scara.clik(tr, m) for m in ("inverse", "transpose", "pseudoinverse")}
    runs["second_order"] = ref = scara.clik2(tr)
    inv = runs["inverse"]
    stab = scara.transpose_stability(tr)
    near = scara.plan_path([[-0.2, 0.002, 0.5], [0.2, 0.002, 0.5]], durations=[3.0], total=3.5)
    below = scara.clik(tr, "transpose", 0.98 * stab.scale_limit * np.asarray(SEED_K))
    figs = {
        "clik_joints": plots.clik_joints_figure(runs),
        "clik_convergence": plots.convergence_figure(
            scara.clik(tr, "inverse", q0=inv.q[0] + [0.01, -0.015, 0.01, 0.02]), horizon=0.03),
        "clik_errors": plots.clik_error_figure({m: runs[m] for m in ("inverse", "transpose")}),
        "clik_components": plots.error_components_figure(runs),
        "clik_stability": plots.transpose_stability_figure(stab, {"2 % below the limit": below}),
        "clik_manipulability": plots.manipulability_figure([inv, runs["pseudoinverse"]]),
        "clik_drift": plots.drift_figure(runs["pseudoinverse"], inv),
        "clik_damping": plots.damping_figure({"exact": scara.clik(near, "inverse"),
                                              "damped": scara.clik(near, "inverse", damping=0.05)}),
        "clik_second_order": plots.second_order_figure(ref),
        "clik_gain": plots.gain_slider_figure(tr, scales=[0.5, 1.0, 2.0]),
    }
    parts = torque_breakdown(ref.q, ref.qd, ref.qdd, P5)
    by_mass = {float(m): scara.inverse_dynamics(ref.q, ref.qd, ref.qdd, scara.ScaraParams().with_payload(m))
               for m in (0, 5, 10)}
    drop = scara.simulate(scara.TorqueController(), plant=P5, duration=0.2,
                          q0=np.array([ref.q[0, 0], ref.q[0, 1], 0.0, 0.0]))
    figs.update({
        "dynamics_share": plots.torque_share_figure(parts),
        "dynamics_terms": plots.torque_terms_figure(tr.t, parts, target=300),
        "dynamics_payload": plots.payload_slider_figure(tr.t, by_mass, target=200, active=1),
        "dynamics_energy": plots.energy_figure(drop.t, drop.energy()),
    })
    robust, adaptive = scara.RobustController(), scara.AdaptiveController()
    op, op_noint = scara.OperationalSpaceController(), scara.OperationalSpaceController(integral=False)
    indep = scara.IndependentJointController()
    rr = scara.simulate(robust, tr, P5, joint_reference=ref)
    ar = scara.simulate(adaptive, tr, P5, joint_reference=ref)
    orr, onr = scara.simulate(op, tr, P5), scara.simulate(op_noint, tr, P5)
    ir = scara.simulate(indep, tr, P5, joint_reference=ref)
    tight = (200.0, 200.0, 155.0, 50.0)
    saturated = {"ideal actuator": ir,
                 "155 N, anti-windup": scara.simulate(scara.IndependentJointController(tau_max=tight), tr, P5,
                                                      joint_reference=ref),
                 "155 N, no anti-windup": scara.simulate(
                     scara.IndependentJointController(tau_max=tight, anti_windup=False), tr, P5, joint_reference=ref)}
    layers = {eps: scara.simulate(scara.RobustController(epsilon=eps), tr, P5, joint_reference=ref)
              for eps in (0.01, 0.05)}
    b33 = scara.inertia(ref.q[0])[2, 2]
    labelled = {CONTROLLER_LABELS[c.name]: r for c, r in ((robust, rr), (adaptive, ar), (op, orr), (op_noint, onr),
                                                         (indep, ir))}
    names = list(labelled)
    # five runs are more than one phone-width legend can name: a dropdown shows the centralised laws, or the
    # joint-space ones with the independent-joint PID; the torque differences leave out the no-integral law
    groups = {"centralised laws": names[:4], "joint space": [names[4], names[0], names[1]]}
    four = {n: labelled[n] for n in names if n != CONTROLLER_LABELS["operational_noint"]}
    ideal = scara.inverse_dynamics(ref.q, ref.qd, ref.qdd, P5)
    slow = {k: scara.simulate(scara.AdaptiveController(K_pi=k), tr, P5, joint_reference=ref) for k in (0.01, 1.0)}
    pdg, ct = scara.PDPlusGravityController(), scara.ComputedTorqueController()
    classic = {CONTROLLER_LABELS[c.name]: scara.simulate(c, tr, P5, joint_reference=ref) for c in (pdg, ct)}
    classic_rest = {CONTROLLER_LABELS["pd_plus_gravity"]: pdg.steady_state_error(P5),
                    CONTROLLER_LABELS["computed_torque"]: ct.steady_state_error(P5)}
    figs.update({
        "control_robust_term": plots.robust_term_figure(rr, robust.epsilon),
        "control_boundary_layer": plots.boundary_layer_slider_figure(layers, 0.016, window=(40.0, 40.15)),
        "control_estimate": plots.payload_estimate_figure(ar, true_mass=5.0),
        "control_steady_state": plots.steady_state_figure(orr, onr, 5.0 * P5.g0 / (b33 * op.K_P[2]),
                                                          5.0 * P5.g0 / b33),
        "control_error_norm": plots.error_norm_figure(labelled, groups=groups),
        "control_classic": plots.joint_error_figure(classic, classic_rest),
        "control_joint_motion": plots.joint_motion_figure(labelled),
        "control_operational_error": plots.operational_error_figure(labelled),
        "control_torques": plots.torque_figure({n: labelled[n] for n in names[:4]}),
        "control_torque_differences": plots.torque_figure(four, reference=ideal, window=(3.95, 4.25),
                                                          title="Torque minus the torque the arm needs<br>"
                                                                "around the corner at t = 4 s"),
        "control_saturation": saturation_figure(saturated, limit=155.0),
        "control_boundary_layer_notes": plots.boundary_layer_slider_figure(
            layers, 0.016, notes={0.01: "sag at rest 0.0123 mm", 0.05: "sag at rest 0.0042 mm"}),
        "control_estimate_slider": figure_slider(
            {f"{k:g}": plots.payload_estimate_figure(r, 5.0, title=f"Adaptive control, K_π = {k:g}")
             for k, r in slow.items()}, "K_π = "),
        "control_payload_sweep": plots.payload_sweep_figure(
            np.array([0.0, 5.0, 10.0]), {n: [1e-4, 2e-4, 3e-4] for n in ("robust", "adaptive", "operational")}),
    })
    results = json.loads((ROOT / "benchmarks" / "results.json").read_text())
    figs["appendix_speed"] = plots.speed_figure(results)
    n = len(tr.t)
    figs["appendix_rotor_coupling"] = plots.rotor_coupling_figure(tr.t, np.full((n, 4), 1e-3), np.ones((n, 4)))
    return figs
