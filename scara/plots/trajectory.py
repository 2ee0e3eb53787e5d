"""Figures of chapter 3 (trajectory planning): the path in 3-D and from above, the time profiles with the
segments shaded, a via point's corner with and without anticipation (also as a kernel-free slider figure),
the joint motion with the manipulability met along the path, and the tool path of a joint-space trajectory
against the operational one (a kernel-free slider over the number of knots).

Every builder takes a :class:`~scara.trajectory.Trajectory` (or the inputs of
:func:`~scara.trajectory.plan_path`) and returns a ``plotly.graph_objects.Figure``. Long series are decimated
to about ``points`` samples for drawing, always keeping the stop instants, so pages stay light. The live waypoint
editor's figures (:func:`editor_top_figure`, :func:`editor_profiles_figure`) are drawn instead from the outputs of
its page program (:mod:`scara.programs.trajectory`), which thins the series the same way, and
:func:`editor_bindings` declares how a move redraws them.
"""
from __future__ import annotations

import math

import numpy as np
import plotly.graph_objects as go
from plotly.subplots import make_subplots

from ..errors import ScaraError, as_array, check_count
from ..trajectory import Trajectory, Trapezoidal, plan_path
from ..trajectory.joint import KINDS, joint_counterpart, path_deviation
from ._common import AXIS_COLOURS, DASHES, JOINT_COLOURS, PALETTE, as_list, slider
from ._common import MAX_POINTS, MAX_SLIDER_SAMPLES, FIGURE_BUDGET
from .panels import Flag, Text
from .kinematics import top_view_arm
from .layout import _text_width, finish_layout, stacked_axes

__all__ = [
    "decimate",
    "timing_law_figure",
    "path_figure",
    "top_view_figure",
    "top_view_series",
    "profiles_figure",
    "profiles_series",
    "segment_shapes",
    "corner_figure",
    "anticipation_slider_figure",
    "joint_profiles_figure",
    "joint_space_series",
    "joint_space_figure", "EDITOR_TOP_ROLES", "PROFILE_ROLES", "editor_labels", "editor_top_figure",
    "editor_profiles_figure", "editor_bindings", "editor_pairs",
]

_VIA_COLOUR = "#E69F00"
_ARC_COLOUR = "#CC79A7"
_COMP = ("x", "y", "z")
#: a plan that stops at a point, drawn against the reference (black, solid): grey and dashed
_STOP_LINE = dict(color="#999999", dash="dash")
#: the reference trajectory or the plan under the slider: black and solid, as the reference everywhere
_VIA_LINE = dict(color=PALETTE["reference"], dash="solid")


def _r(values, digits=5):
    """Rounded float32 values for drawing: light pages (plotly stores arrays in binary) and fast figures
    (plotly validates an array at once, a list item by item); 7 significant digits are plenty on screen."""
    return np.round(np.asarray(values, dtype=float), digits).astype(np.float32)


def _check(traj):
    if not isinstance(traj, Trajectory):
        raise ScaraError(f"expected a Trajectory (from plan_path or reference_trajectory), got {type(traj).__name__}")
    return traj


def decimate(traj: Trajectory, points: int = 2000, lo: float | None = None, hi: float | None = None) -> np.ndarray:
    """Indices of about ``points`` samples of ``traj`` in ``[lo, hi]`` (s), evenly spaced, plus every segment
    start and end inside the window (so corners and stops are drawn where they are).

    Limits: ``points`` from 2 to 10 000 samples per curve (``MAX_POINTS``); a value outside, or not a whole number,
    raises :class:`ScaraError` before any work."""
    points = check_count(points, "points", 2, MAX_POINTS, "samples per curve", FIGURE_BUDGET)
    t = traj.t
    k0 = 0 if lo is None else int(np.searchsorted(t, lo))
    k1 = t.size - 1 if hi is None else int(np.searchsorted(t, hi, side="right")) - 1
    if k1 <= k0:
        raise ScaraError(f"the window [{lo}, {hi}] s holds no samples of the trajectory (0 to {t[-1]:g} s)")
    base = np.linspace(k0, k1, points).round().astype(int)
    marks = np.round(np.r_[traj.segment_start, traj.segment_end] / traj.dt).astype(int)
    marks = marks[(marks >= k0) & (marks <= k1)]
    return np.unique(np.r_[base, marks])


def timing_law_figure(law: Trapezoidal, points: int = 401, title: str | None = None, height: int = 520) -> go.Figure:
    """The trapezoidal timing law of one segment: ``s``, ``sdot`` and ``sddot`` against the time since its start,
    the two blends shaded (the law of Siciliano et al., eq. 4.8, with ``t_f`` its duration).

    Limits: ``points`` from 2 to 10 000 samples per curve (``MAX_POINTS``); a value outside, or not a whole number,
    raises :class:`ScaraError` before any work."""
    points = check_count(points, "points", 2, MAX_POINTS, "samples per curve", FIGURE_BUDGET)
    if not isinstance(law, Trapezoidal):
        raise ScaraError(f"expected a Trapezoidal timing law, got {type(law).__name__}")
    T, tc = law.duration, law.blend
    tau = np.unique(np.r_[np.linspace(0.0, T, points), tc, T - tc, np.nextafter(T - tc, 0), np.nextafter(tc, 0)])
    s, sd, sdd = law.evaluate(tau)
    sdd[-1] = -law.acceleration  # draw the last blend up to its end
    fig = make_subplots(rows=3, cols=1, shared_xaxes=True, vertical_spacing=0.05)
    for row, (y, name) in enumerate(((s, "s"), (sd, "ṡ"), (sdd, "s̈")), 1):
        fig.add_trace(go.Scatter(x=_r(tau, 4), y=_r(y, 6), mode="lines", name=name,
                                 line=dict(color=PALETTE["reference"], width=2, dash=DASHES[row - 1])), row=row, col=1)
    stacked_axes(fig, ("s (m)", "ṡ (m/s)", "s̈ (m/s²)"), "time in the segment, τ (s)")   # fits 390 px
    shapes = [dict(type="rect", xref="x", yref="paper", x0=a, x1=b, y0=0, y1=1, layer="below", fillcolor=_VIA_COLOUR,
                   opacity=0.2, line=dict(width=0)) for a, b in ((0.0, tc), (T - tc, T))]
    fig.add_trace(go.Scatter(x=[None], y=[None], mode="lines", name="blends", showlegend=True, hoverinfo="skip",
                             line=dict(color=_VIA_COLOUR, width=10), opacity=0.35))
    return finish_layout(fig, title or f"L = {law.length:.3f} m, t_f = {T:g} s, t_c = {tc:.3g} s", height,
                         shapes=shapes)


#: font size (px) of the waypoint labels, and the label boxes' place around a marker of size 10, measured in
#: Chromium (px, screen y pointing down): the horizontal span of a label ``w`` px wide, the vertical span
_LABEL_FONT = 12
_LABEL_X = {"center": lambda w: (-w / 2, w / 2), "right": lambda w: (7.2, 7.2 + w), "left": lambda w: (-6.9 - w, -6.9)}
_LABEL_Y = {"top": (-21.2, -7.2), "bottom": (5.2, 19.2), "middle": (-8.0, 6.0)}
#: the label positions tried, in order of preference
_LABEL_POSITIONS = ("top center", "bottom center", "top right", "top left", "bottom right", "bottom left",
                    "middle right", "middle left")
