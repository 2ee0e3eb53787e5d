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
from scara.clik import SEED_K
from scara.dynamics import torque_breakdown
from scara.plots.control import CONTROLLER_LABELS, CONTROLLER_DASHES

from _figure_rules import check_axis_titles_with_units, check_reads_on_a_laptop_and_a_phone

ROOT = Path(__file__).resolve().parents[2]
P5 = scara.ScaraParams().with_payload(5.0)
#: stacked panels sharing one time axis (three or four of them) may be taller than the default 560 px; 780 px
#: still fits a laptop screen with the browser's bars
TALL = {"control_joint_motion": 780, "control_torques": 780, "control_operational_error": 780,
        "control_boundary_layer": 780, "control_robust_term": 780, "control_steady_state": 780}


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
    rr = scara.simulate(robust, tr, P5, joint_reference=ref)
    ar = scara.simulate(adaptive, tr, P5, joint_reference=ref)
    orr, onr = scara.simulate(op, tr, P5), scara.simulate(op_noint, tr, P5)
    layers = {eps: scara.simulate(scara.RobustController(epsilon=eps), tr, P5, joint_reference=ref)
              for eps in (0.01, 0.05)}
    b33 = scara.inertia(ref.q[0])[2, 2]
    labelled = {CONTROLLER_LABELS[c.name]: r for c, r in ((robust, rr), (adaptive, ar), (op, orr), (op_noint, onr))}
    figs.update({
        "control_robust_term": plots.robust_term_figure(rr, robust.epsilon),
        "control_boundary_layer": plots.boundary_layer_slider_figure(layers, 0.016, window=(40.0, 40.15)),
        "control_estimate": plots.payload_estimate_figure(ar, true_mass=5.0),
        "control_steady_state": plots.steady_state_figure(orr, onr, 5.0 * P5.g0 / (b33 * op.K_P[2]),
                                                          5.0 * P5.g0 / b33),
        "control_error_norm": plots.error_norm_figure(labelled),
        "control_joint_motion": plots.joint_motion_figure(labelled),
        "control_operational_error": plots.operational_error_figure(labelled),
        "control_torques": plots.torque_figure(labelled),
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
    dashes = [(t.line.dash or "solid") for t in norm.data if t.name in CONTROLLER_LABELS.values()]
    assert len(set(dashes)) == len(dashes) >= 4


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
