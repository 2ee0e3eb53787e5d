"""Figures of chapter 2 (manipulability): velocity and force ellipses drawn on the arm seen from above, at
chosen configurations and over the workspace, the measure ``w`` as a heat map with its singular circles, the
duality of the two ellipses, and a theta2 sweep with slider steps.

The ellipses are the horizontal (x-y) sections of :func:`scara.velocity_ellipsoid` and
:func:`scara.force_ellipsoid` with ``rows=(0, 1)``: for the SCARA the vertical direction is decoupled (the
z row of ``J_A`` is ``[0, 0, -1, 0]``), so its semi-axis is 1 for both ellipsoids and a top view tells the
whole story. Lengths are drawn multiplied by a scale (metres on the page per m/s, or per N), stated in the
legend. A length too long to draw (at or near a singularity the force ellipse is unbounded) is clipped to
``_CLIP`` metres, far outside the view, so it appears as a strip of parallel lines.
"""
from __future__ import annotations

import dataclasses
import math

import numpy as np
import plotly.graph_objects as go
from plotly.subplots import make_subplots

from ..errors import ScaraError, as_array, as_vector, check_positive
from ..kinematics import _params, ikine
from ..manipulability import force_ellipsoid, manipulability, singular_radii, velocity_ellipsoid, workspace_map
from ._common import PALETTE, slider
from .kinematics import _as_list, _circle, _layout, top_view_arm

__all__ = [
    "REFERENCE_CONFIGURATIONS",
    "ellipse_xy",
    "ellipse_traces",
    "workspace_points",
    "reference_ellipses_figure",
    "workspace_ellipses_figure",
    "manipulability_map_figure",
    "duality_figure",
    "ellipse_slider_figure",
]

#: the five configurations of the SPEC section 2 reference table, with their labels
REFERENCE_CONFIGURATIONS = {
    "q1": (0.0, -math.pi / 2, 0.5, 0.0),
    "q2": (0.0, math.pi / 4, 0.5, 0.0),
    "q3": (0.0, math.pi / 30, 0.5, 0.0),
    "q4": (0.0, 98 * math.pi / 100, 0.5, 0.0),
    "q5": (0.0, -99.99 * math.pi / 100, 0.5, 0.0),
}
_CLIP = 50.0  # m: drawn semi-axes are capped here (the view is about 2.5 m wide)


def ellipse_xy(ellipsoid, scale: float = 1.0, n: int = 181) -> np.ndarray:
    """Outline ``(n, 2)`` of a horizontal ellipse (``rows=(0, 1)``) with its semi-axes times ``scale``.

    Semi-axes longer than ``_CLIP`` m after scaling (an unbounded force ellipse at a singularity, ``inf``) are
    capped at ``_CLIP``: within any view of the arm the result is the strip the true, unbounded ellipse
    draws. Raises :class:`ScaraError` for a scale that is not positive.
    """
    scale = check_positive(scale, "scale")
    lengths = np.minimum(np.asarray(ellipsoid.lengths, dtype=float) * scale, _CLIP)
    clipped = dataclasses.replace(ellipsoid, lengths=lengths)
    return clipped.outline(n=n, scale=1.0, plane=(0, 1))