#: where a label of a crowded 3-D scene may also go: as far again from its point (``_FAR`` px further out, a thin
#: leader line from the label to the point saying which point it names), at a cost (``_FAR_COST``) over a label
#: beside its point
_FAR = 26.0
_FAR_COST = 120.0
_FAR_POSITIONS = tuple("far " + p_ for p_ in _LABEL_POSITIONS)
#: the drawing scales (px per m) a top view takes, from a phone-width page to a laptop screen
_TOP_VIEW_SCALES = (300.0, 340.0, 450.0, 600.0, 800.0)


def _label_box(position, x, y, width):
    """The box ``(x0, y0, x1, y1)`` (screen px, y down) of a label ``width`` px wide placed at plotly's
    ``textposition`` ``position`` around a marker at ``(x, y)``."""
    far, (vert, horiz) = position.startswith("far "), position.removeprefix("far ").split()
    x0, x1 = _LABEL_X[horiz](width)
    y0, y1 = _LABEL_Y[vert]
    if far:
        d = np.array([{"center": 0.0, "right": 1.0, "left": -1.0}[horiz], {"top": -1.0, "bottom": 1.0, "middle": 0.0}[vert]])
        dx, dy = _FAR * d / np.hypot(*d)
        x0, x1, y0, y1 = x0 + dx, x1 + dx, y0 + dy, y1 + dy
    return x + x0, y + y0, x + x1, y + y1


def _box_distance(box, points):
    """Distance (px) from the box ``(x0, y0, x1, y1)`` to each of ``points`` (k, 2): 0 inside."""
    points = np.asarray(points, float)
    dx = np.maximum.reduce([box[0] - points[:, 0], np.zeros(len(points)), points[:, 0] - box[2]])
    dy = np.maximum.reduce([box[1] - points[:, 1], np.zeros(len(points)), points[:, 1] - box[3]])
    return np.hypot(dx, dy)


def _segment_distance(a, b, points):
    """Distance (px) from the segment ``a``-``b`` to each of ``points`` (k, 2)."""
    a, b, points = np.asarray(a, float), np.asarray(b, float), np.asarray(points, float)
    d = b - a
    t = np.clip(((points - a) @ d) / max(float(d @ d), 1e-12), 0.0, 1.0)
    return np.hypot(*(points - (a + t[:, None] * d)).T)


def _boxes_overlap(a, b, pad=1.0):
    return a[0] < b[2] + pad and b[0] < a[2] + pad and a[1] < b[3] + pad and b[1] < a[3] + pad


def _box_hits_polyline(box, xy, pad=1.0):
    """True when some piece of the polyline ``xy`` (m, 2) (screen px) passes through ``box`` (grown by ``pad``):
    Liang-Barsky clipping of every piece at once."""
    if len(xy) < 2:
        return False
    x0, y0, x1, y1 = box[0] - pad, box[1] - pad, box[2] + pad, box[3] + pad
    a, d = xy[:-1], np.diff(xy, axis=0)
    lo, hi = np.zeros(len(d)), np.ones(len(d))
    edges = ((-d[:, 0], a[:, 0] - x0), (d[:, 0], x1 - a[:, 0]), (-d[:, 1], a[:, 1] - y0), (d[:, 1], y1 - a[:, 1]))
    for p_, q_ in edges:
        with np.errstate(divide="ignore", invalid="ignore"):
            r = q_ / p_
        par = p_ == 0
        lo = np.where(~par & (p_ < 0), np.maximum(lo, r), lo)
        hi = np.where(~par & (p_ > 0), np.minimum(hi, r), hi)
        out = par & (q_ < 0)
        lo = np.where(out, 2.0, lo)
    return bool(np.any(lo <= hi))


def _place_waypoint_labels(views, texts, weights=(1000.0, 300.0, 300.0, 40.0)):
    """A ``textposition`` per label such that, at every drawing scale, no two labels overlap and none sits on a
    curve to avoid, if such a choice exists (the least overlap otherwise).

    ``views``: one dict per drawing scale with ``points`` (k, 2) the labelled markers in screen px (y down),
    ``avoid`` a list of polylines (m, 2) in px the labels must not cover (the arc), ``curves`` polylines they
    had better not cover (the path), and optionally ``markers`` (j, 2) other markers and ``forbid``
    ``{index: positions}`` places a label may not take. Empty texts are not placed. The cost of a choice adds,
    over the scales, ``weights``: a pair of overlapping labels, a label on a curve to avoid, on a marker or whose
    box is nearer (or within 4 px as near) to another point than to its own, on the path; plus a tenth per step
    down the order of preference of :data:`_LABEL_POSITIONS`. The choice is made by simulated annealing
    with a fixed seed (the same labels always get the same places), then polished label by label.
    """
    k = len(texts)
    todo = [i for i in range(k) if texts[i]]
    unary, pair = _label_costs(views, texts, todo, weights)
    state = _least_cost_places(unary, pair, todo)
    return [_positions(views)[state[i]] if i in todo else "top center" for i in range(k)]


def _positions(views):
    """The places a label may take in ``views``: beside its point, and with ``far`` views also further out."""
    return _LABEL_POSITIONS + (_FAR_POSITIONS if any(v.get("far") for v in views) else ())


def _label_costs(views, texts, todo, weights):
    """The costs of :func:`_place_waypoint_labels`: ``unary[i, a]`` of label ``i`` at place ``a`` (k, npos) and
    ``pair[i, a, j, b]`` of labels ``i`` at ``a`` and ``j`` at ``b`` together (k, npos, k, npos)."""
    k = len(texts)
    widths = [_text_width(t, _LABEL_FONT) for t in texts]
    places = _positions(views)
    npos = len(places)
    w_label, w_avoid, w_marker, w_curve = weights
    pts0 = np.asarray(views[0]["points"], float)
    # coincident points (p0 and p11) share one label: neither is the other's neighbour
    same = np.all(np.isclose(pts0[:, None, :], pts0[None, :, :]), axis=-1)

    unary = np.zeros((k, npos))
    boxes = []                        # boxes[v][i][a]
    for v in views:
        pts = np.asarray(v["points"], float)
        extra = np.reshape(v.get("markers", np.zeros((0, 2))), (-1, 2))
        per = []
        for i in range(k):
            per.append([_label_box(p_, pts[i, 0], pts[i, 1], widths[i]) for p_ in places])
            if i not in todo:
                continue
            others = np.r_[pts[[j for j in range(k) if not same[i, j]]], extra]
            for a, box in enumerate(per[i]):
                c = w_avoid * (places[a] in v.get("forbid", {}).get(i, ()))
                c += sum(w_avoid for line in v.get("avoid", ()) if _box_hits_polyline(box, line))
                c += sum(w_curve for line in v.get("curves", ()) if _box_hits_polyline(box, line))
                inside = ((others[:, 0] > box[0] - 5) & (others[:, 0] < box[2] + 5)
                          & (others[:, 1] > box[1] - 5) & (others[:, 1] < box[3] + 5))
                c += w_marker * int(inside.sum())
                if places[a].startswith("far "):
                    # a leader line names the point: it must pass no other point once it has left its own
                    # marker (two points a few px apart, p9 and p10 of the reference path in 3-D, each get a
                    # line leaving away from the other), and no other point may sit on its own (within 4 px)
                    c += _FAR_COST
                    tip = np.clip(pts[i], box[:2], box[2:])
                    step = tip - pts[i]
                    start = pts[i] + step * min(1.0, 6.0 / max(float(np.hypot(*step)), 1e-9))
                    if len(others) and (np.min(_segment_distance(start, tip, others)) < 6.0
                                        or np.min(np.hypot(*(others - pts[i]).T)) < 4.0):
                        c += w_marker
                # a label nearer (or within 4 px as near) to another point than to its own would seem to name
                # that point: distances from the label's box, as a reader's eye measures them
                elif len(others) and np.min(_box_distance(box, others)) < _box_distance(box, pts[i][None])[0] + 4.0:
                    c += w_marker
                unary[i, a] += c
        boxes.append(per)
    unary += 0.1 * np.arange(npos)
    pair = np.zeros((k, npos, k, npos))
    for i in todo:
        for j in todo:
            if j <= i:
                continue
            for per in boxes:
                for a in range(npos):
                    for b in range(npos):
                        if _boxes_overlap(per[i][a], per[j][b]):
                            pair[i, a, j, b] += w_label
            pair[j, :, i, :] = pair[i, :, j, :].T

    return unary, pair


