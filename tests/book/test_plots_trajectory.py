"""The figures of scara.plots.trajectory (the timing law, the path in 3-D and from above, the profiles, the corners
and their anticipation, the joint profiles): the drawn curves agree with the laws of chapter 3 written out
independently of scara.trajectory, and the counts beyond a figure's limits are refused before any work. The
joint-space figure and the waypoint labels are tested in test_plots_joint_space.py; ``traj`` is the session's
reference trajectory (tests/conftest.py)."""
from __future__ import annotations

import math

import numpy as np
import pytest

from scara import ScaraError, plan_path, plots, reference_plan
from scara.plots import (anticipation_slider_figure, corner_figure, joint_profiles_figure, path_figure,
                         profiles_figure, timing_law_figure, top_view_figure)
from scara.plots.trajectory import decimate

from _plots_shared import P, refusal


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


@pytest.mark.parametrize("build, kwargs, names", [
    ("path_figure", dict(points=-5), ("points = -5", "2 <= ")),
    ("top_view_figure", dict(points=True), ("points = True", "whole number")),
    ("profiles_figure", dict(points=10**9), ("points = 1000000000", "<= 10000")),
    ("joint_profiles_figure", dict(points=20_001), ("points = 20001", "<= 10000")),
    ("anticipation_slider_figure", dict(points=10_000), ("13 values × points 10000", "<= 100000")),
])
def test_trajectory_figures_refuse_counts_beyond_their_limits_before_any_work(traj, build, kwargs, names):
    first = reference_plan() if build == "anticipation_slider_figure" else traj
    args = (first, 4) if build == "anticipation_slider_figure" else (first,)
    message = refusal(getattr(plots, build), *args, **kwargs)
    for text in names:
        assert text in message


def test_anticipation_slider_opens_at_the_plans_anticipation():
    from scara.trajectory import reference_plan
    plan = reference_plan()
    fig = anticipation_slider_figure(plan, 4)
    (sl,) = fig.layout.sliders
    assert float(sl.steps[sl.active].label) == plan["waypoints"][4].anticipation == 2.0
    assert fig.layout.title.text.startswith("Anticipation at p4: 2 s")


def test_point_labels_sit_below_right_off_the_curves(traj):
    # the curves run above-right of p4's corner and of the minimum of w: the labels go below-right
    fig = joint_profiles_figure(traj)
    (mark,) = [t for t in fig.data if t.name == "min w"]
    assert mark.textposition == "bottom right"
    assert fig.layout.yaxis3.range[0] < 0 < fig.layout.yaxis3.range[1]
