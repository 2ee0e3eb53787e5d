"""Discrete-time controllers of chapter 6 for the arm carrying a payload their models do not know:
independent-joint (decentralised) PID control with actuator saturation and anti-windup, robust control and
Slotine-Li adaptive control in joint space (all three tracking the second-order CLIK's joint reference), and
inverse dynamics control in the operational space with or without integral action.

Each is a :class:`scara.simulate.Controller` whose compiled law runs inside :func:`scara.simulate`; built
with no arguments it carries the book's tuned gains and believes in ``ScaraParams()`` (no payload)::

    from scara import AdaptiveController, ScaraParams, reference_trajectory, simulate
    res = simulate(AdaptiveController(), reference_trajectory(), ScaraParams().with_payload(5.0))
    res.payload_estimate[-1]          # about 5 kg

:func:`control_summary` gives the figures of the chapter's comparison table.
"""
from .._lazy import lazy_names as _lazy_names

#: the names of the package, each loaded from its sub-module on first use
_NAMES = {
    **dict.fromkeys(("ERROR_BOUND", "FAILURE_CAUSES", "MAX_ERROR", "SINGULAR_JACOBIAN", "TAU_MAX", "TORQUE_BOUND",
                     "BoundedController", "chattering", "control_summary", "law_cost", "positive_gains",
                     "replay_law"), "_common"),
    **dict.fromkeys(("AdaptiveController", "adaptation_gains"), "adaptive"),
    **dict.fromkeys(("B_BAR", "IndependentJointController", "OMEGA", "independent_gains", "joint_inertia_spread",
                     "nominal_inertia"), "independent"),
    "OperationalSpaceController": "operational",
    **dict.fromkeys(("B_HAT", "RobustController", "design_inertia_estimate", "inertia_eigenvalues",
                     "inertia_uncertainty", "lyapunov_matrix", "rho_bound", "sliding_matrix", "sliding_weight"),
                    "robust"),
}
__getattr__, __dir__ = _lazy_names(__name__, _NAMES, ("adaptive", "independent", "operational", "robust"))

__all__ = [
    "IndependentJointController", "independent_gains", "nominal_inertia", "joint_inertia_spread", "B_BAR", "OMEGA",
    "RobustController", "AdaptiveController", "OperationalSpaceController", "BoundedController",
    "control_summary", "chattering", "law_cost", "replay_law", "adaptation_gains", "sliding_weight",
    "lyapunov_matrix", "sliding_matrix", "inertia_uncertainty", "inertia_eigenvalues", "design_inertia_estimate", "rho_bound", "B_HAT",
    "TAU_MAX", "MAX_ERROR", "FAILURE_CAUSES", "TORQUE_BOUND", "ERROR_BOUND", "SINGULAR_JACOBIAN",
]
