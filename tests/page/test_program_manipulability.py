"""The page program of the ellipses panel (scara.programs.manipulability): its outputs are the package's own
numbers (w, the SVD of the horizontal block of J_A, the arm, the ellipse outlines of scara.plots), its refusal
carries the panel's message, the figure's bindings redraw the builder's figure exactly, and the translated kernel
computes in Node what numba computes."""
from __future__ import annotations

import base64
import math

import numpy as np
import pytest

from scara import ScaraError, ScaraParams, jacobian, manipulability, pose
from scara._manipulability import Ellipsoid, force_ellipsoid, velocity_ellipsoid
from scara.kinematics import link_frames
from scara.plots.manipulability import ELLIPSE_TRACES, ellipse_xy, major_axis_angle
from scara.plots.panels import apply_update
from scara.programs.manipulability import (ELLIPSE_CLIP, ELLIPSE_DATA, ELLIPSE_OUTPUTS, ELLIPSE_POINTS,
                                           ellipse_data, ellipse_program, planar_ellipse_axes)
from scara.widgets.manipulability import manipulability_declaration

from _largest import record

RNG = np.random.default_rng(20261203)
LONG = ScaraParams().replace(a1=0.6, a2=0.35)


def _settings(n, rng=RNG):
    """``n`` random settings of the panel: angles on the sliders' 1° grid half of the time, anywhere else."""
    out = []
    for k in range(n):
        t1, t2 = rng.uniform(-180.0, 180.0, 2)
        if k % 2:
            t1, t2 = round(t1), round(t2)
        out.append(dict(theta1=float(t1), theta2=float(t2), scale=float(rng.uniform(0.01, 0.5))))
    return out


def _q(s):
    return np.array([math.radians(s["theta1"]), math.radians(s["theta2"]), 0.5, 0.0])


def _aligned(ell: Ellipsoid, phi: float) -> Ellipsoid:
    """``ell`` with its two principal axes' signs turned to point as the program's ``(cos phi, sin phi)`` and
    ``(-sin phi, cos phi)`` do (an axis has no sign: the SVD picks one, the closed form another)."""
    u = np.array([[math.cos(phi), -math.sin(phi)], [math.sin(phi), math.cos(phi)]])
    signs = np.sign(np.sum(ell.axes * u, axis=0))
    return Ellipsoid(ell.centre, ell.axes * signs, ell.lengths, ell.rows, ell.kind)


