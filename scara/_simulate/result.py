"""The result of a closed-loop run (:class:`SimulationResult`): the recorded series, the errors, the energy
bookkeeping and the figures of a chapter's table."""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .._compile import kernel
from ..dynamics import kinetic_energy, potential_energy
from ..errors import ScaraError, check_positive
from ..kinematics import pose_of
from ..params import ScaraParams

__all__ = ["SimulationResult"]


class MissingSignalError(ScaraError, AttributeError):
    """A run has no such attribute or signal (a helper of one kind of controller given another's run): both a
    :class:`~scara.ScaraError` and the ``AttributeError`` that ``getattr`` and ``hasattr`` expect."""


@kernel
def _pose_error(q, x_d, a1, a2, d0, x, e):
    """``x[k] = k(q[k])`` (:func:`~scara.kinematics.pose_of`) and ``e[k] = x_d[k] - x[k]`` for every sample."""
    for k in range(q.shape[0]):
        x[k, 0], x[k, 1], x[k, 2], x[k, 3] = pose_of(q[k, 0], q[k, 1], q[k, 2], q[k, 3], a1, a2, d0)
        for i in range(4):
            e[k, i] = x_d[k, i] - x[k, i]


@dataclass
class SimulationResult:
    """A closed-loop run: samples at ``t`` (N,) of the measured state, the applied torque and the errors.

    Attributes: ``t`` (N,) s; ``q, qd, qdd, tau`` (N, 4) (``qdd`` is the plant's acceleration just after the
    controller's update, ``tau`` the torque held over ``[t_k, t_k + dt)``); ``x`` (N, 4) = ``pose(q)``;
    ``x_d`` (N, 4) desired pose; ``e = x_d - x`` (N, 4); ``reference`` (N, 12) what the controller received;
    ``q_d`` (N, 4) the joint reference (None for operational controllers); ``signals`` dict of the
    controller's internal signals (N,), also readable as attributes (``result.payload_estimate``).
    """

    t: np.ndarray
    q: np.ndarray
    qd: np.ndarray
    qdd: np.ndarray
    tau: np.ndarray
    x: np.ndarray
    x_d: np.ndarray
    e: np.ndarray
    reference: np.ndarray
    reference_kind: str
    q_d: np.ndarray | None
    signals: dict
    controller: str
    plant: ScaraParams
    dt: float
    substeps: int
    elapsed: float = 0.0
    extra: dict = field(default_factory=dict)

    def __getattr__(self, name):
        signals = self.__dict__.get("signals", {})
        if name in signals:
            return signals[name]
        raise MissingSignalError(f"{type(self).__name__} has no attribute or signal {name!r}: the run of "
                                 f"{self.__dict__.get('controller', '?')!r} records the signals {sorted(signals)}")

    @property
    def joint_error(self) -> np.ndarray:
        """``q_d - q`` (N, 4) for joint-space controllers."""
        if self.q_d is None:
            raise ScaraError("an operational-space run has no joint reference; use .e")
        return self.q_d - self.q

    def energy(self) -> dict:
        """Energy bookkeeping of the plant (J), each (N,): ``kinetic``, ``potential``, ``total``,
        ``input_work`` (exact under zero-order hold: ``sum tau_k^T (q_{k+1} - q_k)``), ``friction_work``
        (``int qd^T F qd dt``, cumulative Simpson on the samples) and ``balance`` =
        ``total - total[0] - input_work + friction_work`` (zero up to integration error)."""
        from scipy.integrate import cumulative_simpson  # noqa: PLC0415

        T = kinetic_energy(self.q, self.qd, self.plant)
        U = potential_energy(self.q, self.plant)
        E = T + U
        dq = np.diff(self.q, axis=0)
        w_in = np.concatenate([[0.0], np.cumsum(np.einsum("ij,ij->i", self.tau[:-1], dq))])
        power = np.einsum("ij,j,ij->i", self.qd, self.plant.F, self.qd)
        w_f = cumulative_simpson(power, x=self.t, initial=0.0) if len(self.t) > 2 else np.zeros_like(power)
        out = dict(kinetic=T, potential=U, total=E, input_work=w_in, friction_work=w_f,
                   balance=E - E[0] - w_in + w_f)
        for name, v in out.items():
            if not np.all(np.isfinite(v)):
                k = int(np.argmax(~np.isfinite(v)))
                raise ScaraError(f"the {name} energy is not finite at t = {self.t[k]:g} s: the plant (payload "
                                 f"m_L = {self.plant.m_L:g} kg) or the state (|qd| up to {np.abs(self.qd).max():g}) "
                                 f"is too large for floating point")
        return out

    def summary(self, window: float = 2.0) -> dict:
        """Figures for a chapter's table: per component of ``e = x_d - x`` (m, m, m, rad), each (4,), its
        maximum absolute value ``max_abs_error_components``, RMS ``rms_error_components`` and steady-state value
        ``steady_state_error_components`` (mean over the last ``window`` seconds); the largest absolute torques
        ``max_abs_tau``; and ``elapsed``, the seconds the compiled loop took. ``window`` (s) must be finite and
        ``> 0``."""
        window = check_positive(window, "window")
        last = self.t >= self.t[-1] - window + 1e-12
        return {
            "controller": self.controller,
            "max_abs_error_components": np.abs(self.e).max(axis=0),
            "rms_error_components": np.sqrt(np.mean(self.e ** 2, axis=0)),
            "steady_state_error_components": self.e[last].mean(axis=0),
            "max_abs_tau": np.abs(self.tau).max(axis=0),
            "elapsed": self.elapsed,
        }
