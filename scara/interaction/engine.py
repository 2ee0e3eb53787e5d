"""The closed loop in contact (chapter 7): the engine of chapter 5 with an environment in the plant and a wrist
force sensor whose reading the law receives.

    result = simulate_contact(controller, traj, surface=Surface(), sensor=ForceSensor(), substeps=10)

At every sample ``t_k`` the engine evaluates the contact force ``h_e(t_k)`` at the measured state (recorded in
``result.force``), adds the sensor's error (``result.measured_force``) and, when the controller's ``work_layout``
declares a row named ``measured_force``, writes the reading ``[h_x, h_y, h_z, 0]`` there before calling the law:
the law's signature (:data:`~scara._compile.LAW_SIGNATURE`) is unchanged, and a law reads the force as it reads
any scratch row. Then the plant, with ``tau_k`` held, is integrated to ``t_{k+1}`` by ``substeps`` RK4 steps of
:func:`.plant.contact_rk4_step`, the peg's state (:func:`.environment.inside_after`) updated after each.

Without an environment (``surface=None``) the loop steps the free plant (:func:`scara._simulate.plant._rk4_step`)
and the run is :func:`scara.simulate`'s, bit for bit.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np

from .. import _compile
from .._simulate.engine import (
    Series, Stepping, _check_run, _first_bad_signal, _owned, _raise_failure,
)
from .._simulate.engine import _before_law, _law_failed, _loop_arrays, _loop_start, _state_failed
from .._simulate.interface import (
    MEASURED_FORCE, NOT_FINITE, OK, SINGULAR_INERTIA, _compiled_law, check_law_bounds, law_arrays,
)
from .._simulate.plant import _plant_acceleration, _plant_constants, _rk4_step
from .._simulate.result import SimulationResult, _pose_error
from .._simulate.setpoints import _references, _start_state
from ..dynamics import DP_A1, DP_A2, DP_D0, dynamic_array
from ..errors import ScaraError, ShapeError, check_positive
from ..kinematics import tool_motion_kernel
from ..params import ScaraParams
from .environment import NO_ENVIRONMENT, ForceSensor, Surface, contact_force_kernel, inside_after
from .plant import contact_acceleration, contact_rk4_step, tool_state

__all__ = ["simulate_contact", "ContactResult", "MEASURED_FORCE"]


if _compile.COMPILED:
    _t = _compile.numba_types
    _STEPPING = _t.NamedTuple((_t.float64, _t.int64, _t.float64, _t.float64, _t.float64), Stepping)
    _V, _M = _compile.VECTOR, _compile.MATRIX
    _LOOP_SIGNATURE = _t.void(_compile.LAW_TYPE, _t.UniTuple(_V, 2), _M, _STEPPING, _V, _compile.LAW_DATA_TYPE,
                              _t.NamedUniTuple(_M, 5, Series), _compile.INT_VECTOR, _V, _M, _t.UniTuple(_M, 2), _V,
                              _t.int64)
else:  # pragma: no cover - plain Python
    _LOOP_SIGNATURE = None


@_compile.kernel
def _sense(k, q, qd, a1, a2, d0, env, inside, offsets, force_out, sensed_out, work, row):
    """Sample ``k``'s contact force ``h_e`` (recorded in ``force_out[k]``) and the sensor's reading ``h_e +
    offsets[k]`` (``sensed_out[k]``, and ``work[row]`` when ``row >= 0``)."""
    px, py, pz, vx, vy, vz, J11, J12, J21, J22 = tool_state(q[0], q[1], q[2], (qd[0], qd[1], qd[2], qd[3]), a1, a2,
                                                            d0)
    f = contact_force_kernel(px, py, pz, vx, vy, vz, env, inside)
    for i in range(3):
        force_out[k, i] = -f[i]
        sensed_out[k, i] = -f[i] + offsets[k, i]
    if row >= 0:
        for i in range(3):
            work[row, i] = sensed_out[k, i]
        work[row, 3] = 0.0


@_compile.kernel
def _step_plant(k, n, q, qd, qdd, spare, tau, pc, h, substeps, dp, env, inside_out, info):
    """The plant from sample ``k`` to ``k + 1`` with ``tau`` held (``substeps`` RK4 steps of ``h``), the peg's state
    after each step in ``inside_out[k + 1]``; at the last sample only the acceleration. Returns False when the
    plant's inertia lost definiteness (``info`` then says so)."""
    a1, a2, d0 = dp[DP_A1], dp[DP_A2], dp[DP_D0]
    t = (tau[0], tau[1], tau[2], tau[3])
    inside = inside_out[k]
    if k == n - 1:
        u = (qd[0], qd[1], qd[2], qd[3])
        if env[0] > 0.0:
            a, c, f = contact_acceleration(q[0], q[1], q[2], u, t, pc, a1, a2, d0, env, inside)
        else:
            a, c = _plant_acceleration(math.cos(q[1]), math.sin(q[1]), u, t, pc)
        for i in range(4):
            qdd[i] = a[i]
        ok = c == OK
    else:
        ok = True
        for s in range(substeps):
            if env[0] > 0.0:
                c = contact_rk4_step(q, qd, t, pc, h, qdd if s == 0 else spare, a1, a2, d0, env, inside)
                px, py, pz, vx, vy, vz, J11, J12, J21, J22 = tool_state(q[0], q[1], q[2], (0.0, 0.0, 0.0, 0.0),
                                                                        a1, a2, d0)
                inside = inside_after(px, py, pz, env, inside)
            else:
                c = _rk4_step(q, qd, t, pc, h, qdd if s == 0 else spare)
            if c != OK:
                ok = False
                break
        inside_out[k + 1] = inside
    if not ok:
        info[0] = SINGULAR_INERTIA
        info[1] = k
    return ok


