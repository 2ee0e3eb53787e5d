"""The planner's kernels (scara.programs.path, scara.trajectory._plan): a plan packed as a float vector and sampled
by ``sample_plan`` gives the reference trajectory of chapter 3 exactly; ``plan_path`` plans through the same
kernels (its plan vector is what ``build_plan`` makes of its inputs); the samples follow the trapezoidal law and
the stop points written out independently of the package; each check of ``plan_path`` is a code of the kernel
with the planner's message; the kernels translate to JavaScript and compute the same numbers under Node."""
from __future__ import annotations

import math

import numpy as np
import pytest

from scara import Arc, ScaraError, UnreachableError, Waypoint, plan_path, reference_plan, reference_trajectory
from scara.programs import path as PP
from scara.trajectory import _plan as K

RNG = np.random.default_rng(20240603)


@pytest.fixture(scope="module")
def ref():
    return reference_trajectory()


def _arrays(n):
    return np.empty(n), np.empty((n, 4)), np.empty((n, 4)), np.empty((n, 4))


def _random_plan(k):
    """A random plan of 2 to 5 waypoints in reach: via points, planned orientations, an arc, blends, a total."""
    n = int(RNG.integers(2, 6))
    pts = []
    for _ in range(n):
        r, a = RNG.uniform(0.15, 0.9), RNG.uniform(-math.pi, math.pi)
        pts.append([r * math.cos(a), r * math.sin(a), RNG.uniform(0.05, 0.95)])
    wps = [Waypoint(pts[0], phi=0.3 if k % 3 == 0 else None)]
    wps += [Waypoint(pts[i], anticipation=int(RNG.integers(0, 8)) / 10, phi=float(RNG.uniform(-1, 1)) if k % 2 else None)
            for i in range(1, n - 1)]
    wps.append(Waypoint(pts[-1]))
    durations = [int(RNG.integers(10, 40)) / 10 for _ in range(n - 1)]
    kw = dict(waypoints=wps, durations=durations, dt=0.01, check=False)
    if k % 4 == 0:
        kw["arcs"] = {0: list(np.add(np.add(pts[0], pts[1]) / 2, [0.03, -0.02, 0.01]))}
    if k % 5 == 1:
        kw["blends"] = [d / 2.5 if j % 2 else None for j, d in enumerate(durations)]
    if k % 3 == 2:
        kw["total"] = sum(durations) + 0.5
    return kw


# --------------------------------------------------------------------------------------------------------- sampling
def test_sample_plan_gives_the_reference_trajectory(ref):
    plan = PP.plan_vector(ref)
    n = int(plan[K.P_K]) + 1
    t, x, xd, xdd = _arrays(n)
    assert PP.sample_plan(plan, t, x, xd, xdd) == 0
    for got, want in ((t, ref.t), (x, ref.x), (xd, ref.xd), (xdd, ref.xdd)):
        np.testing.assert_allclose(got, want, rtol=0, atol=1e-12)
        assert np.array_equal(got, want)  # the very kernel plan_path samples with
    # the plan of the reference's inputs is the same vector
    assert np.array_equal(PP.plan_vector(reference_plan()), plan)
    spec = PP.plan_spec(reference_plan())
    again = np.empty(PP.plan_size(12))
    assert PP.build_plan(spec, again, np.zeros(K.INFO_SIZE)) == 0 and np.array_equal(again, plan)
    # arrays of the wrong size are refused with a code, not written past their end
    assert PP.sample_plan(plan, *_arrays(n - 1)) == 1


