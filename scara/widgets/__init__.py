"""ipywidgets panels for tuning live in Jupyter: the only part of the package that imports ipywidgets.

One sub-module per chapter; their panel builders are re-exported here. Each panel shows the package's error
message in place of the plot when a setting is invalid, never a traceback.
"""
from .kinematics import inverse_kinematics_panel, kinematics_panel
from .manipulability import manipulability_panel
from .trajectory import waypoint_editor
from .clik import clik_panel
from .dynamics import dynamics_panel
from .control import control_panel
