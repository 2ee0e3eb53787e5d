"""Manipulability and its ellipsoids (chapter 2) against independent computations."""
import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from scara import (
    ScaraError, ScaraParams, force_ellipsoid, jacobian, manipulability, singular_radii, velocity_ellipsoid,
    workspace_map,
)

angle = st.floats(-math.pi, math.pi, allow_nan=False)
configs = st.tuples(angle, angle, st.floats(0, 1), angle).map(np.array)

#: the five reference configurations of chapter 2 and the manipulability the text states (section Five
#: reference configurations)
BOOK_TABLE = [
    ([0, -math.pi / 2, 0.5, 0], 0.250),
    ([0, math.pi / 4, 0.5, 0], 0.177),
    ([0, math.pi / 30, 0.5, 0], 0.026),
    ([0, 98 * math.pi / 100, 0.5, 0], 0.016),
    ([0, -99.99 * math.pi / 100, 0.5, 0], 0.000),
]


@given(configs)
def test_w_is_abs_det_and_sqrt_det_JJT(q):
    J = jacobian(q)
    w = manipulability(q)
    assert math.isclose(w, abs(np.linalg.det(J)), abs_tol=1e-14)
    assert math.isclose(w, math.sqrt(max(np.linalg.det(J @ J.T), 0.0)), abs_tol=1e-7)


@pytest.mark.parametrize("q, w", BOOK_TABLE)
def test_book_reference_table(q, w):
    assert round(manipulability(q), 3) == w


def test_batch():
    qs = np.array([q for q, _ in BOOK_TABLE], dtype=float)
    assert np.allclose(manipulability(qs), [manipulability(q) for q in qs])


@given(configs.filter(lambda q: abs(math.sin(q[1])) > 1e-3))
def test_ellipsoid_axes_are_singular_vectors_and_values(q):
    ve, fe = velocity_ellipsoid(q), force_ellipsoid(q)
    JP = jacobian(q)[:3]
    s = np.linalg.svd(JP, compute_uv=False)
    assert np.allclose(ve.lengths, s, atol=1e-12)
    # each axis u_i with length s_i satisfies J_P J_P^T u = s^2 u (principal axis of v^T (J J^T)^-1 v = 1)
    for i in range(3):
        u = ve.axes[:, i]
        assert np.allclose(JP @ JP.T @ u, ve.lengths[i] ** 2 * u, atol=1e-12)
        # a point on the axis end lies on the ellipsoid surface
        v = ve.lengths[i] * u
        assert math.isclose(v @ np.linalg.solve(JP @ JP.T, v), 1.0, rel_tol=1e-9)
        f = fe.lengths[i] * fe.axes[:, i]
        assert math.isclose(f @ (JP @ JP.T) @ f, 1.0, rel_tol=1e-9)
    # duality: same directions, reciprocal lengths
    assert np.allclose(np.abs(np.sum(ve.axes * fe.axes, axis=0)), 1.0, atol=1e-12)
    assert np.allclose(ve.lengths * fe.lengths, 1.0, atol=1e-12)
    assert np.allclose(ve.centre, fe.centre)


def test_force_ellipsoid_unbounded_at_singularity():
    fe = force_ellipsoid([0.0, 0.0, 0.5, 0.0])
    assert np.isinf(fe.lengths).sum() == 1
    with pytest.raises(ScaraError, match="unbounded"):
        fe.outline()


def test_horizontal_ellipse_outline():
    q = [0.3, -1.0, 0.5, 0.0]
    ve = velocity_ellipsoid(q, rows=(0, 1))
    pts = ve.outline(n=9)
    J = jacobian(q)[:2, :2]
    d = pts - ve.centre[:2]
    assert np.allclose(np.einsum("ni,ij,nj->n", d, np.linalg.inv(J @ J.T), d), 1.0)
    with pytest.raises(ScaraError, match="rows"):
        velocity_ellipsoid(q, rows=(0, 3))


