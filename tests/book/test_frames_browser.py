"""The frame names of the 3-D views of chapter 1 (Fig. 1.2 and the joint slider) and the course figure of the
introduction, drawn by plotly in Chromium at the width of a 390-px phone page and of a laptop: no two texts
overlap (the checks of ``page_checks.py``, run on the figure alone), every frame name lies inside the figure,
and plotly draws each name where the pixel model of ``scara.plots.kinematics.scene_projection`` puts it.

No book build needed; outside CI a missing Chromium or Playwright skips with the reason (as ``test_browser.py``).
"""
from __future__ import annotations

import math
import shutil
from pathlib import Path

import numpy as np
import plotly.graph_objects as go
import pytest

from scara.plots import arm_figure, joint_slider_figure
from scara.plots.kinematics import scene_projection

from page_checks import LABEL_OVERLAPS
from page_checks import unavailable as _unavailable

#: figure widths: a 390-px phone page (its text column) and a laptop
WIDTHS = (342, 1240)
CONFIGS = [
    [math.radians(40), math.radians(-70), 0.3, math.radians(45)],
    [0.0, math.radians(60), 0.5, 0.0],
    [math.radians(120), math.radians(-45), 0.0, math.radians(10)],
    [math.radians(10), 0.0, 1.0, 0.0],
    [0.0, math.pi, 0.3, 0.0],
]

NAME_BOXES = """() => {
  const gd = document.getElementById('g'), s = gd._fullLayout._size, r = gd.getBoundingClientRect();
  const cx = r.left + s.l + s.w / 2, cy = r.top + s.t + s.h / 2;
  return Array.from(gd.querySelectorAll('.annotation-text-g')).map(g => {
    const b = g.getBoundingClientRect();
    return [g.textContent, b.left - r.left, b.top - r.top, b.right - r.left, b.bottom - r.top,
            cx - r.left, cy - r.top, r.width, r.height, s.h];
  });
}"""


@pytest.fixture(scope="module")
def page():
    from jupyterlab_driver import ARGS, CHROMIUM

    if not (Path(CHROMIUM).exists() or shutil.which(CHROMIUM)):
        _unavailable(f"Chromium not found at {CHROMIUM}")
    try:
        from playwright.sync_api import sync_playwright
    except ImportError:
        _unavailable("playwright (Python) is not installed")
    import plotly

    js = (Path(plotly.__file__).parent / "package_data" / "plotly.min.js").read_text()
    with sync_playwright() as pw:
        browser = pw.chromium.launch(executable_path=CHROMIUM, args=ARGS + ["--use-gl=swiftshader", "--enable-webgl",
                                                                              "--ignore-gpu-blocklist"],
                                     headless=True)

        def show(fig, width):
            pg = browser.new_page(viewport={"width": width + 20, "height": 1000})
            body = fig.to_html(include_plotlyjs=False, full_html=False, div_id="g")
            pg.set_content(f"<html><head><script>{js}</script></head><body style='margin:10px'>"
                           f"<div style='width:{width}px'>{body}</div></body></html>")
            pg.wait_for_function("() => { const gd = document.getElementById('g');"
                                 " return gd && gd._fullLayout && gd.querySelectorAll('.main-svg').length > 0; }")
            pg.wait_for_timeout(300)
            return pg

        yield show
        browser.close()


def _check(pg, fig, where):
    problems = pg.evaluate(LABEL_OVERLAPS)
    assert not problems, (where, problems)
    boxes = pg.evaluate(NAME_BOXES)
    notes = fig.layout.scene.annotations
    assert [b[0] for b in boxes] == [a.text for a in notes], where
    # the plot area plotly drew (a legend or a slider may take a few more pixels of margin than the layout asks)
    plot_height = boxes[0][-1] if boxes else 0.0
    assert abs(plot_height - (fig.layout.height - fig.layout.margin.t - fig.layout.margin.b)) <= 8, where
    project = scene_projection(fig.layout.scene.to_plotly_json(), plot_height)
    for (text, left, top, right, bottom, cx, cy, fw, fh, _), a, (px, py) in zip(
            boxes, notes, project([[a.x, a.y, a.z] for a in notes])):
        assert 0 <= left and right <= fw and 0 <= top and bottom <= fh, (where, text, left, top, right, bottom)
        # the model: the anchor corner of the name's box is the projected origin moved by the shift (px, y up)
        x = {"left": left, "right": right, "center": (left + right) / 2}[a.xanchor]
        y = {"bottom": bottom, "top": top, "middle": (top + bottom) / 2}[a.yanchor]
        rel = np.array([x - cx, cy - y])
        assert np.allclose(rel, [px + a.xshift, py + a.yshift], atol=4.0), (where, text, rel, px, py)


@pytest.mark.parametrize("q", CONFIGS)
@pytest.mark.parametrize("width", WIDTHS)
def test_arm_figure_names_apart_in_the_browser(page, q, width):
    fig = arm_figure(q, names="annotations")
    pg = page(fig, width)
    _check(pg, fig, (q, width))
    pg.close()


@pytest.mark.parametrize("width", WIDTHS)
def test_joint_slider_names_apart_at_every_step_in_the_browser(page, width):
    fig = joint_slider_figure([0.0, math.radians(60), 0.5, 0.0], joint=1)
    pg = page(fig, width)
    for k, step in enumerate(fig.layout.sliders[0].steps):
        if k % 3:  # every third step of 25 (the model test covers them all)
            continue
        pg.evaluate("(a) => Plotly.update(document.getElementById('g'), a[0], a[1], a[2])",
                    [step.args[0], step.args[1], list(step.args[2])])
        pg.wait_for_timeout(1000)
        shown = go.Figure(fig)  # the figure as this step shows it: its names
        shown.layout.scene.annotations = step.args[1]["scene.annotations"]
        _check(pg, shown, (step.label, width))
    pg.close()


@pytest.mark.parametrize("width", WIDTHS)
def test_course_figure_texts_apart_in_the_browser(page, width):
    import scara
    from scara import plots

    fig = plots.course_animation(scara.reference_trajectory())
    pg = page(fig, width)
    problems = pg.evaluate(LABEL_OVERLAPS)
    assert not problems, (width, problems)
    # the legend names the trail, and the colour bar the path
    legend = pg.evaluate("() => document.getElementById('g').querySelector('.legend').textContent")
    assert "path covered" in legend
    bar = pg.evaluate("() => document.getElementById('g').querySelector('.colorbar').textContent")
    assert "path coloured by w" in bar
    pg.close()