def test_the_packed_layouts_are_those_of_the_docstring(ref):
    n = 12
    assert PP.spec_size(n) == 11 + 6 * n + 21 * (n - 1) and PP.plan_size(n) == 18 + 6 * n + 25 * (n - 1)
    plan = PP.plan_vector(ref)
    assert plan[0] == 12 and plan[1] == ref.dt and plan[2] == ref.t.size - 1 and plan[3] * ref.dt == ref.motion_end
    np.testing.assert_array_equal(plan[4:8], ref.x[0])
    np.testing.assert_array_equal(plan[8:12], ref.q0)
    for i in range(n):
        o = 18 + 6 * i
        np.testing.assert_array_equal(plan[o:o + 3], ref.waypoints[i])
        assert plan[o + 3] == ref.phi_waypoints[i] and plan[o + 4] == ref.anticipations[i]
    for j, (seg, law) in enumerate(zip(ref.segments, ref.laws)):
        o = 18 + 6 * n + 25 * j
        assert plan[o] == (seg.kind == "arc")
        assert plan[o + 1] * ref.dt == ref.segment_start[j] and plan[o + 2] * ref.dt == ref.segment_end[j]
        assert (plan[o + 3], plan[o + 4], plan[o + 5]) == (seg.length, law.duration, law.blend)
        assert (plan[o + 6], plan[o + 7]) == (law.cruise_speed, law.acceleration)
        if seg.kind == "arc":
            assert plan[o + 15] == seg.radius
            np.testing.assert_array_equal(plan[o + 22:o + 25], seg.centre)


def test_plans_sample_through_the_kernels_at_any_time():
    for k in range(25):
        kw = _random_plan(k)
        try:
            tr = plan_path(**kw)
        except ScaraError:
            continue
        plan = PP.plan_vector(tr)
        t, x, xd, xdd = _arrays(tr.t.size)
        assert PP.sample_plan(plan, t, x, xd, xdd) == 0
        assert np.array_equal(x, tr.x) and np.array_equal(xd, tr.xd) and np.array_equal(xdd, tr.xdd)
        # at any times, in any order: the same kernel, and on the samples the same numbers
        tt = RNG.uniform(-1.0, tr.total + 1.0, 200)
        got = _arrays(tt.size)[1:]
        assert PP.evaluate_plan(plan, tt, *got) == 0
        for a, b in zip(got, tr.evaluate(tt)):
            assert np.array_equal(a, b)
        ks = RNG.integers(0, tr.t.size, 50)
        for a, b in zip(tr.evaluate(tr.t[ks]), (tr.x[ks], tr.xd[ks], tr.xdd[ks])):
            assert np.array_equal(a, b)


def _trapezoid(tau, L, T, tc):
    """eqs. 4.8-4.9 written out independently of the package."""
    v = L / (T - tc)
    a = v / tc
    s = np.where(tau < tc, 0.5 * a * tau ** 2, np.where(tau < T - tc, v * (tau - tc / 2), L - 0.5 * a * (T - tau) ** 2))
    return np.where(tau <= 0, 0.0, np.where(tau >= T, L, s))


def test_samples_follow_the_trapezoid_and_stop_at_the_stop_points():
    a, b, c = np.array([0.3, 0.2, 0.5]), np.array([0.5, 0.3, 0.4]), np.array([0.4, 0.5, 0.45])
    tr = plan_path([a, Waypoint(b, anticipation=0.5), c], durations=[3.0, 2.0], total=6.0)
    plan = PP.plan_vector(tr)
    t, x, xd, xdd = _arrays(6001)
    PP.sample_plan(plan, t, x, xd, xdd)
    # independent: p = a + u1 s1(t) + u2 s2(t - (3 - 0.5)) with blends of a third of each duration
    L1, L2 = np.linalg.norm(b - a), np.linalg.norm(c - b)
    s1 = _trapezoid(t, L1, 3.0, 1.0)
    s2 = _trapezoid(t - 2.5, L2, 2.0, 2.0 / 3.0)
    expect = a + np.outer(s1, (b - a) / L1) + np.outer(s2, (c - b) / L2)
    np.testing.assert_allclose(x[:, :3], expect, atol=1e-14, rtol=0)
    np.testing.assert_allclose(x[-1, :3], c, atol=1e-15)
    assert np.all(xd[-1] == 0) and np.all(xd[0] == 0) and t[-1] == 6.0
    assert np.all(x[:, 3] == x[0, 3])  # phi held at the start configuration's value