def ellipse_traces(q, p=None, velocity_scale: float = 0.15, force_scale: float | None = None, arm: bool = True,
                   showlegend: bool = True, axes: bool = False, n: int = 181) -> list:
    """2-D traces (top view) of the arm at ``q`` with its horizontal velocity and force ellipses centred at
    the end effector; with ``axes`` also their principal axes as segments.

    ``velocity_scale`` is in metres drawn per m/s (semi-axis ``sigma_i`` for a unit joint-velocity norm),
    ``force_scale`` in metres drawn per N (semi-axis ``1/sigma_i`` for a unit torque norm), by default the
    same number. Returns a list of ``go.Scatter``.
    """
    p = _params(p)
    q = as_vector(q, "q")
    force_scale = velocity_scale if force_scale is None else force_scale
    vel = velocity_ellipsoid(q, p, rows=(0, 1))
    frc = force_ellipsoid(q, p, rows=(0, 1))
    traces = []
    if arm:
        traces.append(top_view_arm(q, p, showlegend=showlegend))
    for ell, sc, key, label in ((vel, velocity_scale, "velocity", "velocity ellipse"),
                                (frc, force_scale, "force", "force ellipse")):
        xy = ellipse_xy(ell, sc, n)
        traces.append(go.Scatter(x=_as_list(xy[:, 0]), y=_as_list(xy[:, 1]), mode="lines",
                                 name=f"{label} (× {sc:g})", legendgroup=key, showlegend=showlegend,
                                 line=dict(color=PALETTE[key], width=2.5, dash="solid" if key == "velocity" else "dash"),
                                 hoverinfo="skip"))
        if axes:
            seg = []
            for i in range(2):
                half = min(sc * ell.lengths[i], _CLIP) * ell.axes[:, i]
                seg += [ell.centre[:2] - half, ell.centre[:2] + half, [np.nan, np.nan]]
            seg = np.array(seg)
            traces.append(go.Scatter(x=_as_list(seg[:, 0]), y=_as_list(seg[:, 1]), mode="lines",
                                     name=f"{key} principal axes", legendgroup=key, showlegend=False,
                                     line=dict(color=PALETTE[key], width=1.2, dash="dot"), hoverinfo="skip"))
    return traces


def workspace_points(radii=(0.3, 0.55, 0.8), n_angles: int = 8, height: float = 0.5) -> np.ndarray:
    """End-effector targets ``(len(radii) * n_angles, 4)`` spread over the workspace: rings of radius
    ``radii`` (m), ``n_angles`` per ring (rings staggered by half a step), at height ``height``, phi = 0."""
    radii = as_array(radii, "radii", (len(np.atleast_1d(radii)),))
    pts = []
    for k, r in enumerate(radii):
        for j in range(int(n_angles)):
            a = 2 * math.pi * (j + 0.5 * (k % 2)) / n_angles
            pts.append([r * math.cos(a), r * math.sin(a), height, 0.0])
    return np.array(pts)


def _top_axes(fig, p, rows_cols, margin=0.2, xr=None, yr=None):
    reach = p.r_max + margin
    xr = xr or [-reach, reach]
    yr = yr or [-reach, reach]
    for k, (r, c) in enumerate(rows_cols):
        fig.update_xaxes(title_text="x (m)", range=xr, zeroline=False, constrain="domain", row=r, col=c)
        anchor = "x" if k == 0 else f"x{k + 1}"
        fig.update_yaxes(title_text="y (m)", range=yr, zeroline=False, scaleanchor=anchor, scaleratio=1,
                         row=r, col=c)


def reference_ellipses_figure(configurations: dict | None = None, p=None, velocity_scale: float = 0.15,
                              force_scale: float | None = None, height: int = 640) -> go.Figure:
    """Velocity and force ellipses on the arm (top view) at named configurations, one panel each (up to 6),
    by default the five reference configurations of SPEC section 2; each panel's title gives ``w``
    (:func:`scara.manipulability`). ``configurations`` maps a label to a joint vector (4,).

    >>> fig = reference_ellipses_figure()
    >>> fig.layout.annotations[0].text
    'q1: θ2 = -90.00°, w = 0.250 m²'
    """
    p = _params(p)
    configurations = dict(REFERENCE_CONFIGURATIONS if configurations is None else configurations)
    if not 1 <= len(configurations) <= 6:
        raise ScaraError(f"{len(configurations)} configurations: give between 1 and 6")
    titles = []
    for name, q in configurations.items():
        q = as_vector(q, f"configuration {name}")
        titles.append(f"{name}: θ2 = {math.degrees(q[1]):.2f}°, w = {manipulability(q, p):.3f} m²")
    ncol = 3 if len(configurations) > 2 else len(configurations)
    nrow = math.ceil(len(configurations) / ncol)
    fig = make_subplots(rows=nrow, cols=ncol, subplot_titles=titles, horizontal_spacing=0.06, vertical_spacing=0.14)
    cells = []
    for k, q in enumerate(configurations.values()):
        r, c = divmod(k, ncol)
        cells.append((r + 1, c + 1))
        for t in ellipse_traces(q, p, velocity_scale, force_scale, showlegend=(k == 0)):
            fig.add_trace(t, row=r + 1, col=c + 1)
    fig.update_layout(**_layout("Velocity and force ellipses at the reference configurations (top view)", height,
                                subplot_titles=True))
    fig.update_annotations(font_size=12)
    _top_axes(fig, p, cells, xr=[-0.5, p.r_max + 0.5], yr=[-0.95, 1.05])
    return fig


