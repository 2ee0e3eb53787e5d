"""Animations that play in the static page (no kernel): plotly frames with Play/Pause buttons and a time slider.

Every builder picks its frame times from the speed of the path (:func:`frame_indices`): a frame every
``fast`` s (0.1 s by default, 10 frames per simulated second) while the tool moves at a quarter of its top speed
or more, sparser as it slows down, and one every ``rest`` s (1 s) at rest. Frames carry only the traces that
change (``go.Frame(traces=[...])``), rounded to 4 decimals in metres (0.1 mm) or 4 significant digits, so
that an animation of the 70 s reference stays under about 1.5 MB of page.

* :func:`trajectory_animation` - chapter 3: the arm, seen from above, following the reference path;
* :func:`clik_animation` - chapter 4: the CLIK methods side by side, their tracking error magnified;
* :func:`control_animation` - chapter 6: the controllers with the unknown payload, and the adaptive estimate;
* :func:`course_animation` - the introduction's course figure with Play/Pause.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable

import numpy as np
import plotly.graph_objects as go
from plotly.subplots import make_subplots

from ..errors import ScaraError, is_bool
from ._common import PALETTE, as_list, envelope, run_colour, run_label, run_name, thin
from .course import course_figure
from .kinematics import top_arm_points, top_axes, top_view_arm
from .layout import finish_layout
from .trajectory import decimate
from ..params import ScaraParams

__all__ = [
    "MAX_FRAMES", "FRAME_MS", "frame_indices", "play_controls", "magnification_text", "trajectory_animation",
    "clik_animation",
    "control_animation", "course_animation",
]

#: most frames an animation may have (each frame is about 0.5 to 2 kB of page)
MAX_FRAMES = 1000
#: playback time of one frame (ms): a 0.1 s frame plays at about 1.7 times real time, a 1 s rest frame at 17
FRAME_MS = 60
_BOTTOM = 165  # px under the plot for the buttons and, under them, the slider
#: colour of the slider's readout (the time): the template's text colour, written out because the slider's own
#: font, which the readout would inherit, is transparent (it hides the step labels, one per frame)
READOUT_COLOUR = "#2a3f5f"


def _positive(value, name: str, upper: float = 10.0) -> float:
    if is_bool(value) or not isinstance(value, (int, float)) or not math.isfinite(value) or not 0 < value <= upper:
        raise ScaraError(f"{name} = {value!r:.80} must be a time step in seconds, above 0 and at most {upper:g}")
    return float(value)


def _sig(values, digits: int = 4) -> list:
    """A plain list rounded to ``digits`` significant digits (for log-scale values)."""
    return [None if not np.isfinite(v) else float(f"{float(v):.{digits}g}") for v in np.ravel(values)]


def frame_indices(t, x, fast: float = 0.1, rest: float = 1.0, dense: tuple | None = None) -> np.ndarray:
    """Sample indices of the frames of an animation of the motion ``x`` (N, >= 2) sampled at ``t`` (N,).

    The frame rule: the spacing is ``fast`` s while the tool speed is at least a quarter of its largest value,
    grows as ``fast * v_fast / v`` below that, and is at most ``rest`` s (at rest). Each step takes the
    smallest spacing met over the next ``rest`` s, so that a motion starting inside a rest step is not skipped.
    ``dense = (t0, t1, h)`` adds a frame every ``h`` s from ``t0`` to ``t1`` s (a fast transient of the run, such
    as an estimate converging, while the path itself barely moves).
    The first and last samples are always frames. Raises :class:`ScaraError` for a bad ``fast`` or ``rest``,
    mismatched shapes, or more than ``MAX_FRAMES`` frames.
    """
    fast = _positive(fast, "fast")
    rest = _positive(rest, "rest")
    if rest < fast:
        raise ScaraError(f"rest = {rest:g} s must be at least fast = {fast:g} s")
    t = np.asarray(t, dtype=float)
    x = np.asarray(x, dtype=float)
    if t.ndim != 1 or t.size < 2 or x.ndim != 2 or x.shape[0] != t.size or x.shape[1] < 2:
        raise ScaraError(f"t (N,) and x (N, >= 2) must describe one motion of at least 2 samples; got shapes "
                         f"{t.shape} and {x.shape}")
    pos = x[:, :3] if x.shape[1] >= 3 else x
    v = np.linalg.norm(np.gradient(pos, t, axis=0), axis=1)
    v_fast = 0.25 * v.max()
    with np.errstate(divide="ignore", invalid="ignore"):
        spacing = np.where(v > 0, fast * v_fast / v, rest) if v_fast > 0 else np.full(t.size, rest)
    spacing = np.clip(spacing, fast, rest)
    dt = (t[-1] - t[0]) / (t.size - 1)
    window = max(1, int(round(rest / dt)))
    idx, k, n = [0], 0, t.size
    while True:
        h = spacing[k:k + window].min()
        # at least one sample on: a run sampled more coarsely than ``fast`` has a frame at every sample
        k = max(k + 1, int(np.searchsorted(t, t[k] + h - 0.5 * dt)))
        if k >= n - 1:
            break
        idx.append(k)
        if len(idx) > MAX_FRAMES:
            raise ScaraError(f"fast = {fast:g} s asks for more than {MAX_FRAMES} frames (the limit) over the "
                             f"{t[-1] - t[0]:g} s run: raise fast or rest")
    idx.append(n - 1)
    if dense is not None:
        try:
            t0, t1, h = (float(v) for v in dense)
        except (TypeError, ValueError):
            raise ScaraError(f"dense = {dense!r:.80} must be (t0, t1, h) in seconds") from None
        _positive(h, "dense step h")
        if not (math.isfinite(t0) and math.isfinite(t1) and t0 <= t1) or (t1 - t0) / h > MAX_FRAMES:
            raise ScaraError(f"dense = {dense!r:.80} must be (t0, t1, h) with t0 <= t1 and at most {MAX_FRAMES} steps")
        extra = np.searchsorted(t, np.arange(t0, t1 + 0.5 * h, h) - 0.5 * dt)
        idx += [int(i) for i in extra if i < n]
    idx = np.unique(np.asarray(idx))
    if idx.size > MAX_FRAMES:
        raise ScaraError(f"these settings ask for {idx.size} frames, more than the limit of {MAX_FRAMES}")
    return idx


def play_controls(times, redraw: bool = False, duration: int = FRAME_MS, prefix: str = "t (s) = ") -> dict:
    """``updatemenus`` (Play/Pause buttons) and ``sliders`` (one step per frame, named ``"0"``, ``"1"``, ...)
    for a figure whose frames play at ``times`` (s); pass the result to ``update_layout``. ``redraw`` must be
    true for 3-D traces."""
    def opts(ms):
        return dict(frame=dict(duration=ms, redraw=redraw), transition=dict(duration=0), mode="immediate")
    buttons = [dict(label="▶ Play", method="animate", args=[None, dict(opts(duration), fromcurrent=True)]),
               dict(label="❚❚ Pause", method="animate", args=[[None], opts(0)])]
    steps = [dict(label=f"{t:.2f}", method="animate", args=[[str(i)], opts(0)]) for i, t in enumerate(times)]
    return dict(
        updatemenus=[dict(type="buttons", direction="left", showactive=False, x=0.0, xanchor="left", y=0.0,
                          yanchor="top", pad=dict(t=56, r=8), buttons=buttons, font=dict(size=12))],
        sliders=[dict(active=0, steps=steps, x=0.0, len=1.0, xanchor="left", y=0.0, yanchor="top",
                      pad=dict(t=96, b=0),
                      currentvalue=dict(prefix=prefix, font=dict(size=13, color=READOUT_COLOUR)),
                      ticklen=0, minorticklen=0, tickwidth=0, font=dict(size=1, color="rgba(0,0,0,0)"))],
    )


def _frames(data, trace_ids) -> list:
    """One frame per entry of ``data`` (a list of lists of :func:`_moved` traces), named by its position, as the
    dicts ``fig.frames`` takes: plotly checks each trace once there (a ``go.Frame`` of ``go.Scatter`` traces is
    checked three times over, most of an animation's build time)."""
    return [dict(data=d, traces=list(trace_ids), name=str(i)) for i, d in enumerate(data)]


def _moved(x, y, z=None) -> dict:
    """The coordinates a frame gives one of its moving traces (a 2-D scatter, or a 3-D one with ``z``)."""
    return dict(type="scatter", x=x, y=y) if z is None else dict(type="scatter3d", x=x, y=y, z=z)


def _arm_xy(q, p):
    pts = top_arm_points(q, p)
    return as_list(pts[:, 0]), as_list(pts[:, 1])


def _box(points, margin=0.05):
    points = np.asarray(points)
    lo, hi = points.min(axis=0) - margin, points.max(axis=0) + margin
    return as_list([lo[0], hi[0]], 3), as_list([lo[1], hi[1]], 3)


def _check_traj(traj):
    if not all(hasattr(traj, a) for a in ("t", "x", "joints")):
        raise ScaraError(f"traj must be a Trajectory (scara.reference_trajectory()); got {type(traj).__name__}")


def trajectory_animation(traj, p=None, fast: float = 0.1, rest: float = 1.0, height: int = 640) -> go.Figure:
    """Chapter 3: the arm seen from above (links as a line, the tool as a marker) following ``traj``, over the
    whole path (thin black) with a trail of the part covered; Play/Pause and a time slider (static page).

    Frames: :func:`frame_indices` (a frame every ``fast`` s while moving, every ``rest`` s at rest). The joint
    values are ``traj.joints()`` (closed-form inverse kinematics). Raises :class:`ScaraError` for bad arguments.
    """
    _check_traj(traj)
    p = ScaraParams.resolve(p)
    idx = frame_indices(traj.t, traj.x, fast, rest)
    q = traj.joints()
    k = decimate(traj, 1500)
    kt = decimate(traj, 150)
    arms = [_arm_xy(q[i], p) for i in idx]
    fig = go.Figure()
    fig.add_trace(go.Scatter(x=as_list(traj.x[k, 0]), y=as_list(traj.x[k, 1]), mode="lines", name="reference path",
                             line=dict(color=PALETTE["reference"], width=1), hoverinfo="skip"))
    fig.add_trace(go.Scatter(x=as_list(traj.x[:1, 0]), y=as_list(traj.x[:1, 1]), mode="lines", name="covered",
                             line=dict(color=PALETTE["inverse"], width=6), opacity=0.4, hoverinfo="skip"))
    fig.add_trace(top_view_arm(q[0], p))
    fig.add_trace(go.Scatter(x=as_list(traj.x[:1, 0]), y=as_list(traj.x[:1, 1]), mode="markers", name="tool",
                             marker=dict(color=PALETTE["transpose"], size=11, symbol="diamond"),
                             hovertemplate="(%{x:.3f}, %{y:.3f}) m<extra>tool</extra>"))
    data = []
    for i, (ax, ay) in zip(idx, arms):
        c = np.r_[kt[kt < i], i]
        data.append([_moved(as_list(traj.x[c, 0]), as_list(traj.x[c, 1])), _moved(ax, ay),
                     _moved(as_list(traj.x[i:i + 1, 0]), as_list(traj.x[i:i + 1, 1]))])
    fig.frames = _frames(data, [1, 2, 3])
    xr, yr = _box(np.vstack([traj.x[k, :2], [[0.0, 0.0]], *[np.c_[a[0], a[1]] for a in arms]]))
    top_axes(fig, p, xr=xr, yr=yr)
    finish_layout(fig, "The arm along the 70 s reference (top view)", height, bottom=_BOTTOM,
                  **play_controls(traj.t[idx]))
    return fig


def _magnification(err, target=0.05):
    """The largest of 1, 2, 5, 10, 20, ... that keeps the largest error ``err`` under ``target`` m on the
    page (at least 1)."""
    top = float(np.max(err)) if np.size(err) else 0.0
    if not np.isfinite(top) or top <= 0:
        return 1.0
    ratio = target / top
    if ratio <= 1:
        return 1.0
    k = math.floor(math.log10(ratio))
    mant = max(m for m in (1, 2, 5) if m * 10.0 ** k <= ratio * (1 + 1e-12))
    return float(mant * 10 ** k)


_SUP = str.maketrans("0123456789", "⁰¹²³⁴⁵⁶⁷⁸⁹")


def magnification_text(m: float) -> str:
    """``m`` (1, 2 or 5 times a power of ten) as text: ``"20"``, ``"10⁶"``, ``"5·10⁵"``."""
    if m < 1000:
        return f"{m:g}"
    k = int(math.floor(math.log10(m) + 1e-9))
    mant = round(m / 10 ** k)
    return ("" if mant == 1 else f"{mant}·") + "10" + str(k).translate(_SUP)


def _tracked_xy_error(r):
    """The x-y tracking error of a run (N, 2), its relaxed component (pseudo-inverse) set to zero."""
    e = np.array(r.e[:, :2], dtype=float)
    relaxed = (getattr(r, "gains", None) or {}).get("relaxed") if isinstance(getattr(r, "gains", None), dict) \
        else None
    if relaxed in ("x", "y"):
        e[:, "xy".index(relaxed)] = 0.0
    return e


def _check_runs(runs, what):
    runs = list(runs.values()) if isinstance(runs, dict) else list(runs) if isinstance(runs, (list, tuple)) else None
    if not runs or not all(hasattr(r, a) for r in runs for a in ("t", "q", "x", "e", "x_d")):
        raise ScaraError(f"runs must be a non-empty list (or dict) of {what} results")
    n = runs[0].t.size
    if any(r.t.size != n for r in runs):
        raise ScaraError(f"the {what} runs must share one time base")
    return runs


@dataclass(frozen=True)
class _RunPanels:
    """The page of a runs animation: its ``title``, ``cols`` top-view panels a row, and under them one full-width
    panel per entry of ``extra_titles``, drawn by ``add_extra(fig, first_row, frame_indices) -> (moving trace
    ids, per-frame traces)``; each top-view panel's title names the magnification after ``caption_word``."""

    title: str
    cols: int
    extra_titles: tuple
    add_extra: Callable
    caption_word: str = "error"


def _runs_animation(runs, p, panels: _RunPanels, *, fast: float, rest: float, height: int, dense=None) -> go.Figure:
    """The shared body of :func:`clik_animation` and :func:`control_animation`: one top-view panel per run
    (path, arm, magnified tool) over the full-width panels of ``panels``; frames by :func:`frame_indices` of the
    first run's ``x_d`` with ``fast``, ``rest`` and ``dense``."""
    p = ScaraParams.resolve(p)
    cols, extra_rows, caption_word = panels.cols, len(panels.extra_titles), panels.caption_word
    n = len(runs)
    rows_arm = -(-n // cols)
    r0 = runs[0]
    idx = frame_indices(r0.t, r0.x_d, fast, rest, dense)
    errs = [_tracked_xy_error(r) for r in runs]
    mags = [_magnification(np.linalg.norm(e, axis=1)) for e in errs]
    # three panels a row leave no room on a phone for the long legend names: the short ones head the panels
    head = run_label if cols < 3 else run_name
    titles = [f"{head(r)}<br>{caption_word} ×{magnification_text(m)}" for r, m in zip(runs, mags)]
    titles += [""] * (rows_arm * cols - n) + list(panels.extra_titles)
    specs = [[{} for _ in range(cols)] for _ in range(rows_arm)] + [[{"colspan": cols}] + [None] * (cols - 1)
                                                                   for _ in range(extra_rows)]
    arm_h = 0.62 / rows_arm if extra_rows else 1.0 / rows_arm
    heights = [arm_h] * rows_arm + [0.38 / extra_rows] * extra_rows if extra_rows else [arm_h] * rows_arm
    # room between the rows for a panel's two-line title above the tick labels of the panel over it
    fig = make_subplots(rows=rows_arm + extra_rows, cols=cols, specs=specs, subplot_titles=titles,
                        row_heights=heights, vertical_spacing=0.13, horizontal_spacing=0.08)
    k = thin(r0.t.size, 1200)
    moving, data = [], [[] for _ in idx]
    pts = [r0.x_d[k, :2], [[0.0, 0.0]]]
    for j, (r, e, m) in enumerate(zip(runs, errs, mags)):
        row, col = j // cols + 1, j % cols + 1
        colour = run_colour(r)
        fig.add_trace(go.Scatter(x=as_list(r.x_d[k, 0]), y=as_list(r.x_d[k, 1]), mode="lines", showlegend=False,
                                 name="reference path", line=dict(color=PALETTE["reference"], width=1),
                                 hoverinfo="skip"), row=row, col=col)
        fig.add_trace(top_view_arm(r.q[0], p, colour=colour, name=run_label(r), showlegend=False, width=4),
                      row=row, col=col)
        tool = r.x[:, :2] - (m - 1.0) * e  # x_d - m e on the tracked components
        fig.add_trace(go.Scatter(x=as_list(tool[:1, 0]), y=as_list(tool[:1, 1]), mode="markers", showlegend=False,
                                 name=f"tool, error ×{magnification_text(m)}",
                                 marker=dict(color=colour, size=10, symbol="diamond",
                                             line=dict(color="black", width=1)),
                                 hovertemplate="(%{x:.4f}, %{y:.4f}) m<extra>tool, error ×"
                                 + magnification_text(m) + "</extra>"),
                      row=row, col=col)
        moving += [len(fig.data) - 2, len(fig.data) - 1]
        arms = [_arm_xy(r.q[i], p) for i in idx]
        pts += [np.c_[a[0], a[1]] for a in arms[:: max(1, len(arms) // 60)]] + [tool[idx]]
        for d, i, (ax, ay) in zip(data, idx, arms):
            d += [_moved(ax, ay), _moved(as_list(tool[i:i + 1, 0]), as_list(tool[i:i + 1, 1]))]
    xr, yr = _box(np.vstack(pts))
    for j in range(n):
        row, col = j // cols + 1, j % cols + 1
        ax_id = "" if j == 0 else str(j + 1)
        # three ticks or so a panel: a phone gives each panel little more than 100 px
        fig.update_xaxes(range=xr, row=row, col=col, zeroline=False, constrain="domain", nticks=3,
                         tickfont_size=10)
        fig.update_yaxes(range=yr, row=row, col=col, zeroline=False, scaleanchor=f"x{ax_id}", scaleratio=1,
                         title_text="y (m)", title_standoff=2, nticks=4, tickfont_size=10)
    extra_moving, extra_data = panels.add_extra(fig, rows_arm + 1, idx)
    moving += extra_moving
    for d, ed in zip(data, extra_data):
        d += ed
    fig.frames = _frames(data, moving)
    finish_layout(fig, panels.title, height, subplot_titles=True, bottom=_BOTTOM, **play_controls(r0.t[idx]))
    fig.update_annotations(font_size=12)
    return fig


def _error_panel(fig, runs, row, idx, errs=None):
    """|e| of each run on a log axis (static, as an envelope) with a moving marker per run."""
    moving, data = [], [[] for _ in idx]
    for j, r in enumerate(runs):
        e = np.linalg.norm(_tracked_xy_error(r), axis=1) if errs is None else errs[j]
        e = np.maximum(e, 1e-12)
        tt, ee = envelope(r.t, e, 700)
        fig.add_trace(go.Scatter(x=_sig(tt), y=_sig(ee), mode="lines", name=run_label(r), legendgroup=run_label(r),
                                 line=dict(color=run_colour(r), width=1.5),
                                 hovertemplate="t = %{x:.2f} s, |e| = %{y:.3g} m<extra>" + run_label(r) + "</extra>"),
                      row=row, col=1)
        fig.add_trace(go.Scatter(x=[0.0], y=_sig(e[:1]), mode="markers", showlegend=False, name=run_label(r),
                                 marker=dict(color=run_colour(r), size=9, line=dict(color="black", width=1)),
                                 hoverinfo="skip"), row=row, col=1)
        moving.append(len(fig.data) - 1)
        for d, i in zip(data, idx):
            d.append(_moved(_sig(r.t[i:i + 1]), _sig(e[i:i + 1])))
    fig.update_yaxes(type="log", exponentformat="power", title_text="|e| (m)", row=row, col=1)
    return moving, data


def clik_animation(runs, p=None, fast: float = 0.1, rest: float = 1.0, height: int = 780) -> go.Figure:
    """Chapter 4: the CLIK runs ``runs`` (list of ``ClikResult``, e.g. the four methods) side by side, two panels
    a row, each the arm seen from above with its tool drawn at ``x_d - M e`` (the x-y tracking error magnified
    ``M`` times, a power of ten named in the panel's title, the relaxed component of a pseudo-inverse run left
    as it is), over a panel of ``|e|`` (log scale, without the relaxed component) with a moving marker per run.

    Frames: :func:`frame_indices` of the first run's ``x_d`` (every ``fast`` s while moving, ``rest`` s at
    rest). Raises :class:`ScaraError` for bad arguments.
    """
    runs = _check_runs(runs, "CLIK")

    def extra(fig, row, idx):
        return _error_panel(fig, runs, row, idx)

    panels = _RunPanels("CLIK methods on the reference path", 2, ("x-y tracking error |e|",), extra)
    fig = _runs_animation(runs, p, panels, fast=fast, rest=rest, height=height)
    fig.update_xaxes(title_text="t (s)", row=-(-len(runs) // 2) + 1, col=1)
    return fig


def control_animation(runs, true_mass: float | None = None, p=None, fast: float = 0.1, rest: float = 1.0,
                      dense=(0.0, 1.0, 0.02), height: int = 780) -> go.Figure:
    """Chapter 6: the closed-loop runs ``runs`` (list or dict of ``SimulationResult``) side by side, each the
    arm seen from above with its tool drawn at ``x_d - M e`` (x-y error magnified ``M`` times, a power of ten
    named in the panel title), over the position error ``|e|`` (log scale) and the payload estimate
    ``payload_estimate`` of the run that has one (the adaptive law), each with a moving marker; ``true_mass``
    (kg) draws the true payload as a dashed line.

    Frames: :func:`frame_indices` of the first run's ``x_d`` (every ``fast`` s while moving, ``rest`` s at
    rest), plus one every 0.02 s over the first second (``dense``), where the estimate converges. Raises
    :class:`ScaraError` for bad arguments.
    """
    runs = _check_runs(runs, "simulation")
    if true_mass is not None and (is_bool(true_mass) or not isinstance(true_mass, (int, float))
                                  or not math.isfinite(true_mass)):
        raise ScaraError(f"true_mass = {true_mass!r:.80} must be a mass in kg")
    est_runs = [r for r in runs if "payload_estimate" in (getattr(r, "signals", None) or {})]

    def extra(fig, row, idx):
        moving, data = _error_panel(fig, runs, row, idx,
                                    errs=[np.linalg.norm(r.e[:, :3], axis=1) for r in runs])
        # a title short enough for the panel's height; the errors span ten decades in a panel about 60 px tall,
        # where four labels 10^k (20 px each with their exponent) ran into each other: one every four decades
        fig.update_yaxes(title_text="|e| (m)", dtick=4, row=row, col=1)
        if est_runs:
            r = est_runs[0]
            m = np.asarray(r.payload_estimate, dtype=float)
            k = thin(r.t.size, 1500)
            k = np.unique(np.r_[k, np.arange(min(r.t.size, 3000))[::5]])  # the fast start in detail
            fig.add_trace(go.Scatter(x=_sig(r.t[k]), y=_sig(m[k]), mode="lines", name="payload estimate",
                                     showlegend=False,
                                     line=dict(color=run_colour(r), width=1.5),
                                     hovertemplate="t = %{x:.2f} s, m̂_L = %{y:.4f} kg<extra></extra>"),
                          row=row + 1, col=1)
            if true_mass is not None:
                fig.add_trace(go.Scatter(x=[0.0, _sig(r.t[-1:])[0]], y=[true_mass, true_mass], mode="lines",
                                         name=f"true {true_mass:g} kg", showlegend=False,
                                         line=dict(color=PALETTE["reference"], dash="dash", width=1),
                                         hoverinfo="skip"), row=row + 1, col=1)
            fig.add_trace(go.Scatter(x=[0.0], y=_sig(m[:1]), mode="markers", showlegend=False, hoverinfo="skip",
                                     marker=dict(color=run_colour(r), size=9, line=dict(color="black", width=1))),
                          row=row + 1, col=1)
            moving.append(len(fig.data) - 1)
            for d, i in zip(data, idx):
                d.append(_moved(_sig(r.t[i:i + 1]), _sig(m[i:i + 1])))
        fig.update_yaxes(title_text="m̂_L (kg)", row=row + 1, col=1)
        fig.update_xaxes(title_text="t (s)", row=row + 1, col=1)
        return moving, data

    panels = _RunPanels("The controllers carrying the unknown payload", len(runs),
                        ("position error |e|", "payload estimate (adaptive)"), extra)
    return _runs_animation(runs, p, panels, fast=fast, rest=rest, height=height, dense=dense)


def course_animation(traj, p=None, fast: float = 0.1, rest: float = 1.0, height: int = 640) -> go.Figure:
    """The introduction's course figure (:func:`~scara.plots.course.course_figure`: the 3-D path coloured by
    the manipulability, the arm and the trail of the part covered) with Play/Pause buttons and a time slider
    whose frames move the arm and the trail.

    Frames: :func:`frame_indices` of ``traj`` (every ``fast`` s while moving, ``rest`` s at rest); 3-D traces
    are redrawn at each frame. Raises :class:`ScaraError` for bad arguments.
    """
    from .kinematics import arm_geometry

    _check_traj(traj)
    p = ScaraParams.resolve(p)
    idx = frame_indices(traj.t, traj.x, fast, rest)
    fig = course_figure(traj, p, steps=61, height=height)  # 61 arms: the scene box holds the arm all along
    names = [t.name for t in fig.data]
    trail, arm = names.index("covered"), names.index("arm (Ch. 1, 4)")
    q = traj.joints()
    kt = decimate(traj, 150)
    data = []
    for i in idx:
        a = arm_geometry(q[i], p)["arm"]
        c = np.r_[kt[kt < i], i]
        tr = traj.x[c]
        data.append([_moved(as_list(tr[:, 0]), as_list(tr[:, 1]), as_list(tr[:, 2])),
                     _moved(as_list(a[:, 0]), as_list(a[:, 1]), as_list(a[:, 2]))])
    fig.frames = _frames(data, [trail, arm])
    fig.layout.title.text = "The course on one figure<br>the arm along the 70 s reference path"
    fig.layout.sliders = ()  # replaced, not merged step by step with the slider of course_figure
    fig.update_layout(margin_b=_BOTTOM, **play_controls(traj.t[idx], redraw=True))
    return fig
