"""scara: modelling, planning and control of a 4-axis SCARA arm, the package behind the course book.

The public names, with the first line of each docstring, are listed on the book's page *The scara package:
how it is organised*. Every function of the robot model takes an optional parameter object, ``p`` (``base`` in
``params_from_pi`` and ``payload_from_pi``); ``None`` means ``ScaraParams()``, the robot of the introduction
without payload.

``import scara`` loads only the first chapters' modules (errors, parameters, kinematics, manipulability); the
names of the later chapters (``reference_trajectory``, ``clik``, ``inertia``, ``simulate``,
``RobustController``...) load their module the first time they are used, and no kernel is compiled before it
is first called. Each public name is listed once, in the ``__all__`` of the module that defines it.
"""
from ._lazy import public_names as _public_names

__version__ = "0.1.0"

#: the modules imported with the package, and those loaded when one of their names is first used
_EAGER = ("errors", "params", "kinematics", "_manipulability")
_LAZY = ("trajectory", "_clik", "dynamics", "_simulate", "control", "interaction")
#: sub-modules that are attributes of the package under their own name (``scara.dynamics``)
_SUBMODULES = ("errors", "params", "kinematics", "trajectory", "dynamics", "control", "interaction", "identification",
               "export")

__all__, __getattr__, __dir__ = _public_names(__name__, _EAGER, _LAZY, _SUBMODULES)
