"""Steady states of the interaction laws on an elastic surface, and the figures of a contact transition
(chapter 7; Siciliano et al., ch. 9), to check against :func:`~.engine.simulate_contact`.

The surface is the elastic environment of the textbook, ``h_e = K (x_e - x_r)`` with ``K = diag(0, 0, k_e, 0)``
(only z is constrained) and ``x_r`` any point of the undeformed surface (``z_r = height``), valid while the tool
presses (``x_e,z < height``; it never pulls). At rest the surface's damper and the regularised friction give no
force, so these are exact equilibria of the simulated plant.
"""
from __future__ import annotations

import numpy as np

from .._compile import kernel
from ..errors import ScaraError, as_array, check_angles, check_positive
from .environment import ForceSensor, Surface
from .laws import ForceController, ParallelController

__all__ = ["elastic_equilibrium", "force_equilibrium", "parallel_equilibrium", "law_equilibrium", "sensor_coupling",
           "contact_transition", "approach_reference", "pressing_target", "approach_run"]


def _surface(surface):
    s = Surface() if surface is None else surface
    if not isinstance(s, Surface):
        raise ScaraError(f"surface must be a Surface or None, got {type(s).__name__}")
    return s


def _bias(sensor) -> np.ndarray:
    if sensor is None:
        return np.zeros(3)
    if not isinstance(sensor, ForceSensor):
        raise ScaraError(f"sensor must be a ForceSensor or None, got {type(sensor).__name__}")
    return np.asarray(sensor.bias, dtype=float)


def sensor_coupling(bias, q, p=None) -> np.ndarray:
    """``c = J_A B^-1 J^T b`` (4,) (m/s^2, rad/s^2): the operational acceleration a force ``b`` (3,) N at the tool
    gives the arm at rest in the configuration ``q`` (``J`` the positional rows of ``J_A``). A law that compensates
    the measured force ``h + b`` (``u = B y + n + J^T (h + b)``) must hold ``y = -B^-1 J^T b`` at rest: the offset
    a sensor's bias leaves in its inner loop. Along z it is about ``b_z / B33``; the rotor of motor 3, carried by
    link 2 (``B13 = B23 != 0``), couples it to x, y and phi.

    >>> c = sensor_coupling([0.0, 0.0, 0.5], [0.0, -np.pi / 2, 0.7, 0.0])
    >>> round(float(c[2]), 4)
    0.0222
    """
    from ..dynamics import inertia  # noqa: PLC0415
    from ..kinematics import jacobian  # noqa: PLC0415

    b = as_array(bias, "bias", (3,))
    J = jacobian(q, p)
    return J @ np.linalg.solve(inertia(q, p), J[:3].T @ b)


def elastic_equilibrium(K_P, x_d, surface: Surface | None = None, offset=None) -> tuple:
    """The rest pose ``x`` (4,) and force ``h_e`` (3,) N of a law that shows the stiffness ``K_P`` (4,) (N/m, N m/rad)
    about ``x_d`` (4,) to the elastic surface (the book's (eq-int-equilibrium), (eq-int-series)): compliance control
    (Siciliano et al., sec. 9.2.2), impedance control and admittance control (sec. 9.3, with their ``K_P``,
    ``K_Pd``) with an ideal sensor.

    ``x = (K_P + K)^-1 (K_P x_d + K x_r)`` and ``h_e = K (x - x_r) = K (K_P + K)^-1 K_P (x_d - x_r)``: the force is
    the surface's stiffness times the penetration the law settles at. When ``x_d`` is not below the surface the
    tool rests at ``x_d`` without contact (``h_e = 0``). ``offset`` (4,) N, N m: a constant force ``w`` the law
    adds at rest, ``K_P x~ = h_A + w`` (a sensor's bias seen through the law, :func:`law_equilibrium`); then
    ``x = (K_P + K)^-1 (K_P x_d + K x_r - w)``.

    >>> x, h = elastic_equilibrium([5000.0] * 4, [0.4, 0.1, 0.2975, 0.0])
    >>> round(float(x[2]), 6), round(float(h[2]), 6)
    (0.2995, -10.0)
    """
    K_P = as_array(K_P, "K_P", (4,))
    if np.any(K_P <= 0):
        raise ScaraError(f"K_P = {K_P.tolist()} must be positive (every entry > 0)")
    x_d = as_array(x_d, "x_d", (4,))
    s = _surface(surface)
    if not x_d[2] < s.height:
        return x_d.copy(), np.zeros(3)
    K = np.diag([0.0, 0.0, s.stiffness, 0.0])
    x_r = np.array([x_d[0], x_d[1], s.height, x_d[3]])
    w = np.zeros(4) if offset is None else as_array(offset, "offset", (4,))
    x = np.linalg.solve(np.diag(K_P) + K, np.diag(K_P) @ x_d + K @ x_r - w)
    return x, (K @ (x - x_r))[:3]


