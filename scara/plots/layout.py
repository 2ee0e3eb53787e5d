"""Page layout of every figure of the book: the template and layout defaults, and :func:`finish_layout`, which
places a short title, the legend under it and the plot so that they never overlap, from a phone-width page to
a laptop screen. The room a legend needs is estimated here (:func:`legend_rows`) from the widths of its
entries' glyphs, as plotly wraps a horizontal legend."""
from __future__ import annotations

from contextlib import contextmanager

import plotly.graph_objects as go
import plotly.io as pio

__all__ = [
    "TEMPLATE", "PHONE_PLOT_WIDTH", "without_template", "base_layout", "legend_entries", "legend_rows",
    "finish_layout", "stacked_axes",
]

#: gaps (px) added between the axes and their tick labels. Where the first x tick and the lowest y tick both sit at
#: the plot's corner (two zeros, say), the y tick label reaches about 7.5 px below its tick (half its height at the
#: book's font size) and the x tick label starts a few px under the axis and about 3.6 px left of the corner (half
#: a "0"), while the y tick labels end about 1 px left of the axis: their boxes overlapped by about 2.6 px each way.
#: Setting every x tick label a little further down and every y tick label a little further left parts them,
#: whatever the figure (plotly takes the room from the plot area, within the same margins).
X_TICK_STANDOFF = 4
Y_TICK_STANDOFF = 4
_template = go.layout.Template(pio.templates["plotly_white"])
_template.layout.xaxis.ticklabelstandoff = X_TICK_STANDOFF
_template.layout.yaxis.ticklabelstandoff = Y_TICK_STANDOFF
pio.templates["scara"] = _template
#: the book's plotly template: plotly's ``plotly_white``, its tick labels set off from the axes as above
TEMPLATE = "scara"
_template_off = 0

#: plot-area width (px) left on a 360-px phone page between the axis margins (227 to 232 px measured in the built
#: book); legends are sized for it
PHONE_PLOT_WIDTH = 230
_TITLE_SIZE = 15
_LEGEND_SIZE = 12
#: room (px) for a dropdown between the legend and the plot
_MENU_PX = 36


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


def legend_entries(fig: go.Figure, visible_only: bool = True) -> list[str]:
    """Names the legend of ``fig`` lists (traces with a name whose ``showlegend`` is not False; heat maps and
    text-only traces only when asked). With ``visible_only`` (the default), traces hidden at first
    (``visible=False``, shown later by a slider step or a dropdown) are left out: the legend as the page opens."""
    names = []
    for t in fig.data:
        if not t.name or t.showlegend is False or (visible_only and t.visible is False):
            continue
        if t.type in ("heatmap", "contour", "surface") and t.showlegend is not True:
            continue
        if getattr(t, "mode", None) == "text" and t.showlegend is not True:
            continue
        names.append(t.name)
    return names


def _text_width(text: str, font_size: float = _LEGEND_SIZE) -> float:
    """Width (px) of ``text`` in plotly's default sans-serif font, from widths measured in Chromium at 12 px
    (an estimate that is never short by more than a pixel and long by at most 9 px on the book's legends)."""
    w = 0.0
    for ch in text:
        if ch in "mwMW":
            w += 9.4
        elif ch in "ijlI|.,:;!'":
            w += 3.2
        elif ch in "frt()[]- ":
            w += 4.2
        elif ch.isupper() or ch.isdigit():
            w += 7.0
        else:
            w += 6.4
    return w * font_size / 12


