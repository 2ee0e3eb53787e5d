"""Shared machinery for live panels: an output area that shows a figure or a clear message."""
from __future__ import annotations

import html

import ipywidgets as ipw
import plotly.graph_objects as go
from IPython.display import HTML, display

from ..errors import ScaraError

__all__ = ["LivePanel"]


class LivePanel:
    """Controls plus an output area; ``render()`` (a function of the control values returning a figure or a
    list of figures) is re-run on every change. A :class:`ScaraError` (or any ``ValueError``) is shown as a
    message in place of the plot."""

    def __init__(self, controls: dict, render, title: str = "", columns: int = 2):
        self.controls = controls
        self.render = render
        self.out = ipw.Output()
        self.message = ipw.HTML()
        for w in controls.values():
            w.observe(self._changed, names="value")
        boxes = list(controls.values())
        grid = ipw.GridBox(boxes, layout=ipw.Layout(grid_template_columns=f"repeat({columns}, minmax(0, 1fr))"))
        head = [ipw.HTML(f"<b>{html.escape(title)}</b>")] if title else []
        self.widget = ipw.VBox(head + [grid, self.message, self.out])
        self.last_error: str | None = None
        self.update()

    def values(self) -> dict:
        return {k: w.value for k, w in self.controls.items()}

    def _changed(self, _change):
        self.update()

    def update(self):
        try:
            figs = self.render(**self.values())
            self.last_error = None
        except (ScaraError, ValueError) as exc:
            self.last_error = str(exc)
            self.message.value = f'<div style="color:#B00020;padding:6px 0"><b>Cannot show this setting:</b> {html.escape(str(exc))}</div>'
            self.out.outputs = ()
            return
        self.message.value = ""
        if isinstance(figs, go.Figure):
            figs = [figs]
        # Fill the output area directly rather than capturing with ``with self.out:``: under nbclient (the
        # book build) the capture can wait on the kernel's own shell channel until the cell times out.
        self.out.outputs = ()
        for f in figs:
            self.out.append_display_data(f if isinstance(f, go.Figure) else HTML(str(f)))

    def _ipython_display_(self):
        display(self.widget)
