"""The schematic of the DH frames of chapter 1 (:func:`scara.plots.frames_figure`) and the frame labels of the 3-D
views (Fig. 1.1 and 1.3): one label per distinct frame position in each view, label boxes that never overlap at
the figure's width and on a 390-px phone page (boxes estimated here from each label's text, font size, anchor and
offset, with the panels' data-to-pixel scale worked out from the layout), frame origins drawn where
``link_frames(q)`` puts them, and bad input refused."""
from __future__ import annotations

import math

import numpy as np
import plotly.graph_objects as go
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
# An independent model of plotly's 3-D view (the matrices gl-plot3d builds): a model matrix mapping each axis range
# onto [-a/2, a/2] for its aspect ratio a, a look-at view matrix from the camera's eye to its centre with +z up,
# a 45° perspective, then clip coordinates to the pixels of the plot area. The frame names are annotations pinned
# at 3-D points and moved by (xshift, yshift) px from where the point is drawn.
FIGURE_WIDTHS = (312, 342, 1240)  # a 360-px and a 390-px phone page, a laptop


def _look_at(eye, centre):
    f = np.asarray(centre, float) - eye
    f /= np.linalg.norm(f)
    s = np.cross(f, [0.0, 0.0, 1.0])
    s /= np.linalg.norm(s)
    u = np.cross(s, f)
    m = np.eye(4)
    m[0, :3], m[1, :3], m[2, :3] = s, u, -f
    m[:3, 3] = -m[:3, :3] @ eye
    return m


def _pixels(fig, points, width):
    """(n, 2) pixel positions, x from the figure's left edge and y up from its bottom, of 3-D ``points``."""
    lay = fig.layout
    sc = lay.scene
    ranges = np.array([sc.xaxis.range, sc.yaxis.range, sc.zaxis.range], float)
    aspect = np.array([sc.aspectratio.x, sc.aspectratio.y, sc.aspectratio.z], float)
    model = np.eye(4)
    model[[0, 1, 2], [0, 1, 2]] = aspect / (ranges[:, 1] - ranges[:, 0])
    model[:3, 3] = -ranges.mean(axis=1) * model[[0, 1, 2], [0, 1, 2]]
    eye = np.array([sc.camera.eye.x, sc.camera.eye.y, sc.camera.eye.z], float)
    centre = np.array([sc.camera.center.x, sc.camera.center.y, sc.camera.center.z], float)
    w = width - lay.margin.l - lay.margin.r
    h = lay.height - lay.margin.t - lay.margin.b
    f = 1 / math.tan(math.pi / 8)
    proj = np.array([[f * h / w, 0, 0, 0], [0, f, 0, 0], [0, 0, -1, -0.02], [0, 0, -1, 0]])
    hom = np.c_[np.asarray(points, float), np.ones(len(points))]
    clip = (proj @ _look_at(eye, centre) @ model @ hom.T).T
    ndc = clip[:, :2] / clip[:, 3:]
    return np.c_[lay.margin.l + (ndc[:, 0] + 1) / 2 * w, lay.margin.b + (ndc[:, 1] + 1) / 2 * h]


def _annotation_boxes(fig, notes, width):
    pts = _pixels(fig, [[a.x, a.y, a.z] for a in notes], width)
    out = []
    for a, (px, py) in zip(notes, pts):
        w = sum(_char_width(c, a.font.size) for c in a.text) + 2 * (a.borderpad or 1)
        h = 1.3 * a.font.size + 2 * (a.borderpad or 1)
        x0 = px + a.xshift - {"left": 0, "center": w / 2, "right": w}[a.xanchor]
        y0 = py + a.yshift - {"bottom": 0, "middle": h / 2, "top": h}[a.yanchor]
        out.append((a.text, (x0, y0, x0 + w, y0 + h)))
    return out


def _check_names(fig, notes, where):
    lay = fig.layout
    for width in FIGURE_WIDTHS:
        boxes = _annotation_boxes(fig, notes, width)
        for i in range(len(boxes)):
            t1, b1 = boxes[i]
            # inside the plot area
            assert lay.margin.l - 1 <= b1[0] and b1[2] <= width - lay.margin.r + 1, (where, width, t1, b1)
            assert lay.margin.b - 1 <= b1[1] and b1[3] <= lay.height - lay.margin.t + 1, (where, width, t1, b1)
            for t2, b2 in boxes[i + 1:]:
                apart = b1[2] <= b2[0] or b2[2] <= b1[0] or b1[3] <= b2[1] or b2[3] <= b1[1]
                assert apart, (where, width, t1, [round(v) for v in b1], t2, [round(v) for v in b2])


@pytest.mark.parametrize("q", [c for c in CONFIGS if c is not None]
                         + [[0.0, math.pi * 0.97, 0.3, 0.0], [0.0, math.pi, 0.3, 0.0]])
def test_3d_frame_names_do_not_overlap(q):
    g = arm_geometry(q)
    assert len(g["labels"]) == len(g["origins"]) == len(set(g["labels"]))
    fig = arm_figure(q, names="annotations")
    notes = fig.layout.scene.annotations
    assert [a.text for a in notes] == g["labels"]
    assert np.allclose([[a.x, a.y, a.z] for a in notes], g["origins"], atol=1e-4)  # pinned to the origins
    _check_names(fig, notes, q)
    # the same names as a 3-D text trace (the live panel's): each centred on its point, where the annotation's
    # box has its centre, so the boxes are the same and do not overlap either
    fig_text = arm_figure(q)
    names = fig_text.data[-1]
    assert names.name == "frame names" and list(names.text) == g["labels"] and names.textposition == "middle center"
    for width in FIGURE_WIDTHS:
        centres = _pixels(fig_text, np.c_[names.x, names.y, names.z], width)
        boxes = _annotation_boxes(fig, notes, width)
        for (text, b), c in zip(boxes, centres):
            assert np.allclose(c, [(b[0] + b[2]) / 2, (b[1] + b[3]) / 2], atol=3.0), (q, width, text, c, b)


@pytest.mark.parametrize("joint", [0, 1, 2, 3])
def test_3d_slider_frame_names_do_not_overlap_at_any_step(joint):
    fig = joint_slider_figure([0.0, math.radians(60), 0.5, 0.0], joint=joint)
    steps = fig.layout.sliders[0].steps
    for s in steps:
        notes = [go.layout.scene.Annotation(a) for a in s.args[1]["scene.annotations"]]
        q = np.array([0.0, math.radians(60), 0.5, 0.0])
        q[joint] = float(s.label) if joint == 2 else math.radians(float(s.label))
        g = arm_geometry(q)
        assert [a.text for a in notes] == g["labels"], s.label
        assert np.allclose([[a.x, a.y, a.z] for a in notes], g["origins"], atol=1e-4), s.label
        _check_names(fig, notes, (joint, s.label))
    # the figure opens on its active step, names included
    active = steps[fig.layout.sliders[0].active].args[1]["scene.annotations"]
    assert [a.text for a in fig.layout.scene.annotations] == [a["text"] for a in active]


def test_3d_triads_are_an_eighth_of_the_scene():
    fig = joint_slider_figure([0.0, math.radians(60), 0.5, 0.0], joint=1)
    # triads of 0.3 m: an eighth of the 2.4-m wide scene
    xs = fig.data[2]
    seg = np.array([[xs.x[0], xs.y[0], xs.z[0]], [xs.x[1], xs.y[1], xs.z[1]]], float)
    assert np.linalg.norm(seg[1] - seg[0]) >= 0.25
