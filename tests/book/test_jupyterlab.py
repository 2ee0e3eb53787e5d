"""The live panels in a real JupyterLab, driven by Debian's Chromium as a learner drives them.

For every chapter with a live panel: open its take-home copy (the book's download) in JupyterLab, *Run All
Cells*, and check that no cell failed, that each panel's figures sit inside the panel (none is displayed beside
it), and that nothing reached the Log Console, the browser console (a reference the markdown renderer cannot
resolve would) or the page's error handler; after the moves below, read the chapter: no raw MyST markup, no
number left as its key or its code, no bare label (``jupyterlab_driver.Lab.raw_myst_text``).
Then move every control as a person does (a key press on a slider handle, a pick in a dropdown, a value typed
in a text box or in the number box beside a slider, a click on a check box) and check that the figures redraw in
place to what the package itself computes for the new values; and for each panel that can refuse a setting, make
one it refuses (a number typed outside a slider's range among them: refused, never clamped) and check that the
message names the value and the limit, that the figures are marked stale, and that setting the control back
restores a valid figure.

The time from each key press or change to the figure's last ``plotly_afterplot`` is recorded (not asserted:
machines are noisy) and printed as a table at the end, with the Run All time of each chapter; the same numbers
go to ``_build/live_panels.json``. ``benchmarks/live_panels.py`` repeats the moves for steadier figures.

Outside CI a missing Chromium or JupyterLab skips with the reason; with ``CI=true`` they fail.
"""
from __future__ import annotations

import json
import math
import os
import re
import statistics
from pathlib import Path

import numpy as np
import pytest

import jupyterlab_driver as lab_driver

IN_CI = os.environ.get("CI", "").lower() == "true"
ROOT = Path(__file__).resolve().parents[2]
RESULTS = ROOT / "_build" / "live_panels.json"
STALE_TITLE = "Not current: this setting was refused (see the message above)"

def _unavailable(reason: str):
    if IN_CI:
        pytest.fail(f"JupyterLab browser test cannot run under CI=true: {reason}")
    pytest.skip(reason)


def _require(module: str, found: bool, reason: str):
    """Skip (fail under CI) unless ``found`` and ``module`` imports."""
    try:
        __import__(module)
    except ImportError:
        found = False
    if not found:
        _unavailable(reason)


@pytest.fixture(scope="module")
def lab_url(request):
    _require("jupyterlab", lab_driver.jupyter_executable() is not None,
             "JupyterLab is not installed (pip install -r requirements.txt)")
    return request.getfixturevalue("jupyterlab_url")   # the worker's one server (tests/conftest.py)


@pytest.fixture(scope="module")
def browser():
    _require("playwright", lab_driver.chromium_available(),
             f"Chromium (at {lab_driver.CHROMIUM}) or playwright is missing (apt-get install chromium)")
    with lab_driver.chromium() as b:
        yield b


