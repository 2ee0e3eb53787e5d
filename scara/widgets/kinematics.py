"""Live panels of chapter 1 (kinematics): move the joints and watch the arm and ``x_e``; type a target and
see both inverse-kinematics solutions (or the reason it cannot be reached). Each move is one run of a page
program of :mod:`scara.programs.kinematics` (the same kernel runs in JupyterLab and, translated, in the book's
pages); the figures are drawn from its outputs."""
from __future__ import annotations

import math

import numpy as np

from ..errors import MAX_ANGLE, UnreachableError, as_vector
from ..kinematics import IK_OUTSIDE_ANNULUS, IK_OUTSIDE_STROKE
from ..plots.kinematics import (ARM_TITLE, ARM_TRACES, IK_TITLE, IK_TRACES, arm_pair, arm_program_data,
                                inverse_kinematics_pair)
from ..plots.panels import Control, Flag, PageProgram, Panel, Text, angle_control, program_panel, stroke_control
from ..programs.kinematics import (ARM_OUTPUTS, IK_ANGLE_TOO_LARGE, IK_OUTPUTS, inverse_kinematics_data,
                                   inverse_kinematics_program, kinematics_program)
from ..book import ahead
from ._common import LivePanel
from ..params import ScaraParams

__all__ = ["kinematics_panel", "inverse_kinematics_panel", "kinematics_declaration", "inverse_kinematics_declaration"]


def kinematics_declaration(q=None, p=None) -> Panel:
    """The direct-kinematics panel as data (:class:`~scara.plots.panels.Panel`); see :func:`kinematics_panel`.
    Its move is :func:`scara.programs.kinematics.kinematics_program`."""
    p = ScaraParams.resolve(p)
    q = np.array([0.0, math.radians(60.0), 0.5 * (p.d3_min + p.d3_max), 0.0]) if q is None else as_vector(q, "q")
    controls = (angle_control(q[0], "theta1", "θ1 (°)"), angle_control(q[1], "theta2", "θ2 (°)"),
                stroke_control(q[2], p), angle_control(q[3], "theta4", "θ4 (°)"))
    pair = arm_pair(p)
    program = PageProgram(
        kinematics_program, ("theta1", "theta2", "d3", "theta4"), arm_program_data(p), ARM_OUTPUTS, {},
        traces={pair.role: ARM_TRACES}, titles={pair.role: ARM_TITLE},
        rows=(("p_x, p_y, p_z (m)", Text("{px:.4f}, {py:.4f}, {pz:.4f}")),
              ("phi = θ1 + θ2 + θ4 (°)", Text("{phi:.2f}")),
              ("det J_A (m²)", Text("{det:.4f}")),
              ("w = |det J_A| (m²)", Text("{w:.4f}"))),
        notes=((Flag("singular"), Text("The arm is singular here (w = {w:.2g} m², θ2 = {theta2:.0f}°): it cannot "
                                       "move its tip along the line of its links.")),))
    return program_panel("direct kinematics", "Direct kinematics: move a joint", controls, program,
                         {pair.role: pair.build}, widget="kinematics_panel")


@ahead(kinematics_program)
def kinematics_panel(q=None, p=None, keep: bool = False) -> LivePanel:
    """A slider per joint (theta1, theta2, theta4 in degrees, d3 in metres); on every move the 3-D arm with
    its frames is redrawn in place and ``x_e`` (1.6), ``det J_A`` and ``w`` are listed.

    ``q`` is the starting configuration (4,) in rad, rad, m, rad (default ``[0, 60°, mid-stroke, 0]``); angles must lie
    in [-180°, 180°] and d3 in the quill's stroke ``p.d3_min`` to ``p.d3_max``, the sliders' ranges, or
    :class:`ScaraError` is raised (naming the value and the range).
    Every slider position is a valid configuration, so this panel refuses only a number typed beside a slider
    outside its range. ``keep=True`` starts from the last accepted settings of the previous direct-kinematics
    panel built in this Python process (re-running the cell keeps the joints set): see :class:`LivePanel`.
    Returns a :class:`LivePanel` (display it as a cell's last expression); its ``declaration`` is
    :func:`kinematics_declaration`.
    """
    return LivePanel(kinematics_declaration(q, p), keep=keep)


