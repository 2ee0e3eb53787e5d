"""Live panel of chapter 3 (trajectory planning): a waypoint editor. Jupyter only.

Pick a waypoint and move it with the x/y/z sliders, make it a via point or a stop, change a segment's
duration or a via point's anticipation: the path is re-planned with :func:`~scara.trajectory.plan_path` and
redrawn in place at once. An invalid or unreachable edit shows the planner's message and marks the figures
stale; the plan keeps its last valid state, so picking another waypoint or undoing the edit goes on from there.
"""
from __future__ import annotations

import ipywidgets as ipw
import numpy as np
import plotly.graph_objects as go

from ..errors import ScaraError
from ..plots.kinematics import top_view_arm
from ..plots.trajectory import profiles_figure, profiles_series, segment_shapes, top_view_figure, top_view_series
from ..trajectory import Waypoint, plan_path, reference_plan
from ._common import LABEL_STYLE, LivePanel, PanelView, table

__all__ = ["WaypointEditor", "waypoint_editor"]

_SELECTED = "#D55E00"
#: samples drawn per curve: enough for the eye, few enough for the browser to redraw at once
TOP_POINTS, PROFILE_POINTS = 600, 500


#: the arguments of :func:`~scara.trajectory.plan_path` a plan may hold
_PLAN_KEYS = ("waypoints", "durations", "blends", "arcs", "phi", "total", "dt", "p", "elbow", "check")


def _listed(value, name: str, what: str) -> list:
    """``value`` (a list, tuple or 1-D array) as a list, or :class:`ScaraError` naming it."""
    if isinstance(value, np.ndarray) and value.ndim >= 1:
        return list(value)
    if not isinstance(value, (list, tuple)):
        raise ScaraError(f"{name} must be a list of {what}, got {type(value).__name__} {value!r:.80}")
    return list(value)


