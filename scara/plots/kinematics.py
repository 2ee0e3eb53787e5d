"""Figures of chapter 1 (kinematics): the arm and its DH frames in 3-D, a joint sweep with slider steps, both
inverse-kinematics solutions of a target seen from above, and the Jacobian determinant against theta2.

Every builder takes joint vectors ``q = [theta1, theta2, d3, theta4]`` (rad, rad, m, rad) and an optional
parameter object ``p`` (``None`` means ``ScaraParams()``) and returns a ``plotly.graph_objects.Figure``. The arm,
its frames, the places of the frames' names and both inverse-kinematics solutions come from the compiled kernels
of :mod:`scara.programs.kinematics`, the ones the chapter's live panels run (in JupyterLab and, translated, in the
book's pages): :func:`arm_panel_figure` and :func:`inverse_kinematics_panel_figure` draw a panel's figure from its
program's outputs, and :data:`ARM_TRACES`, :data:`ARM_TITLE`, :data:`IK_TRACES`, :data:`IK_TITLE` bind those
outputs to the traces and the title.
"""
from __future__ import annotations

import functools
import math

import numpy as np
import plotly.graph_objects as go

from ..errors import ScaraError, UnreachableError, as_array, as_vector, check_angles, check_count
from ..kinematics import _unreachable_message, jacobian, link_frames, pose
from ..params import ScaraParams
from ..programs import kinematics as _prog
from ..programs.kinematics import CANDIDATES, FRAME_NAMES, N_SLOTS, SLOT_LABELS, SLOT_MASKS, SLOT_OF_MASK
from ._common import AXIS_COLOURS, DASHES, JOINT_NAMES, PALETTE, as_list, slider
from ._common import MAX_POINTS, FIGURE_BUDGET
from .panels import FigurePair, Text
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
    "ARM_TRACES", "ARM_TITLE", "IK_TRACES", "IK_TITLE", "ARM_PANEL_HEIGHT", "IK_PANEL_HEIGHT",
    "arm_program_data", "arm_panel_figure", "inverse_kinematics_panel_figure",
]

#: one colour and dash per elbow solution (+1: sin theta2 >= 0, -1: sin theta2 <= 0), told apart in greyscale too
ELBOW_COLOURS = {+1: "#0072B2", -1: "#E69F00"}
ELBOW_DASHES = {+1: "solid", -1: "dash"}
_TRIAD_NAMES = ("x axes", "y axes", "z axes")
#: line widths of the triads: plotly draws a legend's line 30 px long with dashes three widths long, so the
#: dashed y axes are thin enough for their swatch to show two dashes (at width 5 it shows one, as if solid)
_TRIAD_WIDTHS = (5, 3, 5)
#: the heights (px) of the live panels' figures
ARM_PANEL_HEIGHT = 480
IK_PANEL_HEIGHT = 460


def _check_triad(triad) -> float:
    if not (isinstance(triad, (int, float)) and not isinstance(triad, bool) and math.isfinite(triad) and triad > 0):
        raise ScaraError(f"triad = {triad!r} must be a positive length in metres")
    return float(triad)


def arm_geometry(q, p=None, triad: float = 0.3) -> dict:
    """Points to draw the arm at ``q`` in the base frame (:func:`scara.programs.kinematics.arm_points_kernel`).

    Returns a dict with
    ``"arm"`` (5, 3): base, frame-0 origin (top of the column, height ``d0``), elbow, end of link 2, end
    effector (bottom of the quill);
    ``"triads"``: three arrays (3 * 7, 3), the x, y and z axes (length ``triad`` m) of the frames
    ``b, 0, 1, 2, 3, 4, e`` as segments separated by NaN rows;
    ``"origins"`` (n, 3) and ``"labels"``: the distinct frame origins and their names, coincident frames
    sharing one label (frames 3, 4 and e share the end-effector origin;
    :func:`scara.programs.kinematics.frame_groups_kernel`).

    Raises :class:`ShapeError`/:class:`NonFiniteError` for a bad ``q``.
    """
    p = ScaraParams.resolve(p)
    triad = _check_triad(triad)
    q = check_angles(as_array(q, "q", (4,)))
    frames, arm, triads = np.empty((7, 12)), np.empty((5, 3)), np.empty((63, 3))
    _prog.arm_points_kernel(q, p.a1, p.a2, p.d0, triad, frames, arm, triads)
    first, masks = np.empty(7), np.empty(7)
    n = _prog.frame_groups_kernel(frames, first, masks)
    labels = [SLOT_LABELS[SLOT_OF_MASK[int(m)]] for m in masks[:n]]
    origins = frames[first[:n].astype(int), :3].copy()
    return {"arm": arm, "triads": [triads[21 * k:21 * (k + 1)].copy() for k in range(3)], "origins": origins,
            "labels": labels}


