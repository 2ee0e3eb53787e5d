"""Plotly figure builders for the book: data in, ``go.Figure`` out; no robotics is computed here beyond
calls into the math modules. Importing this package registers the book's offline HTML renderer.

One sub-module per chapter; their public builders are re-exported here. :mod:`scara.plots.layout` lays out
every figure on the page; :mod:`scara.plots._common` holds the conventions the chapters share.
"""
from ._common import AXIS_COLOURS, JOINT_COLOURS, PALETTE, publish, slider, use_book_renderer
from .layout import base_layout

use_book_renderer()
from .kinematics import (
    arm_figure, determinant_figure, inverse_kinematics_figure, inverse_kinematics_slider_figure, joint_slider_figure,
    top_view_arm,
)
from .manipulability import (
    base_turn_figure, duality_figure, ellipse_slider_figure, major_axis_angle, manipulability_map_figure,
    reference_ellipses_figure, workspace_ellipses_figure,
)
from .trajectory import (
    anticipation_slider_figure, corner_figure, joint_profiles_figure, joint_space_figure, joint_space_series,
    path_figure, profiles_figure, timing_law_figure, top_view_figure,
)
from .verification import rotor_coupling_figure, speed_figure
from .clik import (
    clik_error_figure, clik_joints_figure, convergence_figure, damping_figure, drift_figure, error_components_figure,
    gain_slider_figure, gain_steps_figure, manipulability_figure, relaxed_figure, second_order_figure,
    transpose_stability_figure,
)
from .dynamics import (
    energy_figure, inertia_figure, inertia_slider_figure, payload_slider_figure, payload_torque_figure,
    torque_share_figure, torque_terms_figure, window_max,
)
from .control import (
    boundary_layer_slider_figure, error_norm_figure, joint_error_figure, joint_motion_figure, operational_error_figure,
    figure_slider, payload_estimate_figure, payload_sweep_figure, robust_term_figure, saturation_figure,
    steady_state_figure, torque_figure, tuning_figure,
)
from .identification import error_size_figure, excitation_figure, validation_figure
from .course import course_figure
from .frames import frames_figure
from .animation import clik_animation, control_animation, course_animation, frame_indices, trajectory_animation
from .interaction import contact_force_figure, peg_animation, stiffness_slider_figure
