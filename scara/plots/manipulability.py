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

from ..errors import ScaraError, as_array, as_vector, check_count, check_number, check_positive
from ..kinematics import ikine
from .._manipulability import force_ellipsoid, manipulability, singular_radii, velocity_ellipsoid, workspace_map
from ._common import PALETTE, as_list, slider
from ._common import MAX_GRID, MAX_POINTS, MAX_SWEEP, MAX_TARGETS, FIGURE_BUDGET
from .kinematics import _circle, top_axes, top_view_arm
from .layout import finish_layout
from .panels import Text
from ..params import ScaraParams
from ..programs.manipulability import ELLIPSE_CLIP

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
    "major_axis_angle",
    "base_turn_figure", "ellipse_panel_figure", "ELLIPSE_TRACES", "ELLIPSE_TITLE",
]

#: the five reference configurations of chapter 2 (section *Five reference configurations*), with their labels
REFERENCE_CONFIGURATIONS = {
    "q1": (0.0, -math.pi / 2, 0.5, 0.0),
    "q2": (0.0, math.pi / 4, 0.5, 0.0),
    "q3": (0.0, math.pi / 30, 0.5, 0.0),
    "q4": (0.0, 98 * math.pi / 100, 0.5, 0.0),
    "q5": (0.0, -99.99 * math.pi / 100, 0.5, 0.0),
}
_CLIP = ELLIPSE_CLIP  # m: drawn semi-axes are capped here (the view is about 2.5 m wide)
#: line style per ellipse kind: velocity solid, force dashed (told apart in greyscale)
_DASH = {"velocity": "solid", "force": "dash"}
#: the same styles for small ellipses (a few millimetres of outline): short dashes that leave each a whole curve
_SMALL_DASH = {"velocity": "solid", "force": "3px,2px"}


def ellipse_xy(ellipsoid, scale: float = 1.0, n: int = 181) -> np.ndarray:
    """Outline ``(n, 2)`` of a horizontal ellipse (``rows=(0, 1)``) with its semi-axes times ``scale``.

    Semi-axes longer than ``_CLIP`` m after scaling (an unbounded force ellipse at a singularity, ``inf``) are
    capped at ``_CLIP``: within any view of the arm the result is the strip the true, unbounded ellipse
    draws. Raises :class:`ScaraError` for a scale that is not positive.

    Limits: ``n`` from 3 to 10 000 samples (``MAX_POINTS``); a value outside, or not a whole number, raises
    :class:`ScaraError` before any work.
    """
    n = check_count(n, "n", 3, MAX_POINTS, "samples", FIGURE_BUDGET)
    scale = check_positive(scale, "scale")
    lengths = np.minimum(np.asarray(ellipsoid.lengths, dtype=float) * scale, _CLIP)
    clipped = dataclasses.replace(ellipsoid, lengths=lengths)
    return clipped.outline(n=n, scale=1.0, plane=(0, 1))


def ellipse_traces(q, p=None, velocity_scale: float = 0.15, force_scale: float | None = None, arm: bool = True,
                   showlegend: bool = True, axes: bool = False, n: int = 181) -> list:
    """2-D traces (top view) of the arm at ``q`` with its horizontal velocity and force ellipses centred at
    the end effector; with ``axes`` also their principal axes as segments (not in the legend).

    ``velocity_scale`` is in metres drawn per m/s (semi-axis ``sigma_i`` for a unit joint-velocity norm),
    ``force_scale`` in metres drawn per N (semi-axis ``1/sigma_i`` for a unit torque norm), by default the
    same number. The velocity ellipse is solid (``PALETTE["velocity"]``), the force ellipse dashed
    (``PALETTE["force"]``), so the two differ in greyscale too. Returns a list of ``go.Scatter``: the arm (if
    ``arm``), the velocity ellipse, [its axes], the force ellipse, [its axes].
    """
    p = ScaraParams.resolve(p)
    q = as_vector(q, "q")
    force_scale = velocity_scale if force_scale is None else force_scale
    vel = velocity_ellipsoid(q, p, rows=(0, 1))
    frc = force_ellipsoid(q, p, rows=(0, 1))
    traces = []
    if arm:
        traces.append(top_view_arm(q, p, showlegend=showlegend))
    for ell, sc, key in ((vel, velocity_scale, "velocity"), (frc, force_scale, "force")):
        xy = ellipse_xy(ell, sc, n)
        traces.append(_outline_trace(key, as_list(xy[:, 0]), as_list(xy[:, 1]), showlegend))
        if axes:
            seg = []
            for i in range(2):
                half = min(sc * ell.lengths[i], _CLIP) * ell.axes[:, i]
                seg += [ell.centre[:2] - half, ell.centre[:2] + half, [np.nan, np.nan]]
            seg = np.array(seg)
            traces.append(_axes_trace(key, as_list(seg[:, 0]), as_list(seg[:, 1])))
    return traces


