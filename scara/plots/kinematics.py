"""Figures of chapter 1 (kinematics): the arm and its DH frames in 3-D, a joint sweep with slider steps, both
inverse-kinematics solutions of a target seen from above, and the Jacobian determinant against theta2.

Every builder takes joint vectors ``q = [theta1, theta2, d3, theta4]`` (rad, rad, m, rad) and an optional
parameter object ``p`` (``None`` means ``ScaraParams()``), calls :mod:`scara.kinematics` for the geometry
and returns a ``plotly.graph_objects.Figure``.
"""
from __future__ import annotations

import math

import numpy as np
import plotly.graph_objects as go

from ..errors import ScaraError, UnreachableError, as_array, as_vector, check_count
from ..kinematics import ikine, jacobian, link_frames, pose
from ..params import ScaraParams
from ._common import AXIS_COLOURS, DASHES, JOINT_NAMES, PALETTE, as_list, slider
from ._common import MAX_POINTS, FIGURE_BUDGET
from .panels import FigurePair
from .layout import _text_width, finish_layout
# still importable from here, where they lived before scara.plots.layout (the figure rules of tests/ use them)

__all__ = [
    "FRAME_NAMES",
    "ELBOW_COLOURS",
    "arm_geometry",
    "scene_projection",
    "frame_label_annotations",
    "frame_names_trace",
    "arm_figure",
    "joint_slider_figure",
    "top_view_arm",
    "top_axes",
    "inverse_kinematics_figure",
    "inverse_kinematics_slider_figure",
    "determinant_figure", "arm_pair", "inverse_kinematics_pair",
]

#: names of the frames drawn by :func:`arm_figure`: the base frame, then the six of :func:`link_frames`
FRAME_NAMES = ("b", "0", "1", "2", "3", "4", "e")
#: one colour and dash per elbow solution (+1: sin theta2 >= 0, -1: sin theta2 <= 0), told apart in greyscale too
ELBOW_COLOURS = {+1: "#0072B2", -1: "#E69F00"}
ELBOW_DASHES = {+1: "solid", -1: "dash"}
_TRIAD_NAMES = ("x axes", "y axes", "z axes")


def arm_geometry(q, p=None, triad: float = 0.3) -> dict:
    """Points to draw the arm at ``q`` in the base frame.

    Returns a dict with
    ``"arm"`` (5, 3): base, frame-0 origin (top of the column, height ``d0``), elbow, end of link 2, end
    effector (bottom of the quill);
    ``"triads"``: three arrays (3 * 7, 3), the x, y and z axes (length ``triad`` m) of the frames
    ``b, 0, 1, 2, 3, 4, e`` as segments separated by NaN rows;
    ``"origins"`` (n, 3) and ``"labels"``: the distinct frame origins and their names, coincident frames
    sharing one label (frames 3, 4 and e share the end-effector origin).

    Raises :class:`ShapeError`/:class:`NonFiniteError` for a bad ``q``.
    """
    p = ScaraParams.resolve(p)
    if not (isinstance(triad, (int, float)) and math.isfinite(triad) and triad > 0):
        raise ScaraError(f"triad = {triad!r} must be a positive length in metres")
    frames = np.concatenate([np.eye(4)[None], link_frames(q, p)])  # b, 0, 1, 2, 3, 4, e
    origins = frames[:, :3, 3]
    arm = np.array([[0.0, 0.0, 0.0], origins[1], origins[2], origins[3], origins[6]])
    triads = []
    for k in range(3):
        seg = np.full((3 * len(frames), 3), np.nan)
        seg[0::3] = origins
        seg[1::3] = origins + triad * frames[:, :3, k]
        triads.append(seg)
    # one label per distinct origin, e.g. "3, 4, e" at the end effector
    labels, label_pts = [], []
    for name, o in zip(FRAME_NAMES, origins):
        for i, other in enumerate(label_pts):
            if np.linalg.norm(other - o) < 1e-9:
                labels[i] += f", {name}"
                break
        else:
            labels.append(name)
            label_pts.append(o)
    return {"arm": arm, "triads": triads, "origins": np.array(label_pts), "labels": labels}


