"""The page program of chapter 6's controllers panel (scara.programs.control): one move is one compiled kernel whose
outputs equal the package's own run (the controllers, scara.simulate, control_summary, the figures' thinning), whose
refusals say what the package says, and whose bindings redraw the panel's figure as its builder draws it. Runs as
plain Python too (SCARA_NO_NUMBA=1, on a short plan; the 70 s reference only with numba)."""
from __future__ import annotations

import math
import re

import numpy as np
import pytest

import scara
from scara import ScaraParams, clik2, plan_path
from scara._compile import COMPILED
from scara.control import control_summary
from scara.control.robust import sliding_matrix, sliding_rows
from scara.errors import ScaraError
from scara.plots._common import CONTROLLER_LABELS, envelope, thin
from scara.plots.panels import apply_update
from scara.programs import control as pc
from scara.widgets.control import control_declaration, make_controller

RNG = np.random.default_rng(20261203)
P = ScaraParams()
#: the panel's defaults, by control (the dropdown aside)
DEFAULTS = dict(payload=5.0, K_P=900.0, K_D=60.0, Lambda=30.0, rho=20.0, epsilon=0.05, K_D_scale=1.0, K_pi=0.01,
                K_I=8000.0, omega=30.0)
GAIN_KEYS = ("K_P", "K_D", "Lambda", "rho", "epsilon", "K_D_scale", "K_pi", "K_I", "omega")
POINTS = 300


@pytest.fixture(scope="module")
def short():
    """A 2.5 s plan (a move of the quill down and a stop): short enough for plain Python."""
    return plan_path([[0.18, 0.20, 0.5], [0.14, 0.20, 0.5], [0.10, 0.20, 0.3]], durations=[1.0, 1.0], total=2.5)


@pytest.fixture(scope="module")
def panel(short):
    return control_declaration(short, points=POINTS)


def _settings(law: str, values: dict | None = None) -> dict:
    return dict(DEFAULTS, controller=CONTROLLER_LABELS[law], **(values or {}))


def _random_settings(law: str) -> dict:
    """Settings drawn log-uniformly inside the panel's sliders (the adaptation weight and the integral gain in the
    ranges where the runs stay within the stated bounds most of the time)."""
    def log(lo, hi):
        return float(10 ** RNG.uniform(math.log10(lo), math.log10(hi)))

    v = dict(payload=float(RNG.choice(np.arange(0.0, 10.5, 0.5))), K_P=log(300.0, 3000.0), K_D=log(30.0, 300.0),
             rho=log(1.0, 50.0), epsilon=log(0.02, 0.5), K_D_scale=log(0.5, 4.0), K_pi=log(3e-3, 0.1),
             omega=log(10.0, 60.0))
    v["Lambda"] = log(2.0, 0.8 * v["K_D"])
    v["K_I"] = log(10.0, 0.5 * v["K_D"] * v["K_P"])
    return _settings(law, v)


def _program(values: dict, data, outputs):
    """``(status, outputs by field)`` of one run of the program for the panel's settings ``values``."""
    inputs = np.array([float(pc.LAWS.index(_key(values["controller"])))] + [float(values[k]) for k in pc.INPUTS[1:]])
    out = np.zeros(outputs.size)
    status = int(pc.control_program(inputs, data, out))
    return status, {n: (out[o] if outputs.sizes[n] == 1 else out[o:o + outputs.sizes[n]].copy())
                    for n, o in zip(outputs.names, outputs.offsets)}


def _key(label: str) -> str:
    return {v: k for k, v in CONTROLLER_LABELS.items()}[label]


def _package(values: dict, traj, jref):
    """The controller the panel's settings make (``make_controller``), its run on the plant carrying the payload,
    and its summary: the package's own API. The robust controller is given the closed-form solution of its Lyapunov
    equation (:func:`~scara.control.robust.sliding_rows`, the program's), which scipy's solve gives to 1e-12."""
    c = make_controller(values["controller"], *(values[k] for k in GAIN_KEYS))
    if c.name == "robust":
        Z = np.empty(32)
        sliding_rows(c.K_P, c.K_D, c.Lambda, Z)
        c.sliding = Z.reshape(4, 8)
    res = c.run(traj, P.with_payload(values["payload"]), joint_reference=jref if c.reference_kind == "joint" else None)
    return c, res, control_summary(res)


