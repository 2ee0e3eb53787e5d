"""The page layout of the book's figures (``scara.plots.layout``) and the conventions the chapters share
(``scara.plots._common``): the legend-row estimate agrees with plotly's wrapping as measured in Chromium, the
title, legend and dropdown get their room, and each method or controller keeps one legend name, colour and
dash style in every chapter."""
from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import plotly.graph_objects as go
from plotly.subplots import make_subplots

from scara.plots._common import (
    CONTROLLER_DASHES, CONTROLLER_LABELS, METHOD_DASHES, METHOD_LABELS, PALETTE, as_list, envelope, f32, run_colour,
    run_dash, run_label, run_name, thin,
)
from scara.plots.layout import (
    PHONE_PLOT_WIDTH, _text_width, base_layout, finish_layout, legend_entries, legend_rows, stacked_axes,
    without_template,
)


def test_legend_rows_matches_plotly_wrapping():
    # legend entry widths (px, 12 px font) measured in Chromium on the built book: the estimate may be long
    # (reserving a little too much room) but never short by more than a pixel (which would let the legend
    # overlap the plot on a phone)
    measured = {"arm": 63.2, "θ2 = 60°": 87.9, "velocity ellipse": 120.2, "workspace boundary": 154.2,
                "σ1 (velocity)": 107.9, "stretched: w = 0, r = 1 m": 171.9, "φ": 50.5, "end effector": 105.7}
    for name, width in measured.items():
        assert -1.0 <= 44 + _text_width(name) - width <= 9.0, (name, 44 + _text_width(name), width)
    # entries fit on one row when their total width fits, else in equal columns as wide as the widest entry
    assert legend_rows(["arm", "x axes", "y axes"]) == 1
    assert legend_rows(["velocity ellipse (x 0.15)", "force ellipse (x 0.15)", "arm"]) == 3
    assert legend_rows(["σ1 (velocity)", "σ2 (velocity)", "1/σ1 (force)", "1/σ2 (force)", "θ2 = 60°"]) == 3
    assert legend_rows(["a" * 10] * 6, plot_width=700) == 1 and legend_rows([]) == 0
    assert 220 <= PHONE_PLOT_WIDTH <= 240  # measured: 227 to 232 px on a 360 px page


def test_finish_layout_reserves_room_for_title_and_legend():
    fig = go.Figure([go.Scatter(x=[0, 1], y=[0, 1], name=f"curve {k}") for k in range(4)])
    finish_layout(fig, "A title<br>on two lines", 500)
    rows = legend_rows(legend_entries(fig))
    assert rows >= 2  # four entries do not fit one row of a phone-width plot
    assert fig.layout.margin.t == 14 + 2 * 22 + 21 * rows + 8
    assert fig.layout.title.yref == "container" and fig.layout.legend.yref == "container"
    assert fig.layout.legend.y < fig.layout.title.y  # the legend sits under the title
    assert fig.layout.showlegend and fig.layout.height == 500
    # no legend: no room for it, and none shown
    bare = finish_layout(go.Figure([go.Scatter(x=[0], y=[0], showlegend=False)]), None, 400)
    assert bare.layout.showlegend is False and bare.layout.margin.t == 14 + 8 and bare.layout.title.text is None


def test_finish_layout_menu_shows_one_group_at_a_time():
    fig = go.Figure([go.Scatter(x=[0], y=[k], name=n) for k, n in enumerate(("a", "b", "c"))])
    finish_layout(fig, "ignored", 480, groups=[[0, 1], [2]],
                  menu=[("first", "Group one"), ("second", "Group two", {"yaxis.title.text": "y (m)"})])
    assert fig.layout.title.text == "Group one"  # the first group's title
    assert [t.visible for t in fig.data] == [True, True, False]
    (menu,) = fig.layout.updatemenus
    first, second = menu.buttons
    assert first.args[0]["visible"] == [True, True, False] and second.args[0]["visible"] == [False, False, True]
    assert second.args[1] == {"title.text": "Group two", "yaxis.title.text": "y (m)"}
    assert fig.layout.margin.t == 14 + 22 + 21 * 1 + 36 + 8  # one legend row, and the dropdown's room