def _least_cost_places(unary, pair, todo):
    """The place index per label that (nearly) minimises the total cost: a greedy start, simulated annealing
    with a fixed seed, then a polish one label at a time (see :func:`_place_waypoint_labels`)."""
    k, npos = unary.shape
    # the conflicts of each place, as short lists (most pairs of places never meet): plain Python is fast here
    un = unary.tolist()
    conflicts = [[[(j, b, float(pair[i, a, j, b])) for j in todo if j != i for b in range(npos) if pair[i, a, j, b]]
                  for a in range(npos)] for i in range(k)]

    def delta(state, i, a):
        d = un[i][a] - un[i][state[i]]
        for j, b, w in conflicts[i][a]:
            if state[j] == b:
                d += w
        for j, b, w in conflicts[i][state[i]]:
            if state[j] == b:
                d -= w
        return d

    state = [0] * k
    for i in todo:                                   # greedy start: the best place given the labels so far
        state[i] = min(range(npos), key=lambda a: un[i][a] + sum(w for j, b, w in conflicts[i][a]
                                                                  if j < i and state[j] == b))
    if todo:
        rng = np.random.default_rng(0)
        steps = 2500 * len(todo)
        picks = rng.integers(len(todo), size=steps).tolist()
        places = rng.integers(npos, size=steps).tolist()
        coins = rng.random(steps).tolist()
        cost, best_cost, best = 0.0, 0.0, list(state)
        for step in range(steps):
            i, a = todo[picks[step]], places[step]
            if a == state[i]:
                continue
            d = delta(state, i, a)
            if d < 0 or coins[step] < math.exp(-d / (200.0 * 1e-4 ** (step / steps))):
                state[i] = a
                cost += d
                if cost < best_cost - 1e-9:
                    best, best_cost = list(state), cost
        state = best
        for _ in range(10):                          # polish: move one label at a time while that helps
            moved = False
            for i in todo:
                a = min(range(npos), key=lambda b: delta(state, i, b))
                if delta(state, i, a) < -1e-9:
                    state[i], moved = a, True
            if not moved:
                break
    return state


def _merged_labels(traj, idx):
    """The label of each waypoint in ``idx``; coincident waypoints are labelled once (``"p0 = p11"``) at the first
    of them, the others get an empty label."""
    labels = []
    for i in idx:
        same = [traj.labels[j] for j in range(len(traj.labels))
                if np.linalg.norm(traj.waypoints[j] - traj.waypoints[i]) < 1e-9]
        labels.append(" = ".join(same) if same[0] == traj.labels[i] else "")
    return labels


def _project(points, scene):
    """Screen coordinates (px per unit of the normalised scene, y down) of ``points`` (k, 3) in a plotly 3-D
    ``scene`` with manual aspect ratio, seen from its camera's eye (perspective about the centre)."""
    lo, hi = scene["lo"], scene["hi"]
    aspect = np.array(scene["aspect"])
    P = (np.asarray(points, float) - (lo + hi) / 2) / np.where(hi > lo, hi - lo, 1.0) * aspect
    eye = np.array(scene["eye"])
    d = -eye / np.linalg.norm(eye)
    right = np.cross(d, [0.0, 0.0, 1.0])
    right /= np.linalg.norm(right)
    up = np.cross(right, d)
    depth = (P - eye) @ d
    return np.c_[(P @ right) / depth, -(P @ up) / depth]


def _waypoint_traces(traj, dims=3, showlegend=True, text=True, views=None):
    """The stop points and the via points (two marker traces), labelled. ``views`` (see :func:`_place_waypoint_labels`),
    built by the caller in the same order as ``traj.waypoints``, decide where each label goes; without them
    every label sits above its point."""
    n = len(traj.labels)
    labels = _merged_labels(traj, range(n))
    positions = ["top center"] * n
    if text and views is not None:
        positions = _place_waypoint_labels(views, labels)
    out = []
    for via, name, symbol, colour in ((False, "stop point", "circle", PALETTE["reference"]),
                                     (True, "via point", "diamond", _VIA_COLOUR)):
        idx = [i for i in range(n) if bool(traj.via[i]) == via]
        pts = traj.waypoints[idx]
        common = dict(mode="markers+text" if text else "markers", name=name, text=[labels[i] for i in idx],
                      textposition=[positions[i] for i in idx], textfont=dict(size=_LABEL_FONT),
                      showlegend=showlegend, hovertext=[traj.labels[i] for i in idx], hoverinfo="text")
        if dims == 3:
            out.append(go.Scatter3d(x=_r(pts[:, 0]), y=_r(pts[:, 1]), z=_r(pts[:, 2]),
                                    marker=dict(size=5, symbol=symbol, color=colour), **common))
        else:
            out.append(go.Scatter(x=_r(pts[:, 0]), y=_r(pts[:, 1]),
                                  marker=dict(size=10, symbol=symbol, color=colour,
                                              line=dict(width=1, color="white")), **common))
    return out


def _top_views(traj, path_xy, arm_xy=None, scales=_TOP_VIEW_SCALES):
    """The label-placement views of a top view (:func:`_place_waypoint_labels`) at each of ``scales`` (px per m):
    the waypoints, the arcs to keep clear, the path and the arm."""
    arcs = [traj.x[decimate(traj, 60, traj.segment_start[j], traj.segment_end[j]), :2]
            for j, kind in enumerate(traj.segment_kinds) if kind == "arc"]
    flip = np.array([1.0, -1.0])
    views = []
    for s in scales:
        curves = [np.asarray(path_xy, float) * flip * s]
        if arm_xy is not None:
            curves.append(np.asarray(arm_xy, float) * flip * s)
        views.append(dict(points=traj.waypoints[:, :2] * flip * s, avoid=[a * flip * s for a in arcs],
                          curves=curves))
    return views


#: px per unit of :func:`_project`'s screen coordinates in the 3-D path figure (plotly sizes a 3-D scene by the
#: figure's height, so the scale is the same on a phone-width page and a laptop screen: 413 px measured in
#: Chromium on the reference path)
_SCENE_SCALES = (380.0, 415.0, 450.0)
#: the 3-D path figure's aspect ratio and camera: narrow enough, with its tick labels and axis titles, to fit a
#: phone-width page
_SCENE_ASPECT = (1.2, 0.65, 0.65)
_SCENE_EYE = (0.9, -2.3, 1.0)


def _scene_box(traj, path_xyz, pad=0.06):
    """The axis ranges ``(lo, hi)`` (3,) of the 3-D path figure: the path and the waypoints with ``pad`` of each
    span more on either side, so that no point sits on the box (plotly hides a label drawn outside it)."""
    every = np.r_[path_xyz, traj.waypoints]
    lo, hi = every.min(axis=0), every.max(axis=0)
    span = np.maximum(hi - lo, 1e-3)
    return lo - pad * span, hi + pad * span


