"""The trapezoidal timing law: linear segments with parabolic blends on a path's arc length.

The arc length ``s(tau)`` (``tau`` = time since the segment started, ``0 <= tau <= T``) accelerates at a
constant rate for the blend time ``t_c``, cruises at ``v_c``, and decelerates symmetrically (Siciliano et al.,
eqs. 4.8-4.9, applied to ``s`` as in section 4.3):

    s = a tau^2 / 2                       0 <= tau < t_c
    s = v_c (tau - t_c / 2)               t_c <= tau < T - t_c
    s = L - a (T - tau)^2 / 2             T - t_c <= tau <= T

with ``v_c = L / (T - t_c)`` and ``a = v_c / t_c``; ``s = 0`` before the start and ``s = L`` after the end.
The blend may not exceed half the duration (``t_c = T/2`` is the triangular profile).

The acceleration is piecewise constant and taken right-continuous: at a switching instant it already has
its new value, so a forward-Euler step from that sample integrates the velocity exactly.

The law is written once, as two compiled kernels that :class:`Trapezoidal` and the planner's sampling
(:mod:`scara.trajectory._plan`) both call: :func:`trapezoid_check` (the blend clipped to ``T/2``, ``v_c`` and ``a``,
or the code of what is wrong) and :func:`trapezoid_at` (``s, sdot, sddot`` at one time).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .._compile import kernel
from ..errors import NonFiniteError, ScaraError, ShapeError, check_positive

__all__ = ["Trapezoidal", "trapezoidal", "DEFAULT_BLEND_FRACTION", "MAX_SEGMENT_SAMPLES", "times",
           "trapezoid_check", "trapezoid_at", "LAW_OK", "LAW_BLEND_TOO_LONG", "LAW_NOT_FINITE"]

#: largest number of sampling periods ``T / dt`` of one profile (:meth:`Trapezoidal.minimum_time`): a
#: trajectory is stored sample by sample, and the planner allows at most ``MAX_SAMPLES`` of them in all
MAX_SEGMENT_SAMPLES = 2_000_000


def times(tau, name: str = "tau") -> np.ndarray:
    """``tau`` as a float array of times (s) of any shape, every entry finite: a NaN or infinite time has no
    place on the profile and is refused (:class:`~scara.NonFiniteError`) rather than read as "before the
    start" or "after the end"."""
    try:
        raw = np.asarray(tau)
        if isinstance(tau, (str, bytes)) or raw.dtype.kind not in "iuf":
            raise TypeError("not numbers")
        arr = raw.astype(float)
    except (TypeError, ValueError, OverflowError) as exc:
        raise ShapeError(f"{name} must be a time or an array of times (s), got {tau!r}") from exc
    bad = ~np.isfinite(arr)
    if bad.any():
        idx = tuple(int(i) for i in np.argwhere(bad)[0])
        where = f"{name}[{idx[0] if len(idx) == 1 else idx}]" if idx else name
        raise NonFiniteError(f"{where} = {arr[idx]} is not a finite time; every time must be a finite number of "
                             f"seconds")
    return arr

#: blend time as a fraction of the duration when none is given (cruise speed 1.5 L / T)
DEFAULT_BLEND_FRACTION = 1.0 / 3.0

#: :func:`trapezoid_check`'s codes: a valid law, a blend longer than half the duration, a speed or an
#: acceleration that is not finite (the planner returns the same numbers for a segment's law)
LAW_OK = 0
LAW_BLEND_TOO_LONG = 21
LAW_NOT_FINITE = 22


@kernel(light=True)
def trapezoid_check(L, T, tc):
    """``(code, blend, v_c, a)`` of the law covering ``L`` (m) in ``T`` (s) with the blend ``tc`` (s), all three
    positive: the blend is refused (:data:`LAW_BLEND_TOO_LONG`) beyond ``T/2`` (with a relative tolerance of
    1e-12) and clipped to it otherwise; ``v_c = L / (T - t_c)`` and ``a = v_c / t_c`` (eqs. 4.8-4.9) must be finite
    (:data:`LAW_NOT_FINITE` otherwise)."""
    if tc > T / 2 * (1 + 1e-12):
        return LAW_BLEND_TOO_LONG, tc, 0.0, 0.0
    blend = min(tc, T / 2)
    v = L / (T - blend)
    a = v / blend
    if not (math.isfinite(v) and math.isfinite(a)):
        return LAW_NOT_FINITE, blend, v, a
    return LAW_OK, blend, v, a


