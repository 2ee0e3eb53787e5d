"""The page program of chapter 3's waypoint editor (scara.programs.trajectory): one move re-planned, checked,
summarised and thinned in one kernel. Its outputs agree with plan_path and the trajectory's own summary on random
edits; every refusal it can reach says what JupyterLab showed (the planner's message in the panel's units); each
figure drawn from the outputs of one setting and updated by the program's bindings to another equals the figure
drawn for the other; the Jupyter panel keeps the last accepted plan; the kernel translates to JavaScript and
computes the same numbers under Node."""
from __future__ import annotations

import re

import numpy as np
import pytest

pytest.importorskip("ipywidgets")

from scara import Arc, ScaraError, Waypoint, link_frames, plan_path, reference_plan  # noqa: E402
from scara.plots.panels import apply_update  # noqa: E402
from scara.plots.trajectory import decimate, segment_shapes  # noqa: E402
from scara.programs import trajectory as E  # noqa: E402
from scara.trajectory import _plan as K  # noqa: E402
from scara.widgets._common import _same, _widget_safe, readable  # noqa: E402
from scara.widgets.trajectory import PROFILE_POINTS, TOP_POINTS, waypoint_editor_declaration  # noqa: E402

RNG = np.random.default_rng(20240604)
REF = dict(reference_plan(), total=None)
SHORT = dict(waypoints=[Waypoint((0.3, 0.2, 0.5)), Waypoint((0.5, 0.2, 0.5), anticipation=0.5),
                        Waypoint((0.5, 0.4, 0.4)), Waypoint((0.35, 0.45, 0.45))],
             durations=[2.0, 1.5, 2.5], arcs={2: (0.45, 0.5, 0.42)})


def _decl(plan=None):
    return waypoint_editor_declaration(plan)


def _controls(d):
    return {c.name: c for c in d.controls}


def _run(d, settings):
    """The program's values for ``settings`` (a fresh run: the declaration's plan is not changed)."""
    return d.page.run(settings, _controls(d))


def _edited(plan, s):
    """The plan the editor plans for ``settings``, built independently of the program."""
    plan = dict(plan, waypoints=[w if isinstance(w, Waypoint) else Waypoint(w) for w in plan["waypoints"]],
                durations=list(plan["durations"]))
    w = plan["waypoints"][s["point"]]
    plan["waypoints"][s["point"]] = w.replace(position=(s["x"], s["y"], s["z"]),
                                              anticipation=s["anticipation"] if s["via"] else 0.0)
    plan["durations"][s["segment"]] = s["duration"]
    return plan


def _random_settings(plan, n, spread=0.08):
    wps = plan["waypoints"]
    out = []
    for _ in range(n):
        i, j = int(RNG.integers(len(wps))), int(RNG.integers(len(wps) - 1))
        x, y, z = (round(float(v + RNG.normal(0, spread)) / 0.005) * 0.005 for v in wps[i].position)
        via = bool(RNG.integers(2)) and 0 < i < len(wps) - 1
        out.append(dict(point=i, via=via, x=x, y=y, z=z, anticipation=round(float(RNG.uniform(0.1, 1.2)), 1),
                        segment=j, duration=round(float(RNG.uniform(1.0, 9.0)), 1)))
    return out


def _normalised(msg):
    """A message with numpy's array padding removed (``[0.18, 0.2 , 0.5 ]`` -> ``[0.18, 0.2, 0.5]``)."""
    return re.sub(r"\[\s+", "[", re.sub(r"\s+(?=[,\]])", "", msg))


def _close(a, b, tol=1e-12):
    a, b = np.asarray(a, float), np.asarray(b, float)
    np.testing.assert_allclose(a, b, rtol=tol, atol=tol * max(1.0, float(np.nanmax(np.abs(b))) if b.size else 1.0))


