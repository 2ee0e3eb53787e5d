"""Live panels of chapter 1 (kinematics): move the joints and watch the arm and ``x_e``; type a target and
see both inverse-kinematics solutions (or the reason it cannot be reached). Jupyter only."""
from __future__ import annotations

import html
import math

import ipywidgets as ipw
import numpy as np

from ..errors import as_vector
from ..kinematics import _params, ikine, jacobian, pose
from ..manipulability import manipulability
from ..plots.kinematics import arm_figure, inverse_kinematics_figure
from ._common import LivePanel

__all__ = ["kinematics_panel", "inverse_kinematics_panel"]

_STYLE = {"description_width": "initial"}


def _table(rows) -> str:
    body = "".join(f"<tr><td style='padding:2px 10px'>{html.escape(a)}</td><td style='padding:2px 10px'>"
                   f"{html.escape(b)}</td></tr>" for a, b in rows)
    return f"<table style='font-family:monospace'>{body}</table>"


def kinematics_panel(q=None, p=None) -> LivePanel:
    """A slider per joint (theta1, theta2, theta4 in degrees, d3 in metres); on every move the 3-D arm with
    its frames is redrawn and ``x_e``, ``det J_A`` and ``w`` are listed (SPEC section 2).

    ``q`` is the starting configuration (4,) in rad, rad, m, rad (default ``[0, 60°, d0/2, 0]``).
    Returns a :class:`LivePanel` (display it as a cell's last expression). A non-finite value is reported in
    the panel, not raised.
    """
    p = _params(p)
    q = np.array([0.0, math.radians(60.0), 0.5 * p.d0, 0.0]) if q is None else as_vector(q, "q")
    deg = dict(min=-180.0, max=180.0, step=1.0, continuous_update=False, style=_STYLE)
    controls = {
        "theta1": ipw.FloatSlider(value=math.degrees(q[0]), description="θ1 (°)", **deg),
        "theta2": ipw.FloatSlider(value=math.degrees(q[1]), description="θ2 (°)", **deg),
        "d3": ipw.FloatSlider(value=q[2], min=0.0, max=p.d0, step=0.01, description="d3 (m)",
                              continuous_update=False, style=_STYLE),
        "theta4": ipw.FloatSlider(value=math.degrees(q[3]), description="θ4 (°)", **deg),
    }

    def render(theta1, theta2, d3, theta4):
        qq = as_vector([math.radians(theta1), math.radians(theta2), d3, math.radians(theta4)], "q")
        x = pose(qq, p)
        fig = arm_figure(qq, p, height=480)
        rows = [("p_x, p_y, p_z (m)", f"{x[0]:.4f}, {x[1]:.4f}, {x[2]:.4f}"),
                ("phi = θ1 + θ2 + θ4 (°)", f"{math.degrees(x[3]):.2f}"),
                ("det J_A (m²)", f"{np.linalg.det(jacobian(qq, p)):.4f}"),
                ("w = |det J_A| (m²)", f"{manipulability(qq, p):.4f}")]
        return [fig, _table(rows)]

    return LivePanel(controls, render, title="Direct kinematics: move a joint")


def inverse_kinematics_panel(x=None, p=None) -> LivePanel:
    """Type a target ``[p_x, p_y, p_z]`` (m) and ``phi`` (degrees); both closed-form solutions (elbow +1 and
    -1) are drawn from above and listed. A target outside the workspace shows the :class:`UnreachableError`
    message naming the limit it breaks. ``x`` is the starting target (4,) in m, m, m, rad (default SPEC
    section 4's ``p0`` with ``phi = 0``)."""
    p = _params(p)
    x = np.array([0.18, 0.20, 0.5, 0.0]) if x is None else as_vector(x, "x")
    box = dict(step=0.01, continuous_update=False, style=_STYLE, layout=ipw.Layout(width="180px"))
    controls = {
        "px": ipw.FloatText(value=x[0], description="p_x (m)", **box),
        "py": ipw.FloatText(value=x[1], description="p_y (m)", **box),
        "pz": ipw.FloatText(value=x[2], description="p_z (m)", **box),
        "phi": ipw.FloatText(value=math.degrees(x[3]), description="phi (°)", **dict(box, step=1.0)),
    }

    def render(px, py, pz, phi):
        target = as_vector([px, py, pz, math.radians(phi)], "target")
        fig = inverse_kinematics_figure(target, p, height=460)
        rows = []
        for elbow in (+1, -1):
            q = ikine(target, p, elbow=elbow)
            rows.append((f"elbow {elbow:+d}: θ1, θ2, θ4 (°); d3 (m)",
                         f"{math.degrees(q[0]):.2f}, {math.degrees(q[1]):.2f}, {math.degrees(q[3]):.2f}; {q[2]:.4f}"))
        return [fig, _table(rows)]

    return LivePanel(controls, render, title="Inverse kinematics: type a target", columns=4)
