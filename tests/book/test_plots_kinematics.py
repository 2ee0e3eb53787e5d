"""The figures of scara.plots.kinematics (the arm in 3-D, its joint sliders, the inverse kinematics and the
determinant of J_A) and the live panels of the arm and of the inverse kinematics: the figures hold the expected
traces and slider steps, the drawn geometry agrees with independent formulas, and the panels show a message for
bad input."""
from __future__ import annotations

import math

import numpy as np
import plotly.graph_objects as go
import pytest

from scara import NonFiniteError, ScaraError, UnreachableError, fkine
from scara.plots import arm_figure, determinant_figure, inverse_kinematics_figure, joint_slider_figure
from scara.plots.kinematics import arm_geometry, inverse_kinematics_slider_figure

from _plots_shared import P, Q, closed_form_position, quiet, refusal, xy


# ------------------------------------------------------------------------------------------------------------ figures
def test_arm_figure_traces_and_frames():
    fig = arm_figure(Q)
    assert isinstance(fig, go.Figure)
    assert [t.name for t in fig.data] == ["arm", "end effector", "x axes", "y axes", "z axes", "frame names"]
    g = arm_geometry(Q)
    assert list(fig.data[-1].text) == g["labels"] and not fig.layout.scene.annotations
    # for the book's static figures, the frame names are scene annotations pinned to the distinct frame origins
    fig_notes = arm_figure(Q, names="annotations")
    assert [t.name for t in fig_notes.data] == ["arm", "end effector", "x axes", "y axes", "z axes"]
    notes = fig_notes.layout.scene.annotations
    assert [a.text for a in notes] == g["labels"]
    assert np.allclose([[a.x, a.y, a.z] for a in notes], g["origins"], atol=1e-4)
    with pytest.raises(ScaraError, match="names"):
        arm_figure(Q, names="labels")
    ee = np.array([fig.data[1].x[0], fig.data[1].y[0], fig.data[1].z[0]])
    assert np.allclose(ee, closed_form_position(Q), atol=1e-4)  # coordinates rounded to 0.1 mm
    # the end-effector triad (last of the 7 segments) points along the columns of R_e^b of eq-fk
    T = fkine(Q)
    for k in range(3):
        seg = np.array([fig.data[2 + k].x[-3:-1], fig.data[2 + k].y[-3:-1], fig.data[2 + k].z[-3:-1]], float).T
        direction = (seg[1] - seg[0]) / np.linalg.norm(seg[1] - seg[0])
        assert np.allclose(direction, T[:3, k], atol=1e-3)
    assert fig.layout.scene.xaxis.title.text == "x (m)" and fig.layout.title.text


def test_arm_geometry_merges_coincident_frame_labels():
    g = arm_geometry([0.2, 0.5, 0.3, 0.0])
    assert g["labels"] == ["b", "0", "1", "2", "3, 4, e"]
    g = arm_geometry([0.2, 0.5, 0.0, 0.0])  # quill fully up: frame 3 at the top of the quill, with frame 2
    assert "2, 3, 4, e" in g["labels"]


def test_joint_slider_figure_steps_move_the_arm():
    fig = joint_slider_figure([0.0, math.radians(60), 0.5, 0.0], joint=1)
    (sl,) = fig.layout.sliders
    assert "θ2" in sl.currentvalue.prefix and 2 <= len(sl.steps) <= 25
    labels = [float(s.label) for s in sl.steps]
    assert labels[0] == -180 and labels[-1] == 180 and 0.0 in labels
    ntr = len(fig.data)
    ee_positions = []
    for s in sl.steps:
        data, layout, idx = s.args
        assert s.method == "update" and list(idx) == list(range(ntr))
        assert len(data["x"]) == ntr and "det J_A" in layout["title.text"]
        ee = np.array([data["x"][1][0], data["y"][1][0], data["z"][1][0]])
        q = np.array([0.0, math.radians(float(s.label)), 0.5, 0.0])
        assert np.allclose(ee, closed_form_position(q), atol=1e-4)
        ee_positions.append(ee)
    assert len({tuple(np.round(e, 3)) for e in ee_positions}) > 20  # the arm really moves
    # the figure starts at the step nearest to q0, and shows that step's data
    active = sl.steps[sl.active]
    assert float(active.label) == 60 and tuple(active.args[0]["x"][0]) == tuple(fig.data[0].x)


def test_joint_slider_figure_prismatic_and_bad_input():
    fig = joint_slider_figure(joint=2)
    zs = [s.args[0]["z"][1][0] for s in fig.layout.sliders[0].steps]
    assert np.allclose(zs, P.d0 - np.linspace(0, P.d0, 21), atol=1e-4)
    with pytest.raises(ScaraError, match="joint"):
        joint_slider_figure(joint=4)
    with pytest.raises(ScaraError, match="slider steps"):
        joint_slider_figure(values=np.linspace(-180, 180, 100))
    with pytest.raises(NonFiniteError):
        arm_figure([0.0, np.nan, 0.5, 0.0])


def test_inverse_kinematics_figure_both_elbows_reach_the_target():
    target = np.array([0.18, 0.20, 0.5, 0.0])
    fig = inverse_kinematics_figure(target)
    arms = [t for t in fig.data if t.name.startswith("elbow")]
    assert len(arms) == 2
    elbows = []
    for t in arms:
        x, y = xy(t)
        assert np.allclose([x[-1], y[-1]], target[:2], atol=1e-4)      # the tip is on the target
        assert math.isclose(math.hypot(x[1], y[1]), P.a1, rel_tol=1e-3)  # the elbow is a1 from the axis
        elbows.append((x[1], y[1]))
    assert np.linalg.norm(np.subtract(*elbows)) > 0.1  # two distinct solutions
    with pytest.raises(UnreachableError, match="annulus"):
        inverse_kinematics_figure([1.5, 0.0, 0.5, 0.0])


