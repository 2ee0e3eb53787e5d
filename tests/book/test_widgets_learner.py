"""Panels that take the reader's own work, from Python: a number typed beside a slider outside its range is refused
with the page panel's message (never clamped) and a valid one restores the figures; the controllers panel runs a
controller of the reader's own (a class or a factory, given the panel's gains) by ``scara.simulate`` and draws it
with the same kernel as its own seven, and refuses one that fails with a message in the panel; the waypoint
editor's plan runs in the controllers panel; ``keep=True`` starts a panel from the last accepted settings of the
previous one. (``test_jupyterlab.py`` types out-of-range values in a real JupyterLab.)"""
from __future__ import annotations

import html
import json
import math
import re

import numpy as np
import pytest

pytest.importorskip("ipywidgets")

from scara import (  # noqa: E402
    Controller, OperationalSpaceController, ScaraError, ScaraParams, clik2, control_law, plan_path, simulate,
)
from scara._compile import ArrayLayout  # noqa: E402
from scara.control import control_summary  # noqa: E402
from scara.dynamics import gravity_kernel  # noqa: E402
from scara.plots.control import TUNING_CONTROLLERS, tuning_figure  # noqa: E402
from scara.plots.panels import range_template  # noqa: E402
from scara.widgets import (  # noqa: E402
    clik_panel, control_panel, dynamics_panel, interaction_panel, inverse_kinematics_panel, kinematics_panel,
    manipulability_panel, waypoint_editor,
)
from scara.widgets._common import REFUSED, STALE_TITLE, NumberSlider, _same, _widget_safe  # noqa: E402
from scara.widgets.control import OWN_GAINS, PER_JOINT, make_controller, own_gains  # noqa: E402

P5 = ScaraParams().with_payload(5.0)


# --------------------------------------------------------------------------------------------------
# a controller of the reader's own, written as the package page shows: PD plus gravity compensation
# --------------------------------------------------------------------------------------------------
def pd_gravity_law(k, t, dt, q, qd, ref, gains, model, state, work, signals, tau):
    g = work[0]                      # the one scratch row (work_rows = 1)
    gravity_kernel(q, model, g)      # g_hat(q) from the controller's own model
    for i in range(4):
        tau[i] = gains[i] * (ref[i] - q[i]) + gains[4 + i] * (ref[4 + i] - qd[i]) + g[i]
    signals[0] = g[2]
    return 0


class MyPDGravity(Controller):
    """The package page's worked example, in plain Python (its law not compiled)."""

    law = staticmethod(pd_gravity_law)
    name = "my_pd_gravity"
    reference_kind = "joint"
    signal_names = ("gravity_compensation",)
    work_rows = 1

    def __init__(self, K_P=(10000.0, 4000.0, 10000.0, 600.0), K_D=(1000.0, 400.0, 1000.0, 60.0), model=None):
        self.K_P, self.K_D = np.asarray(K_P, float), np.asarray(K_D, float)
        self.model = model or ScaraParams()

    def gains_array(self):
        return np.concatenate([self.K_P, self.K_D])


class MyCompiledPDGravity(MyPDGravity):
    """The same, its law compiled by ``control_law``."""

    law = staticmethod(control_law(pd_gravity_law))


@pytest.fixture(scope="module")
def short():
    """A 2.5 s plan (a move of the quill down and a stop): short enough for a law in plain Python."""
    return plan_path([[0.18, 0.20, 0.5], [0.14, 0.20, 0.5], [0.10, 0.20, 0.3]], durations=[1.0, 1.0], total=2.5)


def _stale(panel) -> bool:
    return (panel.last_error is not None and all(fw.layout.title.text == STALE_TITLE for fw in panel.figures)
            and all(t.visible is False for fw in panel.figures for t in fw.data)
            and all("scara-stale" in box._dom_classes for box in panel._boxes))


def _current(panel) -> bool:
    return (panel.last_error is None and panel.message.value == ""
            and not any(fw.layout.title.text == STALE_TITLE for fw in panel.figures)
            and not any("scara-stale" in box._dom_classes for box in panel._boxes))


def _shown_values(panel) -> dict:
    """The values the panel's hidden record says its figures were computed for (what a browser test reads)."""
    text = re.search(r"<span hidden class='scara-panel-values'>(.*)</span>", panel.info.value).group(1)
    return json.loads(text.replace("&quot;", '"').replace("&#x27;", "'").replace("&amp;", "&"))["values"]