def _scene_views(traj, path_xyz, box, aspect, eye):
    """The label-placement views (:func:`_place_waypoint_labels`) of the 3-D path figure: the waypoints, the arcs and the
    path projected on the screen as the figure's camera sees them."""
    scene = dict(lo=box[0], hi=box[1], aspect=aspect, eye=eye)
    pts = _project(traj.waypoints, scene)
    path = _project(path_xyz, scene)
    arcs = [_project(traj.x[decimate(traj, 60, traj.segment_start[j], traj.segment_end[j]), :3], scene)
            for j, kind in enumerate(traj.segment_kinds) if kind == "arc"]
    # plotly does not draw a label below a point at the bottom of the box (the lowest tenth of it)
    z = traj.waypoints[:, 2]
    low = {int(i): {p_ for p_ in _LABEL_POSITIONS if p_.startswith("bottom")}
           for i in np.flatnonzero(z <= z.min() + 0.1 * (z.max() - z.min()))}
    return [dict(points=pts * s, avoid=[a * s for a in arcs], curves=[path * s], forbid=low, far=True)
            for s in _SCENE_SCALES]


def path_figure(traj: Trajectory, points: int = 2000, title: str | None = None, height: int = 520) -> go.Figure:
    """The planned path in 3-D (base frame, m), its half circle highlighted, stop and via points labelled.

    Limits: ``points`` from 2 to 10 000 samples per curve (``MAX_POINTS``); a value outside, or not a whole number,
    raises :class:`ScaraError` before any work."""
    points = check_count(points, "points", 2, MAX_POINTS, "samples per curve", FIGURE_BUDGET)
    traj = _check(traj)
    k = decimate(traj, points)
    x = traj.x[k]
    fig = go.Figure()
    fig.add_trace(go.Scatter3d(x=_r(x[:, 0]), y=_r(x[:, 1]), z=_r(x[:, 2]), mode="lines", name="path",
                               line=dict(color=PALETTE["reference"], width=4)))
    for j, kind in enumerate(traj.segment_kinds):
        if kind == "arc":
            ka = decimate(traj, 200, traj.segment_start[j], traj.segment_end[j])
            fig.add_trace(go.Scatter3d(x=_r(traj.x[ka, 0]), y=_r(traj.x[ka, 1]), z=_r(traj.x[ka, 2]), mode="lines",
                                       name=f"arc {traj.segment_labels[j]}",
                                       line=dict(color=_ARC_COLOUR, width=7)))
    aspect, eye = _SCENE_ASPECT, _SCENE_EYE
    box = _scene_box(traj, x[:, :3])
    coarse = traj.x[decimate(traj, 300), :3]      # labels are placed against a coarser copy of the path
    for tr in _waypoint_traces(traj, 3, text=False):
        fig.add_trace(tr)
    # the labels are scene annotations, which plotly anchors exactly at their points and shifts by the pixels
    # the placement assumed (WebGL text is drawn further from its point than a 2-D label)
    labels = _merged_labels(traj, range(len(traj.labels)))
    # off the path too: a label far out has room to keep clear of it
    places = _place_waypoint_labels(_scene_views(traj, coarse, box, aspect, eye), labels,
                                    weights=(1000.0, 300.0, 300.0, 200.0))
    notes = [_scene_label(traj.waypoints[i], text, places[i]) for i, text in enumerate(labels) if text]
    axes = {f"{c}axis": dict(title_text=f"{c} (m)", range=[float(box[0][i]), float(box[1][i])], nticks=4,
                             tickfont=dict(size=11), title_font=dict(size=12))
            for i, c in enumerate("xyz")}
    finish_layout(fig, title or "The reference path in the base frame", height,
                  scene=dict(**axes, aspectmode="manual", aspectratio=dict(zip("xyz", aspect)),
                             camera=dict(eye=dict(zip("xyz", eye))), annotations=notes))
    # a 3-D scene is drawn at a size set by its height: the side margins would only cut it on a phone
    return fig.update_layout(margin=dict(l=0, r=0))


def _scene_label(point, text, position) -> dict:
    """A waypoint's label as a plotly scene annotation at ``point`` (3,), its box where :func:`_label_box` puts
    a 2-D label at ``position`` (a plotly ``textposition``)."""
    font = dict(size=_LABEL_FONT, color=PALETTE["reference"])
    if position.startswith("far "):
        # the label's centre where the placement put it, a thin leader line from it to the point
        x0, y0, x1, y1 = _label_box(position, 0.0, 0.0, _text_width(text, _LABEL_FONT))
        return dict(x=float(point[0]), y=float(point[1]), z=float(point[2]), text=text, showarrow=True,
                    ax=round((x0 + x1) / 2, 1), ay=round((y0 + y1) / 2, 1), arrowhead=0, arrowwidth=1,
                    arrowcolor="#888888", standoff=3, borderpad=0, font=font)
    vert, horiz = position.split()
    xanchor, xshift = {"center": ("center", 0.0), "right": ("left", 7.2), "left": ("right", -6.9)}[horiz]
    yanchor, yshift = {"top": ("bottom", 7.2), "bottom": ("top", -5.2), "middle": ("middle", 1.0)}[vert]
    return dict(x=float(point[0]), y=float(point[1]), z=float(point[2]), text=text, showarrow=False,
                xanchor=xanchor, yanchor=yanchor, xshift=xshift, yshift=yshift, borderpad=0, font=font)


def top_view_series(traj: Trajectory, points: int = 2000) -> dict:
    """The data :func:`top_view_figure` draws: the path's ``x``, ``y`` (decimated to about ``points``) and the
    stop and via points (``x``, ``y``, labels), so that a live panel can redraw an edited path from these.

    Limits: ``points`` from 2 to 10 000 samples per curve (``MAX_POINTS``); a value outside, or not a whole number,
    raises :class:`ScaraError` before any work."""
    points = check_count(points, "points", 2, MAX_POINTS, "samples per curve", FIGURE_BUDGET)
    traj = _check(traj)
    k = decimate(traj, points)
    arm = top_view_arm(traj.q0, traj.params)
    # labels are placed against a coarser copy of the path: decimate keeps every corner, and a line is a line
    views = _top_views(traj, traj.x[decimate(traj, 300), :2], np.c_[arm.x, arm.y])
    wp = [dict(x=t.x, y=t.y, text=t.text, textposition=t.textposition, hovertext=t.hovertext)
          for t in _waypoint_traces(traj, 2, views=views)]
    return dict(path=(_r(traj.x[k, 0]), _r(traj.x[k, 1])), stop=wp[0], via=wp[1])


def top_view_figure(traj: Trajectory, points: int = 2000, arm: bool = True, title: str | None = None,
                    height: int = 460) -> go.Figure:
    """The path seen from above (x-y plane of the base frame, m) with the arm in its start configuration.

    The waypoints' labels are annotations: on a phone-width page six waypoints stand on one line within 80 px
    (p9 and p10 6 px apart), where no place beside a marker is nearer to it than to its neighbours; such a label
    goes further out with a thin leader line to its point, as in :func:`path_figure`.

    Limits: ``points`` from 2 to 10 000 samples per curve (``MAX_POINTS``); a value outside, or not a whole number,
    raises :class:`ScaraError` before any work."""
    points = check_count(points, "points", 2, MAX_POINTS, "samples per curve", FIGURE_BUDGET)
    traj = _check(traj)
    series = top_view_series(traj, points)
    fig = go.Figure()
    if arm:
        fig.add_trace(top_view_arm(traj.q0, traj.params, name="arm at t = 0", opacity=0.5))
    fig.add_trace(go.Scatter(x=series["path"][0], y=series["path"][1], mode="lines", name="path",
                             line=dict(color=PALETTE["reference"], width=2)))
    for tr in _waypoint_traces(traj, 2, text=False):
        fig.add_trace(tr)
    arm_xy = top_view_arm(traj.q0, traj.params)
    views = [dict(v, far=True) for v in _top_views(traj, traj.x[decimate(traj, 300), :2],
                                                   np.c_[arm_xy.x, arm_xy.y])]
    labels = _merged_labels(traj, range(len(traj.labels)))
    # off the path and the arm too: a label far out has room to keep clear of them
    places = _place_waypoint_labels(views, labels, weights=(1000.0, 300.0, 300.0, 200.0))
    notes = [dict(_scene_label(traj.waypoints[i], text, places[i]), xref="x", yref="y")
             for i, text in enumerate(labels) if text]
    for a in notes:
        a.pop("z")
    finish_layout(fig, title or "The path seen from above", height, annotations=notes)
    fig.update_xaxes(title_text="x (m)")
    fig.update_yaxes(title_text="y (m)", scaleanchor="x", scaleratio=1)
    return fig


