"""Discrete-time controllers of chapter 6 for the arm carrying a payload their models do not know: the two
classic joint-space laws (PD control with gravity compensation and inverse dynamics, or computed torque, control),
independent-joint (decentralised) PID control with actuator saturation and anti-windup, robust control and
Slotine-Li adaptive control in joint space (all three tracking the second-order CLIK's joint reference), and
inverse dynamics control in the operational space with or without integral action.

Each is a :class:`scara._simulate.Controller` whose compiled law runs inside :func:`scara.simulate`; built
with no arguments it carries the book's tuned gains and believes in ``ScaraParams()`` (no payload)::

    from scara import AdaptiveController, ScaraParams, reference_trajectory, simulate
    res = simulate(AdaptiveController(), reference_trajectory(), ScaraParams().with_payload(5.0))
    res.payload_estimate[-1]          # about 5 kg

:func:`control_summary` gives the figures of the chapter's comparison table.
"""
from .._lazy import public_names as _public_names

#: every name of the package is loaded from its sub-module on first use
_EAGER = ()
_LAZY = ("_common", "adaptive", "classic", "independent", "operational", "robust")

__all__, __getattr__, __dir__ = _public_names(__name__, _EAGER, _LAZY, ("adaptive", "classic", "independent", "operational", "robust"))
