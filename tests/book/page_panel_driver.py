"""Driving a page panel of the built book in Chromium through its native controls (its contract is written in
``scara/page/assets.py``): shared by the browser test and the latency benchmark."""
from __future__ import annotations

import json

from page_checks import settle


def open_page(browser, url, page, width=1280, hash_=""):
    ctx = browser.new_context(viewport={"width": width, "height": 900})
    outside = []

    def route(r):
        if r.request.url.startswith(url):
            r.continue_()
        else:
            outside.append(r.request.url)
            r.abort()

    ctx.route("**/*", route)
    pg = ctx.new_page()
    errors = []
    pg.on("pageerror", lambda e: errors.append(str(e)))
    pg.on("console", lambda m: errors.append(m.text) if m.type == "error" else None)
    pg.goto(url + page + hash_, wait_until="load")
    settle(pg)
    return ctx, pg, errors, outside


def state(pg, name):
    return pg.evaluate("""(name) => {
      const root = document.querySelector(`[data-scara-panel="${name}"]`);
      const v = root.querySelector('.scara-panel-values').textContent;
      return {values: v ? JSON.parse(v) : null, stale: root.classList.contains('scara-stale'),
              message: root.querySelector('.scara-panel-message').textContent,
              figures: Array.from(root.querySelectorAll('.scara-panel-figure .js-plotly-plot')).map(gd => ({
                data: gd.data.map(t => ({x: t.x, y: t.y, z: t.z, text: t.text, visible: t.visible, name: t.name})),
                title: gd.closest('.scara-panel-figure').querySelector('.scara-panel-figure-title').textContent}))};
    }""", name)


def seq(pg, name):
    st = state(pg, name)
    return st["values"]["seq"] if st["values"] else 0


def wait_seq(pg, name, above):
    pg.wait_for_function("""([name, above]) => {
      const e = document.querySelector(`[data-scara-panel="${name}"] .scara-panel-values`);
      return e && e.textContent && JSON.parse(e.textContent).seq > above;
    }""", arg=[name, above], timeout=120000)


def set_control(pg, name, control, value, spec_control):
    """Set ``control`` through its native input: a number typed (and committed), an option picked, a box ticked
    or unticked. Every call makes one move (a ``change`` event), even when the value does not change, so the
    caller can wait for its redraw."""
    sel = f'[data-scara-panel="{name}"] [name="{control}"]'
    kind = spec_control["kind"]
    if kind == "dropdown":
        idx = [json.dumps(v) for _, v in spec_control["options"]].index(json.dumps(value))
        pg.select_option(sel, str(idx))
    elif kind == "toggle":
        if pg.is_checked(sel) != bool(value):
            pg.click(sel)  # a click ticks or unticks it (and fires change)
        else:
            pg.dispatch_event(sel, "change")
    else:
        pg.fill(sel, repr(float(value)))
        pg.dispatch_event(sel, "change")


def panel_spec(pg, name):
    return pg.evaluate("""(name) => JSON.parse(document.querySelector(
      `[data-scara-panel="${name}"] script.scara-panel-spec`).textContent)""", name)




def wait_values(pg, name, values: dict, stale: bool | None = False, timeout: float = 120000):
    """Wait until the panel shows ``values`` (as ``.scara-panel-values`` holds them) and is stale or not (None:
    either)."""
    pg.wait_for_function("""([name, values, stale]) => {
      const root = document.querySelector(`[data-scara-panel="${name}"]`);
      const e = root.querySelector('.scara-panel-values');
      if (!e.textContent || (stale !== null && root.classList.contains('scara-stale') !== stale)) return false;
      const v = JSON.parse(e.textContent).values;
      return Object.keys(values).every((k) => JSON.stringify(v[k]) === JSON.stringify(values[k]));
    }""", arg=[name, values, stale], timeout=timeout)