def segment_shapes(traj, lo=None, hi=None):
    """Alternating light bands over the segments and orange bands over the via-point overlaps."""
    shapes = []
    lo = traj.t[0] if lo is None else lo
    hi = traj.t[-1] if hi is None else hi
    for j in range(len(traj.segments)):
        a, b = max(traj.segment_start[j], lo), min(traj.segment_end[j], hi)
        if b > a and j % 2 == 0:
            shapes.append(dict(type="rect", xref="x", yref="paper", x0=a, x1=b, y0=0, y1=1, layer="below",
                               fillcolor="#000000", opacity=0.05, line=dict(width=0)))
    for i in np.flatnonzero(traj.via):
        a, b = max(traj.segment_start[i], lo), min(traj.segment_end[i - 1], hi)
        if b > a:
            shapes.append(dict(type="rect", xref="x", yref="paper", x0=a, x1=b, y0=0, y1=1, layer="below",
                               fillcolor=_VIA_COLOUR, opacity=0.25, line=dict(width=0)))
    return shapes


def profiles_series(traj: Trajectory, points: int = 2000) -> list:
    """The ``(t, y)`` arrays of :func:`profiles_figure`'s traces, in order: ``p_x, p_y, p_z`` of the position,
    then of the velocity, then of the acceleration, then ``phi`` (degrees).

    Limits: ``points`` from 2 to 10 000 samples per curve (``MAX_POINTS``); a value outside, or not a whole number,
    raises :class:`ScaraError` before any work."""
    points = check_count(points, "points", 2, MAX_POINTS, "samples per curve", FIGURE_BUDGET)
    traj = _check(traj)
    k = decimate(traj, points)
    t = _r(traj.t[k], 4)
    out = [(t, _r(arr[k, c], 6)) for arr in (traj.x, traj.xd, traj.xdd) for c in range(3)]
    return out + [(t, _r(np.degrees(traj.x[k, 3]), 4))]


def profiles_figure(traj: Trajectory, points: int = 2000, title: str | None = None, height: int = 560) -> go.Figure:
    """Position, velocity and acceleration of x, y, z against time, and phi, with the segments shaded
    (grey: every other segment; orange: overlaps at via points, where two segments move at once).

    Limits: ``points`` from 2 to 10 000 samples per curve (``MAX_POINTS``); a value outside, or not a whole number,
    raises :class:`ScaraError` before any work."""
    points = check_count(points, "points", 2, MAX_POINTS, "samples per curve", FIGURE_BUDGET)
    traj = _check(traj)
    series = profiles_series(traj, points)
    fig = make_subplots(rows=4, cols=1, shared_xaxes=True, vertical_spacing=0.04,
                        row_heights=[0.3, 0.3, 0.3, 0.1])
    labels = ("p (m)", "ṗ (m/s)", "p̈ (m/s²)")
    for row in range(1, 4):
        for c in range(3):
            x, y = series[3 * (row - 1) + c]
            fig.add_trace(go.Scatter(x=x, y=y, mode="lines", name=f"p_{_COMP[c]}",
                                     legendgroup=_COMP[c], showlegend=row == 1,
                                     line=dict(color=AXIS_COLOURS[c], width=1.6, dash=DASHES[c])), row=row, col=1)
    fig.add_trace(go.Scatter(x=series[9][0], y=series[9][1], mode="lines", name="φ",
                             line=dict(color=AXIS_COLOURS[3], width=1.6, dash=DASHES[3])), row=4, col=1)
    stacked_axes(fig, labels + ("φ (°)",))
    fig.update_yaxes(nticks=3, row=4, col=1)
    _band_legend(fig)
    return finish_layout(fig, title or "Position, velocity, acceleration", height, shapes=segment_shapes(traj))


def _band_legend(fig):
    """Legend entries for the shaded bands of :func:`segment_shapes` (shapes have none of their own)."""
    fig.add_trace(go.Scatter(x=[None], y=[None], mode="lines", name="via overlap", hoverinfo="skip",
                             line=dict(color=_VIA_COLOUR, width=10), opacity=0.4))


def _window(traj, i, margin):
    """From ``margin`` s before the outgoing segment starts to ``margin`` s after the incoming one ends."""
    return max(traj.segment_start[i] - margin, 0.0), min(traj.segment_end[i - 1] + margin, traj.t[-1])


def _corner_data(traj, i, lo, hi, points):
    k = decimate(traj, points, lo, hi)
    return traj.x[k, 0], traj.x[k, 1], traj.t[k], np.linalg.norm(traj.xd[k, :3], axis=1)


def _corner_layout(fig, traj, i, title, height, zoom, **kw):
    """Top row: the corner seen from above (equal scales, +-``zoom`` m around the point); bottom row: the speed."""
    pv = traj.waypoints[i]
    finish_layout(fig, title, height, **kw)
    fig.update_xaxes(title_text="x (m)", range=[pv[0] - zoom, pv[0] + zoom], constrain="domain", row=1, col=1)
    fig.update_yaxes(title_text="y (m)", range=[pv[1] - zoom, pv[1] + zoom], scaleanchor="x", scaleratio=1,
                     row=1, col=1)
    fig.update_xaxes(title_text="t (s)", row=2, col=1)
    fig.update_yaxes(title_text="|ṗ| (m/s)", rangemode="tozero", row=2, col=1)   # no longer than its panel


def _corner_grid():
    return make_subplots(rows=2, cols=1, row_heights=[0.58, 0.42], vertical_spacing=0.16)


def corner_figure(with_via: Trajectory, without: Trajectory, index: int, margin: float = 3.0, zoom: float = 0.03,
                  points: int = 400, title: str | None = None, height: int = 540) -> go.Figure:
    """A via point's corner seen from above (top) and the speed around it (bottom), for the trajectory that
    anticipates the next segment (``with_via``, black and solid like the reference) and one that stops there
    (``without``, grey and dashed).

    Limits: ``points`` from 2 to 10 000 samples per curve (``MAX_POINTS``); a value outside, or not a whole number,
    raises :class:`ScaraError` before any work."""
    points = check_count(points, "points", 2, MAX_POINTS, "samples per curve", FIGURE_BUDGET)
    _check(with_via), _check(without)
    lab = with_via.labels[index]
    fig = _corner_grid()
    for traj, name, line in ((without, f"stop at {lab}", _STOP_LINE),
                             (with_via, f"via, {with_via.anticipations[index]:g} s ahead", _VIA_LINE)):
        lo, hi = _window(traj, index, margin)
        x, y, t, v = _corner_data(traj, index, lo, hi, points)
        fig.add_trace(go.Scatter(x=_r(x), y=_r(y), mode="lines", name=name, legendgroup=name,
                                 line=dict(line, width=2.5)), row=1, col=1)
        fig.add_trace(go.Scatter(x=_r(t, 4), y=_r(v, 6), mode="lines", name=name, legendgroup=name, showlegend=False,
                                 line=dict(line, width=2.5)), row=2, col=1)
    pv = with_via.waypoints[index]
    fig.add_trace(go.Scatter(x=[pv[0]], y=[pv[1]], mode="markers+text", text=[lab], textposition="bottom right",
                             name=f"point {lab}", marker=dict(symbol="diamond", size=10, color=_VIA_COLOUR)),
                  row=1, col=1)
    _corner_layout(fig, with_via, index, title or f"The corner at {lab}, from above, and the speed", height, zoom)
    return fig


