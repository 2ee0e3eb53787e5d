"""The page layout of the book's figures (``scara.plots.layout``) and the conventions the chapters share
(``scara.plots._common``): the legend-row estimate agrees with plotly's wrapping as measured in Chromium, the
title, legend and dropdown get their room, and each method or controller keeps one legend name, colour and
dash style in every chapter. Then every figure of the book, built as the chapters build them, against the book's
reading rules (``_figure_rules``: a height for a laptop and a phone, short titles, a legend with room reserved
for it as it wraps, an axis title with a unit on every axis in use, greyscale-safe styles), every state of the
slider and dropdown figures with its title clear of the legend (in Chromium at a phone's and a laptop's width),
and the page limits every slider figure shares."""
from __future__ import annotations

import math
import tempfile
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import plotly.graph_objects as go
import plotly.io as pio
import pytest
from plotly.offline import get_plotlyjs
from plotly.subplots import make_subplots

import scara
from scara import plan_path, plots, reference_plan, reference_trajectory
from scara.plots import (anticipation_slider_figure, arm_figure, corner_figure, course_figure, determinant_figure,
                         duality_figure, ellipse_slider_figure, inverse_kinematics_figure, joint_profiles_figure,
                         joint_slider_figure, manipulability_map_figure, path_figure, profiles_figure,
                         reference_ellipses_figure, timing_law_figure, top_view_figure, workspace_ellipses_figure)
from scara.plots._common import (
    CONTROLLER_DASHES, CONTROLLER_LABELS, METHOD_DASHES, METHOD_LABELS, PALETTE, as_list, envelope, f32, run_colour,
    run_dash, run_label, run_name, thin,
)
from scara.plots.clik import gain_steps_figure
from scara.plots.kinematics import inverse_kinematics_slider_figure
from scara.plots.layout import (
    PHONE_PLOT_WIDTH, TEMPLATE, _text_width, base_layout, finish_layout, legend_entries, legend_rows, stacked_axes,
    without_template,
)
from scara.plots.manipulability import base_turn_figure

from _figure_rules import check_axis_titles_with_units, check_reads_on_a_laptop_and_a_phone, title_lines
import _plots_shared
from _plots_shared import Q, titles_by_state


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
    assert base_layout()["template"] == TEMPLATE
    with without_template():
        assert "template" not in base_layout("t", 300)
        assert go.Figure().layout.template.layout.to_plotly_json() == {}
    assert base_layout()["template"] == TEMPLATE
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


# ----------------------------------------------------------------- every figure of chapters 1 to 3: the reading rules
def _arm_and_path_figures():
    tr = reference_trajectory()
    plan = reference_plan()
    plan["waypoints"][4] = plan["waypoints"][4].replace(anticipation=0.0)
    stop = plan_path(**plan)
    return {
        "arm": arm_figure(Q), "joint_slider": joint_slider_figure(), "ik": inverse_kinematics_figure([0.18, 0.2, 0.5, 0]),
        "ik_reach": inverse_kinematics_slider_figure([0.5, 0.0, 0.5, 0.0], [0.5, 0.9, 1.0, 1.01]),
        "determinant": determinant_figure(), "reference": reference_ellipses_figure(),
        "workspace": workspace_ellipses_figure(), "map": manipulability_map_figure(n=41),
        "duality": duality_figure([0, math.pi / 3, 0.5, 0]), "sweep": ellipse_slider_figure(),
        "timing": timing_law_figure(tr.laws[1]), "path": path_figure(tr), "top": top_view_figure(tr),
        "profiles": profiles_figure(tr), "corner": corner_figure(tr, stop, 4),
        "anticipation": anticipation_slider_figure(reference_plan(), 4), "joints": joint_profiles_figure(tr),
        "course": course_figure(tr),
    }


@pytest.fixture(scope="module")
def arm_and_path_figures():
    """The figures of the arm, the ellipses, the paths and the course, built as chapters 1 to 3 build them."""
    return _arm_and_path_figures()


def test_every_arm_and_path_figure_reads_on_a_laptop_and_a_phone(arm_and_path_figures):
    for name, fig in arm_and_path_figures.items():
        check_reads_on_a_laptop_and_a_phone(name, fig)


def test_every_arm_and_path_figure_axis_has_a_title_with_a_unit(arm_and_path_figures):
    for name, fig in arm_and_path_figures.items():
        check_axis_titles_with_units(name, fig)