_CAMERA_EYE = (1.05, -1.35, 0.75)
#: the aspect ratio of the arm's x and y axes in its 3-D scene
_SCENE_SIZE = 0.72
_CAMERA_CENTRE = (0.0, 0.0, -0.05)
#: font size (px) of the frame names in the 3-D views
LABEL_SIZE = 13
#: half the width (px) of the narrowest plot area a 3-D view is drawn in: a 360-px phone page, the figure's
#: side margins taken off; the frame names stay within it
_PHONE_HALF_WIDTH = 115
#: bottom margin (px) of a 3-D figure with a slider: the slider's pad (40 px), current value, rail and ticks
_SLIDER_ROOM = 134
#: height (px) of a frame name's box: the text's line and 2 px of padding above and below
_LABEL_HEIGHT = 1.35 * LABEL_SIZE + 4.0


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



def _box_width(text: str) -> float:
    """Width (px) of a frame name's box: the text's width, estimated generously, plus 2 px of padding a side."""
    return _text_width(text, LABEL_SIZE) + 6.0


def _view(scene: dict, plot_height: float) -> np.ndarray:
    """The view of ``scene`` drawn ``plot_height`` px tall, as the placement kernel reads it
    (:data:`scara.programs.kinematics.VIEW`); the names stay within a phone page's plot area."""
    return _prog.view_vector(scene, plot_height, _PHONE_HALF_WIDTH, _LABEL_HEIGHT)


_X_ANCHORS = {0.0: "left", 0.5: "center", 1.0: "right"}
_Y_ANCHORS = {0.0: "bottom", 0.5: "middle", 1.0: "top"}


def _offset(k: int) -> tuple:
    """The candidate place ``k`` of a name (:data:`scara.programs.kinematics.CANDIDATES`) as plotly reads it:
    ``(xshift, yshift, xanchor, yanchor)``."""
    xs, ys, fx, fy = CANDIDATES[k]
    return float(xs), float(ys), _X_ANCHORS[float(fx)], _Y_ANCHORS[float(fy)]


def _placed(g: dict, scene: dict, plot_height: float):
    """:func:`scara.programs.kinematics.place_names_kernel` for the frames of :func:`arm_geometry` ``g``: the
    candidate each name takes, its box (px) and the point of the scene drawn at the box's centre, one row per name."""
    segments = [np.r_[a, b] for poly in [g["arm"], *g["triads"]] for a, b in zip(poly[:-1], poly[1:])
                if np.all(np.isfinite(a)) and np.all(np.isfinite(b))]
    n = len(g["labels"])
    chosen, boxes, spots = np.empty(n), np.empty((n, 4)), np.empty((n, 3))
    _prog.place_names_kernel(np.ascontiguousarray(g["origins"], dtype=float),
                             np.array([_box_width(t) for t in g["labels"]]), np.array(segments),
                             _view(scene, plot_height), CANDIDATES, chosen, boxes, spots)
    return chosen, boxes, spots


