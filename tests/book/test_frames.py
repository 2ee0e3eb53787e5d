"""The schematic of the DH frames of chapter 1 (:func:`scara.plots.frames_figure`) and the frame labels of the 3-D
views (Fig. 1.1 and 1.3): one label per distinct frame position in each view, label boxes that never overlap at
the figure's width and on a 390-px phone page (boxes estimated here from each label's text, font size, anchor and
offset, with the panels' data-to-pixel scale worked out from the layout), frame origins drawn where
``link_frames(q)`` puts them, and bad input refused."""
from __future__ import annotations

import math

import numpy as np
import pytest

from scara import ScaraError, ScaraParams, link_frames
from scara.plots import arm_figure, frames_figure, joint_slider_figure
from scara.plots.kinematics import arm_geometry

from _figure_rules import check_axis_titles_with_units, check_reads_on_a_laptop_and_a_phone

P = ScaraParams()
Q_BOOK = [math.radians(40), math.radians(-70), 0.3, math.radians(45)]
CONFIGS = [
    None,  # the default: the configuration of Fig. 1.1
    Q_BOOK,
    [0.0, math.radians(60), 0.5, 0.0],
    [math.radians(-30), math.radians(100), 0.8, math.radians(-60)],
    [math.radians(120), math.radians(-45), 0.0, math.radians(10)],  # quill up: frames 2, 3, 4, e coincide
    [math.radians(10), 0.0, 1.0, 0.0],  # stretched, quill at the floor
]
NAMES = ("b", "0", "1", "2", "3", "4", "e")


# --------------------------------------------------------------------------- an independent pixel model
def _char_width(ch: str, size: float) -> float:
    """A generous width (px) of one glyph of plotly's sans-serif font."""
    if ch in "mwMW":
        w = 10.0
    elif ch in "ijl.,:;! ":
        w = 4.0
    elif ch.isupper() or ch.isdigit():
        w = 7.5
    else:
        w = 7.0
    return w * size / 12


def _panels(fig, width):
    """{xref: (left px, bottom px, px per m, xmin, ymin)}: the equal-scale panels shown ``width`` px wide."""
    lay = fig.layout
    W = width - lay.margin.l - lay.margin.r
    H = lay.height - lay.margin.t - lay.margin.b
    out = {}
    for xa, ya in (("xaxis", "yaxis"), ("xaxis2", "yaxis2")):
        xr, yr = lay[xa].range, lay[ya].range
        (dx0, dx1), (dy0, dy1) = lay[xa].domain, lay[ya].domain
        assert lay[ya].scaleanchor == ("x" if xa == "xaxis" else "x2") and lay[ya].scaleratio == 1
        dw, dh = W * (dx1 - dx0), H * (dy1 - dy0)
        s = min(dw / (xr[1] - xr[0]), dh / (yr[1] - yr[0]))
        left = lay.margin.l + W * dx0 + (dw - s * (xr[1] - xr[0])) / 2
        bottom = lay.margin.b + H * dy0 + (dh - s * (yr[1] - yr[0])) / 2
        out["x" if xa == "xaxis" else "x2"] = (left, bottom, s, xr[0], yr[0])
    return out


def _boxes(fig, width):
    panels = _panels(fig, width)
    out = []
    for a in fig.layout.annotations:
        if a.name != "label":
            continue
        left, bottom, s, xmin, ymin = panels[a.xref]
        px, py = left + s * (a.x - xmin) + (a.xshift or 0), bottom + s * (a.y - ymin) + (a.yshift or 0)
        size = a.font.size
        w = sum(_char_width(c, size) for c in a.text)
        h = 1.3 * size
        x0 = px - {"left": 0, "center": w / 2, "right": w}[a.xanchor]
        y0 = py - {"bottom": 0, "middle": h / 2, "top": h}[a.yanchor]
        out.append((a.xref, a.text, (x0, y0, x0 + w, y0 + h)))
    return out


def _labels(fig, xref):
    return [a for a in fig.layout.annotations if a.name == "label" and a.xref == xref]


def _expected_groups(q, cols):
    frames = np.concatenate([np.eye(4)[None], link_frames(q if q is not None else Q_BOOK, P)])
    groups = []
    for name, o in zip(NAMES, frames[:, cols, 3]):
        for g in groups:
            if np.allclose(g[1], o, atol=1e-6):
                g[0].append(name)
                break
        else:
            groups.append(([name], o))
    return {", ".join(n): o for n, o in groups}


