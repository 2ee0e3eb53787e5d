"""Closed-loop inverse kinematics (CLIK): turn an operational-space trajectory into joint trajectories.

Four algorithms (chapter 4; Siciliano et al. 2009, section 3.7), all discretised with
Euler's rule at the trajectory's sampling period ``dt``:

* **Jacobian inverse** (4.4): ``qd = J_A^-1 (xd_d + K e)``. The error obeys ``ed = -K e``. Near a
  singularity the inverse can be replaced by the damped least-squares inverse
  ``J^* = J^T (J J^T + lambda^2 I)^-1`` (damped least squares (4.15); Siciliano et al. 2009, section 3.5), with
  a constant damping or one that grows only when the manipulability falls below a threshold.
* **Jacobian transpose** (4.8): ``qd = J_A^T K e``. No inversion; the error converges for a constant
  reference and lags a moving one.
* **Pseudo-inverse** with one operational component relaxed (x by default): the arm becomes functionally
  redundant, ``qd = J_r^+ (xd_r + K_r e_r) + (I - J_r^+ J_r) qd_0`` (4.13) with ``qd_0 = k_0 grad w_0(q)`` (4.14)
  climbing a dexterity measure (``w_0 = sin^2 theta2`` by default, or the manipulability ``w``).
* **Second order** (4.16; Siciliano et al. 2009, section 3.7.4, with the analytic Jacobian):
  ``qdd = J_A^-1 (xdd_d + K_D ed + K_P e - Jd_A qd)``, giving the joint positions, velocities and
  accelerations the control chapter tracks.

The loops run in compiled kernels (see :mod:`scara._compile`) with the closed-form kinematics of
:mod:`scara.kinematics` inside (its planar building blocks, inlined); nothing is allocated per step. Every run
checks its settings first (positive, finite gains; options the method uses, no others; the discrete-time
stability limits derived below; a reachable reference) and stops with an :class:`~scara.errors.UnstableError`
giving the time and the cause if it diverges anyway. A run uses the trajectory's own parameters
(``traj.params``) and elbow (``traj.elbow``) when it carries them, and its result owns every array it holds.

Discrete-time stability (Euler, sampling period ``dt``). Linearising one step,
``e_{k+1} = e_k + (x_d,k+1 - x_d,k) - J_A (q_{k+1} - q_k)``:

* inverse (4.6): ``e_{k+1} = (I - dt K) e_k + O(dt^2)``, stable iff ``0 < dt K_i < 2`` for every component;
* transpose: ``e_{k+1} = (I - dt J_A J_A^T K) e_k + ...``. ``J_A J_A^T K`` is similar to the symmetric
  ``K^1/2 J_A J_A^T K^1/2`` (and to ``J_A^T K J_A``, the matrix of the joint-space iteration), so its
  eigenvalues ``mu_i(q)`` are real and positive and the step is stable iff ``dt mu_max(q) < 2`` at every
  configuration met (4.12). :func:`transpose_stability` evaluates ``mu_max`` along the reference;
* second order, per component with ``a = dt K_D``, ``b = dt^2 K_P``: the characteristic polynomial (4.19)
  ``z^2 - (2 - a) z + (1 - a + b)`` has both roots inside the unit circle iff ``b < a`` and ``2 a - b < 4``
  (Jury's test); with ``K_D = 2 omega``, ``K_P = omega^2`` both poles sit at ``z = 1 - omega dt``.

The package, one job per module (imports flow down this list): :mod:`.records` (the constants, the named
records the loops take and their packers, the ``STATUS_*`` codes), :mod:`.kernels` (the compiled loops and
solves, and the check kernels behind the refusals), :mod:`.result` (:class:`ClikResult`, :class:`TransposeStability`), :mod:`.checks` (the input and
option checks), :mod:`.stability` (the stability limits (4.6), (4.12), (4.19) checked before a run) and
:mod:`.api` (:func:`clik`, :func:`clik2`, :func:`transpose_stability`, :func:`second_order_gains`,
:func:`start_configuration`, :func:`dexterity`).
"""
from __future__ import annotations

from .api import clik, clik2, dexterity, second_order_gains, start_configuration, transpose_stability
from .kernels import (_clik1_kernel, _clik2_kernel, _solve_exact, _solve_kept, _transpose_check_kernel,
                      _transpose_rate_kernel)
from .records import COMPONENTS, MAX_DAMPING_REACH, METHODS, OBJECTIVES, SEED_K
from .result import ClikResult, TransposeStability

__all__ = [
    "METHODS",
    "COMPONENTS",
    "SEED_K",
    "ClikResult",
    "TransposeStability",
    "clik",
    "clik2",
    "start_configuration",
    "transpose_stability",
    "second_order_gains",
    "dexterity",
    "MAX_DAMPING_REACH",
]