def _outline_trace(key: str, x, y, showlegend: bool = True) -> go.Scatter:
    """The outline of the ``key`` ellipse (``"velocity"``: solid, ``"force"``: dashed) through the points ``x``,
    ``y``."""
    return go.Scatter(x=x, y=y, mode="lines", name=f"{key} ellipse", legendgroup=key, showlegend=showlegend,
                      line=dict(color=PALETTE[key], width=2.5, dash=_DASH[key]), hoverinfo="skip")


def _axes_trace(key: str, x, y) -> go.Scatter:
    """The principal axes of the ``key`` ellipse: the segments through ``x``, ``y`` (gaps between them), dotted
    and out of the legend."""
    return go.Scatter(x=x, y=y, mode="lines", name=f"{key} principal axes", legendgroup=key, showlegend=False,
                      line=dict(color=PALETTE[key], width=1.2, dash="dot"), hoverinfo="skip")


def workspace_points(radii=(0.3, 0.55, 0.8), n_angles: int = 8, height: float = 0.5) -> np.ndarray:
    """End-effector targets ``(len(radii) * n_angles, 4)`` spread over the workspace: rings of radius
    ``radii`` (m), ``n_angles`` per ring (rings staggered by half a step), at height ``height``, phi = 0.

    Limits: ``n_angles`` from 1, and at most 200 targets in all (``MAX_TARGETS``, ``len(radii) * n_angles``); more,
    or a count that is not a whole number, raises :class:`ScaraError` before any work."""
    radii = as_array(radii, "radii", (len(np.atleast_1d(radii)),))
    n_angles = check_count(n_angles, "n_angles", 1, MAX_TARGETS, "targets per ring", FIGURE_BUDGET)
    check_count(len(radii) * n_angles, "len(radii) * n_angles", 1, MAX_TARGETS, "targets", FIGURE_BUDGET)
    pts = []
    for k, r in enumerate(radii):
        for j in range(n_angles):
            a = 2 * math.pi * (j + 0.5 * (k % 2)) / n_angles
            pts.append([r * math.cos(a), r * math.sin(a), height, 0.0])
    return np.array(pts)


def _boundary_trace(p, name="workspace boundary", showlegend=False):
    """The reach ``r = a1 + a2`` as a thin grey dashed circle (named in the captions, kept out of the legend so
    that the legend stays short at phone width)."""
    cx, cy = _circle(p.r_max)
    return go.Scatter(x=as_list(cx), y=as_list(cy), mode="lines", name=name, showlegend=showlegend,
                      line=dict(color="#999999", dash="dash", width=1), hoverinfo="skip")


