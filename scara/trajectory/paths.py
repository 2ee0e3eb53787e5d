"""Path primitives in the base frame: the straight segment and the circular arc.

Each primitive maps the arc length ``s`` (m, from 0 to its ``length``) to three vectors (Siciliano et al.,
section 4.3):

* the point ``p(s)``;
* the unit tangent ``t(s) = dp/ds``;
* the curvature vector ``k(s) = d^2 p/ds^2`` (zero on a line, ``-(p - c)/rho^2`` on a circle of radius rho).

With a timing law ``s(t)`` the motion then follows exactly:
``pdot = t sdot`` and ``pddot = t sddot + k sdot^2`` (tangential plus centripetal acceleration).

The geometry of both primitives is computed once, by compiled kernels that the classes and the planner's
kernels (:mod:`scara.trajectory._plan`) share: :func:`line_geometry` (length and tangent), :func:`arc_through`
(the circle through three points) and :func:`arc_geometry` (radius, angle, length and the in-plane axes ``u, v``
of an arc), each returning a code for what it refuses; the classes turn a code into its message.
"""
from __future__ import annotations

import math

import numpy as np

from .._compile import kernel
from ..errors import NonFiniteError, ScaraError, as_array, check_positive

__all__ = ["Line", "Arc", "line_geometry", "arc_through", "arc_geometry", "GEOMETRY_TOL"]

#: distance (m) under which two points count as the same, and an arc's end counts as on its circle
GEOMETRY_TOL = 1e-9

#: the codes of the geometry kernels (shared with the planner's codes, :mod:`scara.trajectory._plan`)
GEOMETRY_OK = 0
LINE_OVERFLOW = 9
LINE_REPEATED = 8
ARC_OVERFLOW = 10
ARC_COLLINEAR = 11
ARC_NORMAL_ZERO = 12
ARC_START_OFF_PLANE = 13
ARC_END_OFF_PLANE = 14
ARC_RADIUS_OVERFLOW = 15
ARC_RADIUS_TOO_SMALL = 16
ARC_START_OFF_CIRCLE = 17
ARC_END_OFF_CIRCLE = 18
ARC_SAME_ENDS = 19

#: the fields of :func:`arc_geometry`'s ``out``: radius, angle, length, the unit vectors ``u``, ``v`` and
#: ``normal``, then the number the message of a refusal needs (the distance off the plane or the circle)
ARC_RADIUS, ARC_ANGLE, ARC_LENGTH, ARC_U, ARC_V, ARC_NORMAL, ARC_INFO, ARC_RHO0, ARC_RHO1 = 0, 1, 2, 3, 6, 9, 12, 13, 14
ARC_OUT = 15


@kernel(light=True)
def line_geometry(a, b):
    """``(code, length, t_x, t_y, t_z)`` of the segment from ``a`` to ``b`` (3,): ``length = |b - a|`` and the unit
    tangent ``t = (b - a) / length`` (eq. 4.34); the code is :data:`LINE_OVERFLOW` for a length that is not finite,
    :data:`LINE_REPEATED` for one of at most :data:`GEOMETRY_TOL`."""
    dx = b[0] - a[0]
    dy = b[1] - a[1]
    dz = b[2] - a[2]
    length = math.sqrt(dx * dx + dy * dy + dz * dz)
    if not math.isfinite(length):
        return LINE_OVERFLOW, length, 0.0, 0.0, 0.0
    if length <= GEOMETRY_TOL:
        return LINE_REPEATED, length, 0.0, 0.0, 0.0
    return GEOMETRY_OK, length, dx / length, dy / length, dz / length


@kernel
def _dot3(ax, ay, az, bx, by, bz):
    return ax * bx + ay * by + az * bz


