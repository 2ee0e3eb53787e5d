"""The book's reading rules for a figure (figures a reader can use), shared by the figure tests of every
chapter: a height that fits a laptop screen, titles short enough for a phone-width page, a legend that names
what is drawn with room reserved for it as it wraps, and an axis title with a unit on every axis in use."""
from __future__ import annotations

import re

from scara.plots.layout import legend_entries, legend_rows

_UNIT = re.compile(r"\(.+\)")


def title_lines(title) -> list[str]:
    """The lines of a plotly title as a reader sees them (tags removed)."""
    return [re.sub(r"<[^>]+>", "", ln) for ln in (title or "").split("<br>")]


def _titles(fig) -> list[str]:
    """The figure's title and every title a slider step or dropdown entry swaps in."""
    lay = fig.layout
    out = [lay.title.text]
    controls = [s for sl in (lay.sliders or []) for s in sl.steps] + \
               [b for m in (lay.updatemenus or []) for b in m.buttons]
    for c in controls:
        args = list(c.args or [])
        for a in args:
            if isinstance(a, dict) and "title.text" in a:
                out.append(a["title.text"])
    return out


def check_reads_on_a_laptop_and_a_phone(name: str, fig, max_height: int = 560, legend: bool = True) -> None:
    """``max_height``: the tallest the figure may be (px; stacked panels of one time axis may take more than the
    default); ``legend=False`` for a figure whose axis labels name what is drawn (a bar chart)."""
    lay = fig.layout
    assert 380 <= lay.height <= max_height, (name, lay.height)
    assert lay.width is None, name  # the width follows the page
    for t in _titles(fig):
        # about 45 characters of the 15 px title font fit a 360 px phone page
        assert all(len(ln) <= 45 for ln in title_lines(t)), (name, t)
    names = legend_entries(fig, visible_only=False)
    if not legend:
        assert not names or lay.showlegend is False, name
        return
    assert names, f"{name}: no legend"
    # a dropdown or a slider that toggles visibility shows one group of traces at a time: count the legend of
    # each group it can show
    controls = [b for m in (lay.updatemenus or []) for b in m.buttons] + \
               [s for sl in (lay.sliders or []) for s in sl.steps]
    groups = [[n for n, v in zip([t.name for t in fig.data], c.args[0]["visible"]) if v and n in names]
              for c in controls if c.args and isinstance(c.args[0], dict) and "visible" in c.args[0]] or [names]
    rows = max(legend_rows(g) for g in groups)
    assert rows <= 4, (name, rows, groups)
    # room is reserved above the plot for the title and the legend as it wraps at phone width
    n_title = len(title_lines(lay.title.text)) if lay.title.text else 0
    assert lay.margin.t >= 14 + 22 * n_title + 21 * rows, (name, lay.margin.t, n_title, rows)
    # ... and no more than that: the plot itself keeps at least half the figure's height
    bottom = lay.margin.b if lay.margin.b is not None else 80
    assert lay.height - lay.margin.t - bottom >= 0.5 * lay.height, (name, lay.height, lay.margin.t, bottom)
    assert lay.legend.yref == "container" and lay.title.yref in (None, "container"), name


def check_axis_titles_with_units(name: str, fig) -> None:
    lay = fig.layout
    if lay.scene.xaxis.title.text:  # 3-D
        for ax in (lay.scene.xaxis, lay.scene.yaxis, lay.scene.zaxis):
            assert _UNIT.search(ax.title.text or ""), (name, ax.title.text)
        return
    # categorical axes (bars over named joints or implementations) have no unit
    planar = [t for t in fig.data if t.type not in ("scatter3d",)]
    categorical_x = {t.xaxis or "x" for t in planar if t.x is not None and len(t.x) and isinstance(t.x[0], str)}
    used_y = {t.yaxis or "y" for t in planar}
    used_x = {t.xaxis or "x" for t in planar} - categorical_x
    for key in used_y:
        ax = lay["yaxis" + key[1:]]
        assert _UNIT.search(ax.title.text or ""), (name, key, ax.title.text)
    # shared x axes carry their title on the bottom plot only: at least one titled x axis per figure, and every
    # titled one names its unit
    titled = [lay["xaxis" + k[1:]].title.text for k in used_x if lay["xaxis" + k[1:]].title.text]
    assert all(_UNIT.search(t) for t in titled) and (titled or not used_x), (name, titled)
