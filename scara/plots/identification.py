"""Figures of the identification section of chapter 5: the exciting trajectory, the torques a model predicts
on another motion against the measured ones, and the identification error against the length of the record and
the noise level. Data in, figure out: the numbers come from :mod:`scara.identification`."""
from __future__ import annotations

import numpy as np
import plotly.graph_objects as go
from plotly.subplots import make_subplots

from ..errors import ScaraError, ShapeError, as_array, check_count
from ._common import DASHES, FIGURE_BUDGET, JOINT_COLOURS, JOINT_UNITS, MAX_POINTS, f32, thin
from .layout import finish_layout, stacked_axes

__all__ = ["excitation_figure", "validation_figure", "error_size_figure"]

_JOINT_LABELS = ("θ1 (rad)", "θ2 (rad)", "d3 (m)", "θ4 (rad)")


def _series(t, y, name):
    t = as_array(t, "t", (np.size(t),))
    y = as_array(y, name, (4,), allow_batch=True)
    if y.ndim != 2 or len(y) != len(t):
        raise ShapeError(f"{name} must have shape ({len(t)}, 4) to match t, got {y.shape}")
    return t, y


def excitation_figure(t, q, q_start=None, title: str = "The exciting trajectory, one period",
                      target: int = 1000, height: int = 560) -> go.Figure:
    """The four joint motions ``q`` (N, 4) of an exciting trajectory against ``t`` (N,), one panel per joint,
    and dotted the motion the optimisation started from (``q_start``, same shape) when given. ``target`` (2 to
    ``MAX_POINTS``) samples per curve."""
    target = check_count(target, "target", 2, MAX_POINTS, "samples per curve", FIGURE_BUDGET)
    t, q = _series(t, q, "q")
    idx = thin(len(t), target)
    fig = make_subplots(rows=4, cols=1, shared_xaxes=True, vertical_spacing=0.04)
    runs = [("optimised", q, "solid", 2.2)]
    if q_start is not None:
        runs.append(("start of the search", _series(t, q_start, "q_start")[1], "dot", 1.6))
    for name, y, dash, width in runs:
        for j in range(4):
            fig.add_scatter(x=f32(t[idx]), y=f32(y[idx, j]), mode="lines", name=name, legendgroup=name,
                            showlegend=j == 0, line=dict(color=JOINT_COLOURS[j] if dash == "solid" else "#555555",
                                                          dash=dash, width=width), row=j + 1, col=1)
    stacked_axes(fig, _JOINT_LABELS)
    return finish_layout(fig, title, height)


def validation_figure(t, measured, predicted, nominal=None, title: str = "Torques on another motion",
                      target: int = 1000, height: int = 560) -> go.Figure:
    """The measured torques ``measured`` (N, 4) of a validation motion against ``t`` (N,), with those the
    identified parameters predict (``predicted``, same shape) and, when given, those of the nominal model
    (``nominal``), one panel per joint (N m; N for joint 3). ``target`` (2 to ``MAX_POINTS``) samples per
    curve."""
    target = check_count(target, "target", 2, MAX_POINTS, "samples per curve", FIGURE_BUDGET)
    t, measured = _series(t, measured, "measured")
    curves = [("measured", measured, "#000000", "solid", 3.0), ("identified π̂", _series(t, predicted, "predicted")[1],
                                                                 "#D55E00", "dash", 2.0)]
    if nominal is not None:
        curves.append(("nominal π", _series(t, nominal, "nominal")[1], "#0072B2", "dot", 2.0))
    idx = thin(len(t), target)
    fig = make_subplots(rows=4, cols=1, shared_xaxes=True, vertical_spacing=0.04)
    for name, y, colour, dash, width in curves:
        for j in range(4):
            fig.add_scatter(x=f32(t[idx]), y=f32(y[idx, j]), mode="lines", name=name, legendgroup=name,
                            showlegend=j == 0, line=dict(color=colour, dash=dash, width=width), row=j + 1, col=1,
                            hovertemplate=f"t = %{{x:.2f}} s<br>τ{j + 1} = %{{y:.4g}} {JOINT_UNITS[j]}"
                                          f"<extra>{name}</extra>")
    stacked_axes(fig, tuple(f"τ{j + 1} ({u})" for j, u in enumerate(JOINT_UNITS)))
    return finish_layout(fig, title, height)


def error_size_figure(duration, errors: dict, theory: dict, title: str = "Identification error against data size",
                      height: int = 460) -> go.Figure:
    """The identification error against the length of the record, on log axes: for each noise level (the keys of
    ``errors``, e.g. ``"1 %"``) the measured errors (markers; ``errors[k]`` of the shape of ``duration`` (M,), s)
    and the theory's line (``theory[k]``, same shape), which falls as ``1 / sqrt(duration)``."""
    duration = as_array(duration, "duration", (np.size(duration),))
    if set(errors) != set(theory) or not errors:
        raise ScaraError(f"errors and theory must have the same noise levels, got {sorted(errors)} and "
                         f"{sorted(theory)}")
    if len(errors) > len(DASHES):
        raise ScaraError(f"{len(errors)} noise levels: at most {len(DASHES)} stay apart in greyscale")
    fig = go.Figure()
    for k, (level, err) in enumerate(errors.items()):
        err = as_array(err, f"errors[{level!r}]", duration.shape)
        th = as_array(theory[level], f"theory[{level!r}]", duration.shape)
        colour = JOINT_COLOURS[k]
        fig.add_scatter(x=f32(duration), y=f32(err), mode="markers", name=f"noise {level}",
                        marker=dict(color=colour, size=9, symbol=("circle", "square", "diamond", "cross")[k]),
                        hovertemplate="%{x:.0f} s of data<br>error %{y:.2e}<extra></extra>")
        fig.add_scatter(x=f32(duration), y=f32(th), mode="lines", name=f"theory {level}",
                        line=dict(color=colour, dash=DASHES[k], width=2),
                        hovertemplate="%{x:.0f} s of data<br>theory %{y:.2e}<extra></extra>")
    fig.update_xaxes(type="log", title_text="length of the record (s)")
    # labels at 1, 2 and 5 of each decade: the minor labels 2 to 9 of a one-decade axis run into each other
    fig.update_yaxes(type="log", exponentformat="power", dtick="D2", title_text="relative error (-)")
    return finish_layout(fig, title, height)

