"""Manipulability (chapter 2): the measure ``w(q)``, the velocity and force ellipsoids, workspace maps."""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ._compile import kernel
from .errors import ScaraError, as_array, check_angles, check_count, check_index
from .kinematics import REACH_TOL, elbow_cosine, jacobian, pose
from .params import ScaraParams

__all__ = [
    "manipulability",
    "manipulability_kernel",
    "Ellipsoid",
    "velocity_ellipsoid",
    "force_ellipsoid",
    "workspace_map",
    "singular_radii",
    "MAX_GRID",
    "MAX_OUTLINE",
]

#: largest number of grid points per side of :func:`workspace_map` (a 2001 x 2001 grid, about 4 million points;
#: the book's finest map has 801 per side)
MAX_GRID = 2001
#: largest number of points of :meth:`Ellipsoid.outline`
MAX_OUTLINE = 100_000


@kernel
def manipulability_kernel(q, a1, a2):
    """``w(q) = sqrt(det(J_A J_A^T)) = |det J_A| = a1 a2 |sin theta2|`` (2.4)."""
    return a1 * a2 * abs(math.sin(q[1]))


def manipulability(q, p: ScaraParams | None = None):
    """Yoshikawa's manipulability ``w(q) = sqrt(det(J_A J_A^T)) = a1 a2 |sin theta2|`` (2.3), (2.4).

    ``q`` of shape (4,) gives a float, ``(N, 4)`` an array (N,).

    >>> round(manipulability([0.0, -math.pi / 2, 0.5, 0.0]), 3)
    0.25
    """
    p = ScaraParams.resolve(p)
    q = check_angles(as_array(q, "q", (4,), allow_batch=True))
    if q.ndim == 1:
        return float(manipulability_kernel(q, p.a1, p.a2))
    out = np.empty(len(q))
    _manipulability_batch(np.ascontiguousarray(q), p.a1, p.a2, out)
    return out


@kernel
def _manipulability_batch(q, a1, a2, out):
    """``out[k] = manipulability_kernel(q[k], a1, a2)`` for every row of ``q`` (N, 4)."""
    for k in range(q.shape[0]):
        out[k] = manipulability_kernel(q[k], a1, a2)


@dataclass(frozen=True)
class Ellipsoid:
    """A manipulability ellipsoid at the end-effector position ``centre``.

    ``axes[:, i]`` is the unit direction of the i-th principal axis (base frame), ``lengths[i]`` its semi-axis
    length (``inf`` along a direction the arm cannot resist or ``0`` along one it cannot move).
    ``rows`` names the operational components kept (0 = x, 1 = y, 2 = z).
    """

    centre: np.ndarray
    axes: np.ndarray
    lengths: np.ndarray
    rows: tuple
    kind: str

    def outline(self, n: int = 73, scale: float = 1.0, plane=(0, 1)) -> np.ndarray:
        """Points ``(n, 2)`` of the ellipse cut by the principal axes lying in ``plane``.

        ``plane`` names two base-frame components (0 = x, 1 = y, 2 = z), both among ``rows``. For the SCARA's
        position part the horizontal and vertical directions decouple, so the x-y ellipse is the section of
        the ellipsoid through its centre. Raises :class:`ScaraError` when the plane is not spanned by two
        principal axes or an axis is unbounded (the force ellipse at a singular configuration), and for a plane
        that is not two integer indices or an ``n`` that is not a whole number in ``2 .. MAX_OUTLINE``.
        """
        n = check_count(n, "n", 2, MAX_OUTLINE, "outline points")
        plane = _indices(plane, "plane", 3)
        if len(plane) != 2 or any(c not in self.rows for c in plane) or plane[0] == plane[1]:
            raise ScaraError(f"plane = {plane} must name two distinct components among rows = {self.rows}")
        local = [self.rows.index(c) for c in plane]  # positions of the plane's components in the axes
        sel = [i for i in range(len(self.rows)) if np.linalg.norm(self.axes[local, i]) > 1 - 1e-9]
        if len(sel) != 2:
            raise ScaraError(f"the {self.kind} ellipsoid has no pair of principal axes in the plane {plane}")
        if not np.all(np.isfinite(self.lengths[sel])):
            raise ScaraError(f"the {self.kind} ellipse is unbounded at a singular configuration (lengths {self.lengths})")
        th = np.linspace(0.0, 2 * math.pi, n)
        pts = (np.outer(np.cos(th), scale * self.lengths[sel[0]] * self.axes[local, sel[0]])
               + np.outer(np.sin(th), scale * self.lengths[sel[1]] * self.axes[local, sel[1]]))
        return pts + self.centre[list(plane)]