# --------------------------------------------------------------------------------------------------
# 1. a typed value outside a slider's range: refused with the page panel's message, never clamped
# --------------------------------------------------------------------------------------------------
def test_a_number_typed_outside_the_range_is_refused_not_clamped_and_a_valid_one_restores():
    panel = dynamics_panel()
    w = panel.controls["payload"]
    assert isinstance(w, NumberSlider) and w.slider.readout is False   # the readout that clamps is not shown
    before = [_widget_safe(fw.to_plotly_json())["data"] for fw in panel.figures]
    w.box.value = 1000.0                        # typed in the box beside the slider (as the browser sends it)
    expected = range_template("payload", 0.0, 20.0, "kg").format(value=1000.0)
    assert expected == "payload = 1000 kg is outside the panel's range 0 to 20 kg"
    assert panel.last_error == expected and panel.message.value == f"<b>{REFUSED}</b> {html.escape(expected)}"
    assert _stale(panel)
    assert w.value == 1000.0 and w.slider.value == 5.0        # the panel's value as typed; the slider left alone
    assert _shown_values(panel)["payload"] == 1000.0
    assert panel.accepted["payload"] == 5.0
    w.box.value = 7.5                           # a valid value: the slider follows, the figures come back
    assert _current(panel) and w.value == w.slider.value == 7.5
    w.box.value = 5.0
    assert _current(panel)
    after = [_widget_safe(fw.to_plotly_json())["data"] for fw in panel.figures]
    assert all(_same(a.get("text"), b.get("text")) for a, b in zip(before[0], after[0]))
    # the slider moved: the box shows its value; from Python the value is the panel's, refused out of range too
    w.slider.value = 12.0
    assert w.value == 12.0 and w.box.value == 12.0 and _current(panel)
    w.value = -1.0
    assert panel.last_error == "payload = -1 kg is outside the panel's range 0 to 20 kg" and w.slider.value == 12.0
    assert w.box.value == -1.0
    w.value = 12.0
    assert _current(panel) and w.slider.value == 12.0


def test_a_log_slider_refuses_a_gain_typed_below_its_range():
    panel = control_panel()
    w = panel.controls["K_P"]
    w.box.value = 0.0
    assert panel.last_error == "K_P = 0 1/s² is outside the panel's range 10 to 100000 1/s²"
    assert _stale(panel) and w.value == 0.0 and w.slider.value == pytest.approx(900.0)
    w.box.value = 1500.0
    assert _current(panel) and w.slider.value == pytest.approx(1500.0) and panel.state["K_P"] == 1500.0
    # a position of the slider is a value of 6 significant digits: the box shows the number the panel uses
    w.slider.value = 10 ** (math.log10(1500.0) + 0.01)
    assert w.value == float(f"{w.slider.value:.6g}") == w.box.value == panel.state["K_P"] == 1534.94
    # a typed or a Python value is taken as it is
    w.value = 1234.56789
    assert panel.state["K_P"] == 1234.56789 and w.box.value == 1234.57 and w.slider.value == pytest.approx(1234.56789)


def test_a_slider_at_the_end_of_its_range_is_never_refused():
    """A position of the slider is its value to 6 significant digits, unless that would leave the range: a slider
    pushed to its end (1.23456789 s, which rounds up past it) gives the end itself, never a refusal."""
    from scara.plots.panels import Control

    for c in (Control("d", "slider", "d (s)", 1.0, 0.1, 1.23456789, 0.01, unit="s"),
              Control("k", "slider", "k (1/s)", 10.0, 1.23456789, 98.7654321, 0.01, scale="log", unit="1/s")):
        w = NumberSlider(c)
        ends = (w.slider.min, w.slider.max) if c.scale == "linear" else (10 ** w.slider.min, 10 ** w.slider.max)
        w.slider.value = ends[1]
        assert w.value == pytest.approx(c.high, rel=5e-6) and w.in_range(w.value), c.name
        if c.scale == "linear":
            assert w.value == c.high
        w.slider.value = ends[0]
        assert w.value == pytest.approx(c.low, rel=5e-6) and w.in_range(w.value), c.name


def test_greying_disables_both_parts_of_a_slider():
    panel = control_panel()
    panel.controls["controller"].value = "adaptive (Slotine-Li)"
    k = panel.controls["K_P"]
    assert k.disabled and k.slider.disabled and k.box.disabled
    panel.controls["controller"].value = "robust"
    assert not (k.disabled or k.slider.disabled or k.box.disabled)