def workspace_ellipses_figure(points=None, p=None, elbow: int = -1, velocity_scale: float = 0.1,
                              force_scale: float = 0.03, height: int = 560) -> go.Figure:
    """Velocity (left) and force (right) ellipses at many end-effector positions over the workspace, each on
    its arm (elbow ``elbow``), top view. ``points`` (N, 4) targets ``[p_x, p_y, p_z, phi]``, by default
    :func:`workspace_points` (24 positions). Raises :class:`UnreachableError` for a target outside the
    workspace."""
    p = _params(p)
    pts = workspace_points() if points is None else as_array(points, "points", (4,), allow_batch=True)
    pts = np.atleast_2d(pts)
    qs = np.atleast_2d(ikine(pts, p, elbow=elbow))
    fig = make_subplots(rows=1, cols=2, horizontal_spacing=0.08,
                        subplot_titles=[f"velocity ellipses (× {velocity_scale:g})", f"force ellipses (× {force_scale:g})"])
    arms = []
    for q in qs:
        t = top_view_arm(q, p)
        arms += list(t.x) + [None], list(t.y) + [None]
    ax = [v for i in range(0, len(arms), 2) for v in arms[i]]
    ay = [v for i in range(1, len(arms), 2) for v in arms[i]]
    for col, key, sc in ((1, "velocity", velocity_scale), (2, "force", force_scale)):
        fig.add_trace(go.Scatter(x=ax, y=ay, mode="lines", name=f"arms (elbow {elbow:+d})", legendgroup="arm",
                                 showlegend=(col == 1), line=dict(color="#BBBBBB", width=1.5), hoverinfo="skip"),
                      row=1, col=col)
        xs, ys = [], []
        for q in qs:
            ell = (velocity_ellipsoid if key == "velocity" else force_ellipsoid)(q, p, rows=(0, 1))
            xy = ellipse_xy(ell, sc, n=61)
            xs += _as_list(xy[:, 0]) + [None]
            ys += _as_list(xy[:, 1]) + [None]
        fig.add_trace(go.Scatter(x=xs, y=ys, mode="lines", name=f"{key} ellipses", line=dict(color=PALETTE[key], width=2),
                                 hoverinfo="skip"), row=1, col=col)
        fig.add_trace(go.Scatter(x=_as_list(pts[:, 0]), y=_as_list(pts[:, 1]), mode="markers", name="end effector",
                                 legendgroup="ee", showlegend=(col == 1),
                                 marker=dict(size=4, color=PALETTE["reference"]),
                                 hovertemplate="(%{x:.2f}, %{y:.2f}) m<extra></extra>"), row=1, col=col)
        cx, cy = _circle(p.r_max)
        fig.add_trace(go.Scatter(x=_as_list(cx), y=_as_list(cy), mode="lines", name="workspace boundary",
                                 legendgroup="ws", showlegend=(col == 1),
                                 line=dict(color="#999999", dash="dash", width=1), hoverinfo="skip"), row=1, col=col)
    fig.update_layout(**_layout(f"Ellipses at {len(pts)} end-effector positions over the workspace", height,
                                subplot_titles=True))
    _top_axes(fig, p, [(1, 1), (1, 2)], margin=0.15)
    return fig


