"""ipywidgets panels for tuning live in Jupyter: the only part of the package that imports ipywidgets.

One sub-module per chapter; their panel builders are re-exported here. Each panel shows the package's error
message in place of the plot when a setting is invalid, never a traceback; a number typed beside a slider
outside its range is refused the same way, never clamped. Every builder takes ``keep=True``: re-running its cell
starts from the last accepted settings of the previous panel of its kind. ``control_panel`` also runs the
reader's own controllers (``controllers={label: class or factory}``) and the waypoint editor's plan
(``control_panel(editor)``).
"""
from .kinematics import inverse_kinematics_panel, kinematics_panel
from .manipulability import manipulability_panel
from .trajectory import waypoint_editor
from .clik import clik_panel
from .dynamics import dynamics_panel
from .control import control_panel
from .interaction import interaction_panel