def _place_frame_names(g: dict, scene: dict, plot_height: float) -> list:
    """Where the names of the frames of :func:`arm_geometry` ``g`` go in the view of ``scene`` drawn
    ``plot_height`` px tall: ``[(text, origin (3,), offset, box), ...]``, each name moved off its frame's origin by
    a pixel ``offset = (xshift, yshift, xanchor, yanchor)`` chosen so that no two names overlap, none covers the
    arm or a triad where another place is free, and each stays within a phone page's plot area; ``box`` is the
    name's box (left, bottom, right, top) in pixels from the centre of the plot area, y up
    (:func:`scene_projection`: the offsets hold at every page width). The choice is
    :func:`scara.programs.kinematics.place_names_kernel`'s."""
    chosen, boxes, _ = _placed(g, scene, plot_height)
    return [(text, o3, _offset(int(k)), tuple(float(v) for v in box))
            for text, o3, k, box in zip(g["labels"], g["origins"], chosen, boxes)]


def _annotation(text, o3, offset) -> dict:
    xs, ys, xa, ya = offset
    return dict(x=round(float(o3[0]), 4), y=round(float(o3[1]), 4), z=round(float(o3[2]), 4), text=text,
                showarrow=False, xshift=round(xs, 1), yshift=round(ys, 1), xanchor=xa, yanchor=ya,
                font=dict(size=LABEL_SIZE, color="#222222"), bgcolor="rgba(255,255,255,0.7)", borderpad=1)


def frame_label_annotations(g: dict, scene: dict, plot_height: float) -> list[dict]:
    """The names of the frames of :func:`arm_geometry` ``g`` as plotly scene annotations (sharp text on a light
    background, checked like any text of the page), each pinned to its frame's origin and moved off it as
    :func:`_place_frame_names` chooses for the view of ``scene`` drawn ``plot_height`` px tall."""
    return [_annotation(text, o3, offset) for text, o3, offset, _ in _place_frame_names(g, scene, plot_height)]


def _names_trace(x, y, z, text) -> go.Scatter3d:
    return go.Scatter3d(x=x, y=y, z=z, mode="text", text=text, name="frame names", showlegend=False,
                        textposition="middle center", textfont=dict(size=LABEL_SIZE, color="#222222"),
                        hoverinfo="skip")


def frame_names_trace(g: dict, scene: dict, plot_height: float) -> go.Scatter3d:
    """The names of the frames of :func:`arm_geometry` ``g`` as one 3-D text trace (named ``"frame names"``),
    each centred on the point of the scene drawn where :func:`_place_frame_names` puts the middle of its box:
    the point at the depth of the frame's origin, on the camera ray through that pixel. A trace moves with the
    data of a live panel (a redraw changes no layout, so a view the reader has turned stays turned)."""
    _, _, spots = _placed(g, scene, plot_height)
    return _names_trace(as_list(spots[:, 0]), as_list(spots[:, 1]), as_list(spots[:, 2]), list(g["labels"]))


def _plot_height(fig) -> float:
    lay = fig.layout
    return lay.height - lay.margin.t - lay.margin.b


def _arm_trace_list(arm, triads, colour=None, name="arm", frames=True, exact=False):
    """The traces of the arm: its polyline ``arm`` (x, y, z) and end effector (its last point), and with
    ``frames`` the triads ``triads`` (three (x, y, z)). Exact: the numbers as they are (a live panel's figure,
    which its program's outputs update); otherwise rounded to 0.1 mm (a page's static figure)."""
    colour = colour or PALETTE["arm"]
    data = (lambda v: np.asarray(v, dtype=float)) if exact else as_list
    ee = [float(arm[c][-1]) if exact else round(arm[c][-1], 4) for c in range(3)]
    traces = [
        go.Scatter3d(x=data(arm[0]), y=data(arm[1]), z=data(arm[2]), mode="lines+markers",
                     name=name, line=dict(color=colour, width=9), marker=dict(size=4, color=colour),
                     hovertemplate="(%{x:.3f}, %{y:.3f}, %{z:.3f}) m<extra>" + name + "</extra>"),
        go.Scatter3d(x=[ee[0]], y=[ee[1]], z=[ee[2]], mode="markers",
                     name="end effector", marker=dict(size=6, color=PALETTE["reference"], symbol="diamond"),
                     hovertemplate="p_e = (%{x:.3f}, %{y:.3f}, %{z:.3f}) m<extra></extra>"),
    ]
    if frames:
        for k in range(3):
            s = triads[k]
            traces.append(go.Scatter3d(x=data(s[0]), y=data(s[1]), z=data(s[2]), mode="lines",
                                       name=_TRIAD_NAMES[k], line=dict(color=AXIS_COLOURS[k], width=_TRIAD_WIDTHS[k], dash=DASHES[k]),
                                       hoverinfo="skip"))
    return traces


