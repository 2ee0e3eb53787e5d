"""scara: modelling, planning and control of a 4-axis SCARA arm, the package behind the course book.

The public names, with the first line of each docstring, are listed on the book's page *The scara package:
how it is organised*. Every function of the robot model takes an optional parameter object, ``p`` (``base`` in
``params_from_pi`` and ``payload_from_pi``); ``None`` means ``ScaraParams()``, the robot of the introduction
without payload.

``import scara`` loads only the first chapters' modules (errors, parameters, kinematics, manipulability); the
names of the later chapters (``reference_trajectory``, ``clik``, ``inertia``, ``simulate``,
``RobustController``...) load their module the first time they are used, and no kernel is compiled before it
is first called.
"""
from .errors import NonFiniteError, ScaraError, ShapeError, UnreachableError, UnstableError
from .params import ScaraParams
from .kinematics import (
    check_reachable, dh_table, fkine, ikine, is_reachable, jacobian, jacobian_dot, link_frames, pose,
)
from .manipulability import (
    Ellipsoid, force_ellipsoid, manipulability, singular_radii, velocity_ellipsoid, workspace_map,
)
from ._lazy import lazy_names as _lazy_names

__version__ = "0.1.0"

#: the names loaded on first use, and the sub-module of each
_LAZY = {
    **dict.fromkeys(("Arc", "JointTrajectory", "Line", "Trajectory", "Trapezoidal", "Waypoint", "cubic",
                     "joint_trajectory", "plan_path", "quintic", "reference_plan", "reference_trajectory",
                     "trapezoidal"), "trajectory"),
    **dict.fromkeys(("ClikResult", "TransposeStability", "clik", "clik2", "second_order_gains",
                     "transpose_stability"), "clik"),
    **dict.fromkeys(("PI_NAMES", "coriolis", "dynamic_array", "dynamic_parameters", "forward_dynamics", "friction",
                     "gravity", "inertia", "inverse_dynamics", "kinetic_energy", "params_from_pi", "payload_from_pi",
                     "potential_energy", "regressor", "total_energy", "torque_breakdown"), "dynamics"),
    **dict.fromkeys(("Controller", "PDGravityController", "SimulationResult", "TorqueController", "control_law",
                     "ikine_reference", "joint_setpoint", "simulate"), "simulate"),
    **dict.fromkeys(("AdaptiveController", "IndependentJointController", "OperationalSpaceController",
                     "RobustController"), "control"),
}
#: sub-modules that are attributes of the package under their own name (``scara.dynamics``)
_SUBMODULES = ("errors", "params", "kinematics", "trajectory", "dynamics", "control")

__all__ = [
    "NonFiniteError", "ScaraError", "ShapeError", "UnreachableError", "UnstableError", "ScaraParams",
    "check_reachable", "dh_table", "fkine", "ikine", "is_reachable", "jacobian", "jacobian_dot", "link_frames",
    "pose", "Ellipsoid", "force_ellipsoid", "manipulability", "singular_radii", "velocity_ellipsoid",
    "workspace_map", *_LAZY, *_SUBMODULES,
]

# ``scara.clik``, ``scara.simulate`` and ``scara.manipulability`` are functions (each defined in the sub-module
# of the same name), also after ``import scara.clik``
__getattr__, __dir__ = _lazy_names(__name__, _LAZY, _SUBMODULES, shadowed=("clik", "simulate", "manipulability"))
