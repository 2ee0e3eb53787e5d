"""Figures of chapter 3 (trajectory planning): the path in 3-D and from above, the time profiles with the
segments shaded, a via point's corner with and without anticipation (also as a kernel-free slider figure),
and the joint motion with the manipulability met along the path.

Every builder takes a :class:`~scara.trajectory.Trajectory` (or the inputs of
:func:`~scara.trajectory.plan_path`) and returns a ``plotly.graph_objects.Figure``. Long series are decimated
to about ``points`` samples for drawing, always keeping the stop instants, so pages stay light.
"""
from __future__ import annotations

import numpy as np
import plotly.graph_objects as go
from plotly.subplots import make_subplots

from ..errors import ScaraError, as_array
from ..trajectory import Trajectory, Trapezoidal, plan_path
from ._common import AXIS_COLOURS, DASHES, JOINT_COLOURS, PALETTE, slider
from ._common import MAX_POINTS, MAX_SLIDER_SAMPLES, check_count
from .kinematics import top_view_arm
from .layout import finish_layout, stacked_axes

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
    points = check_count(points, "points", MAX_POINTS, minimum=2, what="samples per curve")
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
    points = check_count(points, "points", MAX_POINTS, minimum=2, what="samples per curve")
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
    stacked_axes(fig, ("s (m)", "ṡ (m/s)", "s̈ (m/s²)"), "time since the segment started, τ (s)")
    shapes = [dict(type="rect", xref="x", yref="paper", x0=a, x1=b, y0=0, y1=1, layer="below", fillcolor=_VIA_COLOUR,
                   opacity=0.2, line=dict(width=0)) for a, b in ((0.0, tc), (T - tc, T))]
    fig.add_trace(go.Scatter(x=[None], y=[None], mode="lines", name="blends", showlegend=True, hoverinfo="skip",
                             line=dict(color=_VIA_COLOUR, width=10), opacity=0.35))
    return finish_layout(fig, title or f"L = {law.length:.3f} m, t_f = {T:g} s, t_c = {tc:.3g} s", height,
                         shapes=shapes)


def _waypoint_traces(traj, dims=3, showlegend=True, text=True):
    out = []
    for via, name, symbol, colour in ((False, "stop point", "circle", PALETTE["reference"]),
                                     (True, "via point", "diamond", _VIA_COLOUR)):
        idx = [i for i in range(len(traj.labels)) if bool(traj.via[i]) == via]
        # p11 = p0 in the reference: label coincident points once, e.g. "p0 = p11"
        labels = []
        for i in idx:
            same = [traj.labels[j] for j in range(len(traj.labels))
                    if np.linalg.norm(traj.waypoints[j] - traj.waypoints[i]) < 1e-9]
            labels.append(" = ".join(same) if same[0] == traj.labels[i] else "")
        pts = traj.waypoints[idx]
        common = dict(mode="markers+text" if text else "markers", name=name, text=labels,
                      textposition="top center", showlegend=showlegend,
                      hovertext=[traj.labels[i] for i in idx], hoverinfo="text")
        if dims == 3:
            out.append(go.Scatter3d(x=_r(pts[:, 0]), y=_r(pts[:, 1]), z=_r(pts[:, 2]),
                                    marker=dict(size=5, symbol=symbol, color=colour), **common))
        else:
            out.append(go.Scatter(x=_r(pts[:, 0]), y=_r(pts[:, 1]),
                                  marker=dict(size=10, symbol=symbol, color=colour,
                                              line=dict(width=1, color="white")), **common))
    return out


def path_figure(traj: Trajectory, points: int = 2000, title: str | None = None, height: int = 520) -> go.Figure:
    """The planned path in 3-D (base frame, m), its half circle highlighted, stop and via points labelled.

    Limits: ``points`` from 2 to 10 000 samples per curve (``MAX_POINTS``); a value outside, or not a whole number,
    raises :class:`ScaraError` before any work."""
    points = check_count(points, "points", MAX_POINTS, minimum=2, what="samples per curve")
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
    for tr in _waypoint_traces(traj, 3):
        fig.add_trace(tr)
    return finish_layout(fig, title or "The reference path in the base frame", height,
                         scene=dict(xaxis_title="x (m)", yaxis_title="y (m)", zaxis_title="z (m)", aspectmode="manual",
                                    aspectratio=dict(x=1.7, y=0.8, z=0.8),
                                    camera=dict(eye=dict(x=0.7, y=-1.8, z=0.8))))