def _fit_top_axes(fig, p, pad: float = 0.1, limit: float | None = None) -> None:
    """Equal-scale x-y axes (m) of a top view that hold the reach circle and every trace the figure draws, at
    every step of its slider (one fixed range: nothing runs off the plot as the slider moves), ``pad`` m more on
    each side; ``limit`` (m) caps the range (a strip drawn for an unbounded ellipse)."""
    xs, ys = [np.array(_circle(p.r_max)[0])], [np.array(_circle(p.r_max)[1])]
    for t in fig.data:
        xs.append(np.array(t.x, dtype=float)), ys.append(np.array(t.y, dtype=float))
    for sl in fig.layout.sliders or ():
        for st in sl.steps:
            change = st.args[0] if st.args else {}
            xs += [np.array(v, dtype=float) for v in change.get("x", ())]
            ys += [np.array(v, dtype=float) for v in change.get("y", ())]
    x, y = np.concatenate(xs), np.concatenate(ys)
    lo = np.array([np.nanmin(x), np.nanmin(y)]) - pad
    hi = np.array([np.nanmax(x), np.nanmax(y)]) + pad
    if limit is not None:
        lo, hi = np.maximum(lo, -limit), np.minimum(hi, limit)
    top_axes(fig, p, xr=[round(float(lo[0]), 3), round(float(hi[0]), 3)],
             yr=[round(float(lo[1]), 3), round(float(hi[1]), 3)])
    fig.update_xaxes(dtick=0.5)
    fig.update_yaxes(dtick=0.5)


def _inv(s):
    return "∞" if s < 1e-12 else (f"{1.0 / s:.3g}" if 1.0 / s < 1e4 else f"{1.0 / s:.1e}")


def _axes_text(q, p):
    s = velocity_ellipsoid(q, p, rows=(0, 1)).lengths
    return f"σ: {s[0]:.3f}, {s[1]:.3f} m/s; 1/σ: {_inv(s[0])}, {_inv(s[1])} N"


def reference_ellipses_figure(configurations: dict | None = None, p=None, velocity_scale: float = 0.15,
                              force_scale: float | None = None, height: int = 560) -> go.Figure:
    """Static (kernel-free) figure: the arm (top view) with its velocity and force ellipses and their principal
    axes at named configurations, one slider step each, by default the five reference configurations of
    chapter 2 (``REFERENCE_CONFIGURATIONS``). Each step retitles the figure with ``theta2``, ``w``
    (:func:`scara.manipulability`) and the semi-axes. ``configurations`` maps a label to a joint vector (4,);
    between 2 and 25 of them, else :class:`ScaraError`.

    >>> fig = reference_ellipses_figure()
    >>> [s.label for s in fig.layout.sliders[0].steps]
    ['q1', 'q2', 'q3', 'q4', 'q5']
    """
    p = ScaraParams.resolve(p)
    configurations = dict(REFERENCE_CONFIGURATIONS if configurations is None else configurations)
    if not 2 <= len(configurations) <= 25:
        raise ScaraError(f"{len(configurations)} configurations: give between 2 and 25")
    qs = {name: as_vector(q, f"configuration {name}") for name, q in configurations.items()}

    def title(name, q):
        return (f"{name}: θ2 = {math.degrees(q[1]):.2f}°, w = {manipulability(q, p):.3f} m²<br>"
                f"{_axes_text(q, p)}")

    first = next(iter(qs))
    traces = ellipse_traces(qs[first], p, velocity_scale, force_scale, axes=True)
    fig = go.Figure(traces)
    fig.add_trace(_boundary_trace(p))
    steps = []
    for name, q in qs.items():
        tr = ellipse_traces(q, p, velocity_scale, force_scale, axes=True)
        steps.append(dict(label=name, method="update",
                          args=[{"x": [t.x for t in tr], "y": [t.y for t in tr]}, {"title.text": title(name, q)},
                                list(range(len(tr)))]))
    finish_layout(fig, title(first, qs[first]), height, sliders=[slider(steps, prefix="configuration ")])
    # the reach circle whole, and the ellipses as far as a view 3.4 m wide holds them (q5's strip runs off)
    _fit_top_axes(fig, p, limit=1.7)
    return fig


