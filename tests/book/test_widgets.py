"""The live panels' machinery, from Python: one figure widget per figure, built once; a move sends one update
per figure holding only what changed; a refused setting shows its message and marks the figures stale; the
panels never clamp what they are given and speak their own units. (``test_jupyterlab.py`` checks the same in a
real JupyterLab.)"""
from __future__ import annotations

import math

import numpy as np
import pytest

pytest.importorskip("ipywidgets")

import plotly.graph_objects as go  # noqa: E402

from scara import ScaraError, ScaraParams, pose  # noqa: E402
from scara.widgets import (  # noqa: E402
    clik_panel, control_panel, dynamics_panel, interaction_panel, inverse_kinematics_panel, kinematics_panel,
    manipulability_panel, waypoint_editor,
)
from scara.widgets._common import STALE_TITLE, NumberSlider, _delta, _same, readable  # noqa: E402


class Spy:
    """Records the update messages a FigureWidget sends to the browser."""

    def __init__(self, fw):
        self.messages = []
        original = fw._send_update_msg

        def send(restyle_data, relayout_data, trace_indexes=None, source_view_id=None):
            self.messages.append((restyle_data, relayout_data, trace_indexes))
            return original(restyle_data, relayout_data, trace_indexes, source_view_id)

        fw._send_update_msg = send


def _widgets(w):
    yield w
    for child in getattr(w, "children", ()):
        yield from _widgets(child)


def test_figures_are_widgets_inside_the_panel_built_once():
    panel = kinematics_panel()
    assert all(isinstance(fw, go.FigureWidget) for fw in panel.figures) and len(panel.figures) == 1
    inside = [w for w in _widgets(panel.widget) if isinstance(w, go.FigureWidget)]
    assert inside == panel.figures
    fw = panel.figures[0]
    panel.controls["theta1"].value = 25.0
    assert panel.figures[0] is fw  # the same widget, updated in place


def test_one_move_sends_one_update_with_only_what_changed():
    panel = kinematics_panel()
    spy = Spy(panel.figures[0])
    panel.controls["theta2"].value = 30.0
    assert len(spy.messages) == 1
    restyle, relayout, _ = spy.messages[0]
    assert set(relayout) == {"title"}  # the title states the new pose; nothing else of the layout moved
    assert "x" in restyle and "y" in restyle and "line" not in restyle and "name" not in restyle
    # the figure now shows what the package computes for the sliders' q
    q = np.radians([0.0, 30.0, 0.0, 0.0]) + np.array([0.0, 0.0, panel.controls["d3"].value, 0.0])
    ee = panel.figures[0].data[1]
    np.testing.assert_allclose([ee.x[0], ee.y[0], ee.z[0]], pose(q)[:3], atol=1e-4)
    # a move that changes nothing the figure shows sends nothing
    panel.update()
    assert len(spy.messages) == 1


def test_template_is_sent_once():
    panel = manipulability_panel()
    assert panel.figures[0].layout.template.layout.plot_bgcolor is not None
    spy = Spy(panel.figures[0])
    panel.controls["theta1"].value = 40.0
    assert "template" not in spy.messages[0][1]
    assert panel.figures[0].layout.template.layout.plot_bgcolor is not None


def test_refused_setting_marks_figures_stale_and_recovers():
    panel = inverse_kinematics_panel()
    fw = panel.figures[0]
    before = [tuple(t.x) for t in fw.data]
    panel.controls["px"].value = 1.2
    assert panel.last_error and "out of reach" in panel.last_error
    assert "Cannot show this setting" in panel.message.value
    assert fw.layout.title.text == STALE_TITLE and all(t.visible is False for t in fw.data)
    assert "scara-stale" in panel._boxes[0]._dom_classes
    assert "scara-panel-values" in panel.info.value and panel.info.value.count("<tr>") == 0  # no stale table
    panel.controls["px"].value = 0.18
    assert panel.last_error is None and panel.message.value == ""
    assert all(t.visible is not False for t in fw.data) and fw.layout.title.text != STALE_TITLE
    assert "scara-stale" not in panel._boxes[0]._dom_classes
    assert [tuple(t.x) for t in fw.data] == before


