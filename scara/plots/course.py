"""The whole course on one figure (intro page): the arm tracing the reference path, each element labelled
with the chapter that explains it."""
from __future__ import annotations

import numpy as np
import plotly.graph_objects as go

from ..kinematics import _params
from ..manipulability import manipulability
from ._common import PALETTE, base_layout, slider
from .kinematics import _scene, arm_geometry
from .trajectory import _waypoint_traces, decimate

__all__ = ["course_figure"]


def _r(a, digits=4):
    return np.round(np.asarray(a, dtype=float), digits).tolist()


def course_figure(traj, p=None, steps: int = 15, points: int = 1500, height: int = 620) -> go.Figure:
    """3-D view of the reference path of chapter 3, coloured by the manipulability of chapter 2 along it, with
    the arm of chapter 1 drawn at the joint positions the inverse kinematics gives (chapter 4 computes them
    in closed loop; chapters 5 and 6 find the torques). A slider moves the arm along the path in ``steps``
    instants; it works in the static page."""
    p = _params(p)
    k = decimate(traj, points)
    q = traj.joints()
    w = manipulability(q[k], p)
    fig = go.Figure()
    fig.add_trace(go.Scatter3d(
        x=_r(traj.x[k, 0]), y=_r(traj.x[k, 1]), z=_r(traj.x[k, 2]), mode="lines",
        name="Ch. 3: the reference path (colour: Ch. 2, manipulability w)",
        line=dict(width=7, color=_r(w, 4), colorscale="Viridis", cmin=0.0, cmax=p.a1 * p.a2,
                  colorbar=dict(title=dict(text="w (m²)"), len=0.6, x=1.0)),
        hovertemplate="(%{x:.3f}, %{y:.3f}, %{z:.3f}) m<extra>reference path</extra>"))
    for tr in _waypoint_traces(traj, dims=3):
        tr.name = "Ch. 3: " + tr.name
        fig.add_trace(tr)
    times = np.linspace(0.0, traj.t[-1], steps)
    idx = np.minimum(np.round(times / traj.dt).astype(int), traj.t.size - 1)
    arms = [arm_geometry(q[i], p)["arm"] for i in idx]
    arm0 = arms[0]
    arm_index = len(fig.data)
    fig.add_trace(go.Scatter3d(x=_r(arm0[:, 0]), y=_r(arm0[:, 1]), z=_r(arm0[:, 2]), mode="lines+markers",
                               name="Ch. 1: the arm (joints from the inverse kinematics, Ch. 1 and 4)",
                               line=dict(color=PALETTE["arm"], width=9), marker=dict(size=4, color=PALETTE["arm"]),
                               hovertemplate="(%{x:.3f}, %{y:.3f}, %{z:.3f}) m<extra>arm</extra>"))
    steps_ = [dict(label=f"{t:.0f}", method="update",
                   args=[{"x": [_r(a[:, 0])], "y": [_r(a[:, 1])], "z": [_r(a[:, 2])]},
                         {"title.text": _title(t, traj, i)}, [arm_index]])
              for t, a, i in zip(times, arms, idx)]
    fig.update_layout(**base_layout(_title(0.0, traj, idx[0]), height),
                      scene=_scene(p), sliders=[slider(steps_, "time t (s) = ", pad_top=10)])
    fig.update_layout(legend=dict(orientation="h", y=-0.02, yanchor="top"), margin=dict(l=0, r=0, t=70, b=40))
    return fig


def _title(t, traj, i):
    x = traj.x[i]
    return (f"The course on one figure: t = {t:.1f} s, tool at ({x[0]:.3f}, {x[1]:.3f}, {x[2]:.3f}) m"
            "<br><sup>Chapters 5 and 6 compute the torques that make the real arm, with a 5 kg payload, do this</sup>")
