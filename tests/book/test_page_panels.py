"""The live panels of the built book, in Chromium with every request outside the book refused and no kernel.

For every page panel (``[data-scara-panel]``, written by a panel cell's HTML output):

* every control, set through its native ``<input>``/``<select>`` to random valid values, redraws the figures, and
  their bound trace data equal what the Jupyter panel (``scara.widgets.LivePanel``, the ipywidgets figures)
  draws for the same settings: 1e-12 relative for single evaluations, 1e-9 of each array's range for a run;
* ``.scara-panel-values`` holds the settings as ``LivePanel.values()`` gives them, with an increasing ``seq``;
* one refused setting per panel shows the Jupyter panel's message, greys and empties the figures
  (``scara-stale``) and, set back, redraws them;
* the settings live in the page's address: a reload keeps them, the reset button returns to the book's values;
* moves made while the engine is busy collapse to the latest.

Outside CI a missing Chromium or a missing build skips with the reason; with ``CI=true`` they fail.
"""
from __future__ import annotations

import json
import zlib
import math
import os
import re
import shutil
from pathlib import Path

import numpy as np
import pytest

from jupyterlab_driver import ARGS, CHROMIUM
from page_checks import serve, settle
from page_checks import unavailable as _unavailable
from page_panel_driver import open_page as _open, panel_spec as _spec, seq as _seq, set_control as _set
from page_panel_driver import state as _state, wait_seq as _wait_seq, wait_values as _wait_values

ROOT = Path(__file__).resolve().parents[2]
HTML = Path(os.environ.get("SCARA_BOOK_HTML", ROOT / "_build" / "html"))
SHOTS = HTML.parent / "screenshots"
#: random settings tried per panel
TRIALS = int(os.environ.get("SCARA_PANEL_TRIALS", "4"))

#: a setting each panel refuses (control -> value typed into its native input)
REFUSED = {
    "kinematics_panel": {"theta1": 500.0},
    "inverse_kinematics_panel": {"px": 2.0},
    "manipulability_panel": {"scale": 0.0},
    "dynamics_panel": {"payload": 20.0, "K_P3": 100.0},
    "clik_panel": {"Kx": 2500.0},
    "waypoint_editor": {"x": 1.0},
    "control_panel": {"K_D": 2.0},
    "interaction_panel": {"D_z": 5e4},
}


def _pages() -> dict:
    """page -> names of its panels, read from the built HTML."""
    out = {}
    for f in sorted((HTML / "book").glob("*.html")):
        names = re.findall(r'data-scara-panel="([^"]+)"', f.read_text(encoding="utf-8"))
        if names:
            out["book/" + f.name] = names
    return out


@pytest.fixture(scope="module")
def server():
    if not (HTML / "index.html").exists():
        _unavailable(f"the book is not built ({HTML}/index.html missing): run jupyter-book build . first")
    httpd, url = serve(HTML)
    yield url
    httpd.shutdown()


@pytest.fixture(scope="module")
def browser():
    if not (Path(CHROMIUM).exists() or shutil.which(CHROMIUM)):
        _unavailable(f"Chromium not found at {CHROMIUM} (apt-get install chromium)")
    try:
        from playwright.sync_api import sync_playwright
    except ImportError:
        _unavailable("playwright (Python) is not installed")
    with sync_playwright() as pw:
        b = pw.chromium.launch(executable_path=CHROMIUM, args=ARGS, headless=True)
        yield b
        b.close()


def _engine_data(pg, name):
    """The data of panel ``name`` as the page's engine holds it (prepared in the page)."""
    return pg.evaluate("""(name) => document.querySelector(`[data-scara-panel="${name}"]`).__scaraPanel.engineData()""",
                       name)