def _panel_message(exc) -> str:
    """What the panel showed for a refusal of the package before it ran a program: a gain's ``[0]`` dropped."""
    return re.sub(r"\[0\]", "", str(exc))


def _check_run(values, traj, jref, data, outputs, points):
    status, v = _program(values, data, outputs)
    try:
        c, res, s = _package(values, traj, jref)
    except ScaraError as exc:
        assert status != 0, (values, exc)
        assert pc.control_refusals()[status].format({**values, **v}) == _panel_message(exc)
        return None
    assert status == 0, (values, pc.control_refusals()[status].format({**values, **v}))
    for key in ("max_position_error", "rms_position_error", "max_orientation_error", "final_position_error",
                "steady_z_error", "peak_tau", "chattering"):   # numpy's pairwise sums against the kernel's in turn
        np.testing.assert_allclose(v[key], s[key], rtol=1e-12, atol=1e-300, err_msg=key)
    idx = thin(len(res.t), points)
    tt, yy = envelope(res.t, np.linalg.norm(res.e[:, :3], axis=1), points)
    np.testing.assert_array_equal(v["err_t"], tt)
    np.testing.assert_array_equal(v["err_y"], yy)
    np.testing.assert_array_equal(v["t"], res.t[idx])
    for name, j in (("f3", 2), ("tau1", 0), ("tau2", 1), ("tau4", 3)):
        np.testing.assert_array_equal(v[name], res.tau[idx, j])
    law = c.name
    assert [v[f] for f in pc.SHOWN] == [1.0 if n == law else 0.0 for n in pc.LAWS]
    if law == "adaptive":
        np.testing.assert_array_equal(v["estimate"], res.payload_estimate[idx])
        assert v["payload_estimate"] == res.payload_estimate[-1]
    elif law == "robust":
        np.testing.assert_array_equal(v["z_norm"], envelope(res.t, res.z_norm, points)[1])
        assert v["rho_over_epsilon"] == c.rho / c.epsilon
    else:
        np.testing.assert_array_equal(v["e_z"], 1e3 * res.e[idx, 2])
    if law == "independent":
        assert v["largest_K_P"] == c.K_P.max()
    if law == "operational_noint":
        np.testing.assert_allclose(v["theory_mm"], 1e3 * c.steady_state_error(res.plant, res.q[-1])[2], rtol=1e-12)
        np.testing.assert_allclose(v["steady_z_error_mm"], 1e3 * s["steady_z_error"], rtol=1e-12)
    if law in ("pd_plus_gravity", "computed_torque"):   # e_z = d3 - d3_d = -e_3 at rest
        e = c.steady_state_error(res.plant) if law == "pd_plus_gravity" else c.steady_state_error(res.plant, res.q[-1])
        np.testing.assert_allclose(v["theory_mm"], -1e3 * e[2], rtol=1e-12)
        np.testing.assert_allclose(v["steady_z_error_mm"], 1e3 * s["steady_z_error"], rtol=1e-12)
    assert v["not_compensated"] == (1.0 if s["final_position_error"] > 1e-3 else 0.0)
    np.testing.assert_allclose(v["max_position_error_mm"], 1e3 * s["max_position_error"], rtol=1e-12)
    return v


# --------------------------------------------------------------------------------------------------
# the outputs against the package's own functions
# --------------------------------------------------------------------------------------------------
@pytest.mark.parametrize("law", pc.LAWS)
def test_a_move_equals_the_packages_run_and_summary(law, short):
    data = pc.control_data(short, points=POINTS)
    outputs = pc.control_outputs(len(short.t), POINTS)
    jref = clik2(short)
    settings = [_settings(law)] + [_random_settings(law) for _ in range(3 if COMPILED else 1)]
    shown = [_check_run(v, short, jref, data, outputs, POINTS) for v in settings]
    assert shown[0] is not None   # the defaults run


