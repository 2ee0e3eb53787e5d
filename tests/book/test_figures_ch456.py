"""Every figure of chapters 4, 5, 6 and of the verification appendix follows the book's reading rules
(``_figure_rules``): a height for a laptop screen, titles that fit a phone-width page, a legend with room
reserved for it as it wraps, an axis title with a unit on every axis in use. The figures are built as the
chapters build them."""
from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

import scara
from scara import plots
from scara._clik import SEED_K
from scara.dynamics import torque_breakdown
from scara.plots.control import CONTROLLER_LABELS, CONTROLLER_DASHES, figure_slider, saturation_figure

from _figure_rules import check_axis_titles_with_units, check_reads_on_a_laptop_and_a_phone

ROOT = Path(__file__).resolve().parents[2]
P5 = scara.ScaraParams().with_payload(5.0)
#: stacked panels sharing one time axis (three or four of them) may be taller than the default 560 px; 780 px
#: still fits a laptop screen with the browser's bars
TALL = {"control_joint_motion": 780, "control_torques": 780, "control_torque_differences": 780,
        "control_operational_error": 780, "control_boundary_layer": 780, "control_boundary_layer_notes": 780,
        "control_robust_term": 780, "control_steady_state": 780, "control_saturation": 780,
        "control_estimate_slider": 780}