# ---- the Jupyter side ------------------------------------------------------------------------------------------
def _jupyter_panel(spec, prepared=None):
    """The Jupyter panel the page panel was written from: the same scara.widgets function, its program's data
    made equal to the page's (the book may pass its own robot or path). A program whose data the page prepares
    from a compact form (a 70 s path sampled, a 70 s joint reference run) gets ``prepared``, the data as the
    page's engine made it, once it is checked against numba's preparation (1e-9 of the data's range, as a run):
    each move is then compared on the same data, so a difference is the move's own."""
    import scara.widgets as W
    from scara.plots.panels import PageProgram

    from dataclasses import replace

    made = getattr(W, spec["name"])()
    panel = getattr(made, "panel", made)  # the waypoint editor holds its LivePanel
    decl = panel.declaration
    import base64

    data = np.frombuffer(base64.b64decode(spec["program"]["data"]["float64"]), "<f8")
    if spec["program"].get("prepare"):
        from scara.page.assets import program_kernels

        full = np.zeros(spec["program"]["data_size"])
        assert program_kernels()[spec["program"]["prepare"]](data.copy(), full) == 0
        data = full
        if prepared is not None:
            page_data = np.array([np.nan if v is None else v for v in prepared], dtype=float)
            assert page_data.shape == full.shape, "the page's prepared data has another size"
            worst = float(np.max(np.abs(page_data - full))) / float(np.ptp(full))
            assert worst <= 1e-9, f"{spec['name']}: the page prepared its data {worst:.3g} of its range from numba's"
            data = page_data
    if data.shape != decl.page.data.shape or not np.array_equal(data, decl.page.data):
        from scara.plots.panels import program_panel  # noqa: F401 - the book's own data, same bindings

        prog = replace(decl.page, data=data)
        by_name = {c.name: c for c in decl.controls}

        def compute(settings, prog=prog):  # as program_panel's: a carrying panel's accepted move carries
            values = prog.run(settings, by_name)
            prog.carried(values)
            return values

        decl = replace(decl, page=prog, compute=compute, react=prog.reacted if prog.react else decl.react,
                       figures=tuple(replace(f, update=(lambda v, role=f.role, prog=prog: prog.update(role, v)))
                                     for f in decl.figures))
        from scara.widgets._common import LivePanel

        panel = LivePanel(decl)
    assert isinstance(decl.page, PageProgram)
    with panel.hold():  # the settings the book opened the panel at (the chapter may pass its own start)
        for key, value in spec["values"].items():
            panel.controls[key].value = value
    return panel


def _random_settings(spec, rng):
    out = {}
    for c in spec["controls"]:
        if c["kind"] == "dropdown":
            out[c["name"]] = c["options"][rng.integers(len(c["options"]))][1]
        elif c["kind"] == "toggle":
            out[c["name"]] = bool(rng.integers(2))
        elif c["kind"] == "slider":
            if c["scale"] == "log":
                v = 10 ** rng.uniform(math.log10(c["low"]), math.log10(c["high"]))
            else:
                v = rng.uniform(c["low"], c["high"])
            out[c["name"]] = float(f"{v:.6g}")
        else:
            out[c["name"]] = float(f"{c['default'] + rng.normal(0, 0.02 * (abs(c['default']) + 1)):.6g}")
    return out


def _close(a, b, what):
    """Page array ``a`` against the Jupyter panel's ``b`` (None is a gap, NaN in the page)."""
    if isinstance(b, str) or isinstance(a, str):
        assert a == b, what
        return
    if b is None or a is None:
        assert a is None and b is None or (a in (None, []) and b in (None, [])), what
        return
    bb = np.array([np.nan if v is None else v for v in np.ravel(np.asarray(b, dtype=object))], dtype=float)
    aa = np.array([np.nan if v is None else v for v in np.ravel(np.asarray(a, dtype=object))], dtype=float)
    assert aa.shape == bb.shape, f"{what}: {aa.shape} != {bb.shape}"
    assert np.array_equal(np.isnan(aa), np.isnan(bb)), f"{what}: gaps differ"
    ok = ~np.isnan(bb)
    if not ok.any():
        return
    scale = max(float(np.ptp(bb[ok])), float(np.max(np.abs(bb[ok]))) * 1e-3, 1e-12)
    tol = 1e-12 if bb.size <= 64 else 1e-9  # a run's signals: 1e-9 of their range; single evaluations 1e-12
    diff = float(np.max(np.abs(aa[ok] - bb[ok])))
    worst = diff / scale
    # a run's error signal is a difference of quantities up to pi (angles in rad, positions in m) that the run
    # carries for 70 s: the browser's sin and cos differ from numba's libm by one ulp on 3 % of arguments, and the
    # two runs' angles stay a few ulps apart (an ulp of pi is 4.4e-16). That is the floor of the comparison: 8 ulps
    # of pi (3.6e-15) apart passes. A signal whose whole range is 6e-7 rad (the second-order CLIK's orientation
    # error) sees 1.3e-15 as 2e-9 of its range.
    if bb.size > 64 and diff <= 8 * np.spacing(np.pi):
        return
    assert worst <= tol, f"{what}: {worst:.3g} of the range ({diff:.3g} apart)"