_CAMERA_EYE = (1.05, -1.35, 0.75)
_CAMERA_CENTRE = (0.0, 0.0, -0.05)
#: font size (px) of the frame names in the 3-D views
LABEL_SIZE = 13
#: half the width (px) of the narrowest plot area a 3-D view is drawn in: a 360-px phone page, the figure's
#: side margins taken off; the frame names stay within it
_PHONE_HALF_WIDTH = 115
#: bottom margin (px) of a 3-D figure with a slider: the slider's pad (40 px), current value, rail and ticks
_SLIDER_ROOM = 134


def scene_projection(scene: dict, plot_height: float):
    """A function mapping points (n, 3) of the base frame (m) to where plotly draws them in a 3-D ``scene``
    (a layout dict with axis ``range`` s, a manual ``aspectratio`` and a ``camera``): (n, 2) pixel offsets from
    the centre of the plot area, x to the right and y up.

    plotly's model: each axis range maps onto ``[-a/2, a/2]`` for its aspect ratio ``a``; the camera looks from
    ``eye`` at ``center`` with ``up`` = +z, in a perspective of 45° vertical field of view. Since that field is
    fixed vertically, the offsets depend on the plot area's height only: the same at every page width."""
    ranges = np.array([scene[k]["range"] for k in ("xaxis", "yaxis", "zaxis")], float)
    aspect = np.array([scene["aspectratio"][k] for k in "xyz"], float)
    cam = scene.get("camera", {})
    eye = np.array([cam.get("eye", {}).get(k, 1.25) for k in "xyz"], float)
    centre = np.array([cam.get("center", {}).get(k, 0.0) for k in "xyz"], float)
    zc = (eye - centre) / np.linalg.norm(eye - centre)
    xc = np.cross([0.0, 0.0, 1.0], zc)
    xc /= np.linalg.norm(xc)
    yc = np.cross(zc, xc)
    focal = 1.0 / math.tan(math.pi / 8) * plot_height / 2  # pixels per unit of x/z in the camera frame

    def project(points):
        pts = np.atleast_2d(np.asarray(points, float))
        model = (pts - ranges.mean(axis=1)) / (ranges[:, 1] - ranges[:, 0]) * aspect
        rel = model - eye
        depth = -(rel @ zc)
        return focal * np.c_[rel @ xc, rel @ yc] / depth[:, None]
    return project


def _label_box(text, px, py, cand):
    """Box (left, bottom, right, top) in pixels of a frame name pinned at (px, py), moved by ``cand`` =
    ``(xshift, yshift, xanchor, yanchor)``; the text's width is estimated generously, plus 2 px of padding."""
    w = _text_width(text, LABEL_SIZE) + 6.0
    h = 1.35 * LABEL_SIZE + 4.0
    xs, ys, xa, ya = cand
    left = px + xs - {"left": 0.0, "center": w / 2, "right": w}[xa]
    bottom = py + ys - {"bottom": 0.0, "middle": h / 2, "top": h}[ya]
    return (left, bottom, left + w, bottom + h)


def _boxes_overlap(b1, b2, pad=3.0):
    return b1[0] < b2[2] + pad and b2[0] < b1[2] + pad and b1[1] < b2[3] + pad and b2[1] < b1[3] + pad


def _label_candidates(near=(6, 14, 24, 36, 50, 66)):
    """Offsets ``(xshift, yshift, xanchor, yanchor)`` around a point, nearest first; right and up first."""
    dirs = [(1, 1), (1, -1), (-1, 1), (-1, -1), (1, 0), (-1, 0), (0, 1), (0, -1)]
    out = []
    for r in near:
        for dx, dy in dirs:
            k = r / math.hypot(dx, dy)
            out.append((dx * k, dy * k, "left" if dx > 0 else "right" if dx < 0 else "center",
                        "bottom" if dy > 0 else "top" if dy < 0 else "middle"))
    return out