def _panels():
    return [("direct kinematics", kinematics_panel), ("ellipses", manipulability_panel),
            ("inertia matrix", dynamics_panel), ("waypoint editor", lambda: waypoint_editor().panel),
            ("CLIK", clik_panel), ("controllers", control_panel), ("interaction", interaction_panel)]


@pytest.mark.parametrize("name, build", _panels(), ids=[n for n, _ in _panels()])
def test_every_slider_refuses_a_value_outside_its_range_with_the_page_panels_message(name, build):
    panel = build()
    assert panel.declaration.name == name
    for c in panel.declaration.controls:
        if c.kind != "slider":
            continue
        w = panel.controls[c.name]
        start = w.value
        for bad in (c.high + 10 * c.step if c.scale == "linear" else 10 * c.high,
                    c.low - 10 * c.step if c.scale == "linear" else c.low / 10):
            w.box.value = bad
            assert panel.last_error == range_template(c.name, c.low, c.high, c.unit, c.limit).format(value=bad), c
            assert _stale(panel) and w.slider.value == pytest.approx(start, rel=1e-12), c
        w.box.value = start
        assert _current(panel), (c.name, panel.last_error)


# --------------------------------------------------------------------------------------------------
# 2. a controller of the reader's own in the controllers panel
# --------------------------------------------------------------------------------------------------
def test_which_gains_a_controller_of_ones_own_takes():
    assert own_gains(MyPDGravity) == ("K_P", "K_D")
    assert own_gains(lambda K_I, omega, K_P: None) == ("K_P", "K_I", "omega")    # in the sliders' order
    assert own_gains(lambda **gains: None) == OWN_GAINS
    assert own_gains(lambda: None) == ()
    assert set(PER_JOINT) <= set(OWN_GAINS)
    with pytest.raises(ScaraError, match=r"controllers\['mine'\]: .* needs the argument 'alpha', which the panel does "
                                         r"not give.*give 'alpha' a default"):
        control_panel(controllers={"mine": lambda K_P, alpha: None})
    with pytest.raises(ScaraError, match="the label 'robust' is one of the panel's own controllers"):
        control_panel(controllers={"robust": MyPDGravity})
    with pytest.raises(ScaraError, match=r"controllers\['mine'\] must be a controller class or a function"):
        control_panel(controllers={"mine": MyPDGravity()})
    with pytest.raises(ScaraError, match="controllers must be a dict"):
        control_panel(controllers=[MyPDGravity])


def test_ones_own_controller_tuned_in_the_panel_equals_simulate_of_it(traj, jref):
    """The package page's PD + gravity, compiled, chosen in the panel and tuned: the figure and the summary are
    those of ``simulate`` of the same controller (built with the panel's gains as per-joint arrays), drawn as the
    figure of any run is drawn (``tuning_figure``)."""
    label = "my PD + gravity"
    panel = control_panel(traj, controllers={label: MyCompiledPDGravity})
    options = panel.controls["controller"].options
    n = len(TUNING_CONTROLLERS)   # the panel's own controllers come first
    assert tuple(options[:n]) == ("robust", "adaptive (Slotine-Li)", "operational ID + integral",
                                  "operational ID, no integral", "independent joint PID", "PD + gravity compensation",
                                  "computed torque") and options[n] == label
    assert panel.declaration.page is None   # the book's page runs its own controllers only
    with panel.hold():
        panel.controls["controller"].value = label
        panel.controls["K_P"].value = 4000.0
        panel.controls["K_D"].value = 400.0
    assert _current(panel), panel.last_error
    # only the gains it takes are read: the others are greyed out
    assert {k for k, w in panel.controls.items() if w.disabled} == set(OWN_GAINS) - {"K_P", "K_D"}
    res = simulate(MyCompiledPDGravity(K_P=np.full(4, 4000.0), K_D=np.full(4, 400.0)), traj, P5, joint_reference=jref)
    s = control_summary(res)
    v = panel.state
    for key in ("max_position_error", "rms_position_error", "max_orientation_error", "final_position_error",
                "steady_z_error", "chattering"):
        assert v[key] == pytest.approx(s[key], rel=1e-12, abs=1e-300), key
    np.testing.assert_allclose(v["peak_tau"], s["peak_tau"], rtol=1e-12)
    full = _widget_safe(tuning_figure(res, s, points=600).to_plotly_json())
    shown = panel._states[0]["data"]
    own = next(t for t in shown if t["name"] == label)
    assert own["visible"] is True and _same(own["x"], full["data"][0]["x"]) and _same(own["y"], full["data"][0]["y"])
    for t, f in zip(shown[n:n + 7], full["data"][n:n + 7]):   # the torques and the run's own signal (e_z)
        assert t["name"] == f["name"] and _same(t["x"], f["x"]) and _same(t["y"], f["y"]), t["name"]
        assert t.get("visible", True) == f.get("visible", True), t["name"]
    assert not any(t.get("visible", True) for t in shown[:n])   # the panel's controllers' errors hidden
    title = panel.figures[0].layout.title.text
    assert title.startswith(f"{label}: max ‖e_p‖ after 1 s {1e3 * s['max_position_error']:.4g} mm, at rest "
                            f"{1e3 * s['final_position_error']:.3g} mm<br>peak f3 {s['peak_tau'][2]:.0f} N")
    rows, notes = panel.declaration.summary(v)
    assert notes == [f"At rest the tool stays {1e3 * s['final_position_error']:.3g} mm from its target: the "
                     "payload's weight is not fully compensated."] and html.escape(notes[0]) in panel.notes.value
    # back to one of the panel's own: its figure, the reader's trace hidden
    panel.controls["controller"].value = "robust"
    assert _current(panel)
    assert next(t for t in panel._states[0]["data"] if t["name"] == label)["visible"] is False
    assert panel._states[0]["data"][0].get("visible", True) is True