@pytest.mark.parametrize("p", [None, LONG], ids=["book robot", "a1 = 0.6, a2 = 0.35"])
def test_outputs_are_the_packages_numbers(p):
    robot = ScaraParams.resolve(p)
    d = manipulability_declaration(p=p)
    worst = dict(w=0.0, sigma=0.0, sigma2=0.0, arm=0.0, outline=0.0, axes=0.0, major=0.0)
    for s in _settings(300):
        v = d.compute(s)
        q = _q(s)
        H = jacobian(q, robot)[:2, :2]
        sv = np.linalg.svd(H, compute_uv=False)
        w = manipulability(q, robot)
        worst["w"] = max(worst["w"], abs(v["w"] - w) / max(w, 1e-300) if w > 0 else abs(v["w"]))
        worst["sigma"] = max(worst["sigma"], abs(v["sigma1"] - sv[0]) / sv[0])
        # the small semi-axis: LAPACK's is accurate to eps sigma_1 (absolute), the program's w / sigma_1 relatively
        worst["sigma2"] = max(worst["sigma2"], abs(v["sigma2"] - sv[1]) / sv[0])
        assert v["sigma1"] * v["sigma2"] == pytest.approx(w, rel=1e-14, abs=1e-300)
        assert v["sigma1"] ** 2 + v["sigma2"] ** 2 == pytest.approx(np.sum(H ** 2), rel=1e-13)
        singular = sv[1] < 1e-6 * sv[0]
        assert v["singular"] == float(singular) and v["force1"] == 1.0 / v["sigma1"]
        assert v["force2"] == (math.inf if singular else 1.0 / v["sigma2"])
        frames = link_frames(q, robot)
        arm = np.array([[0.0, 0.0], frames[1, :2, 3], frames[2, :2, 3]])
        worst["arm"] = max(worst["arm"], np.abs(np.c_[v["arm_x"], v["arm_y"]] - arm).max())
        np.testing.assert_allclose([v["arm_x"][2], v["arm_y"][2]], pose(q, robot)[:2], rtol=0, atol=1e-15)
        phi = math.radians(v["major"])
        assert -90.0 < v["major"] <= 90.0
        if abs(sv[0] - sv[1]) > 1e-3 * sv[0]:  # a round ellipse has no major axis
            major = major_axis_angle(velocity_ellipsoid(q, robot, rows=(0, 1)))
            worst["major"] = max(worst["major"], abs((v["major"] - major + 90.0) % 180.0 - 90.0))
        # the outlines and principal axes are those scara.plots draws (ellipse_xy; the axes as ellipse_traces draws
        # them), once the SVD's axes point the program's way
        for key, ell in (("vel", velocity_ellipsoid(q, robot, rows=(0, 1))),
                         ("force", force_ellipsoid(q, robot, rows=(0, 1)))):
            ell = _aligned(ell, phi)
            if key == "force" and singular:
                ell = Ellipsoid(ell.centre, ell.axes, np.array([ell.lengths[0], np.inf]), ell.rows, ell.kind)
            xy = ellipse_xy(ell, s["scale"], n=ELLIPSE_POINTS)
            worst["outline"] = max(worst["outline"], np.abs(np.c_[v[f"{key}_x"], v[f"{key}_y"]] - xy).max())
            seg = []
            for i in range(2):
                half = min(s["scale"] * ell.lengths[i], ELLIPSE_CLIP) * ell.axes[:, i]
                seg += [ell.centre[:2] - half, ell.centre[:2] + half, [np.nan, np.nan]]
            seg = np.array(seg)
            got = np.c_[v[f"{key}_axes_x"], v[f"{key}_axes_y"]]
            assert np.array_equal(np.isnan(got), np.isnan(seg))
            worst["axes"] = max(worst["axes"], np.nanmax(np.abs(got - seg)))
    assert record("w against scara.manipulability (relative)", worst["w"]) <= 1e-12
    assert record("sigma_1 against numpy's SVD (relative)", worst["sigma"]) <= 1e-12
    assert record("sigma_2 against numpy's SVD (relative to sigma_1)", worst["sigma2"]) <= 1e-12
    assert record("arm against link_frames (m)", worst["arm"]) <= 1e-12
    assert record("outlines against ellipse_xy (m)", worst["outline"]) <= 1e-12
    assert record("principal axes against ellipse_traces (m)", worst["axes"]) <= 1e-12
    assert record("major axis against major_axis_angle (deg)", worst["major"]) <= 1e-9


def test_outlines_satisfy_their_quadratic_forms():
    d = manipulability_declaration()
    for s in _settings(50):
        v = d.compute(s)
        q = _q(s)
        H = jacobian(q)[:2, :2]
        M = H @ H.T
        if abs(math.sin(q[1])) < 1e-3:
            continue
        c = pose(q)[:2]
        vel = np.c_[v["vel_x"], v["vel_y"]] - c
        frc = np.c_[v["force_x"], v["force_y"]] - c
        sc = s["scale"]
        # v^T (H H^T)^-1 v = scale^2 and f^T (H H^T) f = scale^2 (unclipped: the semi-axes stay under 50 m here)
        if sc * v["force2"] < ELLIPSE_CLIP:
            np.testing.assert_allclose(np.einsum("ni,ij,nj->n", frc, M, frc), sc ** 2, rtol=1e-9)
        np.testing.assert_allclose(np.einsum("ni,ij,nj->n", vel, np.linalg.inv(M), vel), sc ** 2, rtol=1e-9)
        assert vel[0] == pytest.approx(vel[-1], abs=1e-15)  # a closed line