def force_equilibrium(f_d, surface: Surface | None = None, sensor: ForceSensor | None = None) -> tuple:
    """The rest height ``z`` (m) and force ``h_e`` (3,) N of force control with integral action (the book's
    (eq-int-force-rest); Siciliano et al., sec. 9.4.1-9.4.2) or of parallel control (sec. 9.4.3) asked for
    ``f_d`` (3,) N (a number: its z entry) along the surface's normal: the integral makes the *measured* force
    ``f_d``, so the true ``h_z = f_d,z - b_z`` (``b`` the sensor's bias: the force error ``f_d - h_e`` is exactly
    the bias), and the elastic surface sets ``z = height + h_z / k_e``. ``f_d,z`` must press (``f_d,z - b_z < 0``);
    the tangential entries of ``f_d`` must be 0 (a surface without friction at rest bears no tangential force).

    >>> z, h = force_equilibrium(-10.0, sensor=ForceSensor())
    >>> round(float(z), 8), h.tolist()      # the sensor reads 0.5 N too much upward: the tool presses 10.5 N
    (0.299475, [0.0, 0.0, -10.5])
    """
    f = np.array([0.0, 0.0, float(as_array([f_d], "f_d", (1,))[0])]) if np.ndim(f_d) == 0 else \
        np.array(as_array(f_d, "f_d", (3,)), dtype=float)
    if np.any(f[:2] != 0):
        raise ScaraError(f"f_d = {f.tolist()} N: its x and y entries must be 0 (the surface bears no tangential "
                         f"force at rest)")
    s = _surface(surface)
    h = f - _bias(sensor)
    h[:2] = 0.0
    if not h[2] < 0:
        raise ScaraError(f"f_d,z - bias_z = {h[2]:g} N must be < 0: the surface only pushes, the tool must press "
                         f"down")
    return float(s.height + h[2] / s.stiffness), h


def parallel_equilibrium(x_d, f_d, surface: Surface | None = None, sensor: ForceSensor | None = None) -> tuple:
    """The rest pose ``x`` (4,) and force ``h_e`` (3,) of parallel force/position control (Siciliano et al.,
    sec. 9.4.3): ``x = (x_d, y_d, z, phi_d)`` with ``z`` and ``h_e`` of :func:`force_equilibrium`: the force loop
    prevails along the constrained z, the position loop along the free directions.

    >>> x, h = parallel_equilibrium([0.4, 0.1, 0.3, 0.0], -10.0)
    >>> x.round(6).tolist(), h.tolist()
    ([0.4, 0.1, 0.2995, 0.0], [0.0, 0.0, -10.0])
    """
    x = np.array(as_array(x_d, "x_d", (4,)), dtype=float)
    x[2], h = force_equilibrium(f_d, surface, sensor)
    return x, h


