"""Interaction with the environment (chapter 7; Siciliano et al., ch. 9): a compliant surface with friction and a
hole for a peg, a wrist force sensor, the closed loop in contact and the interaction laws.

    from scara.interaction import ForceController, Surface, simulate_contact
    res = simulate_contact(ForceController(), traj, surface=Surface())
    res.force[-1]            # h_e (N): about (0, 0, -10.5): f_d = (0, 0, -10) less the sensor's 0.5 N bias

Modules: :mod:`.environment` (the surface, the hole, the sensor, the contact force), :mod:`.plant` (the plant in
contact), :mod:`.engine` (:func:`simulate_contact`), :mod:`.stability` (the sampled loop along z),
:mod:`.laws` (the five controllers), :mod:`.steady` (steady states and contact transitions), :mod:`.peg`
(peg-in-hole), :mod:`.compare` (the comparison of the laws, the sweeps of the chapter's figures).
"""
from .._lazy import public_names as _public_names

_EAGER = ()
_LAZY = ("environment", "engine", "laws", "steady", "peg", "compare")

__all__, __getattr__, __dir__ = _public_names(__name__, _EAGER, _LAZY, ())
