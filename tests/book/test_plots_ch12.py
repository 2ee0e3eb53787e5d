"""Figure builders of chapters 1, 2 and 3 and the live panels of chapters 1 and 2: the figures hold the expected
traces and slider steps, the drawn geometry agrees with independent formulas, every figure follows the book's
reading rules (short titles, axis titles with units, a legend, a height for laptop and phone, greyscale-safe
styles), and the panels show a message for bad input."""
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
from scara.plots.kinematics import arm_geometry, inverse_kinematics_slider_figure
from scara.plots.layout import legend_entries

from _figure_rules import check_axis_titles_with_units, check_reads_on_a_laptop_and_a_phone
from scara.plots.manipulability import REFERENCE_CONFIGURATIONS, ellipse_xy, workspace_points
from scara._manipulability import force_ellipsoid, velocity_ellipsoid

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
    """Independent of scara: equation (eq-kin-xe) of chapter 1 written out."""
    t1, t2, d3 = q[0], q[1], q[2]
    return np.array([P.a1 * math.cos(t1) + P.a2 * math.cos(t1 + t2),
                     -(P.a1 * math.sin(t1) + P.a2 * math.sin(t1 + t2)), P.d0 - d3])


# ------------------------------------------------------------------------------------------- chapter 1
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


def test_reference_ellipses_figure_steps_carry_the_books_table():
    fig = reference_ellipses_figure()
    (sl,) = fig.layout.sliders
    assert [s.label for s in sl.steps] == ["q1", "q2", "q3", "q4", "q5"]
    for s, w in zip(sl.steps, ["0.250", "0.177", "0.026", "0.016", "0.000"]):
        data, layout, idx = s.args
        assert layout["title.text"].startswith(s.label) and f"w = {w}" in layout["title.text"]
        # the step redraws the arm, both ellipses and their axes at that configuration
        q = np.array(REFERENCE_CONFIGURATIONS[s.label])
        assert list(idx) == [0, 1, 2, 3, 4]
        assert np.allclose([data["x"][0][-1], data["y"][0][-1]], _closed_form_position(q)[:2], atol=1e-4)
    names = [t.name for t in fig.data]
    assert names == ["arm", "velocity ellipse", "velocity principal axes", "force ellipse", "force principal axes",
                     "workspace boundary"]
    assert legend_entries(fig) == ["arm", "velocity ellipse", "force ellipse"]
    with pytest.raises(ScaraError, match="between 2 and 25"):
        reference_ellipses_figure({"only": Q})


def test_workspace_ellipses_figure_has_an_ellipse_per_position():
    pts = workspace_points()
    assert len(pts) >= 20
    fig = workspace_ellipses_figure(pts)
    (sl,) = fig.layout.sliders
    assert [s.label for s in sl.steps] == ["velocity", "force"]
    assert fig.data[1].name == "velocity ellipses" and tuple(fig.data[1].x) == tuple(sl.steps[0].args[0]["x"][0])
    for step, key, dash in zip(sl.steps, ("velocity", "force"), ("solid", "dash")):
        data, layout, idx = step.args
        assert list(idx) == [1] and data["name"] == [f"{key} ellipses"] and data["line.dash"] == [dash]
        strokes = _strokes(*_xy(go.Scatter(x=data["x"][0], y=data["y"][0])))
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
    s1, s2 = by_name["σ1 (velocity)"], by_name["σ2 (velocity)"]
    f1, f2 = by_name["1/σ1 (force)"], by_name["1/σ2 (force)"]
    ok = np.isfinite(f2) & (s2 > 1e-3)
    assert np.allclose((s1 * f1), 1.0, rtol=1e-4) and np.allclose((s2 * f2)[ok], 1.0, rtol=1e-3)
    # the semi-axes are those of the Jacobian's horizontal block (an independent SVD); the drawn values are
    # rounded to 5 decimals, the theta2 grid is the figure's own (its x labels are rounded to 0.01 degree)
    t2 = np.radians(np.linspace(-179.0, 179.0, len(fig.data[0].x)))
    for k in (0, 40, 90, 150):
        sv = np.linalg.svd(jacobian([0.0, t2[k], 0.5, 0.0])[:2, :2], compute_uv=False)
        assert np.allclose([s1[k], s2[k]], sv, atol=1e-5)
    marks = fig.data[-1]
    assert marks.name == "θ2 = 60°" and np.allclose(marks.x, 60.0)


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
    # in the panel's units: the target as (x, y, z) in m with phi in degrees, and the arm's reach
    assert "out of reach" in panel.last_error and "(x, y, z) = (2.000, 0.200, 0.500) m" in panel.last_error
    assert "a1 + a2 = 1 m" in panel.last_error
    _quiet(setattr, panel.controls["px"], "value", 0.3)
    _quiet(setattr, panel.controls["pz"], "value", 1.5)
    assert "stroke" in panel.last_error


