"""Path primitives in the base frame: the straight segment and the circular arc.

Each primitive maps the arc length ``s`` (m, from 0 to its ``length``) to three vectors (Siciliano et al.,
section 4.3):

* the point ``p(s)``;
* the unit tangent ``t(s) = dp/ds``;
* the curvature vector ``k(s) = d^2 p/ds^2`` (zero on a line, ``-(p - c)/rho^2`` on a circle of radius rho).

With a timing law ``s(t)`` the motion then follows exactly:
``pdot = t sdot`` and ``pddot = t sddot + k sdot^2`` (tangential plus centripetal acceleration).
"""
from __future__ import annotations

import math

import numpy as np

from ..errors import NonFiniteError, ScaraError, as_array, check_positive

__all__ = ["Line", "Arc"]

#: distance (m) under which two points count as the same, and an arc's end counts as on its circle
GEOMETRY_TOL = 1e-9


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
        with np.errstate(over="ignore", invalid="ignore"):
            d = self.end - self.start
            self.length = float(np.linalg.norm(d))
        if not np.isfinite(self.length):
            raise NonFiniteError(f"the line from start = {_fmt(self.start)} to end = {_fmt(self.end)} has a length "
                                 f"that overflows; the points must be finite and reasonably sized (m)")
        if self.length <= GEOMETRY_TOL:
            raise ScaraError(f"a line needs two distinct points, but start = end = {_fmt(self.start)} "
                             f"(a repeated point: |end - start| = {self.length:.3g} m <= {GEOMETRY_TOL:g} m)")
        self.tangent = d / self.length

    def evaluate(self, s):
        """Point, unit tangent and curvature vector at arc lengths ``s`` (n,): three arrays (n, 3)."""
        s = np.asarray(s, dtype=float).reshape(-1)
        p = self.start + s[:, None] * self.tangent
        t = np.broadcast_to(self.tangent, p.shape)
        return p, t, np.zeros_like(p)

    def accumulate(self, s, sd, sdd, x, xd, xdd):
        """Add the displacement ``p(s) - start``, ``t sdot`` and ``t sddot`` to ``x, xd, xdd`` (3, n) in place."""
        for c in range(3):
            tc = self.tangent[c]
            if tc != 0.0:
                x[c] += tc * s
                xd[c] += tc * sd
                xdd[c] += tc * sdd

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
        nn = float(np.linalg.norm(n))
        if nn == 0.0:
            raise ScaraError("the normal of an arc's plane must be a non-zero vector, got [0, 0, 0]")
        self.normal = n / nn
        r0 = self.start - self.centre
        r1 = self.end - self.centre
        for name, r, pt in (("start", r0, self.start), ("end", r1, self.end)):
            off = float(r @ self.normal)
            if abs(off) > GEOMETRY_TOL:
                raise ScaraError(f"the arc's {name} {_fmt(pt)} is not on its circle: it lies {off:.3g} m off the "
                                 f"plane through the centre {_fmt(self.centre)} normal to {_fmt(self.normal)} "
                                 f"(tolerance {GEOMETRY_TOL:g} m)")
        with np.errstate(over="ignore", invalid="ignore"):
            rho0, rho1 = float(np.linalg.norm(r0)), float(np.linalg.norm(r1))
        if not (math.isfinite(rho0) and math.isfinite(rho1)):
            raise NonFiniteError(f"the arc from start {_fmt(self.start)} to end {_fmt(self.end)} about the centre "
                                 f"{_fmt(self.centre)} has a radius that overflows; the points must be reasonably sized (m)")
        rho = rho0 if radius is None else check_positive(radius, "radius")
        if not np.isfinite(rho) or rho <= GEOMETRY_TOL:
            raise ScaraError(f"an arc needs a positive radius, got {rho:.3g} m (start {_fmt(self.start)}, "
                             f"centre {_fmt(self.centre)})")
        for name, d, pt in (("start", rho0, self.start), ("end", rho1, self.end)):
            if abs(d - rho) > GEOMETRY_TOL:
                raise ScaraError(f"the arc's {name} {_fmt(pt)} is not on its circle: its distance from the centre "
                                 f"{_fmt(self.centre)} is {d:.9g} m, the radius is {rho:.9g} m "
                                 f"(tolerance {GEOMETRY_TOL:g} m)")
        self.radius = rho
        self._u = r0 / rho0
        self._v = np.cross(self.normal, self._u)
        angle = math.atan2(float(r1 @ self._v), float(r1 @ self._u)) % (2.0 * math.pi)
        if angle * rho <= GEOMETRY_TOL or (2.0 * math.pi - angle) * rho <= GEOMETRY_TOL:
            raise ScaraError(f"an arc needs distinct ends, but start = end = {_fmt(self.start)} (a repeated point)")
        self.angle = angle
        self.length = angle * rho

    @classmethod
    def through(cls, start, via, end) -> "Arc":
        """The arc from ``start`` through ``via`` to ``end`` (three points (3,), m): the circle through
        them, travelled in the order given.

        The centre is the circumcentre ``c = a + (|ac|^2 (ab x ac) x ab + |ab|^2 ac x (ab x ac)) / (2 |ab x ac|^2)``
        with ``ab = via - start``, ``ac = end - start``; the normal is ``ab x ac`` (so the three points follow
        counter-clockwise). Raises :class:`ScaraError` if the points are collinear or two coincide.

        >>> a = Arc.through([0.28, 0.20, 0.5], [0.23, 0.25, 0.5], [0.18, 0.20, 0.5])
        >>> a.centre.round(9).tolist(), round(a.radius, 9), a.normal.tolist()
        ([0.23, 0.2, 0.5], 0.05, [0.0, 0.0, 1.0])
        """
        a, b, c = _point(start, "start"), _point(via, "via"), _point(end, "end")
        with np.errstate(over="ignore", invalid="ignore"):
            ab, ac = b - a, c - a
            n = np.cross(ab, ac)
            nn2 = float(n @ n)
            scale = float(np.linalg.norm(ab) * np.linalg.norm(ac))
        if not (math.isfinite(nn2) and math.isfinite(scale)):
            raise NonFiniteError(f"the circle through start {_fmt(a)}, via {_fmt(b)} and end {_fmt(c)} cannot be "
                                 f"computed: the points are too far apart and the arithmetic overflows")
        if min(np.linalg.norm(ab), np.linalg.norm(ac), np.linalg.norm(c - b)) <= GEOMETRY_TOL or nn2 <= (1e-12 * scale) ** 2:
            raise ScaraError(f"no circle passes through start {_fmt(a)}, via {_fmt(b)} and end {_fmt(c)}: "
                             f"the points are collinear or two of them coincide")
        centre = a + (float(ac @ ac) * np.cross(n, ab) + float(ab @ ab) * np.cross(ac, n)) / (2.0 * nn2)
        return cls(centre, a, c, normal=n)

    def evaluate(self, s):
        """Point, unit tangent and curvature vector at arc lengths ``s`` (n,): three arrays (n, 3)."""
        s = np.asarray(s, dtype=float).reshape(-1)
        th = s / self.radius
        c, sn = np.cos(th)[:, None], np.sin(th)[:, None]
        radial = c * self._u + sn * self._v
        p = self.centre + self.radius * radial
        t = -sn * self._u + c * self._v
        return p, t, -radial / self.radius

    def accumulate(self, s, sd, sdd, x, xd, xdd):
        """Add ``p(s) - start``, ``t sdot`` and ``t sddot + k sdot^2`` to ``x, xd, xdd`` (3, n) in place."""
        th = s / self.radius
        c, sn = np.cos(th), np.sin(th)
        cm1 = c - 1.0
        sd2 = sd * sd / self.radius
        for k in range(3):
            u, v = self._u[k], self._v[k]
            if u == 0.0 and v == 0.0:
                continue
            tk = -sn * u + c * v
            x[k] += self.radius * (cm1 * u + sn * v)
            xd[k] += tk * sd
            xdd[k] += tk * sdd - (c * u + sn * v) * sd2

    def __repr__(self):
        return (f"Arc({_fmt(self.start)} -> {_fmt(self.end)}, centre {_fmt(self.centre)}, radius {self.radius:.4g} m, "
                f"{math.degrees(self.angle):.1f} deg about {_fmt(self.normal)})")