@pytest.mark.skipif(not COMPILED, reason="the 70 s reference takes minutes in plain Python")
@pytest.mark.parametrize("law", pc.LAWS)
def test_the_panels_reference_run_equals_the_packages(law, traj, jref):
    data = pc.control_data(traj)
    outputs = pc.control_outputs(len(traj.t), 600)
    assert _check_run(_settings(law), traj, jref, data, outputs, 600) is not None
    _check_run(_random_settings(law), traj, jref, data, outputs, 600)   # a run, or the same refusal


def test_the_closed_form_lyapunov_solution_is_scipys():
    for _ in range(50):
        kp, kd = 10 ** RNG.uniform(1, 5, 4), 10 ** RNG.uniform(0.4, 3.4, 4)
        lam = kd * RNG.uniform(0.01, 0.99, 4)
        Z = np.empty(32)
        sliding_rows(kp, kd, lam, Z)
        P_w = np.diag(np.concatenate([2.0 * kp * lam, 2.0 * (kd - lam)]))
        np.testing.assert_allclose(Z.reshape(4, 8), sliding_matrix(kp, kd, P_w), rtol=1e-10, atol=1e-12)
        np.testing.assert_allclose(Z.reshape(4, 8)[:, :4], np.diag(lam), rtol=1e-14)


@pytest.mark.parametrize("n, points", [(2, 2), (5, 7), (600, 600), (601, 600), (1501, 300), (70001, 600),
                                       (70001, 1000), (12345, 9999)])
def test_thinning_and_envelopes_are_the_figures(n, points):
    idx = thin(n, points)
    assert pc.thin_length(n, points) == len(idx)
    assert [pc.thin_index(n, points, j) for j in range(len(idx))] == idx.tolist()
    t = np.arange(n) * 1e-3
    y = RNG.normal(size=n)
    tt, yy = envelope(t, y, points)
    assert pc.envelope_length(n, points) == len(tt)
    a, b = np.empty(len(tt)), np.empty(len(tt))
    assert pc.envelope_kernel(t, y, points, a, b) == len(tt)
    np.testing.assert_array_equal(a, tt)
    np.testing.assert_array_equal(b, yy)


def test_the_layouts_and_data_are_those_the_kernel_reads(short):
    n = len(short.t)
    data = pc.control_data(short, points=POINTS)
    outputs = pc.control_outputs(n, POINTS)
    h = pc.HEADER.offsets
    assert data.size == pc.HEADER.size + 24 * n
    for name, at in (("x", h.x_at), ("xd", h.xd_at), ("xdd", h.xdd_at)):
        np.testing.assert_array_equal(data[int(data[at]):int(data[at]) + 4 * n].reshape(n, 4), getattr(short, name))
    # the joint reference, computed once with the data: scara.clik2 of the trajectory, to the last bit
    jref, at = clik2(short), int(data[h.jref_at])
    assert data[h.jref_code] == 0
    for k, name in enumerate(("q", "qd", "qdd")):
        np.testing.assert_array_equal(data[at + 4 * n * k:at + 4 * n * (k + 1)].reshape(n, 4), getattr(jref, name))
    for k, name in enumerate(pc.ARRAYS):
        assert int(data[h.out_at + k]) == getattr(outputs.offsets, name)
    assert outputs.sizes["err_t"] == pc.envelope_length(n, POINTS) and outputs.sizes["t"] == pc.thin_length(n, POINTS)
    with pytest.raises(ScaraError, match="points = 1"):
        pc.control_data(short, points=1)
    with pytest.raises(ScaraError, match="geometry"):
        pc.control_data(short, P.replace(a1=0.6))