def _arm_traces(q, p, triad, colour=None, name="arm", frames=True):
    g = arm_geometry(q, p, triad)
    return _arm_trace_list(g["arm"].T, [s.T for s in g["triads"]], colour, name, frames)


def _scene(p):
    reach = p.r_max + 0.2
    ztop = p.d0 + 0.2
    # small enough that the box, its tick labels and axis titles fit a phone-width page (plotly sizes a scene
    # by its height); a tick a metre, the axis titles small
    ticks = dict(dtick=1.0, tickfont=dict(size=11), title_font=dict(size=12))
    return dict(
        xaxis=dict(title="x (m)", range=[-reach, reach], **ticks),
        yaxis=dict(title="y (m)", range=[-reach, reach], **ticks),
        zaxis=dict(title="z (m)", range=[0.0, ztop], **dict(ticks, dtick=0.5)),
        aspectmode="manual", aspectratio=dict(x=_SCENE_SIZE, y=_SCENE_SIZE, z=_SCENE_SIZE * ztop / (2 * reach)),
        camera=dict(eye=dict(zip("xyz", _CAMERA_EYE)), center=dict(zip("xyz", _CAMERA_CENTRE))),
    )


def _pose_text(q, p, head: str = ""):
    """Two title lines (each short enough for a phone-width page): the position, then phi and det J_A."""
    # rounded first, then + 0.0, so that a tiny negative value reads 0.000, not -0.000
    x = pose(q, p)
    phi = round(math.degrees(x[3]), 1) + 0.0  # from phi itself (as in ARM_TITLE), not from phi rounded in rad
    x = np.round(x, 3) + 0.0
    det = round(float(np.linalg.det(jacobian(q, p))), 3) + 0.0
    return (f"{head}p = ({x[0]:.3f}, {x[1]:.3f}, {x[2]:.3f}) m<br>"
            f"φ = {phi:.1f}°, det J_A = {det:.3f} m²")



# --------------------------------------------------------------------------------------------------
# the arm in 3-D: drawn from the outputs of the direct-kinematics program
# --------------------------------------------------------------------------------------------------
#: the outputs of :func:`scara.programs.kinematics.kinematics_program` that each trace of :func:`arm_panel_figure`
#: shows (a trace's name -> {property: output})
ARM_TRACES = {
    "arm": {"x": "arm_x", "y": "arm_y", "z": "arm_z"},
    "end effector": {"x": ("px",), "y": ("py",), "z": ("pz",)},
    **{name: {c: f"{a}_axes_{c}" for c in "xyz"} for a, name in zip("xyz", _TRIAD_NAMES)},
    "frame names": {"x": "names_x", "y": "names_y", "z": "names_z"},
}
#: the arm's title: two lines short enough for a phone-width page, the position (1.5), then phi and det J_A
ARM_TITLE = Text("p = ({title_px:.3f}, {title_py:.3f}, {title_pz:.3f}) m<br>"
                 "φ = {title_phi:.1f}°, det J_A = {title_det:.3f} m²")


@functools.lru_cache(maxsize=32)
def _arm_plot_height(height: int, title_lines: int, frames: bool) -> float:
    """The height (px) of the plot area of :func:`arm_figure` (its legend and a title of ``title_lines`` lines
    above it), which the frame names are placed for."""
    names = ["arm", "end effector", *(_TRIAD_NAMES if frames else ())]
    fig = go.Figure([go.Scatter3d(name=n) for n in names])
    finish_layout(fig, "<br>".join(["."] * title_lines), height)
    return _plot_height(fig)