@pytest.fixture(scope="module")
def record():
    """The moves and Run All times of this worker's chapters; at the end they join those the other worker wrote in
    the same run (``RESULTS`` holds the run's id), under a lock, so the file holds every chapter of the run."""
    import fcntl

    data = {"moves": [], "run_all": {}}
    yield data
    RESULTS.parent.mkdir(parents=True, exist_ok=True)
    run = os.environ.get("PYTEST_XDIST_TESTRUNUID", "")
    with open(RESULTS.with_suffix(".lock"), "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        try:
            earlier = json.loads(RESULTS.read_text()) if RESULTS.is_file() else {}
        except ValueError:
            earlier = {}
        if run and earlier.get("run") == run:
            data = {"moves": earlier["moves"] + data["moves"], "run_all": {**earlier["run_all"], **data["run_all"]}}
        RESULTS.write_text(json.dumps({"run": run, **data}, indent=1))
    print("\n" + latency_table(data))


def latency_table(data) -> str:
    """Median and max latency per control of every panel (ms), and Run All per chapter (s)."""
    rows = {}
    for m in data["moves"]:
        if m["latency_ms"] is not None and not m["refused"]:
            rows.setdefault((m["chapter"], m["panel"], m["control"]), []).append(m)
    lines = ["chapter  panel               control                   3-D  moves  median ms  max ms  compute ms"
             "  python ms", "-" * 110]
    for (ch, panel, control), ms in rows.items():
        lat = [m["latency_ms"] for m in ms]
        comp = [m["compute_ms"] for m in ms if m["compute_ms"] is not None] or [float("nan")]
        py = [m["python_ms"] for m in ms if m["python_ms"] is not None] or [float("nan")]
        lines.append(f"{ch:8} {panel:19} {control:25} {'yes' if ms[0]['three_d'] else 'no':4} {len(lat):5d} "
                     f"{statistics.median(lat):10.0f} {max(lat):7.0f} {statistics.median(comp):11.1f}"
                     f" {statistics.median(py):10.1f}")
    lines.append("")
    lines += [f"Run All {name}: {sec:.1f} s" for name, sec in data["run_all"].items()]
    return "\n".join(lines)


# -- what the package computes, to compare the figures with ------------------------------------------------
def _trace(fig, name):
    for t in fig["traces"]:
        if t["name"] == name:
            return t
    raise AssertionError(f"no trace named {name!r} in {[t['name'] for t in fig['traces']]}")


def check_kinematics(values, figs):
    from scara import jacobian, pose

    q = np.array([math.radians(values["theta1"]), math.radians(values["theta2"]), values["d3"],
                  math.radians(values["theta4"])])
    x = pose(q)
    ee = _trace(figs[0], "end effector")
    assert np.allclose([ee["x"][0], ee["y"][0], ee["z"][0]], x[:3], atol=1e-4), (ee, x)
    arm = _trace(figs[0], "arm")
    assert np.allclose([arm["x"][-1], arm["y"][-1], arm["z"][-1]], x[:3], atol=1e-4)
    xr = np.round(x, 3) + 0.0
    assert f"p = ({xr[0]:.3f}, {xr[1]:.3f}, {xr[2]:.3f}) m" in figs[0]["title"], figs[0]["title"]
    det = round(float(np.linalg.det(jacobian(q))), 3) + 0.0
    assert f"det J_A = {det:.3f}" in figs[0]["title"]


def check_inverse_kinematics(values, figs):
    from scara import ikine
    from scara.plots import top_view_arm

    target = np.array([values["px"], values["py"], values["pz"], math.radians(values["phi"])])
    for elbow, name in ((+1, "elbow +1"), (-1, "elbow −1")):
        q = ikine(target, elbow=elbow)
        shown = _trace(figs[0], name)
        expected = top_view_arm(q, name=name)
        assert np.allclose(shown["x"], np.asarray(expected.x, float), atol=1e-4)
        assert np.allclose(shown["y"], np.asarray(expected.y, float), atol=1e-4)
        assert np.allclose([shown["x"][-1], shown["y"][-1]], target[:2], atol=1e-4)
        assert f"{math.degrees(q[1]):.1f}°".replace("-", "−") in figs[0]["title"], figs[0]["title"]


def check_manipulability(values, figs):
    from scara import manipulability, velocity_ellipsoid

    q = np.array([math.radians(values["theta1"]), math.radians(values["theta2"]), 0.5, 0.0])
    assert f"w = {manipulability(q):.3f} m²" in figs[0]["title"], figs[0]["title"]
    v = velocity_ellipsoid(q, rows=(0, 1))
    ell = _trace(figs[0], "velocity ellipse")
    r = np.hypot(np.array(ell["x"]) - v.centre[0], np.array(ell["y"]) - v.centre[1])
    assert math.isclose(r.max(), values["scale"] * v.lengths[0], rel_tol=2e-3, abs_tol=2e-4)


def check_waypoints(values, figs):
    top = figs[0]
    marker = next(t for t in top["traces"] if t["name"].startswith("editing "))
    assert np.allclose([marker["x"][0], marker["y"][0]], [values["x"], values["y"]], atol=1e-5)
    kind = "via point" if values["via"] else "stop point"
    pts = _trace(top, kind)  # every waypoint, a gap (NaN, None from the browser) where it is of the other kind
    assert np.nanmin(np.hypot(np.array(pts["x"], float) - values["x"], np.array(pts["y"], float) - values["y"])) < 1e-5
    # the path passes through a stop point; it rounds a via point
    path = _trace(top, "path")
    gap = np.nanmin(np.hypot(np.array(path["x"], float) - values["x"], np.array(path["y"], float) - values["y"]))
    assert (gap < 1e-4) if not values["via"] else (gap > 1e-5), gap
    assert f"(editing {marker['name'][8:]})" in top["title"]


_CLIK_DECLARATIONS = {}


def _clik_declaration(traj):
    """The CLIK panel as the chapter declares it on ``traj`` (made once per trajectory)."""
    from scara.widgets.clik import clik_declaration

    if id(traj) not in _CLIK_DECLARATIONS:
        _CLIK_DECLARATIONS[id(traj)] = (traj, clik_declaration(traj))
    return _CLIK_DECLARATIONS[id(traj)][1]


def check_clik(values, figs, traj):
    from scara import clik, clik2, second_order_gains
    from scara.widgets.clik import _METHODS

    m = _METHODS[values["method"]]
    K = np.array([values["Kx"], values["Ky"], values["Kz"], values["Kphi"]])
    if m == "second_order":
        r = clik2(traj, *second_order_gains(K), damping=values["damping"])
    elif m == "pseudoinverse":
        r = clik(traj, m, K, damping=values["damping"], relaxed=values["relaxed"], k0=values["k0"])
    elif m == "inverse":
        r = clik(traj, m, K, damping=values["damping"])
    else:  # the transpose solves no linear system: its panel does not read the (greyed-out) damping
        r = clik(traj, m, K)
    mm = r.summary()["max_position_error"] * 1e3
    # the title the panel declares (its template, filled with the dropdown's text and the run's error)
    declared = _clik_declaration(traj)
    assert values["method"] in declared.control("method").values, values["method"]
    expected = declared.page.titles["clik"].format(dict(values, max_ep_mm=mm))
    assert figs[0]["title"] == expected, (figs[0]["title"], expected)


def check_dynamics(values, figs):
    from scara import ScaraParams, inertia

    q = np.array([math.radians(values["theta1"]), math.radians(values["theta2"]), values["d3"],
                  math.radians(values["theta4"])])
    B = inertia(q, ScaraParams().with_payload(values["payload"]))
    shown = _trace(figs[0], "B(q)")
    assert shown["text"] == [f"{v:.3g}" for v in B.ravel()], (shown["text"], B)
    assert f"{values['payload']:g} kg payload at θ2 = {values['theta2']:.0f}°" in figs[0]["title"]


def check_control(values, figs, traj, jref):
    from scara import ScaraParams
    from scara.control import control_summary
    from scara.plots._common import run_label as _label
    from scara.widgets.control import make_controller

    keys = ("K_P", "K_D", "Lambda", "rho", "epsilon", "K_D_scale", "K_pi", "K_I")
    c = make_controller(values["controller"], *(values[k] for k in keys))
    res = c.run(traj, ScaraParams().with_payload(values["payload"]),
                joint_reference=jref if c.reference_kind == "joint" else None)
    s = control_summary(res)
    head = (f"{_label(res)}: max ‖e_p‖ after 1 s {1e3 * s['max_position_error']:.4g} mm, at rest "
            f"{1e3 * s['final_position_error']:.3g} mm<br>peak f3 {s['peak_tau'][2]:.0f} N, chattering {s['chattering']:.3g}")
    assert figs[0]["title"].split(";")[0] == head, (figs[0]["title"], head)


def check_interaction(values, figs):
    from scara.interaction import contact_transition
    from scara.programs.interaction import interaction_run, make_controller

    c = make_controller(values["law"], *(values[k] for k in ("force", "K_z", "D_z", "M_z", "K_F", "K_I")))
    tr = contact_transition(interaction_run(c, values["k_e"], values["force"]))
    head = f"{values['law']}: final −h_z {tr['final_force']:.4g} N"
    assert figs[0]["title"].startswith(head), (figs[0]["title"], head)
    assert f"peak {tr['peak_force']:.4g} N, first touch at {tr['first_touch']:.3f} s" in figs[0]["title"]


# -- the moves, per panel: (control, action, argument); "refuse" moves must be refused --------------------
def _ref():
    from scara import clik2, reference_trajectory

    traj = reference_trajectory()
    return traj, clik2(traj)


KEYS = ["ArrowRight", "ArrowRight", "ArrowLeft"]
PANELS = {
    "01_kinematics.ipynb": [
        dict(name="direct kinematics", three_d=True, check=lambda v, f, ref: check_kinematics(v, f),
             moves=[(c, "key", k) for c in ("θ1 (°)", "θ2 (°)", "d3 (m)", "θ4 (°)") for k in KEYS],
             refuse=None),
        dict(name="inverse kinematics", three_d=False, check=lambda v, f, ref: check_inverse_kinematics(v, f),
             moves=[("p_x (m)", "type", 0.3), ("p_y (m)", "type", 0.1), ("p_z (m)", "type", 0.4),
                    ("phi (°)", "type", 30), ("p_x (m)", "type", 0.25)],
             refuse=[("p_x (m)", "type", 1.2, ("out of reach", "1.200", "r = 1.2")), ("p_x (m)", "type", 0.3, None)]),
    ],
    "02_manipulability.ipynb": [
        dict(name="ellipses", three_d=False, check=lambda v, f, ref: check_manipulability(v, f),
             moves=[(c, "key", k) for c in ("θ1 (°)", "θ2 (°)", "ellipse scale") for k in KEYS],
             refuse=[("ellipse scale", "readout", "0", ("ellipse scale is 0",)), ("ellipse scale", "readout", "0.15", None)]),
    ],
    "03_trajectory.ipynb": [
        dict(name="waypoint editor", three_d=False, check=lambda v, f, ref: check_waypoints(v, f),
             moves=[("waypoint", "select", "p4")] + [(c, "key", k) for c in ("x (m)", "y (m)", "z (m)") for k in KEYS]
             + [("anticipation (s)", "key", "ArrowRight"), ("anticipation (s)", "key", "ArrowLeft"),
                ("via point (do not stop)", "click", None), ("via point (do not stop)", "click", None),
                ("segment", "select", "p5->p6"), ("duration (s)", "key", "ArrowRight"),
                ("duration (s)", "key", "ArrowLeft"), ("waypoint", "select", "p8"), ("x (m)", "key", "ArrowLeft")],
             refuse=[("x (m)", "readout", "0.99", ("waypoint p8", "(x, y, z) = (0.99, 0.2, 0.5) m", "unreachable",
                                                    "r = 1.01")),
                     ("x (m)", "readout", "0.35", None)]),
    ],
    "04_clik.ipynb": [
        dict(name="CLIK", three_d=False, check=lambda v, f, ref: check_clik(v, f, ref[0]),
             moves=[("method", "select", "Jacobian transpose")]
             + [(c, "key", k) for c in ("K_x (1/s)", "K_y (1/s)", "K_z (1/s)", "K_φ (1/s)") for k in KEYS]
             + [("method", "select", "pseudo-inverse + null space"),  # the damping is greyed out for the transpose
                ("damping λ (m)", "key", "ArrowRight"), ("damping λ (m)", "key", "ArrowLeft"),
                ("relaxed (pseudo-inverse)", "select", "y"),
                ("null-space gain k0 (1/s)", "key", "ArrowRight"), ("method", "select", "second order"),
                ("method", "select", "Jacobian inverse")],
             refuse=[("method", "select", "Jacobian transpose", None),
                     ("K_z (1/s)", "readout", "2500", ("K_z = 2500 1/s", "limit")), ("K_z (1/s)", "readout", "400", None)]),
    ],
    "05_dynamics.ipynb": [
        dict(name="inertia matrix", three_d=False, check=lambda v, f, ref: check_dynamics(v, f),
             moves=[(c, "key", k) for c in ("payload m_L (kg)", "θ1 (°)", "θ2 (°)", "d3 (m)", "θ4 (°)", "K_P3 (N/m)")
                    for k in KEYS],
             refuse=[("payload m_L (kg)", "readout", "20", None),
                     ("K_P3 (N/m)", "readout", "100", ("K_P3 = 100 N/m", "stroke")),
                     ("K_P3 (N/m)", "readout", "10000", None),
                     # a number outside the slider's range is refused with the page panel's message, never clamped
                     ("payload m_L (kg)", "readout", "1000",
                      ("payload = 1000 kg is outside the panel's range 0 to 20 kg",)),
                     ("payload m_L (kg)", "readout", "5", None)]),
    ],
    "06_control.ipynb": [
        dict(name="controllers", three_d=False, check=lambda v, f, ref: check_control(v, f, *ref),
             moves=[(c, "key", k) for c in ("true payload m_L (kg)", "K_P (1/s²)", "K_D (1/s)", "Λ (1/s)",
                                             "ρ (m/s²)", "ε (boundary layer)") for k in KEYS[:2]]
             + [("controller", "select", "adaptive (Slotine-Li)"), ("adaptive K_D (× book)", "key", "ArrowRight"),
                ("K_π (weight of m3)", "key", "ArrowRight"), ("Λ (1/s)", "key", "ArrowLeft"),
                ("controller", "select", "operational ID + integral"), ("K_I (1/s³)", "key", "ArrowRight"),
                ("K_I (1/s³)", "key", "ArrowLeft"), ("controller", "select", "operational ID, no integral"),
                ("K_P (1/s²)", "key", "ArrowLeft")],
             refuse=[("controller", "select", "operational ID + integral", None),
                     ("K_I (1/s³)", "readout", "1000000", ("K_I", "Routh")), ("K_I (1/s³)", "readout", "8000", None),
                     ("K_P (1/s²)", "readout", "0", ("K_P = 0 1/s² is outside the panel's range 10 to 100000 1/s²",)),
                     ("K_P (1/s²)", "readout", "900", None)]),
    ],
    "07_interaction.ipynb": [
        dict(name="interaction", three_d=False, check=lambda v, f, ref: check_interaction(v, f),
             moves=[(c, "key", k) for c in ("pressing force (N)", "stiffness along z, K_P / K_Pd (N/m)",
                                             "surface stiffness k_e (N/m)") for k in KEYS[:2]]
             + [("interaction law", "select", "impedance"), ("mass along z, M_d (kg)", "key", "ArrowRight"),
                ("interaction law", "select", "force"), ("force integral gain K_I (m/(N s))", "key", "ArrowLeft"),
                ("interaction law", "select", "compliance")],
             refuse=[("damping along z, K_D / K_Dd (N s/m)", "readout", "50000", ("spectral radius",)),
                     ("damping along z, K_D / K_Dd (N s/m)", "readout", "650", None)]),
    ],
}


def _control(page, panel, desc):
    """The control labelled ``desc``: a slider with its number box (``.scara-slider``), another labelled widget, or a
    check box."""
    exact = re.compile("^" + re.escape(desc) + "$")
    label = page.locator("label.widget-label", has_text=exact)
    box = panel.locator(".scara-slider").filter(has=label)
    if box.count() == 0:
        box = panel.locator(".widget-inline-hbox").filter(has=label)
    if box.count() == 0:
        box = panel.locator(".widget-checkbox").filter(has_text=desc)
    assert box.count() == 1, f"control {desc!r}: {box.count()} matches"
    return box


def _act(page, box, action, arg):
    if action == "key":
        handle = box.locator(".noUi-handle")
        handle.focus()
        page.keyboard.press(arg)
    elif action == "select":
        box.locator("select").select_option(label=arg)
    elif action == "type":
        field = box.locator("input")
        field.fill(str(arg))
        field.press("Enter")
    elif action == "readout":  # a number typed in the box beside a slider, as a person types it
        field = box.locator(".widget-text input")
        assert field.count() == 1, f"no number box beside the slider: {field.count()} matches"
        field.click()
        page.keyboard.press("Control+A")
        page.keyboard.type(str(arg))
        page.keyboard.press("Enter")
    elif action == "click":
        box.locator("input[type=checkbox]").click()
    else:
        raise ValueError(action)


def _is_stale(figs) -> bool:
    return all(f["stale"] and f["title"] == STALE_TITLE and all(t["visible"] is False for t in f["traces"])
               for f in figs)


@pytest.mark.parametrize("chapter", list(PANELS))
def test_live_panels(chapter, lab_url, browser, record):
    lab = lab_driver.Lab(browser, lab_url)
    try:
        lab.open(chapter)
        record["run_all"][chapter] = lab.run_all()
        assert lab.cell_errors() == [], f"{chapter}: cells failed"
        wanted_panels = PANELS[chapter]
        panels = lab.panels()
        assert panels.count() == len(wanted_panels), f"{chapter}: {panels.count()} live panels, expected {len(wanted_panels)}"
        # every figure of a panel's cell is inside the panel
        for k in range(panels.count()):
            cell = panels.nth(k).locator("xpath=ancestor::div[contains(@class, 'jp-Cell')][1]")
            outside = cell.evaluate("(c) => Array.from(c.querySelectorAll('.js-plotly-plot'))"
                                    ".filter(gd => !gd.closest('.scara-panel')).length")
            assert outside == 0, f"{chapter}: a figure shown outside panel {k}"
            assert panels.nth(k).locator(".js-plotly-plot").count() >= 1, f"{chapter}: panel {k} shows no figure"
        ref = _ref() if chapter in ("04_clik.ipynb", "06_control.ipynb") else None
        for k in range(len(wanted_panels)):  # every figure drawn before the redraws are hooked and timed
            panels.nth(k).scroll_into_view_if_needed()
            lab.wait_drawn(panels.nth(k))
        lab.instrument()
        for k, wanted in enumerate(wanted_panels):
            panel = panels.nth(k)
            panel.scroll_into_view_if_needed()
            figs0 = lab.figures(panel)
            wanted["check"](lab.values(panel), figs0, ref)  # the figure as first drawn
            for desc, action, arg in wanted["moves"]:
                _move(lab, panel, wanted, chapter, desc, action, arg, ref, record, refused=False)
            for desc, action, arg, expect in wanted["refuse"] or []:
                _move(lab, panel, wanted, chapter, desc, action, arg, ref, record, refused=expect)
        assert lab.page_errors == [], f"{chapter}: page errors {lab.page_errors[:3]}"
        # none: a reference jupyterlab-myst cannot resolve would log "Cross reference target was not found"
        assert lab.console_errors == [], f"{chapter}: console errors {lab.console_errors[:3]}"
        assert lab.external == [], f"{chapter}: requests outside the server {lab.external[:3]}"
        raw = lab.raw_myst_text()  # the chapter read after Run All: numbers, captions and references as the book's
        assert raw == [], f"{chapter}: {len(raw)} things a reader should not see, the first: {raw[:3]}"
        log = lab.log_console_entries()
        assert log == [], f"{chapter}: {len(log)} entries in the Log Console, the first: {log[0][-3000:]}"
    finally:
        shots = ROOT / "_build" / "screenshots"
        shots.mkdir(parents=True, exist_ok=True)
        try:
            lab.page.screenshot(path=str(shots / f"jupyterlab-{chapter.replace('.ipynb', '')}.png"))
        except Exception:  # noqa: BLE001 - a screenshot is a courtesy, never the failure
            pass
        lab.close()


def _move(lab, panel, wanted, chapter, desc, action, arg, ref, record, refused):
    box = _control(lab.page, panel, desc)
    box.scroll_into_view_if_needed()
    before = lab.state(panel)
    mark = lab.mark()
    _act(lab.page, box, action, arg)
    timing = lab.timing_since(mark, panel, before)
    state = lab.state(panel)
    values = state["values"]
    figs = lab.figures(panel)
    message = lab.message(panel)
    where = f"{chapter} / {wanted['name']} / {desc} {action} {arg}"
    if refused not in (False, None):
        assert message, f"{where}: no message for a refused setting"
        for piece in refused:
            assert piece in message, f"{where}: message {message!r} lacks {piece!r}"
        assert _is_stale(figs), f"{where}: the figures are not marked stale: {[f['title'] for f in figs]}"
    else:
        assert message == "", f"{where}: unexpected message {message!r}"
        assert not any(f["stale"] for f in figs), f"{where}: figure still marked stale"
        wanted["check"](values, figs, ref)
    record["moves"].append(dict(chapter=chapter[:2], panel=wanted["name"], control=desc, action=action,
                                three_d=wanted["three_d"], refused=refused not in (False, None),
                                latency_ms=timing["latency_ms"], redraws=timing["redraws"],
                                compute_ms=state.get("compute_ms"), python_ms=sum(state.get(k, 0.0) for k in
                                                                                 ("compute_ms", "draw_ms", "send_ms"))))
    # one move, at most one redraw of each figure
    assert timing["redraws"] <= len(figs), f"{where}: {timing['redraws']} redraws for {len(figs)} figures"