def test_hold_recomputes_once():
    panel = kinematics_panel()
    calls = []
    compute = panel.compute
    panel.compute = lambda v: calls.append(v) or compute(v)
    with panel.hold():
        panel.controls["theta1"].value = 10.0
        panel.controls["theta2"].value = 20.0
    assert len(calls) == 1 and calls[0]["theta1"] == 10.0 and calls[0]["theta2"] == 20.0


def test_waypoint_pick_redraws_once_and_highlights_the_point():
    ed = waypoint_editor()
    spies = [Spy(fw) for fw in ed.panel.figures]
    ed.panel.controls["point"].value = 7
    assert sum(len(s.messages) for s in spies) == 1  # the top view moves its marker; the profiles stay
    c = ed.panel.controls
    assert (c["x"].value, c["y"].value, c["z"].value) == (0.70, 0.15, 0.3)
    marker = ed.panel.figures[0].data[-1]
    assert marker.name == "editing p7" and (marker.x[0], marker.y[0]) == (0.70, 0.15)


@pytest.mark.parametrize("n", [2, 3])
def test_waypoint_editor_opens_on_any_valid_plan(n):
    pts = [(0.3, 0.2, 0.5), (0.5, 0.2, 0.5), (0.5, 0.4, 0.4)][:n]
    ed = waypoint_editor(dict(waypoints=pts, durations=[2.0] * (n - 1)))
    assert ed.panel.last_error is None
    c = ed.panel.controls
    c["duration"].value = 3.0
    assert ed.panel.last_error is None and ed.trajectory.durations[c["segment"].value] == 3.0
    c["x"].value = 0.99  # out of reach: refused, then usable again
    assert "unreachable" in ed.panel.last_error
    c["x"].value = 0.35
    assert ed.panel.last_error is None


@pytest.mark.parametrize("n", [2, 3])
def test_waypoint_editor_recovers_after_a_refused_edit_on_a_short_reference_plan(n):
    """A plan as ``reference_plan()`` returns it, cut to ``n`` waypoints: the editor opens, refuses an
    unreachable move, and after moving back and picking another waypoint and segment every figure is current
    (titles, traces shown, not greyed out), including after a second refusal."""
    from scara import reference_plan

    ref = reference_plan()
    plan = dict(ref, waypoints=ref["waypoints"][:n], durations=ref["durations"][:n - 1], arcs={})
    ed = waypoint_editor(plan)
    c, panel = ed.panel.controls, ed.panel
    assert len(c["segment"].options) == n - 1 and panel.last_error is None

    def current():
        assert panel.last_error is None and panel.message.value == ""
        for fw, box in zip(panel.figures, panel._boxes):
            assert fw.layout.title.text != STALE_TITLE
            assert all(t.visible is not False for t in fw.data)
            assert "scara-stale" not in box._dom_classes

    for _ in range(2):  # twice: the second refusal must not leave a figure stuck stale
        c["point"].value = n - 1
        x0 = c["x"].value
        c["x"].value = 0.99
        assert panel.last_error and "unreachable" in panel.last_error
        c["x"].value = x0
        current()
        c["x"].value = 0.99
        c["point"].value = 0
        c["segment"].value = n - 2
        c["duration"].value = 3.0
        current()
        assert ed.trajectory.durations[n - 2] == 3.0
        assert panel.figures[0].data[-1].name == "editing p0"