def manipulability_map_figure(p=None, n: int = 101, height: int = 560) -> go.Figure:
    """Heat map of ``w`` (m²) over the horizontal workspace (:func:`scara.workspace_map`), with the circles
    where ``w = 0`` (stretched ``r = a1 + a2``; folded ``r = |a1 - a2|``, a single point when ``a1 = a2``)
    and the circle of largest ``w`` (``theta2 = ±90°``, ``r = sqrt(a1² + a2²)``). ``n`` grid points per side
    (>= 3, else :class:`ScaraError`).

    >>> fig = manipulability_map_figure(n=41)
    >>> fig.data[0].type
    'heatmap'
    """
    p = _params(p)
    xs, ys, W = workspace_map(p, n)
    r_in, r_out = singular_radii(p)
    fig = go.Figure()
    fig.add_trace(go.Heatmap(x=_as_list(xs), y=_as_list(ys), z=[_as_list(row) for row in W], colorscale="Viridis",
                             zmin=0.0, zmax=p.a1 * p.a2, name="w", colorbar=dict(title=dict(text="w (m²)")),
                             hovertemplate="x = %{x:.2f} m, y = %{y:.2f} m<br>w = %{z:.3f} m²<extra></extra>"))
    cx, cy = _circle(r_out)
    fig.add_trace(go.Scatter(x=_as_list(cx), y=_as_list(cy), mode="lines", name=f"stretched, w = 0 (r = {r_out:g} m)",
                             line=dict(color="#D55E00", width=3), hoverinfo="skip"))
    if r_in > 1e-9:
        cx, cy = _circle(r_in)
        fig.add_trace(go.Scatter(x=_as_list(cx), y=_as_list(cy), mode="lines", name=f"folded, w = 0 (r = {r_in:g} m)",
                                 line=dict(color="#CC79A7", width=3), hoverinfo="skip"))
    else:
        fig.add_trace(go.Scatter(x=[0.0], y=[0.0], mode="markers", name="folded, w = 0 (r = 0: the joint-1 axis)",
                                 marker=dict(color="#CC79A7", size=12, symbol="circle-open", line=dict(width=3))))
    cx, cy = _circle(math.hypot(p.a1, p.a2))
    fig.add_trace(go.Scatter(x=_as_list(cx), y=_as_list(cy), mode="lines",
                             name=f"largest w = a1 a2 (r = {math.hypot(p.a1, p.a2):.3f} m)",
                             line=dict(color="#FFFFFF", width=2, dash="dot"), hoverinfo="skip"))
    fig.update_layout(**_layout("Manipulability w over the workspace (top view)", height, legend_rows=2))
    reach = r_out + 0.1
    fig.update_xaxes(title_text="x (m)", range=[-reach, reach], constrain="domain")
    fig.update_yaxes(title_text="y (m)", range=[-reach, reach], scaleanchor="x", scaleratio=1)
    return fig


def duality_figure(q, p=None, scale: float = 0.15, n: int = 181, height: int = 480) -> go.Figure:
    """The two ellipses are dual. Left: velocity and force ellipses at ``q`` with their principal axes (same
    directions). Right: their semi-axis lengths ``sigma_1, sigma_2`` and ``1/sigma_1, 1/sigma_2`` against
    ``theta2`` on a log scale (mirror images: each product is 1), with ``q`` marked."""
    p = _params(p)
    q = as_vector(q, "q")
    fig = make_subplots(rows=1, cols=2, column_widths=[0.45, 0.55], horizontal_spacing=0.1,
                        subplot_titles=[f"at θ2 = {math.degrees(q[1]):.0f}°: same axes, reciprocal lengths",
                                        "semi-axis lengths against θ2"])
    for t in ellipse_traces(q, p, scale, scale, axes=True):
        fig.add_trace(t, row=1, col=1)
    t2 = np.linspace(-179.0, 179.0, int(n))
    sig = np.array([velocity_ellipsoid([q[0], math.radians(v), q[2], q[3]], p, rows=(0, 1)).lengths for v in t2])
    styles = (("velocity", "σ1 (velocity, major)", "solid"), ("velocity", "σ2 (velocity, minor)", "dot"),
              ("force", "1/σ1 (force, minor)", "solid"), ("force", "1/σ2 (force, major)", "dot"))
    for k, (key, name, dash) in enumerate(styles):
        with np.errstate(divide="ignore"):
            y = sig[:, k % 2] if k < 2 else 1.0 / sig[:, k % 2]
        fig.add_trace(go.Scatter(x=_as_list(t2, 2), y=_as_list(y, 5), mode="lines", name=name, legendgroup=key,
                                 line=dict(color=PALETTE[key], dash=dash, width=2)), row=1, col=2)
    here = velocity_ellipsoid(q, p, rows=(0, 1)).lengths
    fig.add_trace(go.Scatter(x=[math.degrees(q[1])] * 4, y=_as_list(np.concatenate([here, 1.0 / here]), 5),
                             mode="markers", name="this configuration",
                             marker=dict(size=9, color=PALETTE["reference"], symbol="circle-open", line=dict(width=2))),
                  row=1, col=2)
    fig.update_layout(**_layout("Duality of the velocity and force ellipses", height, legend_rows=2,
                                subplot_titles=True))
    reach = p.r_max + 0.2
    fig.update_xaxes(title_text="x (m)", range=[-0.4, reach], constrain="domain", row=1, col=1)
    fig.update_yaxes(title_text="y (m)", range=[-0.7, 0.7], scaleanchor="x", scaleratio=1, row=1, col=1)
    fig.update_xaxes(title_text="θ2 (deg)", tickvals=list(range(-180, 181, 90)), row=1, col=2)
    fig.update_yaxes(title_text="semi-axis length (m/s or N, log scale)", type="log", range=[-2, 2], row=1, col=2)
    return fig