def _check_values(v, traj, s):
    """The program's outputs ``v`` against the trajectory ``traj`` plan_path gives for the settings ``s``."""
    summ = traj.summary()
    assert v["motion_end"] == traj.motion_end
    _close(v["peak_speed_cm"], 100 * summ["max_speed"])
    _close(v["peak_acc_cm"], 100 * summ["max_acceleration"])
    _close(v["w_min"], summ["min_manipulability"])
    assert v["w_min_time"] == summ["min_manipulability_time"]
    assert v["near_singular"] == (summ["min_manipulability"] < 0.01)
    n = len(traj.labels)
    corners = traj.corner_distances()
    for i in range(1, n - 1):
        want = 1000 * corners[traj.labels[i]][0] if traj.via[i] else 0.0
        _close(v[f"corner_{i}"], want)
    # the arm at t = 0: base axis, elbow, wrist
    origins = link_frames(traj.q0, traj.params)[:3, :3, 3]
    _close(v["arm_x"], origins[:, 0])
    _close(v["arm_y"], origins[:, 1])
    via = np.asarray(traj.via)
    for kind, mask in (("stop", ~via), ("via", via)):
        for c, comp in enumerate("xy"):
            got = v[f"{kind}_{comp}"]
            assert np.array_equal(np.isnan(got), ~mask)
            assert np.array_equal(got[mask], traj.waypoints[mask, c])
    assert (v["edit_point"], v["edit_x"], v["edit_y"]) == (s["point"], s["x"], s["y"])
    # the thinned series: decimate's samples, then the last one repeated
    for points, names in ((TOP_POINTS, ("path_x", "path_y")), (PROFILE_POINTS, ("prof_t",) + E.PROFILE_SERIES)):
        k = decimate(traj, points)
        size = points + 2 * (n - 1)
        k = np.r_[k, np.full(size - k.size, traj.t.size - 1)]
        series = {"path_x": traj.x[k, 0], "path_y": traj.x[k, 1], "prof_t": traj.t[k],
                  "prof_phi": np.degrees(traj.x[k, 3])}
        for c, comp in enumerate("xyz"):
            series[f"prof_{comp}"], series[f"prof_v{comp}"], series[f"prof_a{comp}"] = (
                traj.x[k, c], traj.xd[k, c], traj.xdd[k, c])
        for name in names:
            assert np.array_equal(v[name], series[name]), name
    # the bands: every other segment, and the overlap at each via point (shown only there)
    for g in range(n // 2):
        assert (v[f"band_{g}_x0"], v[f"band_{g}_x1"]) == (traj.segment_start[2 * g], traj.segment_end[2 * g])
    for i in range(1, n - 1):
        assert (v[f"overlap_{i}_x0"], v[f"overlap_{i}_x1"]) == (traj.segment_start[i], traj.segment_end[i - 1])
        assert v[f"overlap_{i}_on"] == float(bool(traj.via[i]))


# ------------------------------------------------------------------------------------------ outputs vs the package
@pytest.mark.parametrize("plan, count", [(REF, 10), (SHORT, 25)], ids=["reference", "short"])
def test_outputs_agree_with_plan_path_on_random_edits(plan, count):
    d = _decl(plan)
    accepted = refused = 0
    for s in [d.defaults()] + _random_settings(plan, count):
        try:
            traj = plan_path(**_edited(plan, s))
        except ScaraError as exc:
            with pytest.raises(ScaraError) as got:
                _run(d, s)
            assert _normalised(str(got.value)) == _normalised(readable(str(exc)))
            refused += 1
            continue
        _check_values(_run(d, s), traj, s)
        accepted += 1
    assert accepted >= 3


def test_summary_rows_and_notes_are_the_trajectorys():
    d = _decl()
    v = _run(d, d.defaults())
    rows, notes = d.summary(v)
    traj = plan_path(**REF)
    s = traj.summary()
    assert rows[0] == ("motion ends at (s)", f"{s['motion_end']:.1f}")
    assert rows[1] == ("peak speed (cm/s)", f"{100 * s['max_speed']:.2f}")
    assert rows[2] == ("peak acceleration (cm/s²)", f"{100 * s['max_acceleration']:.2f}")
    assert rows[3] == ("min manipulability (m²)",
                       f"{s['min_manipulability']:.4f} at {s['min_manipulability_time']:.1f} s")
    corners = dict(part.split(": ") for part in rows[4][1].split(", "))
    assert list(corners) == [f"p{i}" for i in range(1, 11)]
    for name, mm in s["corner_distances"].items():
        assert corners[name] == f"{1000 * mm:.1f} mm"
    assert corners["p1"] == "0.0 mm" and notes == []
    # a path through the singular rim: the note says so
    near = dict(waypoints=[(0.3, 0.0, 0.5), (0.9999, 0.0, 0.5)], durations=[2.0])
    dn = _decl(near)
    vn = _run(dn, dn.defaults())
    (note,) = dn.summary(vn)[1]
    assert "close to a singular configuration" in note and vn["w_min"] < 0.01


# ---------------------------------------------------------------------------------------------------- refusals
def _settings_for(plan, point, **changes):
    w = plan["waypoints"][point]
    w = w if isinstance(w, Waypoint) else Waypoint(w)
    s = dict(point=point, via=w.via, x=w.position[0], y=w.position[1], z=w.position[2],
             anticipation=w.anticipation or 1.0, segment=min(point, len(plan["durations"]) - 1))
    s["duration"] = plan["durations"][s["segment"]]
    s.update(changes)
    return s


_BLENDED = dict(SHORT, blends=[0.8, None, None])
_GIVEN = dict(waypoints=[(0.28, 0.20, 0.5), (0.18, 0.20, 0.5), (0.18, 0.35, 0.5)], durations=[3.0, 2.0],
              arcs={0: Arc([0.23, 0.20, 0.5], [0.28, 0.20, 0.5], [0.18, 0.20, 0.5])})
_TOTAL = dict(SHORT, total=7.0)
_LOOSE = dict(SHORT, check=False)
_FINE = dict(waypoints=[(0.3, 0.2, 0.5), (0.5, 0.2, 0.5)], durations=[2.0], dt=1e-5)
_EDGE = dict(waypoints=[(0.5, 0.0, 0.5), (0.9, 0.0, 0.5)], durations=[2.0])


def _climb(points, last):
    """A plan climbing towards the end of the quill's stroke, with short middle segments and long anticipations:
    three or more segments move at once (``last``: the last segment's duration)."""
    n = len(points)
    wps = [Waypoint(points[0])] + [Waypoint(p, anticipation=0.9) for p in points[1:-1]] + [Waypoint(points[-1])]
    return dict(waypoints=wps, durations=[2.0] + [1.0] * (n - 3) + [last], dt=0.01)


_THREE = _climb([(0.5, 0.071, 0.862), (0.502, 0.066, 0.936), (0.579, 0.004, 0.941), (0.502, 0.089, 0.949),
                 (0.679, 0.018, 0.975)], 1.9)
_FOUR = _climb([(0.5, 0.069, 0.897), (0.505, 0.01, 0.926), (0.52, 0.088, 0.966), (0.602, 0.085, 0.983),
                (0.629, 0.041, 0.988)], 1.2)


@pytest.mark.parametrize("plan, settings, code", [
    (SHORT, _settings_for(SHORT, 1, duration=1.0005, segment=0), K.DURATION_NOT_WHOLE),
    (_FINE, _settings_for(_FINE, 0, duration=20.5), K.DURATION_TOO_MANY),
    (SHORT, _settings_for(SHORT, 0, via=True, anticipation=0.5), K.VIA_FIRST),
    (SHORT, _settings_for(SHORT, 3, via=True, anticipation=0.5), K.VIA_LAST),
    (SHORT, _settings_for(SHORT, 1, anticipation=1.8), K.ANTICIPATION_TOO_LONG),
    (SHORT, _settings_for(SHORT, 1, anticipation=0.5005), K.ANTICIPATION_NOT_WHOLE),
    (SHORT, _settings_for(SHORT, 1, x=0.3, y=0.2, z=0.5), K.REPEATED_POINT),
    (SHORT, _settings_for(SHORT, 3, x=0.4, y=0.6, z=0.44), K.ARC_COLLINEAR),
    (_BLENDED, _settings_for(_BLENDED, 0, duration=1.5), K.LAW_BLEND),
    (_GIVEN, _settings_for(_GIVEN, 0, x=0.285), K.GIVEN_ARC_START),
    (_GIVEN, _settings_for(_GIVEN, 1, x=0.185), K.GIVEN_ARC_END),
    (SHORT, _settings_for(SHORT, 0, x=0.99, y=0.3), K.START_OUTSIDE_ANNULUS),
    (SHORT, _settings_for(SHORT, 0, z=1.1), K.START_OUTSIDE_STROKE),
    (_TOTAL, _settings_for(_TOTAL, 1, segment=2, duration=5.0), K.TOTAL_TOO_SHORT),
    (SHORT, _settings_for(SHORT, 2, x=0.95, y=0.4), K.SAMPLE_OUT),
    (SHORT, _settings_for(SHORT, 2, z=1.2), K.SAMPLE_OUT + 1),
    (SHORT, _settings_for(SHORT, 1, x=0.9921946632915598, y=0.3622555443740769, z=1.0216420845728607,
                          anticipation=0.4), K.SAMPLE_OUT + 2),
    (SHORT, _settings_for(SHORT, 2, via=True, z=1.0288717024039806, anticipation=0.4), K.SAMPLE_OUT + 3),
    (_THREE, _settings_for(_THREE, 4, z=1.122), K.SAMPLE_OUT + 5),
    (_FOUR, _settings_for(_FOUR, 4, z=1.178), K.SAMPLE_OUT + 7),
    (_EDGE, _settings_for(_EDGE, 1, x=1 + 6e-13), K.SAMPLE_OUT + 10),
    (REF, _settings_for(REF, 11, x=0.99, y=0.2), K.SAMPLE_OUT),
    (REF, _settings_for(REF, 8, x=0.99, y=0.2), K.WAYPOINT_OUTSIDE_ANNULUS),
    (SHORT, _settings_for(SHORT, 2, via=True, z=1.0247653346366634, anticipation=1.4), K.WAYPOINT_OUTSIDE_STROKE),
    (_LOOSE, _settings_for(_LOOSE, 2, x=0.95, y=0.4), E.SUMMARY_OUTSIDE_ANNULUS),
])
def test_each_refusal_is_reached_with_the_planners_message(plan, settings, code):
    d = _decl(plan)
    out = np.zeros(d.page.outputs.size)
    got = int(d.page.kernel(d.page.pack(settings, _controls(d)), d.page.data, out))
    assert got == code
    with pytest.raises(ScaraError) as msg:
        _run(d, settings)
    with pytest.raises(ScaraError) as exc:
        traj = plan_path(**_edited(plan, settings))
        traj.summary()  # a plan that is not checked fails in its summary
    assert _normalised(str(msg.value)) == _normalised(readable(str(exc.value)))


def test_every_code_the_kernels_return_has_a_text():
    d = _decl()
    names = ("DURATION_TOO_MANY DURATION_NOT_WHOLE VIA_FIRST VIA_LAST ANTICIPATION_TOO_LONG ANTICIPATION_TOO_MANY "
             "ANTICIPATION_NOT_WHOLE REPEATED_POINT LINE_OVERFLOW ARC_OVERFLOW ARC_COLLINEAR ARC_NORMAL_ZERO "
             "ARC_START_OFF_PLANE ARC_END_OFF_PLANE ARC_RADIUS_OVERFLOW ARC_RADIUS_TOO_SMALL ARC_START_OFF_CIRCLE "
             "ARC_END_OFF_CIRCLE ARC_SAME_ENDS LAW_BLEND LAW_NOT_FINITE GIVEN_ARC_START GIVEN_ARC_END "
             "START_OUTSIDE_ANNULUS START_OUTSIDE_STROKE MOTION_TOO_MANY TOTAL_TOO_MANY TOTAL_NOT_WHOLE "
             "TOTAL_SAMPLES_TOO_MANY TOTAL_TOO_SHORT SAMPLE_NOT_FINITE WAYPOINT_OUTSIDE_ANNULUS "
             "WAYPOINT_OUTSIDE_STROKE").split()
    codes = {getattr(K, name) for name in names} | {K.SAMPLE_OUT + k for k in range(12)}
    codes |= {E.SUMMARY_OUTSIDE_ANNULUS, E.SUMMARY_OUTSIDE_STROKE}
    assert len(codes) == len(names) + 14 and codes == set(d.page.refusals)


# ------------------------------------------------------------------------------------------------------ figures
@pytest.mark.parametrize("plan", [REF, SHORT], ids=["reference", "short"])
def test_updated_figures_equal_the_figures_drawn(plan):
    d = _decl(plan)
    valid = []
    for s in [d.defaults()] + _random_settings(plan, 12, spread=0.03):
        try:
            valid.append(_run(d, s))
        except ScaraError:
            pass
    assert len(valid) >= 4
    assert any(v["via"] for v in valid) and any(not v["via"] for v in valid)
    for v0, v1 in zip(valid, valid[1:] + valid[:1]):
        for pair in d.figures:
            first = _widget_safe(pair.build(v0).to_plotly_json())
            applied = apply_update(first, _widget_safe(pair.updated(v1)), pair)
            full = _widget_safe(pair.build(v1).to_plotly_json())
            assert len(applied["data"]) == len(full["data"])
            for i, (a, b) in enumerate(zip(applied["data"], full["data"])):
                for key in b:
                    assert _same(a.get(key), b[key]), (pair.role, i, key)
            assert applied["layout"]["title"] == full["layout"]["title"]
            assert _same(applied["layout"].get("shapes"), full["layout"].get("shapes")), pair.role


def test_the_profiles_bands_are_the_chapters():
    d = _decl()
    for s in (d.defaults(), dict(d.defaults(), point=4, via=False, x=0.1, y=0.1, z=0.5, segment=3)):
        v = _run(d, s)
        traj = plan_path(**_edited(REF, s))
        shown = [dict(sh) for sh in d.figures[1].build(v).to_plotly_json()["layout"]["shapes"]
                 if sh.get("visible", True)]
        for sh in shown:
            sh.pop("visible", None)
        assert shown == [dict(sh) for sh in (_widget_safe(x) for x in segment_shapes(traj))]


# ------------------------------------------------------------------------------------------- the Jupyter panel
def test_the_panel_keeps_the_last_accepted_plan():
    d = _decl()
    base = np.array(d.page.data)
    moved = dict(d.defaults(), x=0.08)  # p3, a via point
    d.compute(moved)
    assert not np.array_equal(d.page.data, base, equal_nan=True)
    # picking p7 with its own values keeps the edit of p3, in the program's data too
    p7 = dict(moved, point=7, via=False, x=0.70, y=0.15, z=0.3, segment=6, duration=9.0)
    v = d.compute(p7)
    traj = plan_path(**_edited(_edited(REF, moved), p7))
    _check_values(v, traj, p7)
    kept = np.array(d.page.data)
    with pytest.raises(ScaraError, match="leaves the workspace"):
        d.compute(dict(p7, x=0.99))
    assert np.array_equal(d.page.data, kept, equal_nan=True)  # a refused move changes nothing
    _check_values(d.compute(p7), traj, p7)


def test_the_program_is_declared_for_the_page():
    d = _decl()
    assert d.widget == "waypoint_editor" and d.page.inputs == tuple(c.name for c in d.controls)
    spec = d.page.describe(d)
    assert spec["kernel"] == "editor_program" and spec["size"] == d.page.outputs.size
    assert set(spec["traces"]) == {"top view", "profiles"} and "shapes.0.x0" in spec["paths"]["profiles"]
    assert len(spec["refusals"]) == len(d.page.refusals)


# ------------------------------------------------------------------------------------------- JavaScript under Node
def test_the_program_translates_and_computes_the_same_under_node():
    from scara.page.translate import translate

    from ._node import run_js

    d = _decl()
    settings = [d.defaults(), dict(d.defaults(), x=0.08, duration=4.0),
                dict(d.defaults(), point=7, via=False, x=0.99, y=0.15, z=0.3, segment=6, duration=9.0),
                dict(d.defaults(), point=4, via=True, anticipation=2.0, x=0.1, y=0.1, z=0.5, segment=3, duration=1.5)]
    controls = _controls(d)
    calls = [("editor_program", [d.page.pack(s, controls), d.page.data, np.zeros(d.page.outputs.size)], 3)
             for s in settings]
    results = run_js(translate([E.editor_program]), calls)
    for s, (ret, args, ms) in zip(settings, results):
        out = np.zeros(d.page.outputs.size)
        code = d.page.kernel(d.page.pack(s, controls), d.page.data, out)
        assert int(ret) == code
        assert np.array_equal(np.isnan(args[2]), np.isnan(out))
        np.testing.assert_allclose(args[2], out, rtol=1e-12, atol=1e-13)
    print(f"editor_program under Node: {results[0][2]:.1f} ms for the reference plan")