@_compile.kernel(inline="always")
def _contact_after_law(k, n, code, q, qd, qdd, spare, tau, sig, pc, h, substeps, limit, d3_mid, d3_half, plant_dp,
                       env, inside_out, q_out, qd_out, qdd_out, tau_out, sig_out, info):
    """The end of sample ``k`` of the contact loop, after the law returned ``code`` with the torque ``tau`` and
    the signals ``sig``: both recorded, the law's failure, a torque past ``limit``, the plant in contact to
    ``k + 1`` (:func:`_step_plant`), a divergence and the quill leaving its stroke checked (``info`` then says
    which, as :func:`scara._simulate.engine._after_law` does for the free plant). Returns True when the loop
    stops (a failure, or the last sample done); the one end of a sample of :func:`contact_loop_kernel` and of the
    interaction panel's program."""
    if _law_failed(k, code, tau, sig, limit, tau_out, sig_out, info):
        return True
    if not _step_plant(k, n, q, qd, qdd, spare, tau, pc, h, substeps, plant_dp, env, inside_out, info):
        return True
    for i in range(4):
        qdd_out[k, i] = qdd[i]
    if k == n - 1:
        return True
    return _state_failed(k, q, qd, limit, d3_mid, d3_half, q_out, qd_out, info)


@_compile.signature_kernel(_LOOP_SIGNATURE)
def contact_loop_kernel(law, start, ref, stepping, plant_dp, data, out, info, env, offsets, forces, inside_out,
                        force_row):
    """The loop of :func:`simulate_contact`: :func:`scara._simulate.closed_loop_kernel`'s, with the contact force
    sensed before each call of the law and the plant in contact between samples. ``env`` the
    :data:`~.environment.ENVIRONMENT` array, ``offsets`` (N, 3) the sensor's errors, ``forces = (h_e, reading)``
    (N, 3) each, ``inside_out`` (N,) the peg's state, ``force_row`` the scratch row of the reading (-1: none)."""
    q0, qd0 = start
    dt, substeps, limit = stepping.dt, stepping.substeps, stepping.limit
    d3_mid, d3_half = stepping.d3_mid, stepping.d3_half
    gains, model, state, work = data.gains, data.model, data.state, data.work
    q_out, qd_out, qdd_out, tau_out, sig_out = out.q, out.qd, out.qdd, out.tau, out.signals
    force_out, sensed_out = forces
    n = ref.shape[0]
    pc = _plant_constants(plant_dp)
    a1, a2, d0 = plant_dp[DP_A1], plant_dp[DP_A2], plant_dp[DP_D0]
    q, qd, qdd, spare, q_law, qd_law, r, tau, sig = _loop_arrays(ref.shape[1], sig_out.shape[1])
    _loop_start(q0, qd0, q, qd, n, info)
    h = dt / substeps
    for k in range(n):
        _before_law(k, q, qd, q_out, qd_out, q_law, qd_law, tau, sig)
        _sense(k, q, qd, a1, a2, d0, env, inside_out[k], offsets, force_out, sensed_out, work, force_row)
        for i in range(ref.shape[1]):
            r[i] = ref[k, i]
        code = law(k, k * dt, dt, q_law, qd_law, r, gains, model, state, work, sig, tau)
        if _contact_after_law(k, n, code, q, qd, qdd, spare, tau, sig, pc, h, substeps, limit, d3_mid, d3_half,
                              plant_dp, env, inside_out, q_out, qd_out, qdd_out, tau_out, sig_out, info):
            return


