"""Figure builders and live panels of chapters 1 and 2: the figures hold the expected traces and slider steps,
the drawn geometry agrees with independent formulas, and the panels show a message for bad input."""
from __future__ import annotations

import contextlib
import io
import math

import numpy as np
import plotly.graph_objects as go
import pytest

from scara import NonFiniteError, ScaraError, ScaraParams, UnreachableError, fkine, jacobian, pose
from scara.plots import (arm_figure, determinant_figure, duality_figure, ellipse_slider_figure,
                         inverse_kinematics_figure, joint_slider_figure, manipulability_map_figure,
                         reference_ellipses_figure, workspace_ellipses_figure)
from scara.plots.kinematics import arm_geometry
from scara.plots.manipulability import REFERENCE_CONFIGURATIONS, ellipse_xy, workspace_points
from scara.manipulability import force_ellipsoid, velocity_ellipsoid

P = ScaraParams()
Q = np.array([0.3, -1.2, 0.4, 0.1])


def _xy(trace):
    return np.array([np.nan if v is None else v for v in trace.x], float), \
        np.array([np.nan if v is None else v for v in trace.y], float)


def _strokes(x, y):
    """Split None/NaN-separated polylines into arrays of points."""
    out, cur = [], []
    for a, b in zip(x, y):
        if np.isnan(a):
            if cur:
                out.append(np.array(cur))
            cur = []
        else:
            cur.append((a, b))
    if cur:
        out.append(np.array(cur))
    return out


def _closed_form_position(q):
    """Independent of scara: SPEC section 2 written out."""
    t1, t2, d3 = q[0], q[1], q[2]
    return np.array([P.a1 * math.cos(t1) + P.a2 * math.cos(t1 + t2),
                     -(P.a1 * math.sin(t1) + P.a2 * math.sin(t1 + t2)), P.d0 - d3])


# ------------------------------------------------------------------------------------------- chapter 1
def test_arm_figure_traces_and_frames():
    fig = arm_figure(Q)
    assert isinstance(fig, go.Figure)
    assert [t.name for t in fig.data] == ["arm", "end effector", "x axes", "y axes", "z axes", "frame names"]
    ee = np.array([fig.data[1].x[0], fig.data[1].y[0], fig.data[1].z[0]])
    assert np.allclose(ee, _closed_form_position(Q), atol=1e-4)  # coordinates rounded to 0.1 mm
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
        assert np.allclose(ee, _closed_form_position(q), atol=1e-4)
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
        x, y = _xy(t)
        assert np.allclose([x[-1], y[-1]], target[:2], atol=1e-4)      # the tip is on the target
        assert math.isclose(math.hypot(x[1], y[1]), P.a1, rel_tol=1e-3)  # the elbow is a1 from the axis
        elbows.append((x[1], y[1]))
    assert np.linalg.norm(np.subtract(*elbows)) > 0.1  # two distinct solutions
    with pytest.raises(UnreachableError, match="annulus"):
        inverse_kinematics_figure([1.5, 0.0, 0.5, 0.0])


def test_determinant_figure_matches_closed_form():
    fig = determinant_figure(n=73)
    t2 = np.radians(np.array(fig.data[0].x, float))
    det = np.array(fig.data[0].y, float)
    assert np.allclose(det, P.a1 * P.a2 * np.sin(t2), atol=1e-5)
    assert np.allclose(np.array(fig.data[1].y, float), np.abs(det), atol=1e-12)


# ------------------------------------------------------------------------------------------- chapter 2
@pytest.mark.parametrize("theta2", [math.radians(60), -2.0, 0.3])
def test_ellipse_outlines_satisfy_their_quadratic_forms(theta2):
    q = np.array([0.7, theta2, 0.5, 0.0])
    Jh = jacobian(q)[:2, :2]
    M = Jh @ Jh.T
    c = pose(q)[:2]
    for scale in (1.0, 0.2):
        v = ellipse_xy(velocity_ellipsoid(q, rows=(0, 1)), scale, n=37) - c
        f = ellipse_xy(force_ellipsoid(q, rows=(0, 1)), scale, n=37) - c
        # v^T (J J^T)^-1 v = scale^2 and f^T (J J^T) f = scale^2 (eq-manip-vel, eq-manip-force)
        assert np.allclose(np.einsum("ni,ij,nj->n", v, np.linalg.inv(M), v), scale**2, rtol=1e-9)
        assert np.allclose(np.einsum("ni,ij,nj->n", f, M, f), scale**2, rtol=1e-9)