@pytest.mark.parametrize("theta2", [0.0, 180.0, -180.0])
def test_a_singular_arm_has_an_unbounded_force_ellipse(theta2):
    d = manipulability_declaration()
    v = d.compute(dict(theta1=30.0, theta2=theta2, scale=0.15))
    assert v["singular"] == 1.0 and v["force2"] == math.inf and v["sigma2"] < 1e-15
    assert np.all(np.isfinite(v["force_x"])) and np.all(np.isfinite(v["force_y"]))
    c = np.array([v["arm_x"][2], v["arm_y"][2]])
    reach = np.hypot(v["force_x"] - c[0], v["force_y"] - c[1]).max()
    assert reach == pytest.approx(ELLIPSE_CLIP, rel=1e-12)  # clipped: a strip far outside the view
    rows, notes = d.summary(v)
    force = dict(rows)["force semi-axes 1/σ (N, unit torque norm; inf: unbounded along the links, singular arm)"]
    assert force.endswith(", inf") and "e+" not in force
    assert len(notes) == 1 and f"singular at θ2 = {theta2:.0f}°" in notes[0] and "unbounded" in notes[0]
    # a regular arm: no note, two numbers
    v = d.compute(dict(theta1=30.0, theta2=60.0, scale=0.15))
    rows, notes = d.summary(v)
    assert notes == [] and v["singular"] == 0.0 and "inf" not in dict(rows)["major velocity axis direction (°)"]


def test_closed_form_axes_on_their_own():
    # a diagonal block: the axes are the coordinate axes; a round one: phi = 0
    s1, s2, phi = planar_ellipse_axes(0.0, -0.5, -1.0, 0.0, 0.5)
    assert (s1, s2, phi) == (1.0, 0.5, math.pi / 2)
    s1, s2, phi = planar_ellipse_axes(1.0, 0.0, 0.0, 1.0, 1.0)
    assert (s1, s2, phi) == (1.0, 1.0, 0.0)
    H = RNG.normal(size=(2, 2))
    s1, s2, phi = planar_ellipse_axes(H[0, 0], H[0, 1], H[1, 0], H[1, 1], abs(np.linalg.det(H)))
    u = np.array([math.cos(phi), math.sin(phi)])
    np.testing.assert_allclose(H @ H.T @ u, s1 ** 2 * u, rtol=1e-13)
    np.testing.assert_allclose(np.linalg.svd(H, compute_uv=False), [s1, s2], rtol=1e-13)


def test_the_scale_of_zero_is_refused_with_the_panels_message():
    d = manipulability_declaration()
    with pytest.raises(ScaraError) as info:
        d.compute(dict(theta1=0.0, theta2=60.0, scale=0.0))
    assert str(info.value) == ("the ellipse scale is 0: it must be above 0 to draw the ellipses (metres drawn per "
                               "m/s and per N)")
    out = np.zeros(ELLIPSE_OUTPUTS.size)
    assert ellipse_program(np.array([0.0, 60.0, -0.1]), ellipse_data(ScaraParams()), out) == 1
    assert ellipse_program(np.array([0.0, 60.0, 0.1]), ellipse_data(ScaraParams()), out) == 0


def test_data_and_inputs():
    d = manipulability_declaration(p=LONG)
    assert d.page.inputs == ("theta1", "theta2", "scale") and d.widget == "manipulability_panel"
    np.testing.assert_array_equal(d.page.data, ELLIPSE_DATA.pack(a1=0.6, a2=0.35))
    assert d.defaults() == dict(theta1=0.0, theta2=pytest.approx(60.0), scale=0.15)


# ------------------------------------------------------------------------------------------------ the figure
def _decoded(v):
    """Plotly JSON with its base64 arrays (``{"dtype", "bdata"}``) and lists of numbers as float arrays."""
    if isinstance(v, dict):
        if "bdata" in v and "dtype" in v:
            return np.frombuffer(base64.b64decode(v["bdata"]), dtype=np.dtype(v["dtype"])).astype(float)
        return {k: _decoded(x) for k, x in v.items()}
    if isinstance(v, np.ndarray):
        return v.astype(float) if v.dtype.kind in "fiu" else v
    if isinstance(v, (list, tuple)) and v and all(isinstance(x, (int, float)) or x is None for x in v):
        return np.array([np.nan if x is None else x for x in v], dtype=float)
    if isinstance(v, (list, tuple)):
        return [_decoded(x) for x in v]
    return v


def _assert_same(a, b, where):
    a, b = _decoded(a), _decoded(b)
    if isinstance(b, np.ndarray) or isinstance(a, np.ndarray):
        np.testing.assert_array_equal(np.asarray(a), np.asarray(b), err_msg=str(where))
    elif isinstance(b, dict):
        assert isinstance(a, dict) and a.keys() == b.keys(), where
        for k in b:
            _assert_same(a[k], b[k], (*where, k))
    else:
        assert a == b, (where, a, b)