def arm_program_data(p=None, height: int = ARM_PANEL_HEIGHT, triad: float = 0.3, title_lines: int = 2,
                     frames: bool = True) -> np.ndarray:
    """The ``data`` of :func:`scara.programs.kinematics.kinematics_program` for the robot ``p`` drawn by
    :func:`arm_figure` ``height`` px tall with a title of ``title_lines`` lines: the lengths, the triads' length
    ``triad`` (m), the 3-D view and the widths of the frame names' boxes."""
    p = ScaraParams.resolve(p)
    view = _view(_scene(p), _arm_plot_height(int(height), int(title_lines), bool(frames)))
    return _prog.arm_data(p.a1, p.a2, p.d0, _check_triad(triad), view, [_box_width(t) for t in SLOT_LABELS])


def _arm_xyz(values, prefix):
    return [values[f"{prefix}_{c}"] for c in "xyz"]


def _shown_slots(values) -> list:
    """The slots of the names the program shows, in the order of their first frames."""
    return [s for s in range(N_SLOTS) if np.isfinite(values["names_x"][s])]


def arm_panel_figure(values: dict, p=None, height: int = ARM_PANEL_HEIGHT) -> go.Figure:
    """The direct-kinematics panel's figure, drawn from the outputs ``values`` of
    :func:`scara.programs.kinematics.kinematics_program` run on :func:`arm_program_data` ``(p, height)``: the
    figure of :func:`arm_figure`, the numbers unrounded and the frame names' trace holding every possible name (those
    not shown at NaN), so that the program's outputs bound by :data:`ARM_TRACES` and :data:`ARM_TITLE` redraw it."""
    p = ScaraParams.resolve(p)
    fig = go.Figure(_arm_trace_list(_arm_xyz(values, "arm"), [_arm_xyz(values, f"{a}_axes") for a in "xyz"],
                                    exact=True))
    finish_layout(fig, ARM_TITLE.format(values), height, scene=_scene(p), uirevision="arm")
    fig.update_layout(margin=dict(l=0, r=0))    # the scene's size is set by its height: side margins only cut it
    fig.add_trace(_names_trace(*(np.asarray(values[f"names_{c}"], dtype=float) for c in "xyz"), list(SLOT_LABELS)))
    return fig


def arm_figure(q, p=None, frames: bool = True, triad: float = 0.3, title: str | None = None,
               height: int = 500, names: str = "text") -> go.Figure:
    """3-D view of the arm at ``q`` with the triads of its DH frames (x, y, z axes coloured as
    ``AXIS_COLOURS`` and dashed as ``DASHES``), frame names, and the end-effector position.

    ``q`` (4,) in rad, rad, m, rad. The title states ``x_e`` (equation ``eq-kin-xe`` of chapter 1) and ``det J_A``.
    The frame names are placed by :func:`_place_frame_names`, so that none overlaps another in the figure's
    view: with ``names="text"`` (the default, what a live panel redraws) as a 3-D text trace, the last trace;
    with ``names="annotations"`` (the book's static figures) as scene annotations. Everything drawn comes from one
    run of :func:`scara.programs.kinematics.arm_kernel`, the direct-kinematics panel's kernel.

    >>> fig = arm_figure([0.3, -1.2, 0.4, 0.1])
    >>> [t.name for t in fig.data]
    ['arm', 'end effector', 'x axes', 'y axes', 'z axes', 'frame names']
    >>> [a.text for a in arm_figure([0.3, -1.2, 0.4, 0.1], names="annotations").layout.scene.annotations]
    ['b', '0', '1', '2', '3, 4, e']
    """
    p = ScaraParams.resolve(p)
    q = check_angles(as_vector(q, "q"))
    if names not in ("text", "annotations"):
        raise ScaraError(f"names = {names!r} must be 'text' (a 3-D text trace) or 'annotations'")
    lines = title.count("<br>") + 1 if title else ARM_TITLE.template.count("<br>") + 1
    values = _prog.run_arm(q, arm_program_data(p, height, triad, lines, frames))
    fig = go.Figure(_arm_trace_list(_arm_xyz(values, "arm"), [_arm_xyz(values, f"{a}_axes") for a in "xyz"],
                                    frames=frames))
    finish_layout(fig, title or ARM_TITLE.format(values), height, scene=_scene(p), uirevision="arm")
    fig.update_layout(margin=dict(l=0, r=0))    # the scene's size is set by its height: side margins only cut it
    if frames:
        shown = _shown_slots(values)
        if names == "annotations":
            origins = values["origins"].reshape(7, 3)
            fig.layout.scene.annotations = [
                _annotation(SLOT_LABELS[s], origins[(SLOT_MASKS[s] & -SLOT_MASKS[s]).bit_length() - 1],
                            _offset(int(values["names_choice"][s]))) for s in shown]
        else:
            fig.add_trace(_names_trace(*(as_list(values[f"names_{c}"][shown]) for c in "xyz"),
                                       [SLOT_LABELS[s] for s in shown]))
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
    # the side margins this figure keeps for its slider's end labels leave the scene less width than the other
    # arm figures: the view a little to the side, so that its z title stays inside the scene on a phone
    scene["camera"]["center"]["x"] -= 0.05
    name = JOINT_NAMES[joint]
    labels = [f"{v:.2f}" if prismatic else f"{v:.0f}" for v in values]
    finish_layout(fig, _pose_text(qs[active], p, f"{name} = {labels[active]}{sep}{unit}: "), height,
                  scene=scene, uirevision="arm")
    # room under the plot for the slider (its pad, current value, rail and ticks), so that plotly need not
    # enlarge the margin, which would shrink the scene the frame names were placed for
    fig.update_layout(margin=dict(b=_SLIDER_ROOM, l=18, r=18))   # room for the slider's end labels only
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