def test_ellipse_xy_at_a_singularity_is_a_segment_and_a_strip():
    q = np.array([0.0, 0.0, 0.5, 0.0])  # stretched along x
    seg = ellipse_xy(velocity_ellipsoid(q, rows=(0, 1)), 0.15) - pose(q)[:2]
    assert np.max(np.abs(seg[:, 0])) < 1e-12  # the arm can only move across itself (along y)
    strip = ellipse_xy(force_ellipsoid(q, rows=(0, 1)), 0.15) - pose(q)[:2]
    assert np.all(np.isfinite(strip)) and np.max(np.abs(strip[:, 0])) > 10  # clipped, far outside the view
    with pytest.raises(ScaraError, match="scale"):
        ellipse_xy(velocity_ellipsoid(q, rows=(0, 1)), 0.0)


def test_reference_ellipses_figure_titles_carry_the_spec_table():
    fig = reference_ellipses_figure()
    titles = [a.text for a in fig.layout.annotations]
    for name, w in zip(["q1", "q2", "q3", "q4", "q5"], ["0.250", "0.177", "0.026", "0.016", "0.000"]):
        assert any(t.startswith(name) and f"w = {w}" in t for t in titles), (name, titles)
    names = [t.name for t in fig.data]
    assert names.count("arm") == 5 and names.count("velocity ellipse (× 0.15)") == 5
    assert names.count("force ellipse (× 0.15)") == 5
    assert sum(bool(t.showlegend) for t in fig.data) == 3  # one legend entry per kind


def test_workspace_ellipses_figure_has_an_ellipse_per_position():
    pts = workspace_points()
    assert len(pts) >= 20
    fig = workspace_ellipses_figure(pts)
    for key in ("velocity ellipses", "force ellipses"):
        (tr,) = [t for t in fig.data if t.name == key]
        strokes = _strokes(*_xy(tr))
        assert len(strokes) == len(pts)
        centres = np.array([s[:-1].mean(axis=0) for s in strokes])  # closed outline: drop the repeated point
        assert np.allclose(centres, pts[:, :2], atol=1e-3)
    with pytest.raises(UnreachableError):
        workspace_ellipses_figure([[2.0, 0.0, 0.5, 0.0]])


def test_manipulability_map_figure():
    fig = manipulability_map_figure(n=41)
    heat = fig.data[0]
    assert isinstance(heat, go.Heatmap) and heat.zmax == pytest.approx(P.a1 * P.a2)
    z = np.array([[np.nan if v is None else v for v in row] for row in heat.z], float)
    X, Y = np.meshgrid(np.array(heat.x, float), np.array(heat.y, float))
    r = np.hypot(X, Y)
    inside = r < P.r_max - 1e-9
    c2 = (r[inside] ** 2 - P.a1**2 - P.a2**2) / (2 * P.a1 * P.a2)
    assert np.allclose(z[inside], P.a1 * P.a2 * np.sqrt(1 - c2**2), atol=1e-4)
    names = " ".join(t.name for t in fig.data[1:])
    assert "stretched" in names and "folded" in names
    # unequal links: the folded singularity becomes a circle of radius |a1 - a2|
    fig2 = manipulability_map_figure(ScaraParams(a1=0.7, a2=0.3), n=21)
    (circle,) = [t for t in fig2.data if t.name.startswith("folded")]
    x, y = _xy(circle)
    assert np.allclose(np.hypot(x, y), 0.4, atol=1e-4)