def test_arm_and_path_figure_styles_survive_greyscale(arm_and_path_figures):
    def dash(t):
        return t.line.dash or "solid"

    # velocity ellipses solid, force ellipses dashed, wherever they are drawn
    for name in ("reference", "sweep"):
        by = {t.name: t for t in arm_and_path_figures[name].data}
        assert dash(by["velocity ellipse"]) == "solid" and dash(by["force ellipse"]) == "dash", name
    assert {dash(t) for t in arm_and_path_figures["duality"].data[:4]} == {"solid", "dash", "dot", "dashdot"}
    # the two elbows, the x/y/z triads, the components of the profiles and the joints differ by dash too
    elbows = [t for t in arm_and_path_figures["ik"].data if t.name.startswith("elbow")]
    assert dash(elbows[0]) != dash(elbows[1])
    triads = [t for t in arm_and_path_figures["arm"].data if t.name.endswith("axes")]
    assert len({dash(t) for t in triads}) == 3
    comps = [t for t in arm_and_path_figures["profiles"].data
             if t.name in ("p_x", "p_y", "p_z", "φ") and t.showlegend is not False]
    assert len({dash(t) for t in comps}) == 4
    joints = [t for t in arm_and_path_figures["joints"].data if t.name in ("θ1", "θ2", "d3", "θ4")]
    assert len({dash(t) for t in joints}) == 4


# ---------------------------------------------------------------- every figure of chapters 4 to 6 and of the appendix
@pytest.fixture(scope="module")
def run_figures():
    """Every figure of chapters 4, 5, 6 and of the verification appendix, built as the chapters build them."""
    return _plots_shared.run_figures()


#: stacked panels sharing one time axis (three or four of them) may be taller than the default 560 px; 780 px
#: still fits a laptop screen with the browser's bars
TALL = {"control_joint_motion": 780, "control_torques": 780, "control_torque_differences": 780,
        "control_operational_error": 780, "control_boundary_layer": 780, "control_boundary_layer_notes": 780,
        "control_robust_term": 780, "control_steady_state": 780, "control_saturation": 780,
        "control_estimate_slider": 780, "control_classic": 780}


def _broken(figures, check, **per_figure):
    out = []
    for name, fig in figures.items():
        try:
            check(name, fig, **{k: f(name) for k, f in per_figure.items()})
        except AssertionError as exc:
            out.append(str(exc))
    return out


def test_every_run_figure_reads_on_a_laptop_and_a_phone(run_figures):
    # the speed bars are labelled on their axis (one bar per implementation): no legend needed
    broken = _broken(run_figures, check_reads_on_a_laptop_and_a_phone, max_height=lambda n: TALL.get(n, 560),
                     legend=lambda n: n != "appendix_speed")
    assert not broken, "\n".join(broken)


def test_every_run_figure_axis_has_a_title_with_a_unit(run_figures):
    broken = _broken(run_figures, check_axis_titles_with_units)
    assert not broken, "\n".join(broken)


def test_run_figures_keep_each_method_and_controllers_colour_and_dash(run_figures):
    """One palette per method across the book, and a dash style per controller, so curves stay apart in
    greyscale."""
    errors = run_figures["clik_errors"]
    inv = [t for t in errors.data if t.name and "inverse" in t.name and "pseudo" not in t.name]
    tra = [t for t in errors.data if t.name and "transpose" in t.name]
    assert inv and tra and {t.line.color for t in inv} == {plots.PALETTE["inverse"]}
    assert {t.line.color for t in tra} == {plots.PALETTE["transpose"]}
    assert (inv[0].line.dash or "solid") != (tra[0].line.dash or "solid")
    norm = run_figures["control_error_norm"]
    for key, label in CONTROLLER_LABELS.items():
        traces = [t for t in norm.data if t.name == label]
        if traces:
            assert traces[0].line.color == plots.PALETTE[key], key
            assert (traces[0].line.dash or "solid") == CONTROLLER_DASHES[key], key
    style = {t.name: ((t.line.dash or "solid"), t.line.color) for t in norm.data
             if t.name in CONTROLLER_LABELS.values()}
    assert len(style) == 5
    assert len({d for d, _ in style.values()}) == len({c for _, c in style.values()}) == 5
    # each dropdown entry shows its own group, and every run of the group once
    for button in norm.layout.updatemenus[0].buttons:
        shown = [t.name for t, v in zip(norm.data, button.args[0]["visible"]) if v]
        assert len(shown) == len(set(shown)) >= 3


# --------------------------------------------------------------------- every state of the slider and dropdown figures
@pytest.fixture(scope="module")
def state_figures(ref):
    """Figures whose sliders or dropdowns swap in a title: the gain sweeps and relaxed runs of chapter 4, the
    turn of the base and the theta2 sweep of chapter 2."""
    return {
        "clik_gain": _plots_shared.gain_figure(ref),
        "clik_uniform": _plots_shared.uniform_gains(ref)[3],
        "clik_kz": gain_steps_figure(ref, {"400": [400, 400, 400, 100], "2500": [400, 400, 2500, 100]},
                                     "second_order", prefix="K_z = ", suffix=" s⁻¹"),
        "clik_relaxed": _plots_shared.relaxed_runs(ref)[2],
        "manip_turn": base_turn_figure(),
        "manip_stretch": ellipse_slider_figure([60, 50, 40, 30, 20, 10, 5, 0]),
    }


