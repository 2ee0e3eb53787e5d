"""The page programs of chapter 1 (scara.programs.kinematics): the direct- and inverse-kinematics panels' moves as
one kernel each. Their outputs agree with the package's own functions on random settings, each refusal is reached
with the panel's message, each figure drawn from the outputs of one setting and updated by the program's bindings
to another equals the figure drawn for the other, the book's static figures come from the same kernels, and the
kernels translate to JavaScript and compute the same numbers under Node."""
from __future__ import annotations

import base64
import math
import re

import numpy as np
import pytest

from scara import ScaraError, ScaraParams, UnreachableError, ikine, jacobian, link_frames, manipulability, pose
from scara.plots import arm_figure, inverse_kinematics_figure
from scara.plots.kinematics import (LABEL_SIZE, _PHONE_HALF_WIDTH, _arm_plot_height, _scene, arm_program_data,
                                    scene_projection)
from scara.plots.layout import _text_width
from scara.plots.panels import apply_update
from scara.programs import kinematics as K
from scara.widgets.kinematics import inverse_kinematics_declaration, kinematics_declaration

P = ScaraParams()
OTHER = ScaraParams().replace(a1=0.6, a2=0.35, d3_min=0.1, d3_max=0.8)  # a hole in the workspace, a shorter stroke
RNG = np.random.default_rng(20240521)
N = 30  # random settings per check


def _settings_kinematics(n, p=P):
    """Random slider settings, with the boundary cases: the arm stretched and folded, the quill at its ends."""
    out = [dict(theta1=float(RNG.uniform(-180, 180)), theta2=float(RNG.uniform(-180, 180)),
                d3=float(RNG.uniform(p.d3_min, p.d3_max)), theta4=float(RNG.uniform(-180, 180))) for _ in range(n)]
    out += [dict(theta1=0.0, theta2=60.0, d3=0.5, theta4=0.0), dict(theta1=25.0, theta2=0.0, d3=0.3, theta4=0.0),
            dict(theta1=10.0, theta2=180.0, d3=p.d3_min, theta4=-40.0),
            dict(theta1=-120.0, theta2=-180.0, d3=p.d3_max, theta4=90.0),
            dict(theta1=120.0, theta2=-45.0, d3=p.d3_min, theta4=10.0)]
    return out


def _q(s):
    return np.array([math.radians(s["theta1"]), math.radians(s["theta2"]), s["d3"], math.radians(s["theta4"])])


def _targets(n, p=P):
    """Reachable targets (px, py, pz in m, phi in degrees): the poses of random configurations, and the rim."""
    out = []
    for _ in range(n):
        q = np.r_[RNG.uniform(-math.pi, math.pi, 2), RNG.uniform(p.d3_min, p.d3_max), RNG.uniform(-math.pi, math.pi)]
        x = pose(q, p)
        out.append(dict(px=float(x[0]), py=float(x[1]), pz=float(x[2]), phi=float(math.degrees(x[3]))))
    out += [dict(px=0.18, py=0.2, pz=0.5, phi=0.0), dict(px=1.0, py=0.0, pz=0.5, phi=30.0),
            dict(px=0.0, py=0.0, pz=0.0, phi=-90.0)]
    return out


def _close(a, b, tol=1e-12):
    a, b = np.asarray(a, float), np.asarray(b, float)
    np.testing.assert_allclose(a, b, rtol=tol, atol=tol * max(1.0, float(np.nanmax(np.abs(b)))))


# ------------------------------------------------------------------------------------ the direct-kinematics program
def _groups(frames):
    """Independent of the kernels: the frames sharing an origin, in order (the first origin each one meets)."""
    groups = []
    for k, o in enumerate(frames[:, :3, 3]):
        for g in groups:
            if np.linalg.norm(frames[g[0], :3, 3] - o) < 1e-9:
                g.append(k)
                break
        else:
            groups.append([k])
    return groups