def test_the_kernels_write_the_extremes_and_corners_the_summary_reports(ref):
    out = np.empty(K.EXTREMES)
    assert K.plan_extremes(ref.plan_vector, ref.x, ref.xd, ref.xdd, out) == 0
    s = ref.summary()
    sp = np.linalg.norm(ref.xd[:, :3], axis=1)
    assert out[K.X_SPEED] == pytest.approx(sp.max(), rel=1e-15) and out[K.X_W] == s["min_manipulability"]
    w = ref.manipulability()
    assert out[K.X_W] == pytest.approx(w.min(), rel=1e-13) and int(out[K.X_W_K]) == int(np.argmin(w))
    for i in (3, 4, 5, 8):
        d, when = K.corner_distance(ref.plan_vector, ref.x, i)
        assert (d, when) == ref.corner_distances()[f"p{i}"]


# ------------------------------------------------------------------------------------ the checks are kernel codes
def _code(kw):
    spec = PP.plan_spec(kw)
    info = np.zeros(K.INFO_SIZE)
    return PP.build_plan(spec, np.empty(PP.plan_size(len(kw["waypoints"]))), info), dict(zip(K.INFO.names, info))


PTS = [[0.3, 0.2, 0.5], [0.4, 0.2, 0.5], [0.4, 0.3, 0.5]]


@pytest.mark.parametrize("kw, code, error, text", [
    (dict(waypoints=PTS, durations=[1.0005, 1.0]), K.DURATION_NOT_WHOLE, ScaraError,
     "duration of segment p0->p1 = 1.0005 s is not a whole number of sampling periods dt = 0.001 s (1000.5 periods)"),
    (dict(waypoints=PTS[:2], durations=[2.0], dt=1e-9), K.DURATION_TOO_MANY, ScaraError, "more than a plan may hold"),
    (dict(waypoints=[Waypoint(PTS[0], anticipation=0.5), PTS[1]], durations=[1.0]), K.VIA_FIRST, ScaraError,
     "p0 is the first waypoint and cannot be a via point (anticipation = 0.5 s)"),
    (dict(waypoints=[PTS[0], Waypoint(PTS[1], anticipation=0.5)], durations=[1.0]), K.VIA_LAST, ScaraError,
     "p1 is the last waypoint and cannot be a via point"),
    (dict(waypoints=[PTS[0], Waypoint(PTS[1], anticipation=1.0), PTS[2]], durations=[3.0, 1.0]),
     K.ANTICIPATION_TOO_LONG, ScaraError, "anticipation at via point p1 = 1 s must be shorter than both segments it "
                                          "joins: p0->p1 lasts 3 s and p1->p2 lasts 1 s"),
    (dict(waypoints=[PTS[0], Waypoint(PTS[1], anticipation=0.5005), PTS[2]], durations=[3.0, 1.0]),
     K.ANTICIPATION_NOT_WHOLE, ScaraError, "anticipation at p1 = 0.5005 s is not a whole number"),
    (dict(waypoints=[PTS[0], PTS[0], PTS[1]], durations=[1.0, 1.0]), K.REPEATED_POINT, ScaraError,
     "repeated point: p1 = p0 = [0.3, 0.2, 0.5]"),
    (dict(waypoints=[[0.1, 0.2, 0.5], [0.3, 0.2, 0.5]], durations=[2.0], arcs={0: [0.2, 0.2, 0.5]}),
     K.ARC_COLLINEAR, ScaraError, "segment p0->p1: no circle passes through start"),
    (dict(waypoints=[[0.28, 0.20, 0.5], [0.19, 0.2, 0.5]], durations=[2.0],
          arcs={0: Arc([0.23, 0.20, 0.5], [0.28, 0.20, 0.5], [0.18, 0.20, 0.5])}), K.GIVEN_ARC_END, ScaraError,
     "segment p0->p1: its end [0.18, 0.2 , 0.5 ] is not the waypoint [0.19, 0.2 , 0.5 ]"),
    (dict(waypoints=PTS, durations=[1.0, 1.0], blends=[0.6, None]), K.LAW_BLEND, ScaraError,
     "segment p0->p1: blend = 0.6 s is longer than half the duration T/2 = 0.5 s"),
    (dict(waypoints=[[0.99, 0.2, 0.5], [0.5, 0.2, 0.5]], durations=[2.0]), K.START_OUTSIDE_ANNULUS, UnreachableError,
     "point x = [0.99 0.2  0.5  0.  ] is unreachable: its distance from the joint-1 axis"),
    (dict(waypoints=[[0.5, 0.2, 1.5], [0.5, 0.2, 0.5]], durations=[2.0], phi=0.4), K.START_OUTSIDE_STROKE,
     UnreachableError, "point x = [0.5 0.2 1.5 0.4] is unreachable: p_z = 1.5 m needs d3 = d0 - p_z = -0.5 m"),
    (dict(waypoints=PTS, durations=[1.0, 1.0], total=2.0005), K.TOTAL_NOT_WHOLE, ScaraError,
     "total = 2.0005 s is not a whole number"),
    (dict(waypoints=PTS[:2], durations=[2.0], total=1e6), K.TOTAL_TOO_MANY, ScaraError,
     "total = 1e+06 s is 1e+09 sampling periods"),
    (dict(waypoints=PTS, durations=[1.0, 1.0], total=1.5), K.TOTAL_TOO_SHORT, ScaraError,
     "total = 1.5 s is shorter than the motion, which ends at 2 s"),
])
def test_each_check_is_a_code_of_the_kernel_with_the_planners_message(kw, code, error, text):
    got, info = _code(kw)
    assert got == code
    with pytest.raises(error) as exc:
        plan_path(**kw)
    assert type(exc.value) is error and text in str(exc.value)


