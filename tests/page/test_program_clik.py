"""The page program of the CLIK panel (scara.programs.clik): its outputs are the package's own runs (clik, clik2,
their summaries, the plots' envelope and thinning), every refusal code carries the message the package gives
(after the panel's method and gains), the figure's bindings redraw the builder's figure exactly, and the
translated kernel computes in Node what numba computes."""
from __future__ import annotations

import dataclasses
import math
from types import SimpleNamespace

import numpy as np
import pytest

pytest.importorskip("ipywidgets")

from scara import ScaraError  # noqa: E402
from scara._clik.checks import _check_initial_error  # noqa: E402
from scara._clik.records import STATUS_ERROR_BOUND, STATUS_NONFINITE, STATUS_SINGULAR, COMPONENTS  # noqa: E402
from scara._clik.result import ClikResult, _fail  # noqa: E402
from scara._compile import COMPILED  # noqa: E402
from scara.plots._common import LOG_FLOOR, envelope, thin  # noqa: E402
from scara.plots.clik import CLIK_PANEL_ROLES, METHOD_CHOICES, run_method  # noqa: E402
from scara.plots.panels import apply_update  # noqa: E402
from scara.programs import clik as P  # noqa: E402
from scara.trajectory import plan_path  # noqa: E402
from scara.widgets._common import _widget_safe  # noqa: E402
from scara.widgets.clik import clik_controls, clik_declaration, clik_page_program  # noqa: E402

CONTROLS = {c.name: c for c in clik_controls()}
DEFAULTS = {c.name: c.default for c in clik_controls()}
LABELS = {m: label for label, m in METHOD_CHOICES.items()}
GAIN_KEYS = ("Kx", "Ky", "Kz", "Kphi")
RNG = np.random.default_rng(20261203)


def _short(dt=1e-3):
    """A 0.6 s move (the planned path of tests/test_clik.py): fast enough to run many settings, in plain Python too."""
    return plan_path([[0.3, 0.2, 0.5], [0.45, 0.1, 0.45]], durations=[0.5], total=0.6, dt=dt)


def _constant(x, T, dt=1e-3):
    n = int(round(T / dt)) + 1
    return SimpleNamespace(t=np.arange(n) * dt, x=np.tile(np.asarray(x, float), (n, 1)), xd=np.zeros((n, 4)),
                           xdd=np.zeros((n, 4)), dt=dt)


@pytest.fixture(scope="module")
def short():
    return _short()


@pytest.fixture(scope="module")
def program(short):
    return clik_page_program(short)


def _settings(**kw):
    s = dict(DEFAULTS)
    s.update(kw)
    return s


def _random_settings(rng, method=None):
    s = dict(DEFAULTS, method=method or rng.choice(list(METHOD_CHOICES)), relaxed=str(rng.choice(COMPONENTS)),
             damping=float(rng.choice([0.0, rng.uniform(0.0, 0.2)])), k0=float(rng.uniform(0.0, 20.0)))
    lo = rng.choice([0.0, 2.0])  # gains over the whole slider, or in its upper part (where the limits are)
    for k in GAIN_KEYS:
        s[k] = float(10 ** rng.uniform(lo, math.log10(2500.0)))
    return s


def _status(prog, s):
    """The kernel's status and its outputs (by field) for the settings ``s``."""
    out = np.zeros(prog.outputs.size)
    status = int(prog.kernel(prog.pack(s, CONTROLS), prog.data, out))
    return status, prog.values(out, s)


def _head(s):
    return (f"{s['method']} with K_x = {s['Kx']:.4g} 1/s, K_y = {s['Ky']:.4g} 1/s, K_z = {s['Kz']:.4g} 1/s, "
            f"K_φ = {s['Kphi']:.4g} 1/s: ")


def _package_run(traj, s):
    """What the panel did before its program: run_method (clik, or clik2 with K_P = K^2, K_D = 2 K)."""
    m = METHOD_CHOICES[s["method"]]
    K = np.array([s[k] for k in GAIN_KEYS])
    return run_method(traj, m, K, damping=s["damping"] if m != "transpose" else 0.0, relaxed=s["relaxed"],
                      k0=s["k0"])


def _refused_message(prog, s) -> str:
    with pytest.raises(ScaraError) as info:
        prog.run(s, CONTROLS)
    return str(info.value)