def _indices(values, name, size) -> tuple:
    """``values`` as a tuple of integer indices ``0..size-1`` (a float such as 0.7, a bool or a string is refused:
    truncating it would silently pick another component)."""
    if isinstance(values, (str, bytes)) or np.ndim(values) != 1:
        raise ScaraError(f"{name} = {values!r} must be a sequence of integer indices among 0..{size - 1}")
    out = []
    for v in values:
        try:
            out.append(check_index(v, "index", size))
        except ScaraError as exc:
            raise ScaraError(f"{name} = {tuple(values)!r} must hold integer indices among 0..{size - 1} (0 = x, "
                             f"1 = y, 2 = z): its entry {v!r} is not one") from exc
    return tuple(out)


def _position_svd(q, p, rows):
    rows = _indices(rows, "rows", 3)
    if not rows or any(r not in (0, 1, 2) for r in rows) or len(set(rows)) != len(rows):
        raise ScaraError(f"rows = {rows} must be distinct operational position components among 0 (x), 1 (y), 2 (z)")
    J = jacobian(q, p)[list(rows), :]  # jacobian checks q
    U, s, _ = np.linalg.svd(J, full_matrices=False)
    return U, s, rows


def velocity_ellipsoid(q, p: ScaraParams | None = None, rows=(0, 1, 2)) -> Ellipsoid:
    """The velocity manipulability ellipsoid ``v^T (J_P J_P^T)^-1 v = 1`` of the position rows ``J_P``.

    From the SVD ``J_P = U S V^T``: axes are the columns of ``U``, semi-axis lengths the singular values
    (Siciliano et al., section 3.9). ``rows=(0, 1)`` gives the horizontal ellipse.
    """
    p = ScaraParams.resolve(p)
    U, s, rows = _position_svd(q, p, rows)
    return Ellipsoid(pose(q, p)[:3], U, s, rows, "velocity")


def force_ellipsoid(q, p: ScaraParams | None = None, rows=(0, 1, 2)) -> Ellipsoid:
    """The force manipulability ellipsoid ``f^T (J_P J_P^T) f = 1``, dual of :func:`velocity_ellipsoid`.

    Same principal directions, reciprocal lengths ``1/sigma_i`` (``inf`` where ``sigma_i = 0``): where the arm
    moves fast it pushes weakly and the other way round.
    """
    p = ScaraParams.resolve(p)
    U, s, rows = _position_svd(q, p, rows)
    with np.errstate(divide="ignore"):
        lengths = np.where(s > 0, 1.0 / np.where(s > 0, s, 1.0), np.inf)
    return Ellipsoid(pose(q, p)[:3], U, lengths, rows, "force")


def singular_radii(p: ScaraParams | None = None) -> tuple[float, float]:
    """Radii ``(|a1 - a2|, a1 + a2)`` of the circles where ``w = 0`` (arm folded, arm stretched)."""
    p = ScaraParams.resolve(p)
    return p.r_min, p.r_max


def workspace_map(p: ScaraParams | None = None, n: int = 201):
    """``w`` over a square grid of end-effector positions ``(x, y)`` covering the workspace.

    ``w`` depends on the distance ``r`` to the joint-1 axis only: ``cos theta2 = (r^2 - a1^2 - a2^2) / (2 a1 a2)``
    (1.9) and ``w = a1 a2 sin|theta2|`` (2.7), the same for both elbows. Returns ``(xs, ys, W)`` with ``W[i, j]`` at
    ``(xs[j], ys[i])`` and NaN where the point is outside the annulus (no configuration reaches it).

    ``n`` is a whole number of grid points per side, ``3 <= n <= MAX_GRID = 2001`` (checked before any work).
    """
    p = ScaraParams.resolve(p)
    n = check_count(n, "n", 3, MAX_GRID, "grid points per side")
    xs = np.linspace(-p.r_max, p.r_max, n)
    X, Y = np.meshgrid(xs, xs)
    c2 = elbow_cosine(X, Y, p.a1, p.a2)
    inside = np.abs(c2) <= 1.0 + REACH_TOL  # the rule of ikine: points on the singular circles are reachable
    W = np.full(X.shape, np.nan)
    W[inside] = p.a1 * p.a2 * np.sqrt(np.clip(1.0 - c2[inside] ** 2, 0.0, None))
    return xs, xs.copy(), W
