"""The figures of scara.plots.manipulability (the velocity and force ellipses, the manipulability map, the duality
of their semi-axes, the theta2 sweep and the turn of the base) and the live panel of the ellipses: the outlines
satisfy their quadratic forms, the slider steps carry the book's table, the major axis is the top eigenvector of
H H^T found without the package's SVD, the ellipses turn rigidly with the arm, and bad input is refused."""
from __future__ import annotations

import math

import numpy as np
import plotly.graph_objects as go
import pytest

from scara import ScaraError, ScaraParams, UnreachableError, jacobian, manipulability, pose, velocity_ellipsoid
from scara._manipulability import force_ellipsoid
from scara.plots import (duality_figure, ellipse_slider_figure, manipulability_map_figure, reference_ellipses_figure,
                         workspace_ellipses_figure)
from scara.plots.layout import legend_entries
from scara.plots.manipulability import (REFERENCE_CONFIGURATIONS, base_turn_figure, ellipse_xy, major_axis_angle,
                                        workspace_points)

from _figure_rules import title_lines
from _plots_shared import P, Q, closed_form_position, quiet, refusal, xy


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


# ----------------------------------------------------------------------------------------------------------- ellipses
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
        assert np.allclose([data["x"][0][-1], data["y"][0][-1]], closed_form_position(q)[:2], atol=1e-4)
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
    # the force ellipses dashed in dashes short enough (a few px) that each small outline stays a whole curve
    for step, key, dash in zip(sl.steps, ("velocity", "force"), ("solid", "3px,2px")):
        data, layout, idx = step.args
        assert list(idx) == [1] and data["name"] == [f"{key} ellipses"] and data["line.dash"] == [dash]
        strokes = _strokes(*xy(go.Scatter(x=data["x"][0], y=data["y"][0])))
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
    x, y = xy(circle)
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
        assert np.allclose([arm_x[-1], arm_y[-1]], closed_form_position(q)[:2], atol=1e-4)
        assert all(v is None or math.isfinite(v) for v in data["x"][2])  # even at the singular steps
    # the workspace boundary (trace 3) is not restyled by the steps
    assert fig.data[3].name == "workspace boundary"


def test_reference_configurations_are_the_books_ones():
    assert np.allclose(np.array(list(REFERENCE_CONFIGURATIONS.values()))[:, 1],
                       [-math.pi / 2, math.pi / 4, math.pi / 30, 0.98 * math.pi, -0.9999 * math.pi])


@pytest.mark.parametrize("build, kwargs, names", [
    (duality_figure, dict(q=Q, n=10**5), ("n = 100000", "<= 2001")),
    (duality_figure, dict(q=Q, n=181.0), ("n = 181.0", "whole number")),
    (manipulability_map_figure, dict(n=10**4), ("n = 10000", "<= 301")),
    (ellipse_xy, dict(ellipsoid=None, n=10**8), ("n = 100000000", "<= 10000")),
    (workspace_points, dict(n_angles=1000), ("n_angles = 1000", "<= 200")),
    (workspace_points, dict(n_angles=100), ("len(radii) * n_angles = 300", "<= 200")),
    (workspace_ellipses_figure, dict(points=np.tile([0.5, 0.2, 0.5, 0.0], (500, 1))),
     ("the number of points = 500", "<= 200")),
])
def test_manipulability_figures_refuse_counts_beyond_their_limits(build, kwargs, names):
    message = refusal(build, **kwargs)
    for text in names:
        assert text in message


# ----------------------------------------------------------------------------------------------- the turn of the base
def _major_by_eigh(q) -> float:
    """Direction (degrees, modulo 180, in (-90, 90]) of the eigenvector of H H^T with the larger eigenvalue, H
    the horizontal block of J_A: the major axis of the velocity ellipse, found without the package's SVD."""
    H = jacobian(q)[:2, :2]
    vals, vecs = np.linalg.eigh(H @ H.T)
    u = vecs[:, int(np.argmax(vals))]
    a = math.degrees(math.atan2(u[1], u[0])) % 180.0
    return a - 180.0 if a > 90.0 else a


def test_major_axis_angle_is_the_top_eigenvector_of_h_h_transpose():
    rng = np.random.default_rng(7)
    for t1, t2 in rng.uniform(-3.0, 3.0, (200, 2)):
        if abs(math.sin(t2)) < 0.05 or abs(math.cos(t2) + 0.2) < 0.05:
            continue  # near-singular or near-round ellipses have no well-defined major axis
        q = np.array([t1, t2, 0.5, 0.0])
        got = major_axis_angle(velocity_ellipsoid(q, rows=(0, 1)))
        assert -90.0 < got <= 90.0
        diff = (got - _major_by_eigh(q) + 90.0) % 180.0 - 90.0
        assert abs(diff) < 1e-7, (q, got)