@kernel
def trapezoid_at(tau, L, T, tc, v, a):
    """``(s, sdot, sddot)`` of the trapezoidal law (eqs. 4.8-4.9) at ``tau`` (s since the start), for the blend
    ``tc``, cruise speed ``v`` and acceleration ``a`` of :func:`trapezoid_check`: ``0, 0, 0`` before the start,
    ``L, 0, 0`` from ``T`` on, the acceleration right-continuous at every switching instant."""
    if tau < 0.0:
        return 0.0, 0.0, 0.0
    if tau >= T:
        return L, 0.0, 0.0
    if tau < tc:
        return 0.5 * a * tau * tau, a * tau, a
    if tau < T - tc:
        return v * (tau - 0.5 * tc), v, 0.0
    r = T - tau
    return L - 0.5 * a * r * r, a * r, -a


@kernel
def _trapezoid_batch(tau, L, T, tc, v, a, s, sd, sdd):
    """:func:`trapezoid_at` at every entry of ``tau`` (n,), written into ``s, sd, sdd`` (n,)."""
    for i in range(tau.shape[0]):
        s[i], sd[i], sdd[i] = trapezoid_at(tau[i], L, T, tc, v, a)


def in_time_order(evaluate, t: np.ndarray):
    """For times ``t`` (n,) out of ascending order: ``evaluate`` (which walks the segments forwards, so needs
    them sorted) run on the sorted times, its outputs (arrays of n rows) put back in the order of ``t``.
    ``None`` when ``t`` is already in order, for the caller to evaluate directly."""
    if t.size < 2 or not np.any(np.diff(t) < 0):
        return None
    order = np.argsort(t, kind="stable")
    out = []
    for a in evaluate(t[order]):
        o = np.empty_like(a)
        o[order] = a
        out.append(o)
    return tuple(out)