def anticipation_slider_figure(plan: dict, index: int, values=None, margin: float = 3.0, zoom: float = 0.03,
                               points: int = 300, title: str | None = None, height: int = 560) -> go.Figure:
    """Kernel-free slider figure: the corner at waypoint ``index`` (top view, top) and the speed around it
    (bottom), as its anticipation takes each of ``values`` (s; default 0 to 3 s by 0.25 s). ``plan`` holds the
    keyword arguments of :func:`plan_path` (e.g. :func:`~scara.trajectory.reference_plan()`); the other
    waypoints are unchanged. At 0 the arm stops at the point (grey, dashed, always shown); the distance by
    which the corner is cut grows with the anticipation. Raises :class:`ScaraError` for fewer than 2 or more
    than 25 values.

    Limits: ``points`` from 2 to 10 000 samples per curve (``MAX_POINTS``), and at most 100 000 samples per curve
    in all the steps together (values × ``points``, ``MAX_SLIDER_SAMPLES``); a value outside, or not a whole
    number, raises :class:`ScaraError` before any work (each value re-plans the path)."""
    points = check_count(points, "points", 2, MAX_POINTS, "samples per curve", FIGURE_BUDGET)
    if values is None:
        values = np.arange(0.0, 3.01, 0.25)
    else:
        values = as_array(values, "values", (len(np.atleast_1d(values)),))
    if values.size < 2 or values.size > 25:
        raise ScaraError(f"give between 2 and 25 anticipation values, got {values.size}")
    check_count(values.size * points, f"{values.size} values × points {points}", 1, MAX_SLIDER_SAMPLES, "samples per curve in all the slider steps", FIGURE_BUDGET)
    wps = list(plan["waypoints"])
    lab = wps[index].label or f"p{index}"
    trajs = []
    for a in values:
        kw = dict(plan, waypoints=[w.replace(anticipation=float(a)) if j == index else w for j, w in enumerate(wps)])
        trajs.append(plan_path(**kw))
    # one common time window: around the arrival at the point when it is a stop
    stop = trajs[0]
    lo = stop.segment_end[index - 1] - float(values.max()) - margin
    hi = stop.segment_end[index - 1] + margin
    data = [_corner_data(tr, index, max(lo, 0.0), min(hi, tr.t[-1]), points) for tr in trajs]
    dist = [tr.corner_distances().get(lab, (0.0, 0.0))[0] if a > 0 else 0.0 for tr, a in zip(trajs, values)]

    fig = _corner_grid()
    x, y, t, v = data[0]
    fig.add_trace(go.Scatter(x=_r(x), y=_r(y), mode="lines", name=f"stop at {lab}",
                             line=dict(_STOP_LINE, width=2)), row=1, col=1)
    fig.add_trace(go.Scatter(x=_r(t, 4), y=_r(v, 6), mode="lines", name=f"stop at {lab}",
                             showlegend=False, line=dict(_STOP_LINE, width=2)), row=2, col=1)
    # the slider opens at the plan's own anticipation (the reference's, as in the figures around it)
    a0 = int(np.argmin(np.abs(values - float(wps[index].anticipation))))
    x, y, t, v = data[a0]
    name = "anticipation on the slider"
    fig.add_trace(go.Scatter(x=_r(x), y=_r(y), mode="lines", name=name, line=dict(_VIA_LINE, width=3)),
                  row=1, col=1)
    fig.add_trace(go.Scatter(x=_r(t, 4), y=_r(v, 6), mode="lines", name=name, showlegend=False,
                             line=dict(_VIA_LINE, width=3)), row=2, col=1)
    pv = stop.waypoints[index]
    fig.add_trace(go.Scatter(x=[pv[0]], y=[pv[1]], mode="markers+text", text=[lab], textposition="bottom right",
                             name=f"point {lab}", marker=dict(symbol="diamond", size=10, color=_VIA_COLOUR)),
                  row=1, col=1)
    heading = title or f"Anticipation at {lab}"

    def head(a, d):
        return f"{heading}: {a:g} s<br>the arm passes {1000 * d:.1f} mm from {lab}"

    steps = []
    for a, (x, y, t, v), d in zip(values, data, dist):
        steps.append(dict(label=f"{a:g}", method="update", args=[
            {"x": [_r(x), _r(t, 4)], "y": [_r(y), _r(v, 6)]}, {"title.text": head(a, d)}, [2, 3]]))
    _corner_layout(fig, stop, index, head(values[a0], dist[a0]), height, zoom,
                   sliders=[slider(steps, "anticipation (s): ", active=a0, pad_top=50)])
    fig.update_layout(margin=dict(b=110))
    return fig


def joint_profiles_figure(traj: Trajectory, points: int = 2000, p=None, title: str | None = None,
                          height: int = 560) -> go.Figure:
    """The joint motion the path implies (closed-form inverse kinematics with the trajectory's elbow) and the
    manipulability ``w = a1 a2 |sin θ2|`` met along it, its minimum marked.

    Limits: ``points`` from 2 to 10 000 samples per curve (``MAX_POINTS``); a value outside, or not a whole number,
    raises :class:`ScaraError` before any work."""
    points = check_count(points, "points", 2, MAX_POINTS, "samples per curve", FIGURE_BUDGET)
    traj = _check(traj)
    q = traj.joints(p)
    w = traj.manipulability(p)
    k = decimate(traj, points)
    t = _r(traj.t[k], 4)
    fig = make_subplots(rows=3, cols=1, shared_xaxes=True, vertical_spacing=0.05, row_heights=[0.45, 0.2, 0.35])
    for j, name in ((0, "θ1"), (1, "θ2"), (3, "θ4")):
        fig.add_trace(go.Scatter(x=t, y=_r(np.degrees(q[k, j]), 3), mode="lines", name=name,
                                 line=dict(color=JOINT_COLOURS[j], width=1.8, dash=DASHES[j])), row=1, col=1)
    fig.add_trace(go.Scatter(x=t, y=_r(q[k, 2], 5), mode="lines", name="d3",
                             line=dict(color=JOINT_COLOURS[2], width=1.8, dash=DASHES[2])), row=2, col=1)
    fig.add_trace(go.Scatter(x=t, y=_r(w[k], 5), mode="lines", name="w",
                             line=dict(color=PALETTE["reference"], width=1.8)), row=3, col=1)
    km = int(np.argmin(w))
    fig.add_trace(go.Scatter(x=[round(float(traj.t[km]), 3)], y=[round(float(w[km]), 5)], mode="markers+text",
                             text=[f"{w[km]:.4f} m² at {traj.t[km]:.1f} s"], textposition="bottom right",
                             name="min w", marker=dict(size=10, color=PALETTE["force"], symbol="diamond")),
                  row=3, col=1)
    stacked_axes(fig, ("angle (°)", "d3 (m)", "w (m²)"))
    # from a little under zero: the panel's "0" would sit on the time axis's "0" in the corner
    top = float(w.max()) * 1.08
    fig.update_yaxes(range=[-0.12 * top, top], row=3, col=1)
    _band_legend(fig)
    return finish_layout(fig, title or "Joint motion and manipulability", height, shapes=segment_shapes(traj))