# --------------------------------------------------------------------------------------------------
# the refusals: each reached, with the package's message
# --------------------------------------------------------------------------------------------------
REFUSED = [   # (settings, what the package refuses them with: its message as the panel shows it)
    ("robust", dict(Lambda=100.0)),
    ("robust", dict(Lambda=61.0, K_D=60.0)),
    ("robust", dict(K_P=-1.5)), ("robust", dict(K_D=math.nan)), ("robust", dict(rho=-1.5)),
    ("robust", dict(epsilon=math.nan)), ("robust", dict(Lambda=0.0)),
    ("robust", dict(K_P=1e5, K_D=3000.0, Lambda=300.0, rho=200.0)),            # the torque bound, at once
    ("adaptive", dict(K_pi=1e-5)),                                             # adaptation far too fast
    ("adaptive", dict(K_pi=1e-320)), ("adaptive", dict(K_pi=-2.5)), ("adaptive", dict(K_D_scale=-0.5)),
    ("adaptive", dict(Lambda=math.inf)),
    ("operational", dict(K_I=1e6, K_P=10.0)), ("operational", dict(K_I=-1.5)),
    ("operational_noint", dict(K_P=1e5, K_D=2.0)),
    ("independent", dict(omega=1.0)),                                          # the sag passes max_error
    ("independent", dict(omega=0.42)), ("independent", dict(omega=0.3)),       # below the quill's, the wrist's friction
    ("independent", dict(omega=-1.5)),
    ("pd_plus_gravity", dict(omega=1.0)), ("computed_torque", dict(omega=1.0)),  # the sag passes max_error
    ("pd_plus_gravity", dict(omega=0.5)),                                      # below the quill's friction (PD)
    ("pd_plus_gravity", dict(omega=math.nan)),
    ("computed_torque", dict(omega=1500.0)), ("computed_torque", dict(omega=-1.5)),   # the sampling limit (Jury)
    ("robust", dict(payload=-1.5)),
]


@pytest.mark.filterwarnings("ignore:overflow encountered")   # plain Python: the rate 1 / 1e-320 the check refuses
@pytest.mark.parametrize("law, values", REFUSED, ids=lambda v: str(v))
def test_refusals_say_what_the_package_says(law, values, short):
    data = pc.control_data(short, points=POINTS)
    outputs = pc.control_outputs(len(short.t), POINTS)
    settings = _settings(law, values)
    status, v = _program(settings, data, outputs)
    with pytest.raises(ScaraError) as info:
        _package(settings, short, clik2(short))
    assert status != 0
    assert pc.control_refusals()[status].format({**settings, **v}) == _panel_message(info.value)


def test_the_panel_refuses_with_the_programs_message(panel):
    values = _settings("adaptive", dict(K_pi=1e-5))
    with pytest.raises(ScaraError, match=r"^the closed loop of adaptive diverged at t = [0-9.]+ s \(sample \d+\): the "
                                         r"controller's law returned code 2: a commanded torque exceeded its bound"):
        panel.compute(values)
    with pytest.raises(ScaraError, match=r"^Lambda = 100 must be < K_D = 60: the weight P"):
        panel.compute(_settings("robust", dict(Lambda=100.0)))


@pytest.mark.parametrize("law", pc.LAWS)
def test_every_stop_of_the_loop_is_worded_as_the_engine_words_it(law):
    """The stops the chapter-6 laws never reach (their own bounds come first) are worded from the engine's own
    templates: the program's refusal of each, for the numbers of a stop, equals :func:`scara.simulate`'s message."""
    from scara._simulate.engine import _raise_failure
    from scara._simulate.interface import DIVERGED, JOINT_LIMIT, LAW_FAILED, NOT_FINITE, SINGULAR_INERTIA

    ctl = pc._CLASSES[pc.LAWS.index(law)]
    ctl = ctl(integral=False) if law == "operational_noint" else ctl()
    n, n_sig = 10, len(ctl.signal_names)
    q, qd, tau = RNG.normal(size=(n, 4)), RNG.normal(size=(n, 4)), RNG.normal(size=(n, 4))
    sig = RNG.normal(size=(n, n_sig))
    refusals = pc.control_refusals()
    cases = [(LAW_FAILED, 4, c) for c in (2, 3, 4, 7)] + [(DIVERGED, 5, 0), (SINGULAR_INERTIA, 6, 0)]
    cases += [(NOT_FINITE, 3, i) for i in range(4 + n_sig)] + [(JOINT_LIMIT, 7, 0), (JOINT_LIMIT, 8, 0)]
    for status, k, extra in cases:
        info = np.array([status, k, extra])
        qq = q.copy()
        if status == JOINT_LIMIT:
            qq[k, 2] = 1.25 if k == 7 else -0.25
        if status == NOT_FINITE:
            (tau if extra < 4 else sig)[k, extra if extra < 4 else extra - 4] = (math.nan, math.inf, -math.inf)[k % 3]
        out = np.zeros(pc.SCALARS.size)
        code = pc.run_refusal(pc._R_RUN + 100 * pc.LAWS.index(law), info.astype(float), 1e-3, qq, qd, tau, sig,
                              P.d3_min, P.d3_max, out, pc._RUN_AT)
        values = {name: out[at] for name, at in zip(pc.SCALARS.names, pc.SCALARS.offsets)}
        with pytest.raises(scara.UnstableError) as exc:
            _raise_failure(ctl, info, 1e-3, pc.LIMIT, (qq, qd, None, tau, None, None, sig), P, ctl.signal_names)
        assert refusals[code].format(values) == str(exc.value), (status, extra)


