"""The robot's parameters (the table of the book's introduction, book/intro.md) in one frozen object."""
from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field

import numpy as np

from .errors import ScaraError, _numbers

__all__ = ["ScaraParams"]


#: the range of the arm's lengths (m): ``a1``, ``a2`` and ``d0`` lie in ``[MIN_LENGTH, MAX_LENGTH]``, the other
#: lengths (``l1``, ``l2``, the stroke) in ``[0, MAX_LENGTH]``. A micrometre to a thousand kilometres: outside it
#: the squares of the kinematics and dynamics underflow or overflow (an arm of 1e-300 m or 1e308 m)
MIN_LENGTH, MAX_LENGTH = 1e-6, 1e6
LENGTHS = ("d0", "a1", "a2", "l1", "l2", "d3_min", "d3_max")
#: the largest mass (kg), inertia (kg m^2), gear ratio, friction or gravity a field accepts
MAX_FIELD = 1e9


def _vec(*values):
    return field(default_factory=lambda: tuple(float(v) for v in values))


@dataclass(frozen=True)
class ScaraParams:
    """Geometry, masses, inertias, motors and payload of the 4-axis SCARA arm (the table of book/intro.md).

    ``ScaraParams()`` is the robot of the course without payload. The object is frozen: a heavier payload
    or a controller's wrong estimate is a copy, made with :meth:`with_payload` or :meth:`replace`.

    Units: metres, kilograms, kg m^2, N m s/rad; ``k_r[2]`` is in rad/m (rotor radians per metre of ``d3``).
    The joint limits are the quill's stroke ``d3_min <= d3 <= d3_max`` (:attr:`q_min`, :attr:`q_max`); the
    revolute joints have none.

    Examples
    --------
    >>> p = ScaraParams().with_payload(5.0)
    >>> p.m3
    15.0
    """

    d0: float = 1.0
    a1: float = 0.5
    a2: float = 0.5
    l1: float = 0.25
    l2: float = 0.25
    m_l1: float = 20.0
    m_l2: float = 20.0
    m_l3: float = 10.0
    I_l1: float = 4.0
    I_l2: float = 4.0
    I_l4: float = 1.0
    k_r: tuple = _vec(1.0, 1.0, 50.0, 20.0)
    I_m: tuple = _vec(0.01, 0.01, 0.005, 0.001)
    F_m: tuple = _vec(5e-5, 5e-5, 0.01, 0.005)
    m_L: float = 0.0
    g0: float = 9.81
    d3_min: float = 0.0
    d3_max: float = 1.0

    def __post_init__(self):
        for f in dataclasses.fields(self):
            v = getattr(self, f.name)
            if f.default_factory is not dataclasses.MISSING:  # a per-joint field: k_r, I_m, F_m
                arr = _numbers(v, f"{f.name} must be 4 numbers (one per joint)")
                if arr.shape != (4,):
                    raise ScaraError(f"{f.name} must have 4 entries (one per joint), got shape {arr.shape}")
                if not np.all(np.isfinite(arr)) or np.any(arr < 0):
                    raise ScaraError(f"{f.name} = {arr.tolist()} must be finite and >= 0")
                if f.name == "k_r" and np.any(arr <= 0):
                    raise ScaraError(f"k_r = {arr.tolist()} must be > 0 for every joint: a gear ratio of 0 would leave "
                                     f"the joint undriven by its motor")
                if np.any(arr > MAX_FIELD):
                    raise ScaraError(f"{f.name} = {arr.tolist()} has an entry above {MAX_FIELD:g}, the largest value a "
                                     f"field accepts (beyond it the model's products overflow or lose every digit)")
                object.__setattr__(self, f.name, tuple(float(x) for x in arr))
            else:
                if isinstance(v, (bool, np.bool_, str, bytes, tuple, list, dict, np.ndarray)):
                    raise ScaraError(f"{f.name} must be a number, got {v!r}")
                try:
                    x = float(v)
                except (TypeError, ValueError) as exc:
                    raise ScaraError(f"{f.name} must be a number, got {v!r}") from exc
                if not np.isfinite(x) or x < 0:
                    raise ScaraError(f"{f.name} = {x} must be finite and >= 0")
                if x > (MAX_LENGTH if f.name in LENGTHS else MAX_FIELD):
                    raise ScaraError(f"{f.name} = {x:g} is above {MAX_LENGTH if f.name in LENGTHS else MAX_FIELD:g}, the "
                                     f"largest value the field accepts (beyond it the model's products overflow or lose "
                                     f"every digit)")
                object.__setattr__(self, f.name, x)
        for name in ("a1", "a2", "d0"):
            if getattr(self, name) <= 0:
                raise ScaraError(f"{name} = {getattr(self, name)} must be > 0 (a length of the arm)")
            if getattr(self, name) < MIN_LENGTH:
                raise ScaraError(f"{name} = {getattr(self, name):g} m is below {MIN_LENGTH:g} m, the shortest link the "
                                 f"package accepts (shorter, the kinematics' squares and products lose every digit)")
        if not self.d3_min < self.d3_max:
            raise ScaraError(f"the quill's stroke d3_min = {self.d3_min:g} m .. d3_max = {self.d3_max:g} m must be a "
                             f"range: d3_min < d3_max")

    # -- the one way every function turns its optional ``p`` into parameters --------------------------
    @classmethod
    def resolve(cls, p) -> "ScaraParams":
        """``p`` itself when it is a :class:`ScaraParams`, the course's robot ``ScaraParams()`` when it is None;
        anything else raises :class:`~scara.ScaraError` naming its type. Every function of the package that takes
        an optional parameter object ``p`` starts with ``p = ScaraParams.resolve(p)``.

        >>> ScaraParams.resolve(None) == ScaraParams()
        True
        """
        if p is None:
            return _DEFAULT
        if not isinstance(p, cls):
            raise ScaraError(f"p must be a ScaraParams object or None, got {type(p).__name__}")
        return p

    #: the fields a planned path depends on: the links' lengths, the height of frame 0 and the quill's stroke
    GEOMETRY = ("a1", "a2", "d0", "d3_min", "d3_max")

    @classmethod
    def for_trajectory(cls, traj, p=None, name: str = "p") -> "ScaraParams":
        """The parameters a computation on the planned ``traj`` uses: ``p`` when given (checked to have the
        geometry, :attr:`GEOMETRY`, that ``traj`` was planned and checked with, ``traj.params``), else
        ``traj.params``, else ``ScaraParams()`` for a trajectory that carries none. Masses and payloads may
        differ (a plant carrying a payload follows a path planned without it); a ``p`` of another geometry is
        refused with a :class:`~scara.ScaraError` naming each field and both values (``name`` names ``p`` in
        the message, e.g. ``"plant"``).
        """
        own = getattr(traj, "params", None)
        if own is None:
            return cls.resolve(p)
        if not isinstance(own, cls):
            raise ScaraError(f"traj.params must be a ScaraParams object (the parameters the trajectory was planned "
                             f"with) or None, got {type(own).__name__}")
        if p is None:
            return own
        p = cls.resolve(p)
        diff = [f for f in cls.GEOMETRY if getattr(p, f) != getattr(own, f)]
        if diff:
            shown = "; ".join(f"{f} = {getattr(p, f)!r} in {name}, {getattr(own, f)!r} in traj.params" for f in diff)
            raise ScaraError(f"{name} has another geometry than traj.params, the arm the trajectory was planned for "
                             f"({shown}); plan the trajectory for this arm (plan_path(..., p={name}))")
        return p

    # -- copies -------------------------------------------------------------------------------------
    def replace(self, **changes) -> "ScaraParams":
        """Return a copy with the given fields replaced, e.g. ``p.replace(m_l3=12.0)``."""
        unknown = set(changes) - {f.name for f in dataclasses.fields(self)}
        if unknown:
            raise ScaraError(f"unknown parameter(s) {sorted(unknown)}; known: {[f.name for f in dataclasses.fields(self)]}")
        return dataclasses.replace(self, **changes)

    def with_payload(self, m_L: float) -> "ScaraParams":
        """Return a copy carrying a point-mass payload ``m_L`` (kg) on the joint-4 axis."""
        return self.replace(m_L=m_L)

    # -- derived quantities -------------------------------------------------------------------------
    @property
    def m3(self) -> float:
        """Mass moving with the quill: ``m_l3 + m_L`` (kg)."""
        return self.m_l3 + self.m_L

    @property
    def F(self) -> np.ndarray:
        """Viscous friction at the joints, ``diag(k_ri^2 F_mi)`` (chapter 5), shape (4,)."""
        return np.asarray(self.k_r) ** 2 * np.asarray(self.F_m)

    @property
    def r_min(self) -> float:
        """Inner radius of the reachable annulus, ``|a1 - a2|`` (m)."""
        return abs(self.a1 - self.a2)

    @property
    def r_max(self) -> float:
        """Outer radius of the reachable annulus, ``a1 + a2`` (m)."""
        return self.a1 + self.a2

    @property
    def q_min(self) -> np.ndarray:
        """Lower joint limits (rad, rad, m, rad): the quill's stroke ``d3_min``; the revolute joints turn freely
        (``-inf``)."""
        return np.array([-np.inf, -np.inf, self.d3_min, -np.inf])

    @property
    def q_max(self) -> np.ndarray:
        """Upper joint limits (rad, rad, m, rad): the quill's stroke ``d3_max``; the revolute joints turn freely."""
        return np.array([np.inf, np.inf, self.d3_max, np.inf])

    def kinematic_array(self) -> np.ndarray:
        """``[a1, a2, d0]`` as a float array, the form compiled kinematic kernels take."""
        return np.array([self.a1, self.a2, self.d0])

    def table(self) -> list[tuple[str, str, str]]:
        """Rows ``(symbol, value, meaning)`` of the parameter table, for display."""
        fmt = lambda v: ", ".join(f"{x:g}" for x in v) if isinstance(v, tuple) else f"{v:g}"  # noqa: E731
        rows = [
            ("d0", "m", "height of frame 0 above the base"),
            ("a1", "m", "length of link 1"), ("a2", "m", "length of link 2"),
            ("l1", "m", "centre of mass of link 1 from joint 1"), ("l2", "m", "centre of mass of link 2 from joint 2"),
            ("m_l1", "kg", "mass of link 1"), ("m_l2", "kg", "mass of link 2"), ("m_l3", "kg", "mass of the quill"),
            ("I_l1", "kg m^2", "inertia of link 1 about its centre of mass"),
            ("I_l2", "kg m^2", "inertia of link 2 about its centre of mass"),
            ("I_l4", "kg m^2", "inertia of link 4 about its axis"),
            ("k_r", "-, -, rad/m, -", "gear ratios"), ("I_m", "kg m^2", "rotor inertias"),
            ("F_m", "N m s/rad", "viscous friction at the rotors"), ("m_L", "kg", "payload"),
            ("g0", "m/s^2", "gravity"),
            ("d3_min", "m", "top of the quill's stroke"), ("d3_max", "m", "bottom of the quill's stroke"),
        ]
        return [(s, f"{fmt(getattr(self, s))} {u}", m) for s, u, m in rows]


#: the robot of the course without payload, returned by :meth:`ScaraParams.resolve` for ``p=None``
_DEFAULT = ScaraParams()
