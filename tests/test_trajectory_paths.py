"""Tests of scara.trajectory.paths (chapter 3): the line and arc primitives, checked against the circle's equation
and closed-form geometry, and the arcs that are refused."""
from __future__ import annotations

import math

import numpy as np
import pytest

from scara import Arc, Line, ScaraError, plan_path

from _trajectory_shared import CENTRE


# --------------------------------------------------------------------------------------------------
# the half circle
# --------------------------------------------------------------------------------------------------
def test_arc_from_centre_and_from_three_points_agree():
    a = Arc(CENTRE, [0.28, 0.20, 0.5], [0.18, 0.20, 0.5], normal=[0, 0, 1], radius=0.05)
    b = Arc.through([0.28, 0.20, 0.5], [0.23, 0.25, 0.5], [0.18, 0.20, 0.5])
    np.testing.assert_allclose(b.centre, CENTRE, atol=1e-15)
    assert b.radius == pytest.approx(0.05, abs=1e-15) and a.length == pytest.approx(math.pi * 0.05, rel=1e-15)
    s = np.linspace(0, a.length, 7)
    # the circumcentre carries ~1e-16 m of rounding: an angle error ~1e-16/rho ~ 2e-15 rad, which shows as
    # ~1e-16 m in the points, ~2e-15 in the unit tangents and ~4e-14 1/m in the curvature vectors (|k| = 20)
    for u, w, tol in zip(a.evaluate(s), b.evaluate(s), (1e-15, 1e-14, 1e-13)):
        np.testing.assert_allclose(u, w, atol=tol, rtol=0)
    # tangent and curvature are the first and second derivatives of the point (finite differences)
    h = 1e-5
    p_plus, p0, p_minus = (a.evaluate(s + d)[0] for d in (h, 0, -h))
    np.testing.assert_allclose((p_plus - p_minus) / (2 * h), a.evaluate(s)[1], atol=1e-9)
    np.testing.assert_allclose((p_plus - 2 * p0 + p_minus) / h ** 2, a.evaluate(s)[2], atol=2e-4)
    # the other sense (normal -z) goes through y < 0.20
    c = Arc(CENTRE, [0.28, 0.20, 0.5], [0.18, 0.20, 0.5], normal=[0, 0, -1])
    assert c.evaluate([c.length / 2])[0][0, 1] == pytest.approx(0.15)


def test_line_primitive():
    ln = Line([0, 0, 0.5], [0.3, 0.4, 0.5])
    p, t, k = ln.evaluate([0.0, 0.25, 0.5])
    np.testing.assert_allclose(p[-1], [0.3, 0.4, 0.5], atol=1e-16)
    np.testing.assert_allclose(t, [[0.6, 0.8, 0]] * 3)
    assert np.all(k == 0)


# --------------------------------------------------------------------------------------------------
# validation: every bad input is refused with a message naming it
# --------------------------------------------------------------------------------------------------
def test_arc_whose_ends_are_not_on_its_circle():
    with pytest.raises(ScaraError, match="end .* is not on its circle: its distance from the centre"):
        Arc(CENTRE, [0.28, 0.20, 0.5], [0.19, 0.20, 0.5])
    with pytest.raises(ScaraError, match="start .* is not on its circle"):
        Arc(CENTRE, [0.29, 0.20, 0.5], [0.18, 0.20, 0.5], radius=0.05)
    with pytest.raises(ScaraError, match="off the plane"):
        Arc(CENTRE, [0.28, 0.20, 0.5], [0.23, 0.20, 0.55])
    with pytest.raises(ScaraError, match="collinear"):
        Arc.through([0.1, 0.2, 0.5], [0.2, 0.2, 0.5], [0.3, 0.2, 0.5])
    arc = Arc(CENTRE, [0.28, 0.20, 0.5], [0.18, 0.20, 0.5])
    with pytest.raises(ScaraError, match=r"segment p0->p1: its end .* is not the waypoint"):
        plan_path([[0.28, 0.20, 0.5], [0.19, 0.2, 0.5]], durations=[2.0], arcs={0: arc})


def test_overflowing_line_and_bad_radius_raise_scara_errors():
    from scara import NonFiniteError
    with pytest.raises(NonFiniteError, match=r"the line from start = \[1\.e\+308, 0\.e\+000, 0\.e\+000\] .* has a "
                                             r"length that overflows"):
        Line([1e308, 0.0, 0.0], [-1e308, 0.0, 0.0])
    with pytest.raises(ScaraError, match=r"radius must be a number, got ''"):
        Arc(CENTRE, CENTRE + [0.05, 0, 0], CENTRE - [0.05, 0, 0], radius="")


def test_overflowing_arcs_raise_non_finite_errors():
    from scara import NonFiniteError
    with pytest.raises(NonFiniteError, match=r"the circle through start \[1\.e\+300, 0\.e\+000, 0\.e\+000\].* cannot be "
                                             r"computed: the points are too far apart"):
        Arc.through([1e300, 0, 0], [0, 1e300, 0], [-1e300, 0, 0])
    with pytest.raises(NonFiniteError, match=r"has a radius that overflows"):
        Arc([0, 0, 0], [1e300, 0, 0], [0, 1e300, 0])
