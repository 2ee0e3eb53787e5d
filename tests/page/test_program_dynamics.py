"""The page program of the inertia panel (scara.programs.dynamics): its outputs are the package's own numbers
(B, inertia_split, g, the PD + gravity sag of PDGravityController), the Jacobi eigenvalues agree with LAPACK's,
each refusal carries the panel's message, the figure's bindings redraw the builder's figure exactly, and the
translated kernel computes in Node what numba computes."""
from __future__ import annotations

import math

import numpy as np
import pytest

from scara import PDGravityController, ScaraError, ScaraParams, gravity, inertia
from scara.dynamics import dynamic_array, inertia_split
from scara.plots.dynamics import INERTIA_TRACES, inertia_figure, text_colours
from scara.programs.dynamics import (B_FIELDS, DYNAMICS_DATA, DYNAMICS_OUTPUTS, REFUSED_GAIN, REFUSED_PAYLOAD,
                                     REFUSED_SAG, dynamics_data, dynamics_program, inertia_values,
                                     symmetric_eigenvalues)
from scara._simulate.controllers import pd_gravity_steady_state_kernel
from scara.widgets.dynamics import dynamics_declaration

from _largest import record

from .test_program_manipulability import check_bindings

RNG = np.random.default_rng(20261204)
HEAVY = ScaraParams().replace(I_m=(0.02, 0.01, 0.01, 0.002), a1=0.6, d3_min=0.1, d3_max=0.8)


def _settings(n, p=None, rng=RNG):
    p = ScaraParams.resolve(p)
    return [dict(payload=float(rng.uniform(0.0, 20.0)), theta1=float(rng.uniform(-180, 180)),
                 theta2=float(rng.uniform(-180, 180)), d3=float(rng.uniform(p.d3_min, p.d3_max)),
                 theta4=float(rng.uniform(-180, 180)), K_P3=float(10 ** rng.uniform(2, 6))) for _ in range(n)]


def _q(s):
    return np.array([math.radians(s["theta1"]), math.radians(s["theta2"]), s["d3"], math.radians(s["theta4"])])


def _sag(s, p):
    ctrl = PDGravityController(K_P=(1.0, 1.0, s["K_P3"], 1.0), model=p.with_payload(0.0))
    return -ctrl.steady_state_error(p.with_payload(s["payload"]))[2]


@pytest.mark.parametrize("p", [None, HEAVY], ids=["book robot", "another robot"])
def test_outputs_are_the_packages_numbers(p):
    robot = ScaraParams.resolve(p)
    d = dynamics_declaration(p=p)
    worst = dict(eig=0.0, shade=0.0)
    drawn = refused = 0
    for s in _settings(300, robot):
        sag = _sag(s, robot)
        if s["d3"] + sag > robot.d3_max:
            refused += 1
            with pytest.raises(ScaraError, match="past the end of its stroke"):
                d.compute(s)
            continue
        drawn += 1
        v = d.compute(s)
        plant = robot.with_payload(s["payload"])
        q = _q(s)
        B = inertia(q, plant)
        assert np.array_equal([v[f] for f in B_FIELDS], B.ravel())  # the same kernel, the same robot
        parts = inertia_split(q, plant)
        for key, field in (("links", "d_links"), ("rotors", "d_rotors"), ("payload", "d_payload")):
            assert np.array_equal(v[field], np.diag(parts[key])), key
        shade = np.log10(np.abs(B) + 1e-3).ravel()
        worst["shade"] = max(worst["shade"], np.abs(v["shade"] - shade).max())
        assert v["cmax"] == pytest.approx(max(shade.max(), 0.0), abs=1e-15)
        eig = np.linalg.eigvalsh(B)
        got = np.array([v[f"eig{i}"] for i in range(1, 5)])
        worst["eig"] = max(worst["eig"], np.max(np.abs(got - eig) / eig))
        assert v["cond"] == got[3] / got[0]
        assert np.array_equal([v[f"g{i}"] for i in range(1, 5)], gravity(q, plant))
        assert v["sag"] == sag and v["sag_mm"] == sag * 1e3 and v["d3_need"] == s["d3"] + sag
        assert v["sag_note"] == float(sag > 0.003)
    assert drawn > 100 and refused > 10
    assert record("eigenvalues against numpy.linalg.eigvalsh (relative, each)", worst["eig"]) <= 1e-12
    assert record("shades against numpy's log10", worst["shade"]) <= 1e-15


def test_jacobi_eigenvalues_against_lapack():
    worst = 0.0
    for n in (1, 2, 3, 4, 5, 6):
        for _ in range(200):
            X = RNG.normal(size=(n, n))
            A = X + X.T if _ % 2 else X @ X.T + 1e-3 * np.eye(n)  # indefinite, or positive definite
            got = np.empty(n)
            symmetric_eigenvalues(A, got)
            worst = max(worst, np.abs(got - np.linalg.eigvalsh(A)).max() / np.abs(A).max())
    A = np.diag([3.0, 1.0, 2.0, 1.0])  # already diagonal (a repeated eigenvalue): no rotation, only the sort
    got = np.empty(4)
    symmetric_eigenvalues(A, got)
    assert got.tolist() == [1.0, 1.0, 2.0, 3.0] and A[0, 0] == 3.0
    assert record("Jacobi against eigvalsh, random symmetric (relative to max |a_ij|)", worst) <= 1e-13