#: colour of the joint-space trajectory's tool path and its knots
_JOINT_COLOUR = PALETTE["inverse"]


def joint_space_series(traj: Trajectory, extra: int = 0, kind: str = "cubic", points: int = 600) -> dict:
    """The data :func:`joint_space_figure` draws for ``extra`` knots per segment: the joint-space counterpart's
    tool path (``x``, ``y``, m) and knots, and the distance from the operational path against time (``t`` s,
    ``d`` mm), decimated to about ``points`` samples keeping the knots and the farthest sample; ``max_mm`` the
    largest distance (over every sample), ``max_t`` when, ``knots`` their number.

    Limits: ``points`` from 2 to 10 000 samples per curve (``MAX_POINTS``); a value outside, or not a whole number,
    raises :class:`ScaraError` before any work."""
    points = check_count(points, "points", 2, MAX_POINTS, "samples per curve", FIGURE_BUDGET)
    traj = _check(traj)
    jt = joint_counterpart(traj, kind, extra=extra)
    d = path_deviation(jt, traj)
    x = jt.tool()[0]
    k_max = int(np.argmax(d))
    knots = np.round(jt.times / jt.dt).astype(int)
    k = np.unique(np.r_[np.linspace(0, jt.t.size - 1, points).round().astype(int), knots, k_max])
    return dict(x=_r(x[k, 0]), y=_r(x[k, 1]), knot_x=_r(x[knots, 0]), knot_y=_r(x[knots, 1]), t=_r(jt.t[k], 4),
                d=_r(1000 * d[k], 4), max_mm=float(1000 * d[k_max]), max_t=float(jt.t[k_max]), knots=len(knots))


def joint_space_figure(traj: Trajectory, extras=(0, 1, 3, 7, 15), kind: str = "cubic", points: int = 600,
                       title: str | None = None, height: int = 560) -> go.Figure:
    """Kernel-free slider figure: the tool path of the joint-space trajectory through the waypoints of ``traj``
    (:func:`~scara.trajectory.joint_counterpart`, cubic or quintic) against the operational path (top, seen from
    above), and the distance between the two against time (bottom), as the number of extra knots per segment
    takes each of ``extras`` (the slider; 2 to 10 values from 0 to 1000). The title gives the largest distance.

    Limits: ``points`` from 2 to 10 000 samples per curve (``MAX_POINTS``), so at most 100 000 samples per curve
    in all the steps together (``MAX_SLIDER_SAMPLES``); a value outside, or not a whole number, raises
    :class:`ScaraError` before any work."""
    points = check_count(points, "points", 2, MAX_POINTS, "samples per curve", FIGURE_BUDGET)
    traj = _check(traj)
    if not isinstance(kind, str) or kind not in KINDS:
        raise ScaraError(f"kind = {kind!r} must be one of {sorted(KINDS)}")
    if isinstance(extras, (str, bytes)) or np.ndim(extras) != 1:
        raise ScaraError(f"extras must be a sequence of knot counts (whole numbers 0 to 1000), got {extras!r}")
    extras = [check_count(e, "extras entry", 0, 1000, "knots per segment") for e in extras]
    if not 2 <= len(extras) <= 10:
        raise ScaraError(f"give between 2 and 10 values in extras, got {len(extras)}")
    data = [joint_space_series(traj, e, kind, points) for e in extras]
    heading = title or kind.capitalize()

    def head(s):
        return f"{heading}, {s['knots']} knots:<br>the tool strays up to {s['max_mm']:.1f} mm"

    # what each step draws, as JSON lists: short decimals keep the page light (10 um, 1 ms, 1 um); the figure
    # opens on the first step, with the very same numbers
    drawn = [dict(x=[as_list(s["x"], 5), as_list(s["knot_x"], 5), as_list(s["t"], 3)],
                  y=[as_list(s["y"], 5), as_list(s["knot_y"], 5), as_list(s["d"], 3)]) for s in data]
    fig = make_subplots(rows=2, cols=1, row_heights=[0.45, 0.55], vertical_spacing=0.16)
    k = decimate(traj, points)
    fig.add_trace(go.Scatter(x=_r(traj.x[k, 0]), y=_r(traj.x[k, 1]), mode="lines", name="operational path",
                             line=dict(color=PALETTE["reference"], width=2)), row=1, col=1)
    d0 = drawn[0]
    fig.add_trace(go.Scatter(x=d0["x"][0], y=d0["y"][0], mode="lines", name="joint-space tool path",
                             line=dict(color=_JOINT_COLOUR, width=2, dash="dash")), row=1, col=1)
    fig.add_trace(go.Scatter(x=d0["x"][1], y=d0["y"][1], mode="markers", name="knots",
                             marker=dict(color=_JOINT_COLOUR, size=6, symbol="circle-open", line=dict(width=1.5))),
                  row=1, col=1)
    fig.add_trace(go.Scatter(x=d0["x"][2], y=d0["y"][2], mode="lines", name="joint-space tool path", showlegend=False,
                             line=dict(color=_JOINT_COLOUR, width=1.6, dash="dash")), row=2, col=1)
    steps = [dict(label=f"{e}", method="update", args=[dr, {"title.text": head(s)}, [1, 2, 3]])
             for e, s, dr in zip(extras, data, drawn)]
    s0 = data[0]
    finish_layout(fig, head(s0), height, sliders=[slider(steps, "extra knots per segment: ", pad_top=50)])
    fig.update_xaxes(title_text="x (m)", constrain="domain", row=1, col=1)
    fig.update_yaxes(title_text="y (m)", scaleanchor="x", scaleratio=1, row=1, col=1)
    fig.update_xaxes(title_text="t (s)", row=2, col=1)
    fig.update_yaxes(title_text="distance (mm)", rangemode="tozero", row=2, col=1)
    fig.update_layout(margin=dict(b=110))
    return fig


#: the colour of the waypoint being edited in the waypoint editor
_EDITING_COLOUR = "#D55E00"
#: the roles of :func:`editor_top_figure`'s traces, in order (the last one is named after the waypoint edited)
EDITOR_TOP_ROLES = ("arm", "path", "stop point", "via point", "editing")
#: the roles of :func:`profiles_figure`'s traces, in order: each component of the position, velocity and
#: acceleration, then phi and the legend entry of the via bands
PROFILE_ROLES = tuple(f"{kind} {c}" for kind in ("p", "ṗ", "p̈") for c in _COMP) + ("φ", "via overlap")
#: the editor's title and the name of its ringed waypoint, made from the program's outputs
EDITOR_TITLE = Text("The edited path seen from above (editing p{edit_point:.0f})")
EDITOR_MARKER_NAME = Text("editing p{edit_point:.0f}")
#: the title of the editor's time profiles
EDITOR_PROFILES_TITLE = "Its position, velocity and acceleration (orange: via overlaps)"


#: the drawing scales (px per m) of the waypoint editor's top view: its height sets its scale, about 559 px per m
#: on a phone-width page and a laptop screen alike (measured in Chromium on the reference plan)
_EDITOR_SCALES = (520.0, 560.0, 600.0)


