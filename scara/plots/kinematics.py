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

from ..errors import ScaraError, as_array, as_vector
from ..kinematics import _params, ikine, jacobian, link_frames, pose
from ._common import AXIS_COLOURS, DASHES, JOINT_NAMES, PALETTE, as_list, slider
from ._common import MAX_POINTS, check_count
from .layout import finish_layout
# still importable from here, where they lived before scara.plots.layout (the figure rules of tests/ use them)

__all__ = [
    "FRAME_NAMES",
    "ELBOW_COLOURS",
    "arm_geometry",
    "arm_figure",
    "joint_slider_figure",
    "top_view_arm",
    "top_axes",
    "inverse_kinematics_figure",
    "determinant_figure",
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
    ``"origins"`` (7, 3) and ``"labels"``: the frame origins and names, coincident frames sharing one label
    (frames 3, 4 and e share the end-effector origin); ``"label_points"``: where those labels are drawn, each
    moved off its origin and its triad, no two closer than 0.2 m.

    Raises :class:`ShapeError`/:class:`NonFiniteError` for a bad ``q``.
    """
    p = _params(p)
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
    return {"arm": arm, "triads": triads, "origins": np.array(label_pts), "labels": labels,
            "label_points": _label_points(np.array(label_pts), origins[2], p),
            "label_positions": _label_positions(np.array(label_pts), p)}


#: offsets (m) of the 3-D frame labels from their origins, to the right as the default camera of :func:`_scene`
#: sees them and up (down at the gripper); labels closer than ``_LABEL_GAP`` are moved apart
_LABEL_SIDE, _LABEL_UP, _LABEL_GAP = 0.07, 0.06, 0.2
_CAMERA_EYE = (1.05, -1.35, 0.75)


def _label_points(points, elbow, p):
    """Where the 3-D frame labels go: each origin moved right (as the default camera sees the scene) by
    ``_LABEL_SIDE`` and up by ``_LABEL_UP`` (down for the gripper, below the arm's plane), the text drawn on that
    side of the point, so that a label sits beside its triad, not on it; a label that would still come within
    ``_LABEL_GAP`` of an earlier one is lifted until it does not, so no two labels overlap."""
    eye = np.array(_CAMERA_EYE)
    right = np.cross(-eye, [0.0, 0.0, 1.0])
    right /= np.linalg.norm(right)
    out = []
    for o in points:
        low = p.d0 - 1e-9 > o[2] > 1e-9
        pt = o + _LABEL_SIDE * right + [0.0, 0.0, -_LABEL_UP if low else _LABEL_UP]
        while any(np.linalg.norm(pt - other) < _LABEL_GAP for other in out):
            pt[2] += 0.5 * _LABEL_GAP
        out.append(pt)
    return np.array(out)


def _label_positions(points, p):
    """plotly ``textposition`` of each label of :func:`_label_points`: above right, below right at the gripper."""
    return ["bottom right" if p.d0 - 1e-9 > o[2] > 1e-9 else "top right" for o in points]


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
        o = g["label_points"]
        traces.append(go.Scatter3d(x=as_list(o[:, 0]), y=as_list(o[:, 1]), z=as_list(o[:, 2]),
                                   mode="text", text=g["labels"], name="frame names", showlegend=False,
                                   textposition=g["label_positions"],
                                   textfont=dict(size=13, color="#222222"), hoverinfo="skip"))
    return traces


def _scene(p):
    reach = p.r_max + 0.2
    ztop = p.d0 + 0.2
    return dict(
        xaxis=dict(title="x (m)", range=[-reach, reach]),
        yaxis=dict(title="y (m)", range=[-reach, reach]),
        zaxis=dict(title="z (m)", range=[0.0, ztop]),
        aspectmode="manual", aspectratio=dict(x=1.15, y=1.15, z=1.15 * ztop / (2 * reach)),
        camera=dict(eye=dict(zip("xyz", _CAMERA_EYE)), center=dict(x=0, y=0, z=-0.05)),
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
               height: int = 500) -> go.Figure:
    """3-D view of the arm at ``q`` with the triads of its DH frames (x, y, z axes coloured as
    ``AXIS_COLOURS`` and dashed as ``DASHES``), frame names, and the end-effector position.

    ``q`` (4,) in rad, rad, m, rad. The title states ``x_e`` (equation ``eq-kin-xe`` of chapter 1) and ``det J_A``.

    >>> fig = arm_figure([0.3, -1.2, 0.4, 0.1])
    >>> [t.name for t in fig.data][:2]
    ['arm', 'end effector']
    """
    p = _params(p)
    q = as_vector(q, "q")
    fig = go.Figure(_arm_traces(q, p, triad, frames=frames))
    return finish_layout(fig, title or _pose_text(q, p), height, scene=_scene(p), uirevision="arm")


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
    p = _params(p)
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
    steps = []
    for v, q in zip(values, qs):
        tr = _arm_traces(q, p, triad)
        label = f"{v:.2f}" if prismatic else f"{v:.0f}"
        steps.append(dict(
            label=label, method="update",
            args=[{"x": [t.x for t in tr], "y": [t.y for t in tr], "z": [t.z for t in tr],
                   "text": [t.text for t in tr]},
                  {"title.text": _pose_text(q, p, f"{JOINT_NAMES[joint]} = {label}{sep}{unit}: ")},
                  list(range(len(tr)))]))
    name = JOINT_NAMES[joint]
    return finish_layout(fig, _pose_text(qs[active], p, f"{name} = {steps[active]['label']}{sep}{unit}: "), height,
                         scene=_scene(p), uirevision="arm",
                         sliders=[slider(steps, prefix=f"{name} ({unit}) = ", active=active)])


def top_view_arm(q, p=None, colour=None, name="arm", width: float = 5, showlegend=True, opacity=1.0,
                 dash: str = "solid") -> go.Scatter:
    """The arm at ``q`` seen from above (base x-y plane) as one 2-D line trace: base axis, elbow, end effector."""
    p = _params(p)
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
    p = _params(p)
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


def determinant_figure(p=None, theta1: float = 0.0, n: int = 181, height: int = 400) -> go.Figure:
    """``det J_A`` (numerical determinant of :func:`jacobian`) and ``w = |det J_A|`` against ``theta2`` over
    [-180°, 180°], with the singular configurations (stretched, folded) marked. ``theta1`` in rad; ``n``
    samples (>= 3).

    Limits: ``n`` from 3 to 10 000 samples (``MAX_POINTS``); a value outside, or not a whole number, raises
    :class:`ScaraError` before any work."""
    n = check_count(n, "n", MAX_POINTS, minimum=3, what="samples")
    p = _params(p)
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
