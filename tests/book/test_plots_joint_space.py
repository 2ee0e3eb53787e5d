"""Figures of chapter 3's section Joint-space trajectories (scara.plots.trajectory.joint_space_figure) and the
placement of the waypoint labels of the path figures (Fig. 3.2, 3.3): what each slider step draws is checked
against the package's joint-space trajectory and the direct kinematics, the labels against boxes measured in
Chromium, and the figures against the book's reading rules."""
from __future__ import annotations

import re

import numpy as np
import pytest

from scara import ScaraError, pose, reference_trajectory
from scara.plots.trajectory import (
    _LABEL_POSITIONS, _TOP_VIEW_SCALES, _box_hits_polyline, _boxes_overlap, _label_box, _place_waypoint_labels, _text_width,
    joint_space_figure, joint_space_series, path_figure, top_view_figure, top_view_series,
)
from scara.trajectory import joint_counterpart, path_deviation

from _figure_rules import check_axis_titles_with_units, check_reads_on_a_laptop_and_a_phone


@pytest.fixture(scope="module")
def traj():
    return reference_trajectory()


@pytest.fixture(scope="module")
def fig(traj):
    return joint_space_figure(traj, extras=(0, 1, 3))


def test_each_slider_step_draws_the_counterpart_with_that_many_knots(traj, fig):
    (sl,) = fig.layout.sliders
    assert [s.label for s in sl.steps] == ["0", "1", "3"]
    for step, extra in zip(sl.steps, (0, 1, 3)):
        data, layout, idx = step.args
        assert list(idx) == [1, 2, 3]
        jt = joint_counterpart(traj, "cubic", extra=extra)
        # the knots: the tool at the knot times, by the direct kinematics of the knots themselves
        knots = pose(jt.points)
        np.testing.assert_allclose(np.c_[data["x"][1], data["y"][1]], knots[:, :2], atol=1e-5)
        assert len(data["x"][1]) == len(jt.times) == 12 + 11 * extra
        # the tool path: forward kinematics of the sampled joint motion at the drawn times
        t = np.asarray(data["x"][2], float)
        k = np.round(t / jt.dt).astype(int)
        np.testing.assert_allclose(t, jt.t[k], atol=1e-4)
        np.testing.assert_allclose(np.c_[data["x"][0], data["y"][0]], pose(jt.q[k])[:, :2], atol=1e-5)
        # the distance and the title's largest one: path_deviation, and the farthest sample is drawn
        d = path_deviation(jt, traj)
        np.testing.assert_allclose(np.asarray(data["y"][2], float), 1000 * d[k], atol=1e-3)
        title = layout["title.text"]
        shown = float(re.search(r"up to ([0-9.]+) mm", title).group(1))
        assert abs(shown - 1000 * d.max()) <= 0.05 + 1e-9 and f"{12 + 11 * extra} knots" in title
        assert np.max(np.asarray(data["y"][2], float)) == pytest.approx(1000 * d.max(), abs=1e-3)


def test_the_first_step_is_what_the_page_shows(fig):
    data, layout, _ = fig.layout.sliders[0].steps[0].args
    np.testing.assert_array_equal(np.asarray(fig.data[1].x), np.asarray(data["x"][0]))
    np.testing.assert_array_equal(np.asarray(fig.data[3].y), np.asarray(data["y"][2]))
    assert fig.layout.title.text == layout["title.text"]


def test_more_knots_bring_the_tool_closer(traj):
    mm = [joint_space_series(traj, e, points=200)["max_mm"] for e in (0, 3, 15)]
    assert mm[0] > mm[1] > mm[2]


def test_quintic_and_titles(traj):
    f = joint_space_figure(traj, extras=(0, 1), kind="quintic", points=300)
    assert f.layout.title.text.startswith("Quintic, 12 knots")


def test_reading_rules(fig):
    check_reads_on_a_laptop_and_a_phone("joint space", fig)
    check_axis_titles_with_units("joint space", fig)
    # the two curves of the joint-space trajectory are told apart from the operational path in greyscale
    assert fig.data[0].line.dash in (None, "solid") and fig.data[1].line.dash == "dash"


@pytest.mark.parametrize("kwargs, words", [
    (dict(extras=(0,)), ["between 2 and 10 values", "got 1"]),
    (dict(extras=(0, 1.5)), ["extras entry = 1.5", "whole number"]),
    (dict(extras=(0, 2000)), ["extras entry = 2000", "<= 1000"]),
    (dict(extras="0, 1"), ["extras must be a sequence"]),
    (dict(kind="linear"), ["kind = 'linear'"]),
    (dict(points=1), ["points = 1", "2 <= "]),
    (dict(extras=tuple(range(10)), points=10_001), ["points = 10001", "<= 10000"]),
])
def test_bad_input_is_refused_before_any_work(traj, kwargs, words):
    with pytest.raises(ScaraError) as info:
        joint_space_figure(traj, **kwargs)
    for w in words:
        assert w in str(info.value), (w, str(info.value))
    with pytest.raises(ScaraError, match="expected a Trajectory"):
        joint_space_figure("the reference")