def _check_against_package(prog, traj, s, points=800):
    """The program's outputs for ``s`` against the package's run, or its refusal against the package's."""
    status, v = _status(prog, s)
    m = METHOD_CHOICES[s["method"]]
    try:
        r = _package_run(traj, s)
        sm = r.summary()
    except ScaraError as exc:
        assert status != 0, (s, str(exc))
        assert _refused_message(prog, s) == _head(s) + str(exc)
        return status
    assert status == 0, (s, status)
    for key in ("max_position_error", "rms_position_error", "max_orientation_error", "min_manipulability",
                "mean_manipulability"):
        np.testing.assert_allclose(v[key], sm[key], rtol=1e-12, atol=0, err_msg=key)
    assert v["max_ep_mm"] == v["max_position_error"] * 1e3 and v["max_eo_mrad"] == v["max_orientation_error"] * 1e3
    assert v["strays"] == (sm["max_position_error"] > 1e-3) and v["pseudo"] == (m == "pseudoinverse")
    if m == "pseudoinverse":
        assert v["drift"] == np.abs(r.e[:, COMPONENTS.index(s["relaxed"])]).max()
    te, ep = envelope(r.t, r.position_error, points)
    _, eo = envelope(r.t, r.orientation_error, points)
    idx = thin(len(r.t), points)
    np.testing.assert_allclose(v["t_env"], te, rtol=1e-12, atol=0)
    np.testing.assert_allclose(v["t_thin"], r.t[idx], rtol=1e-12, atol=0)
    np.testing.assert_allclose(v[f"ep_{m}"], ep, rtol=1e-12, atol=0)
    np.testing.assert_allclose(v[f"eo_{m}"], eo, rtol=1e-12, atol=0)
    np.testing.assert_allclose(v[f"w_{m}"], r.w[idx], rtol=1e-12, atol=0)
    for other in P.PANEL_METHODS:
        assert v[f"show_{other}"] == (other == m)
        if other != m:
            assert not v[f"ep_{other}"].any() and not v[f"w_{other}"].any()
    return status


# --------------------------------------------------------------------------------------------------
# the outputs are the package's numbers
# --------------------------------------------------------------------------------------------------
def test_outputs_are_the_package_runs_on_random_settings(short, program):
    rng = np.random.default_rng(7)
    statuses = [_check_against_package(program, short, _random_settings(rng, list(METHOD_CHOICES)[k % 4]))
                for k in range(48 if COMPILED else 12)]
    assert 0 in statuses and any(s != 0 for s in statuses)  # runs drawn and runs refused, both checked


@pytest.mark.skipif(not COMPILED, reason="the 70 s reference is run many times: compiled only")
def test_outputs_on_the_reference(ref):
    prog = clik_page_program(ref)
    rng = np.random.default_rng(11)
    for method in METHOD_CHOICES:
        assert _check_against_package(prog, ref, dict(DEFAULTS, method=method)) == 0
        _check_against_package(prog, ref, _random_settings(rng, method))


def test_fewer_samples_than_points_are_drawn_as_they_are(short):
    prog = clik_page_program(short, points=2000)  # 601 samples: no thinning
    _check_against_package(prog, short, _settings(method=LABELS["pseudoinverse"], relaxed="phi"), points=2000)
    _check_against_package(prog, short, _settings(method=LABELS["second_order"]), points=2000)


@pytest.mark.parametrize("n, points", [(10, 2), (10, 3), (11, 5), (12, 5), (601, 600), (601, 800), (70001, 800),
                                       (70001, 10_000), (1000, 999), (997, 13)])
def test_thinning_kernels_are_the_plots_own(n, points):
    t = np.arange(n) * 1e-3 + 0.25
    y = RNG.normal(size=n) * np.exp(RNG.uniform(-30, 0, size=n))
    y[::7] = 0.0
    tt, yy = np.zeros(n), np.zeros(n)
    k = P.envelope_kernel(t, y, points, tt, yy)
    te, ye = envelope(t, y, points)
    assert k == len(te) == P.envelope_length(n, points)
    np.testing.assert_array_equal(tt[:k], te)
    np.testing.assert_array_equal(yy[:k], ye)
    assert P.LOG_FLOOR == LOG_FLOOR
    k = P.thin_kernel(t, y, points, tt, yy)
    idx = thin(n, points)
    assert k == len(idx) == P.thin_length(n, points)
    np.testing.assert_array_equal(tt[:k], t[idx])
    np.testing.assert_array_equal(yy[:k], y[idx])