def _refusals(p) -> dict:
    """Why a target is refused, in the panel's units (m and degrees), by the inverse-kinematics program's status:
    :class:`~scara.plots.panels.Text` templates of its outputs and settings."""
    where = "the target (x, y, z) = ({px:.3f}, {py:.3f}, {pz:.3f}) m, φ = {phi:.1f}°"
    return {
        IK_OUTSIDE_ANNULUS: Text(f"{where} is out of reach: it lies r = {{r:.4f}} m from the joint-1 axis, and the arm "
                                 f"reaches from |a1 − a2| = {p.r_min:g} m to a1 + a2 = {p.r_max:g} m."),
        IK_OUTSIDE_STROKE: Text(f"{where} is out of reach: z = {{pz:.3f}} m needs the quill at d3 = d0 − z = "
                                f"{{d3:.3f}} m, outside its stroke d3_min to d3_max = {p.d3_min:g} to {p.d3_max:g} m."),
        IK_ANGLE_TOO_LARGE: Text(f"x[3] = {{phi_rad:.6g}} rad is beyond the largest angle the package accepts, "
                                 f"|theta| <= MAX_ANGLE = {MAX_ANGLE:g} rad (beyond it sin and cos lose all "
                                 "precision); reduce the angle modulo 2 pi"),
    }


def inverse_kinematics_declaration(x=None, p=None) -> Panel:
    """The inverse-kinematics panel as data (:class:`~scara.plots.panels.Panel`); see
    :func:`inverse_kinematics_panel`. Its move is :func:`scara.programs.kinematics.inverse_kinematics_program`;
    an unreachable start raises :class:`UnreachableError` with the message the panel shows."""
    p = ScaraParams.resolve(p)
    x = np.array([0.18, 0.20, 0.5, 0.0]) if x is None else as_vector(x, "x")
    controls = (Control("px", "number", "p_x (m)", float(x[0]), step=0.01, unit="m"),
                Control("py", "number", "p_y (m)", float(x[1]), step=0.01, unit="m"),
                Control("pz", "number", "p_z (m)", float(x[2]), step=0.01, unit="m"),
                Control("phi", "number", "phi (°)", math.degrees(x[3]), step=1.0, unit="°"))
    pair = inverse_kinematics_pair(p)
    row = "{theta1_%s:.2f}, {theta2_%s:.2f}, {theta4_%s:.2f}; {d3:.4f}"
    program = PageProgram(
        inverse_kinematics_program, ("px", "py", "pz", "phi"), inverse_kinematics_data(p), IK_OUTPUTS,
        _refusals(p), traces={pair.role: IK_TRACES}, titles={pair.role: IK_TITLE},
        rows=(("elbow +1: θ1, θ2, θ4 (°); d3 (m)", Text(row % (("up",) * 3))),
              ("elbow -1: θ1, θ2, θ4 (°); d3 (m)", Text(row % (("down",) * 3)))),
        notes=((Flag("coincide"), Text("The two elbows coincide: the target is on the rim of the workspace, where the "
                                       "arm is singular.")),))
    panel = program_panel("inverse kinematics", "Inverse kinematics: type a target", controls, program,
                          {pair.role: pair.build}, widget="inverse_kinematics_panel", columns=4)
    settings = panel.defaults()
    out = np.zeros(IK_OUTPUTS.size)
    status = int(program.kernel(program.pack(settings, {c.name: c for c in controls}), program.data, out))
    if status in (IK_OUTSIDE_ANNULUS, IK_OUTSIDE_STROKE):
        raise UnreachableError(program.refusals[status].format(program.values(out, settings)))
    return panel


@ahead(inverse_kinematics_program)
def inverse_kinematics_panel(x=None, p=None, keep: bool = False) -> LivePanel:
    """Type a target ``p_x, p_y, p_z`` (m) and ``phi`` (degrees); both closed-form solutions (elbow +1 and
    -1) are drawn from above and listed. A target outside the workspace shows why, in metres and degrees,
    and the figure is marked stale until a reachable target is typed. ``x`` is the starting target (4,) in
    m, m, m, rad (default the first point of the reference path of chapter 3, ``p0 = (0.18, 0.20, 0.5)`` m,
    with ``phi = 0``); an unreachable start raises :class:`UnreachableError`. ``keep=True`` starts from the last
    accepted target of the previous inverse-kinematics panel built in this Python process (see
    :class:`LivePanel`). Its ``declaration`` is :func:`inverse_kinematics_declaration`."""
    return LivePanel(inverse_kinematics_declaration(x, p), keep=keep)