def test_inertia_matrix_structure_behind_the_eigenvalue_kernel():
    """B34 = 0, B13 = B23, B14 = B24: (e1 - e2)/sqrt 2 couples with (e1 + e2)/sqrt 2 only, but no block splits
    off (B13 and B14 are not zero), so the eigenvalues need the full 4x4 iteration."""
    B = inertia([0.3, -1.1, 0.4, 0.2], ScaraParams().with_payload(5.0))
    assert B[2, 3] == 0.0 and B[0, 2] == B[1, 2] != 0.0 and B[0, 3] == B[1, 3] != 0.0
    P = np.array([[1, 1, 0, 0], [-1, 1, 0, 0], [0, 0, math.sqrt(2), 0], [0, 0, 0, math.sqrt(2)]]) / math.sqrt(2)
    T = P.T @ B @ P
    assert np.allclose(T[0, 2:], 0.0, atol=1e-15) and abs(T[0, 1]) > 1 and abs(T[1, 2]) > 0.1 and abs(T[1, 3]) > 1


def test_the_refusals_carry_the_panels_messages():
    d = dynamics_declaration()
    s = dict(payload=20.0, theta1=0.0, theta2=-90.0, d3=0.5, theta4=0.0, K_P3=100.0)
    sag = 20.0 * 9.81 / 100.0
    with pytest.raises(ScaraError) as info:
        d.compute(s)
    assert str(info.value) == (
        f"with K_P3 = {100.0:.3g} N/m the {20.0:g} kg payload would sag {sag * 1e3:.1f} mm under PD + gravity: the "
        f"quill, at d3 = {0.5:.2f} m, would need d3 = {0.5 + sag:.3f} m, past the end of its stroke (d3_min to "
        "d3_max = 0 to 1 m). Raise K_P3 or lighten the payload.")
    with pytest.raises(ScaraError, match=r"^payload = -1 must be >= 0$"):
        d.compute(dict(s, payload=-1.0))
    with pytest.raises(ScaraError, match=r"^K_P3 = 0 must be > 0$"):
        d.compute(dict(s, K_P3=0.0))
    out = np.zeros(DYNAMICS_OUTPUTS.size)
    data = dynamics_data(ScaraParams())
    for inputs, code in (([20.0, 0.0, -90.0, 0.5, 0.0, 100.0], REFUSED_SAG),
                         ([-1.0, 0, 0, 0.5, 0, 1e4], REFUSED_PAYLOAD),
                         ([1.0, 0, 0, 0.5, 0, -5.0], REFUSED_GAIN), ([1.0, 0, 0, 0.5, 0, 1e4], 0)):
        assert dynamics_program(np.array(inputs, dtype=float), data, out) == code
    # the stroke is the robot's: a shorter quill refuses sooner, and says so
    short = ScaraParams().replace(d3_min=0.1, d3_max=0.6)
    with pytest.raises(ScaraError, match=r"d3_min to d3_max = 0.1 to 0.6 m\)"):
        dynamics_declaration(q=(0.0, 0.0, 0.59, 0.0), K_P3=1e4, p=short).compute(
            dict(payload=20.0, theta1=0.0, theta2=0.0, d3=0.59, theta4=0.0, K_P3=1e4))


def test_the_summary_is_the_panels_table():
    d = dynamics_declaration()
    v = d.compute(dict(payload=5.0, theta1=0.0, theta2=-90.0, d3=0.5, theta4=0.0, K_P3=1e4))
    rows, notes = d.summary(v)
    B = inertia([0.0, -math.pi / 2, 0.5, 0.0], ScaraParams().with_payload(5.0))
    eig = np.linalg.eigvalsh(B)
    assert rows == [("eigenvalues of B", ", ".join(f"{x:.4g}" for x in eig)),
                    ("condition number of B", f"{eig[-1] / eig[0]:.1f}"),
                    ("gravity torques g(q) (N m, N m, N, N m)", "0, 0, -147.2, 0"),
                    ("quill sag under PD + gravity (payload-free model)", "4.905 mm = m_L g0 / K_P3")]
    assert notes == ["The quill sags 4.9 mm with K_P3 = 1e+04 N/m: more than 3 mm, visible at the tool. A stiffer "
                     "K_P3, integral action or a model that knows the payload (chapter 6) removes it."]
    rows, notes = d.summary(d.compute(dict(payload=1.0, theta1=0.0, theta2=-90.0, d3=0.5, theta4=0.0, K_P3=1e4)))
    assert notes == [] and rows[3][1] == "0.981 mm = m_L g0 / K_P3"