def ellipse_slider_figure(theta2_deg=None, theta1: float = 0.0, p=None, scale: float = 0.15,
                          height: int = 600) -> go.Figure:
    """Static (kernel-free) figure: the arm and its velocity and force ellipses (top view) with one slider
    sweeping ``theta2`` over ``theta2_deg`` (degrees; default 25 steps from 180° folded, through 0°
    stretched, to -180° folded the other way). Each step restyles the arm and both ellipses (traces 0-2) and
    retitles the figure with ``w`` and the semi-axes. ``theta1`` in rad. Raises :class:`ScaraError` for fewer
    than 2 or more than 61 steps or a scale that is not positive.

    >>> fig = ellipse_slider_figure()
    >>> len(fig.layout.sliders[0].steps), fig.layout.sliders[0].currentvalue.prefix
    (25, 'θ2 (°) = ')
    """
    p = _params(p)
    vals = np.linspace(180.0, -180.0, 25) if theta2_deg is None else as_array(theta2_deg, "theta2_deg",
                                                                                (len(np.atleast_1d(theta2_deg)),))
    if not 2 <= len(vals) <= 61:
        raise ScaraError(f"{len(vals)} slider steps: use between 2 and 61 (pages stay light)")
    qs = [np.array([theta1, math.radians(v), 0.5 * p.d0, 0.0]) for v in vals]

    def title(v, q):
        s = velocity_ellipsoid(q, p, rows=(0, 1)).lengths
        return (f"θ2 = {v:.0f}°: w = {manipulability(q, p):.3f} m²<br>velocity semi-axes σ = ({s[0]:.3f}, {s[1]:.3f}),"
                f" force semi-axes 1/σ = ({_inv(s[0])}, {_inv(s[1])})")

    active = int(np.argmin(np.abs(vals - 90.0)))
    fig = go.Figure(ellipse_traces(qs[active], p, scale, scale, n=91))
    steps = []
    for v, q in zip(vals, qs):
        tr = ellipse_traces(q, p, scale, scale, n=91)
        steps.append(dict(label=f"{v:.0f}", method="update",
                          args=[{"x": [t.x for t in tr], "y": [t.y for t in tr]}, {"title.text": title(v, q)},
                                list(range(len(tr)))]))
    cx, cy = _circle(p.r_max)
    fig.add_trace(go.Scatter(x=_as_list(cx), y=_as_list(cy), mode="lines", name="workspace boundary",
                             line=dict(color="#999999", dash="dash", width=1), hoverinfo="skip"))
    fig.update_layout(**_layout(title(vals[active], qs[active]), height),
                      sliders=[slider(steps, prefix="θ2 (°) = ", active=active)])
    reach = p.r_max + 0.2
    fig.update_xaxes(title_text="x (m)", range=[-reach, reach], constrain="domain")
    fig.update_yaxes(title_text="y (m)", range=[-reach, reach], scaleanchor="x", scaleratio=1)
    return fig


def _inv(s):
    return "∞" if s < 1e-12 else (f"{1.0 / s:.3g}" if 1.0 / s < 1e4 else f"{1.0 / s:.1e}")