def test_the_in_reach_check_is_a_kernel_code():
    kw = dict(waypoints=[[0.5, 0.2, 0.5], [0.9, 0.6, 0.5]], durations=[2.0])
    tr = plan_path(**kw, check=False)
    info = np.zeros(K.INFO_SIZE)
    code = K.plan_reach(tr.plan_vector, tr.x, info)
    assert code == K.SAMPLE_OUT  # one segment moving, outside the annulus
    k = int(info[K.I_SAMPLE])
    r = np.hypot(tr.x[:, 0], tr.x[:, 1])
    assert k == int(np.argmax(r > 1.0 + 1e-12)) and info[K.I_R] == math.hypot(*tr.x[k, :2])
    with pytest.raises(UnreachableError, match=rf"leaves the workspace at t = {tr.t[k]:.3f} s \(sample {k}\) on "
                                               r"segment p0->p1: its point x = \["):
        plan_path(**kw)
    plan = reference_plan()
    plan["waypoints"][8] = plan["waypoints"][8].replace(position=(0.99, 0.2, 0.5))
    raw = plan_path(**plan, check=False)
    assert K.plan_reach(raw.plan_vector, raw.x, info) == K.WAYPOINT_OUTSIDE_ANNULUS and info[K.I_W_A] == 8


# ------------------------------------------------------------------------------------------- JavaScript under Node
def test_the_kernels_translate_and_compute_the_same_under_node(ref):
    from ._node import run_js
    from scara.page.translate import translate

    script = translate([PP.sample_plan, PP.evaluate_plan, PP.build_plan])
    plan = np.array(ref.plan_vector)
    n = plan.size
    spec = PP.plan_spec(reference_plan())
    tt = np.linspace(-1.0, 71.0, 999)
    res = run_js(script, [("sample_plan", [plan, *_arrays(ref.t.size)], 3),
                          ("evaluate_plan", [plan, tt, *_arrays(tt.size)[1:]], 1),
                          ("build_plan", [spec, np.zeros(n), np.zeros(K.INFO_SIZE)], 1)])
    (ret, args, ms), (ret2, args2, _), (ret3, args3, _) = res
    assert ret == 0 and ret2 == 0 and ret3 == 0
    np.testing.assert_allclose(args3[1], plan, rtol=1e-15, atol=1e-15)
    for got, want in zip(args[1:], (ref.t, ref.x, ref.xd, ref.xdd)):
        np.testing.assert_allclose(got, want, rtol=0, atol=1e-15)
    for got, want in zip(args2[2:], ref.evaluate(tt)):
        np.testing.assert_allclose(got, want, rtol=0, atol=1e-15)
    print(f"sample_plan under Node: {ms:.1f} ms for the 70 001 samples")