@dataclass
class ContactResult(SimulationResult):
    """A run in contact (:func:`simulate_contact`): a :class:`~scara._simulate.SimulationResult` with the
    contact force, the sensor's readings and the peg's state at every sample.

    ``force`` (N, 3) N: the true ``h_e(t_k)``, the force the end effector exerts on the environment (its z entry
    is negative while the tool presses down); ``measured_force`` (N, 3) N: what the sensor read (what the law
    saw); ``inside`` (N,) bool: the peg in the hole; ``surface``, ``sensor``: the run's environment and sensor.
    """

    force: np.ndarray | None = None
    measured_force: np.ndarray | None = None
    inside: np.ndarray | None = None
    surface: Surface | None = None
    sensor: ForceSensor | None = None

    def tool_velocity(self) -> np.ndarray:
        """``J qd`` (N, 3) m/s: the tool's velocity at each sample (:func:`~scara.kinematics.tool_motion_kernel`)."""
        out = np.empty((len(self.t), 12))
        tool_motion_kernel(np.ascontiguousarray(self.q), np.ascontiguousarray(self.qd),
                           np.ascontiguousarray(self.qdd), self.plant.a1, self.plant.a2, self.plant.d0, out)
        return out[:, 4:7]

    def energy(self) -> dict:
        """:meth:`SimulationResult.energy` with the environment: ``contact_work`` (J), the work the environment did
        on the tool, ``int -h_e . v dt`` (cumulative Simpson on the samples, as the friction's), and ``balance`` =
        ``total - total[0] - input_work + friction_work - contact_work`` (zero up to the integration error and
        the quadrature's: the contact power has a kink where contact begins or ends)."""
        from scipy.integrate import cumulative_simpson  # noqa: PLC0415

        out = super().energy()
        power = -np.einsum("ij,ij->i", self.force, self.tool_velocity())
        w = cumulative_simpson(power, x=self.t, initial=0.0) if len(self.t) > 2 else np.zeros_like(power)
        out["contact_work"] = w
        out["balance"] = out["balance"] - w
        return out

    def summary(self, window: float = 2.0) -> dict:
        """:meth:`SimulationResult.summary` and the contact's figures: those of
        :func:`~.steady.contact_transition` (``first_touch``, ``peak_force``, ``contact_losses``, ``bounced``,
        ``final_force``) and ``mean_force`` (3,) N, the mean ``h_e`` over the last ``window`` s."""
        from .steady import contact_transition  # noqa: PLC0415

        out = super().summary(window)
        last = self.t >= self.t[-1] - window + 1e-12
        out.update(contact_transition(self), mean_force=self.force[last].mean(axis=0))
        return out

    @property
    def normal_force(self) -> np.ndarray:
        """``-h_z`` (N,) N: how hard the tool presses down (0 out of contact)."""
        return -self.force[:, 2]

    @property
    def in_contact(self) -> np.ndarray:
        """(N,) bool: the environment pushes the tool at the sample."""
        return np.any(self.force != 0.0, axis=1)


def _force_row(controller) -> int:
    """The scratch row named :data:`MEASURED_FORCE` in ``controller.work_layout``, or -1."""
    layout = getattr(controller, "work_layout", None)
    names = getattr(layout, "names", ())
    return int(getattr(layout.offsets, MEASURED_FORCE)) if MEASURED_FORCE in names else -1