def test_manipulability_panel_reports_bad_scale():
    from scara.widgets import manipulability_panel

    panel = _quiet(manipulability_panel)
    assert panel.last_error is None and set(panel.controls) == {"theta1", "theta2", "scale"}
    _quiet(setattr, panel.controls["scale"], "value", 0.0)
    assert "scale is 0" in panel.last_error and "above 0" in panel.last_error
    _quiet(setattr, panel.controls["scale"], "value", 0.2)
    _quiet(setattr, panel.controls["theta2"], "value", 0.0)  # singular: drawn, not an error
    assert panel.last_error is None
    with pytest.raises(ScaraError):
        manipulability_panel(scale=-1.0)


def test_reference_configurations_are_the_books_ones():
    assert np.allclose(np.array(list(REFERENCE_CONFIGURATIONS.values()))[:, 1],
                       [-math.pi / 2, math.pi / 4, math.pi / 30, 0.98 * math.pi, -0.9999 * math.pi])


# ------------------------------------------------------------------------------------------- chapter 3
from scara import plan_path, reference_plan, reference_trajectory  # noqa: E402
from scara.plots import (anticipation_slider_figure, corner_figure, joint_profiles_figure,  # noqa: E402
                         path_figure, profiles_figure, timing_law_figure, top_view_figure)
from scara.plots.trajectory import decimate  # noqa: E402
from scara.plots import course_figure  # noqa: E402


@pytest.fixture(scope="module")
def traj():
    return reference_trajectory()


@pytest.fixture(scope="module")
def stop_at_p4():
    plan = reference_plan()
    plan["waypoints"][4] = plan["waypoints"][4].replace(anticipation=0.0)
    return plan_path(**plan)


def _trapezoid(tau, L, T, tc):
    """eq-trapezoidal written out independently of scara.trajectory."""
    v = L / (T - tc)
    a = v / tc
    return np.where(tau < tc, 0.5 * a * tau**2, np.where(tau < T - tc, v * (tau - tc / 2), L - 0.5 * a * (T - tau)**2))


def test_timing_law_figure_is_the_trapezoid(traj):
    law = traj.laws[1]
    fig = timing_law_figure(law)
    s_tr, sd_tr, sdd_tr = fig.data[:3]
    tau = np.array(s_tr.x, float)
    assert np.allclose(np.array(s_tr.y, float), _trapezoid(tau, law.length, law.duration, law.blend), atol=1e-6)
    # the speed is the derivative of s: compare with central differences of the closed form
    h = 1e-6
    fd = (_trapezoid(tau + h, law.length, law.duration, law.blend)
          - _trapezoid(tau - h, law.length, law.duration, law.blend)) / (2 * h)
    inside = (np.abs(tau - law.blend) > 1e-3) & (np.abs(tau - (law.duration - law.blend)) > 1e-3) & (tau > 1e-3)
    assert np.allclose(np.array(sd_tr.y, float)[inside], fd[inside], atol=1e-6)
    assert set(np.round(np.array(sdd_tr.y, float), 6)) <= {0.0, round(law.acceleration, 6), round(-law.acceleration, 6)}
    assert len(fig.layout.shapes) == 2 and "t_f = 8 s" in fig.layout.title.text


def test_decimate_keeps_every_stop_and_corner(traj):
    k = decimate(traj, 500)
    marks = np.round(np.r_[traj.segment_start, traj.segment_end] / traj.dt).astype(int)
    assert set(marks) <= set(k) and k[0] == 0 and k[-1] == traj.t.size - 1 and len(k) < 600
    with pytest.raises(ScaraError, match="window"):
        decimate(traj, 100, lo=80.0, hi=90.0)


