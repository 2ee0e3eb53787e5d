"""scara: modelling, planning and control of a 4-axis SCARA arm, the package behind the course book.

The public names are listed in DESIGN.md; every function takes an optional parameter object ``p``
(``None`` means :class:`ScaraParams()`, the robot of SPEC section 1 without payload).
"""
from .errors import NonFiniteError, ScaraError, ShapeError, UnreachableError, UnstableError
from .params import ScaraParams
from .kinematics import (
    check_reachable, dh_table, fkine, ikine, is_reachable, jacobian, jacobian_dot, link_frames, pose,
)
from .manipulability import (
    Ellipsoid, force_ellipsoid, manipulability, singular_radii, velocity_ellipsoid, workspace_map,
)

__version__ = "0.1.0"