def _place_frame_names(g: dict, scene: dict, plot_height: float) -> list:
    """Where the names of the frames of :func:`arm_geometry` ``g`` go in the view of ``scene`` drawn
    ``plot_height`` px tall: ``[(text, origin (3,), offset, box), ...]``, each name moved off its frame's origin by
    a pixel ``offset = (xshift, yshift, xanchor, yanchor)`` chosen so that no two names overlap, none covers the
    arm or a triad where another place is free, and each stays within a phone page's plot area; ``box`` is the
    name's box (left, bottom, right, top) in pixels from the centre of the plot area, y up
    (:func:`scene_projection`: the offsets hold at every page width)."""
    project = scene_projection(scene, plot_height)
    origins = project(g["origins"])
    # the drawing the names should not cover: the arm and the triads, sampled along each segment
    samples = []
    for poly in [g["arm"], *g["triads"]]:
        for a, b in zip(poly[:-1], poly[1:]):
            if np.all(np.isfinite(a)) and np.all(np.isfinite(b)):
                samples.append(a + np.linspace(0.0, 1.0, 9)[:, None] * (b - a))
    drawn = project(np.vstack(samples))
    half_h = plot_height / 2
    out = []
    for text, o3, (px, py) in zip(g["labels"], g["origins"], origins):
        best, best_score = None, None
        for rank, cand in enumerate(_label_candidates()):
            box = _label_box(text, px, py, cand)
            if box[0] < -_PHONE_HALF_WIDTH or box[2] > _PHONE_HALF_WIDTH or box[1] < -half_h or box[3] > half_h:
                continue
            if any(_boxes_overlap(box, other[3]) for other in out):
                continue
            inside = (drawn[:, 0] > box[0]) & (drawn[:, 0] < box[2]) & (drawn[:, 1] > box[1]) & (drawn[:, 1] < box[3])
            score = int(inside.sum()) + 0.5 * rank
            if best_score is None or score < best_score:
                best, best_score = cand, score
        if best is None:  # nowhere free within the phone's plot area: the last resort, far above
            best = (0.0, 80.0, "center", "bottom")
        out.append((text, o3, best, _label_box(text, px, py, best)))
    return out


def frame_label_annotations(g: dict, scene: dict, plot_height: float) -> list[dict]:
    """The names of the frames of :func:`arm_geometry` ``g`` as plotly scene annotations (sharp text on a light
    background, checked like any text of the page), each pinned to its frame's origin and moved off it as
    :func:`_place_frame_names` chooses for the view of ``scene`` drawn ``plot_height`` px tall."""
    out = []
    for text, o3, (xs, ys, xa, ya), _ in _place_frame_names(g, scene, plot_height):
        out.append(dict(x=round(float(o3[0]), 4), y=round(float(o3[1]), 4), z=round(float(o3[2]), 4), text=text,
                        showarrow=False, xshift=round(xs, 1), yshift=round(ys, 1), xanchor=xa, yanchor=ya,
                        font=dict(size=LABEL_SIZE, color="#222222"), bgcolor="rgba(255,255,255,0.7)",
                        borderpad=1))
    return out