def test_ones_own_run_is_drawn_by_the_kernel_of_the_panels_own_runs(traj):
    """The package's own operational law, handed in as a factory of the reader's: its run (scara.simulate) and the
    panel's program run of "operational ID, no integral" with the same gains give the same figure and numbers, to
    the last bit: one definition of what a run shows."""
    own = "operational, mine"
    panel = control_panel(traj, controllers={own: lambda K_P, K_D: OperationalSpaceController(False, K_P, K_D)})
    with panel.hold():
        panel.controls["K_P"].value = 1500.0
        panel.controls["K_D"].value = 80.0
        panel.controls["controller"].value = "operational ID, no integral"
    assert _current(panel)
    theirs = panel.state
    panel.controls["controller"].value = own
    assert _current(panel)
    mine = panel.state
    assert {k for k, w in panel.controls.items() if w.disabled} == set(OWN_GAINS) - {"K_P", "K_D"}
    for key in ("err_t", "err_y", "t", "f3", "tau1", "tau2", "tau4", "e_z"):
        np.testing.assert_array_equal(mine[key], theirs[key], err_msg=key)
    for key in ("max_position_error", "rms_position_error", "max_orientation_error", "final_position_error",
                "steady_z_error", "chattering", "max_position_error_mm", "final_position_error_mm", "peak_f3",
                "duration", "dt_ms", "not_compensated", "e_z_shown"):
        assert mine[key] == theirs[key], key
    assert mine["operational_noint_shown"] == 0.0 and theirs["operational_noint_shown"] == 1.0
    # the traces drawn: the same curve, under the reader's label
    shown = {t["name"]: t for t in panel._states[0]["data"] if t.get("visible", True)}
    assert own in shown and "operational ID, no integral" not in shown
    np.testing.assert_array_equal(np.array(shown[own]["y"], float), theirs["err_y"])


def test_ones_own_law_in_plain_python_runs_as_its_compiled_twin(short):
    """A law not compiled runs in simulate's loop as plain Python (seconds on the 70 s reference; a 2.5 s plan
    here): the same run, to the last bit, as the law compiled."""
    panel = control_panel(short, controllers={"plain": MyPDGravity, "compiled": MyCompiledPDGravity})
    with panel.hold():
        panel.controls["K_P"].value = 4000.0
        panel.controls["K_D"].value = 400.0
        panel.controls["controller"].value = "plain"
    assert _current(panel), panel.last_error
    plain = panel.state
    panel.controls["controller"].value = "compiled"
    assert _current(panel)
    for key in ("err_y", "f3", "tau1", "tau2", "tau4", "e_z", "max_position_error", "chattering"):
        np.testing.assert_array_equal(plain[key], panel.state[key], err_msg=key)
    jref = clik2(short)
    res = simulate(MyPDGravity(np.full(4, 4000.0), np.full(4, 400.0)), short, P5, joint_reference=jref)
    twin = simulate(MyCompiledPDGravity(np.full(4, 4000.0), np.full(4, 400.0)), short, P5, joint_reference=jref)
    for key in ("q", "qd", "tau", "e"):
        np.testing.assert_array_equal(getattr(res, key), getattr(twin, key), err_msg=key)
    assert plain["max_position_error"] == pytest.approx(control_summary(res)["max_position_error"], rel=1e-12)