def test_path_figure_passes_through_the_stop_points(traj):
    fig = path_figure(traj)
    path = np.array([fig.data[0].x, fig.data[0].y, fig.data[0].z], float).T
    for i in np.flatnonzero(~np.asarray(traj.via)):
        assert np.min(np.linalg.norm(path - traj.waypoints[i], axis=1)) < 1e-5
    (arc,) = [t for t in fig.data if t.name.startswith("arc")]
    pts = np.array([arc.x, arc.y, arc.z], float).T
    assert np.allclose(np.linalg.norm(pts - [0.23, 0.20, 0.5], axis=1), 0.05, atol=1e-4)  # the arc of the reference scenario, chapter 3
    assert {t.name for t in fig.data} >= {"path", "stop point", "via point"}
    with pytest.raises(ScaraError, match="Trajectory"):
        path_figure("not a trajectory")


def test_top_view_and_profiles(traj):
    fig = top_view_figure(traj)
    (path,) = [t for t in fig.data if t.name == "path"]
    assert np.allclose(path.x[0], traj.x[0, 0]) and fig.layout.yaxis.scaleanchor == "x"
    fig = profiles_figure(traj)
    comps = [t for t in fig.data if t.name in ("p_x", "p_y", "p_z")]
    assert len(comps) == 9  # position, velocity, acceleration of each
    t = np.array(comps[0].x, float)
    k = np.round(t / traj.dt).astype(int)
    assert np.allclose(np.array(comps[0].y, float), traj.x[k, 0], atol=1e-5)
    # every stop shows as a zero velocity: at each segment end the velocity traces read 0
    vel = [tr for tr in fig.data if tr.yaxis == "y2"]
    ends = [np.flatnonzero(np.isclose(t, e))[0] for e in traj.segment_end if not traj.via[list(traj.segment_end).index(e) + 1]]
    for tr in vel:
        assert np.allclose(np.array(tr.y, float)[ends], 0.0, atol=1e-9)


def test_corner_figure_cuts_the_corner_by_the_corner_distance(traj, stop_at_p4):
    fig = corner_figure(traj, stop_at_p4, 4)
    (via,) = [t for t in fig.data if t.name.startswith("via") and t.xaxis == "x"]
    (stop,) = [t for t in fig.data if t.name.startswith("stop") and t.xaxis == "x"]
    p4 = traj.waypoints[4][:2]
    d_via = np.min(np.hypot(np.array(via.x, float) - p4[0], np.array(via.y, float) - p4[1]))
    d_stop = np.min(np.hypot(np.array(stop.x, float) - p4[0], np.array(stop.y, float) - p4[1]))
    d_exact = traj.corner_distances()["p4"][0]
    # decimated to 400 points over ~10 s at <= 3 cm/s: samples ~0.75 mm apart, so the drawn minimum is within
    # half a spacing above the true one; coordinates are rounded to 1e-5 m, which may put it 0.71e-5 m below
    assert d_exact - 0.71e-5 <= d_via <= d_exact + 4e-4 and d_stop < 1e-5
    assert via.line.dash == "solid" and stop.line.dash == "dash"


def test_anticipation_slider_steps_follow_the_corner_law():
    fig = anticipation_slider_figure(reference_plan(), 4, values=[0.0, 0.5, 1.0, 2.0, 3.0])
    (sl,) = fig.layout.sliders
    assert [s.label for s in sl.steps] == ["0", "0.5", "1", "2", "3"]
    import re
    mm = [float(re.search(r"passes ([0-9.]+) mm", s.args[1]["title.text"]).group(1)) for s in sl.steps]
    assert mm[0] == 0.0

    def corner_mm(dt):
        """eq-traj-corner written out: segments p3->p4 and p4->p5 of 6 s each, blends t_f / 3 = 2 s."""
        pts = [np.array(w.position, float) for w in reference_plan()["waypoints"][3:6]]
        u1, u2 = pts[1] - pts[0], pts[2] - pts[1]
        a1, a2 = (np.linalg.norm(u) / ((6.0 - 2.0) * 2.0) for u in (u1, u2))
        tau = np.linspace(0.0, dt, 200001)[:, None]
        d = -0.5 * a1 * (dt - tau) ** 2 * u1 / np.linalg.norm(u1) + 0.5 * a2 * tau**2 * u2 / np.linalg.norm(u2)
        return 1000 * np.linalg.norm(d, axis=1).min()

    # within the 2 s blends the titles state eq-traj-corner's distance, rounded to 0.1 mm
    for a, shown in zip((0.5, 1.0, 2.0), mm[1:4]):
        assert abs(shown - corner_mm(a)) <= 0.05 + 1e-9, (a, shown, corner_mm(a))
    for s in sl.steps:
        assert list(s.args[2]) == [2, 3]
    with pytest.raises(ScaraError, match="between 2 and 25"):
        anticipation_slider_figure(reference_plan(), 4, values=[1.0])