def frame_names_trace(g: dict, scene: dict, plot_height: float) -> go.Scatter3d:
    """The names of the frames of :func:`arm_geometry` ``g`` as one 3-D text trace (named ``"frame names"``),
    each centred on the point of the scene drawn where :func:`_place_frame_names` puts the middle of its box:
    the point at the depth of the frame's origin, on the camera ray through that pixel. A trace moves with the
    data of a live panel (a redraw changes no layout, so a view the reader has turned stays turned)."""
    ranges = np.array([scene[k]["range"] for k in ("xaxis", "yaxis", "zaxis")], float)
    aspect = np.array([scene["aspectratio"][k] for k in "xyz"], float)
    eye = np.array([scene["camera"]["eye"][k] for k in "xyz"], float)
    centre = np.array([scene["camera"]["center"][k] for k in "xyz"], float)
    zc = (eye - centre) / np.linalg.norm(eye - centre)
    xc = np.cross([0.0, 0.0, 1.0], zc)
    xc /= np.linalg.norm(xc)
    yc = np.cross(zc, xc)
    focal = 1.0 / math.tan(math.pi / 8) * plot_height / 2
    texts, points = [], []
    for text, o3, _, box in _place_frame_names(g, scene, plot_height):
        model = (o3 - ranges.mean(axis=1)) / (ranges[:, 1] - ranges[:, 0]) * aspect
        depth = -((model - eye) @ zc)
        cx, cy = (box[0] + box[2]) / 2, (box[1] + box[3]) / 2
        model_pt = eye + depth * (cx / focal * xc + cy / focal * yc - zc)
        points.append(model_pt / aspect * (ranges[:, 1] - ranges[:, 0]) + ranges.mean(axis=1))
        texts.append(text)
    pts = np.array(points)
    return go.Scatter3d(x=as_list(pts[:, 0]), y=as_list(pts[:, 1]), z=as_list(pts[:, 2]), mode="text", text=texts,
                        name="frame names", showlegend=False, textposition="middle center",
                        textfont=dict(size=LABEL_SIZE, color="#222222"), hoverinfo="skip")


def _plot_height(fig) -> float:
    lay = fig.layout
    return lay.height - lay.margin.t - lay.margin.b


def _arm_traces(q, p, triad, colour=None, name="arm", frames=True):
    g = arm_geometry(q, p, triad)
    colour = colour or PALETTE["arm"]
    arm, ee = g["arm"], g["arm"][-1]
    traces = [
        go.Scatter3d(x=as_list(arm[:, 0]), y=as_list(arm[:, 1]), z=as_list(arm[:, 2]), mode="lines+markers",
                     name=name, line=dict(color=colour, width=9), marker=dict(size=4, color=colour),
                     hovertemplate="(%{x:.3f}, %{y:.3f}, %{z:.3f}) m<extra>" + name + "</extra>"),
        go.Scatter3d(x=[round(ee[0], 4)], y=[round(ee[1], 4)], z=[round(ee[2], 4)], mode="markers",
                     name="end effector", marker=dict(size=6, color=PALETTE["reference"], symbol="diamond"),
                     hovertemplate="p_e = (%{x:.3f}, %{y:.3f}, %{z:.3f}) m<extra></extra>"),
    ]
    if frames:
        for k in range(3):
            s = g["triads"][k]
            traces.append(go.Scatter3d(x=as_list(s[:, 0]), y=as_list(s[:, 1]), z=as_list(s[:, 2]), mode="lines",
                                       name=_TRIAD_NAMES[k], line=dict(color=AXIS_COLOURS[k], width=5, dash=DASHES[k]),
                                       hoverinfo="skip"))
    return traces


def _scene(p):
    reach = p.r_max + 0.2
    ztop = p.d0 + 0.2
    return dict(
        xaxis=dict(title="x (m)", range=[-reach, reach]),
        yaxis=dict(title="y (m)", range=[-reach, reach]),
        zaxis=dict(title="z (m)", range=[0.0, ztop]),
        aspectmode="manual", aspectratio=dict(x=1.15, y=1.15, z=1.15 * ztop / (2 * reach)),
        camera=dict(eye=dict(zip("xyz", _CAMERA_EYE)), center=dict(zip("xyz", _CAMERA_CENTRE))),
    )


def _pose_text(q, p, head: str = ""):
    """Two title lines (each short enough for a phone-width page): the position, then phi and det J_A."""
    # rounded first, then + 0.0, so that a tiny negative value reads 0.000, not -0.000
    x = np.round(pose(q, p), 3) + 0.0
    det = round(float(np.linalg.det(jacobian(q, p))), 3) + 0.0
    phi = round(math.degrees(x[3]), 1) + 0.0
    return (f"{head}p = ({x[0]:.3f}, {x[1]:.3f}, {x[2]:.3f}) m<br>"
            f"φ = {phi:.1f}°, det J_A = {det:.3f} m²")