@kernel(light=True)
def arc_through(a, b, c, out):
    """The circle through ``a``, ``b``, ``c`` (3,), travelled in that order: the centre (circumcentre)
    ``a + (|ac|^2 (ab x ac) x ab + |ab|^2 ac x (ab x ac)) / (2 |ab x ac|^2)`` written into ``out[0:3]`` and the
    normal ``ab x ac`` into ``out[3:6]``. Returns :data:`ARC_OVERFLOW` when the arithmetic overflows,
    :data:`ARC_COLLINEAR` when two points coincide (within :data:`GEOMETRY_TOL`) or the three are collinear,
    :data:`GEOMETRY_OK` otherwise."""
    abx, aby, abz = b[0] - a[0], b[1] - a[1], b[2] - a[2]
    acx, acy, acz = c[0] - a[0], c[1] - a[1], c[2] - a[2]
    nx = aby * acz - abz * acy
    ny = abz * acx - abx * acz
    nz = abx * acy - aby * acx
    nn2 = _dot3(nx, ny, nz, nx, ny, nz)
    lab = math.sqrt(_dot3(abx, aby, abz, abx, aby, abz))
    lac = math.sqrt(_dot3(acx, acy, acz, acx, acy, acz))
    scale = lab * lac
    if not (math.isfinite(nn2) and math.isfinite(scale)):
        return ARC_OVERFLOW
    bcx, bcy, bcz = c[0] - b[0], c[1] - b[1], c[2] - b[2]
    lbc = math.sqrt(_dot3(bcx, bcy, bcz, bcx, bcy, bcz))
    if min(lab, lac, lbc) <= GEOMETRY_TOL or nn2 <= (1e-12 * scale) ** 2:
        return ARC_COLLINEAR
    fa = _dot3(acx, acy, acz, acx, acy, acz)
    fb = _dot3(abx, aby, abz, abx, aby, abz)
    # n x ab and ac x n
    p1x, p1y, p1z = ny * abz - nz * aby, nz * abx - nx * abz, nx * aby - ny * abx
    p2x, p2y, p2z = acy * nz - acz * ny, acz * nx - acx * nz, acx * ny - acy * nx
    den = 2.0 * nn2
    out[0] = a[0] + (fa * p1x + fb * p2x) / den
    out[1] = a[1] + (fa * p1y + fb * p2y) / den
    out[2] = a[2] + (fa * p1z + fb * p2z) / den
    out[3] = nx
    out[4] = ny
    out[5] = nz
    return GEOMETRY_OK


@kernel(light=True)
def arc_geometry(centre, start, end, normal, radius, out):
    """The arc about ``centre`` from ``start`` to ``end`` (3,), counter-clockwise about ``normal`` (3,), written into
    ``out`` (:data:`ARC_OUT`,): the radius ``rho`` (``radius``, or ``|start - centre|`` when ``radius`` is NaN),
    the angle swept in ``[0, 2 pi)``, the length ``angle rho`` and the unit vectors ``u = (start - c)/|start - c|``,
    ``v = n x u`` and ``n`` of eq. 4.37. Returns the code of what is refused (a zero normal, an end off the plane
    or off the circle by more than :data:`GEOMETRY_TOL`, a radius that overflows or is not positive, ends that
    coincide; ``out[ARC_INFO]`` then holds the distance the message names) or :data:`GEOMETRY_OK`."""
    nn = math.sqrt(_dot3(normal[0], normal[1], normal[2], normal[0], normal[1], normal[2]))
    if nn == 0.0:
        return ARC_NORMAL_ZERO
    n0, n1, n2 = normal[0] / nn, normal[1] / nn, normal[2] / nn
    out[ARC_NORMAL] = n0
    out[ARC_NORMAL + 1] = n1
    out[ARC_NORMAL + 2] = n2
    r0x, r0y, r0z = start[0] - centre[0], start[1] - centre[1], start[2] - centre[2]
    r1x, r1y, r1z = end[0] - centre[0], end[1] - centre[1], end[2] - centre[2]
    off = _dot3(r0x, r0y, r0z, n0, n1, n2)
    if abs(off) > GEOMETRY_TOL:
        out[ARC_INFO] = off
        return ARC_START_OFF_PLANE
    off = _dot3(r1x, r1y, r1z, n0, n1, n2)
    if abs(off) > GEOMETRY_TOL:
        out[ARC_INFO] = off
        return ARC_END_OFF_PLANE
    rho0 = math.sqrt(_dot3(r0x, r0y, r0z, r0x, r0y, r0z))
    rho1 = math.sqrt(_dot3(r1x, r1y, r1z, r1x, r1y, r1z))
    out[ARC_RHO0] = rho0
    out[ARC_RHO1] = rho1
    if not (math.isfinite(rho0) and math.isfinite(rho1)):
        return ARC_RADIUS_OVERFLOW
    rho = rho0 if math.isnan(radius) else radius
    out[ARC_RADIUS] = rho
    if not math.isfinite(rho) or rho <= GEOMETRY_TOL:
        return ARC_RADIUS_TOO_SMALL
    if abs(rho0 - rho) > GEOMETRY_TOL:
        out[ARC_INFO] = rho0
        return ARC_START_OFF_CIRCLE
    if abs(rho1 - rho) > GEOMETRY_TOL:
        out[ARC_INFO] = rho1
        return ARC_END_OFF_CIRCLE
    ux, uy, uz = r0x / rho0, r0y / rho0, r0z / rho0
    vx, vy, vz = n1 * uz - n2 * uy, n2 * ux - n0 * uz, n0 * uy - n1 * ux
    angle = math.atan2(_dot3(r1x, r1y, r1z, vx, vy, vz), _dot3(r1x, r1y, r1z, ux, uy, uz)) % (2.0 * math.pi)
    if angle * rho <= GEOMETRY_TOL or (2.0 * math.pi - angle) * rho <= GEOMETRY_TOL:
        return ARC_SAME_ENDS
    out[ARC_ANGLE] = angle
    out[ARC_LENGTH] = angle * rho
    out[ARC_U] = ux
    out[ARC_U + 1] = uy
    out[ARC_U + 2] = uz
    out[ARC_V] = vx
    out[ARC_V + 1] = vy
    out[ARC_V + 2] = vz
    return GEOMETRY_OK