def test_data_holds_the_reference_at_the_declared_offsets(short):
    data = P.clik_data(short)
    h = P.HEADER.offsets
    n = len(short.t)
    assert int(data[h.n]) == n and data[h.dt] == short.dt and int(data[h.points]) == 800
    np.testing.assert_array_equal(data[int(data[h.t_at]):][:n], short.t)
    for key, arr in (("x_at", short.x), ("xd_at", short.xd), ("xdd_at", short.xdd)):
        at = int(data[getattr(h, key)])
        np.testing.assert_array_equal(data[at:at + 4 * n].reshape(n, 4), arr)
    assert len(data) == int(data[h.xdd_at]) + 4 * n
    from scara import start_configuration

    np.testing.assert_array_equal(data[h.q0:h.q0 + 4], start_configuration(short))


# --------------------------------------------------------------------------------------------------
# every refusal, with the package's message
# --------------------------------------------------------------------------------------------------
def _refuses(prog, s, code, expected):
    status, _ = _status(prog, s)
    assert status == code, (status, code)
    assert code in prog.refusals
    assert _refused_message(prog, s) == _head(s) + expected


def _package_message(fn, *a, **kw):
    with pytest.raises(ScaraError) as info:
        fn(*a, **kw)
    return str(info.value)


@pytest.mark.parametrize("method", ["inverse", "pseudoinverse"])
@pytest.mark.parametrize("i", range(4))
def test_gains_past_the_first_order_limit(short, program, method, i):
    s = _settings(method=LABELS[method], relaxed=COMPONENTS[(i + 1) % 4])
    s[GAIN_KEYS[i]] = 2500.0
    expected = _package_message(_package_run, short, s)
    _refuses(program, s, P.R_GAIN + 4 * (method == "pseudoinverse") + i, expected)
    assert "past the discrete-time stability limit" in expected


def test_relaxed_gain_is_not_checked(short, program):
    s = _settings(method=LABELS["pseudoinverse"], relaxed="x", Kx=2500.0)
    assert _check_against_package(program, short, s) == 0


def test_null_space_gain_past_its_limit():
    slow = _short(dt=0.1)  # dt = 0.1 s: k0 < 2 / (dt 2) = 10 1/s, within the slider
    prog = clik_page_program(slow)
    s = _settings(method=LABELS["pseudoinverse"], Kx=5.0, Ky=5.0, Kz=5.0, Kphi=5.0, k0=10.0)
    _refuses(prog, s, P.R_K0, _package_message(_package_run, slow, s))
    assert _check_against_package(prog, slow, dict(s, k0=9.5)) == 0


@pytest.mark.parametrize("gains", [(1600.0, 1600.0, 1600.0, 400.0), (400.0, 400.0, 2200.0, 100.0),
                                   (2500.0, 2500.0, 2500.0, 2500.0)])
def test_transpose_past_its_limit(request, gains):
    if not COMPILED and gains[2] < 2000.0:  # (a z gain past 2 / dt is refused on any path)
        pytest.skip("past the limit along the 70 s reference: compiled only")
    traj = request.getfixturevalue("ref") if COMPILED else _short()
    prog = clik_page_program(traj)
    s = _settings(method=LABELS["transpose"], **dict(zip(GAIN_KEYS, gains)))
    expected = _package_message(_package_run, traj, s)
    assert "largest eigenvalue of J J^T K reaches" in expected
    _refuses(prog, s, P.R_TRANSPOSE, expected)


def test_transpose_overflow(program):
    s = _settings(method=LABELS["transpose"], Kx=1e300, Ky=1e300)  # beyond the sliders: the kernel still refuses
    with np.errstate(over="ignore", invalid="ignore"):  # plain Python computes with numpy scalars
        status, _ = _status(program, s)
        message = _refused_message(program, s)
    assert status == P.R_TRANSPOSE_NONFINITE
    assert "gives a non-finite largest eigenvalue mu of J_A J_A^T K" in message