def workspace_ellipses_figure(points=None, p=None, elbow: int = -1, velocity_scale: float = 0.1,
                              force_scale: float = 0.03, height: int = 560) -> go.Figure:
    """Static (kernel-free) figure: the arms (elbow ``elbow``, top view) reaching many end-effector positions
    over the workspace, with a two-step slider that shows their velocity ellipses (first step) or their force
    ellipses. ``points`` (N, 4) targets ``[p_x, p_y, p_z, phi]``, by default :func:`workspace_points`
    (24 positions). Raises :class:`UnreachableError` for a target outside the workspace, and
    :class:`ScaraError` for more than 200 targets (``MAX_TARGETS``), before any work.

    Trace 1 holds the ellipses of the step shown (named ``"velocity ellipses"`` or ``"force ellipses"``).
    """
    p = ScaraParams.resolve(p)
    pts = workspace_points() if points is None else as_array(points, "points", (4,), allow_batch=True)
    pts = np.atleast_2d(pts)
    check_count(len(pts), "the number of points", 1, MAX_TARGETS, "targets", FIGURE_BUDGET)
    qs = np.atleast_2d(ikine(pts, p, elbow=elbow))
    # the arms of the outer ring only (radius largest): 24 arms tangle into a web hiding the ellipses
    r = np.hypot(pts[:, 0], pts[:, 1])
    outer = np.isclose(r, r.max(), atol=1e-9)
    ax, ay = [], []
    for q in qs[outer]:
        t = top_view_arm(q, p)
        ax += list(t.x) + [None]
        ay += list(t.y) + [None]
    outlines = {}
    for key, sc in (("velocity", velocity_scale), ("force", force_scale)):
        xs, ys = [], []
        for q in qs:
            ell = (velocity_ellipsoid if key == "velocity" else force_ellipsoid)(q, p, rows=(0, 1))
            xy = ellipse_xy(ell, sc, n=61)
            xs += as_list(xy[:, 0]) + [None]
            ys += as_list(xy[:, 1]) + [None]
        outlines[key] = (xs, ys, sc)
    fig = go.Figure()
    fig.add_trace(go.Scatter(x=ax, y=ay, mode="lines", name=f"arms, outer ring (elbow {elbow:+d})",
                             line=dict(color="#C8C8C8", width=1.5), hoverinfo="skip"))
    xs, ys, sc = outlines["velocity"]
    fig.add_trace(go.Scatter(x=xs, y=ys, mode="lines", name="velocity ellipses", hoverinfo="skip",
                             line=dict(color=PALETTE["velocity"], width=2, dash=_SMALL_DASH["velocity"])))
    fig.add_trace(go.Scatter(x=as_list(pts[:, 0]), y=as_list(pts[:, 1]), mode="markers", name="end effector",
                             marker=dict(size=4, color=PALETTE["reference"]),
                             hovertemplate="(%{x:.2f}, %{y:.2f}) m<extra></extra>"))
    fig.add_trace(_boundary_trace(p))

    def title(key, sc):
        unit = "m/s" if key == "velocity" else "N"
        return f"{key.capitalize()} ellipses at {len(pts)} positions<br>(drawn at {sc:g} m per {unit})"

    steps = []
    for key in ("velocity", "force"):
        xs, ys, sc = outlines[key]
        steps.append(dict(label=key, method="update", args=[
            {"x": [xs], "y": [ys], "name": [f"{key} ellipses"], "line.color": [PALETTE[key]],
             "line.dash": [_SMALL_DASH[key]]}, {"title.text": title(key, sc)}, [1]]))
    finish_layout(fig, title("velocity", velocity_scale), height, sliders=[slider(steps, prefix="ellipses: ")])
    top_axes(fig, p, margin=0.1)
    return fig