def _reference_places(origins, labels, segments, scene, plot_height):
    """Independent of the kernels: the greedy placement of the frame names written with numpy (the candidates,
    nearest first; the free ones in the phone's plot area, scored by the drawing they cover plus half a point per
    rank), projected by :func:`scene_projection`. Returns the candidate each name takes."""
    project = scene_projection(scene, plot_height)
    samples = [a + np.linspace(0.0, 1.0, 9)[:, None] * (b - a) for a, b in segments]
    drawn = project(np.vstack(samples))
    h = 1.35 * LABEL_SIZE + 4.0
    boxes, chosen = [], []
    for text, (px, py) in zip(labels, project(origins)):
        w = _text_width(text, LABEL_SIZE) + 6.0
        best, best_score = len(K.CANDIDATES) - 1, None
        for rank, (xs, ys, fx, fy) in enumerate(K.CANDIDATES[:-1]):
            left, bottom = px + xs - fx * w, py + ys - fy * h
            box = (left, bottom, left + w, bottom + h)
            if box[0] < -_PHONE_HALF_WIDTH or box[2] > _PHONE_HALF_WIDTH or abs(box[1]) > plot_height / 2 or \
                    abs(box[3]) > plot_height / 2:
                continue
            if any(box[0] < b[2] + 3 and b[0] < box[2] + 3 and box[1] < b[3] + 3 and b[1] < box[3] + 3 for b in boxes):
                continue
            inside = (drawn[:, 0] > box[0]) & (drawn[:, 0] < box[2]) & (drawn[:, 1] > box[1]) & (drawn[:, 1] < box[3])
            score = int(inside.sum()) + 0.5 * rank
            if best_score is None or score < best_score:
                best, best_score = rank, score
        xs, ys, fx, fy = K.CANDIDATES[best]
        left, bottom = px + xs - fx * w, py + ys - fy * h
        boxes.append((left, bottom, left + w, bottom + h))
        chosen.append(best)
    return chosen


@pytest.mark.parametrize("p", [P, OTHER], ids=["book", "other"])
def test_kinematics_program_agrees_with_the_package(p):
    d = kinematics_declaration(p=p)
    scene = _scene(p)
    plot_height = _arm_plot_height(480, 2, True)
    for s in _settings_kinematics(N, p):
        v = d.compute(s)
        q = _q(s)
        assert np.array_equal(v["q"], q)
        frames = link_frames(q, p)
        frames = np.concatenate([np.eye(4)[None], frames])  # b, 0, 1, 2, 3, 4, e
        origins = frames[:, :3, 3]
        _close(v["origins"].reshape(7, 3), origins)
        _close(np.c_[v["arm_x"], v["arm_y"], v["arm_z"]], origins[[0, 1, 2, 3, 6]])
        for a, axis in enumerate("xyz"):  # triads 0.3 m long along the columns of each frame's rotation
            seg = np.c_[v[f"{axis}_axes_x"], v[f"{axis}_axes_y"], v[f"{axis}_axes_z"]].reshape(7, 3, 3)
            _close(seg[:, 0], origins)
            _close(seg[:, 1], origins + 0.3 * frames[:, :3, a])
            assert np.all(np.isnan(seg[:, 2]))
        x = pose(q, p)
        _close([v["px"], v["py"], v["pz"]], x[:3])
        _close(v["phi"], math.degrees(x[3]))
        assert abs(v["det"] - np.linalg.det(jacobian(q, p))) < 1e-14
        _close(v["w"], manipulability(q, p))
        assert v["singular"] == float(manipulability(q, p) < 1e-3)
        for key, val, half in (("title_px", x[0], 5e-4), ("title_pz", x[2], 5e-4),
                               ("title_phi", math.degrees(x[3]), 0.05), ("title_det", v["det"], 5e-4)):
            assert v[key] == (0.0 if abs(val) < half else val)
        # one name per distinct origin, in its slot; the others not drawn
        groups = _groups(frames)
        shown = [k for k in range(K.N_SLOTS) if np.isfinite(v["names_x"][k])]
        labels = [", ".join(K.FRAME_NAMES[k] for k in g) for g in groups]
        assert [K.SLOT_LABELS[k] for k in shown] == labels
        assert np.all(np.isnan(np.delete(v["names_choice"], shown)))
        segments = [(a, b) for a, b in zip(origins[[0, 1, 2, 3]], origins[[1, 2, 3, 6]])]
        segments += [(o, o + 0.3 * frames[k, :3, a]) for a in range(3) for k, o in enumerate(origins)]
        chosen = _reference_places(origins[[g[0] for g in groups]], labels, segments, scene, plot_height)
        assert [int(v["names_choice"][k]) for k in shown] == chosen, s
        # each name drawn at the depth of its frame's origin, where its box's centre projects
        project = scene_projection(scene, plot_height)
        spots = np.c_[v["names_x"][shown], v["names_y"][shown], v["names_z"][shown]]
        for g, label, spot, k in zip(groups, labels, spots, chosen):
            xs, ys, fx, fy = K.CANDIDATES[k]
            w = _text_width(label, LABEL_SIZE) + 6.0
            centre = project(origins[g[0]])[0] + [xs + (0.5 - fx) * w, ys + (0.5 - fy) * (1.35 * LABEL_SIZE + 4.0)]
            np.testing.assert_allclose(project(spot)[0], centre, atol=1e-6)