@pytest.mark.parametrize("i", range(4))
def test_second_order_past_jury(short, program, i):
    s = _settings(method=LABELS["second_order"])
    s[GAIN_KEYS[i]] = 2500.0
    expected = _package_message(_package_run, short, s)
    assert f"K_P[{COMPONENTS[i]}] = 6.25e+06" in expected and "|z| = 1.5 >= 1" in expected
    _refuses(program, s, P.R_JURY + i, expected)


@pytest.mark.parametrize("i", range(4))
def test_initial_error_above_the_bound(short, program, i):
    data = program.data.copy()
    at = int(data[P.HEADER.offsets.x_at])
    data[at + i] += 0.15  # x_d(0) moved away from the start q0 on component i
    prog = dataclasses.replace(program, data=data)
    x0 = data[at:at + 4]
    q0 = data[P.HEADER.offsets.q0:P.HEADER.offsets.q0 + 4]
    from scara import ScaraParams

    expected = _package_message(_check_initial_error, x0, q0, ScaraParams(), np.ones(4), 0.1)
    _refuses(prog, _settings(), P.R_INITIAL + i, expected)


def test_damping_above_its_ceiling(short, program):
    s = _settings(damping=11.0)  # beyond the slider
    _refuses(program, s, P.R_DAMPING, _package_message(_package_run, short, s))
    s = _settings(damping=11.0, method=LABELS["transpose"])  # the transpose does not read the damping
    assert _status(program, s)[0] == 0


def test_singular_start():
    tr = _constant([1.0, 0.0, 0.5, 0.0], T=0.2)  # the arm stretched along x: theta2 = 0
    prog = clik_page_program(tr)
    s = _settings(method=LABELS["second_order"])
    _refuses(prog, s, P.R_SINGULAR_START, _package_message(_package_run, tr, s))
    s = _settings(method=LABELS["inverse"])  # the inverse starts, and stops at once
    expected = _package_message(_package_run, tr, s)
    assert "singular" in expected
    _refuses(prog, s, P.R_DIVERGED + 8 * P.P_INVERSE + 5, expected)


def test_run_shorter_than_the_settling_time():
    tr = _constant([0.5, 0.2, 0.5, 0.0], T=0.05)
    prog = clik_page_program(tr)
    s = _settings()
    _refuses(prog, s, P.R_SHORT, _package_message(lambda: _package_run(tr, s).summary()))


@pytest.mark.parametrize("method", P.PANEL_METHODS)
def test_runs_that_leave_the_error_bound(method):
    fast = plan_path([[0.6, 0.3, 0.5], [0.2, -0.6, 0.3]], durations=[0.5], total=0.6)  # 1 m in 0.5 s
    prog = clik_page_program(fast)
    s = _settings(method=LABELS[method], Kx=1.0, Ky=1.0, Kz=1.0, Kphi=1.0, relaxed="z", damping=0.2)
    expected = _package_message(_package_run, fast, s)
    assert "the tracking error exceeded max_error (y error" in expected
    status, _ = _status(prog, s)
    base = P.R_DIVERGED + 8 * P.PANEL_METHODS.index(method)
    assert status == base + 1 + 1
    _refuses(prog, s, status, expected)


@pytest.mark.parametrize("m", range(4))
@pytest.mark.parametrize("status, cause", [(STATUS_NONFINITE, 0)] + [(STATUS_ERROR_BOUND, 1 + i) for i in range(4)]
                         + [(STATUS_SINGULAR, 5)])
def test_every_divergence_code_words_the_package_message(program, m, status, cause):
    """Each cause of a stop (the loop's status; the component past the bound) has its code and the words of
    scara._clik.result._fail: checked on a made-up stop, as a NaN or a singular step is hard to meet on purpose."""
    n, k = 6, 4
    t = np.arange(n) * 1e-3
    e = RNG.normal(size=(n, 4)) * 1e-3
    if status == STATUS_ERROR_BOUND:
        e[k, cause - 1] = 0.12 * (-1) ** cause
    q, w = RNG.normal(size=(n, 4)), RNG.uniform(0, 0.25, size=n)
    method = P.PANEL_METHODS[m]
    keep = np.ones(4)
    if method == "pseudoinverse" and status == STATUS_ERROR_BOUND:
        keep[cause % 4] = 0.0  # another component relaxed
    out = np.zeros(program.outputs.size)
    code = P._diagnosis(m, np.array([status, k], float), t, q, e, w, keep, out)
    assert code == P.R_DIVERGED + 8 * m + cause
    s = _settings(method=LABELS[method])
    values = program.values(out, s)
    result = ClikResult(t, q, q, None, q, e, w, q, method, keep.astype(bool), 1e-3)
    what = "the second-order CLIK" if method == "second_order" else f"the {method} CLIK"
    expected = str(_fail(np.array([status, k]), result, what))
    assert program.refusals[code].format(values) == _head(s) + expected