def test_slider_and_dropdown_figures_read_on_a_laptop_and_a_phone(state_figures):
    for name, fig in state_figures.items():
        check_reads_on_a_laptop_and_a_phone(name, fig)
        check_axis_titles_with_units(name, fig)
        # at most two title lines in every state: a third would run into the legend
        assert all(len(title_lines(t)) <= 2 for t in titles_by_state(fig).values()), name


_BOXES = """async (gd) => {
  const box = (sel) => { const e = gd.querySelector(sel); if (!e) return null;
                         const r = e.getBoundingClientRect(); return [r.left, r.top, r.right, r.bottom]; };
  const states = [];
  const take = (label) => states.push({label, title: box('.gtitle'), legend: box('.legend'), plot: box('.nsewdrag'),
      drawn: gd.data.some(t => t.visible !== false && t.showlegend !== false && t.x && t.x.length > 0)});
  take('start');
  const controls = [...(gd.layout.sliders || []).flatMap(s => s.steps),
                    ...(gd.layout.updatemenus || []).flatMap(m => m.buttons)];
  for (const c of controls) {
    await Plotly.update(gd, c.args[0] || {}, c.args[1] || {}, c.args[2]);
    take(c.label);
  }
  return states;
}"""


def _overlap(a, b) -> bool:
    return a is not None and b is not None and min(a[2], b[2]) - max(a[0], b[0]) > 1 and \
        min(a[3], b[3]) - max(a[1], b[1]) > 1


def test_titles_clear_the_legend_in_every_state_at_phone_and_laptop_width(state_figures):
    from jupyterlab_driver import ARGS, CHROMIUM, chromium_available

    if not chromium_available():
        pytest.skip(f"Chromium is not installed at {CHROMIUM}")
    sync_playwright = pytest.importorskip("playwright.sync_api").sync_playwright
    divs = "".join(f'<div id="{name}" style="width:100%">'
                   f'{pio.to_html(fig, include_plotlyjs=False, full_html=False, div_id=name + "-plot")}</div>'
                   for name, fig in state_figures.items())
    with tempfile.TemporaryDirectory() as tmp:
        page = Path(tmp) / "state_figures.html"
        page.write_text(f"<html><head><meta charset='utf-8'><script>{get_plotlyjs()}</script></head>"
                        f"<body style='margin:8px'>{divs}</body></html>")
        problems = []
        with sync_playwright() as pw:
            browser = pw.chromium.launch(executable_path=CHROMIUM, args=ARGS, headless=True)
            for width in (390, 1280):
                pg = browser.new_page(viewport={"width": width, "height": 900})
                pg.goto(page.as_uri())
                pg.wait_for_function("() => Array.from(document.querySelectorAll('.plotly-graph-div'))"
                                     ".every(gd => gd._fullLayout)")
                for name in state_figures:
                    gd = pg.query_selector(f"#{name}-plot")
                    for st in gd.evaluate(_BOXES):
                        # a legend whenever a curve is drawn (a refused gain draws none, and plotly shows no legend)
                        assert st["title"] and st["plot"] and (st["legend"] or not st["drawn"]), (name, width, st)
                        if _overlap(st["title"], st["legend"]):
                            problems.append(f"{name} at {width} px, {st['label']}: title over legend")
                        if _overlap(st["legend"], st["plot"]):
                            problems.append(f"{name} at {width} px, {st['label']}: legend over plot")
                pg.close()
            browser.close()
    assert not problems, problems


# ------------------------------------------------------------------------- the page limits every slider figure shares
def test_slider_figures_refuse_more_steps_than_a_page_can_carry():
    t = np.linspace(0.0, 1.0, 11)
    many = {float(m): np.zeros((11, 4)) for m in range(200)}
    with pytest.raises(scara.ScaraError, match=r"len\(torques_by_mass\) = 200 .* <= 121 "):
        plots.payload_slider_figure(t, many)
    some = {float(m): np.zeros((11, 4)) for m in range(50)}
    with pytest.raises(scara.ScaraError, match=r"50 masses × target 5000 = 250000 .* <= 100000 "):
        plots.payload_slider_figure(t, some, target=5000)
    with pytest.raises(scara.ScaraError, match=r"runs must be a non-empty dict"):
        plots.boundary_layer_slider_figure({}, 1.0)