def test_steady_state_error_is_the_kernels():
    for _ in range(200):
        model = ScaraParams().replace(m_L=float(RNG.uniform(0, 10)), g0=float(RNG.uniform(9.7, 9.9)))
        plant = ScaraParams().replace(m_L=float(RNG.uniform(0, 10)), m_l3=float(RNG.uniform(5, 15)))
        kp = float(10 ** RNG.uniform(0, 6))
        e = PDGravityController(K_P=(1e4, 4e3, kp, 600.0), model=model).steady_state_error(plant)
        assert e[[0, 1, 3]].tolist() == [0.0, 0.0, 0.0]
        assert e[2] == (model.m3 * model.g0 - plant.m3 * plant.g0) / kp  # the formula it replaced, to the last bit
        assert e[2] == pd_gravity_steady_state_kernel(dynamic_array(model), dynamic_array(plant), kp)
    assert PDGravityController(K_P=(1e4, 4e3, 0.0, 600.0)).steady_state_error(ScaraParams())[2] == math.inf
    assert pd_gravity_steady_state_kernel(dynamic_array(), dynamic_array(), 0.0) == math.inf


# ------------------------------------------------------------------------------------------------ the figure
def test_the_bindings_redraw_the_builders_figure():
    d = dynamics_declaration()
    settings = [s for s in _settings(40) if s["d3"] + _sag(s, ScaraParams()) <= 1.0][:20]
    settings.insert(0, d.defaults())
    check_bindings(d, list(zip(settings[:-1], settings[1:])))
    assert set(INERTIA_TRACES["inertia"]) == {"B(q) shade", "B(q)", "link inertia", "rotors", "payload"}
    fig = d.figures[0].build(d.compute(dict(d.defaults(), payload=2.5, theta2=30.0)))
    assert fig.layout.title.text == "B(q) with a 2.5 kg payload at θ2 = 30°"


def test_the_text_colours_need_no_binding_over_the_sliders_range():
    """The entries' text colours (white on the dark squares) are the one data-dependent property left unbound
    (a binding sets numbers and strings, not a list of colours chosen by a threshold): over the panel's range of
    payload and theta2 (the only settings B depends on) they do not change, so every figure the panel draws has
    the colours of its first."""
    first = text_colours(inertia_values([0.0, 0.0, 0.5, 0.0], ScaraParams())["shade"])
    for m in np.arange(0.0, 20.01, 0.5):
        p = ScaraParams().with_payload(m)
        for t2 in range(-180, 181):
            assert text_colours(inertia_values([0.0, math.radians(t2), 0.5, 0.0], p)["shade"]) == first, (m, t2)
    fig = inertia_figure([0.0, 0.3, 0.5, 0.0], ScaraParams().with_payload(20.0))
    assert list(fig.data[1].textfont.color) == first and first.count("white") == 10


def test_the_static_figure_is_drawn_from_the_same_kernel():
    q, p = np.array([0.2, 1.3, 0.4, -0.5]), ScaraParams().with_payload(7.0)
    fig = inertia_figure(q, p, "B")
    v = inertia_values(q, p)
    assert list(fig.data[1].text) == [f"{x:.3g}" for x in inertia(q, p).ravel()]
    assert np.array_equal(fig.data[0].z, v["shade"]) and fig.data[0].zmax == v["cmax"]
    assert [t.name for t in fig.data] == ["B(q) shade", "B(q)", "link inertia", "rotors", "payload"]
    assert np.array_equal(np.asarray(fig.data[4].x), np.diag(inertia_split(q, p)["payload"]))


# --------------------------------------------------------------------------------------- plain Python, Node
def _inputs(s):
    return np.array([s["payload"], s["theta1"], s["theta2"], s["d3"], s["theta4"], s["K_P3"]])


def test_plain_python_computes_what_numba_computes():
    py = getattr(dynamics_program, "py_func", None)
    if py is None:
        pytest.skip("numba is off: the kernel is plain Python already")
    data = dynamics_data(ScaraParams())
    for s in _settings(30):
        a, b = np.zeros(DYNAMICS_OUTPUTS.size), np.zeros(DYNAMICS_OUTPUTS.size)
        assert dynamics_program(_inputs(s), data, a) == py(_inputs(s), data, b)
        np.testing.assert_allclose(a, b, rtol=1e-13, atol=1e-15)


def test_the_translated_program_computes_what_numba_computes():
    translate = pytest.importorskip("scara.page.translate").translate
    from ._node import run_js

    js = translate([dynamics_program])
    data = dynamics_data(ScaraParams())
    calls, expected = [], []
    for s in _settings(60) + [dict(payload=-1.0, theta1=0, theta2=0, d3=0.5, theta4=0, K_P3=1e4)]:
        out = np.zeros(DYNAMICS_OUTPUTS.size)
        expected.append((dynamics_program(_inputs(s), data, out), out))
        calls.append(("dynamics_program", [_inputs(s), data, np.zeros(DYNAMICS_OUTPUTS.size)], 1))
    worst, codes = 0.0, set()
    for (ret, args, _), (status, out) in zip(run_js(js, calls), expected):
        assert ret == status
        codes.add(status)
        worst = max(worst, float(np.max(np.abs(args[2] - out) / np.maximum(np.abs(out), 1.0))))
    assert codes == {0, REFUSED_SAG, REFUSED_PAYLOAD}
    assert record("Node against numba", worst) <= 1e-12
    assert DYNAMICS_DATA.size == len(data)