def arm_figure(q, p=None, frames: bool = True, triad: float = 0.3, title: str | None = None,
               height: int = 500, names: str = "text") -> go.Figure:
    """3-D view of the arm at ``q`` with the triads of its DH frames (x, y, z axes coloured as
    ``AXIS_COLOURS`` and dashed as ``DASHES``), frame names, and the end-effector position.

    ``q`` (4,) in rad, rad, m, rad. The title states ``x_e`` (equation ``eq-kin-xe`` of chapter 1) and ``det J_A``.
    The frame names are placed by :func:`_place_frame_names`, so that none overlaps another in the figure's
    view: with ``names="text"`` (the default, what a live panel redraws) as a 3-D text trace, the last trace;
    with ``names="annotations"`` (the book's static figures) as scene annotations.

    >>> fig = arm_figure([0.3, -1.2, 0.4, 0.1])
    >>> [t.name for t in fig.data]
    ['arm', 'end effector', 'x axes', 'y axes', 'z axes', 'frame names']
    >>> [a.text for a in arm_figure([0.3, -1.2, 0.4, 0.1], names="annotations").layout.scene.annotations]
    ['b', '0', '1', '2', '3, 4, e']
    """
    p = ScaraParams.resolve(p)
    q = as_vector(q, "q")
    if names not in ("text", "annotations"):
        raise ScaraError(f"names = {names!r} must be 'text' (a 3-D text trace) or 'annotations'")
    fig = go.Figure(_arm_traces(q, p, triad, frames=frames))
    scene = _scene(p)
    finish_layout(fig, title or _pose_text(q, p), height, scene=scene, uirevision="arm")
    if frames:
        g = arm_geometry(q, p, triad)
        if names == "annotations":
            fig.layout.scene.annotations = frame_label_annotations(g, scene, _plot_height(fig))
        else:
            fig.add_trace(frame_names_trace(g, scene, _plot_height(fig)))
    return fig


def joint_slider_figure(q0=None, joint: int = 1, values=None, p=None, triad: float = 0.3,
                        height: int = 540) -> go.Figure:
    """Static (kernel-free) figure: the arm of :func:`arm_figure` with one slider sweeping joint ``joint``
    (0-based: 0 = theta1, 1 = theta2, 2 = d3, 3 = theta4) over ``values``, the other joints held at ``q0``.

    ``values`` are in degrees for a revolute joint and metres for ``d3``; by default 25 steps over
    [-180°, 180°] (or [0, d0] for d3). Each step restyles the traces and retitles the figure with ``x_e`` and
    ``det J_A``, so a reader of the HTML page moves the joint and sees the arm move. Raises
    :class:`ScaraError` for an unknown joint, more than 61 steps or (via kinematics) a non-finite value.

    >>> fig = joint_slider_figure(joint=1)
    >>> len(fig.layout.sliders[0].steps), fig.layout.sliders[0].steps[0].label
    (25, '-180')
    """
    p = ScaraParams.resolve(p)
    q0 = np.array([0.0, math.radians(60), 0.5, 0.0]) if q0 is None else as_vector(q0, "q0")
    if joint not in (0, 1, 2, 3):
        raise ScaraError(f"joint = {joint!r} must be 0 (theta1), 1 (theta2), 2 (d3) or 3 (theta4)")
    prismatic = joint == 2
    if values is None:
        values = np.linspace(0.0, p.d0, 21) if prismatic else np.linspace(-180.0, 180.0, 25)
    values = as_array(values, "values", (len(np.atleast_1d(values)),))
    if not 2 <= len(values) <= 61:
        raise ScaraError(f"{len(values)} slider steps: use between 2 and 61 (pages stay light)")
    unit = "m" if prismatic else "°"
    sep = " " if prismatic else ""  # "0.50 m" but "60°"
    qs = []
    for v in values:
        q = q0.copy()
        q[joint] = v if prismatic else math.radians(v)
        qs.append(q)
    active = int(np.argmin(np.abs(values - (q0[joint] if prismatic else math.degrees(q0[joint])))))
    fig = go.Figure(_arm_traces(qs[active], p, triad))
    scene = _scene(p)
    name = JOINT_NAMES[joint]
    labels = [f"{v:.2f}" if prismatic else f"{v:.0f}" for v in values]
    finish_layout(fig, _pose_text(qs[active], p, f"{name} = {labels[active]}{sep}{unit}: "), height,
                  scene=scene, uirevision="arm")
    # room under the plot for the slider (its pad, current value, rail and ticks), so that plotly need not
    # enlarge the margin, which would shrink the scene the frame names were placed for
    fig.update_layout(margin_b=_SLIDER_ROOM)
    plot_height = _plot_height(fig)
    steps, notes = [], []
    for label, q in zip(labels, qs):
        tr = _arm_traces(q, p, triad)
        notes.append(frame_label_annotations(arm_geometry(q, p, triad), scene, plot_height))
        steps.append(dict(
            label=label, method="update",
            args=[{"x": [t.x for t in tr], "y": [t.y for t in tr], "z": [t.z for t in tr]},
                  {"title.text": _pose_text(q, p, f"{name} = {label}{sep}{unit}: "), "scene.annotations": notes[-1]},
                  list(range(len(tr)))]))
    fig.layout.scene.annotations = notes[active]
    fig.update_layout(sliders=[slider(steps, prefix=f"{name} ({unit}) = ", active=active)])
    return fig