def _top_arm_trace(xs, ys, colour=None, name="arm", width: float = 5, showlegend=True, opacity=1.0,
                   dash: str = "solid", exact: bool = False) -> go.Scatter:
    """The arm seen from above through the points ``xs``, ``ys`` (base axis, elbow, end effector) as one 2-D line
    trace; exact: the numbers as they are (a live panel's figure), otherwise rounded to 0.1 mm."""
    colour = colour or PALETTE["arm"]
    data = (lambda v: np.asarray(v, dtype=float)) if exact else as_list
    return go.Scatter(x=data(xs), y=data(ys), mode="lines+markers", name=name,
                      line=dict(color=colour, width=width, dash=dash), marker=dict(size=[9, 7, 7], color=colour),
                      opacity=opacity, showlegend=showlegend,
                      hovertemplate="(%{x:.3f}, %{y:.3f}) m<extra>" + name + "</extra>")


def top_view_arm(q, p=None, colour=None, name="arm", width: float = 5, showlegend=True, opacity=1.0,
                 dash: str = "solid") -> go.Scatter:
    """The arm at ``q`` seen from above (base x-y plane) as one 2-D line trace: base axis, elbow, end effector."""
    pts = top_arm_points(q, p)
    return _top_arm_trace(pts[:, 0], pts[:, 1], colour, name, width, showlegend, opacity, dash)


def top_arm_points(q, p=None) -> np.ndarray:
    """The points of the arm at ``q`` seen from above, (3, 2): the base axis, the elbow, the end effector (m)."""
    p = ScaraParams.resolve(p)
    origins = link_frames(q, p)[:, :3, 3]
    return np.array([[0.0, 0.0], origins[1, :2], origins[2, :2]])


def _circle(radius, n=145):
    th = np.linspace(0, 2 * math.pi, n)
    return radius * np.cos(th), radius * np.sin(th)


def top_axes(fig, p, margin: float = 0.2, xr=None, yr=None) -> None:
    """Equal-scale x-y axes (m) of a top view, by default covering the workspace disc and ``margin`` m more;
    ``xr``, ``yr`` set the ranges instead."""
    reach = p.r_max + margin
    fig.update_xaxes(title_text="x (m)", range=xr or [-reach, reach], zeroline=False, constrain="domain")
    fig.update_yaxes(title_text="y (m)", range=yr or [-reach, reach], zeroline=False, scaleanchor="x", scaleratio=1)



