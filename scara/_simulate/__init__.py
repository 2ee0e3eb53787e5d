"""The closed-loop simulation engine: a discrete-time controller at ``dt`` (zero-order hold) driving the
continuous-time plant ``B qdd + C qd + F qd + g = tau`` (the model of chapter 5), integrated by fixed-step RK4.

    result = simulate(controller, traj, plant, dt=1e-3, substeps=1)

At every sample ``t_k = k dt`` the controller reads the measured ``q(t_k), qd(t_k)`` and its reference row
``r_k`` and returns a torque ``tau_k``; ``tau_k`` is held constant while the plant (the true robot, e.g.
``ScaraParams().with_payload(5.0)``) is integrated from ``t_k`` to ``t_{k+1}`` by ``substeps`` RK4 steps.

The controller interface
------------------------
A controller is any object (subclass :class:`Controller` for the defaults) with

``law``
    A compiled step kernel with exactly the signature :data:`LAW_SIGNATURE`, made with the decorator
    :func:`control_law`::

        @control_law
        def law(k, t, dt, q, qd, ref, gains, model, state, work, signals, tau):
            ...            # write tau[0:4] and signals[:]; update state[:] in place
            return OK      # OK (0) = fine; any other integer stops the run with an UnstableError

    ``k`` (int) sample index, ``t = k dt`` (s), ``dt`` (s) sampling period; ``q``, ``qd`` (4,) measured
    state (read only); ``ref`` (12,) reference row ``[pos(4), vel(4), acc(4)]``; ``gains`` (n_g,) and
    ``model`` (n_m,) constant float arrays; ``state`` (n_s,) persistent memory (integrators, estimates),
    carried from one sample to the next; ``work`` (work_rows, 4) scratch (4x4 matrices are
    ``work[0:4]``...), not kept between samples; ``signals`` (len(signal_names),) the row of internal signals
    recorded at this sample; ``tau`` (4,) the torque to apply. The law must not allocate arrays: it calls the
    compiled kernels of :mod:`scara.dynamics` and :mod:`scara.kinematics` with ``model`` and its scratch.

``reference_kind``
    ``"joint"``: ``ref = [q_d, qd_d, qdd_d]`` from ``clik2(traj)`` (or ``joint_reference=``);
    ``"operational"``: ``ref = [x_d, xd_d, xdd_d]`` from the trajectory; ``"none"``: zeros (open loop).
``gains_array()``, ``model_array()``, ``initial_state()``
    The flat float arrays passed as ``gains``, ``model`` (by default ``dynamic_array`` of the controller's
    own parameter object ``self.model``, which does not know the payload) and the initial ``state``. A
    controller declares its gains once with :class:`scara._compile.ArrayLayout`: the law reads the offsets
    it gives, ``gains_array()`` returns its ``pack(...)`` (see :data:`PD_GAINS`).
``signal_names``, ``work_rows``, ``name``
    Names of the recorded internal signals (they become ``result.signals[name]`` and attributes of the
    result), rows of the scratch array, and the label used in tables and legends.

The engine's loop :func:`closed_loop_kernel` takes the law as a first-class function argument of type
``numba.types.FunctionType(LAW_SIGNATURE)``; because both the loop and the laws are compiled for explicit
signatures, numba's on-disk cache works for every controller (a dispatcher-typed argument would recompile the
loop in every new process). Both are compiled (or loaded from the cache) when first used, by :func:`simulate`,
not at import. Without numba (``SCARA_NO_NUMBA=1``) the same loop and laws run as plain Python.

The package, one job per module (imports flow down this list): :mod:`.interface` (the law signature, the
decorator, :class:`Controller`, the status codes), :mod:`.plant` (the plant's acceleration and RK4 step),
:mod:`.controllers` (the two controllers of chapter 5), :mod:`.reference` (the references a controller
receives), :mod:`.result` (:class:`SimulationResult`) and :mod:`.engine` (the compiled loop and
:func:`simulate`).

:class:`PDGravityController` is the worked example; the package page of the book (book/package.ipynb, section
Writing your own controller) walks through it.
"""
from __future__ import annotations

from .controllers import PD_GAINS, TORQUE_GAINS, PDGravityController, TorqueController, pd_gravity_law, torque_law
from .engine import closed_loop_kernel, simulate
from .interface import (
    DIVERGED, JOINT_LIMIT, LAW_FAILED, LAW_SIGNATURE, OK, SINGULAR_INERTIA, Controller, _compiled_law, control_law,
)
from .plant import PlantConstants, _plant_acceleration, _plant_constants, _rk4_step
from .reference import (
    _clik2_reference, _joint_reference_array, _operational_from_joint, ikine_reference, joint_setpoint,
)
from .result import SimulationResult

__all__ = [
    "LAW_SIGNATURE", "control_law", "Controller", "PDGravityController", "TorqueController",
    "closed_loop_kernel", "simulate", "SimulationResult", "ikine_reference", "joint_setpoint",
]
