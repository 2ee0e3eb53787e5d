"""Live panel of chapter 2 (manipulability): move theta1 and theta2 and watch the velocity and force
ellipses change on the arm. Jupyter only."""
from __future__ import annotations

import math

from ..errors import ScaraError, as_vector
from .._manipulability import force_ellipsoid, manipulability, velocity_ellipsoid
from ..plots.manipulability import ellipse_pair
from ..plots.panels import Control, Panel, angle_control, start_value
from ._common import LivePanel
from ..params import ScaraParams

__all__ = ["manipulability_panel", "manipulability_declaration"]

#: below this ratio of the smaller to the larger velocity semi-axis the arm is treated as singular
_SINGULAR_RATIO = 1e-6


def manipulability_declaration(theta1: float = 0.0, theta2: float = math.pi / 3, scale: float = 0.15,
                               p=None) -> Panel:
    """The ellipses panel as data (:class:`~scara.plots.panels.Panel`); see :func:`manipulability_panel`."""
    p = ScaraParams.resolve(p)
    sc0 = start_value(scale, 0.0, 0.5, "scale", "m per m/s")
    if sc0 <= 0:
        raise ScaraError(f"scale = {sc0:g} must be > 0 (metres drawn per m/s and per N)")
    controls = (angle_control(theta1, "theta1", "θ1 (°)"), angle_control(theta2, "theta2", "θ2 (°)"),
                Control("scale", "slider", "ellipse scale", sc0, 0.0, 0.5, 0.01, unit="m per m/s"))

    def compute(v):
        theta1, theta2, scale = v["theta1"], v["theta2"], v["scale"]
        if not scale > 0:
            raise ScaraError(f"the ellipse scale is {scale:g}: it must be above 0 to draw the ellipses "
                             "(metres drawn per m/s and per N)")
        q = as_vector([math.radians(theta1), math.radians(theta2), 0.5 * (p.d3_min + p.d3_max), 0.0], "q")
        v = velocity_ellipsoid(q, p, rows=(0, 1))
        singular = v.lengths[1] < _SINGULAR_RATIO * v.lengths[0]
        return dict(q=q, theta=(theta1, theta2), scale=scale, w=manipulability(q, p), v=v,
                    f=None if singular else force_ellipsoid(q, p, rows=(0, 1)))

    def summary(s):
        v, f = s["v"], s["f"]
        major = math.degrees(math.atan2(v.axes[1, 0], v.axes[0, 0]))
        notes = []
        if f is None:
            force = "unbounded along the links (singular arm)"
            notes.append(f"The arm is singular at θ2 = {s['theta'][1]:.0f}°: it cannot move its tip along the line "
                         "of its links, and so it can resist any force along that line with no torque; the "
                         "force ellipse degenerates into an infinitely long segment.")
        else:
            force = ", ".join(f"{x:.4g}" for x in f.lengths)
        rows = [("velocity semi-axes σ (m/s, unit joint-speed norm)", ", ".join(f"{x:.4f}" for x in v.lengths)),
                ("force semi-axes 1/σ (N, unit torque norm)", force),
                ("major velocity axis direction (°)", f"{major:.1f}"),
                ("vertical semi-axis (both)", "1 (z is decoupled)")]
        return rows, notes

    return Panel("ellipses", "Velocity and force ellipses: move the arm", controls, compute, (ellipse_pair(p),),
                 summary, columns=3)


def manipulability_panel(theta1: float = 0.0, theta2: float = math.pi / 3, scale: float = 0.15, p=None) -> LivePanel:
    """Sliders for theta1 and theta2 (degrees) and the ellipse scale (metres drawn per m/s and per N); the
    top view of the arm with its horizontal velocity and force ellipses is redrawn in place on every move, with
    ``w`` and the semi-axes listed. The starting angles are given here in rad (within [-180°, 180°]) and the
    scale within (0, 0.5]; values outside these ranges raise :class:`ScaraError`. A scale of 0 set on the
    slider is refused in the panel. At a singular configuration the force ellipse is unbounded: the table says
    so instead of printing a huge number. Its ``declaration`` is :func:`manipulability_declaration`."""
    return LivePanel(manipulability_declaration(theta1, theta2, scale, p))