@pytest.mark.parametrize("plan, text", [
    ([1, 2], "plan must be a dict"),
    (dict(waypoints=5, durations=[1.0]), "plan['waypoints'] must be a list"),
    (dict(waypoints=[(0.3, 0.2, 0.5), (0.4, 0.2, 0.5)], durations="ab"), "plan['durations'] must be a list"),
    (dict(waypoints=[(0.3, 0.2, 0.5), (0.4, 0.2, 0.5)], durations=["1"]), "duration of segment 0 must be a number (in s), got '1'"),
    (dict(waypoints=[(0.3, 0.2, 0.5), (0.4, 0.2, 0.5)], durations=[1.0], speed=2), "unknown keys ['speed']"),
])
def test_waypoint_editor_refuses_a_malformed_plan_with_a_scara_error(plan, text):
    with pytest.raises(ScaraError) as info:
        waypoint_editor(plan)
    assert text in str(info.value)


def test_panels_never_clamp_their_start_values():
    with pytest.raises(ScaraError, match="d3 = 5"):
        kinematics_panel(q=[0.0, 0.0, 5.0, 0.0])
    with pytest.raises(ScaraError, match="payload = -1"):
        control_panel(payload=-1.0)
    with pytest.raises(ScaraError, match="payload = 1e"):
        dynamics_panel(payload=1e6)
    with pytest.raises(ScaraError, match="theta2 = 400"):
        manipulability_panel(theta2=math.radians(400.0))
    with pytest.raises(ScaraError):
        inverse_kinematics_panel(x=[1.5, 0.0, 0.5, 0.0])


@pytest.mark.parametrize("build, kwargs, names", [
    (control_panel, dict(payload=-1.0), ("payload = -1 kg", "0 to 10 kg")),
    (control_panel, dict(payload=1e6), ("payload = 1e+06 kg", "0 to 10 kg")),
    (kinematics_panel, dict(q=[0.0, 0.0, 5.0, 0.0]), ("d3 = 5 m", "stroke d3_min to d3_max = 0 to 1 m")),
    (dynamics_panel, dict(q=(0.0, 0.0, -0.1, 0.0)), ("d3 = -0.1 m", "stroke d3_min to d3_max = 0 to 1 m")),
    (dynamics_panel, dict(payload=25.0), ("payload = 25 kg", "0 to 20 kg")),
    (dynamics_panel, dict(K_P3=50.0), ("K_P3 = 50 N/m", "100 to 1e+06 N/m")),
    (manipulability_panel, dict(scale=0.9), ("scale = 0.9", "0 to 0.5")),
    (manipulability_panel, dict(theta1=math.radians(-200.0)), ("theta1 = -200°", "-180 to 180°")),
])
def test_panels_refuse_start_values_outside_their_sliders_range(build, kwargs, names):
    with pytest.raises(ScaraError) as info:
        build(**kwargs)
    for text in names:
        assert text in str(info.value)


def test_panels_use_the_quills_stroke_from_the_params():
    short = ScaraParams().replace(d3_min=0.1, d3_max=0.6)
    panel = kinematics_panel(p=short)
    d3 = panel.controls["d3"]
    assert (d3.min, d3.max) == (0.1, 0.6) and d3.value == pytest.approx(0.35)
    with pytest.raises(ScaraError, match=r"d3 = 0.8 m is outside the quill's stroke d3_min to d3_max = 0.1 to 0.6 m"):
        kinematics_panel(q=[0.0, 0.0, 0.8, 0.0], p=short)
    with pytest.raises(ScaraError, match=r"d3 = 0.05 m .* 0.1 to 0.6 m"):
        dynamics_panel(q=(0.0, 0.0, 0.05, 0.0), p=short)