def _point(value, name):
    return as_array(value, name, (3,)).copy()


def _fmt(v) -> str:
    return np.array2string(np.asarray(v, dtype=float), precision=4, separator=", ")


class Line:
    """The straight segment from ``start`` to ``end`` (both (3,), m).

    ``p(s) = start + s t`` with the constant unit tangent ``t = (end - start) / |end - start|``
    (Siciliano et al., eq. 4.34).

    Raises
    ------
    ScaraError
        ``start`` and ``end`` coincide (a repeated point: the segment would have no direction).

    >>> Line([0, 0, 0.5], [0.3, 0.4, 0.5]).length
    0.5
    """

    kind = "line"

    def __init__(self, start, end):
        self.start = _point(start, "start")
        self.end = _point(end, "end")
        code, length, tx, ty, tz = line_geometry(self.start, self.end)
        self.length = float(length)
        if code == LINE_OVERFLOW:
            raise NonFiniteError(f"the line from start = {_fmt(self.start)} to end = {_fmt(self.end)} has a length "
                                 f"that overflows; the points must be finite and reasonably sized (m)")
        if code == LINE_REPEATED:
            raise ScaraError(f"a line needs two distinct points, but start = end = {_fmt(self.start)} "
                             f"(a repeated point: |end - start| = {self.length:.3g} m <= {GEOMETRY_TOL:g} m)")
        self.tangent = np.array([tx, ty, tz])

    def evaluate(self, s):
        """Point, unit tangent and curvature vector at arc lengths ``s`` (n,): three arrays (n, 3)."""
        s = np.asarray(s, dtype=float).reshape(-1)
        p = self.start + s[:, None] * self.tangent
        t = np.broadcast_to(self.tangent, p.shape)
        return p, t, np.zeros_like(p)

    def __repr__(self):
        return f"Line({_fmt(self.start)} -> {_fmt(self.end)}, length {self.length:.4g} m)"


class Arc:
    """A circular arc of centre ``centre`` from ``start`` to ``end``, turning counter-clockwise about
    the unit ``normal`` (right-hand rule); its plane is the one through ``centre`` normal to ``normal``.

    With ``u = (start - c)/rho`` and ``v = n x u``: ``p(s) = c + rho (cos(s/rho) u + sin(s/rho) v)``
    (Siciliano et al., eq. 4.37), ``t(s) = -sin u + cos v``, ``k(s) = -(cos u + sin v)/rho``.

    Parameters
    ----------
    centre, start, end : array (3,)
        Metres, in the base frame.
    normal : array (3,)
        Axis of the arc's plane; the sense of travel is counter-clockwise about it. Default +z (the arc
        turns counter-clockwise seen from above).
    radius : float, optional
        If given, both ends must lie at this distance from the centre.

    Raises
    ------
    ScaraError
        An end is not on the circle (its distance from the centre differs from the radius, or from the other
        end's, by more than 1e-9 m), an end is off the plane, the radius is zero, the normal is zero, or
        start and end coincide.

    >>> a = Arc([0.23, 0.20, 0.5], [0.28, 0.20, 0.5], [0.18, 0.20, 0.5])
    >>> round(a.length, 6)   # a half circle of radius 0.05 m
    0.15708
    """

    kind = "arc"

    def __init__(self, centre, start, end, normal=(0.0, 0.0, 1.0), radius=None):
        self.centre = _point(centre, "centre")
        self.start = _point(start, "start")
        self.end = _point(end, "end")
        n = as_array(normal, "normal", (3,))
        rho_in = math.nan if radius is None else check_positive(radius, "radius")
        out = np.zeros(ARC_OUT)
        code = arc_geometry(self.centre, self.start, self.end, np.ascontiguousarray(n, dtype=float), rho_in, out)
        if code != GEOMETRY_OK:
            raise arc_error(code, out, self.centre, self.start, self.end)
        self.normal = out[ARC_NORMAL:ARC_NORMAL + 3].copy()
        self.radius = float(out[ARC_RADIUS])
        self._u = out[ARC_U:ARC_U + 3].copy()
        self._v = out[ARC_V:ARC_V + 3].copy()
        self.angle = float(out[ARC_ANGLE])
        self.length = float(out[ARC_LENGTH])

    @classmethod
    def through(cls, start, via, end) -> "Arc":
        """The arc from ``start`` through ``via`` to ``end`` (three points (3,), m): the circle through
        them, travelled in the order given (:func:`arc_through`).

        The centre is the circumcentre ``c = a + (|ac|^2 (ab x ac) x ab + |ab|^2 ac x (ab x ac)) / (2 |ab x ac|^2)``
        with ``ab = via - start``, ``ac = end - start``; the normal is ``ab x ac`` (so the three points follow
        counter-clockwise). Raises :class:`ScaraError` if the points are collinear or two coincide.

        >>> a = Arc.through([0.28, 0.20, 0.5], [0.23, 0.25, 0.5], [0.18, 0.20, 0.5])
        >>> a.centre.round(9).tolist(), round(a.radius, 9), a.normal.tolist()
        ([0.23, 0.2, 0.5], 0.05, [0.0, 0.0, 1.0])
        """
        a, b, c = _point(start, "start"), _point(via, "via"), _point(end, "end")
        out = np.zeros(6)
        code = arc_through(a, b, c, out)
        if code != GEOMETRY_OK:
            raise through_error(code, a, b, c)
        return cls(out[:3], a, c, normal=out[3:6])

    def evaluate(self, s):
        """Point, unit tangent and curvature vector at arc lengths ``s`` (n,): three arrays (n, 3)."""
        s = np.asarray(s, dtype=float).reshape(-1)
        th = s / self.radius
        c, sn = np.cos(th)[:, None], np.sin(th)[:, None]
        radial = c * self._u + sn * self._v
        p = self.centre + self.radius * radial
        t = -sn * self._u + c * self._v
        return p, t, -radial / self.radius

    def __repr__(self):
        return (f"Arc({_fmt(self.start)} -> {_fmt(self.end)}, centre {_fmt(self.centre)}, radius {self.radius:.4g} m, "
                f"{math.degrees(self.angle):.1f} deg about {_fmt(self.normal)})")