# --------------------------------------------------------------------------------------------------
# the inverse kinematics from above: drawn from the outputs of the inverse-kinematics program
# --------------------------------------------------------------------------------------------------
#: the outputs of :func:`scara.programs.kinematics.inverse_kinematics_program` that each trace of
#: :func:`inverse_kinematics_panel_figure` shows
IK_TRACES = {
    "elbow +1": {"x": "up_x", "y": "up_y"},
    "elbow −1": {"x": "down_x", "y": "down_y"},
    "target": {"x": ("target_x",), "y": ("target_y",)},
}
#: the title of the inverse kinematics: the target and the quill's ``d3``, then theta2 of each elbow (theta2 of
#: elbow -1 is never positive: its size follows a minus sign)
IK_TITLE = Text("p = ({px:.2f}, {py:.2f}, {pz:.2f}) m, d3 = {d3:.2f} m<br>"
                "θ2 = {theta2_up:.1f}° (elbow +1), −{theta2_down_size:.1f}° (elbow −1)")


def _inverse_kinematics(x, p):
    """One run of :func:`scara.programs.kinematics.inverse_kinematics_kernel` for the target ``x`` (m, m, m, rad):
    ``(status, values)``, the outputs by field with the target as the panel's controls (``px, py, pz`` in m,
    ``phi`` in degrees)."""
    status, values = _prog.run_inverse_kinematics(x, _prog.inverse_kinematics_data(p))
    values.update(px=float(x[0]), py=float(x[1]), pz=float(x[2]), phi=math.degrees(x[3]))
    return status, values


def _inverse_kinematics_drawing(values, p, height, exact) -> go.Figure:
    fig = go.Figure()
    cx, cy = _circle(p.r_max)
    fig.add_trace(go.Scatter(x=as_list(cx), y=as_list(cy), mode="lines", name=f"reach {p.r_max:g} m",
                             line=dict(color="#999999", dash="dash", width=1), hoverinfo="skip"))
    if p.r_min > 0:
        cx, cy = _circle(p.r_min)
        fig.add_trace(go.Scatter(x=as_list(cx), y=as_list(cy), mode="lines",
                                 name=f"hole {p.r_min:g} m",
                                 line=dict(color="#999999", dash="dot", width=1), hoverinfo="skip"))
    for elbow, key in ((+1, "up"), (-1, "down")):
        sign = "+" if elbow > 0 else "−"
        fig.add_trace(_top_arm_trace(values[f"{key}_x"], values[f"{key}_y"], colour=ELBOW_COLOURS[elbow],
                                     name=f"elbow {sign}1", dash=ELBOW_DASHES[elbow], exact=exact))
    fig.add_trace(go.Scatter(x=[values["target_x"]], y=[values["target_y"]], mode="markers", name="target",
                             marker=dict(symbol="x", size=13, color=PALETTE["reference"]),
                             hovertemplate="target (%{x:.3f}, %{y:.3f}) m<extra></extra>"))
    finish_layout(fig, IK_TITLE.format(values), height)
    top_axes(fig, p, margin=0.15)
    return fig


def inverse_kinematics_panel_figure(values: dict, p=None, height: int = IK_PANEL_HEIGHT) -> go.Figure:
    """The inverse-kinematics panel's figure, drawn from the outputs ``values`` of
    :func:`scara.programs.kinematics.inverse_kinematics_program` (with the panel's settings): the figure of
    :func:`inverse_kinematics_figure`, the numbers unrounded, so that the outputs bound by :data:`IK_TRACES` and
    :data:`IK_TITLE` redraw it."""
    return _inverse_kinematics_drawing(values, ScaraParams.resolve(p), height, exact=True)


def inverse_kinematics_figure(x, p=None, height: int = 500) -> go.Figure:
    """Top view of both closed-form inverse-kinematics solutions (elbow +1 and -1) reaching the target ``x``.

    ``x = [p_x, p_y, p_z, phi]`` (m, m, m, rad). Draws the workspace boundary circles ``r = a1 + a2`` and
    ``r = |a1 - a2|``, both arms (elbow +1 solid, elbow -1 dashed) and the target; the title gives theta2 of
    each. The solutions are those of :func:`scara.programs.kinematics.inverse_kinematics_kernel`, the
    inverse-kinematics panel's kernel. Raises :class:`UnreachableError` (the message of :func:`ikine`) when the
    target is outside the workspace.

    >>> fig = inverse_kinematics_figure([0.18, 0.20, 0.5, 0.0])
    >>> [t.name for t in fig.data][1]
    'elbow +1'
    """
    p = ScaraParams.resolve(p)
    x = check_angles(as_vector(x, "x"), "x", columns=(3,))
    status, values = _inverse_kinematics(x, p)
    if status != 0:
        raise UnreachableError(_unreachable_message(x, status, p))
    return _inverse_kinematics_drawing(values, p, height, exact=False)