def manipulability_map_figure(p=None, n: int = 101, height: int = 520) -> go.Figure:
    """Heat map of ``w`` (m²) over the horizontal workspace (:func:`scara.workspace_map`), with the circles
    where ``w = 0`` (stretched ``r = a1 + a2``; folded ``r = |a1 - a2|``, a single point when ``a1 = a2``)
    and the circle of largest ``w`` (``theta2 = ±90°``, ``r = sqrt(a1² + a2²)``). ``n`` grid points per side,
    from 3 to 301 (``MAX_GRID``: 90 601 cells); a value outside, or not a whole number, raises
    :class:`ScaraError` before any work. Viridis runs from dark to light, so the map reads in greyscale.

    >>> fig = manipulability_map_figure(n=41)
    >>> fig.data[0].type
    'heatmap'
    """
    n = check_count(n, "n", 3, MAX_GRID, "grid points per side", FIGURE_BUDGET)
    p = ScaraParams.resolve(p)
    xs, ys, W = workspace_map(p, n)
    r_in, r_out = singular_radii(p)
    fig = go.Figure()
    fig.add_trace(go.Heatmap(x=as_list(xs), y=as_list(ys), z=[as_list(row) for row in W], colorscale="Viridis",
                             zmin=0.0, zmax=p.a1 * p.a2, name="w",
                             colorbar=dict(title=dict(text="w (m²)", side="right"), thickness=14),
                             hovertemplate="x = %{x:.2f} m, y = %{y:.2f} m<br>w = %{z:.3f} m²<extra></extra>"))
    cx, cy = _circle(r_out)
    fig.add_trace(go.Scatter(x=as_list(cx), y=as_list(cy), mode="lines", name=f"stretched: w = 0, r = {r_out:g} m",
                             line=dict(color=PALETTE["force"], width=3), hoverinfo="skip"))
    if r_in > 1e-9:
        cx, cy = _circle(r_in)
        fig.add_trace(go.Scatter(x=as_list(cx), y=as_list(cy), mode="lines", name=f"folded: w = 0, r = {r_in:g} m",
                                 line=dict(color="#CC79A7", width=3, dash="dash"), hoverinfo="skip"))
    else:
        fig.add_trace(go.Scatter(x=[0.0], y=[0.0], mode="markers", name="folded: w = 0, r = 0",
                                 marker=dict(color="#CC79A7", size=12, symbol="circle-open", line=dict(width=3))))
    cx, cy = _circle(math.hypot(p.a1, p.a2))
    fig.add_trace(go.Scatter(x=as_list(cx), y=as_list(cy), mode="lines",
                             name=f"largest w: r = {math.hypot(p.a1, p.a2):.3f} m",
                             line=dict(color=PALETTE["reference"], width=2, dash="dot"), hoverinfo="skip"))
    finish_layout(fig, "Manipulability w over the workspace", height)
    reach = r_out + 0.1
    fig.update_xaxes(title_text="x (m)", range=[-reach, reach], constrain="domain")
    fig.update_yaxes(title_text="y (m)", range=[-reach, reach], scaleanchor="x", scaleratio=1)
    return fig


def duality_figure(q, p=None, n: int = 181, height: int = 440) -> go.Figure:
    """The two ellipses are dual: the semi-axis lengths ``sigma_1, sigma_2`` of the velocity ellipse and
    ``1/sigma_1, 1/sigma_2`` of the force ellipse against ``theta2`` (degrees, the other joints as in ``q``)
    on a log scale, mirror images of each other because each product is 1, with the values at ``q`` marked.
    ``n`` samples of theta2 over [-179°, 179°] (>= 3, else :class:`ScaraError`).

    Limits: ``n`` from 3 to 2001 samples (``MAX_SWEEP``); a value outside, or not a whole number, raises
    :class:`ScaraError` before any work."""
    n = check_count(n, "n", 3, MAX_SWEEP, "samples", FIGURE_BUDGET)
    p = ScaraParams.resolve(p)
    q = as_vector(q, "q")
    t2 = np.linspace(-179.0, 179.0, n)
    sig = np.array([velocity_ellipsoid([q[0], math.radians(v), q[2], q[3]], p, rows=(0, 1)).lengths for v in t2])
    fig = go.Figure()
    styles = (("velocity", "σ1 (velocity)", "solid", 0, False), ("velocity", "σ2 (velocity)", "dash", 1, False),
              ("force", "1/σ1 (force)", "dot", 0, True), ("force", "1/σ2 (force)", "dashdot", 1, True))
    for key, name, dash, k, inverse in styles:
        with np.errstate(divide="ignore"):
            y = 1.0 / sig[:, k] if inverse else sig[:, k]
        fig.add_trace(go.Scatter(x=as_list(t2, 2), y=as_list(y, 5), mode="lines", name=name, legendgroup=key,
                                 line=dict(color=PALETTE[key], dash=dash, width=2.5)))
    here = velocity_ellipsoid(q, p, rows=(0, 1)).lengths
    fig.add_trace(go.Scatter(x=[round(math.degrees(q[1]), 2)] * 4, y=as_list(np.concatenate([here, 1.0 / here]), 5),
                             mode="markers", name=f"θ2 = {math.degrees(q[1]):.0f}°",
                             marker=dict(size=9, color=PALETTE["reference"], symbol="circle-open", line=dict(width=2))))
    finish_layout(fig, "Semi-axes of the two ellipses against θ2", height)
    fig.update_xaxes(title_text="θ2 (°)", tickvals=list(range(-180, 181, 90)))
    fig.update_yaxes(title_text="semi-axis (m/s or N, log)", type="log", range=[-2, 2])
    return fig