# --------------------------------------------------------------------------- the schematic
@pytest.mark.parametrize("q", CONFIGS)
def test_one_label_per_distinct_frame_position_in_each_view(q):
    fig = frames_figure(q)
    for xref, cols in (("x", [0, 1]), ("x2", [0, 2])):
        expected = _expected_groups(q, cols)
        frame_labels = {a.text: (a.x, a.y) for a in _labels(fig, xref) if a.text[0] in "b01234e"}
        assert set(frame_labels) == set(expected), (xref, frame_labels.keys(), expected.keys())
        for text, o in expected.items():  # each label is pinned to its frame's origin
            assert np.allclose(frame_labels[text], o, atol=1e-9), text
    top = {a.text for a in _labels(fig, "x")}
    side = {a.text for a in _labels(fig, "x2")}
    assert {"a1", "a2"} <= top and "d0" in side
    for k, name in ((0, "θ1"), (1, "θ2"), (3, "θ4")):  # an angle is marked unless it is zero
        assert (name in top) == (q is None or abs(q[k]) > 1e-3), name
    if q is None or q[2] > 0:
        assert "d3" in side


@pytest.mark.parametrize("q", CONFIGS)
@pytest.mark.parametrize("width", [390, 700])
def test_label_boxes_do_not_overlap(q, width):
    fig = frames_figure(q)
    boxes = _boxes(fig, width)
    for i in range(len(boxes)):
        for j in range(i + 1, len(boxes)):
            (_, t1, b1), (_, t2, b2) = boxes[i], boxes[j]
            apart = b1[2] <= b2[0] or b2[2] <= b1[0] or b1[3] <= b2[1] or b2[3] <= b1[1]
            assert apart, (width, t1, [round(v) for v in b1], t2, [round(v) for v in b2])


def test_frame_origins_drawn_where_link_frames_puts_them():
    q = [math.radians(-25), math.radians(80), 0.45, math.radians(30)]
    fig = frames_figure(q)
    frames = np.concatenate([np.eye(4)[None], link_frames(q, P)])
    arm = [t for t in fig.data if t.name == "arm"]
    assert len(arm) == 2
    top, side = arm
    # base, top of the column (frame 0), elbow (1), top of the quill (2), gripper (e)
    assert np.allclose(np.c_[top.x, top.y], np.array([[0, 0], *frames[[1, 2, 3, 6], :2, 3]]), atol=1e-12)
    assert np.allclose(np.c_[side.x, side.y], np.array([[0, 0], *frames[[1, 2, 3, 6]][:, [0, 2], 3]]), atol=1e-12)
    # the x axes drawn from every origin shown in the view start at the frames' origins
    xs = [t for t in fig.data if t.name == "x axes" and t.xaxis in (None, "x") and t.mode == "lines"][0]
    starts = np.array([(x, y) for x, y, prev in zip(xs.x, xs.y, [None] + list(xs.x[:-1])) if x is not None
                       and prev is None], float)
    assert np.allclose(starts, frames[:, :2, 3], atol=1e-12)


def test_default_configuration_and_page_rules():
    fig = frames_figure()
    check_reads_on_a_laptop_and_a_phone("frames", fig)
    check_axis_titles_with_units("frames", fig)
    assert fig.layout.height <= 560
    assert {a.text for a in _labels(fig, "x")} >= {"b, 0", "1", "2, 3, 4, e"}
    assert {a.text for a in _labels(fig, "x2")} >= {"b", "0", "1", "2", "3, 4, e"}


@pytest.mark.parametrize("bad", [[0.0, 0.0, 0.0], [0.0, float("nan"), 0.1, 0.0], "abc", [0, 0, 0, 1e9]])
def test_bad_q_raises(bad):
    with pytest.raises(ScaraError):
        frames_figure(bad)


def test_bad_p_raises():
    with pytest.raises(ScaraError):
        frames_figure(None, p="robot")


# --------------------------------------------------------------------------- the 3-D views
def _apart(points, gap=0.15):
    pts = np.asarray(points, float)
    d = np.linalg.norm(pts[:, None] - pts[None], axis=-1) + np.eye(len(pts)) * 1e9
    return d.min() >= gap


@pytest.mark.parametrize("q", [c for c in CONFIGS if c is not None]
                         + [[0.0, math.pi * 0.97, 0.3, 0.0], [0.0, math.pi, 0.3, 0.0]])
def test_3d_labels_at_distinct_positions(q):
    g = arm_geometry(q)
    assert len(g["labels"]) == len(g["label_points"]) == len(set(g["labels"]))
    assert _apart(g["label_points"]), (g["labels"], g["label_points"])
    fig = arm_figure(q)
    names = fig.data[-1]
    assert names.name == "frame names" and list(names.text) == g["labels"]
    assert _apart(np.c_[names.x, names.y, names.z])


def test_3d_slider_labels_at_distinct_positions_and_triads_larger():
    fig = joint_slider_figure([0.0, math.radians(60), 0.5, 0.0], joint=1)
    for s in fig.layout.sliders[0].steps:
        data = s.args[0]
        pts = np.c_[data["x"][-1], data["y"][-1], data["z"][-1]]
        assert _apart(pts), s.label
    # triads of 0.3 m: an eighth of the 2.4-m wide scene
    xs = fig.data[2]
    seg = np.array([[xs.x[0], xs.y[0], xs.z[0]], [xs.x[1], xs.y[1], xs.z[1]]], float)
    assert np.linalg.norm(seg[1] - seg[0]) >= 0.25