def _reach_title(x, status, values, p) -> str:
    """Two title lines for the target ``x`` reached (``status`` 0) or refused, from the outputs ``values`` of
    :func:`_inverse_kinematics`."""
    r = values["r"]
    head = f"p = ({x[0]:.2f}, {x[1]:.2f}, {x[2]:.2f}) m, r = {r:.3f} m"
    if status != 0:
        if r > p.r_max:
            why = f"out of reach: r > a1 + a2 = {p.r_max:g} m"
        elif r < p.r_min:
            why = f"out of reach: r < |a1 − a2| = {p.r_min:g} m"
        else:
            why = f"out of reach: d3 = {p.d0 - x[2]:.2f} m is off the stroke"
        return f"{head}<br>{why}"
    t_up, t_down = (round(values[key], 1) + 0.0 for key in ("theta2_up", "theta2_down"))
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
    check_angles(x, "x", columns=(3,))
    targets, runs = [], []
    for v in values:
        t = x.copy()
        t[component] = v
        targets.append(t)
        runs.append(_inverse_kinematics(t, p))
    if runs[0][0] != 0:
        raise UnreachableError(f"the first target {targets[0][:3].round(4).tolist()} m is out of reach: start the "
                               "slider at a reachable value")
    fig = inverse_kinematics_figure(targets[0], p, height=height)
    names = [t.name for t in fig.data]
    moving = [names.index("elbow +1"), names.index("elbow −1"), names.index("target")]
    steps = []
    for v, t, (status, s) in zip(values, targets, runs):
        xs = [as_list(s[f"{key}_x"]) if status == 0 else [] for key in ("up", "down")]
        ys = [as_list(s[f"{key}_y"]) if status == 0 else [] for key in ("up", "down")]
        xs.append([round(float(t[0]), 4)])
        ys.append([round(float(t[1]), 4)])
        steps.append(dict(label=f"{v:.2f}", method="update",
                          args=[{"x": xs, "y": ys}, {"title.text": _reach_title(t, status, s, p)}, moving]))
    fig.layout.title.text = _reach_title(targets[0], *runs[0], p)
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
                             text=["folded", "stretched", "folded"],
                             # off the curves: beside the ends, and below-right of 0° where both curves rise
                             textposition=["middle left", "bottom right", "middle right"],
                             marker=dict(size=11, color=PALETTE["reference"], symbol="circle-open", line=dict(width=2))))
    finish_layout(fig, "det J_A against θ2 (θ1, d3, θ4 held)", height)
    fig.update_xaxes(title_text="θ2 (°)", tickvals=list(range(-180, 181, 90)), range=[-250, 250])
    fig.update_yaxes(title_text="det J_A (m²)")
    return fig



def arm_pair(p=None, height: int = ARM_PANEL_HEIGHT) -> FigurePair:
    """The direct-kinematics panel's figure: :func:`arm_panel_figure` of the outputs of
    :func:`scara.programs.kinematics.kinematics_program` (run on :func:`arm_program_data` of the same ``p`` and
    ``height``)."""
    p = ScaraParams.resolve(p)
    return FigurePair("arm", lambda values: arm_panel_figure(values, p, height=height))


def inverse_kinematics_pair(p=None, height: int = IK_PANEL_HEIGHT) -> FigurePair:
    """The inverse-kinematics panel's figure: :func:`inverse_kinematics_panel_figure` of the outputs of
    :func:`scara.programs.kinematics.inverse_kinematics_program`."""
    p = ScaraParams.resolve(p)
    return FigurePair("inverse kinematics", lambda values: inverse_kinematics_panel_figure(values, p, height=height))
