"""Live panel of chapter 3 (trajectory planning): a waypoint editor. Jupyter only.

Pick a waypoint and move it with the x/y/z sliders, make it a via point or a stop, change a segment's
duration or a via point's anticipation: the path is re-planned with :func:`~scara.trajectory.plan_path` and
redrawn at once. An invalid or unreachable edit shows the planner's message in place of the plot.
"""
from __future__ import annotations

import html

import ipywidgets as ipw

from ..trajectory import Waypoint, plan_path, reference_plan
from ..plots.trajectory import profiles_figure, top_view_figure
from ._common import LivePanel

__all__ = ["WaypointEditor", "waypoint_editor"]

_STYLE = {"description_width": "initial"}


class WaypointEditor:
    """The editor's state (``plan``: keyword arguments of :func:`plan_path`) and its :class:`LivePanel`.

    ``plan`` defaults to the reference scenario with ``total=None`` (the series ends when the motion does, so
    a longer edit is never refused for overrunning 70 s). ``editor.trajectory`` is the last valid plan;
    ``editor.panel.last_error`` the last message shown, or None.
    """

    def __init__(self, plan: dict | None = None, profiles: bool = True):
        self.plan = dict(reference_plan(), total=None) if plan is None else dict(plan)
        self.plan["waypoints"] = [w if isinstance(w, Waypoint) else Waypoint(w, label=f"p{i}")
                                  for i, w in enumerate(self.plan["waypoints"])]
        self.plan["waypoints"] = [w if w.label else w.replace(label=f"p{i}") for i, w in enumerate(self.plan["waypoints"])]
        self.plan["durations"] = list(self.plan["durations"])
        self.profiles = profiles
        self.trajectory = None
        wps = self.plan["waypoints"]
        labels = [w.label for w in wps]
        segs = [f"{labels[j]}->{labels[j + 1]}" for j in range(len(wps) - 1)]
        first_via = next((i for i, w in enumerate(wps) if w.via), 1)
        w0 = wps[first_via]
        slide = dict(continuous_update=False, style=_STYLE, readout_format=".3f")
        controls = {
            "point": ipw.Dropdown(options=[(lab, i) for i, lab in enumerate(labels)], value=first_via,
                                  description="waypoint", style=_STYLE),
            "via": ipw.Checkbox(value=w0.via, description="via point (do not stop)", style=_STYLE),
            "x": ipw.FloatSlider(value=w0.position[0], min=-1.0, max=1.0, step=0.005, description="x (m)", **slide),
            "anticipation": ipw.FloatSlider(value=w0.anticipation or 1.0, min=0.1, max=5.0, step=0.1,
                                            description="anticipation (s)", continuous_update=False, style=_STYLE),
            "y": ipw.FloatSlider(value=w0.position[1], min=-1.0, max=1.0, step=0.005, description="y (m)", **slide),
            "segment": ipw.Dropdown(options=[(s, j) for j, s in enumerate(segs)], value=first_via,
                                    description="segment", style=_STYLE),
            "z": ipw.FloatSlider(value=w0.position[2], min=0.0, max=1.0, step=0.005, description="z (m)", **slide),
            "duration": ipw.FloatSlider(value=self.plan["durations"][first_via], min=0.5, max=20.0, step=0.1,
                                        description="duration (s)", continuous_update=False, style=_STYLE),
        }
        self._loaded = (first_via, first_via)
        self._loading = False
        self._last = None
        self.panel = LivePanel(controls, self._render, title="Waypoint editor: edit the path, watch it re-planned")

    # the panel calls this on every change
    def _render(self, point, via, x, anticipation, y, segment, z, duration):
        if self._loading:  # widgets being set to the newly picked waypoint's values: nothing changed yet
            if self._last is None:
                raise ValueError("loading")
            return self._last
        if (point, segment) != self._loaded:
            self._load(point, segment)
        else:
            w = self.plan["waypoints"][point]
            self.plan["waypoints"][point] = w.replace(position=(x, y, z), anticipation=anticipation if via else 0.0)
            self.plan["durations"][segment] = duration
        traj = plan_path(**self.plan)
        self.trajectory = traj
        s = traj.summary()
        corner = ", ".join(f"{k}: {1000 * v:.1f} mm" for k, v in s["corner_distances"].items()) or "none"
        info = (f"<div style='font-family:monospace'>motion ends at {s['motion_end']:.1f} s · peak speed "
                f"{100 * s['max_speed']:.2f} cm/s · peak acceleration {100 * s['max_acceleration']:.2f} cm/s² · "
                f"min manipulability {s['min_manipulability']:.4f} m² at {s['min_manipulability_time']:.1f} s<br>"
                f"corner distances at the via points: {html.escape(corner)}</div>")
        figs = [top_view_figure(traj, points=1200, title="The edited path seen from above", height=460)]
        if self.profiles:
            figs.append(profiles_figure(traj, points=1000, height=620,
                                        title="Its position, velocity and acceleration (orange: via overlaps)"))
        self._last = figs + [info]
        return self._last

    def _load(self, point, segment):
        """Show the picked waypoint's and segment's current values on the sliders."""
        c = self.panel.controls if hasattr(self, "panel") else None
        w = self.plan["waypoints"][point]
        self._loading = True
        try:
            if c is not None:
                c["x"].value, c["y"].value, c["z"].value = w.position
                c["via"].value = w.via
                if w.via:
                    c["anticipation"].value = w.anticipation
                c["duration"].value = self.plan["durations"][segment]
        finally:
            self._loading = False
        self._loaded = (point, segment)

    def _ipython_display_(self):
        self.panel._ipython_display_()


def waypoint_editor(plan: dict | None = None, profiles: bool = True) -> WaypointEditor:
    """A live waypoint editor on ``plan`` (default: the reference scenario of SPEC section 4).

    Controls: the waypoint to edit and its x/y/z (m), via or stop and the anticipation (s), the segment to
    edit and its duration (s). Every change re-plans the path and redraws the top view (and, with
    ``profiles``, the time profiles); an invalid edit shows the planner's message instead. Display the
    returned object as a cell's last expression.
    """
    return WaypointEditor(plan, profiles)
