"""The whole course on one figure (intro page): the arm tracing the reference path, each element labelled
with the chapter that explains it."""
from __future__ import annotations

import numpy as np
import plotly.graph_objects as go

from ..kinematics import _params
from ..manipulability import manipulability
from ._common import PALETTE, as_list, slider
from ._common import MAX_POINTS, MAX_STEPS, check_count
from .kinematics import arm_geometry
from .layout import finish_layout
from .trajectory import _waypoint_traces, decimate

__all__ = ["course_figure"]


def _box(points: np.ndarray, margin: float = 0.05) -> tuple[np.ndarray, np.ndarray]:
    """Corners of the axis-aligned box around ``points`` (n, 3), ``margin`` m wider on every side."""
    return points.min(axis=0) - margin, points.max(axis=0) + margin


def course_figure(traj, p=None, steps: int = 36, points: int = 1500, height: int = 560) -> go.Figure:
    """3-D view of the reference path of chapter 3, coloured by the manipulability of chapter 2 along it, with
    the arm of chapter 1 drawn at the joint positions the inverse kinematics gives (chapter 4 computes them
    in closed loop; chapters 5 and 6 find the torques). A slider moves the arm along the path in ``steps``
    instants (it works in the static page), and a trail shows the part of the path the tool has covered.

    The scene is cropped to the box that holds the path and every drawn arm (equal scales on x and y, the
    height drawn shorter), so that the path fills the figure instead of the whole reach of the arm; hover on
    a point for its name.

    Limits: ``steps`` from 1 to 121 slider steps (``MAX_STEPS``); ``points`` from 2 to 10 000 samples per curve
    (``MAX_POINTS``); a value outside, or not a whole number, raises :class:`ScaraError` before any work.
    """
    steps = check_count(steps, "steps", MAX_STEPS, minimum=1, what="slider steps")
    points = check_count(points, "points", MAX_POINTS, minimum=2, what="samples per curve")
    p = _params(p)
    k = decimate(traj, points)
    q = traj.joints()
    w = manipulability(q[k], p)
    times = np.linspace(0.0, traj.t[-1], steps)
    idx = np.minimum(np.round(times / traj.dt).astype(int), traj.t.size - 1)
    arms = [arm_geometry(q[i], p)["arm"] for i in idx]

    fig = go.Figure()
    fig.add_trace(go.Scatter3d(
        x=as_list(traj.x[k, 0]), y=as_list(traj.x[k, 1]), z=as_list(traj.x[k, 2]), mode="lines",
        name="path (Ch. 3)",
        line=dict(width=6, color=as_list(w, 4), colorscale="Viridis", cmin=0.0, cmax=p.a1 * p.a2,
                  colorbar=dict(title=dict(text="w (m²)<br>Ch. 2"), len=0.55, thickness=14, x=1.0)),
        hovertemplate="(%{x:.3f}, %{y:.3f}, %{z:.3f}) m<extra>reference path</extra>"))
    for tr in _waypoint_traces(traj, dims=3, text=False):
        tr.name = tr.name.split()[0] + " (Ch. 3)"
        fig.add_trace(tr)
    # the trail: the samples of the decimated path covered by time t (a prefix), thinned for the slider steps
    kt = decimate(traj, 300)
    trail_index = len(fig.data)
    fig.add_trace(go.Scatter3d(x=[traj.x[0, 0]], y=[traj.x[0, 1]], z=[traj.x[0, 2]], mode="lines",
                               name="covered", line=dict(color=PALETTE["reference"], width=10),
                               opacity=0.35, hoverinfo="skip", showlegend=False))
    arm_index = len(fig.data)
    fig.add_trace(go.Scatter3d(x=as_list(arms[0][:, 0]), y=as_list(arms[0][:, 1]), z=as_list(arms[0][:, 2]),
                               mode="lines+markers",
                               name="arm (Ch. 1, 4)",
                               line=dict(color=PALETTE["arm"], width=9), marker=dict(size=4, color=PALETTE["arm"]),
                               hovertemplate="(%{x:.3f}, %{y:.3f}, %{z:.3f}) m<extra>arm</extra>"))
    step_list = []
    for t, a, i in zip(times, arms, idx):
        covered = kt[kt <= i]
        trail = traj.x[np.r_[covered, i]]
        step_list.append(dict(label=f"{t:.0f}", method="update",
                              args=[{"x": [as_list(trail[:, 0]), as_list(a[:, 0])],
                                     "y": [as_list(trail[:, 1]), as_list(a[:, 1])],
                                     "z": [as_list(trail[:, 2]), as_list(a[:, 2])]},
                                    {"title.text": _title(t, traj, i)}, [trail_index, arm_index]]))
    lo, hi = _box(np.vstack([traj.x[k, :3], *arms, [[0.0, 0.0, 0.0]]]))
    span = hi - lo
    scene = dict(xaxis=dict(title="x (m)", range=as_list([lo[0], hi[0]], 3)),
                 yaxis=dict(title="y (m)", range=as_list([lo[1], hi[1]], 3)),
                 zaxis=dict(title="z (m)", range=as_list([0.0, hi[2]], 3)),
                 aspectmode="manual",
                 aspectratio=dict(x=1.1, y=1.1 * span[1] / span[0], z=0.75),
                 camera=dict(eye=dict(x=1.1, y=-1.7, z=0.8), center=dict(x=0.0, y=0.0, z=-0.1)))
    return finish_layout(fig, _title(0.0, traj, idx[0]), height, scene=scene, uirevision="course",
                         sliders=[slider(step_list, "t (s) = ", pad_top=10)])


def _title(t, traj, i):
    x = traj.x[i]
    return f"The course on one figure, t = {t:.0f} s<br>tool at ({x[0]:.3f}, {x[1]:.3f}, {x[2]:.3f}) m"