def test_start_and_reference_refusals_say_what_the_package_says(short):
    """A trajectory whose start is out of reach, one the CLIK cannot follow, a run shorter than the table's first
    second, and an operational start outside the stroke: the program's messages are the package's."""
    from types import SimpleNamespace

    from scara.kinematics import ikine

    def traj_of(x, q0=None, n=None):
        n = len(x) if n is None else n
        return SimpleNamespace(t=short.t[:n].copy(), x=x[:n], xd=short.xd[:n].copy(), xdd=short.xdd[:n].copy(),
                               dt=short.dt, elbow=-1, q0=short.q0 if q0 is None else q0, params=short.params)

    def refusal(traj, law):
        data = pc.control_data(traj, points=POINTS)
        outputs = pc.control_outputs(len(traj.t), POINTS)
        status, v = _program(_settings(law), data, outputs)
        assert status != 0
        return pc.control_refusals()[status].format({**_settings(law), **v})

    from scara.widgets._common import readable

    for x0 in ([1.2, 0.0, 0.5, 0.3], [0.3, 0.2, -0.5, 0.0]):   # outside the annulus, outside the stroke
        x = short.x.copy()
        x[0] = x0
        with pytest.raises(scara.UnreachableError) as exc:
            ikine(np.array(x0), P, elbow=-1)
        assert refusal(traj_of(x), "robust") == readable(str(exc.value))
    x = short.x.copy()
    x[200:, 0] += 0.15   # a step the second-order CLIK cannot follow within its max_error
    with pytest.raises(scara.UnstableError) as exc:
        clik2(traj_of(x))
    assert refusal(traj_of(x), "adaptive") == str(exc.value)
    with pytest.raises(ScaraError) as exc:
        control_summary(OperationalSpaceController_run(traj_of(short.x, n=800)))
    assert refusal(traj_of(short.x, n=800), "operational") == str(exc.value)
    q0 = short.q0.copy()
    q0[2] = 1.25
    with pytest.raises(scara.UnreachableError) as exc:
        scara.OperationalSpaceController().run(traj_of(short.x, q0=q0), P.with_payload(5.0))
    assert refusal(traj_of(short.x, q0=q0), "operational") == str(exc.value)


def OperationalSpaceController_run(traj):  # noqa: N802 - the run a short trajectory gives
    return scara.OperationalSpaceController().run(traj, P.with_payload(5.0))