@pytest.mark.parametrize("build, kwargs, names", [
    (control_panel, dict(payload="5"), ("payload must be a number (in kg)", "got '5'")),
    (control_panel, dict(payload=[5.0]), ("payload must be a number (in kg)", "got [5.0]")),
    (control_panel, dict(traj="ref"), ("traj must be a Trajectory", "got str 'ref'")),
    (dynamics_panel, dict(payload=True), ("payload must be a number (in kg)", "got True")),
    (dynamics_panel, dict(K_P3="1e4"), ("K_P3 must be a number (in N/m)", "got '1e4'")),
    (manipulability_panel, dict(theta1="0"), ("theta1 must be a number (in rad)", "got '0'")),
    (manipulability_panel, dict(theta2=[1.0]), ("theta2 must be a number (in rad)", "got [1.0]")),
    (kinematics_panel, dict(q=[0.0, 0.0, 0.5]), ("q must have shape (4,)", "got (3,)")),
    (kinematics_panel, dict(q="abcd"), ("q must be an array of numbers", "'abcd'")),
    (inverse_kinematics_panel, dict(x=[0.3, 0.2]), ("x must have shape (4,)", "got (2,)")),
    (clik_panel, dict(traj=[1, 2]), ("traj must be a Trajectory", "got list [1, 2]")),
    (waypoint_editor, dict(profiles="yes"), ("profiles = 'yes' must be True or False", "got str")),
])
def test_panels_refuse_start_values_of_the_wrong_type(build, kwargs, names):
    with pytest.raises(ScaraError) as info:
        build(**kwargs)
    for text in names:
        assert text in str(info.value)


@pytest.mark.parametrize("build", [clik_panel, control_panel, interaction_panel])
@pytest.mark.parametrize("points, names", [
    (10**6, ("points = 1000000", "2 <= points <= 10000")),
    (0, ("points = 0", "2 <= points <= 10000")),
    (2.5, ("points = 2.5", "whole number", "between 2 and 10000")),
])
def test_panels_refuse_a_number_of_samples_beyond_the_limit_before_any_run(build, points, names):
    calls = []
    import scara.trajectory as st

    original = st.reference_trajectory
    st.reference_trajectory = lambda *a, **k: calls.append(1) or original(*a, **k)
    try:
        with pytest.raises(ScaraError) as info:
            build(points=points)
    finally:
        st.reference_trajectory = original
    for text in names:
        assert text in str(info.value)
    assert not calls  # refused before the 70 s reference was even built


def test_messages_in_the_panels_units():
    assert readable("waypoint p8 x = [0.99 0.2  0.5 ] is unreachable") == \
        "waypoint p8 (x, y, z) = (0.99, 0.2, 0.5) m is unreachable"
    assert "φ = 90°" in readable(f"its point x = [0.7 0.15 0.3 {math.pi / 2}] is unreachable")
    panel = inverse_kinematics_panel()
    panel.controls["phi"].value = 45.0
    panel.controls["pz"].value = 1.5
    assert "φ = 45.0°" in panel.last_error and "d3 = d0 − z = -0.500 m" in panel.last_error
    # a singular arm: the force ellipse is unbounded, said in words, not as 1e18 N
    m = manipulability_panel()
    m.controls["theta2"].value = 0.0
    assert m.last_error is None and "unbounded" in m.info.value and "singular" in m.notes.value
    assert "e+1" not in m.info.value
    # a weak quill gain: the sag is flagged; past the stroke the setting is refused
    d = dynamics_panel()
    d.controls["K_P3"].value = 1e4
    d.controls["payload"].value = 20.0
    assert "19.6 mm" in d.notes.value
    d.controls["K_P3"].value = 100.0
    assert "stroke" in d.last_error and "K_P3 = 100 N/m" in d.last_error


def test_clik_refusal_names_the_gains():
    from scara import reference_trajectory

    panel = clik_panel(reference_trajectory())
    panel.controls["Kz"].value = 2500.0
    assert "K_z = 2500 1/s" in panel.last_error and "limit" in panel.last_error
    assert panel.figures[0].layout.title.text == STALE_TITLE


def test_diff_helpers():
    a = np.array([1.0, np.nan])
    assert _same(a, a.copy()) and not _same(a, np.array([1.0, 2.0])) and _same({"x": [1, 2]}, {"x": (1, 2)})
    assert _delta({"a": 1, "b": 2}, {"a": 1, "c": 3}) == {"c": 3, "b": None}
    # an unchanged array (NaN gaps included) is not sent again; a property the new figure drops is reset
    assert _delta({"template": 1, "x": a}, {"x": a.copy()}) == {"template": None}