class WaypointEditor:
    """The editor's state (``plan``: keyword arguments of :func:`plan_path`) and its :class:`LivePanel`.

    ``plan`` defaults to the reference scenario of chapter 3 with ``total=None`` (the series ends when the
    motion does, so a longer edit is never refused for overrunning 70 s); any valid plan of two waypoints or
    more opens. ``editor.trajectory`` is the last valid plan; ``editor.panel.last_error`` the message shown, or
    None. The sliders' ranges cover the plan's own values (positions within the arm's reach, durations and
    anticipations from 0.1 s), so loading a waypoint never clamps it.
    """

    def __init__(self, plan: dict | None = None, profiles: bool = True):
        if not isinstance(profiles, (bool, np.bool_)):
            raise ScaraError(f"profiles must be True or False, got {type(profiles).__name__} {profiles!r:.80}")
        if plan is not None and not isinstance(plan, dict):
            raise ScaraError(f"plan must be a dict of the arguments of plan_path (as reference_plan() returns), "
                             f"got {type(plan).__name__} {plan!r:.80}")
        plan = dict(reference_plan(), total=None) if plan is None else dict(plan)
        if "waypoints" not in plan or "durations" not in plan:
            raise ScaraError("a plan needs 'waypoints' and 'durations' (the arguments of plan_path)")
        unknown = sorted(set(plan) - set(_PLAN_KEYS))
        if unknown:
            raise ScaraError(f"plan has unknown keys {unknown}: plan_path takes {', '.join(_PLAN_KEYS)}")
        plan["waypoints"] = _listed(plan["waypoints"], "plan['waypoints']", "waypoints")
        plan["durations"] = _listed(plan["durations"], "plan['durations']", "durations (s)")
        wps = []
        for i, w in enumerate(plan["waypoints"]):
            try:
                wps.append(w if isinstance(w, Waypoint) else Waypoint(w))
            except ScaraError:
                raise
            except (TypeError, ValueError) as exc:
                raise ScaraError(f"waypoint {i} = {w!r} is not a waypoint: give (x, y, z) in m or a Waypoint") from exc
        plan["waypoints"] = [w if w.label else w.replace(label=f"p{i}") for i, w in enumerate(wps)]
        durations = []
        for j, d in enumerate(plan["durations"]):
            if isinstance(d, (bool, str, bytes)) or not isinstance(d, (int, float, np.integer, np.floating)):
                raise ScaraError(f"duration of segment {j} = {d!r} must be a number of seconds")
            durations.append(float(d))
        plan["durations"] = durations
        self.trajectory = plan_path(**plan)  # an invalid plan raises here, with the planner's message
        self.plan = plan
        self.profiles = profiles
        self._drawn = False  # after the first draw, only the figures' data, title and shapes are rebuilt
        wps = plan["waypoints"]
        labels = [w.label for w in wps]
        segs = [f"{labels[j]}->{labels[j + 1]}" for j in range(len(wps) - 1)]
        first = next((i for i, w in enumerate(wps) if w.via), 0)
        w0, seg0 = wps[first], min(first, len(segs) - 1)
        durations = plan["durations"]
        ants = [w.anticipation for w in wps if w.via]
        slide = dict(continuous_update=False, style=LABEL_STYLE, readout_format=".3f")
        reach = max(1.0, *(abs(v) for w in wps for v in w.position[:2]))
        controls = {
            "point": ipw.Dropdown(options=[(lab, i) for i, lab in enumerate(labels)], value=first,
                                  description="waypoint", style=LABEL_STYLE),
            "via": ipw.Checkbox(value=w0.via, description="via point (do not stop)", style=LABEL_STYLE),
            "x": ipw.FloatSlider(value=w0.position[0], min=-reach, max=reach, step=0.005, description="x (m)",
                                 **slide),
            "anticipation": ipw.FloatSlider(value=w0.anticipation or 1.0, min=0.1, max=max(5.0, *ants, 0.1),
                                            step=0.1, description="anticipation (s)", continuous_update=False,
                                            style=LABEL_STYLE),
            "y": ipw.FloatSlider(value=w0.position[1], min=-reach, max=reach, step=0.005, description="y (m)",
                                 **slide),
            "segment": ipw.Dropdown(options=[(s, j) for j, s in enumerate(segs)], value=seg0,
                                    description="segment", style=LABEL_STYLE),
            "z": ipw.FloatSlider(value=w0.position[2], min=min(0.0, *(w.position[2] for w in wps)),
                                 max=max(1.0, *(w.position[2] for w in wps)), step=0.005, description="z (m)",
                                 **slide),
            "duration": ipw.FloatSlider(value=durations[seg0], min=min(0.1, *durations),
                                        max=max(20.0, *durations), step=0.1, description="duration (s)",
                                        continuous_update=False, style=LABEL_STYLE),
        }
        self.panel = LivePanel(controls, self._compute, self._draw,
                               title="Waypoint editor: edit the path, watch it re-planned", react=self._react)

    # ------------------------------------------------------------------------------------------------------
    def _react(self, change):
        """A waypoint or segment picked: show its current values on the sliders (one redraw follows)."""
        c = self.panel.controls
        if change["owner"] is c["point"]:
            w = self.plan["waypoints"][change["new"]]
            c["x"].value, c["y"].value, c["z"].value = w.position
            c["via"].value = w.via
            if w.via:
                c["anticipation"].value = w.anticipation
        elif change["owner"] is c["segment"]:
            c["duration"].value = self.plan["durations"][change["new"]]

    def _compute(self, point, via, x, anticipation, y, segment, z, duration):
        """Apply the sliders to the picked waypoint and segment and re-plan; the plan changes only if the
        planner accepts the edit."""
        plan = dict(self.plan, waypoints=list(self.plan["waypoints"]), durations=list(self.plan["durations"]))
        w = plan["waypoints"][point]
        plan["waypoints"][point] = w.replace(position=(x, y, z), anticipation=anticipation if via else 0.0)
        plan["durations"][segment] = duration
        traj = plan_path(**plan)
        self.plan, self.trajectory = plan, traj
        return dict(traj=traj, point=point, summary=traj.summary())

    def _draw(self, s):
        traj, k = s["traj"], s["point"]
        label = traj.labels[k]
        title = f"The edited path seen from above (editing {label})"
        pos = traj.waypoints[k]
        marker = dict(x=[float(pos[0])], y=[float(pos[1])], name=f"editing {label}")
        if self._drawn:  # the same figures with new data: no layout to rebuild
            top = top_view_series(traj, points=TOP_POINTS)
            arm = top_view_arm(traj.q0, traj.params)
            data = [dict(x=arm.x, y=arm.y), dict(x=top["path"][0], y=top["path"][1]), top["stop"], top["via"], marker]
            figs = [dict(data=data, title=title)]
            if self.profiles:
                figs.append(dict(data=[dict(x=x, y=y) for x, y in profiles_series(traj, points=PROFILE_POINTS)],
                                 layout=dict(shapes=segment_shapes(traj))))
        else:
            top = top_view_figure(traj, points=TOP_POINTS, title=title, height=460)
            top.add_trace(go.Scatter(mode="markers", marker=dict(size=18, symbol="circle-open", color=_SELECTED,
                                                                 line=dict(width=3)), hoverinfo="skip", **marker))
            figs = [top]
            if self.profiles:
                figs.append(profiles_figure(traj, points=PROFILE_POINTS, height=620,
                                            title="Its position, velocity and acceleration (orange: via overlaps)"))
            self._drawn = True
        summ = s["summary"]
        corner = ", ".join(f"{name}: {1000 * v:.1f} mm" for name, v in summ["corner_distances"].items()) or "none"
        rows = [("motion ends at (s)", f"{summ['motion_end']:.1f}"),
                ("peak speed (cm/s)", f"{100 * summ['max_speed']:.2f}"),
                ("peak acceleration (cm/s²)", f"{100 * summ['max_acceleration']:.2f}"),
                ("min manipulability (m²)",
                 f"{summ['min_manipulability']:.4f} at {summ['min_manipulability_time']:.1f} s"),
                ("corner distances at the via points", corner)]
        notes = []
        if summ["min_manipulability"] < 0.01:
            notes.append(f"The path passes close to a singular configuration (w = {summ['min_manipulability']:.2g} m² "
                         f"at {summ['min_manipulability_time']:.1f} s): the joints must move fast there.")
        return PanelView(figs, table(rows), notes)

    def _ipython_display_(self):
        self.panel._ipython_display_()


def waypoint_editor(plan: dict | None = None, profiles: bool = True) -> WaypointEditor:
    """A live waypoint editor on ``plan`` (default: the reference scenario of chapter 3).

    Controls: the waypoint to edit and its x/y/z (m), via or stop and the anticipation (s), the segment to
    edit and its duration (s). Every change re-plans the path and redraws the top view (and, with
    ``profiles``, the time profiles) in place; an invalid edit shows the planner's message instead and marks
    the figures stale. Display the returned object as a cell's last expression.
    """
    return WaypointEditor(plan, profiles)