def test_inverse_kinematics_slider_figure_follows_the_law_of_cosines():
    values = [0.3, 0.6, 0.9, 1.0, 1.01, 1.2]
    fig = inverse_kinematics_slider_figure([0.3, 0.0, 0.5, 0.0], values)
    steps = fig.layout.sliders[0].steps
    assert [s.label for s in steps] == [f"{v:.2f}" for v in values]
    names = [t.name for t in fig.data]
    for s, v in zip(steps, values):
        data, layout, idx = s.args
        assert [names[k] for k in idx] == ["elbow +1", "elbow −1", "target"]
        assert data["x"][2] == [v] and data["y"][2] == [0.0]
        c2 = (v**2 - P.a1**2 - P.a2**2) / (2 * P.a1 * P.a2)  # the law of cosines, independent of scara
        if abs(c2) <= 1:
            t2 = math.degrees(math.acos(c2))
            assert f"θ2 = {t2:.1f}° (elbow +1), −{t2:.1f}° (−1)".replace("−0.0", "0.0") in layout["title.text"]
            for arm_x, arm_y in zip(data["x"][:2], data["y"][:2]):
                assert np.allclose([arm_x[-1], arm_y[-1]], [v, 0.0], atol=1e-4)  # each arm's tip on the target
                assert math.isclose(math.hypot(arm_x[1], arm_y[1]), P.a1, rel_tol=1e-3)
        else:
            assert "out of reach: r > a1 + a2 = 1 m" in layout["title.text"]
            assert data["x"][:2] == [[], []] and data["y"][:2] == [[], []]
    # the figure opens on its first step
    assert fig.layout.title.text == steps[0].args[1]["title.text"]
    with pytest.raises(ScaraError, match="component"):
        inverse_kinematics_slider_figure([0.3, 0.0, 0.5, 0.0], values, component=3)
    with pytest.raises(ScaraError, match="slider steps"):
        inverse_kinematics_slider_figure([0.3, 0.0, 0.5, 0.0], [0.3])
    with pytest.raises(UnreachableError, match="first target"):
        inverse_kinematics_slider_figure([1.2, 0.0, 0.5, 0.0], [1.2, 0.5])
    # a height the quill cannot reach is named too
    fig = inverse_kinematics_slider_figure([0.5, 0.0, 0.5, 0.0], [0.5, 1.5], component=2)
    assert "off the stroke" in fig.layout.sliders[0].steps[1].args[1]["title.text"]


def test_determinant_figure_matches_closed_form():
    fig = determinant_figure(n=73)
    t2 = np.radians(np.array(fig.data[0].x, float))
    det = np.array(fig.data[0].y, float)
    assert np.allclose(det, P.a1 * P.a2 * np.sin(t2), atol=1e-5)
    assert np.allclose(np.array(fig.data[1].y, float), np.abs(det), atol=1e-12)


@pytest.mark.parametrize("build, kwargs, names", [
    (determinant_figure, dict(n=10**6), ("n = 1000000", "<= 10000")),
    (determinant_figure, dict(n=2), ("n = 2", "3 <= ")),
])
def test_kinematics_figures_refuse_counts_beyond_their_limits(build, kwargs, names):
    message = refusal(build, **kwargs)
    for text in names:
        assert text in message


# ------------------------------------------------------------------------------------------------------------- panels
def test_kinematics_panel_redraws_and_reports_bad_input():
    from scara.widgets import kinematics_panel

    panel = quiet(kinematics_panel)
    assert panel.last_error is None and set(panel.controls) == {"theta1", "theta2", "d3", "theta4"}
    quiet(setattr, panel.controls["theta1"], "value", float("nan"))
    assert panel.last_error and "not finite" in panel.last_error
    assert "Cannot show" in panel.message.value
    quiet(setattr, panel.controls["theta1"], "value", 10.0)
    assert panel.last_error is None and panel.message.value == ""


def test_inverse_kinematics_panel_reports_unreachable_targets():
    from scara.widgets import inverse_kinematics_panel

    panel = quiet(inverse_kinematics_panel)
    assert panel.last_error is None
    quiet(setattr, panel.controls["px"], "value", 2.0)
    # in the panel's units: the target as (x, y, z) in m with phi in degrees, and the arm's reach
    assert "out of reach" in panel.last_error and "(x, y, z) = (2.000, 0.200, 0.500) m" in panel.last_error
    assert "a1 + a2 = 1 m" in panel.last_error
    quiet(setattr, panel.controls["px"], "value", 0.3)
    quiet(setattr, panel.controls["pz"], "value", 1.5)
    assert "stroke" in panel.last_error


def test_dashed_triads_show_their_dashes_in_the_legend():
    from scara.plots.kinematics import arm_figure
    # plotly draws a legend line 30 px long, with dashes and gaps three line widths long each
    fig = arm_figure([0.3, -1.2, 0.4, 0.1])
    for t in fig.data:
        if t.name.endswith("axes") and t.line.dash == "dash":
            assert 3 * 3 * t.line.width <= 30, t.name


def test_singular_labels_sit_off_the_curves():
    from scara.plots.kinematics import determinant_figure
    fig = determinant_figure()
    (sing,) = [t for t in fig.data if t.name == "singular"]
    assert list(sing.textposition) == ["middle left", "bottom right", "middle right"]
    assert fig.layout.xaxis.range[0] < -200 and fig.layout.xaxis.range[1] > 200