def test_joint_profiles_mark_the_smallest_manipulability(traj):
    fig = joint_profiles_figure(traj)
    (mark,) = [t for t in fig.data if t.name == "min w"]
    w = traj.manipulability()
    assert math.isclose(mark.y[0], float(w.min()), abs_tol=1e-5) and math.isclose(mark.x[0], traj.t[np.argmin(w)])
    (wtr,) = [t for t in fig.data if t.name == "w"]
    # independent: w from the distance to the joint-1 axis along the path (eq-manip-wr)
    k = np.round(np.array(wtr.x, float) / traj.dt).astype(int)
    r = np.hypot(traj.x[k, 0], traj.x[k, 1])
    c2 = (r**2 - P.a1**2 - P.a2**2) / (2 * P.a1 * P.a2)
    assert np.allclose(np.array(wtr.y, float), P.a1 * P.a2 * np.sqrt(1 - c2**2), atol=1e-5)


def test_course_figure_moves_the_arm_along_the_path(traj):
    fig = course_figure(traj, steps=8)
    (sl,) = fig.layout.sliders
    assert len(sl.steps) == 8 and sl.steps[0].label == "0" and sl.steps[-1].label == "70"
    names = [t.name for t in fig.data]
    arm, trail = names.index("arm (Ch. 1, 4)"), names.index("covered")
    for s in sl.steps:
        data, layout, idx = s.args
        assert list(idx) == [trail, arm]
        t = float(s.label)
        k = int(round(t / traj.dt))
        tool = np.array([data["x"][1][-1], data["y"][1][-1], data["z"][1][-1]])
        # the arm's last point is the gripper, at the path's position at that instant (forward kinematics of
        # the inverse kinematics: an independent route through eq. (1.5))
        assert np.allclose(tool, traj.x[k, :3], atol=1e-4), (t, tool, traj.x[k, :3])
        assert np.allclose([data["x"][0][-1], data["y"][0][-1]], traj.x[k, :2], atol=1e-4)
        assert f"t = {t:.0f} s" in layout["title.text"]
    # the scene holds the whole path and the arm's base
    lay = fig.layout.scene
    for ax, c in ((lay.xaxis, 0), (lay.yaxis, 1)):
        assert ax.range[0] <= min(traj.x[:, c].min(), 0.0) and ax.range[1] >= traj.x[:, c].max()


# ------------------------------------------------------------------------------------------- reading rules
def _all_figures():
    tr = reference_trajectory()
    plan = reference_plan()
    plan["waypoints"][4] = plan["waypoints"][4].replace(anticipation=0.0)
    stop = plan_path(**plan)
    return {
        "arm": arm_figure(Q), "joint_slider": joint_slider_figure(), "ik": inverse_kinematics_figure([0.18, 0.2, 0.5, 0]),
        "ik_reach": inverse_kinematics_slider_figure([0.5, 0.0, 0.5, 0.0], [0.5, 0.9, 1.0, 1.01]),
        "determinant": determinant_figure(), "reference": reference_ellipses_figure(),
        "workspace": workspace_ellipses_figure(), "map": manipulability_map_figure(n=41),
        "duality": duality_figure([0, math.pi / 3, 0.5, 0]), "sweep": ellipse_slider_figure(),
        "timing": timing_law_figure(tr.laws[1]), "path": path_figure(tr), "top": top_view_figure(tr),
        "profiles": profiles_figure(tr), "corner": corner_figure(tr, stop, 4),
        "anticipation": anticipation_slider_figure(reference_plan(), 4), "joints": joint_profiles_figure(tr),
        "course": course_figure(tr),
    }


@pytest.fixture(scope="module")
def figures():
    return _all_figures()


def test_every_figure_reads_on_a_laptop_and_a_phone(figures):
    for name, fig in figures.items():
        check_reads_on_a_laptop_and_a_phone(name, fig)


def test_every_axis_has_a_title_with_a_unit(figures):
    for name, fig in figures.items():
        check_axis_titles_with_units(name, fig)