def _compare(page_state, panel, spec):
    figs = [fw.to_plotly_json() for fw in panel.figures]
    prog = spec["program"]
    assert len(page_state["figures"]) == len(figs)
    for k, (pf, jf, fspec) in enumerate(zip(page_state["figures"], figs, spec["figures"])):
        role = fspec["role"]
        assert len(pf["data"]) == len(jf["data"]), role
        for key, props in prog["traces"].get(role, {}).items():
            i = fspec["index"][key]
            for p in props:
                if p in ("x", "y", "z", "text"):
                    _close(pf["data"][i].get(p), jf["data"][i].get(p), f"figure {role}, trace {key}, {p}")
        if role in prog["titles"]:  # shown above the figure as text, plotly's <br> as a line break
            text = re.sub(r"<br\s*/?>", "\n", (jf["layout"].get("title") or {}).get("text") or "", flags=re.I)
            assert pf["title"] == re.sub(r"<[^>]*>", "", text), role


@pytest.mark.parametrize("page", sorted(_pages()) or ["(no page panels built)"])
def test_page_panels_equal_the_jupyter_panels(server, browser, page):
    if page.startswith("("):
        pytest.fail("the built book holds no page panel")
    names = _pages()[page]
    ctx, pg, errors, outside = _open(browser, server, page)
    rng = np.random.default_rng(zlib.crc32(page.encode()))  # the same settings on every run
    try:
        for name in names:
            spec = _spec(pg, name)
            _wait_seq(pg, name, 0)
            panel = _jupyter_panel(spec, _engine_data(pg, name) if spec["program"].get("prepare") else None)
            by_name = {c["name"]: c for c in spec["controls"]}
            assert [c["name"] for c in spec["controls"]] == list(panel.controls)
            assert _state(pg, name)["values"]["values"] == json.loads(json.dumps(panel.values()))
            for trial in range(TRIALS):
                settings = _random_settings(spec, rng)
                # move by move on both sides (a move may set other controls, or build on the last: the editor)
                for key, value in settings.items():
                    if pg.is_disabled(f'[data-scara-panel="{name}"] [name="{key}"]'):
                        continue  # a control the selector's choice does not read
                    seq = _seq(pg, name)
                    _set(pg, name, key, value, by_name[key])
                    _wait_seq(pg, name, seq)
                    panel.controls[key].value = value
                    # the redraw of this move (an earlier move's may land first): the panel's values
                    _wait_values(pg, name, json.loads(json.dumps(panel.values())), stale=None)
                st = _state(pg, name)
                if panel.last_error is not None:
                    assert st["stale"] and panel.last_error in st["message"], (settings, st["message"])
                    continue
                assert not st["stale"], (name, settings, st["message"])
                assert st["values"]["values"] == json.loads(json.dumps(panel.values())), name
                try:
                    _compare(st, panel, spec)
                except AssertionError as exc:
                    raise AssertionError(f"{name} after {settings}: {exc}") from None
            pg.screenshot(path=str(SHOTS / f"page_panel_{name}.png"), full_page=False)
            # one refused setting, then back
            bad = REFUSED.get(name)
            if bad:
                pg.click(f'[data-scara-panel="{name}"] .scara-panel-reset')
                _wait_values(pg, name, spec["values"])
                fresh = _jupyter_panel(spec)  # at the book's values, as the page after its reset
                for key, value in bad.items():
                    seq = _seq(pg, name)
                    _set(pg, name, key, value, by_name[key])
                    _wait_seq(pg, name, seq)
                st = _state(pg, name)
                assert st["stale"], (name, bad)
                expected = _expected_refusal(fresh, bad)
                assert st["message"] == f"{spec['refused']} {expected}", (st["message"], expected)
                for f in st["figures"]:
                    assert all(t["visible"] is False for t in f["data"]) and f["title"] == spec["stale_title"]
                pg.click(f'[data-scara-panel="{name}"] .scara-panel-reset')
                _wait_values(pg, name, spec["values"])
                st = _state(pg, name)
                assert not st["stale"] and st["values"]["values"] == spec["values"], (name, st["message"])
        assert not errors, errors
        assert not outside, outside
    finally:
        ctx.close()


