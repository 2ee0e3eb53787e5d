"""Live panel of chapter 2 (manipulability): move theta1 and theta2 and watch the velocity and force
ellipses change on the arm. Every move is one run of the page program
:func:`scara.programs.manipulability.ellipse_program`, drawn by the bindings of
:data:`scara.plots.manipulability.ELLIPSE_TRACES` (the same in JupyterLab and in the book's pages)."""
from __future__ import annotations

import math

from ..errors import ScaraError
from ..plots.manipulability import ELLIPSE_TITLE, ELLIPSE_TRACES, ellipse_panel_figure
from ..plots.panels import Control, Flag, PageProgram, Panel, Text, angle_control, program_panel, start_value
from ..programs.manipulability import (ELLIPSE_INPUTS, ELLIPSE_OUTPUTS, REFUSED_SCALE, ellipse_data,
                                       ellipse_program)
from ..book import ahead
from ._common import LivePanel
from ..params import ScaraParams

__all__ = ["manipulability_panel", "manipulability_declaration"]


def manipulability_declaration(theta1: float = 0.0, theta2: float = math.pi / 3, scale: float = 0.15,
                               p=None) -> Panel:
    """The ellipses panel as data (:class:`~scara.plots.panels.Panel`); see :func:`manipulability_panel`."""
    p = ScaraParams.resolve(p)
    sc0 = start_value(scale, 0.0, 0.5, "scale", "m per m/s")
    if sc0 <= 0:
        raise ScaraError(f"scale = {sc0:g} must be > 0 (metres drawn per m/s and per N)")
    controls = (angle_control(theta1, "theta1", "θ1 (°)"), angle_control(theta2, "theta2", "θ2 (°)"),
                Control("scale", "slider", "ellipse scale", sc0, 0.0, 0.5, 0.01, unit="m per m/s"))
    program = PageProgram(
        ellipse_program, ELLIPSE_INPUTS, ellipse_data(p), ELLIPSE_OUTPUTS,
        refusals={REFUSED_SCALE: Text("the ellipse scale is {scale:g}: it must be above 0 to draw the ellipses "
                                      "(metres drawn per m/s and per N)")},
        traces=ELLIPSE_TRACES, titles={"ellipses": ELLIPSE_TITLE},
        rows=(("velocity semi-axes σ (m/s, unit joint-speed norm)", Text("{sigma1:.4f}, {sigma2:.4f}")),
              ("force semi-axes 1/σ (N, unit torque norm; inf: unbounded along the links, singular arm)",
               Text("{force1:.4g}, {force2:.4g}")),
              ("major velocity axis direction (°)", Text("{major:.1f}")),
              ("vertical semi-axis (both)", Text("1 (z is decoupled)"))),
        notes=((Flag("singular"),
                Text("The arm is singular at θ2 = {theta2:.0f}°: it cannot move its tip along the line of its links, "
                     "and so it can resist any force along that line with no torque; the force ellipse is unbounded: "
                     "it degenerates into an infinitely long segment.")),))
    return program_panel("ellipses", "Velocity and force ellipses: move the arm", controls, program,
                         {"ellipses": lambda values: ellipse_panel_figure(values, p)}, widget="manipulability_panel",
                         columns=3)


@ahead(ellipse_program)
def manipulability_panel(theta1: float = 0.0, theta2: float = math.pi / 3, scale: float = 0.15, p=None,
                         keep: bool = False) -> LivePanel:
    """Sliders for theta1 and theta2 (degrees) and the ellipse scale (metres drawn per m/s and per N); the
    top view of the arm with its horizontal velocity and force ellipses is redrawn in place on every move, with
    ``w`` and the semi-axes listed. The starting angles are given here in rad (within [-180°, 180°]) and the
    scale within (0, 0.5]; values outside these ranges raise :class:`ScaraError`. A scale of 0 set on the
    slider is refused in the panel. At a singular configuration the force ellipse is unbounded: the table lists
    its long semi-axis as ``inf`` instead of a huge number, and a note says why. ``keep=True`` starts from the last
    accepted settings of the previous ellipses panel built in this Python process (see
    :class:`~scara.widgets._common.LivePanel`). Its ``declaration`` is :func:`manipulability_declaration`."""
    return LivePanel(manipulability_declaration(theta1, theta2, scale, p), keep=keep)