def test_refusals_are_declared_once_per_code(program):
    codes = set(program.refusals)
    assert len(codes) == 8 + 3 + 4 + 4 + 3 + 4 * 6
    assert 0 not in codes


# --------------------------------------------------------------------------------------------------
# the figure: the bindings redraw the builder's figure
# --------------------------------------------------------------------------------------------------
def _check_bindings(panel, v0, v1):
    pair = panel.figures[0]
    prog = panel.page
    first = _widget_safe(pair.build(v0).to_plotly_json())
    applied = apply_update(first, _widget_safe(pair.updated(v1)), pair)
    full = _widget_safe(pair.build(v1).to_plotly_json())
    assert len(applied["data"]) == len(full["data"]) == len(CLIK_PANEL_ROLES)
    for role, props in prog.traces["clik"].items():
        i = CLIK_PANEL_ROLES.index(role)
        for prop in props:
            assert applied["data"][i][prop] == full["data"][i][prop], (role, prop)
    for a, b in zip(applied["data"], full["data"]):  # and every other property of every trace
        assert a == b
    assert applied["layout"]["title"]["text"] == full["layout"]["title"]["text"]
    assert applied["layout"] == dict(full["layout"], title=applied["layout"]["title"])


def test_bindings_redraw_the_builders_figure(short):
    panel = clik_declaration(_short())
    assert panel.widget == "clik_panel" and panel.page is not None
    rng = np.random.default_rng(3)
    v0 = panel.compute(panel.defaults())
    checked = 0
    for k in range(24 if COMPILED else 8):
        s = _random_settings(rng, list(METHOD_CHOICES)[k % 4])
        try:
            v1 = panel.compute(s)
        except ScaraError:
            continue
        _check_bindings(panel, v0, v1)
        _check_bindings(panel, v1, v0)
        checked += 1
    assert checked >= (12 if COMPILED else 4)


def test_figure_shows_the_method_run(short):
    panel = clik_declaration(_short())
    for label, m in METHOD_CHOICES.items():
        v = panel.compute(_settings(method=label, relaxed="y"))
        fig = panel.figures[0].build(v)
        shown = [t for t in fig.data if t.visible is not False]
        assert len(shown) == 3 and all(t.line.color == shown[0].line.color for t in shown)
        assert shown[0].name == ("pseudo-inverse (y relaxed)" if m == "pseudoinverse" else label)
        assert shown[0].showlegend and not shown[1].showlegend and shown[2].name == "w"
        assert fig.layout.title.text == f"{label}: max ‖e_p‖ after 0.1 s = {v['max_ep_mm']:.4g} mm"


# --------------------------------------------------------------------------------------------------
# the translated kernel
# --------------------------------------------------------------------------------------------------
def test_translated_program_computes_what_numba_computes(program):
    from scara.page.translate import translate

    from ._node import run_js

    script = translate([P.clik_program])
    cases = [_settings(method=label, relaxed="y", damping=0.01, k0=3.0) for label in METHOD_CHOICES]
    cases += [_settings(Kz=2500.0), _settings(method=LABELS["transpose"], Kx=1.0, Ky=1.0, Kz=1.0, Kphi=1.0)]
    calls = [("clik_program", (program.pack(s, CONTROLS), program.data, np.zeros(program.outputs.size)), 1)
             for s in cases]
    results = run_js(script, calls)
    for s, (ret, args, _) in zip(cases, results):
        status, v = _status(program, s)
        assert int(ret) == status, s
        np.testing.assert_allclose(args[2], np.concatenate([np.atleast_1d(v[n]) for n in program.outputs.names]),
                                   rtol=1e-9, atol=1e-12)