def _expected_refusal(panel, bad: dict) -> str:
    """The message the Jupyter side gives for ``bad``: the range check of a typed value, else the panel's."""
    from scara.errors import ScaraError
    from scara.plots.panels import start_value

    decl = panel.declaration
    settings = dict(panel.values(), **bad)
    for c in decl.controls:
        if c.kind == "slider":
            try:
                start_value(settings[c.name], c.low, c.high, c.name, c.unit, c.limit)
            except ScaraError as exc:
                return str(exc)
    try:
        decl.compute(settings)
    except ScaraError as exc:
        return panel.explain(exc, settings)
    raise AssertionError(f"{bad} is not refused by the Jupyter panel")


def test_address_keeps_a_setting_and_reset_returns(server, browser):
    pages = _pages()
    if not pages:
        pytest.fail("the built book holds no page panel")
    page, names = sorted(pages.items())[0]
    name = names[0]
    ctx, pg, errors, _ = _open(browser, server, page)
    try:
        spec = _spec(pg, name)
        c = next(c for c in spec["controls"] if c["kind"] == "slider")
        value = float(f"{0.3 * c['low'] + 0.7 * c['high']:.4g}")
        _wait_seq(pg, name, 0)
        seq = _seq(pg, name)
        _set(pg, name, c["name"], value, c)
        _wait_seq(pg, name, seq)
        url = pg.url
        assert f"{name}.{c['name']}=" in url
        pg.goto(url.replace(server, server), wait_until="load")
        pg.reload(wait_until="load")
        settle(pg)
        _wait_seq(pg, name, 0)
        assert _state(pg, name)["values"]["values"][c["name"]] == value
        assert float(pg.input_value(f'[data-scara-panel="{name}"] [name="{c["name"]}"]')) == value
        seq = _seq(pg, name)
        pg.click(f'[data-scara-panel="{name}"] .scara-panel-reset')
        _wait_seq(pg, name, seq)
        assert _state(pg, name)["values"]["values"] == spec["values"]
        assert f"{name}." not in pg.url
        # moves made while the engine is busy collapse to the latest
        seq = _seq(pg, name)
        sel = f'[data-scara-panel="{name}"] input[type=range][aria-label^="{c["label"]}"]'
        pg.evaluate("""([sel, lo, hi]) => { const r = document.querySelector(sel);
          for (let i = 0; i <= 40; i++) { r.value = String(lo + (hi - lo) * i / 40); r.dispatchEvent(new Event('input')); } }""",
                    [sel, c["low"], c["high"]] if c["scale"] == "linear" else
                    [sel, math.log10(c["low"]), math.log10(c["high"])])
        pg.wait_for_function("""([name, v]) => { const e = document.querySelector(`[data-scara-panel="${name}"] .scara-panel-values`);
          return JSON.parse(e.textContent).values[%s] !== undefined && Math.abs(JSON.parse(e.textContent).values[%s] - v) < 1e-9 * Math.max(1, Math.abs(v)); }"""
                             % (json.dumps(c["name"]), json.dumps(c["name"])), arg=[name, c["high"]], timeout=120000)
        pg.wait_for_timeout(300)
        assert _seq(pg, name) - seq < 41, "every move was drawn: they did not collapse"
        assert not errors, errors
    finally:
        ctx.close()