def test_the_laws_pass_their_trial_on_guarded_copies_and_a_short_array_is_caught():
    """The program's trial (check_law_bounds' guard entries) passes every law with the arrays its layouts declare;
    an array shorter than the law reads or writes is caught, named by its refusal code."""
    q0, qd0 = np.array([0.4, -2.5, 0.5, 0.0]), np.zeros(4)
    model = scara.dynamics.dynamic_array(P)
    inputs = np.array([0.0] + [DEFAULTS[k] for k in pc.INPUTS[1:]])
    data = np.zeros(pc.HEADER.size)
    h = pc.HEADER.offsets
    data[h.tau_max:h.tau_max + 4] = pc.TAU_MAX
    data[h.max_error] = pc.MAX_ERROR
    data[h.B_hat:h.B_hat + 4] = pc.B_HAT
    data[h.B_bar:h.B_bar + 4] = pc.B_BAR
    data[h.adaptive_K_D:h.adaptive_K_D + 4] = pc.ADAPTIVE_K_D
    data[h.dt] = 1e-3   # computed torque's gains are checked against the sampling period
    for law in range(len(pc.LAWS)):
        inputs[0] = law
        r0 = np.concatenate([q0 if pc._JOINT[law] else scara.pose(q0), np.zeros(8)])   # at rest where the arm is
        gains, state = np.zeros(pc._NG[law]), np.zeros(pc._NS[law])
        work = np.zeros((pc._NW[law], 4))
        out = np.zeros(pc.SCALARS.size)
        assert pc._make_law(law, inputs, data, model, gains, state, out) == 0
        assert pc._bounds_status(law, q0, qd0, r0, 1e-3, gains, model, state, work, pc._NSIG[law], out) == 0
        if not COMPILED:   # numpy's views check their bounds (an IndexError); numba's and the page's do not
            continue
        code = pc._bounds_status(law, q0, qd0, r0, 1e-3, gains[:-1], model, state, work, pc._NSIG[law], out)
        assert code == pc._R_TRIAL + 20 * law + 1   # reads past gains (its last entry, max_error)
        if pc._NW[law]:
            code = pc._bounds_status(law, q0, qd0, r0, 1e-3, gains, model, state, work[:-1], pc._NSIG[law], out)
            assert code in (pc._R_TRIAL + 20 * law + 6, pc._R_TRIAL + 20 * law + 7)   # work: written or read past
        code = pc._bounds_status(law, q0, qd0, r0, 1e-3, gains, model, state, work, pc._NSIG[law] - 1, out)
        assert code == pc._R_TRIAL + 20 * law + 8 and out[pc._O_FAIL_K] == pc._NSIG[law] - 1   # writes signals[n]


# --------------------------------------------------------------------------------------------------
# the figure: the bindings redraw what the builder draws
# --------------------------------------------------------------------------------------------------
def _at(tree, path):
    for part in path.split("."):
        tree = tree[int(part)] if isinstance(tree, list) else tree[part]
    return tree


def test_updates_redraw_what_the_builder_draws(panel):
    from scara.widgets._common import _widget_safe

    pair = panel.figures[0]
    program = panel.page
    laws = list(pc.LAWS)
    settings = [_settings(law) for law in laws] + [_random_settings(laws[i % 5]) for i in range(4 if COMPILED else 1)]
    runs = []
    for v in settings:
        try:
            runs.append(panel.compute(v))
        except ScaraError:
            pass
    assert len(runs) >= 5
    for k in range(len(runs)):
        v0, v1 = runs[k], runs[(k + 1) % len(runs)]
        new = _widget_safe(apply_update(pair.build(v0).to_plotly_json(), pair.updated(v1), pair))
        full = _widget_safe(pair.build(v1).to_plotly_json())
        for role, props in program.traces["tuning"].items():
            i = pair.roles.index(role)
            for prop in props:
                a, b = new["data"][i][prop], full["data"][i][prop]
                if isinstance(b, (bool, str)):
                    assert a == b, (role, prop)
                else:
                    np.testing.assert_array_equal(np.asarray(a, dtype=float), np.asarray(b, dtype=float))
        for path in program.paths["tuning"]:
            assert _at(new["layout"], path) == _at(full["layout"], path), path
        assert new["layout"]["title"]["text"] == full["layout"]["title"]["text"]
        shown = [t["name"] for t in full["data"] if t.get("visible", True)]
        assert shown[0] == v1["controller"] and len(shown) == 6   # the run's error, 4 torques, its own signal


def test_the_panel_keeps_its_controls_and_notes(panel):
    assert [c.name for c in panel.controls] == list(pc.INPUTS)
    assert panel.selector == "controller" and panel.widget == "control_panel"
    v = panel.compute(_settings("operational_noint"))
    rows, notes = panel.summary(v)
    assert rows == [] and notes == [f"At rest the tool stays {v['final_position_error_mm']:.3g} mm from its target: "
                                    "the payload's weight is not fully compensated."]
    assert panel.summary(panel.compute(_settings("operational")))[1] == []
    title = panel.figures[0].build(v).layout.title.text
    assert title.startswith("operational ID, no integral: max ‖e_p‖ after 1 s ") and "<br>" in title
    assert panel.page.describe(panel)["kernel"] == "control_program"