def _old_kinematics_summary(s, p=P):
    """The summary of the panel before its move was a program (its text, word for word)."""
    q = _q(s)
    x = pose(q, p)
    w = manipulability(q, p)
    rows = [("p_x, p_y, p_z (m)", f"{x[0]:.4f}, {x[1]:.4f}, {x[2]:.4f}"),
            ("phi = θ1 + θ2 + θ4 (°)", f"{math.degrees(x[3]):.2f}"),
            ("det J_A (m²)", None), ("w = |det J_A| (m²)", f"{w:.4f}")]
    notes = [f"The arm is singular here (w = {w:.2g} m², θ2 = {math.degrees(q[1]):.0f}°): it cannot move its tip "
             "along the line of its links."] if w < 1e-3 else []
    return rows, notes, float(np.linalg.det(jacobian(q, p)))


def test_kinematics_summary_and_title_read_as_before():
    d = kinematics_declaration()
    for s in _settings_kinematics(N):
        v = d.compute(s)
        rows, notes = d.summary(v)
        old_rows, old_notes, det = _old_kinematics_summary(s)
        assert [r for r in rows if r[0] != "det J_A (m²)"] == [r for r in old_rows if r[1] is not None]
        assert float(dict(rows)["det J_A (m²)"]) == pytest.approx(det, abs=1e-4)
        assert notes == old_notes
        title = d.page.titles["arm"].format(v)
        x = np.round(pose(_q(s)), 3) + 0.0
        assert title.startswith(f"p = ({x[0]:.3f}, {x[1]:.3f}, {x[2]:.3f}) m<br>φ = ")
        assert title.endswith(f"det J_A = {round(det, 3) + 0.0:.3f} m²")
        assert not [t for t in re.findall(r"-\d+\.\d+", title) if float(t) == 0.0], title  # no "-0.000"


# ----------------------------------------------------------------------------------- the inverse-kinematics program
def test_inverse_kinematics_program_agrees_with_the_package():
    d = inverse_kinematics_declaration()
    for s in _targets(N):
        v = d.compute(s)
        x = np.array([s["px"], s["py"], s["pz"], math.radians(s["phi"])])
        for elbow, key in ((+1, "up"), (-1, "down")):
            q = ikine(x, elbow=elbow)
            _close(v[f"q_{key}"], q)
            origins = link_frames(q)[:, :3, 3]
            _close(v[f"{key}_x"], [0.0, origins[1, 0], origins[2, 0]])
            _close(v[f"{key}_y"], [0.0, origins[1, 1], origins[2, 1]])
            for j, name in ((0, "theta1"), (1, "theta2"), (3, "theta4")):
                _close(v[f"{name}_{key}"], math.degrees(q[j]))
        assert v["theta2_down_size"] >= 0.0 and v["theta2_down_size"] == -v["theta2_down"]
        assert (v["target_x"], v["target_y"]) == (s["px"], s["py"])
        _close(v["r"], math.hypot(s["px"], s["py"]))
        assert v["d3"] == P.d0 - s["pz"]
        assert v["coincide"] == float(abs(math.sin(ikine(x)[1])) < 1e-3)
        rows, notes = d.summary(v)
        expected = [(f"elbow {e:+d}: θ1, θ2, θ4 (°); d3 (m)",
                     f"{math.degrees(q[0]):.2f}, {math.degrees(q[1]):.2f}, {math.degrees(q[3]):.2f}; {q[2]:.4f}")
                    for e, q in ((e, ikine(x, elbow=e)) for e in (+1, -1))]
        assert rows == expected
        assert bool(notes) == bool(v["coincide"])


def _old_unreachable_text(target, p=P) -> str:
    """The refusal of the panel before its move was a program (word for word)."""
    r = math.hypot(target[0], target[1])
    where = (f"the target (x, y, z) = ({target[0]:.3f}, {target[1]:.3f}, {target[2]:.3f}) m, "
             f"φ = {math.degrees(target[3]):.1f}°")
    if not (p.r_min - 1e-12 <= r <= p.r_max + 1e-12):
        return (f"{where} is out of reach: it lies r = {r:.4f} m from the joint-1 axis, and the arm reaches "
                f"from |a1 − a2| = {p.r_min:g} m to a1 + a2 = {p.r_max:g} m.")
    return (f"{where} is out of reach: z = {target[2]:.3f} m needs the quill at d3 = d0 − z = "
            f"{p.d0 - target[2]:.3f} m, outside its stroke d3_min to d3_max = {p.d3_min:g} to {p.d3_max:g} m.")