def top_view_arm(q, p=None, colour=None, name="arm", width: float = 5, showlegend=True, opacity=1.0,
                 dash: str = "solid") -> go.Scatter:
    """The arm at ``q`` seen from above (base x-y plane) as one 2-D line trace: base axis, elbow, end effector."""
    p = ScaraParams.resolve(p)
    origins = link_frames(q, p)[:, :3, 3]
    pts = np.array([[0.0, 0.0], origins[1, :2], origins[2, :2]])
    colour = colour or PALETTE["arm"]
    return go.Scatter(x=as_list(pts[:, 0]), y=as_list(pts[:, 1]), mode="lines+markers", name=name,
                      line=dict(color=colour, width=width, dash=dash), marker=dict(size=[9, 7, 7], color=colour),
                      opacity=opacity, showlegend=showlegend,
                      hovertemplate="(%{x:.3f}, %{y:.3f}) m<extra>" + name + "</extra>")


def _circle(radius, n=145):
    th = np.linspace(0, 2 * math.pi, n)
    return radius * np.cos(th), radius * np.sin(th)


def top_axes(fig, p, margin: float = 0.2, xr=None, yr=None) -> None:
    """Equal-scale x-y axes (m) of a top view, by default covering the workspace disc and ``margin`` m more;
    ``xr``, ``yr`` set the ranges instead."""
    reach = p.r_max + margin
    fig.update_xaxes(title_text="x (m)", range=xr or [-reach, reach], zeroline=False, constrain="domain")
    fig.update_yaxes(title_text="y (m)", range=yr or [-reach, reach], zeroline=False, scaleanchor="x", scaleratio=1)


