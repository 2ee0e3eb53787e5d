"""How fast the live panels feel: from a key press (or a pick, or a typed value) to the figure's redraw.

Starts JupyterLab on 127.0.0.1 (a free port, no token) on a temporary copy of the chapters, opens each chapter
in Debian's Chromium, runs all cells (timed), then moves every control of every live panel ``--repeats`` times
(sliders one step right then back, dropdowns to another option and back, text boxes to another value and
back) and measures the time from the key press or change event to the last ``plotly_afterplot`` of the
panel's figures, with the time the kernel spent computing (the package's compiled code) and in Python overall
(computing, building the figures, sending what changed). Prints a table per control and, with ``--startup``,
the import and Run All times of ``benchmarks/startup.py``. Writes ``benchmarks/live_panels.json``.

    .venv/bin/python benchmarks/live_panels.py [--repeats 5] [--chapters 01 04] [--startup]

Targets (checked by reading the table, never asserted: machines are noisy): median <= 150 ms and max <= 400 ms
for 2-D figures, median <= 300 ms for 3-D scenes (headless Chromium draws 3-D with software WebGL).
"""
from __future__ import annotations

import argparse
import json
import statistics
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent / "tests" / "book"))

import jupyterlab_driver as drv  # noqa: E402
from test_jupyterlab import PANELS, _act, _control  # noqa: E402


def _pairs(moves):
    """The panel's moves in order (a dropdown pick sets the context of the controls after it), one per
    control in a row: (control, forth, back), the move and the move that undoes it."""
    out = []
    for desc, action, arg in moves:
        if out and out[-1][0] == desc and action == "key":
            continue
        if action == "key":
            out.append((desc, ("key", "ArrowRight"), ("key", "ArrowLeft")))
        elif action == "click":
            out.append((desc, ("click", None), ("click", None)))
        else:  # select or type: to the move's value and back to where it was
            out.append((desc, (action, arg), (action, None)))
    return out


def measure(chapters, repeats: int) -> dict:
    data = {"moves": [], "run_all": {}}
    with drv.jupyterlab_server() as url, drv.chromium() as browser:
        for chapter in chapters:
            lab = drv.Lab(browser, url)
            try:
                lab.open(chapter)
                data["run_all"][chapter] = lab.run_all()
                for k in range(len(PANELS[chapter])):  # every figure drawn before its redraws are hooked
                    lab.panels().nth(k).scroll_into_view_if_needed()
                    lab.wait_drawn(lab.panels().nth(k))
                lab.instrument()
                for k, wanted in enumerate(PANELS[chapter]):
                    panel = lab.panels().nth(k)
                    for desc, forth, back in _pairs(wanted["moves"]):
                        box = _control(lab.page, panel, desc)
                        box.scroll_into_view_if_needed()
                        if back[1] is None and back[0] != "click":  # the value to come back to
                            if back[0] == "select":
                                back = (back[0], box.locator("select").evaluate("s => s.options[s.selectedIndex].text"))
                            else:
                                back = (back[0], box.locator("input").input_value())
                        for r in range(repeats):
                            action = forth if r % 2 == 0 else back
                            before = lab.state(panel)
                            mark = lab.mark()
                            _act(lab.page, box, *action)
                            t = lab.timing_since(mark, panel, before)
                            st = lab.state(panel)
                            data["moves"].append(dict(
                                chapter=chapter[:2], panel=wanted["name"], control=desc, three_d=wanted["three_d"],
                                refused=bool(lab.message(panel)), latency_ms=t["latency_ms"], redraws=t["redraws"],
                                compute_ms=st.get("compute_ms"), draw_ms=st.get("draw_ms"), send_ms=st.get("send_ms"),
                                python_ms=sum(st.get(x, 0.0) for x in ("compute_ms", "draw_ms", "send_ms"))))
            finally:
                lab.close()
    return data


def table(data) -> str:
    rows = {}
    for m in data["moves"]:
        if m["latency_ms"] is not None and not m["refused"]:
            rows.setdefault((m["chapter"], m["panel"], m["control"]), []).append(m)
    out = [f"{'ch':3} {'panel':19} {'control':25} {'3-D':4} {'n':>3} {'median ms':>10} {'max ms':>7} "
           f"{'compute ms':>11} {'python ms':>10}", "-" * 100]
    for (ch, panel, control), ms in rows.items():
        lat = [m["latency_ms"] for m in ms]
        out.append(f"{ch:3} {panel:19} {control:25} {'yes' if ms[0]['three_d'] else 'no':4} {len(lat):3d} "
                   f"{statistics.median(lat):10.0f} {max(lat):7.0f} "
                   f"{statistics.median(m['compute_ms'] for m in ms):11.1f} "
                   f"{statistics.median(m['python_ms'] for m in ms):10.1f}")
    flat2 = [m["latency_ms"] for v in rows.values() for m in v if not m["three_d"]]
    flat3 = [m["latency_ms"] for v in rows.values() for m in v if m["three_d"]]
    out.append("-" * 100)
    if flat2:
        out.append(f"all 2-D moves: median {statistics.median(flat2):.0f} ms, max {max(flat2):.0f} ms "
                   f"(targets: median <= 150, max <= 400)")
    if flat3:
        out.append(f"all 3-D moves: median {statistics.median(flat3):.0f} ms, max {max(flat3):.0f} ms "
                   f"(target: median <= 300)")
    out += [f"Run All {name}: {sec:.1f} s" for name, sec in data["run_all"].items()]
    return "\n".join(out)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=5, help="moves per control, odd (forth, back, ..., forth)")
    ap.add_argument("--chapters", nargs="*", default=None, help="chapter prefixes, e.g. 01 04")
    ap.add_argument("--startup", action="store_true", help="also the import and Run All times (startup.py)")
    args = ap.parse_args(argv)
    args.repeats += 1 - args.repeats % 2  # odd: each control ends moved forth, as the next moves expect
    chapters = [c for c in PANELS if not args.chapters or c[:2] in args.chapters]
    if not drv.chromium_available():
        sys.exit(f"Chromium not found at {drv.CHROMIUM} (apt-get install chromium)")
    data = measure(chapters, args.repeats)
    print(table(data))
    if args.startup:
        import startup  # noqa: PLC0415 - beside this file

        print()
        startup.main([])
    (HERE / "live_panels.json").write_text(json.dumps(data, indent=1))


if __name__ == "__main__":
    main()