def test_stacked_axes_titles_every_panel_and_the_shared_time_axis():
    fig = make_subplots(rows=3, cols=1, shared_xaxes=True)
    assert stacked_axes(fig, ("a (m)", "b (m/s)", "c (rad)"), log=(2,)) is fig
    assert [fig.layout[f"yaxis{k}" if k > 1 else "yaxis"].title.text for k in (1, 2, 3)] == ["a (m)", "b (m/s)",
                                                                                             "c (rad)"]
    assert fig.layout.yaxis2.type == "log" and fig.layout.yaxis2.exponentformat == "power"
    assert fig.layout.yaxis.type is None and fig.layout.yaxis3.type is None
    assert fig.layout.xaxis3.title.text == "t (s)" and fig.layout.xaxis.title.text is None


def test_legend_entries_leave_out_what_the_page_does_not_list():
    fig = go.Figure([go.Scatter(x=[0], y=[0], name="shown"), go.Scatter(x=[0], y=[0], name="off", showlegend=False),
                     go.Scatter(x=[0], y=[0], name="later", visible=False),
                     go.Scatter(x=[0], y=[0], name="labels", mode="text"), go.Heatmap(z=[[1]], name="map")])
    assert legend_entries(fig) == ["shown"]
    assert legend_entries(fig, visible_only=False) == ["shown", "later"]


def test_without_template_drops_the_template_inside_the_block_only():
    assert base_layout()["template"] == "plotly_white"
    with without_template():
        assert "template" not in base_layout("t", 300)
        assert go.Figure().layout.template.layout.to_plotly_json() == {}
    assert base_layout()["template"] == "plotly_white"
    assert go.Figure().layout.template.layout.to_plotly_json() != {}


def test_each_method_and_controller_keeps_its_name_colour_and_dash():
    clik_run = SimpleNamespace(method="pseudoinverse", gains={"relaxed": "y"})
    sim_run = SimpleNamespace(controller="adaptive")
    assert run_name(clik_run) == "pseudoinverse" and run_name(sim_run) == "adaptive"
    assert run_name(SimpleNamespace(controller="")) == "controller"
    assert run_label(clik_run) == "pseudo-inverse (y relaxed)" and run_label("pseudoinverse") == "pseudo-inverse"
    assert run_label(sim_run) == CONTROLLER_LABELS["adaptive"] and run_label("inverse") == METHOD_LABELS["inverse"]
    assert run_label("something new") == "something new"
    assert run_colour(sim_run) == PALETTE["adaptive"] and run_colour("unknown") == PALETTE["reference"]
    assert run_dash(clik_run) == METHOD_DASHES["pseudoinverse"] and run_dash(sim_run) == CONTROLLER_DASHES["adaptive"]
    assert run_dash("unknown") == "solid"
    # the two families share no key, so that one lookup serves both chapters
    assert not set(METHOD_LABELS) & set(CONTROLLER_LABELS)


def test_plot_data_converters():
    assert as_list([1.23456, np.nan, 2.0], 2) == [1.23, None, 2.0]
    assert as_list(np.array([[1.0, 2.0], [3.0, np.inf]])) == [1.0, 2.0, 3.0, None]
    a = f32([1.0, 2.5])
    assert a.dtype == np.float32 and a.tolist() == [1.0, 2.5]


def test_thin_keeps_both_ends_and_envelope_every_peak():
    assert thin(5, 10).tolist() == [0, 1, 2, 3, 4]
    idx = thin(10_001, 100)
    assert idx[0] == 0 and idx[-1] == 10_000 and len(idx) == 100 and np.all(np.diff(idx) > 0)
    t = np.arange(10_001) * 1e-3
    y = np.zeros_like(t)
    y[4321] = -3.0  # one spike, between thinned samples
    tt, yy = envelope(t, y, 100)
    assert yy.max() == 3.0 and yy.min() == 1e-12 and len(tt) == len(yy) <= 101