@pytest.mark.parametrize("p", [P, OTHER], ids=["book", "other"])
def test_each_refusal_is_reached_with_the_panels_message(p):
    d = inverse_kinematics_declaration(p=p)
    controls = {c.name: c for c in d.controls}
    cases = {1: [dict(px=2.0, py=0.2, pz=0.5, phi=0.0), dict(px=-0.3, py=1.2, pz=0.4, phi=45.0),
                 dict(px=1.1, py=-0.2, pz=1.5, phi=-30.0)],  # outside the annulus first, stroke or not
             2: [dict(px=0.3, py=0.2, pz=1.5, phi=0.0), dict(px=0.5, py=-0.4, pz=-0.7, phi=12.0)]}
    if p.r_min > 0:
        cases[1].append(dict(px=0.05, py=0.0, pz=0.5, phi=0.0))  # in the hole
    for code, settings in cases.items():
        for s in settings:
            out = np.zeros(K.IK_OUTPUTS.size)
            assert d.page.kernel(d.page.pack(s, controls), d.page.data, out) == code, s
            target = [s["px"], s["py"], s["pz"], math.radians(s["phi"])]
            with pytest.raises(ScaraError) as info:
                d.compute(s)
            assert str(info.value) == _old_unreachable_text(target, p)
    # an angle beyond the one the package takes: the message of ikine, checked first
    s = dict(px=2.0, py=0.3, pz=0.5, phi=1e9)
    with pytest.raises(ScaraError) as info:
        d.compute(s)
    with pytest.raises(ScaraError) as expected:
        ikine([2.0, 0.3, 0.5, math.radians(1e9)], p)
    assert str(info.value) == str(expected.value)
    # a start the arm cannot reach is refused as unreachable, with the same message
    with pytest.raises(UnreachableError) as info:
        inverse_kinematics_declaration([2.0, 0.2, 0.5, 0.0], p)
    assert str(info.value) == _old_unreachable_text([2.0, 0.2, 0.5, 0.0], p)
    # a number that is not finite never reaches the kernel
    with pytest.raises(ScaraError, match="px = nan is not finite"):
        d.compute(dict(px=float("nan"), py=0.2, pz=0.5, phi=0.0))


# ----------------------------------------------------------------------------------------- figures and bindings
def _plain(v):
    """A plotly JSON value with arrays and lists of numbers as float arrays (None as NaN; plotly's base64 arrays
    decoded), for exact comparison."""
    if isinstance(v, dict) and "bdata" in v and "dtype" in v:
        arr = np.frombuffer(base64.b64decode(v["bdata"]), dtype=np.dtype(v["dtype"]))
        return arr.astype(float).reshape([int(n) for n in str(v["shape"]).split(",")] if v.get("shape") else -1)
    if isinstance(v, dict):
        return {k: _plain(x) for k, x in v.items()}
    if isinstance(v, np.ndarray) or (isinstance(v, (list, tuple)) and v and
                                     all(x is None or isinstance(x, (int, float)) for x in v)):
        return np.array([np.nan if x is None else x for x in v], float) if not isinstance(v, np.ndarray) else \
            np.asarray(v, float)
    if isinstance(v, (list, tuple)):
        return [_plain(x) for x in v]
    return v


def _same(a, b, where):
    if isinstance(a, dict):
        assert isinstance(b, dict) and a.keys() == b.keys(), (where, set(a) ^ set(b))
        for k in a:
            _same(a[k], b[k], f"{where}.{k}")
    elif isinstance(a, np.ndarray):
        assert isinstance(b, np.ndarray) and a.shape == b.shape and np.array_equal(a, b, equal_nan=True), where
    elif isinstance(a, list):
        assert isinstance(b, list) and len(a) == len(b), where
        for i, (x, y) in enumerate(zip(a, b)):
            _same(x, y, f"{where}[{i}]")
    else:
        assert a == b, (where, a, b)


@pytest.mark.parametrize("declare, settings", [(kinematics_declaration, _settings_kinematics),
                                               (inverse_kinematics_declaration, _targets)], ids=["arm", "ik"])