def inverse_kinematics_figure(x, p=None, height: int = 500) -> go.Figure:
    """Top view of both closed-form inverse-kinematics solutions (elbow +1 and -1) reaching the target ``x``.

    ``x = [p_x, p_y, p_z, phi]`` (m, m, m, rad). Draws the workspace boundary circles ``r = a1 + a2`` and
    ``r = |a1 - a2|``, both arms (elbow +1 solid, elbow -1 dashed) and the target; the title gives theta2 of
    each. Raises :class:`UnreachableError` (from :func:`ikine`) when the target is outside the workspace.

    >>> fig = inverse_kinematics_figure([0.18, 0.20, 0.5, 0.0])
    >>> [t.name for t in fig.data][1]
    'elbow +1'
    """
    p = ScaraParams.resolve(p)
    x = as_vector(x, "x")
    fig = go.Figure()
    cx, cy = _circle(p.r_max)
    fig.add_trace(go.Scatter(x=as_list(cx), y=as_list(cy), mode="lines", name=f"reach {p.r_max:g} m",
                             line=dict(color="#999999", dash="dash", width=1), hoverinfo="skip"))
    if p.r_min > 0:
        cx, cy = _circle(p.r_min)
        fig.add_trace(go.Scatter(x=as_list(cx), y=as_list(cy), mode="lines",
                                 name=f"hole {p.r_min:g} m",
                                 line=dict(color="#999999", dash="dot", width=1), hoverinfo="skip"))
    parts = []
    for elbow in (+1, -1):
        q = ikine(x, p, elbow=elbow)
        sign = "+" if elbow > 0 else "−"
        fig.add_trace(top_view_arm(q, p, colour=ELBOW_COLOURS[elbow], name=f"elbow {sign}1", dash=ELBOW_DASHES[elbow]))
        parts.append(f"θ2 = {math.degrees(q[1]):.1f}°".replace("-", "−"))
    fig.add_trace(go.Scatter(x=[x[0]], y=[x[1]], mode="markers", name="target",
                             marker=dict(symbol="x", size=13, color=PALETTE["reference"]),
                             hovertemplate="target (%{x:.3f}, %{y:.3f}) m<extra></extra>"))
    finish_layout(fig, f"p = ({x[0]:.2f}, {x[1]:.2f}, {x[2]:.2f}) m, d3 = {p.d0 - x[2]:.2f} m<br>"
                       f"{parts[0]} (elbow +1), {parts[1][5:]} (elbow −1)", height)
    top_axes(fig, p, margin=0.15)
    return fig


def _reach_title(x, q, p) -> str:
    """Two title lines for the target ``x`` reached by ``q`` = {elbow: joints}, or refused (``q`` is None)."""
    r = math.hypot(x[0], x[1])
    head = f"p = ({x[0]:.2f}, {x[1]:.2f}, {x[2]:.2f}) m, r = {r:.3f} m"
    if q is None:
        if r > p.r_max:
            why = f"out of reach: r > a1 + a2 = {p.r_max:g} m"
        elif r < p.r_min:
            why = f"out of reach: r < |a1 − a2| = {p.r_min:g} m"
        else:
            why = f"out of reach: d3 = {p.d0 - x[2]:.2f} m is off the stroke"
        return f"{head}<br>{why}"
    t_up, t_down = (round(math.degrees(q[e][1]), 1) + 0.0 for e in (+1, -1))
    return f"{head}<br>θ2 = {t_up:.1f}° (elbow +1), {t_down:.1f}° (−1)".replace("-", "−")


def inverse_kinematics_slider_figure(x, values, component: int = 0, p=None, height: int = 520) -> go.Figure:
    """Static (kernel-free) figure: :func:`inverse_kinematics_figure` with a slider that moves one component of
    the target ``x = [p_x, p_y, p_z, phi]`` over ``values`` (m; ``component`` 0, 1 or 2), as the live panel of
    chapter 1 does when the value is typed. Each step draws both elbow solutions and names their theta2 in the
    title; a target out of reach is drawn alone, both arms removed, and the title says which limit it breaks.

    Raises :class:`ScaraError` for a component other than 0, 1, 2, fewer than 2 or more than 61 values, or a
    starting target (the first value) out of reach.

    >>> fig = inverse_kinematics_slider_figure([0.9, 0.0, 0.5, 0.0], [0.9, 1.0, 1.01])
    >>> [s.label for s in fig.layout.sliders[0].steps]
    ['0.90', '1.00', '1.01']
    """
    p = ScaraParams.resolve(p)
    x = as_vector(x, "x")
    if component not in (0, 1, 2):
        raise ScaraError(f"component = {component!r} must be 0 (p_x), 1 (p_y) or 2 (p_z)")
    values = as_array(values, "values", (len(np.atleast_1d(values)),))
    if not 2 <= len(values) <= 61:
        raise ScaraError(f"{len(values)} slider steps: use between 2 and 61 (pages stay light)")
    targets, solutions = [], []
    for v in values:
        t = x.copy()
        t[component] = v
        targets.append(t)
        try:
            solutions.append({e: ikine(t, p, elbow=e) for e in (+1, -1)})
        except UnreachableError:
            solutions.append(None)
    if solutions[0] is None:
        raise UnreachableError(f"the first target {targets[0][:3].round(4).tolist()} m is out of reach: start the "
                               "slider at a reachable value")
    fig = inverse_kinematics_figure(targets[0], p, height=height)
    names = [t.name for t in fig.data]
    moving = [names.index("elbow +1"), names.index("elbow −1"), names.index("target")]
    steps = []
    for v, t, q in zip(values, targets, solutions):
        xs, ys = [], []
        for e in (+1, -1):
            arm = top_view_arm(q[e], p) if q is not None else None
            xs.append(list(arm.x) if arm is not None else [])
            ys.append(list(arm.y) if arm is not None else [])
        xs.append([round(float(t[0]), 4)])
        ys.append([round(float(t[1]), 4)])
        steps.append(dict(label=f"{v:.2f}", method="update", args=[{"x": xs, "y": ys},
                                                                    {"title.text": _reach_title(t, q, p)}, moving]))
    fig.layout.title.text = _reach_title(targets[0], solutions[0], p)
    name = ("p_x", "p_y", "p_z")[component]
    fig.update_layout(sliders=[slider(steps, prefix=f"{name} (m) = ")], margin_b=_SLIDER_ROOM)
    return fig