def legend_rows(names, plot_width: float = PHONE_PLOT_WIDTH, font_size: float = _LEGEND_SIZE) -> int:
    """Rows a horizontal plotly legend with entries ``names`` takes in a plot area ``plot_width`` px wide.

    Plotly packs the entries in one row when they fit, else in equal columns as wide as the widest entry
    (seen in Chromium); an entry is 44 px of symbol and padding plus its text."""
    if not names:
        return 0
    widths = [44 + _text_width(n, font_size) for n in names]
    if sum(widths) <= plot_width:
        return 1
    per_row = max(1, int(plot_width // max(widths)))
    return -(-len(names) // per_row)


def finish_layout(fig: go.Figure, title: str | None, height: int, subplot_titles: bool = False,
                  groups: list | None = None, menu: list | None = None, bottom: int | None = None,
                  **kw) -> go.Figure:
    """Apply the book's layout to a finished ``fig``: a short title (lines split with ``<br>``) at the top, the
    legend under it, and room reserved for the legend as it wraps on a phone-width page, so that neither the
    title, the legend nor the plot overlap at any width. Returns ``fig``.

    ``groups`` (trace indices per group) counts the legend rows on the traces one group shows; with ``menu``
    (a list of ``(label, title)`` or ``(label, title, relayout)``, one per group) a dropdown between the legend
    and the plot shows one group at a time (plotly ``updatemenus``: it works on a static page). ``bottom`` sets
    the bottom margin (px); ``kw`` goes to :func:`base_layout`.
    """
    if groups:
        rows = max(legend_rows([fig.data[k].name for k in g
                                if fig.data[k].name and fig.data[k].showlegend is not False]) for g in groups)
    else:
        rows = legend_rows(legend_entries(fig))
    if menu:
        title = menu[0][1]
    lines = 0 if not title else title.count("<br>") + 1
    title_px = 22 * lines
    top = 14 + title_px + 21 * rows + (_MENU_PX if menu else 0) + (26 if subplot_titles else 8)
    lay = base_layout(None, height, **kw)
    if title:
        # plotly anchors a title of several lines about 11 px too high, whatever their number (measured in
        # Chromium): lower it by that much so that the first line is not cut off at the top of the figure
        lay["title"] = dict(text=title, x=0.0, xanchor="left", y=1.0 - (10 if lines == 1 else 21) / height,
                            yanchor="top", yref="container", font=dict(size=_TITLE_SIZE), pad=dict(l=8))
    lay["legend"] = dict(orientation="h", xanchor="left", x=0.0, yref="container", yanchor="top",
                         y=1.0 - (12 + title_px) / height, font=dict(size=_LEGEND_SIZE), tracegroupgap=0)
    lay["margin"] = dict(lay["margin"], t=top) if bottom is None else dict(lay["margin"], t=top, b=bottom)
    lay["showlegend"] = rows > 0
    fig.update_layout(**lay)
    if menu:
        n = len(fig.data)
        buttons = []
        for group, entry in zip(groups, menu):
            label, head, extra = (tuple(entry) + ({},))[:3]
            vis = [k in group for k in range(n)]
            buttons.append(dict(label=label, method="update", args=[{"visible": vis}, {"title.text": head, **extra}]))
        for k in range(n):
            fig.data[k].visible = k in groups[0]
        plot_px = height - top - lay["margin"]["b"]
        fig.update_layout(updatemenus=[dict(buttons=buttons, direction="down", x=1.0, xanchor="right",
                                            y=1.0 + 6 / plot_px, yanchor="bottom", showactive=True, active=0,
                                            pad=dict(t=0, b=0), font=dict(size=12))])
    return fig


def stacked_axes(fig: go.Figure, y_titles, x_title: str = "t (s)", log=()) -> go.Figure:
    """Axis titles of panels stacked in one column over a shared x axis: ``y_titles[k]`` on row ``k + 1``, the
    rows listed in ``log`` (numbered from 1) on log axes labelled in powers of ten, ``x_title`` under the last
    panel. Returns ``fig``."""
    for row, text in enumerate(y_titles, start=1):
        scale = dict(type="log", exponentformat="power") if row in log else {}
        fig.update_yaxes(title_text=text, row=row, col=1, **scale)
    fig.update_xaxes(title_text=x_title, row=len(y_titles), col=1)
    return fig