@dataclass(frozen=True)
class Trapezoidal:
    """A trapezoidal velocity profile covering ``length`` (m) in ``duration`` (s) with blends of ``blend`` (s).

    Attributes ``cruise_speed`` (m/s) and ``acceleration`` (m/s^2) follow from the three inputs.

    Raises
    ------
    ScaraError
        A non-positive length, duration or blend, or a blend longer than half the duration.

    >>> law = Trapezoidal(length=0.3, duration=3.0, blend=1.0)
    >>> law.cruise_speed, law.acceleration
    (0.15, 0.15)
    >>> [float(v) for v in law.evaluate(1.5)]     # mid-way: half the length, cruising, no acceleration
    [0.15, 0.15, 0.0]
    """

    length: float
    duration: float
    blend: float

    def __post_init__(self):
        L = check_positive(self.length, "length")
        T = check_positive(self.duration, "duration")
        tc = check_positive(self.blend, "blend")
        code, blend, v, a = trapezoid_check(L, T, tc)
        if code != LAW_OK:
            raise ScaraError(law_message(code, L, T, tc, blend, v, a))
        object.__setattr__(self, "length", L)
        object.__setattr__(self, "duration", T)
        object.__setattr__(self, "blend", blend)

    @property
    def cruise_speed(self) -> float:
        """``v_c = L / (T - t_c)`` (m/s), the peak of ``sdot``."""
        return self.length / (self.duration - self.blend)

    @property
    def acceleration(self) -> float:
        """``a = v_c / t_c`` (m/s^2), the magnitude of ``sddot`` during the blends."""
        return self.cruise_speed / self.blend

    @classmethod
    def minimum_time(cls, length, speed, acceleration, dt=None) -> "Trapezoidal":
        """The fastest profile over ``length`` with speed at most ``speed`` and acceleration ``acceleration``.

        If the cruise speed is reachable (``L >= v^2/a``): ``t_c = v/a`` and ``T = L/v + v/a``; otherwise the
        profile is triangular, ``t_c = sqrt(L/a)``, ``T = 2 t_c``. With ``dt`` the duration is rounded up to a
        whole number of samples and the blend recomputed for the same acceleration,
        ``t_c = T/2 - sqrt(T^2/4 - L/a)`` (Siciliano et al., eq. 4.10), so the speed stays within ``speed``.

        >>> law = Trapezoidal.minimum_time(0.4, speed=0.2, acceleration=0.4)
        >>> law.duration, law.blend
        (2.5, 0.5)
        """
        L = check_positive(length, "length")
        v = check_positive(speed, "speed")
        a = check_positive(acceleration, "acceleration")
        if L >= v * v / a:
            tc, T = v / a, L / v + v / a
        else:
            tc = math.sqrt(L / a)
            T = 2.0 * tc
        if dt is not None:
            dt = check_positive(dt, "dt")
            if not T / dt <= MAX_SEGMENT_SAMPLES:
                raise ScaraError(f"dt = {dt:g} s is too short for this profile: its duration {T:g} s would take "
                                 f"{T / dt:.4g} sampling periods, more than MAX_SEGMENT_SAMPLES = "
                                 f"{MAX_SEGMENT_SAMPLES:g}")
            n = math.ceil(T / dt - 1e-9)
            T = n * dt
            tc = T / 2 - math.sqrt(max(T * T / 4 - L / a, 0.0))
        return cls(L, T, tc)

    def evaluate(self, tau):
        """``s, sdot, sddot`` at times ``tau`` (s since the segment's start; scalar or array of any shape), by
        :func:`trapezoid_at`.

        Before the start the values are ``0, 0, 0``; after the end ``L, 0, 0``. A NaN or infinite time raises
        :class:`~scara.NonFiniteError`.
        """
        tau = times(tau)
        flat = np.ascontiguousarray(tau, dtype=float).reshape(-1)
        s, sd, sdd = np.empty_like(flat), np.empty_like(flat), np.empty_like(flat)
        _trapezoid_batch(flat, self.length, self.duration, self.blend, self.cruise_speed, self.acceleration, s, sd,
                         sdd)
        return s.reshape(tau.shape), sd.reshape(tau.shape), sdd.reshape(tau.shape)

    def evaluate_sorted(self, tau):
        """:meth:`evaluate` for a sorted 1-D array ``tau`` within ``[0, T)`` (kept for callers that know their
        times are sorted; the law is evaluated time by time either way). A NaN or infinite time raises
        :class:`~scara.NonFiniteError`."""
        return self.evaluate(np.asarray(times(tau), dtype=float).reshape(-1))

    def switching_times(self) -> np.ndarray:
        """The instants (since the start) where ``sddot`` jumps: ``[0, t_c, T - t_c, T]`` (s)."""
        return np.array([0.0, self.blend, self.duration - self.blend, self.duration])


def law_message(code, L, T, tc, blend, v, a) -> str:
    """The message of :func:`trapezoid_check`'s ``code`` for the law ``L, T, tc`` (its outputs ``blend, v, a``)."""
    if code == LAW_BLEND_TOO_LONG:
        return (f"blend = {tc:g} s is longer than half the duration T/2 = {T / 2:g} s; a trapezoidal profile needs "
                f"0 < blend <= T/2")
    return (f"length = {L:g} m over duration = {T:g} s with blend = {blend:g} s needs a speed {v:g} m/s and an "
            f"acceleration {a:g} m/s^2 that are not finite: the length is too large for the duration")


def trapezoidal(tau, length, duration, blend=None):
    """``s, sdot, sddot`` of the trapezoidal timing law at times ``tau`` (see :class:`Trapezoidal`).

    ``blend`` defaults to a third of the duration (cruise speed ``1.5 L / T``).

    >>> s, sd, sdd = trapezoidal([0.0, 1.0, 2.0, 3.0], length=0.3, duration=3.0)
    >>> s.round(3).tolist(), sd.round(3).tolist()
    ([0.0, 0.075, 0.225, 0.3], [0.0, 0.15, 0.15, 0.0])
    """
    T = check_positive(duration, "duration")
    law = Trapezoidal(length, T, DEFAULT_BLEND_FRACTION * T if blend is None else blend)
    return law.evaluate(tau)