def test_an_update_redraws_the_figure_of_the_new_setting(declare, settings):
    d = declare()
    (pair,) = d.figures
    cases = settings(8)
    start = d.compute(cases[0])
    first = pair.build(start).to_plotly_json()
    for s in cases[1:]:
        v = d.compute(s)
        applied = apply_update(first, pair.updated(v), pair)
        full = pair.build(v).to_plotly_json()
        # every trace property (bound or not) and the title; the rest of the layout does not move
        _same(_plain(applied["data"]), _plain(full["data"]), "data")
        assert applied["layout"] == full["layout"]


def test_the_static_figures_come_from_the_same_kernels():
    d = kinematics_declaration()
    for s in _settings_kinematics(6):
        v = d.compute(s)
        fig = arm_figure(_q(s), height=480)
        shown = [k for k in range(K.N_SLOTS) if np.isfinite(v["names_x"][k])]
        for trace, xyz in zip(fig.data, [("arm_x", "arm_y", "arm_z"), None, *[(f"{a}_axes_x", f"{a}_axes_y",
                                                                              f"{a}_axes_z") for a in "xyz"]]):
            if xyz is None:
                continue
            for prop, field in zip("xyz", xyz):
                np.testing.assert_allclose(_plain(list(getattr(trace, prop))), v[field], atol=5e-5)
        names = fig.data[-1]
        assert list(names.text) == [K.SLOT_LABELS[k] for k in shown]
        np.testing.assert_allclose(np.asarray(names.x, float), v["names_x"][shown], atol=5e-5)
        assert fig.layout.title.text == d.page.titles["arm"].format(v)
    d = inverse_kinematics_declaration()
    for s in _targets(6):
        v = d.compute(s)
        fig = inverse_kinematics_figure([s["px"], s["py"], s["pz"], math.radians(s["phi"])])
        assert fig.layout.title.text == d.page.titles["inverse kinematics"].format(v)
        for key, name in (("up", "elbow +1"), ("down", "elbow −1")):
            t = next(t for t in fig.data if t.name == name)
            np.testing.assert_allclose(np.asarray(t.x, float), v[f"{key}_x"], atol=5e-5)
    with pytest.raises(UnreachableError, match="annulus"):
        inverse_kinematics_figure([1.5, 0.0, 0.5, 0.0])


def test_declarations_name_their_widgets_and_describe_their_programs():
    import json

    for d, widget in ((kinematics_declaration(), "kinematics_panel"),
                      (inverse_kinematics_declaration(), "inverse_kinematics_panel")):
        assert d.widget == widget and d.page is not None
        described = d.page.describe(d)
        json.dumps(described, allow_nan=False)
        assert described["kernel"] in ("kinematics_program", "inverse_kinematics_program")
    # the data a program is given is made for the figure it draws
    assert np.array_equal(kinematics_declaration().page.data, arm_program_data(P))


# --------------------------------------------------------------------------------------------- the page's engine
def test_the_programs_translate_and_compute_the_same_under_node():
    from scara.page.translate import translate

    from ._node import run_js

    js = translate([K.kinematics_program, K.inverse_kinematics_program])
    dk, di = kinematics_declaration(), inverse_kinematics_declaration()
    ck, ci = ({c.name: c for c in d.controls} for d in (dk, di))
    calls, expected = [], []
    for s in _settings_kinematics(10):
        vec = dk.page.pack(s, ck)
        out = np.zeros(K.ARM_OUTPUTS.size)
        status = K.kinematics_program(vec, dk.page.data, out)
        calls.append(("kinematics_program", [vec, dk.page.data, np.zeros(K.ARM_OUTPUTS.size)], 1))
        expected.append((status, out))
    for s in _targets(10) + [dict(px=2.0, py=0.2, pz=0.5, phi=0.0), dict(px=0.3, py=0.2, pz=1.5, phi=0.0)]:
        vec = di.page.pack(s, ci)
        out = np.zeros(K.IK_OUTPUTS.size)
        status = K.inverse_kinematics_program(vec, di.page.data, out)
        calls.append(("inverse_kinematics_program", [vec, di.page.data, np.zeros(K.IK_OUTPUTS.size)], 1))
        expected.append((status, out))
    for (ret, args, _), (status, out) in zip(run_js(js, calls), expected):
        assert ret == status
        got = args[2]
        assert np.array_equal(np.isnan(got), np.isnan(out))
        ok = np.isfinite(out)
        np.testing.assert_allclose(got[ok], out[ok], rtol=1e-12, atol=1e-12)