def test_styles_survive_greyscale(figures):
    def dash(t):
        return t.line.dash or "solid"

    # velocity ellipses solid, force ellipses dashed, wherever they are drawn
    for name in ("reference", "sweep"):
        by = {t.name: t for t in figures[name].data}
        assert dash(by["velocity ellipse"]) == "solid" and dash(by["force ellipse"]) == "dash", name
    assert {dash(t) for t in figures["duality"].data[:4]} == {"solid", "dash", "dot", "dashdot"}
    # the two elbows, the x/y/z triads, the components of the profiles and the joints differ by dash too
    elbows = [t for t in figures["ik"].data if t.name.startswith("elbow")]
    assert dash(elbows[0]) != dash(elbows[1])
    triads = [t for t in figures["arm"].data if t.name.endswith("axes")]
    assert len({dash(t) for t in triads}) == 3
    comps = [t for t in figures["profiles"].data if t.name in ("p_x", "p_y", "p_z", "φ") and t.showlegend is not False]
    assert len({dash(t) for t in comps}) == 4
    joints = [t for t in figures["joints"].data if t.name in ("θ1", "θ2", "d3", "θ4")]
    assert len({dash(t) for t in joints}) == 4


@pytest.mark.parametrize("build, kwargs, names", [
    ("course_figure", dict(steps=10**6), ("steps = 1000000", "limit of 121")),
    ("course_figure", dict(steps=0), ("steps = 0", "the least is 1")),
    ("course_figure", dict(steps=2.5), ("steps = 2.5", "whole number", "1 to 121")),
    ("course_figure", dict(steps="36"), ("steps = '36'", "whole number")),
    ("course_figure", dict(points=10**7), ("points = 10000000", "limit of 10000")),
    ("path_figure", dict(points=-5), ("points = -5", "the least is 2")),
    ("top_view_figure", dict(points=True), ("points = True", "whole number")),
    ("profiles_figure", dict(points=10**9), ("points = 1000000000", "limit of 10000")),
    ("joint_profiles_figure", dict(points=20_001), ("points = 20001", "limit of 10000")),
    ("anticipation_slider_figure", dict(points=10_000), ("13 values × points 10000", "limit of 100000")),
])
def test_chapter3_figures_refuse_counts_beyond_their_limits_before_any_work(traj, build, kwargs, names):
    from scara import plots, reference_plan

    first = reference_plan() if build == "anticipation_slider_figure" else traj
    args = (first, 4) if build == "anticipation_slider_figure" else (first,)
    with pytest.raises(ScaraError) as info:
        getattr(plots, build)(*args, **kwargs)
    for text in names:
        assert text in str(info.value)


@pytest.mark.parametrize("build, kwargs, names", [
    (determinant_figure, dict(n=10**6), ("n = 1000000", "limit of 10000")),
    (determinant_figure, dict(n=2), ("n = 2", "the least is 3")),
    (duality_figure, dict(q=Q, n=10**5), ("n = 100000", "limit of 2001")),
    (duality_figure, dict(q=Q, n=181.0), ("n = 181.0", "whole number")),
    (manipulability_map_figure, dict(n=10**4), ("n = 10000", "limit of 301")),
    (ellipse_xy, dict(ellipsoid=None, n=10**8), ("n = 100000000", "limit of 10000")),
    (workspace_points, dict(n_angles=1000), ("n_angles = 1000", "limit of 200")),
    (workspace_points, dict(n_angles=100), ("len(radii) * n_angles = 300", "limit of 200")),
    (workspace_ellipses_figure, dict(points=np.tile([0.5, 0.2, 0.5, 0.0], (500, 1))),
     ("the number of points = 500", "limit of 200")),
])
def test_chapter12_figures_refuse_counts_beyond_their_limits(build, kwargs, names):
    with pytest.raises(ScaraError) as info:
        build(**kwargs)
    for text in names:
        assert text in str(info.value)


def test_course_figure_with_a_million_steps_is_refused_at_once(traj):
    import time

    from scara.plots import course_figure

    t0 = time.perf_counter()
    with pytest.raises(ScaraError, match=r"steps = 1000000 asks for more slider steps than the limit of 121"):
        course_figure(traj, steps=10**6)
    assert time.perf_counter() - t0 < 0.5
    assert len(course_figure(traj, steps=121).layout.sliders[0].steps) == 121  # the limit itself is drawn