def check_bindings(d, settings_pairs):
    """For each ``(s0, s1)``: the builder's figure of ``s0`` with the program's update for ``s1`` applied is the
    builder's figure of ``s1``, in every trace property (the bound ones and the others) and the title; and every
    trace the bindings name exists."""
    for s0, s1 in settings_pairs:
        v0, v1 = d.compute(s0), d.compute(s1)
        for pair in d.figures:
            first = pair.build(v0).to_plotly_json()
            full = pair.build(v1).to_plotly_json()
            bound = d.page.traces[pair.role]
            names = [t.get("name") for t in full["data"]]
            assert set(bound) <= set(names), (set(bound) - set(names))
            applied = apply_update(first, pair.updated(v1), pair)
            assert len(applied["data"]) == len(full["data"])
            for i, (a, b) in enumerate(zip(applied["data"], full["data"])):
                assert a.keys() == b.keys(), (pair.role, i)
                for key in b:
                    _assert_same(a[key], b[key], (pair.role, i, key))
            assert applied["layout"]["title"]["text"] == full["layout"]["title"]["text"]
            _assert_same({k: v for k, v in applied["layout"].items() if k != "template"},
                         {k: v for k, v in full["layout"].items() if k != "template"}, (pair.role, "layout"))


def test_the_bindings_redraw_the_builders_figure():
    d = manipulability_declaration()
    settings = _settings(24)
    settings.append(dict(theta1=10.0, theta2=0.0, scale=0.3))  # singular: the force ellipse clipped
    check_bindings(d, list(zip(settings[:-1], settings[1:])))
    assert set(ELLIPSE_TRACES["ellipses"]) == {"arm", "velocity ellipse", "velocity principal axes", "force ellipse",
                                               "force principal axes"}
    fig = d.figures[0].build(d.compute(dict(theta1=20.0, theta2=-45.0, scale=0.2)))
    assert fig.layout.title.text == f"θ1 = 20°, θ2 = -45°: w = {0.25 * math.sin(math.pi / 4):.3f} m²"
    assert [t.line.dash for t in fig.data[1:]] == ["solid", "dot", "dash", "dot"]


# --------------------------------------------------------------------------------------- plain Python, Node
def test_plain_python_computes_what_numba_computes():
    py = getattr(ellipse_program, "py_func", None)
    if py is None:
        pytest.skip("numba is off: the kernel is plain Python already")
    data = ellipse_data(ScaraParams())
    for s in _settings(20):
        inputs = np.array([s["theta1"], s["theta2"], s["scale"]])
        a, b = np.zeros(ELLIPSE_OUTPUTS.size), np.zeros(ELLIPSE_OUTPUTS.size)
        assert ellipse_program(inputs, data, a) == py(inputs, data, b) == 0
        np.testing.assert_allclose(a, b, rtol=1e-13, atol=1e-15)


def test_the_translated_program_computes_what_numba_computes():
    translate = pytest.importorskip("scara.page.translate").translate
    from ._node import run_js

    js = translate([ellipse_program])
    data = ellipse_data(ScaraParams())
    calls, expected = [], []
    for s in _settings(40) + [dict(theta1=0.0, theta2=0.0, scale=0.2), dict(theta1=0.0, theta2=60.0, scale=0.0)]:
        inputs = np.array([s["theta1"], s["theta2"], s["scale"]])
        out = np.zeros(ELLIPSE_OUTPUTS.size)
        status = ellipse_program(inputs, data, out)
        calls.append(("ellipse_program", [inputs, data, np.zeros(ELLIPSE_OUTPUTS.size)], 1))
        expected.append((status, out))
    worst = 0.0
    for (ret, args, _), (status, out) in zip(run_js(js, calls), expected):
        assert ret == status
        got = args[2]
        assert np.array_equal(np.isnan(got), np.isnan(out)) and np.array_equal(np.isinf(got), np.isinf(out))
        fin = np.isfinite(out)
        worst = max(worst, float(np.max(np.abs(got[fin] - out[fin]) / np.maximum(np.abs(out[fin]), 1.0))))
    assert record("Node against numba", worst) <= 1e-12