def ellipse_slider_figure(theta2_deg=None, theta1: float = 0.0, p=None, scale: float = 0.15,
                          height: int = 560) -> go.Figure:
    """Static (kernel-free) figure: the arm and its velocity and force ellipses (top view) with one slider
    sweeping ``theta2`` over ``theta2_deg`` (degrees; default 25 steps from 180° folded, through 0°
    stretched, to -180° folded the other way). Each step restyles the arm and both ellipses (traces 0-2) and
    retitles the figure with ``w`` and the semi-axes. ``theta1`` in rad. Raises :class:`ScaraError` for fewer
    than 2 or more than 61 steps or a scale that is not positive.

    >>> fig = ellipse_slider_figure()
    >>> len(fig.layout.sliders[0].steps), fig.layout.sliders[0].currentvalue.prefix
    (25, 'θ2 (°) = ')
    """
    p = ScaraParams.resolve(p)
    vals = np.linspace(180.0, -180.0, 25) if theta2_deg is None else as_array(theta2_deg, "theta2_deg",
                                                                                (len(np.atleast_1d(theta2_deg)),))
    if not 2 <= len(vals) <= 61:
        raise ScaraError(f"{len(vals)} slider steps: use between 2 and 61 (pages stay light)")
    check_positive(scale, "scale")
    qs = [np.array([theta1, math.radians(v), 0.5 * p.d0, 0.0]) for v in vals]

    def title(v, q):
        return f"θ2 = {v:.0f}°: w = {manipulability(q, p):.3f} m²<br>{_axes_text(q, p)}"

    active = int(np.argmin(np.abs(vals - 90.0)))
    fig = go.Figure(ellipse_traces(qs[active], p, scale, scale, n=91))
    steps = []
    for v, q in zip(vals, qs):
        tr = ellipse_traces(q, p, scale, scale, n=91)
        steps.append(dict(label=f"{v:.0f}", method="update",
                          args=[{"x": [t.x for t in tr], "y": [t.y for t in tr]}, {"title.text": title(v, q)},
                                list(range(len(tr)))]))
    fig.add_trace(_boundary_trace(p))
    finish_layout(fig, title(vals[active], qs[active]), height,
                  sliders=[slider(steps, prefix="θ2 (°) = ", active=active)])
    top_axes(fig, p)
    return fig


def major_axis_angle(ellipsoid) -> float:
    """Direction of the major axis of a horizontal ellipse (``rows=(0, 1)``): the principal axis ``u_i`` of
    (2.2) with the largest semi-axis ``sigma_i``, in degrees from ``x_b`` towards ``y_b``, in (-90°, 90°]: an
    axis has no sign, so the angle is taken modulo 180°."""
    u = np.asarray(ellipsoid.axes)[:, int(np.argmax(ellipsoid.lengths))]
    a = math.degrees(math.atan2(u[1], u[0])) % 180.0
    return a - 180.0 if a > 90.0 else a