def test_panels_use_the_robot_they_are_given():
    long = ScaraParams().replace(a1=0.6)
    panel = kinematics_panel(p=long)
    ee = panel.figures[0].data[1]
    q = panel.state["q"]
    np.testing.assert_allclose([ee.x[0], ee.y[0]], pose(q, long)[:2], atol=1e-4)


def _same_data(state, fig_json, traces=None):
    from scara.widgets._common import _widget_safe

    full = _widget_safe(fig_json)
    for i, (a, b) in enumerate(zip(state["data"], full["data"])):
        if traces is not None and i not in traces:
            continue
        for key in ("x", "y", "name", "text"):
            assert _same(a.get(key), b.get(key)), (i, key)


def _package_run(values, traj, jref):
    """The run and summary the package's own API gives for the controllers panel's settings ``values``. The panel's
    program solves the robust law's Lyapunov equation in closed form (scipy's solve agrees to about 1e-12): the
    controller is given that solution, so that both runs are the same arithmetic."""
    from scara import ScaraParams
    from scara.control import control_summary
    from scara.control.robust import sliding_rows
    from scara.widgets.control import make_controller

    keys = ("K_P", "K_D", "Lambda", "rho", "epsilon", "K_D_scale", "K_pi", "K_I", "omega")
    ctl = make_controller(values["controller"], *(values[k] for k in keys))
    if ctl.name == "robust":
        Z = np.empty(32)
        sliding_rows(ctl.K_P, ctl.K_D, ctl.Lambda, Z)
        ctl.sliding = Z.reshape(4, 8)
    res = ctl.run(traj, ScaraParams().with_payload(values["payload"]),
                  joint_reference=jref if ctl.reference_kind == "joint" else None)
    return res, control_summary(res)