def law_equilibrium(controller, x_d, surface: Surface | None = None, sensor: ForceSensor | None = None,
                    p=None, elbow: int = -1) -> tuple:
    """The rest pose ``x`` (4,) and force ``h_e`` (3,) of an interaction law held at ``x_d`` (4,) on the elastic
    surface, the sensor's bias ``b`` included: the one formula per law, checked against the simulation.

    * compliance (no sensor): :func:`elastic_equilibrium` with ``K_P``;
    * impedance, admittance: :func:`elastic_equilibrium` with their stiffness ``S`` and the offset
      ``w = b_A - G c``, ``c = J_A B^-1 J^T b`` (:func:`sensor_coupling`) and ``G`` the law's ``bias_gain()``
      (impedance ``M_d``, admittance ``K_Pd / K_P``); ``w = 0`` for an ideal sensor;
    * parallel: :func:`parallel_equilibrium`, whose free directions keep ``K_P,i x~_i = -c_i``.

    ``c`` is evaluated at the rest configuration (inverse kinematics of ``x`` with ``elbow``, found by fixed-point
    iteration). Force control (whose free directions depend on the transient) has :func:`force_equilibrium`.
    """
    from ..kinematics import ikine  # noqa: PLC0415

    s = _surface(surface)
    b = _bias(sensor)
    x_d = as_array(x_d, "x_d", (4,))
    if isinstance(controller, ParallelController):
        x, h = parallel_equilibrium(x_d, [0.0, 0.0, controller.f_d], s, sensor)
        for _ in range(3):
            c = sensor_coupling(b, ikine(x, p, elbow=elbow), p)
            x = x_d + c / controller.K_P  # K_P x~ = -c: x = x_d + c / K_P
            x[2] = parallel_equilibrium(x_d, [0.0, 0.0, controller.f_d], s, sensor)[0][2]
        return x, h
    if getattr(controller, "stiffness_field", None) is None:
        raise ScaraError(f"law_equilibrium takes a compliance, impedance, admittance or parallel controller, got "
                         f"{type(controller).__name__} (force control's rest is force_equilibrium's)")
    G = controller.bias_gain()
    S = controller.stiffness()
    x, h = elastic_equilibrium(S, x_d, s)
    if G is None or not np.any(b):
        return x, h
    for _ in range(3):
        w = np.append(b, 0.0) - G * sensor_coupling(b, ikine(x, p, elbow=elbow), p)
        x, h = elastic_equilibrium(S, x_d, s, offset=w)
    return x, h


@kernel
def transition_kernel(force, figures):
    """The figures of :func:`contact_transition` from the forces ``h_e`` (N, 3) N of a run, into ``figures`` (5,):
    the index of the first sample in contact (-1: none), the peak normal force ``-h_z`` (N), the losses of contact
    after the first touch, the normal force at the last sample (N), the number of samples in contact. A sample is
    in contact when any entry of its force is nonzero."""
    n = force.shape[0]
    first = -1
    losses = 0
    touching = 0
    before = False
    peak = -force[0, 2]
    for k in range(n):
        now = force[k, 0] != 0.0 or force[k, 1] != 0.0 or force[k, 2] != 0.0
        if now:
            touching += 1
            if first < 0:
                first = k
        elif before and first >= 0:
            losses += 1
        before = now
        fn = -force[k, 2]
        if fn > peak:
            peak = fn
    figures[0] = first
    figures[1] = peak
    figures[2] = losses
    figures[3] = -force[n - 1, 2]
    figures[4] = touching


@kernel
def pressing_height(height, force, kz, ke):
    """The set point's height (m) at which a law showing the stiffness ``kz`` (N/m) presses the surface at
    ``height`` (m) of stiffness ``ke`` (N/m) with ``force`` N: ``height - force (kz + ke) / (kz ke)``
    (:func:`pressing_target`)."""
    return height - force * (kz + ke) / (kz * ke)


def contact_transition(result) -> dict:
    """The figures of a run from free space onto the surface (a :class:`~.engine.ContactResult`): ``first_touch``
    (s, NaN without contact), ``peak_force`` (N, the largest normal force ``-h_z``), ``contact_losses`` (how
    many times the contact was lost after the first touch), ``bounced`` (any loss), ``final_force`` (N, the
    normal force at the last sample)."""
    force = getattr(result, "force", None)
    if force is None:
        raise ScaraError(f"contact_transition needs a run of simulate_contact, got {type(result).__name__}")
    figures = np.zeros(5)
    transition_kernel(np.ascontiguousarray(force, dtype=float), figures)
    k0, peak, losses, final = int(figures[0]), float(figures[1]), int(figures[2]), float(figures[3])
    if k0 < 0:
        return {"first_touch": float("nan"), "peak_force": 0.0, "contact_losses": 0, "bounced": False,
                "final_force": final}
    return {"first_touch": float(result.t[k0]), "peak_force": peak, "contact_losses": losses,
            "bounced": losses > 0, "final_force": final}


class _Reference:
    """An operational reference (``t``, ``x``, ``xd``, ``xdd``, ``dt``) as :func:`scara.simulate` reads it."""

    def __init__(self, t, x, xd, xdd, dt):
        self.t, self.x, self.xd, self.xdd, self.dt = t, x, xd, xdd, dt