def editor_labels(traj: Trajectory) -> dict:
    """The waypoint editor's labels, fixed when it opens: the name of each waypoint (``labels``, shown on hover),
    the text drawn beside it (``text``) and where it sits around its marker (``positions``), placed at the
    editor's own scale (:data:`_EDITOR_SCALES`) against the plan it opens on (:func:`_place_waypoint_labels`) and
    kept there while the points move.

    A waypoint on an earlier one (p11 on p0 in the reference plan) is drawn without text: the one free place
    beside p0 (the arc, the arm and p1 are all around it) holds one label, and two labels there would each be as
    near to the other's point. Its name stays in its hover text, in the point dropdown and, while it is edited,
    in the ring's legend entry; moved apart, it is drawn unlabelled."""
    traj = _check(traj)
    arm = top_view_arm(traj.q0, traj.params)
    views = _top_views(traj, traj.x[decimate(traj, 300), :2], np.c_[arm.x, arm.y], scales=_EDITOR_SCALES)
    labels = list(traj.labels)
    text = [name if not any(np.linalg.norm(traj.waypoints[j] - traj.waypoints[i]) < 1e-9 for j in range(i))
            else "" for i, name in enumerate(labels)]
    positions = _place_waypoint_labels(views, text)
    # drawn as a space: plotly drops the text of another point of a trace with gaps (NaN) when one text is empty
    return dict(labels=labels, text=[t or " " for t in text], positions=positions)


def _editor_points(values, labels, text, positions, via):
    name, symbol, colour = (("via point", "diamond", _VIA_COLOUR) if via else
                            ("stop point", "circle", PALETTE["reference"]))
    key = "via" if via else "stop"
    return go.Scatter(x=values[f"{key}_x"], y=values[f"{key}_y"], mode="markers+text", name=name, text=list(text),
                      textposition=list(positions), textfont=dict(size=_LABEL_FONT), hovertext=list(labels),
                      hoverinfo="text", showlegend=True, marker=dict(size=10, symbol=symbol, color=colour,
                                                    line=dict(width=1, color="white")))


def editor_top_figure(values, labels: dict, height: int = 460) -> go.Figure:
    """The waypoint editor's top view drawn from its program's outputs ``values``
    (:func:`scara.programs.trajectory.editor_program`): the arm at ``t = 0``, the path, the stop and via points
    (each trace holds every waypoint, NaN where a point is of the other kind) labelled as :func:`editor_labels`
    placed them, and the edited waypoint ringed. The look of :func:`top_view_figure`."""
    fig = go.Figure()
    arm = top_view_arm(np.zeros(4), None, name="arm at t = 0", opacity=0.5)
    fig.add_trace(arm.update(x=values["arm_x"], y=values["arm_y"]))
    fig.add_trace(go.Scatter(x=values["path_x"], y=values["path_y"], mode="lines", name="path",
                             line=dict(color=PALETTE["reference"], width=2)))
    for via in (False, True):
        fig.add_trace(_editor_points(values, labels["labels"], labels.get("text", labels["labels"]),
                                     labels["positions"], via))
    fig.add_trace(go.Scatter(x=[values["edit_x"]], y=[values["edit_y"]], mode="markers",
                             name=EDITOR_MARKER_NAME.format(values), hoverinfo="skip",
                             marker=dict(size=18, symbol="circle-open", color=_EDITING_COLOUR, line=dict(width=3))))
    finish_layout(fig, EDITOR_TITLE.format(values), height)
    fig.update_xaxes(title_text="x (m)")
    fig.update_yaxes(title_text="y (m)", scaleanchor="x", scaleratio=1)
    return fig


def _editor_bands(n):
    """The fields of the profiles' shaded bands, in the order of the shapes: ``(x0, x1, on)`` per band (``on``
    None for the grey bands of every other segment, always shown)."""
    grey = [(f"band_{g}_x0", f"band_{g}_x1", None) for g in range(n // 2)]
    return grey + [(f"overlap_{i}_x0", f"overlap_{i}_x1", f"overlap_{i}_on") for i in range(1, n - 1)]


def editor_profiles_figure(values, n: int, height: int = 620) -> go.Figure:
    """The waypoint editor's time profiles drawn from its program's outputs ``values`` for a plan of ``n``
    waypoints: :func:`profiles_figure`'s traces and bands, the band over a via point's overlap hidden while the
    point is a stop."""
    fig = make_subplots(rows=4, cols=1, shared_xaxes=True, vertical_spacing=0.04, row_heights=[0.3, 0.3, 0.3, 0.1])
    series = ("prof_x", "prof_y", "prof_z", "prof_vx", "prof_vy", "prof_vz", "prof_ax", "prof_ay", "prof_az")
    for row in range(1, 4):
        for c in range(3):
            fig.add_trace(go.Scatter(x=values["prof_t"], y=values[series[3 * (row - 1) + c]], mode="lines",
                                     name=f"p_{_COMP[c]}", legendgroup=_COMP[c], showlegend=row == 1,
                                     line=dict(color=AXIS_COLOURS[c], width=1.6, dash=DASHES[c])), row=row, col=1)
    fig.add_trace(go.Scatter(x=values["prof_t"], y=values["prof_phi"], mode="lines", name="φ",
                             line=dict(color=AXIS_COLOURS[3], width=1.6, dash=DASHES[3])), row=4, col=1)
    stacked_axes(fig, ("p (m)", "ṗ (m/s)", "p̈ (m/s²)", "φ (°)"))
    fig.update_yaxes(nticks=3, row=4, col=1)
    _band_legend(fig)
    shapes = []
    for x0, x1, on in _editor_bands(n):
        shape = dict(type="rect", xref="x", yref="paper", x0=values[x0], x1=values[x1], y0=0, y1=1, layer="below",
                     fillcolor="#000000" if on is None else _VIA_COLOUR, opacity=0.05 if on is None else 0.25,
                     line=dict(width=0))
        if on is not None:
            shape["visible"] = bool(values[on] != 0)
        shapes.append(shape)
    return finish_layout(fig, EDITOR_PROFILES_TITLE, height, shapes=shapes)


def editor_bindings(n: int, profiles: bool = True) -> dict:
    """How the editor's figures are drawn from its program's outputs, for a plan of ``n`` waypoints: the
    ``traces``, ``paths`` and ``titles`` of its :class:`~scara.plots.panels.PageProgram`."""
    series = ("prof_x", "prof_y", "prof_z", "prof_vx", "prof_vy", "prof_vz", "prof_ax", "prof_ay", "prof_az",
              "prof_phi")
    traces = {"top view": {"arm": {"x": "arm_x", "y": "arm_y"}, "path": {"x": "path_x", "y": "path_y"},
                           "stop point": {"x": "stop_x", "y": "stop_y"}, "via point": {"x": "via_x", "y": "via_y"},
                           "editing": {"x": ("edit_x",), "y": ("edit_y",), "name": EDITOR_MARKER_NAME}}}
    titles = {"top view": EDITOR_TITLE}
    paths = {}
    if profiles:
        traces["profiles"] = {role: {"x": "prof_t", "y": y} for role, y in zip(PROFILE_ROLES, series)}
        paths["profiles"] = {}
        for k, (x0, x1, on) in enumerate(_editor_bands(n)):
            paths["profiles"][f"shapes.{k}.x0"] = x0
            paths["profiles"][f"shapes.{k}.x1"] = x1
            if on is not None:
                paths["profiles"][f"shapes.{k}.visible"] = Flag(on)
    return dict(traces=traces, paths=paths, titles=titles)


def editor_pairs(labels: dict, n: int, profiles: bool = True) -> tuple:
    """The waypoint editor's figures: ``(builders, roles)`` for :func:`~scara.plots.panels.program_panel`, the top
    view (:func:`editor_top_figure`) and, with ``profiles``, the time profiles (:func:`editor_profiles_figure`)."""
    builders = {"top view": lambda values: editor_top_figure(values, labels)}
    roles = {"top view": EDITOR_TOP_ROLES}
    if profiles:
        builders["profiles"] = lambda values: editor_profiles_figure(values, n)
        roles["profiles"] = PROFILE_ROLES
    return builders, roles