# --------------------------------------------------------------------------------------------------
# the waypoint labels of Fig. 3.2 and 3.3
# --------------------------------------------------------------------------------------------------
def test_label_boxes_are_the_ones_measured_in_chromium():
    """Boxes of a 12 px label "p10" (20.3 px wide) around a marker of size 10, measured in Chromium."""
    measured = {"top center": (-10.0, -21.2, 10.3, -7.2), "bottom right": (7.2, 5.2, 27.6, 19.2),
                "middle left": (-27.3, -8.0, -6.9, 6.0)}
    assert abs(_text_width("p10", 12) - 20.3) < 0.5
    for pos, box in measured.items():
        got = _label_box(pos, 0.0, 0.0, 20.3)
        assert np.allclose(got, box, atol=0.5), (pos, got)


def _labels(fig):
    return [(float(x), float(y), text, pos) for tr in fig.data if tr.name in ("stop point", "via point")
            for x, y, text, pos in zip(tr.x, tr.y, tr.text, tr.textposition) if text]


def _note_box(a, s):
    """The screen box (px, y down) of a 2-D label annotation ``a`` of a top view drawn at ``s`` px per m."""
    x, y, w = a.x * s, -a.y * s, _text_width(a.text, 12)
    if a.showarrow:                          # a label further out, centred where its leader line starts
        return x + a.ax - w / 2, y + a.ay - 7.0, x + a.ax + w / 2, y + a.ay + 7.0
    x0 = {"left": x + a.xshift, "right": x + a.xshift - w, "center": x - w / 2}[a.xanchor]
    y0 = {"bottom": y - a.yshift - 14.0, "top": y - a.yshift, "middle": y - a.yshift - 7.0}[a.yanchor]
    return x0, y0, x0 + w, y0 + 14.0


def test_top_view_labels_neither_overlap_nor_cover_the_arc(traj):
    fig = top_view_figure(traj)
    notes = fig.layout.annotations
    assert {a.text for a in notes} >= {"p0 = p11", "p1", "p9", "p10"} and len(notes) == 11
    for a in notes:                          # each anchored at its waypoint
        i = traj.labels.index(a.text.split(" = ")[0])
        assert np.allclose([a.x, a.y], traj.waypoints[i, :2]) and (a.xref, a.yref) == ("x", "y")
    assert not any("text" in tr.mode for tr in fig.data if tr.name in ("stop point", "via point"))
    arc = traj.x[(traj.t >= traj.segment_start[10]) & (traj.t <= traj.segment_end[10]), :2][::50]
    for s in _TOP_VIEW_SCALES:
        boxes = [(_note_box(a, s), a.text) for a in notes]
        for i, (a, ta) in enumerate(boxes):
            assert not _box_hits_polyline(a, arc * [s, -s]), (s, ta)
            for b, tb in boxes[i + 1:]:
                assert not _boxes_overlap(a, b, pad=0.0), (s, ta, tb)
    # the coincident points share one label
    assert sum("p11" in a.text for a in notes) == 1
    series = top_view_series(traj)
    assert sum("p11" in t for t in series["stop"]["text"]) == 1


def test_path_figure_labels_stay_apart_on_the_screen(traj):
    fig = path_figure(traj)
    # scene annotations, anchored by plotly exactly at their points (crowded ones with a leader line)
    notes = fig.layout.scene.annotations
    labels = [a.text for a in notes]
    assert len(labels) == 11 and "p0 = p11" in labels
    for a in notes:
        i = traj.labels.index(a.text.split(" = ")[0])
        assert np.allclose([a.x, a.y, a.z], traj.waypoints[i])
    assert not any("text" in tr.mode for tr in fig.data if tr.name in ("stop point", "via point"))
    lay = fig.layout.scene
    for ax, c in ((lay.xaxis, 0), (lay.yaxis, 1), (lay.zaxis, 2)):
        # every point strictly inside the box (plotly hides a label drawn outside it)
        assert ax.range[0] < traj.waypoints[:, c].min() and ax.range[1] > traj.waypoints[:, c].max()


def test_place_waypoint_labels_separates_two_crowded_points():
    # two points 10 px apart on a horizontal line: both labels above would overlap
    views = [dict(points=np.array([[0.0, 0.0], [10.0, 0.0]]), curves=[np.array([[-100.0, 0.0], [100.0, 0.0]])])]
    pos = _place_waypoint_labels(views, ["p9", "p10"])
    a, b = (_label_box(p_, x, y, _text_width(t, 12)) for p_, (x, y), t in zip(pos, views[0]["points"], ("p9", "p10")))
    assert not _boxes_overlap(a, b) and all(p_ in _LABEL_POSITIONS for p_ in pos)
    assert _place_waypoint_labels(views, ["p9", ""])[1] == "top center"   # an empty label is left alone