class _NaNLaw(MyPDGravity):
    @staticmethod
    def law(k, t, dt, q, qd, ref, gains, model, state, work, signals, tau):
        for i in range(4):
            tau[i] = 0.0
        if k == 100:
            tau[1] = math.nan
        return 0


class _PastLaw(MyPDGravity):
    @staticmethod
    def law(k, t, dt, q, qd, ref, gains, model, state, work, signals, tau):
        tau[0] = gains[8]       # gains holds 8 numbers
        return 0


class _RaisingLaw(MyPDGravity):
    @staticmethod
    def law(k, t, dt, q, qd, ref, gains, model, state, work, signals, tau):
        raise RuntimeError("my law is not finished")


class _WrongSize(MyPDGravity):
    gains_layout = ArrayLayout(("K_P", 4), ("K_D", 4))

    def gains_array(self):
        return np.zeros(7)


def _broken(K_P):
    raise ValueError(f"no gains like {K_P[0]:g} here")


BAD = [   # (the reader's controller, what its refusal says)
    (_broken, "bad with K_P = 900: building it failed: ValueError: no gains like 900 here"),
    (lambda: None, "bad with no gain: controller None has no compiled law: see scara.simulate's interface"),
    (_NaNLaw, "bad with K_P = 900, K_D = 60: the closed loop of my_pd_gravity diverged at t = 0.1000 s (sample 100): "
              "the controller's law returned the torque tau_2 = nan, which is not finite"),
    (_PastLaw, "bad with K_P = 900, K_D = 60: the law of controller my_pd_gravity indexes gains[8]"),
    (_RaisingLaw, "bad with K_P = 900, K_D = 60: the law of controller my_pd_gravity failed on its trial call at t = 0 "
                  "(plain Python, bounds-checked): RuntimeError: my law is not finished"),
    (_WrongSize, "bad with K_P = 900, K_D = 60: the gains array of controller my_pd_gravity holds 7 numbers, but its "
                 "gains_layout declares 8"),
]


@pytest.mark.parametrize("factory, message", BAD, ids=["raises", "not a controller", "NaN torque", "reads past",
                                                      "law raises", "wrong size"])
def test_a_controller_of_ones_own_that_fails_is_refused_in_the_panel(factory, message, short):
    panel = control_panel(short, controllers={"bad": factory})
    panel.controls["controller"].value = "bad"
    assert panel.last_error is not None and panel.last_error.startswith(message), panel.last_error
    assert _stale(panel) and "Traceback" not in panel.message.value
    panel.controls["controller"].value = "robust"   # the panel goes on
    assert _current(panel)


# --------------------------------------------------------------------------------------------------
# 3. the waypoint editor's plan in the controllers panel
# --------------------------------------------------------------------------------------------------
def test_the_editors_plan_runs_in_the_controllers_panel():
    ed = waypoint_editor()
    ed.panel.controls["x"].value = 0.08
    assert ed.panel.last_error is None
    edited = ed.trajectory
    assert edited.plan_vector is not None
    for given in (ed, edited):   # the editor itself, or its trajectory
        panel = control_panel(given)
        assert _current(panel)
        assert panel.state["duration"] == pytest.approx(edited.t[-1], abs=1e-9)
    # the joint reference is computed for the edited path: the robust law's run is the package's on clik2 of it
    jref = clik2(edited)
    values = panel.values()
    ctl = make_controller(values["controller"], *(values[k] for k in OWN_GAINS))
    from scara.control.robust import sliding_rows

    Z = np.empty(32)
    sliding_rows(ctl.K_P, ctl.K_D, ctl.Lambda, Z)
    ctl.sliding = Z.reshape(4, 8)   # the program's closed-form Lyapunov solution (scipy's to 1e-12)
    res = ctl.run(edited, P5, joint_reference=jref)
    full = _widget_safe(tuning_figure(res, control_summary(res), points=600).to_plotly_json())
    assert _same(panel._states[0]["data"][0]["y"], full["data"][0]["y"])
    # and a controller of one's own tracks the same reference
    own = control_panel(ed, controllers={"mine": MyCompiledPDGravity})
    with own.hold():
        own.controls["controller"].value = "mine"
        own.controls["K_P"].value = 4000.0
        own.controls["K_D"].value = 400.0
    assert _current(own)
    res = simulate(MyCompiledPDGravity(np.full(4, 4000.0), np.full(4, 400.0)), edited, P5, joint_reference=jref)
    assert own.state["max_position_error"] == pytest.approx(control_summary(res)["max_position_error"], rel=1e-12)


