"""Live panels of chapter 1 (kinematics): move the joints and watch the arm and ``x_e``; type a target and
see both inverse-kinematics solutions (or the reason it cannot be reached). Jupyter only."""
from __future__ import annotations

import math

import numpy as np

from ..errors import UnreachableError, as_vector
from ..kinematics import ikine, jacobian, pose
from .._manipulability import manipulability
from ..plots.kinematics import arm_pair, inverse_kinematics_pair
from ..plots.panels import Control, Panel, angle_control, stroke_control
from ._common import LivePanel
from ..params import ScaraParams

__all__ = ["kinematics_panel", "inverse_kinematics_panel", "kinematics_declaration", "inverse_kinematics_declaration"]


def kinematics_declaration(q=None, p=None) -> Panel:
    """The direct-kinematics panel as data (:class:`~scara.plots.panels.Panel`); see :func:`kinematics_panel`."""
    p = ScaraParams.resolve(p)
    q = np.array([0.0, math.radians(60.0), 0.5 * (p.d3_min + p.d3_max), 0.0]) if q is None else as_vector(q, "q")
    controls = (angle_control(q[0], "theta1", "θ1 (°)"), angle_control(q[1], "theta2", "θ2 (°)"),
                stroke_control(q[2], p), angle_control(q[3], "theta4", "θ4 (°)"))

    def compute(v):
        qq = as_vector([math.radians(v["theta1"]), math.radians(v["theta2"]), v["d3"], math.radians(v["theta4"])], "q")
        return dict(q=qq, x=pose(qq, p), det=float(np.linalg.det(jacobian(qq, p))), w=manipulability(qq, p))

    def summary(s):
        x = s["x"]
        rows = [("p_x, p_y, p_z (m)", f"{x[0]:.4f}, {x[1]:.4f}, {x[2]:.4f}"),
                ("phi = θ1 + θ2 + θ4 (°)", f"{math.degrees(x[3]):.2f}"),
                ("det J_A (m²)", f"{s['det']:.4f}"),
                ("w = |det J_A| (m²)", f"{s['w']:.4f}")]
        notes = []
        if s["w"] < 1e-3:
            notes.append(f"The arm is singular here (w = {s['w']:.2g} m², θ2 = {math.degrees(s['q'][1]):.0f}°): "
                         "it cannot move its tip along the line of its links.")
        return rows, notes

    return Panel("direct kinematics", "Direct kinematics: move a joint", controls, compute, (arm_pair(p),), summary)


def kinematics_panel(q=None, p=None) -> LivePanel:
    """A slider per joint (theta1, theta2, theta4 in degrees, d3 in metres); on every move the 3-D arm with
    its frames is redrawn in place and ``x_e`` (1.6), ``det J_A`` and ``w`` are listed.

    ``q`` is the starting configuration (4,) in rad, rad, m, rad (default ``[0, 60°, mid-stroke, 0]``); angles must lie
    in [-180°, 180°] and d3 in the quill's stroke ``p.d3_min`` to ``p.d3_max``, the sliders' ranges, or
    :class:`ScaraError` is raised (naming the value and the range).
    Every slider position is a valid configuration, so this panel never refuses a setting.
    Returns a :class:`LivePanel` (display it as a cell's last expression); its ``declaration`` is
    :func:`kinematics_declaration`.
    """
    return LivePanel(kinematics_declaration(q, p))


def _unreachable_text(target, p) -> str:
    """Why a target is out of reach, in the panel's units (m and degrees)."""
    r = math.hypot(target[0], target[1])
    where = (f"the target (x, y, z) = ({target[0]:.3f}, {target[1]:.3f}, {target[2]:.3f}) m, "
             f"φ = {math.degrees(target[3]):.1f}°")
    if not (p.r_min - 1e-12 <= r <= p.r_max + 1e-12):
        return (f"{where} is out of reach: it lies r = {r:.4f} m from the joint-1 axis, and the arm reaches "
                f"from |a1 − a2| = {p.r_min:g} m to a1 + a2 = {p.r_max:g} m.")
    return (f"{where} is out of reach: z = {target[2]:.3f} m needs the quill at d3 = d0 − z = "
            f"{p.d0 - target[2]:.3f} m, outside its stroke d3_min to d3_max = {p.d3_min:g} to {p.d3_max:g} m.")


def inverse_kinematics_declaration(x=None, p=None) -> Panel:
    """The inverse-kinematics panel as data (:class:`~scara.plots.panels.Panel`); see
    :func:`inverse_kinematics_panel`."""
    p = ScaraParams.resolve(p)
    x = np.array([0.18, 0.20, 0.5, 0.0]) if x is None else as_vector(x, "x")
    controls = (Control("px", "number", "p_x (m)", float(x[0]), step=0.01, unit="m"),
                Control("py", "number", "p_y (m)", float(x[1]), step=0.01, unit="m"),
                Control("pz", "number", "p_z (m)", float(x[2]), step=0.01, unit="m"),
                Control("phi", "number", "phi (°)", math.degrees(x[3]), step=1.0, unit="°"))

    def compute(v):
        target = as_vector([v["px"], v["py"], v["pz"], math.radians(v["phi"])], "target")
        try:
            return dict(target=target, q={elbow: ikine(target, p, elbow=elbow) for elbow in (+1, -1)})
        except UnreachableError as exc:
            raise UnreachableError(_unreachable_text(target, p)) from exc

    def summary(s):
        rows = [(f"elbow {elbow:+d}: θ1, θ2, θ4 (°); d3 (m)",
                 f"{math.degrees(q[0]):.2f}, {math.degrees(q[1]):.2f}, {math.degrees(q[3]):.2f}; {q[2]:.4f}")
                for elbow, q in s["q"].items()]
        notes = []
        if abs(math.sin(s["q"][1][1])) < 1e-3:
            notes.append("The two elbows coincide: the target is on the rim of the workspace, where the arm is "
                         "singular.")
        return rows, notes

    return Panel("inverse kinematics", "Inverse kinematics: type a target", controls, compute,
                 (inverse_kinematics_pair(p),), summary, columns=4)


def inverse_kinematics_panel(x=None, p=None) -> LivePanel:
    """Type a target ``p_x, p_y, p_z`` (m) and ``phi`` (degrees); both closed-form solutions (elbow +1 and
    -1) are drawn from above and listed. A target outside the workspace shows why, in metres and degrees,
    and the figure is marked stale until a reachable target is typed. ``x`` is the starting target (4,) in
    m, m, m, rad (default the first point of the reference path of chapter 3, ``p0 = (0.18, 0.20, 0.5)`` m,
    with ``phi = 0``); an unreachable start raises :class:`UnreachableError`. Its ``declaration`` is
    :func:`inverse_kinematics_declaration`."""
    return LivePanel(inverse_kinematics_declaration(x, p))
