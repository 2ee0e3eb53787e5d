"""The results of the CLIK: :class:`ClikResult` (the joint trajectory of a run, its pose, error and the figures
of the chapter's table) and :class:`TransposeStability` (the discrete-time margin (4.12) of the transpose), and
:func:`_fail`, the :class:`~scara.errors.UnstableError` of a run that stopped."""
from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field

import numpy as np

from ..errors import ScaraError, UnstableError, check_number
from .kernels import _bound_component
from .records import _CAUSES, COMPONENTS, STATUS_ERROR_BOUND, STATUS_SINGULAR

__all__ = ["ClikResult", "TransposeStability"]


def _settle_text(settle: float) -> str:
    """The refusal of a settling time not shorter than the run, as a template with the field ``run_length``."""
    return f"settle = {settle:g} s must lie in [0, {{run_length:g}}) s, the run's length"


@dataclass
class ClikResult:
    """The joint trajectory a CLIK run produced, with its pose and error.

    Every array is the result's own: none shares memory with the trajectory or the options it was given.

    Attributes
    ----------
    t : (N,) s
    q, qd : (N, 4)
        Joint positions (rad, rad, m, rad) and velocities; ``q[k+1] = q[k] + dt qd[k]`` (4.2).
    qdd : (N, 4) or None
        Joint accelerations (second-order CLIK (4.16) only).
    x : (N, 4)
        End-effector pose ``x_e = k(q)`` (1.5) reached, ``[px, py, pz, phi]``.
    e : (N, 4)
        ``x_d - x_e`` (4.3). For the pseudo-inverse the relaxed component is uncontrolled: its entry is the drift.
    w : (N,)
        Manipulability ``a1 a2 |sin theta2|`` (m^2) (2.4).
    x_d : (N, 4)
        The reference that was tracked.
    method : str
        ``"inverse"``, ``"transpose"``, ``"pseudoinverse"`` or ``"second_order"``.
    kept : (4,) bool
        Components under control (all but the relaxed one for the pseudo-inverse).
    dt : float
        Sampling period (s).
    gains : dict
        The gains and options used (``K`` or ``K_P``/``K_D``, damping, null-space gain, ...).
    elapsed : float
        Seconds spent in the compiled loop.
    """

    t: np.ndarray
    q: np.ndarray
    qd: np.ndarray
    qdd: np.ndarray | None
    x: np.ndarray
    e: np.ndarray
    w: np.ndarray
    x_d: np.ndarray
    method: str
    kept: np.ndarray
    dt: float
    gains: dict = field(default_factory=dict)
    elapsed: float = 0.0

    @property
    def position_error(self) -> np.ndarray:
        """Norm of the position error over the kept position components, (N,) in m."""
        cols = [i for i in range(3) if self.kept[i]]
        return np.sqrt(np.sum(self.e[:, cols] ** 2, axis=1)) if cols else np.zeros(len(self.t))

    @property
    def orientation_error(self) -> np.ndarray:
        """``|phi_d - phi_e|`` (N,) in rad (zeros if phi is the relaxed component)."""
        return np.abs(self.e[:, 3]) if self.kept[3] else np.zeros(len(self.t))

    def summary(self, settle: float = 0.1) -> dict:
        """The figures of the chapter's comparison table, in SI units.

        Error figures skip the first ``settle`` seconds (the start-up transient, where a given ``q0`` may
        leave a large initial error); position figures use the kept position components only. Manipulability
        figures cover the whole run.

        Returns a dict with ``method``, ``max_position_error`` and ``rms_position_error`` (m),
        ``max_orientation_error`` (rad), ``min_manipulability`` and ``mean_manipulability`` (m^2), ``elapsed``
        (s). Raises :class:`ScaraError` if ``settle`` is not a number, negative or not shorter than the run.
        """
        length = self.t[-1] - self.t[0]
        settle = check_number(settle, "settle", unit="s")
        if not 0.0 <= settle < length:
            raise ScaraError(_settle_text(settle).format(run_length=length))
        after = self.t >= self.t[0] + settle - 1e-12
        ep = self.position_error[after]
        return {
            "method": self.method,
            "max_position_error": float(ep.max()),
            "rms_position_error": float(np.sqrt(np.mean(ep**2))),
            "max_orientation_error": float(self.orientation_error[after].max()),
            "min_manipulability": float(self.w.min()),
            "mean_manipulability": float(self.w.mean()),
            "elapsed": float(self.elapsed),
        }

    def __repr__(self):
        return (f"ClikResult(method={self.method!r}, N={len(self.t)}, dt={self.dt:g} s, "
                f"max |e_p| = {self.position_error.max():.3g} m, elapsed = {self.elapsed * 1e3:.2f} ms)")


@dataclass(frozen=True)
class TransposeStability:
    """Discrete-time stability of the Jacobian-transpose CLIK along a reference (4.12).

    ``mu`` (N,) is the largest eigenvalue of ``J_A J_A^T K`` (1/s) at the reference's configurations, ``limit``
    is ``2 / dt``; ``scale_limit = limit / mu_max`` is the factor by which ``K`` may be multiplied before Euler's
    rule goes unstable (> 1: stable). ``t_worst`` is where ``mu`` peaks.
    """

    t: np.ndarray
    mu: np.ndarray
    mu_max: float
    t_worst: float
    limit: float
    scale_limit: float

    @property
    def stable(self) -> bool:
        return self.scale_limit > 1.0


def _divergence_text(what: str, status: int, component: str = "") -> str:
    """The message of a loop that stopped with ``status`` (a ``STATUS_*`` code), as a template with the fields
    ``t_fail`` (s), ``step_fail``, and ``e_fail`` (the error of ``component`` past the bound) or ``theta2_fail``
    (rad) and ``w_fail`` (m^2, a singular Jacobian)."""
    extra = ""
    if status == STATUS_ERROR_BOUND:
        extra = f" ({component} error {{e_fail:.4g}})"
    elif status == STATUS_SINGULAR:
        extra = " (theta2 = {theta2_fail:.6g} rad, manipulability {w_fail:.3g} m^2)"
    return f"{what} diverged at t = {{t_fail:.4f}} s (step {{step_fail:.0f}}): {_CAUSES[status]}{extra}"


def _fail(info, result: ClikResult, what: str) -> UnstableError:
    """The :class:`~scara.errors.UnstableError` of a loop that stopped with ``info = [status, step]``: the message
    (:func:`_divergence_text`) gives the time and the cause; ``exc.result`` holds the run up to that step,
    ``exc.time`` and ``exc.cause``."""
    status, k = int(info[0]), int(info[1])
    cause = _CAUSES[status]
    i = _bound_component(result.e, k, np.ascontiguousarray(result.kept, float))
    exc = UnstableError(_divergence_text(what, status, COMPONENTS[i]).format(
        t_fail=result.t[k], step_fail=k, e_fail=result.e[k, i], theta2_fail=result.q[k, 1], w_fail=result.w[k]))
    cut = slice(0, k + 1)
    exc.result = dataclasses.replace(
        result, t=result.t[cut], q=result.q[cut], qd=result.qd[cut],
        qdd=None if result.qdd is None else result.qdd[cut], x=result.x[cut], e=result.e[cut], w=result.w[cut],
        x_d=result.x_d[cut])
    exc.time = float(result.t[k])
    exc.cause = cause
    return exc