@pytest.fixture(scope="module")
def figures():
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
    figs.update({
        "control_robust_term": plots.robust_term_figure(rr, robust.epsilon),
        "control_boundary_layer": plots.boundary_layer_slider_figure(layers, 0.016, window=(40.0, 40.15)),
        "control_estimate": plots.payload_estimate_figure(ar, true_mass=5.0),
        "control_steady_state": plots.steady_state_figure(orr, onr, 5.0 * P5.g0 / (b33 * op.K_P[2]),
                                                          5.0 * P5.g0 / b33),
        "control_error_norm": plots.error_norm_figure(labelled, groups=groups),
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


def _broken(figures, check, **per_figure):
    out = []
    for name, fig in figures.items():
        try:
            check(name, fig, **{k: f(name) for k, f in per_figure.items()})
        except AssertionError as exc:
            out.append(str(exc))
    return out


def test_every_figure_reads_on_a_laptop_and_a_phone(figures):
    # the speed bars are labelled on their axis (one bar per implementation): no legend needed
    broken = _broken(figures, check_reads_on_a_laptop_and_a_phone, max_height=lambda n: TALL.get(n, 560),
                     legend=lambda n: n != "appendix_speed")
    assert not broken, "\n".join(broken)


def test_every_axis_has_a_title_with_a_unit(figures):
    broken = _broken(figures, check_axis_titles_with_units)
    assert not broken, "\n".join(broken)


def test_each_method_and_controller_keeps_its_colour_and_dash(figures):
    """One palette per method across the book, and a dash style per controller, so curves stay apart in
    greyscale."""
    errors = figures["clik_errors"]
    inv = [t for t in errors.data if t.name and "inverse" in t.name and "pseudo" not in t.name]
    tra = [t for t in errors.data if t.name and "transpose" in t.name]
    assert inv and tra and {t.line.color for t in inv} == {plots.PALETTE["inverse"]}
    assert {t.line.color for t in tra} == {plots.PALETTE["transpose"]}
    assert (inv[0].line.dash or "solid") != (tra[0].line.dash or "solid")
    norm = figures["control_error_norm"]
    for key, label in CONTROLLER_LABELS.items():
        traces = [t for t in norm.data if t.name == label]
        if traces:
            assert traces[0].line.color == plots.PALETTE[key], key
            assert (traces[0].line.dash or "solid") == CONTROLLER_DASHES[key], key
    style = {t.name: ((t.line.dash or "solid"), t.line.color) for t in norm.data
             if t.name in CONTROLLER_LABELS.values()}
    assert len(style) == 5
    assert len({d for d, _ in style.values()}) == len({c for _, c in style.values()}) == 5
    # each dropdown entry shows its own group, and every run of the group once
    for button in norm.layout.updatemenus[0].buttons:
        shown = [t.name for t, v in zip(norm.data, button.args[0]["visible"]) if v]
        assert len(shown) == len(set(shown)) >= 3


def test_torque_differences_tell_the_controllers_apart(figures):
    """The torques of the controllers coincide at the scale of the torques (a few tenths of a N m against
    the 147 N on the quill); the differences from the torque the arm needs, around one corner at full sampling,
    draw each controller as its own curve: distinct colour and dash, and curves that are not on top of each other
    (the adaptive law's stays near zero, the others' reach a tenth of a N m)."""
    fig = figures["control_torque_differences"]
    panels = {}
    for tr in fig.data:
        panels.setdefault(tr.yaxis or "y", []).append(tr)
    assert len(panels) == 4
    for axis, traces in panels.items():
        assert len(traces) == 4
        assert len({(t.line.color, t.line.dash) for t in traces}) == 4
        t0 = np.asarray(traces[0].x)
        assert t0.min() >= 3.95 - 1e-6 and t0.max() <= 4.25 + 1e-6 and len(t0) == 301  # every sample of the window
        peaks = {t.name: float(np.abs(np.asarray(t.y)).max()) for t in traces}
        assert peaks["adaptive (Slotine-Li)"] < 0.1 * max(peaks.values()), (axis, peaks)
    assert fig.layout.yaxis.title.text == "τ1 − τ1_d (N m)" and fig.layout.yaxis3.title.text == "f3 − f3_d (N)"
    with pytest.raises(scara.ScaraError, match=r"reference has shape \(3, 4\)"):
        plots.torque_figure(fig_runs_for_refusal(), reference=np.zeros((3, 4)))


def fig_runs_for_refusal():
    from types import SimpleNamespace as NS

    n = 10
    return {"a": NS(t=np.arange(n) * 1e-3, tau=np.zeros((n, 4)), e=np.zeros((n, 4)), controller="robust")}


def test_saturation_figure_and_the_figure_slider(figures):
    sat = figures["control_saturation"]
    assert [t.name for t in sat.data if t.showlegend is not False][:3] == [
        "ideal actuator", "155 N, anti-windup", "155 N, no anti-windup"]
    bound = [t for t in sat.data if t.name and t.name.startswith("bound")]
    assert len(bound) == 1 and list(bound[0].y) == [-155.0, -155.0]  # the quill pushes up: only -155 N is near
    assert len({(t.line.color, t.line.dash) for t in sat.data[:9]}) == 3
    sl = figures["control_estimate_slider"]
    steps = sl.layout.sliders[0].steps
    assert [s.label for s in steps] == ["0.01", "1"]
    half = len(sl.data) // 2
    assert steps[1].args[0]["visible"] == [i >= half for i in range(len(sl.data))]
    assert "K_π = 1" in steps[1].args[1]["title.text"]
    notes = figures["control_boundary_layer_notes"].layout.sliders[0].steps
    assert notes[1].args[1]["title.text"].endswith("<br>sag at rest 0.0042 mm")
    with pytest.raises(scara.ScaraError, match=r"notes name widths without a run: \[0\.3\]"):
        plots.boundary_layer_slider_figure({0.05: None}, 0.016, notes={0.3: "x"})
    with pytest.raises(scara.ScaraError, match="carries no integral_action_3"):
        saturation_figure({"robust": fig_runs_for_refusal()["a"]})
    with pytest.raises(scara.ScaraError, match=r"len\(runs\) = 9"):
        saturation_figure({str(k): None for k in range(9)})
    with pytest.raises(scara.ScaraError, match="figures must be a non-empty dict"):
        figure_slider({}, "x")
    with pytest.raises(scara.ScaraError, match="plotly Figure"):
        figure_slider({"a": 1}, "x")


@pytest.mark.parametrize("build, args, count", [
    ("clik_joints_figure", (None,), "points"), ("clik_error_figure", (None,), "points"),
    ("error_components_figure", (None,), "points"), ("manipulability_figure", (None,), "points"),
    ("drift_figure", (None,), "points"), ("damping_figure", ({},), "points"),
    ("second_order_figure", (None,), "points"), ("gain_slider_figure", (None,), "points"),
    ("joint_motion_figure", (None,), "points"), ("operational_error_figure", (None,), "points"),
    ("error_norm_figure", (None,), "points"), ("torque_figure", (None,), "points"),
    ("payload_estimate_figure", (None, 5.0), "points"), ("robust_term_figure", (None, 0.05), "points"),
    ("tuning_figure", (None, {}), "points"),
    ("torque_terms_figure", (None, {}), "target"), ("payload_torque_figure", (None, {}), "target"),
    ("payload_slider_figure", (None, {}), "target"), ("energy_figure", (None, {}), "target"),
    ("rotor_coupling_figure", (None, None, None), "max_points"),
])
@pytest.mark.parametrize("value, names", [
    (10**6, ("= 1000000", "limit of 10000")),
    (1, ("= 1", "the least is 2")),
    (500.5, ("= 500.5", "whole number")),
    ("500", ("= '500'", "whole number")),
])
def test_chapter456_figures_refuse_sample_counts_beyond_the_limit_before_any_work(build, args, count, value, names):
    """The count is checked first: the (here absent) runs are never looked at."""
    with pytest.raises(scara.ScaraError) as info:
        getattr(plots, build)(*args, **{count: value})
    assert str(info.value).startswith(f"{count} = ")
    for text in names:
        assert text in str(info.value)


def test_slider_figures_refuse_more_steps_than_a_page_can_carry():
    t = np.linspace(0.0, 1.0, 11)
    many = {float(m): np.zeros((11, 4)) for m in range(200)}
    with pytest.raises(scara.ScaraError, match=r"len\(torques_by_mass\) = 200 asks for more .* limit of 121"):
        plots.payload_slider_figure(t, many)
    some = {float(m): np.zeros((11, 4)) for m in range(50)}
    with pytest.raises(scara.ScaraError, match=r"50 masses × target 5000 = 250000 asks for more .* limit of 100000"):
        plots.payload_slider_figure(t, some, target=5000)
    with pytest.raises(scara.ScaraError, match=r"runs must be a non-empty dict"):
        plots.boundary_layer_slider_figure({}, 1.0)