def test_fast_redraws_equal_full_figures():
    """After the first draw the panels send only new data and titles (no layout rebuilt): what they show
    must equal the figure the builder draws from scratch for the same run."""
    from scara import clik2, reference_trajectory
    from scara.plots.control import tuning_figure
    from scara.plots.trajectory import profiles_figure, top_view_figure

    traj = reference_trajectory()
    jref = clik2(traj)
    c = control_panel(traj)
    c.controls["K_P"].value = 1500.0
    res, summary = _package_run(c.values(), traj, jref)   # the same run by the package's own API
    full = tuning_figure(res, summary, "x", points=600)
    _same_data(c._states[0], full.to_plotly_json())
    _same_data(c._states[0], c.declaration.figures[0].build(c.state).to_plotly_json())
    assert c.figures[0].layout.title.text.split("<br>")[0] == full.layout.title.text.split("<br>")[0]
    for name in ("adaptive (Slotine-Li)", "operational ID, no integral", "robust"):  # another law, same figure
        c.controls["controller"].value = name
        res, summary = _package_run(c.values(), traj, jref)
        full = tuning_figure(res, summary, "x", points=600).to_plotly_json()
        _same_data(c._states[0], full)
        built = c.declaration.figures[0].build(c.state).to_plotly_json()
        _same_data(c._states[0], built)
        for t, f, b in zip(c._states[0]["data"], full["data"], built["data"]):
            assert t["line"]["color"] == f["line"]["color"] == b["line"]["color"]
            assert t.get("visible", True) == f.get("visible", True) == b.get("visible", True)
        for axis in ("yaxis4", "yaxis5", "yaxis6"):   # the run's own signal, on its own axis
            shown = c._states[0]["layout"][axis]
            assert shown.get("type", "linear") == full["layout"][axis].get("type", "linear")
            assert shown["title"] == full["layout"][axis]["title"] and shown["visible"] == built["layout"][axis]["visible"]
            assert shown["visible"] == full["layout"][axis]["visible"]

    # the waypoint editor: its figures are drawn from its program's outputs (float64, every waypoint in both the
    # stop and the via trace, NaN where a point is of the other kind), so after each move what it shows must be
    # the full rebuild from the same values: every trace property, the title and the shapes (the profiles' bands)
    from scara.widgets._common import _widget_safe

    ed = waypoint_editor()
    c = ed.panel.controls
    for key, value in (("x", 0.08), ("duration", 4.0), ("point", 7), ("via", True), ("y", 0.1)):
        c[key].value = value
        assert ed.panel.last_error is None, (key, ed.panel.last_error)
        assert len(ed.panel._states) == len(ed.panel.declaration.figures) == 2
        for state, pair in zip(ed.panel._states, ed.panel.declaration.figures):
            full = _widget_safe(pair.build(ed.panel.state).to_plotly_json())
            assert len(state["data"]) == len(full["data"]), (key, pair.role)
            for i, (a, b) in enumerate(zip(state["data"], full["data"])):
                assert a.keys() == b.keys() and all(_same(a[p], b[p]) for p in b), (key, pair.role, i)
            assert state["layout"]["title"]["text"] == full["layout"]["title"]["text"], (key, pair.role)
            assert _same(state["layout"].get("shapes"), full["layout"].get("shapes")), (key, pair.role)
    # and what it shows is the plan the package's planner gives for the edited waypoints: the bands shown are
    # those of profiles_figure, the arm and the waypoints those of top_view_figure (which rounds to 0.1 mm)
    traj2 = ed.trajectory
    shown = [{k: v for k, v in s.items() if k != "visible"} for s in ed.panel._states[1]["layout"]["shapes"]
             if s.get("visible", True)]
    assert _same(shown, _widget_safe(profiles_figure(traj2).to_plotly_json())["layout"]["shapes"])
    top = _widget_safe(top_view_figure(traj2).to_plotly_json())["data"]
    drawn = {t["name"]: t for t in ed.panel._states[0]["data"]}
    for t in top:
        if t["name"] in ("arm at t = 0", "stop point", "via point"):
            for axis in ("x", "y"):
                xs = np.array(drawn[t["name"]][axis], float)
                np.testing.assert_allclose(xs[np.isfinite(xs)], np.array(t[axis], float), atol=1e-4)

    k = clik_panel(traj)
    first = k._states[0]["data"][0]["y"].copy()
    k.controls["Kx"].value = 600.0
    from scara import clik
    from scara.plots.clik import envelope

    r = clik(traj, "inverse", [600.0, 400.0, 400.0, 100.0])  # the run the panel's program made
    assert not _same(first, k._states[0]["data"][0]["y"])
    assert _same(k._states[0]["data"][0]["y"], envelope(r.t, r.position_error, 800)[1].astype(float))
    k.controls["method"].value = "Jacobian transpose"
    shown = [t for t in k._states[0]["data"] if t.get("visible") is not False]  # a trace per method, one shown
    assert len(shown) == 3 and shown[0]["name"] == "Jacobian transpose"
    assert shown[0]["line"]["color"] == shown[2]["line"]["color"] != "#0072B2"


def _moves():
    """Each panel, with one move of its controls (and, for the panels with a selector, a change of choice)."""
    from scara import reference_trajectory

    traj = reference_trajectory()
    return [
        ("direct kinematics", lambda: kinematics_panel(), dict(theta1=25.0, d3=0.3)),
        ("inverse kinematics", lambda: inverse_kinematics_panel(), dict(px=0.3, phi=30.0)),
        ("ellipses", lambda: manipulability_panel(), dict(theta2=30.0, scale=0.2)),
        ("waypoint editor", lambda: waypoint_editor().panel, dict(x=0.08, duration=4.0)),
        ("CLIK", lambda: clik_panel(traj), dict(Kx=600.0)),
        ("CLIK", lambda: clik_panel(traj), dict(method="pseudo-inverse + null space", relaxed="y")),
        ("inertia matrix", lambda: dynamics_panel(), dict(payload=10.0, theta2=30.0)),
        ("controllers", lambda: control_panel(traj), dict(K_P=1500.0)),
        ("controllers", lambda: control_panel(traj), dict(controller="adaptive (Slotine-Li)")),
        ("interaction", lambda: interaction_panel(), dict(force=20.0, k_e=5e4)),
        ("interaction", lambda: interaction_panel(), dict(law="force", K_I=1e-3)),
    ]


