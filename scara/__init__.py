"""scara: modelling, planning and control of a 4-axis SCARA arm, the package behind the course book.

The public names, with the first line of each docstring, are listed on the book's page *The scara package:
how it is organised*. Every function of the robot model takes an optional parameter object, ``p`` (``base`` in
``params_from_pi`` and ``payload_from_pi``); ``None`` means ``ScaraParams()``, the robot of the introduction
without payload.
"""
from .errors import NonFiniteError, ScaraError, ShapeError, UnreachableError, UnstableError
from .params import ScaraParams
from .kinematics import (
    check_reachable, dh_table, fkine, ikine, is_reachable, jacobian, jacobian_dot, link_frames, pose,
)
from .manipulability import (
    Ellipsoid, force_ellipsoid, manipulability, singular_radii, velocity_ellipsoid, workspace_map,
)
from .trajectory import (
    Arc, Line, Trajectory, Trapezoidal, Waypoint, plan_path, reference_plan, reference_trajectory, trapezoidal,
)
from .clik import ClikResult, TransposeStability, clik, clik2, second_order_gains, transpose_stability
from .dynamics import (
    PI_NAMES, coriolis, dynamic_array, dynamic_parameters, forward_dynamics, friction, gravity, inertia,
    inverse_dynamics, kinetic_energy, params_from_pi, payload_from_pi, potential_energy, regressor, total_energy,
    torque_breakdown,
)
from .simulate import (
    Controller, PDGravityController, SimulationResult, TorqueController, control_law, ikine_reference,
    joint_setpoint, simulate,
)

__version__ = "0.1.0"
from .control import AdaptiveController, OperationalSpaceController, RobustController
