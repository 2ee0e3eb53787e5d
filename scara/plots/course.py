"""The whole course on one figure (intro page): the arm tracing the reference path, each element labelled
with the chapter that explains it."""
from __future__ import annotations

import numpy as np
import plotly.graph_objects as go

from .._manipulability import manipulability
from ..errors import check_count
from ._common import PALETTE, as_list, slider
from ._common import MAX_POINTS, MAX_STEPS, FIGURE_BUDGET
from .kinematics import arm_geometry
from .layout import finish_layout
from .trajectory import _waypoint_traces, decimate
from ..params import ScaraParams

__all__ = ["course_figure", "TRAIL_LEGEND", "COLOURBAR_TITLE"]

#: the legend's name for the grey trail, the part of the path the tool has already covered
TRAIL_LEGEND = "path covered"
#: the colour bar's title: it names the path and what colours it
COLOURBAR_TITLE = "path coloured by w (m², Ch. 2)"
#: room (px) under the plot area for the horizontal colour bar (title, bar, tick labels); a slider goes under it
COLOURBAR_ROOM = 52
#: height of the scene box, in plotly's aspect-ratio units (its longer horizontal side is 1)
Z_ASPECT = 0.8
#: where the camera stands, in the same units: in front, a little to the right and above. plotly scales a 3-D
#: scene to the height of the plot area, so the scene must not be wider than it is tall from here: at this
#: distance the box and its axis labels fit a 360-px phone page (a plot area about 300 px wide and tall)
CAMERA_EYE = (0.42, -2.0, 1.32)
#: height of the point the camera looks at, below the box centre: it raises the drawing into the empty top
CAMERA_CENTRE_Z = -0.3
#: left and right margins (px): a 3-D scene draws its own axes, and wider margins only narrow it on a phone
SIDE_MARGIN = 8
#: height (px) of a slider without its current value: rail, tick labels and padding
_SLIDER_PX = 66


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
    a point for its name. The legend names the stop and via points, the arm and the trail
    (:data:`TRAIL_LEGEND`); the path itself is named by its colour bar (:data:`COLOURBAR_TITLE`), laid
    horizontally under the scene, above the slider.

    Limits: ``steps`` from 1 to 121 slider steps (``MAX_STEPS``); ``points`` from 2 to 10 000 samples per curve
    (``MAX_POINTS``); a value outside, or not a whole number, raises :class:`ScaraError` before any work.
    """
    steps = check_count(steps, "steps", 1, MAX_STEPS, "slider steps", FIGURE_BUDGET)
    points = check_count(points, "points", 2, MAX_POINTS, "samples per curve", FIGURE_BUDGET)
    p = ScaraParams.resolve(p)
    k = decimate(traj, points)
    q = traj.joints()
    w = manipulability(q[k], p)
    times = np.linspace(0.0, traj.t[-1], steps)
    idx = np.minimum(np.round(times / traj.dt).astype(int), traj.t.size - 1)
    arms = [arm_geometry(q[i], p)["arm"] for i in idx]

    fig = go.Figure()
    # the path is named by its colour bar (under the scene), not in the legend: a line coloured by w shows as a
    # plain black line in a legend, and a fifth entry would take the legend to five rows on a phone page
    fig.add_trace(go.Scatter3d(
        x=as_list(traj.x[k, 0]), y=as_list(traj.x[k, 1]), z=as_list(traj.x[k, 2]), mode="lines",
        name="path (Ch. 3)", showlegend=False,
        line=dict(width=6, color=as_list(w, 4), colorscale="Viridis", cmin=0.0, cmax=p.a1 * p.a2,
                  colorbar=dict(title=dict(text=COLOURBAR_TITLE, side="top", font=dict(size=12)), orientation="h",
                                x=1.0, xanchor="right", y=0.0, yanchor="top", ypad=0, len=0.55, thickness=8,
                                tickvals=[0.0, 0.1, 0.2], tickfont=dict(size=11), outlinewidth=0)),
        hovertemplate="(%{x:.3f}, %{y:.3f}, %{z:.3f}) m<extra>reference path</extra>"))
    for tr in _waypoint_traces(traj, dims=3, text=False):
        tr.name = tr.name.split()[0] + " (Ch. 3)"
        fig.add_trace(tr)
    # the trail: the samples of the decimated path covered by time t (a prefix), thinned for the slider steps.
    # Its trace keeps the name "covered" (how course_animation finds it); the legend names it through a
    # legend-only entry of the same legend group, which also shows and hides it
    kt = decimate(traj, 300)
    trail_style = dict(color=PALETTE["reference"], width=10)
    trail_index = len(fig.data)
    fig.add_trace(go.Scatter3d(x=[traj.x[0, 0]], y=[traj.x[0, 1]], z=[traj.x[0, 2]], mode="lines",
                               name="covered", line=trail_style, opacity=0.35, hoverinfo="skip",
                               showlegend=False, legendgroup="trail"))
    arm_index = len(fig.data)
    fig.add_trace(go.Scatter3d(x=as_list(arms[0][:, 0]), y=as_list(arms[0][:, 1]), z=as_list(arms[0][:, 2]),
                               mode="lines+markers",
                               name="arm (Ch. 1, 4)",
                               line=dict(color=PALETTE["arm"], width=9), marker=dict(size=4, color=PALETTE["arm"]),
                               hovertemplate="(%{x:.3f}, %{y:.3f}, %{z:.3f}) m<extra>arm</extra>"))
    fig.add_trace(go.Scatter3d(x=[None], y=[None], z=[None], mode="lines", name=TRAIL_LEGEND, line=trail_style,
                               opacity=0.35, hoverinfo="skip", legendgroup="trail"))
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
    lo[2] = 0.0
    span = hi - lo
    # equal scales on x and y, the longer side 1 long; the height drawn shorter (Z_ASPECT)
    aspect = np.r_[span[:2] / span[:2].max(), Z_ASPECT]
    scene = dict(xaxis=dict(title="x (m)", range=as_list([lo[0], hi[0]], 3), nticks=5),
                 yaxis=dict(title="y (m)", range=as_list([lo[1], hi[1]], 3), nticks=5),
                 zaxis=dict(title="z (m)", range=as_list([lo[2], hi[2]], 3), nticks=4),
                 aspectmode="manual", aspectratio=dict(zip("xyz", (round(float(v), 3) for v in aspect))),
                 camera=dict(eye=dict(zip("xyz", CAMERA_EYE)), center=dict(x=0.0, y=0.0, z=CAMERA_CENTRE_Z)))
    # the slider under the colour bar; the title states the time, so the slider does not repeat it above its rail
    sliders = [dict(slider(step_list, "t (s) = ", pad_top=COLOURBAR_ROOM), currentvalue=dict(visible=False))]
    fig = finish_layout(fig, _title(0.0, traj, idx[0]), height, scene=scene, uirevision="course", sliders=sliders)
    fig.update_layout(margin=dict(l=SIDE_MARGIN, r=SIDE_MARGIN, b=COLOURBAR_ROOM + _SLIDER_PX))
    return fig


def _title(t, traj, i):
    x = traj.x[i]
    return f"The course on one figure, t = {t:.0f} s<br>tool at ({x[0]:.3f}, {x[1]:.3f}, {x[2]:.3f}) m"
