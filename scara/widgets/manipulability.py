"""Live panel of chapter 2 (manipulability): move theta1 and theta2 and watch the velocity and force
ellipses change on the arm. Jupyter only."""
from __future__ import annotations

import math

import ipywidgets as ipw
import plotly.graph_objects as go

from ..errors import as_vector, check_positive
from ..kinematics import _params
from ..manipulability import force_ellipsoid, manipulability, velocity_ellipsoid
from ..plots.kinematics import finish_layout
from ..plots.manipulability import ellipse_traces
from ._common import LivePanel
from .kinematics import _table

__all__ = ["manipulability_panel"]

_STYLE = {"description_width": "initial"}


def manipulability_panel(theta1: float = 0.0, theta2: float = math.pi / 3, scale: float = 0.15, p=None) -> LivePanel:
    """Sliders for theta1 and theta2 (degrees) and the ellipse scale (metres drawn per m/s and per N); the
    top view of the arm with its horizontal velocity and force ellipses is redrawn on every move, with ``w``
    and the semi-axes listed. Angles given here in rad. A scale of 0 (or any invalid value) is reported in the
    panel, not raised."""
    p = _params(p)
    check_positive(scale, "scale")
    deg = dict(min=-180.0, max=180.0, step=1.0, continuous_update=False, style=_STYLE)
    controls = {
        "theta1": ipw.FloatSlider(value=math.degrees(theta1), description="θ1 (°)", **deg),
        "theta2": ipw.FloatSlider(value=math.degrees(theta2), description="θ2 (°)", **deg),
        "scale": ipw.FloatSlider(value=scale, min=0.0, max=0.5, step=0.01, description="ellipse scale",
                                 continuous_update=False, style=_STYLE),
    }

    def render(theta1, theta2, scale):
        q = as_vector([math.radians(theta1), math.radians(theta2), 0.5 * p.d0, 0.0], "q")
        sc = check_positive(scale, "ellipse scale")
        fig = go.Figure(ellipse_traces(q, p, sc, sc, axes=True))
        finish_layout(fig, f"θ1 = {theta1:.0f}°, θ2 = {theta2:.0f}°: w = {manipulability(q, p):.3f} m²", 520)
        reach = p.r_max + 0.2
        fig.update_xaxes(title_text="x (m)", range=[-reach, reach], constrain="domain")
        fig.update_yaxes(title_text="y (m)", range=[-reach, reach], scaleanchor="x", scaleratio=1)
        v = velocity_ellipsoid(q, p, rows=(0, 1))
        f = force_ellipsoid(q, p, rows=(0, 1))
        rows = [("velocity semi-axes σ (m/s, unit joint-speed norm)", ", ".join(f"{s:.4f}" for s in v.lengths)),
                ("force semi-axes 1/σ (N, unit torque norm)", ", ".join(f"{s:.4g}" for s in f.lengths)),
                ("major velocity axis direction (°)",
                 f"{math.degrees(math.atan2(v.axes[1, 0], v.axes[0, 0])):.1f}"),
                ("vertical semi-axis (both)", "1 (z is decoupled)")]
        return [fig, _table(rows)]

    return LivePanel(controls, render, title="Velocity and force ellipses: move the arm", columns=3)