@pytest.mark.parametrize("name, build, move", _moves(), ids=lambda v: v if isinstance(v, str) else "")
def test_panels_are_built_from_their_declaration(name, build, move):
    """The ipywidgets match the declared controls (names, labels, kinds, ranges, steps, scales, defaults,
    choices), and each figure pair's update, applied to the builder's figure of the default state, gives the
    builder's figure of the moved state (every trace property and the title)."""
    import ipywidgets as ipw

    from scara.plots.panels import apply_update
    from scara.widgets._common import _widget_safe

    panel = build()
    d = panel.declaration
    assert d.name == name and list(panel.controls) == [c.name for c in d.controls]
    for c in d.controls:
        w = panel.controls[c.name]
        assert w.description == c.label and (c.unit in c.label or c.name == "scale"), c
        if c.kind == "slider":  # a slider without its (clamping) readout and a number box beside it
            assert type(w) is NumberSlider and (w.min, w.max, w.step, w.value) == (c.low, c.high, c.step, c.default)
            s = w.slider
            if c.scale == "log":
                assert type(s) is ipw.FloatLogSlider and s.base == 10 and s.step == c.step
                assert (s.min, s.max) == pytest.approx((math.log10(c.low), math.log10(c.high)), abs=1e-12)
                assert s.value == pytest.approx(c.default, rel=1e-12)
            else:
                assert type(s) is ipw.FloatSlider and (s.min, s.max, s.step, s.value) == (c.low, c.high, c.step,
                                                                                          c.default)
            assert s.readout is False and s.description == c.label and s.continuous_update is False
            assert type(w.box) is ipw.FloatText and w.box.value == float(f"{c.default:.6g}")
            assert s.disabled == w.box.disabled == w.disabled
        elif c.kind == "dropdown":
            assert type(w) is ipw.Dropdown and w.value == c.default
            assert tuple(o[1] if isinstance(o, tuple) else o for o in w.options) == c.values
        elif c.kind == "number":
            assert type(w) is ipw.FloatText and (w.value, w.step) == (c.default, c.step)
        else:
            assert type(w) is ipw.Checkbox and w.value == c.default
        assert w.disabled == (not d.applies(c, d.defaults()))

    start = d.compute(d.defaults())
    first = [_widget_safe(pair.build(start).to_plotly_json()) for pair in d.figures]
    moved = d.compute(dict(d.defaults(), **move))
    for pair, fig in zip(d.figures, first):
        applied = apply_update(fig, _widget_safe(pair.updated(moved)), pair)
        full = _widget_safe(pair.build(moved).to_plotly_json())
        assert len(applied["data"]) == len(full["data"])
        for i, (a, b) in enumerate(zip(applied["data"], full["data"])):
            for key in b:
                assert _same(a.get(key), b[key]), (pair.role, i, key)
        assert applied["layout"]["title"]["text"] == full["layout"]["title"]["text"]
    # the same move through the widgets shows the same figures
    with panel.hold():
        for key, value in move.items():
            panel.controls[key].value = value
    assert panel.last_error is None
    for pair, state in zip(d.figures, panel._states):
        full = _widget_safe(pair.build(panel.state).to_plotly_json())
        for a, b in zip(state["data"], full["data"]):
            for key in ("x", "y", "z", "name", "text"):
                assert _same(a.get(key), b.get(key)), (pair.role, key)