def test_a_waypoint_dragged_on_the_top_view_is_the_jupyter_editors_edit(server, browser):
    """In the page's waypoint editor the reader drags a waypoint on the top view with the pointer: it is picked, its
    x and y follow the pointer (on the sliders' steps), the path is re-planned on the way, and the figures equal
    the Jupyter editor's for the waypoint so picked and moved. Plotly's zoom does not start."""
    page = next((p for p, names in _pages().items() if "waypoint_editor" in names), None)
    if page is None:
        pytest.fail("the built book holds no waypoint editor")
    name = "waypoint_editor"
    ctx, pg, errors, outside = _open(browser, server, page)
    try:
        spec = _spec(pg, name)
        _wait_seq(pg, name, 0)
        by_name = {c["name"]: c for c in spec["controls"]}
        sel = f'[data-scara-panel="{name}"] .scara-panel-figure .js-plotly-plot'
        pg.locator(sel).first.scroll_into_view_if_needed()
        # a waypoint other than the one the panel opens at, and where it is on the screen
        points = pg.evaluate("""([sel, name]) => {
          const gd = document.querySelector(sel), fl = gd._fullLayout, r = gd.getBoundingClientRect();
          const p = document.querySelector(`[data-scara-panel="${name}"]`).__scaraPanel, d = p.prog.drag;
          const rx = p.prog.react[d.pick][d.x], ry = p.prog.react[d.pick][d.y];
          return p.spec.controls.find(c => c.name === d.pick).options.map(([, i]) => {
            const x = p.data[rx.offset + rx.stride * i], y = p.data[ry.offset + ry.stride * i];
            return {i, x, y, px: r.left + fl.xaxis.l2p(x) + fl.xaxis._offset, py: r.top + fl.yaxis.l2p(y) + fl.yaxis._offset,
                    left: r.left + fl.xaxis._offset, top: r.top + fl.yaxis._offset, w: fl.xaxis._length, h: fl.yaxis._length};
          });
        }""", [sel, name])
        start = spec["values"]["point"]
        target = next(p for p in points if p["i"] != start and
                      all(math.hypot(p["px"] - q["px"], p["py"] - q["py"]) > 20 for q in points if q is not p))
        ranges = [pg.evaluate(f"() => document.querySelector('{sel}')._fullLayout.{a}axis.range.slice()")
                  for a in "xy"]
        seq = _seq(pg, name)
        pg.mouse.move(target["px"], target["py"])
        pg.mouse.down()
        to = (target["px"] + 0.06 * target["w"], target["py"] - 0.05 * target["h"])
        for k in range(1, 6):
            pg.mouse.move(target["px"] + (to[0] - target["px"]) * k / 5, target["py"] + (to[1] - target["py"]) * k / 5)
            pg.wait_for_timeout(60)
        pg.mouse.up()
        # the drop's place in the axes' units, on the sliders' steps
        want = {}
        for axis, key, pix, lo, size in (("x", "x", to[0], target["left"], target["w"]),
                                         ("y", "y", to[1], target["top"], target["h"])):
            r = ranges["xy".index(axis)]
            frac = (pix - lo) / size if axis == "x" else 1 - (pix - lo) / size
            step = by_name[key]["step"]
            want[key] = float(f"{round((r[0] + frac * (r[1] - r[0])) / step) * step:.12g}")
        _wait_seq(pg, name, seq)
        pg.wait_for_function("""([name, i]) => { const e = document.querySelector(`[data-scara-panel="${name}"] .scara-panel-values`);
          const v = JSON.parse(e.textContent).values; return v.point === i; }""", arg=[name, target["i"]], timeout=120000)
        pg.wait_for_timeout(800)  # the last pointer move's redraw
        st = _state(pg, name)
        got = st["values"]["values"]
        assert got["point"] == target["i"] and not st["stale"], (got, st["message"])
        for key in ("x", "y"):   # within a step of the pointer's place (a pixel is smaller than a step)
            assert abs(got[key] - want[key]) <= by_name[key]["step"] + 1e-12, (key, got[key], want[key])
            assert got[key] != pytest.approx(target[key], abs=1e-9), "the waypoint did not move"
        assert pg.evaluate(f"() => document.querySelector('{sel}')._fullLayout.xaxis.range.slice()") == ranges[0], \
            "plotly zoomed instead of the waypoint moving"
        panel = _jupyter_panel(spec)
        for key in ("point", "x", "y"):   # the same edit made with the Jupyter editor's controls
            panel.controls[key].value = got[key]
        assert panel.last_error is None and st["values"]["values"] == json.loads(json.dumps(panel.values()))
        _compare(st, panel, spec)
        pg.screenshot(path=str(SHOTS / "page_panel_waypoint_dragged.png"), full_page=False)
        # a second edit on another waypoint (the first stays in the plan), then a reload of the address: the
        # page replays both edits and draws the same figures, the same settings
        other = next(p for p in points if p["i"] not in (target["i"], start))
        for key, value in (("point", other["i"]), ("z", float(f"{other['i'] * 0.01 + 0.3:.4g}"))):
            seq = _seq(pg, name)
            _set(pg, name, key, value, by_name[key])
            _wait_seq(pg, name, seq)
            panel.controls[key].value = value
        _wait_values(pg, name, json.loads(json.dumps(panel.values())))
        before = _state(pg, name)
        assert not before["stale"], before["message"]
        _compare(before, panel, spec)
        assert f"{name}.edits=" in pg.url, pg.url
        pg.reload(wait_until="load")
        settle(pg)
        _wait_values(pg, name, before["values"]["values"])
        after = _state(pg, name)
        assert after["figures"] == before["figures"], "a reload did not replay the edits"
        assert not errors, errors
        assert not outside, outside
    finally:
        ctx.close()