def test_workspace_map():
    xs, ys, W = workspace_map(n=101)
    X, Y = np.meshgrid(xs, ys)
    r = np.hypot(X, Y)
    inside = r <= 1.0 + 1e-12
    assert np.all(np.isnan(W[~inside])) and not np.any(np.isnan(W[inside]))
    # w depends on r only, largest (a1 a2 = 0.25) where theta2 = +-pi/2, i.e. r = sqrt(a1^2 + a2^2)
    assert math.isclose(np.nanmax(W), 0.25, rel_tol=1e-3)
    i, j = np.unravel_index(np.nanargmax(W), W.shape)
    assert math.isclose(math.hypot(xs[j], ys[i]), math.sqrt(0.5), abs_tol=0.02)
    assert singular_radii() == (0.0, 1.0)
    assert singular_radii(ScaraParams(a1=0.6, a2=0.4)) == pytest.approx((0.2, 1.0))


@pytest.mark.parametrize("rows, plane", [((0, 1), (0, 1)), ((1, 0), (0, 1)), ((0, 2), (0, 2))])
def test_outline_in_any_plane_lies_on_the_ellipsoid(rows, plane):
    q = [0.4, -1.3, 0.3, 0.0]
    ve = velocity_ellipsoid(q, rows=rows)
    pts = ve.outline(n=13, plane=plane)
    JP = jacobian(q)[list(plane), :]
    d = pts - ve.centre[list(plane)]
    assert np.allclose(np.einsum("ni,ij,nj->n", d, np.linalg.inv(JP @ JP.T), d), 1.0)


def test_outline_needs_principal_axes_in_the_plane():
    # with all three rows, the horizontal axes are generally not along x, so x-z is no principal section
    with pytest.raises(ScaraError, match="no pair of principal axes in the plane"):
        velocity_ellipsoid([0.4, -1.3, 0.3, 0.0]).outline(plane=(0, 2))


def test_outline_plane_must_be_among_rows():
    with pytest.raises(ScaraError, match=r"plane = \(0, 2\) must name two distinct components among rows = \(0, 1\)"):
        velocity_ellipsoid([0.4, -1.3, 0.3, 0.0], rows=(0, 1)).outline(plane=(0, 2))


def test_ellipsoid_rows_must_be_integer_indices():
    q = [0.0, 1.0, 0.5, 0.0]
    with pytest.raises(ScaraError, match=r"rows = \(0\.7, 1\.2\) must hold integer indices among 0\.\.2 .* its entry "
                                         r"0\.7 is not one"):
        velocity_ellipsoid(q, rows=(0.7, 1.2))
    with pytest.raises(ScaraError, match=r"rows = \(0, 5\) must hold integer indices among 0\.\.2 .* its entry 5"):
        force_ellipsoid(q, rows=(0, 5))
    with pytest.raises(ScaraError, match=r"rows = \(1, 1\) must be distinct"):
        velocity_ellipsoid(q, rows=(1, 1))
    with pytest.raises(ScaraError, match=r"rows = True must be a sequence of integer indices"):
        velocity_ellipsoid(q, rows=True)
    with pytest.raises(ScaraError, match=r"plane = \(0\.2, 1\) must hold integer indices"):
        velocity_ellipsoid(q).outline(plane=(0.2, 1))


def test_workspace_map_grid_is_bounded_before_any_work():
    from scara._manipulability import MAX_GRID
    with pytest.raises(ScaraError, match=rf"n = 1000000000 grid points per side is outside the allowed range 3 <= n "
                                         rf"<= {MAX_GRID}"):
        workspace_map(n=10**9)
    with pytest.raises(ScaraError, match=r"n = 2\.5 must be a whole number \(an int\) of grid points per side"):
        workspace_map(n=2.5)
    with pytest.raises(ScaraError, match=r"n = 1000000000\.0 must be a whole number \(an int\) of outline points"):
        velocity_ellipsoid([0.0, 1.0, 0.5, 0.0]).outline(n=1e9)
