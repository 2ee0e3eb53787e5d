"""The figure of chapter 7's live interaction panel (:func:`scara.widgets.interaction_panel`), drawn from the
outputs of its page program (:func:`scara.programs.interaction.interaction_program`): every property that changes
with the settings is a binding (:data:`PRESS_TRACES`, :data:`PRESS_TITLE`), so the Jupyter panel and the book's
page set the same properties to the same numbers.
"""
from __future__ import annotations

import plotly.graph_objects as go
from plotly.subplots import make_subplots

from ._common import AXIS_COLOURS, PALETTE
from .control import _value
from .layout import finish_layout, stacked_axes
from .panels import Flag, Text

__all__ = ["PRESS_ROLES", "PRESS_TRACES", "PRESS_TITLE", "PRESS_ROWS", "press_build", "press_bindings"]

#: the roles of :func:`press_build`'s traces, in order: the normal force ``-h_z`` and the steady force the
#: formulas predict, the tool's height above the surface and its set point
PRESS_ROLES = ("force", "formula", "z", "z_d")
#: the bindings of the traces to the program's outputs
PRESS_TRACES = {
    "force": {"x": "t", "y": "force"},
    "formula": {"x": ("t_start", "duration"), "y": ("formula", "formula")},
    "z": {"x": "t", "y": "z"},
    "z_d": {"x": "t", "y": "z_d"},
}
#: the title: the run's figures
PRESS_TITLE = Text("{law}: final −h_z {final_force:.4g} N (formula {formula:.4g} N, error {force_error:+.3g} N)"
                   "<br>peak {peak_force:.4g} N, first touch at {first_touch:.3f} s, {contact_losses:.0f} "
                   "loss(es) of contact")
#: the summary's rows under the figure
PRESS_ROWS = (
    ("steady force −h_z (N)", Text("{final_force:.5g}")),
    ("formula (N)", Text("{formula:.5g}")),
    ("error (N)", Text("{force_error:+.3g}")),
    ("peak force (N)", Text("{peak_force:.4g}")),
    ("first touch (s)", Text("{first_touch:.3f}")),
    ("losses of contact (bounces)", Text("{contact_losses:.0f}")),
    ("set point below the surface (mm)", Text("{target_mm:.4g}")),
    ("spectral radius along z, in contact / free", Text("{radius:.5f} / {radius_free:.5f}")),
)
#: a note when the tool bounced
PRESS_NOTES = ((Flag("bounced"), Text("The tool bounced: it lost contact {contact_losses:.0f} time(s) after the "
                                      "first touch.")),)


def press_build(values, height: int = 560) -> go.Figure:
    """The panel's figure for the program's ``values`` (outputs by field, with the settings): the normal force
    ``-h_z`` (N) against the steady force the formulas predict, and the tool's height above the surface (mm)
    against its set point, over the run (s)."""
    fig = make_subplots(rows=2, cols=1, shared_xaxes=True, vertical_spacing=0.08)
    styles = {"force": ("−h_z (N)", PALETTE["reference"], None, 1),
              "formula": ("formula (N)", AXIS_COLOURS[1], "dash", 1),
              "z": ("p_z − height (mm)", AXIS_COLOURS[0], None, 2),
              "z_d": ("set point (mm)", AXIS_COLOURS[2], "dot", 2)}
    for role in PRESS_ROLES:
        name, colour, dash, row = styles[role]
        props = {prop: [_value(x, values) for x in b] if isinstance(b, tuple) else _value(b, values)
                 for prop, b in PRESS_TRACES[role].items()}
        fig.add_trace(go.Scatter(mode="lines", name=name, line=dict(color=colour, width=1.6, dash=dash), **props),
                      row=row, col=1)
    stacked_axes(fig, ("−h_z (N)", "p_z − surface (mm)"))
    finish_layout(fig, PRESS_TITLE.format(values), height)
    return fig


def press_bindings() -> dict:
    """The bindings of the panel's figure ``"press"`` for its :class:`~scara.plots.panels.PageProgram`."""
    return dict(traces={"press": PRESS_TRACES}, titles={"press": PRESS_TITLE}, rows=PRESS_ROWS, notes=PRESS_NOTES)