def simulate_contact(controller, traj=None, plant: ScaraParams | None = None, dt: float | None = None, *,
                     surface: Surface | None = None, sensor: ForceSensor | None = None, q0=None, qd0=None,
                     substeps: int = 10, duration: float | None = None, elbow: int | None = None,
                     limit: float = 1e6) -> ContactResult:
    """Run ``controller`` in closed loop on ``plant`` in contact with ``surface``, sensing with ``sensor``.

    The arguments are :func:`scara.simulate`'s, and: ``surface`` a :class:`~.environment.Surface` (None: free
    space, the run is :func:`scara.simulate`'s bit for bit); ``sensor`` a :class:`~.environment.ForceSensor`
    (default ``ForceSensor()``: 0.2 N noise, 0.5 N bias on ``f_z``; ``ForceSensor(noise=0, bias=(0, 0, 0))`` is an
    ideal one); ``substeps`` RK4 steps per sampling period, default 10 (a step of 0.1 ms: the stiff walls of a hole
    and the friction's ``tanh`` are then resolved; the tests check the run against finer steps).

    A controller's law receives the sensor's reading in its scratch row named :data:`MEASURED_FORCE` (see the
    module). A controller with a ``check_contact(surface, plant, dt)`` method has its gains checked against the
    surface first (:class:`~scara.UnstableError` when the sampled loop in contact would be unstable).

    Raises :class:`~scara.ScaraError` for inconsistent inputs or a surface the tool cannot reach, and
    :class:`~scara.UnstableError` when the run diverges.

    >>> from scara import TorqueController
    >>> r = simulate_contact(TorqueController(), duration=0.01, q0=[0, -1.5, 0.69, 0], surface=Surface())
    >>> bool(r.in_contact.any())
    False
    """
    plant = ScaraParams.resolve(plant)
    if surface is not None and not isinstance(surface, Surface):
        raise ScaraError(f"surface must be a Surface or None, got {type(surface).__name__}")
    sensor = ForceSensor() if sensor is None else sensor
    if not isinstance(sensor, ForceSensor):
        raise ScaraError(f"sensor must be a ForceSensor or None, got {type(sensor).__name__}")
    kind, dt, substeps = _check_run(controller, traj, dt, substeps)
    limit = check_positive(limit, "limit")
    if surface is not None:
        surface.check_reach(plant)
        check = getattr(controller, "check_contact", None)
        if check is not None:
            check(surface, plant, dt)
    ref, jref, x_d, xop, n = _references(kind, traj, None, duration, dt, plant)
    if n < 1:
        raise ShapeError(f"the reference holds {n} samples: a run needs at least one (N >= 1)")
    q0, qd0 = _start_state(q0, qd0, jref, xop, traj, plant, elbow)
    stepping = Stepping(float(dt), int(substeps), float(limit), 0.5 * (plant.d3_min + plant.d3_max),
                        0.5 * (plant.d3_max - plant.d3_min))
    env = NO_ENVIRONMENT.copy() if surface is None else surface.array()
    data, sig_out, names = law_arrays(controller, n)
    check_law_bounds(controller, data, len(names), (q0, qd0, ref[0]), stepping.dt)
    block = np.empty((7, n, 4))
    q_out, qd_out, qdd_out, tau_out, x, e, spare = block
    forces = np.zeros((2, n, 3))
    inside = np.zeros(n)
    info = np.zeros(3, dtype=np.int64)
    offsets = np.ascontiguousarray(sensor.offsets(n))
    law = _compiled_law(controller.law)
    if _compile.python_law(law) is law:
        loop = getattr(contact_loop_kernel, "py_func", contact_loop_kernel)
    else:
        loop = _compile.dispatcher_of(contact_loop_kernel)
    t0 = time.perf_counter()
    loop(law, (q0, qd0), ref, stepping, dynamic_array(plant), data, Series(q_out, qd_out, qdd_out, tau_out, sig_out),
         info, env, offsets, (forces[0], forces[1]), inside, _force_row(controller))
    elapsed = time.perf_counter() - t0
    out = (q_out, qd_out, qdd_out, tau_out, x, e, sig_out, spare)
    bad_signal = _first_bad_signal(sig_out, n if info[0] == OK else int(info[1]) + 1)
    if bad_signal is not None and (info[0] == OK or bad_signal[0] < info[1]):
        info[:] = NOT_FINITE, bad_signal[0], 4 + bad_signal[1]
    if info[0] != OK:
        _raise_failure(controller, info, dt, limit, out, plant, names)
    _pose_error(q_out, q_out if x_d is None else np.ascontiguousarray(x_d), plant.a1, plant.a2, plant.d0, x, e)
    if x_d is None:
        spare[:] = x
        x_d = spare
        e[:] = 0.0
    x_d = _owned(x_d, (traj,), into=spare)
    return ContactResult(t=np.arange(n) * dt, q=q_out, qd=qd_out, qdd=qdd_out, tau=tau_out, x=x, x_d=x_d, e=e,
                         reference=_owned(ref, (traj,)), reference_kind=kind, q_d=None if jref is None else
                         _owned(jref[:, :4], (traj,)),
                         signals={nm: np.ascontiguousarray(sig_out[:, i]) for i, nm in enumerate(names)},
                         controller=getattr(controller, "name", type(controller).__name__), plant=plant, dt=dt,
                         substeps=substeps, elapsed=elapsed, extra={"final_state": data.state},
                         force=forces[0], measured_force=forces[1], inside=inside > 0.0, surface=surface,
                         sensor=sensor)