# --------------------------------------------------------------------------------------------------
# 4. keep=True: a re-run cell starts from the last accepted settings
# --------------------------------------------------------------------------------------------------
def _keep_cases():
    """(panel, builder, an accepted move, a refused setting after it)"""
    return [
        ("direct kinematics", kinematics_panel, dict(theta1=25.0, d3=0.3), dict(theta2=500.0)),
        ("inverse kinematics", inverse_kinematics_panel, dict(px=0.3, phi=30.0), dict(px=1.2)),
        ("ellipses", manipulability_panel, dict(theta2=30.0, scale=0.2), dict(scale=0.0)),
        ("inertia matrix", dynamics_panel, dict(payload=10.0, K_P3=2e4), dict(payload=1000.0)),
        ("CLIK", clik_panel, dict(method="pseudo-inverse + null space", Kx=600.0), dict(Kx=1e4)),
        ("controllers", control_panel, dict(controller="adaptive (Slotine-Li)", K_pi=0.02), dict(K_P=0.0)),
        ("interaction", interaction_panel, dict(law="impedance", M_z=20.0), dict(D_z=1e5)),
    ]


@pytest.mark.parametrize("name, build, move, bad", _keep_cases(), ids=[c[0] for c in _keep_cases()])
def test_keep_starts_from_the_last_accepted_settings_of_the_previous_panel(name, build, move, bad):
    first = build()
    assert first.declaration.name == name
    defaults = first.values()
    with first.hold():
        for key, value in move.items():
            first.controls[key].value = value
    assert first.last_error is None and first.accepted == dict(defaults, **move)
    for key, value in bad.items():
        first.controls[key].value = value
    assert first.last_error is not None   # refused: not what is kept
    again = build(keep=True)
    assert again.values() == dict(defaults, **move) and again.accepted == again.values() and _current(again)
    assert build().values() == defaults   # keep=False: the declaration's start
    with pytest.raises(ScaraError, match="keep = 'yes' must be True or False"):
        build(keep="yes")


def test_keep_drops_a_choice_the_new_panel_does_not_offer_and_shows_a_kept_setting_it_refuses(short):
    first = control_panel(short, controllers={"mine": MyCompiledPDGravity})
    with first.hold():
        first.controls["controller"].value = "mine"
        first.controls["K_P"].value = 4000.0
    assert first.last_error is None
    plain = control_panel(short, keep=True)   # no "mine" here: the dropdown starts at its default
    assert plain.values()["controller"] == "robust" and plain.values()["K_P"] == 4000.0 and _current(plain)
    # the reader's controller now fails: the panel opens, on its start values, and shows the kept setting refused
    control_panel(short, controllers={"mine": MyCompiledPDGravity}).controls["controller"].value = "mine"
    broken = control_panel(short, controllers={"mine": _NaNLaw}, keep=True)
    assert broken.values()["controller"] == "mine" and _stale(broken)
    assert "diverged" in broken.last_error and broken.accepted["controller"] == "robust"
    broken.controls["controller"].value = "robust"
    assert _current(broken)


def test_keep_starts_the_editor_from_the_last_accepted_plan():
    ed = waypoint_editor()
    c = ed.panel.controls
    c["point"].value = 7   # loads p7 = (0.70, 0.15, 0.3) m into the sliders
    c["x"].value = 0.65
    c["segment"].value = 2
    c["duration"].value = 4.0
    c["x"].value = 0.99   # unreachable: refused, not kept
    assert ed.panel.last_error is not None
    plan = ed.plan
    again = waypoint_editor(keep=True)
    assert again.plan["waypoints"] == plan["waypoints"] and again.plan["durations"] == plan["durations"]
    assert again.plan["waypoints"][7].position[0] == 0.65 and again.plan["durations"][2] == 4.0
    v = again.panel.values()
    assert (v["point"], v["x"], v["segment"], v["duration"]) == (7, 0.65, 2, 4.0) and _current(again.panel)
    assert again.trajectory.durations[2] == 4.0
    assert waypoint_editor().plan["waypoints"][7].position[0] == 0.70   # keep=False: the reference scenario