def _luminance(rgb: str) -> float:
    """The relative luminance (WCAG 2) of a computed ``rgb(...)``/``rgba(...)`` colour."""
    r, g, b = (float(v) / 255 for v in re.findall(r"[\d.]+", rgb)[:3])
    lin = [c / 12.92 if c <= 0.04045 else ((c + 0.055) / 1.055) ** 2.4 for c in (r, g, b)]
    return 0.2126 * lin[0] + 0.7152 * lin[1] + 0.0722 * lin[2]


@pytest.mark.parametrize("mode", ["light", "dark"])
def test_every_control_reads_in_both_themes_on_a_phone(server, browser, mode):
    """At 390 px, in the theme's light and dark modes, every panel's labels, typed numbers and menus stand out
    from what is behind them (WCAG's 4.5:1 for text): a cell's output area is a light block in dark mode, so a
    panel has its own colours."""
    pages = _pages()
    if not pages:
        pytest.fail("the built book holds no page panel")
    for page, names in sorted(pages.items()):
        ctx = browser.new_context(viewport={"width": 390, "height": 900})
        ctx.add_init_script(f"localStorage.setItem('mode', '{mode}'); localStorage.setItem('theme', '{mode}');")
        ctx.route("**/*", lambda r: r.continue_() if r.request.url.startswith(server) else r.abort())
        pg = ctx.new_page()
        try:
            pg.goto(server + page, wait_until="load")
            settle(pg)
            for name in names:
                _wait_seq(pg, name, 0)
                pairs = pg.evaluate("""(name) => {
                  const root = document.querySelector(`[data-scara-panel="${name}"]`);
                  const bg = (e) => { for (; e; e = e.parentElement) { const c = getComputedStyle(e).backgroundColor;
                    if (c && !/rgba\\(.*,\\s*0\\)$/.test(c) && c !== 'transparent') return c; } return 'rgb(255, 255, 255)'; };
                  return Array.from(root.querySelectorAll('.scara-panel-label, input[type=number], select, .scara-panel-head b'))
                    .filter((e) => !e.disabled).map((e) => [e.name || e.className || e.tagName, getComputedStyle(e).color, bg(e)]);
                }""", name)
                assert pairs, name
                for what, fg, bgc in pairs:
                    a, b = sorted((_luminance(fg), _luminance(bgc)))
                    ratio = (b + 0.05) / (a + 0.05)
                    assert ratio >= 4.5, f"{page} {name} {mode}: {what} is {fg} on {bgc} ({ratio:.2f}:1)"
        finally:
            ctx.close()
