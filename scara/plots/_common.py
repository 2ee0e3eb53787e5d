"""Shared figure conventions: the book renderer, one palette per method, base layout, slider steps."""
from __future__ import annotations

from contextlib import contextmanager

import plotly.graph_objects as go
import plotly.io as pio
from plotly.io._base_renderers import MimetypeRenderer

__all__ = [
    "PALETTE", "AXIS_COLOURS", "JOINT_COLOURS", "TEMPLATE", "without_template", "base_layout", "slider", "new_figure", "use_book_renderer", "publish",
]

# Okabe-Ito colours: distinguishable with the common colour-vision deficiencies and, with the dash styles
# below, in greyscale. One colour per method or signal, the same across the whole book.
PALETTE = {
    "reference": "#000000",
    "inverse": "#0072B2",
    "transpose": "#D55E00",
    "pseudoinverse": "#009E73",
    "second_order": "#CC79A7",
    "robust": "#E69F00",
    "adaptive": "#56B4E9",
    "operational": "#009E73",
    "operational_noint": "#D55E00",
    "pd_gravity": "#999999",
    "velocity": "#0072B2",
    "force": "#D55E00",
    "arm": "#4D4D4D",
}
#: colours of the x, y, z, phi components (and of joints 1..4)
AXIS_COLOURS = ("#0072B2", "#D55E00", "#009E73", "#CC79A7")
JOINT_COLOURS = AXIS_COLOURS
DASHES = ("solid", "dash", "dot", "dashdot")


class _BookHtmlRenderer(MimetypeRenderer):
    """Returns ``text/html`` that needs ``plotly.min.js`` already loaded by the page (offline book)."""

    def to_mimebundle(self, fig_dict):
        html = pio.to_html(fig_dict, include_plotlyjs=False, include_mathjax=False, full_html=False,
                           auto_play=False, validate=False, config={"displaylogo": False, "responsive": True})
        return {"text/html": html}


def use_book_renderer() -> None:
    """Register the ``scara_book`` renderer and make ``plotly_mimetype+scara_book`` the default.

    JupyterLab keeps its native plotly view (the JSON bundle); the static book uses the HTML bundle, whose
    ``plotly.min.js`` the book serves itself (see ``_ext/offline_assets.py``).
    """
    pio.renderers["scara_book"] = _BookHtmlRenderer()
    pio.renderers.default = "plotly_mimetype+scara_book"
    _plain_numpy_scalars()


def _plain_numpy_scalars() -> None:
    """Show numpy scalars as plain numbers (``22.5``, not ``np.float64(22.5)``) in IPython, so that numbers
    glued into the text with ``myst_nb.glue`` can be formatted (``{glue:text}`name:.3f```)."""
    try:
        from IPython import get_ipython
    except ImportError:  # pragma: no cover
        return
    ip = get_ipython()
    if ip is None:
        return
    import numpy as np

    fmt = ip.display_formatter.formatters["text/plain"]
    fmt.for_type(np.floating, lambda obj, pp, cycle: pp.text(repr(float(obj))))
    fmt.for_type(np.integer, lambda obj, pp, cycle: pp.text(repr(int(obj))))
    fmt.for_type(np.bool_, lambda obj, pp, cycle: pp.text(repr(bool(obj))))


#: the book's plotly template
TEMPLATE = "plotly_white"
_template_off = 0


@contextmanager
def without_template():
    """Build figures without the book's template inside this block.

    Applying a template costs about 13 ms per figure; a live panel sends its template once, with the figure it
    first shows, and builds every later figure of the same kind in this block (only what changes is sent).
    """
    global _template_off
    # plotly's own default template would be applied instead: switch it off for the block. The setter of
    # ``pio.templates.default`` validates the template (11 ms a call), so its stored value is swapped directly.
    has_default = hasattr(pio.templates, "_default")
    default = pio.templates._default if has_default else None
    _template_off += 1
    if has_default:
        pio.templates._default = None
    try:
        yield
    finally:
        _template_off -= 1
        if has_default and not _template_off:
            pio.templates._default = default


def base_layout(title: str | None = None, height: int = 420, **kw) -> dict:
    """The book's layout defaults: readable on a laptop and a phone-width page."""
    lay = dict(
        template=TEMPLATE,
        height=height,
        margin=dict(l=60, r=20, t=60 if title else 30, b=50),
        legend=dict(orientation="h", yanchor="bottom", y=1.02, xanchor="left", x=0),
        font=dict(size=13),
    )
    if title:
        lay["title"] = dict(text=title, x=0.0, xanchor="left")
    lay.update(kw)
    if _template_off:
        lay.pop("template", None)
    return lay


def new_figure(title: str | None = None, height: int = 420, **kw) -> go.Figure:
    """An empty figure with :func:`base_layout`."""
    return go.Figure(layout=base_layout(title, height, **kw))


def slider(steps: list[dict], prefix: str, active: int = 0, pad_top: int = 40) -> dict:
    """A plotly slider from a list of ``{"label": str, "method": ..., "args": [...]}`` steps."""
    return dict(
        active=active,
        currentvalue=dict(prefix=prefix, font=dict(size=13)),
        pad=dict(t=pad_top, b=10),
        steps=[dict(label=s["label"], method=s.get("method", "update"), args=s["args"]) for s in steps],
    )


class _FigureBundle:
    """Wraps a figure so that ``myst_nb.glue`` stores its mime bundle (a plotly figure displays itself
    through ``_ipython_display_``, which glue cannot capture)."""

    def __init__(self, fig: go.Figure):
        self.fig = fig

    def _repr_mimebundle_(self, include=None, exclude=None):
        return pio.renderers._build_mime_bundle(self.fig.to_dict(), renderers_string=pio.renderers.default)


def publish(fig: go.Figure, name: str) -> None:
    """Show ``fig`` under its cell and glue it as ``name`` for a numbered, captioned figure in the book.

    In the notebook the figure appears under the cell as usual (JupyterLab). In the book the cell carries
    the tag ``remove-output`` and a markdown cell places the figure with its caption and label::

        ```{glue:figure} fig-arm
        :name: fig-arm

        The arm at q = 0, with its DH frames.
        ```

    so that ``{numref}`fig-arm``` refers to it from any chapter.
    """
    from myst_nb import glue

    glue(name, _FigureBundle(fig), display=True)