def top_view_series(traj: Trajectory, points: int = 2000) -> dict:
    """The data :func:`top_view_figure` draws: the path's ``x``, ``y`` (decimated to about ``points``) and the
    stop and via points (``x``, ``y``, labels), so that a live panel can redraw an edited path from these.

    Limits: ``points`` from 2 to 10 000 samples per curve (``MAX_POINTS``); a value outside, or not a whole number,
    raises :class:`ScaraError` before any work."""
    points = check_count(points, "points", MAX_POINTS, minimum=2, what="samples per curve")
    traj = _check(traj)
    k = decimate(traj, points)
    wp = [dict(x=t.x, y=t.y, text=t.text, hovertext=t.hovertext) for t in _waypoint_traces(traj, 2)]
    return dict(path=(_r(traj.x[k, 0]), _r(traj.x[k, 1])), stop=wp[0], via=wp[1])


def top_view_figure(traj: Trajectory, points: int = 2000, arm: bool = True, title: str | None = None,
                    height: int = 460) -> go.Figure:
    """The path seen from above (x-y plane of the base frame, m) with the arm in its start configuration.

    Limits: ``points`` from 2 to 10 000 samples per curve (``MAX_POINTS``); a value outside, or not a whole number,
    raises :class:`ScaraError` before any work."""
    points = check_count(points, "points", MAX_POINTS, minimum=2, what="samples per curve")
    traj = _check(traj)
    series = top_view_series(traj, points)
    fig = go.Figure()
    if arm:
        fig.add_trace(top_view_arm(traj.q0, traj.params, name="arm at t = 0", opacity=0.5))
    fig.add_trace(go.Scatter(x=series["path"][0], y=series["path"][1], mode="lines", name="path",
                             line=dict(color=PALETTE["reference"], width=2)))
    for tr in _waypoint_traces(traj, 2):
        fig.add_trace(tr)
    finish_layout(fig, title or "The path seen from above", height)
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
    points = check_count(points, "points", MAX_POINTS, minimum=2, what="samples per curve")
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
    points = check_count(points, "points", MAX_POINTS, minimum=2, what="samples per curve")
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
    fig.update_yaxes(title_text="speed |ṗ| (m/s)", rangemode="tozero", row=2, col=1)


def _corner_grid():
    return make_subplots(rows=2, cols=1, row_heights=[0.58, 0.42], vertical_spacing=0.16)


def corner_figure(with_via: Trajectory, without: Trajectory, index: int, margin: float = 3.0, zoom: float = 0.03,
                  points: int = 400, title: str | None = None, height: int = 540) -> go.Figure:
    """A via point's corner seen from above (top) and the speed around it (bottom), for the trajectory that
    anticipates the next segment (``with_via``, black and solid like the reference) and one that stops there
    (``without``, grey and dashed).

    Limits: ``points`` from 2 to 10 000 samples per curve (``MAX_POINTS``); a value outside, or not a whole number,
    raises :class:`ScaraError` before any work."""
    points = check_count(points, "points", MAX_POINTS, minimum=2, what="samples per curve")
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
    fig.add_trace(go.Scatter(x=[pv[0]], y=[pv[1]], mode="markers+text", text=[lab], textposition="top right",
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
    points = check_count(points, "points", MAX_POINTS, minimum=2, what="samples per curve")
    if values is None:
        values = np.arange(0.0, 3.01, 0.25)
    else:
        values = as_array(values, "values", (len(np.atleast_1d(values)),))
    if values.size < 2 or values.size > 25:
        raise ScaraError(f"give between 2 and 25 anticipation values, got {values.size}")
    check_count(values.size * points, f"{values.size} values × points {points}", MAX_SLIDER_SAMPLES,
                what="samples per curve in all the slider steps")
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
    a0 = len(values) // 2
    x, y, t, v = data[a0]
    name = "anticipation on the slider"
    fig.add_trace(go.Scatter(x=_r(x), y=_r(y), mode="lines", name=name, line=dict(_VIA_LINE, width=3)),
                  row=1, col=1)
    fig.add_trace(go.Scatter(x=_r(t, 4), y=_r(v, 6), mode="lines", name=name, showlegend=False,
                             line=dict(_VIA_LINE, width=3)), row=2, col=1)
    pv = stop.waypoints[index]
    fig.add_trace(go.Scatter(x=[pv[0]], y=[pv[1]], mode="markers+text", text=[lab], textposition="top right",
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
    points = check_count(points, "points", MAX_POINTS, minimum=2, what="samples per curve")
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
                             text=[f"{w[km]:.4f} m² at {traj.t[km]:.1f} s"], textposition="top right",
                             name="min w", marker=dict(size=10, color=PALETTE["force"], symbol="diamond")),
                  row=3, col=1)
    stacked_axes(fig, ("angle (°)", "d3 (m)", "w (m²)"))
    fig.update_yaxes(rangemode="tozero", row=3, col=1)
    _band_legend(fig)
    return finish_layout(fig, title or "Joint motion and manipulability", height, shapes=segment_shapes(traj))