def approach_reference(start, target, move: float = 1.0, hold: float = 2.0, dt: float = 1e-3, p=None):
    """A rest-to-rest operational reference from ``start`` to ``target`` (4,) in ``move`` s (a quintic,
    :func:`scara.trajectory.quintic`), then ``hold`` s at ``target``: the approach of a transition run. Both
    poses must be reachable by the arm ``p`` (:func:`~scara.kinematics.check_reachable`, which raises
    :class:`~scara.UnreachableError` naming the pose and the limit).

    >>> r = approach_reference([0.4, 0.1, 0.32, 0.0], [0.4, 0.1, 0.29, 0.0], 0.5, 0.5)
    >>> r.x.shape, float(r.x[-1, 2])
    ((1001, 4), 0.29)
    """
    from .._simulate.interface import _sample_count  # noqa: PLC0415
    from ..kinematics import check_reachable  # noqa: PLC0415
    from ..trajectory import quintic  # noqa: PLC0415

    dt = check_positive(dt, "dt")
    move = _sample_count(move, dt, "move") * dt
    hold = check_positive(hold, "hold", strict=False)
    n_hold = _sample_count(hold, dt, "hold") if hold > 0 else 0
    ends = [as_array(start, "start", (4,)), as_array(target, "target", (4,))]
    for name, x in zip(("start", "target"), ends):
        check_reachable(x[:3], p, label=name)
        check_angles(x, name, columns=(3,))
    jt = quintic(ends[0], ends[1], move, dt=dt, check=False)
    rest = np.repeat(jt.q[-1:], n_hold, axis=0)
    x = np.vstack([jt.q, rest])
    xd = np.vstack([jt.qd, np.zeros_like(rest)])
    xdd = np.vstack([jt.qdd, np.zeros_like(rest)])
    return _Reference(np.arange(len(x)) * dt, x, xd, xdd, dt)


def pressing_target(controller, start, surface: Surface | None = None, force: float = 10.0) -> np.ndarray:
    """The set point (4,) at which ``controller`` presses the surface with ``force`` N (> 0) below ``start`` (4,):
    for a law that shows a stiffness ``S_z`` (compliance, impedance, admittance), ``z_d = height - force (S_z +
    k_e) / (S_z k_e)`` (:func:`elastic_equilibrium` solved for ``z_d``, ideal sensor); for a force law, the
    surface's height (the force comes from its ``f_d``).

    >>> from scara.interaction import ComplianceController
    >>> float(pressing_target(ComplianceController(), [0.4, 0.1, 0.32, 0.0])[2])
    0.2975
    """
    s = _surface(surface)
    force = check_positive(force, "force")
    target = np.array(as_array(start, "start", (4,)), dtype=float)
    if getattr(controller, "stiffness_field", None) is None:
        target[2] = s.height
    else:
        target[2] = pressing_height(s.height, force, float(controller.stiffness()[2]), s.stiffness)
    return target


def approach_run(controller, surface: Surface | None = None, sensor: ForceSensor | None = None, *,
                 at=(0.4, 0.1), lift: float = 0.02, force: float = 10.0, move: float = 1.0, hold: float = 2.0,
                 substeps: int = 10):
    """A transition run from free space onto the surface: the tool starts at rest ``lift`` m above the surface at
    ``at`` (x, y) m (elbow -1, ``theta4 = 0``); the reference moves (a quintic of ``move`` s) to
    :func:`pressing_target` (a force law keeps its start and lets its force loop lower it) and holds ``hold`` s.
    Returns the :class:`~.engine.ContactResult` (:func:`contact_transition` gives its figures)."""
    from ..kinematics import ikine  # noqa: PLC0415
    from .engine import simulate_contact  # noqa: PLC0415

    s = _surface(surface)
    xy = as_array(at, "at", (2,))
    lift = check_positive(lift, "lift")
    q = ikine([xy[0], xy[1], s.height + lift, 0.0], elbow=-1)
    start = np.array([xy[0], xy[1], s.height + lift, q[0] + q[1]])
    target = start if isinstance(controller, ForceController) else pressing_target(controller, start, s, force)
    return simulate_contact(controller, approach_reference(start, target, move, hold), surface=s, sensor=sensor,
                            substeps=substeps, elbow=-1)