def base_turn_figure(theta1_deg=None, theta2: float = math.pi / 4, p=None, scale: float = 0.15,
                     height: int = 560) -> go.Figure:
    """Static (kernel-free) figure: the arm and its velocity and force ellipses with their principal axes
    (top view), one slider step per ``theta1`` of ``theta1_deg`` (degrees; default 0° to 60° in steps of 10°)
    with ``theta2`` (rad) held, by default 45° (configuration q2). Each step restyles the arm and the ellipses
    and retitles the figure with ``theta1``, ``w`` (2.4), the direction of the major velocity axis
    (:func:`major_axis_angle`) and the semi-axes ``sigma_1, sigma_2`` and ``1/sigma_1, 1/sigma_2``. Raises :class:`ScaraError` for fewer than 2 or more than 61
    steps or a scale that is not positive.

    >>> fig = base_turn_figure()
    >>> [s.label for s in fig.layout.sliders[0].steps]
    ['0', '10', '20', '30', '40', '50', '60']
    """
    p = ScaraParams.resolve(p)
    vals = np.arange(0.0, 61.0, 10.0) if theta1_deg is None else as_array(theta1_deg, "theta1_deg",
                                                                            (len(np.atleast_1d(theta1_deg)),))
    if not 2 <= len(vals) <= 61:
        raise ScaraError(f"{len(vals)} slider steps: use between 2 and 61 (pages stay light)")
    scale = check_positive(scale, "scale")
    theta2 = check_number(theta2, "theta2", "an angle in rad")
    qs = [np.array([math.radians(v), theta2, 0.5 * p.d0, 0.0]) for v in vals]

    def title(v, q):
        major = major_axis_angle(velocity_ellipsoid(q, p, rows=(0, 1)))
        return (f"θ1 = {v:.0f}°: w = {manipulability(q, p):.3f} m², major axis {major:.1f}°<br>"
                f"{_axes_text(q, p)}")

    fig = go.Figure(ellipse_traces(qs[0], p, scale, scale, axes=True))
    steps = []
    for v, q in zip(vals, qs):
        tr = ellipse_traces(q, p, scale, scale, axes=True)
        steps.append(dict(label=f"{v:.0f}", method="update",
                          args=[{"x": [t.x for t in tr], "y": [t.y for t in tr]}, {"title.text": title(v, q)},
                                list(range(len(tr)))]))
    fig.add_trace(_boundary_trace(p))
    finish_layout(fig, title(vals[0], qs[0]), height, sliders=[slider(steps, prefix="θ1 (°) = ")])
    _fit_top_axes(fig, p)      # one range that holds the ellipses at every step
    return fig


#: how the ellipses panel draws its program's outputs (:mod:`scara.programs.manipulability`): the arm and each
#: ellipse's outline and principal axes, keyed by trace name (a :class:`~scara.plots.panels.PageProgram`'s
#: ``traces``); :func:`ellipse_panel_figure` draws the same fields
ELLIPSE_TRACES = {"ellipses": {
    "arm": {"x": "arm_x", "y": "arm_y"},
    "velocity ellipse": {"x": "vel_x", "y": "vel_y"},
    "velocity principal axes": {"x": "vel_axes_x", "y": "vel_axes_y"},
    "force ellipse": {"x": "force_x", "y": "force_y"},
    "force principal axes": {"x": "force_axes_x", "y": "force_axes_y"},
}}
#: the ellipses panel's title, from the sliders' angles and ``w``
ELLIPSE_TITLE = Text("θ1 = {theta1:.0f}°, θ2 = {theta2:.0f}°: w = {w:.3f} m²")


def ellipse_panel_figure(values, p=None, height: int = 520) -> go.Figure:
    """The ellipses panel's figure, drawn from the outputs of :func:`scara.programs.manipulability.ellipse_program`
    (``values``: the program's outputs by field with the settings): the top view of the arm with its horizontal
    velocity and force ellipses and their principal axes (styled as :func:`ellipse_traces` styles them), titled
    :data:`ELLIPSE_TITLE`. The fields drawn are those of :data:`ELLIPSE_TRACES`."""
    p = ScaraParams.resolve(p)
    arm = top_view_arm(np.zeros(4), p)
    arm.update(x=values["arm_x"], y=values["arm_y"])
    fig = go.Figure([arm, _outline_trace("velocity", values["vel_x"], values["vel_y"]),
                     _axes_trace("velocity", values["vel_axes_x"], values["vel_axes_y"]),
                     _outline_trace("force", values["force_x"], values["force_y"]),
                     _axes_trace("force", values["force_axes_x"], values["force_axes_y"])])
    finish_layout(fig, ELLIPSE_TITLE.format(values), height)
    top_axes(fig, p)
    return fig