# --------------------------------------------------------------------------------------------------
# the page: the translation computes what numba computes
# --------------------------------------------------------------------------------------------------
def test_the_program_translates_and_runs_in_the_page(short):
    from scara.page.translate import translate

    from ._node import NODE, run_js

    script = translate([pc.control_program])
    if NODE is None:
        pytest.skip("node is not installed")
    data = pc.control_data(short, points=POINTS)
    outputs = pc.control_outputs(len(short.t), POINTS)
    refused = []
    for law in pc.LAWS:
        v = _settings(law)
        status, ref = _program(v, data, outputs)
        inputs = np.array([float(pc.LAWS.index(law))] + [float(v[k]) for k in pc.INPUTS[1:]])
        try:
            (ret, args, _), = run_js(script, [("control_program", [inputs, data, np.zeros(outputs.size)], 1)])
        except RuntimeError as exc:   # a construct the page's runtime does not run yet
            refused.append((law, [line for line in str(exc).splitlines() if "Error: " in line][:1]))
            continue
        assert ret == status == 0
        got = args[2]
        want = np.concatenate([np.atleast_1d(ref[n]) for n in outputs.names])
        # V8's sin and cos are not glibc's: the runs agree to the last digits, not bit for bit
        np.testing.assert_allclose(got, want, rtol=1e-6, atol=1e-9 * np.max(np.abs(want)))
    if refused:
        pytest.xfail(f"the page's runtime refused: {refused}")


def test_the_scratch_after_the_data_gives_the_same_moves(short):
    """The panel appends control_scratch entries to the data (PageProgram.scratch) for the run's series: moves
    through it, one law after another and refused ones between (each leaving its series there), equal moves on the
    data alone (which allocate their own), bit for bit; the program reads nothing it did not write in the move. The
    panel's program sends only the data to the page and hands the kernel the data and its scratch."""
    n = len(short.t)
    data = pc.control_data(short, points=POINTS)
    outputs = pc.control_outputs(n, POINTS)
    with_scratch = np.concatenate([data, np.full(pc.control_scratch(n), np.nan)])  # stale NaN would show
    moves = [_settings(law) for law in pc.LAWS] + [_settings("robust", dict(K_P=-1.0))] + \
            [_random_settings(law) for law in reversed(pc.LAWS)]
    for values in moves:
        assert _same_moves(_program(values, with_scratch, outputs), _program(values, data, outputs)), values
    assert np.array_equal(with_scratch[:data.size], data)   # the data itself is never written
    decl = control_declaration(short, points=POINTS)
    prog = decl.page
    assert prog.scratch == pc.control_scratch(n) and prog.data.size == data.size
    described = prog.describe(decl)
    assert described["scratch"] == prog.scratch and described["data_size"] == data.size


def _same_moves(a, b) -> bool:
    """Two results of :func:`_program` equal entry by entry (arrays bit for bit, NaN equal to NaN)."""
    (s1, o1), (s2, o2) = a, b
    return s1 == s2 and o1.keys() == o2.keys() and all(
        np.array_equal(np.asarray(o1[k]), np.asarray(o2[k]), equal_nan=True) for k in o1)


def test_a_scratch_is_a_count(short):
    import dataclasses

    prog = control_declaration(short, points=POINTS).page
    for bad in (-1, 2.5, "10", True):
        with pytest.raises(ScaraError, match=f"scratch must be a count of entries .*got {re.escape(repr(bad))}"):
            dataclasses.replace(prog, scratch=bad)
    bare = dataclasses.replace(prog, scratch=0)
    assert bare._given is bare.data   # no scratch: the kernel is given the data itself
    assert np.array_equal(prog._given[:prog.data.size], prog.data) and prog._given.size == prog.data.size + prog.scratch
