"""The figures of scara.plots.control, built as chapter 6 builds them: the torque differences tell the controllers
apart, the saturation figure and the figure slider draw what they name and refuse bad input, and every control
figure refuses a sample count beyond its limit before any work. The reading rules of these figures are checked with
every figure's in test_plots_layout.py."""
from __future__ import annotations

import numpy as np
import pytest

import scara
from scara import plots
from scara.plots.control import CONTROLLER_LABELS, figure_slider, saturation_figure

from _plots_shared import SAMPLE_COUNTS, check_sample_count_refused, run_figures


@pytest.fixture(scope="module")
def figures():
    return run_figures()


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


def test_joint_error_figure_draws_each_joint_and_the_predicted_sag(figures):
    fig = figures["control_classic"]
    labels = [CONTROLLER_LABELS["pd_plus_gravity"], CONTROLLER_LABELS["computed_torque"]]
    assert [t.name for t in fig.data if t.showlegend is not False] == labels
    for key, label in zip(("pd_plus_gravity", "computed_torque"), labels):
        mine = [t for t in fig.data if t.legendgroup == label]
        assert len(mine) == 5 and {t.line.color for t in mine} == {plots.PALETTE[key]}
        predicted = mine[-1]
        assert predicted.line.dash == "dot" and predicted.yaxis == "y3"   # the quill's panel, in mm
        sag = scara.PDPlusGravityController().steady_state_error(scara.ScaraParams().with_payload(5.0))[2]
        assert predicted.y[0] == pytest.approx(1e3 * sag, rel=1e-3)
    from types import SimpleNamespace as NS

    run = NS(t=np.arange(10) * 1e-3, q=np.zeros((10, 4)), q_d=np.zeros((10, 4)), tau=np.zeros((10, 4)), e=np.zeros((10, 4)),
             controller="robust")
    with pytest.raises(scara.ScaraError, match=r"predicted must map labels of the runs \['a'\] .*unknown: \['x'\]"):
        plots.joint_error_figure({"a": run}, {"x": np.zeros(4)})
    with pytest.raises(scara.ScaraError, match=r"predicted\['a'\] must be 4 finite joint errors"):
        plots.joint_error_figure({"a": run}, {"a": [0.0, np.nan, 0.0, 0.0]})


@pytest.mark.parametrize("build, args, count", [
    ("joint_motion_figure", (None,), "points"), ("joint_error_figure", (None,), "points"), ("operational_error_figure", (None,), "points"),
    ("error_norm_figure", (None,), "points"), ("torque_figure", (None,), "points"),
    ("payload_estimate_figure", (None, 5.0), "points"), ("robust_term_figure", (None, 0.05), "points"),
    ("tuning_figure", (None, {}), "points"),
])
@pytest.mark.parametrize("value, names", SAMPLE_COUNTS)
def test_control_figures_refuse_sample_counts_beyond_the_limit_before_any_work(build, args, count, value, names):
    check_sample_count_refused(build, args, count, value, names)
