"""Latency of the book's page panels in headless Chromium on this machine, per control, and the page's compute
time beside numba's for the same program.

    .venv/bin/python benchmarks/page_panels.py [--moves 15] [--html _build/html] [--panel control_panel ...]

Serves the built book, opens each page that holds a panel (every request outside the book refused), and for every
control of every panel makes ``--moves`` moves through its native input (a typed value committed, an option
picked, a box ticked), each waiting for the redraw. A move's latency is what the page records from the input
event to the last figure's redraw (``total_ms`` in ``.scara-panel-values``). Prints, per control, the median and
largest latency, then per panel the median compute time in the page's worker against numba's best time for the
same program and inputs (the ratio, one run, same machine).
"""
from __future__ import annotations

import argparse
import json
import math
import statistics
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
#: the resolution of performance.now() in a page that is not cross-origin isolated (Chromium, ms)
TIMER_STEP_MS = 0.1
sys.path[:0] = [str(ROOT), str(ROOT / "tests" / "book")]

from jupyterlab_driver import ARGS, CHROMIUM  # noqa: E402
from page_checks import serve  # noqa: E402
from page_panel_driver import open_page, panel_spec, seq, set_control, state, wait_seq, wait_values  # noqa: E402


def _moves(c, n, rng):
    if c["kind"] == "dropdown":
        return [c["options"][i % len(c["options"])][1] for i in range(1, n + 1)]
    if c["kind"] == "toggle":
        return [bool(i % 2) for i in range(1, n + 1)]
    if c["kind"] == "slider":
        if c["scale"] == "log":
            return [float(f"{10 ** rng.uniform(math.log10(c['low']), math.log10(c['high'])):.5g}") for _ in range(n)]
        return [float(f"{rng.uniform(c['low'], c['high']):.5g}") for _ in range(n)]
    return [float(f"{c['default'] + rng.normal(0, 0.02 * (abs(c['default']) + 1)):.5g}") for _ in range(n)]


def numba_ms(name: str, inputs, data, size, repeats: int = 20) -> float:
    """numba's best time (ms) for the program ``name`` on ``inputs``."""
    from scara.page.assets import program_kernels

    kernel = program_kernels()[name]
    inp, dat = np.asarray(inputs, float), np.asarray(data, float)
    kernel(inp, dat, np.zeros(size))  # compiled or loaded from the cache
    best = math.inf
    for _ in range(repeats):
        out = np.zeros(size)
        t0 = time.perf_counter()
        kernel(inp, dat, out)
        best = min(best, time.perf_counter() - t0)
    return 1e3 * best


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--moves", type=int, default=15)
    ap.add_argument("--html", default=str(ROOT / "_build" / "html"))
    ap.add_argument("--panel", action="append", help="only this panel (the name of its scara.widgets function)")
    args = ap.parse_args(argv)
    from playwright.sync_api import sync_playwright

    html = Path(args.html)
    pages = {}
    for f in sorted((html / "book").glob("*.html")):
        import re

        names = re.findall(r'data-scara-panel="([^"]+)"', f.read_text(encoding="utf-8"))
        names = [n for n in names if not args.panel or n in args.panel]
        if names:
            pages["book/" + f.name] = names
    httpd, url = serve(html)
    rng = np.random.default_rng(1)
    rows, ratios = [], []
    with sync_playwright() as pw:
        browser = pw.chromium.launch(executable_path=CHROMIUM, args=ARGS, headless=True)
        for page, names in pages.items():
            ctx, pg, errors, outside = open_page(browser, url, page)
            for name in names:
                spec = panel_spec(pg, name)
                wait_seq(pg, name, 0)
                computes = []
                by = {c["name"]: c for c in spec["controls"]}
                for c in spec["controls"]:
                    lat, parts = [], []
                    sel = spec["selector"]
                    if c["applies_to"] is not None and sel:  # pick a choice of the selector that reads it
                        s = seq(pg, name)
                        set_control(pg, name, sel, c["applies_to"][0], by[sel])
                        wait_seq(pg, name, s)
                    for value in _moves(c, args.moves, rng):
                        s = seq(pg, name)
                        set_control(pg, name, c["name"], value, c)
                        wait_seq(pg, name, s)
                        wait_values(pg, name, {c["name"]: value}, stale=None)
                        st = state(pg, name)["values"]
                        if "total_ms" in st:  # an accepted move (a refused one shows no figure to time)
                            lat.append(st["total_ms"])
                            parts.append((st["compute_ms"], st["draw_ms"]))
                    if lat:
                        rows.append((name, c["name"], len(lat), statistics.median(lat), max(lat),
                                     statistics.median(p[0] for p in parts), statistics.median(p[1] for p in parts)))
                    pg.click(f'[data-scara-panel="{name}"] .scara-panel-reset')
                    wait_values(pg, name, spec["values"])
                # the page's compute time against numba's, at the book's settings
                s = seq(pg, name)
                pg.click(f'[data-scara-panel="{name}"] .scara-panel-reset')
                wait_seq(pg, name, s)
                page_ms = []
                for _ in range(7):
                    s = seq(pg, name)
                    c = next(c for c in spec["controls"] if c["kind"] != "toggle" and c["applies_to"] is None)
                    set_control(pg, name, c["name"], spec["values"][c["name"]], c)
                    wait_seq(pg, name, s)
                    wait_values(pg, name, spec["values"])
                    page_ms.append(state(pg, name)["values"]["compute_ms"])
                prog = spec["program"]
                by = {c["name"]: c for c in spec["controls"]}
                inputs = []
                for i in prog["inputs"]:
                    v = spec["values"][i["name"]]
                    c = by[i["name"]]
                    inputs.append([json.dumps(o[1]) for o in c["options"]].index(json.dumps(v)) if c["kind"] == "dropdown"
                                  else float(bool(v)) if c["kind"] == "toggle" else float(v))
                import base64

                data = np.frombuffer(base64.b64decode(prog["data"]["float64"]), "<f8")
                if prog.get("prepare"):
                    from scara.page.assets import program_kernels

                    full = np.zeros(prog["data_size"])
                    program_kernels()[prog["prepare"]](data.copy(), full)
                    data = full
                nb = numba_ms(prog["kernel"], inputs, data, prog["size"])
                ratios.append((name, min(page_ms), nb))
            ctx.close()
        browser.close()
    httpd.shutdown()
    every = [r[3] for r in rows]
    print(f"{'panel':28s} {'control':16s} {'moves':>5s} {'median ms':>10s} {'largest ms':>11s} "
          f"{'compute ms':>11s} {'draw ms':>8s}")
    for name, c, n, med, mx, comp, draw in rows:
        print(f"{name:28s} {c:16s} {n:5d} {med:10.1f} {mx:11.1f} {comp:11.1f} {draw:8.1f}")
    by_panel = {}
    for name, c, n, med, mx, _, _ in rows:
        by_panel.setdefault(name, []).append((med, mx))
    print()
    for name, v in by_panel.items():
        print(f"{name:28s} median of the controls' medians {statistics.median(m for m, _ in v):6.1f} ms, "
              f"largest {max(x for _, x in v):6.1f} ms")
    print()
    print(f"{'panel':28s} {'page compute ms':>16s} {'numba ms':>9s} {'ratio':>6s}")
    for name, pm, nb in ratios:
        # a page without cross-origin isolation times in steps of 0.1 ms: a shorter run has no ratio to show
        ratio = f"{pm / nb:6.2f}" if pm >= 10 * TIMER_STEP_MS else "  (below the page timer's 0.1 ms step)"
        print(f"{name:28s} {pm:16.2f} {nb:9.3f} {ratio}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
