"""The closed-loop simulation engine: a discrete-time controller at ``dt`` (zero-order hold) driving the
continuous-time plant ``B qdd + C qd + F qd + g = tau`` (the model of chapter 5), integrated by fixed-step RK4.

    result = simulate(controller, traj, plant, dt=1e-3, substeps=1)

At every sample ``t_k = k dt`` the controller reads the measured ``q(t_k), qd(t_k)`` and its reference row
``r_k`` and returns a torque ``tau_k``; ``tau_k`` is held constant while the plant (the true robot, e.g.
``ScaraParams().with_payload(5.0)``) is integrated from ``t_k`` to ``t_{k+1}`` by ``substeps`` RK4 steps.

The controller interface
------------------------
A controller is any object (subclass :class:`Controller` for the defaults) that follows the contract written,
as a numbered list, in the docstring of :class:`Controller` (``help(scara.Controller)``; read it first): a
compiled ``law`` with the signature :data:`LAW_SIGNATURE` (made with :func:`control_law`), its
``reference_kind``, and five arrays each declared once by a :class:`scara._compile.ArrayLayout`: the constant
``gains`` and ``model``, the ``state`` carried between samples, the scratch ``work`` rows and the recorded
``signals`` (whose entry names are ``signal_names``). One function, :func:`~.interface.law_arrays`, prepares
those arrays for the engine and for any replay of a law (:func:`scara.control.replay_law`), and a trial call
on bounds-checked copies (:func:`~.interface.check_law_bounds`) refuses a law that would read or write past
them before the compiled run.

The engine's loop :func:`closed_loop_kernel` takes the law as a first-class function argument of type
``numba.types.FunctionType(LAW_SIGNATURE)``; because both the loop and the laws are compiled for explicit
signatures, numba's on-disk cache works for every controller (a dispatcher-typed argument would recompile the
loop in every new process). Both are compiled (or loaded from the cache) when first used, by :func:`simulate`,
not at import. Without numba (``SCARA_NO_NUMBA=1``) the same loop and laws run as plain Python.

The package, one job per module (imports flow down this list): :mod:`.interface` (the contract :class:`Controller`,
the preparation and check of a law's arrays, the status codes), :mod:`.plant` (the plant's acceleration and RK4 step),
:mod:`.controllers` (the two controllers of chapter 5), :mod:`.setpoints` (the references a controller
receives), :mod:`.result` (:class:`SimulationResult`) and :mod:`.engine` (the compiled loop and
:func:`simulate`).

:class:`PDGravityController` is the worked example; the package page of the book (book/package.ipynb, section
Writing your own controller) walks through it.
"""
from __future__ import annotations

from .controllers import PD_GAINS, TORQUE_GAINS, PDGravityController, TorqueController, pd_gravity_law, torque_law
from .engine import closed_loop_kernel, simulate
from .interface import (
    DIVERGED, JOINT_LIMIT, LAW_FAILED, LAW_SIGNATURE, NOT_FINITE, OK, SINGULAR_INERTIA, Controller, _compiled_law,
    check_law_bounds, control_law, law_arrays,
)
from .plant import PlantConstants, _plant_acceleration, _plant_constants, _rk4_step
from .setpoints import (
    _clik2_reference, _joint_reference_array, _operational_from_joint, ikine_reference, joint_setpoint,
)
from .result import SimulationResult

__all__ = [
    "LAW_SIGNATURE", "control_law", "Controller", "PDGravityController", "TorqueController",
    "closed_loop_kernel", "simulate", "SimulationResult", "ikine_reference", "joint_setpoint",
]