def test_base_turn_figure_turns_the_ellipses_rigidly_with_the_arm():
    fig = base_turn_figure(theta1_deg=[0, 20, 60], theta2=math.pi / 4)
    steps = fig.layout.sliders[0].steps
    assert [s.label for s in steps] == ["0", "20", "60"]
    w = P.a1 * P.a2 * math.sin(math.pi / 4)
    angles = []
    for s in steps:
        q = np.array([math.radians(float(s.label)), math.pi / 4, 0.5 * P.d0, 0.0])
        data, layout, idx = s.args
        arm_x, arm_y = data["x"][0], data["y"][0]
        assert np.allclose([arm_x[-1], arm_y[-1]], pose(q)[:2], atol=1e-4)          # the arm drawn at q
        line1, line2 = title_lines(layout["title.text"])
        major = _major_by_eigh(q)
        assert line1 == f"θ1 = {float(s.label):.0f}°: w = {w:.3f} m², major axis {major:.1f}°"
        assert math.isclose(manipulability(q), w, rel_tol=1e-12)
        angles.append(major)
        sv = np.linalg.svd(jacobian(q)[:2, :2], compute_uv=False)
        assert line2.startswith(f"σ: {sv[0]:.3f}, {sv[1]:.3f} m/s; 1/σ: {1 / sv[0]:.3g}, {1 / sv[1]:.3g} N")
    # turning theta1 by +d turns the picture by -d seen from above (frame 0 points down)
    for a, b, d in ((angles[0], angles[1], 20.0), (angles[0], angles[2], 60.0)):
        assert abs((b - a + d + 90.0) % 180.0 - 90.0) < 1e-9


@pytest.mark.parametrize("kwargs, error", [
    (dict(theta1_deg=[10.0]), "2 and 61"), (dict(theta1_deg=np.arange(62.0)), "2 and 61"),
    (dict(scale=0.0), "> 0"), (dict(theta2=float("nan")), "not finite"), (dict(theta2="45°"), "an angle in rad"),
])
def test_base_turn_figure_refuses_bad_arguments(kwargs, error):
    with pytest.raises(ScaraError, match=error):
        base_turn_figure(**kwargs)


# -------------------------------------------------------------------------------------------------------------- panel
def test_manipulability_panel_reports_bad_scale():
    from scara.widgets import manipulability_panel

    panel = quiet(manipulability_panel)
    assert panel.last_error is None and set(panel.controls) == {"theta1", "theta2", "scale"}
    quiet(setattr, panel.controls["scale"], "value", 0.0)
    assert "scale is 0" in panel.last_error and "above 0" in panel.last_error
    quiet(setattr, panel.controls["scale"], "value", 0.2)
    quiet(setattr, panel.controls["theta2"], "value", 0.0)  # singular: drawn, not an error
    assert panel.last_error is None
    with pytest.raises(ScaraError):
        manipulability_panel(scale=-1.0)


def test_workspace_ellipses_figure_draws_the_arms_of_one_ring():
    # 24 arms tangle into a web over the ellipses: the arms of the outer ring only
    fig = workspace_ellipses_figure(workspace_points())
    arms = [s for s in _strokes(*xy(fig.data[0]))]
    assert len(arms) == 8


def _extent(fig, k, step=None):
    x = fig.data[k].x if step is None else step.args[0]["x"][k]
    y = fig.data[k].y if step is None else step.args[0]["y"][k]
    x, y = np.array(x, dtype=float), np.array(y, dtype=float)
    return np.nanmin(x), np.nanmax(x), np.nanmin(y), np.nanmax(y)


def test_base_turn_figure_range_holds_the_ellipses_at_every_step():
    fig = base_turn_figure()
    xr, yr = fig.layout.xaxis.range, fig.layout.yaxis.range
    for step in fig.layout.sliders[0].steps:
        for k in range(len(step.args[0]["x"])):
            x0, x1, y0, y1 = _extent(fig, k, step)
            assert xr[0] < x0 and x1 < xr[1] and yr[0] < y0 and y1 < yr[1], (step.label, k)


def test_reference_ellipses_figure_range_holds_the_reach_circle():
    fig = reference_ellipses_figure()
    xr, yr = fig.layout.xaxis.range, fig.layout.yaxis.range
    r = 1.0
    assert xr[0] < -r and xr[1] > r and yr[0] < -r and yr[1] > r