def test_duality_figure_lengths_are_reciprocal():
    fig = duality_figure([0.0, math.radians(60), 0.5, 0.0])
    by_name = {t.name: np.array([np.nan if v is None else v for v in t.y], float) for t in fig.data
               if t.name and ("σ" in t.name)}
    s1, s2 = by_name["σ1 (velocity, major)"], by_name["σ2 (velocity, minor)"]
    f1, f2 = by_name["1/σ1 (force, minor)"], by_name["1/σ2 (force, major)"]
    ok = np.isfinite(f2) & (s2 > 1e-3)
    assert np.allclose((s1 * f1), 1.0, rtol=1e-4) and np.allclose((s2 * f2)[ok], 1.0, rtol=1e-3)


def test_ellipse_slider_figure_sweeps_theta2():
    fig = ellipse_slider_figure()
    (sl,) = fig.layout.sliders
    assert "θ2" in sl.currentvalue.prefix and len(sl.steps) == 25
    labels = [float(s.label) for s in sl.steps]
    assert labels[0] == 180 and labels[-1] == -180 and 0.0 in labels
    for s in sl.steps:
        data, layout, idx = s.args
        assert list(idx) == [0, 1, 2] and "w = " in layout["title.text"]
        q = np.array([0.0, math.radians(float(s.label)), 0.5, 0.0])
        arm_x, arm_y = data["x"][0], data["y"][0]
        assert np.allclose([arm_x[-1], arm_y[-1]], _closed_form_position(q)[:2], atol=1e-4)
        assert all(v is None or math.isfinite(v) for v in data["x"][2])  # even at the singular steps
    # the workspace boundary (trace 3) is not restyled by the steps
    assert fig.data[3].name == "workspace boundary"


# ------------------------------------------------------------------------------------------- panels
def _quiet(fn, *a, **kw):
    with contextlib.redirect_stdout(io.StringIO()):
        return fn(*a, **kw)


def test_kinematics_panel_redraws_and_reports_bad_input():
    from scara.widgets import kinematics_panel

    panel = _quiet(kinematics_panel)
    assert panel.last_error is None and set(panel.controls) == {"theta1", "theta2", "d3", "theta4"}
    _quiet(setattr, panel.controls["theta1"], "value", float("nan"))
    assert panel.last_error and "not finite" in panel.last_error
    assert "Cannot show" in panel.message.value
    _quiet(setattr, panel.controls["theta1"], "value", 10.0)
    assert panel.last_error is None and panel.message.value == ""


def test_inverse_kinematics_panel_reports_unreachable_targets():
    from scara.widgets import inverse_kinematics_panel

    panel = _quiet(inverse_kinematics_panel)
    assert panel.last_error is None
    _quiet(setattr, panel.controls["px"], "value", 2.0)
    assert "unreachable" in panel.last_error and "annulus" in panel.last_error
    _quiet(setattr, panel.controls["px"], "value", 0.3)
    _quiet(setattr, panel.controls["pz"], "value", 1.5)
    assert "stroke" in panel.last_error


def test_manipulability_panel_reports_bad_scale():
    from scara.widgets import manipulability_panel

    panel = _quiet(manipulability_panel)
    assert panel.last_error is None and set(panel.controls) == {"theta1", "theta2", "scale"}
    _quiet(setattr, panel.controls["scale"], "value", 0.0)
    assert "scale" in panel.last_error and "> 0" in panel.last_error
    _quiet(setattr, panel.controls["scale"], "value", 0.2)
    _quiet(setattr, panel.controls["theta2"], "value", 0.0)  # singular: drawn, not an error
    assert panel.last_error is None
    with pytest.raises(ScaraError):
        manipulability_panel(scale=-1.0)


def test_reference_configurations_are_the_spec_ones():
    assert np.allclose(np.array(list(REFERENCE_CONFIGURATIONS.values()))[:, 1],
                       [-math.pi / 2, math.pi / 4, math.pi / 30, 0.98 * math.pi, -0.9999 * math.pi])