def determinant_figure(p=None, theta1: float = 0.0, n: int = 181, height: int = 400) -> go.Figure:
    """``det J_A`` (numerical determinant of :func:`jacobian`) and ``w = |det J_A|`` against ``theta2`` over
    [-180°, 180°], with the singular configurations (stretched, folded) marked. ``theta1`` in rad; ``n``
    samples (>= 3).

    Limits: ``n`` from 3 to 10 000 samples (``MAX_POINTS``); a value outside, or not a whole number, raises
    :class:`ScaraError` before any work."""
    n = check_count(n, "n", 3, MAX_POINTS, "samples", FIGURE_BUDGET)
    p = ScaraParams.resolve(p)
    t2 = np.linspace(-180.0, 180.0, n)
    det = np.array([np.linalg.det(jacobian([theta1, math.radians(v), 0.5 * p.d0, 0.0], p)) for v in t2])
    fig = go.Figure()
    fig.add_trace(go.Scatter(x=as_list(t2, 2), y=as_list(det, 5), mode="lines", name="det J_A",
                             line=dict(color=AXIS_COLOURS[0], width=3)))
    fig.add_trace(go.Scatter(x=as_list(t2, 2), y=as_list(np.abs(det), 5), mode="lines",
                             name="w = |det J_A|", line=dict(color=AXIS_COLOURS[1], dash="dash", width=2)))
    fig.add_trace(go.Scatter(x=[-180, 0, 180], y=[0, 0, 0], mode="markers+text", name="singular",
                             text=["folded", "stretched", "folded"], textposition="top center",
                             marker=dict(size=11, color=PALETTE["reference"], symbol="circle-open", line=dict(width=2))))
    finish_layout(fig, "det J_A against θ2 (θ1, d3, θ4 held)", height)
    fig.update_xaxes(title_text="θ2 (°)", tickvals=list(range(-180, 181, 90)))
    fig.update_yaxes(title_text="det J_A (m²)")
    return fig


def arm_pair(p=None, height: int = 480) -> FigurePair:
    """The direct-kinematics panel's figure: :func:`arm_figure` of the state's ``q`` (redrawn whole, trace by
    name)."""
    p = ScaraParams.resolve(p)
    return FigurePair("arm", lambda state: arm_figure(state["q"], p, height=height))


def inverse_kinematics_pair(p=None, height: int = 460) -> FigurePair:
    """The inverse-kinematics panel's figure: :func:`inverse_kinematics_figure` of the state's ``target``."""
    p = ScaraParams.resolve(p)
    return FigurePair("inverse kinematics", lambda state: inverse_kinematics_figure(state["target"], p, height=height))