def through_error(code, a, b, c) -> ScaraError:
    """The error of :func:`arc_through`'s ``code`` for the points ``a``, ``b``, ``c``."""
    if code == ARC_OVERFLOW:
        return NonFiniteError(f"the circle through start {_fmt(a)}, via {_fmt(b)} and end {_fmt(c)} cannot be "
                              f"computed: the points are too far apart and the arithmetic overflows")
    return ScaraError(f"no circle passes through start {_fmt(a)}, via {_fmt(b)} and end {_fmt(c)}: "
                      f"the points are collinear or two of them coincide")


def arc_error(code, out, centre, start, end) -> ScaraError:
    """The error of :func:`arc_geometry`'s ``code`` (its ``out``) for the arc about ``centre`` from ``start`` to
    ``end``."""
    if code == ARC_NORMAL_ZERO:
        return ScaraError("the normal of an arc's plane must be a non-zero vector, got [0, 0, 0]")
    if code in (ARC_START_OFF_PLANE, ARC_END_OFF_PLANE):
        name, pt = ("start", start) if code == ARC_START_OFF_PLANE else ("end", end)
        normal = out[ARC_NORMAL:ARC_NORMAL + 3]
        return ScaraError(f"the arc's {name} {_fmt(pt)} is not on its circle: it lies {out[ARC_INFO]:.3g} m off the "
                          f"plane through the centre {_fmt(centre)} normal to {_fmt(normal)} "
                          f"(tolerance {GEOMETRY_TOL:g} m)")
    if code == ARC_RADIUS_OVERFLOW:
        return NonFiniteError(f"the arc from start {_fmt(start)} to end {_fmt(end)} about the centre "
                              f"{_fmt(centre)} has a radius that overflows; the points must be reasonably sized (m)")
    rho = float(out[ARC_RADIUS])
    if code == ARC_RADIUS_TOO_SMALL:
        return ScaraError(f"an arc needs a positive radius, got {rho:.3g} m (start {_fmt(start)}, "
                          f"centre {_fmt(centre)})")
    if code in (ARC_START_OFF_CIRCLE, ARC_END_OFF_CIRCLE):
        name, pt = ("start", start) if code == ARC_START_OFF_CIRCLE else ("end", end)
        return ScaraError(f"the arc's {name} {_fmt(pt)} is not on its circle: its distance from the centre "
                          f"{_fmt(centre)} is {out[ARC_INFO]:.9g} m, the radius is {rho:.9g} m "
                          f"(tolerance {GEOMETRY_TOL:g} m)")
    return ScaraError(f"an arc needs distinct ends, but start = end = {_fmt(start)} (a repeated point)")
