"""Peg-in-hole along z (chapter 7): the peg above a hole of the surface, off-centre within or beyond the
clearance, inserted to the bottom by parallel force/position control (:class:`~.laws.ParallelController`), and
the frames an animation of it needs.

The run: the reference lowers the peg from ``lift`` above the surface to the surface's plane in ``move`` s, rests
``pause`` s, then slides it to the hole's axis in ``move`` s and rests there. Meanwhile the force loop asks for
``f_d`` along z: where the surface bears the peg it presses with ``f_d``; above the hole nothing bears it, the
integral lowers the reference at ``K_I |f_d|`` and the peg goes down until the bottom bears it. A peg within the
clearance drops in at once; one beyond lands on the surface and slides (against friction) until its axis is
within the clearance of the hole's, where it drops in.
"""
from __future__ import annotations

import numpy as np

from ..errors import ScaraError, as_array, check_count, check_positive
from ..kinematics import ikine
from ..params import ScaraParams
from .engine import simulate_contact
from .environment import ForceSensor, Hole, Surface
from .laws import ParallelController
from .steady import _Reference, approach_reference

__all__ = ["peg_in_hole", "insertion_summary", "peg_frames"]


def _concatenate(parts, dt):
    x = np.vstack([p.x[:-1] for p in parts[:-1]] + [parts[-1].x])
    xd = np.vstack([p.xd[:-1] for p in parts[:-1]] + [parts[-1].xd])
    xdd = np.vstack([p.xdd[:-1] for p in parts[:-1]] + [parts[-1].xdd])
    return _Reference(np.arange(len(x)) * dt, x, xd, xdd, dt)


def peg_in_hole(offset=(1e-3, 0.0), surface: Surface | None = None, controller=None,
                sensor: ForceSensor | None = None, lift: float = 0.01, move: float = 1.0, pause: float = 0.5,
                rest: float = 3.0, plant: ScaraParams | None = None, dt: float = 1e-3, substeps: int = 10):
    """Insert the peg, starting ``lift`` m (> 0) above the surface and ``offset`` (2,) m off the hole's axis
    (module docstring): the :class:`~.engine.ContactResult` of the run.

    ``surface`` default ``Surface(hole=Hole())`` (hole at (0.4, 0.1) m, clearance 0.5 mm, depth 30 mm);
    ``controller`` default ``ParallelController()`` (``f_d = -10`` N); the elbow is -1 and ``phi`` that of
    ``theta4 = 0`` at the start. ``move``, ``pause``, ``rest`` in s (whole numbers of ``dt``).
    """
    s = Surface(hole=Hole()) if surface is None else surface
    if not isinstance(s, Surface) or s.hole is None:
        raise ScaraError(f"surface must be a Surface with a Hole, got {s!r:.120}")
    off = as_array(offset, "offset", (2,))
    lift = check_positive(lift, "lift")
    c = np.asarray(s.hole.centre)
    p0 = np.array([c[0] + off[0], c[1] + off[1], s.height + lift, 0.0])
    q0 = ikine(p0, plant, elbow=-1)
    p0[3] = q0[0] + q0[1]
    down = p0.copy()
    down[2] = s.height
    axis = down.copy()
    axis[:2] = c
    ref = _concatenate([approach_reference(p0, down, move, pause, dt), approach_reference(down, axis, move, rest,
                                                                                              dt)], dt)
    ctrl = ParallelController() if controller is None else controller
    return simulate_contact(ctrl, ref, plant, dt, surface=s, sensor=sensor, substeps=substeps, elbow=-1)


def insertion_summary(result) -> dict:
    """The figures of a peg-in-hole run: ``landed_on_surface`` (the surface bore the peg before it went in),
    ``entered`` (s, when the peg went into the hole; NaN if never), ``bottom_reached`` (s, the first sample the
    bottom bears it; NaN if never), ``depth_reached`` (m, below the surface, at the end), ``peak_lateral_force`` (N,
    the largest horizontal force while inside: the walls', and the bottom's friction when the peg slides on it),
    ``final_force`` (3,) N: ``h_e`` at the end."""
    s = getattr(result, "surface", None)
    if s is None or s.hole is None:
        raise ScaraError("insertion_summary needs a run of simulate_contact on a Surface with a Hole")
    inside = np.asarray(result.inside)
    z = result.x[:, 2]
    bottom = s.height - s.hole.depth
    k_in = int(np.argmax(inside)) if inside.any() else None
    on_bottom = inside & (z < bottom) & (result.force[:, 2] < 0)
    lateral = np.hypot(result.force[:, 0], result.force[:, 1])
    return {
        "landed_on_surface": bool(np.any(result.in_contact[:k_in] if k_in is not None else result.in_contact)),
        "entered": float(result.t[k_in]) if k_in is not None else float("nan"),
        "bottom_reached": float(result.t[int(np.argmax(on_bottom))]) if on_bottom.any() else float("nan"),
        "depth_reached": float(s.height - z[-1]),
        "peak_lateral_force": float(lateral[inside].max()) if inside.any() else 0.0,
        "final_force": result.force[-1].copy(),
    }


def peg_frames(result, every: int = 20, peg_radius: float = 5e-3, peg_length: float = 0.05) -> dict:
    """What an animation of a peg-in-hole run needs, one frame every ``every`` samples: ``t`` (M,) s, ``tip``
    (M, 3) m (the peg's end), ``top`` (M, 3) (its other end, ``peg_length`` above), ``force`` (M, 3) N (``h_e``),
    ``inside`` (M,) bool; and the scene: ``centre`` (2,), ``hole_radius`` (``peg_radius`` + clearance),
    ``peg_radius``, ``height``, ``bottom`` (m)."""
    s = getattr(result, "surface", None)
    if s is None or s.hole is None:
        raise ScaraError("peg_frames needs a run of simulate_contact on a Surface with a Hole")
    every = check_count(every, "every", 1, 1_000_000, "samples per frame")
    peg_radius = check_positive(peg_radius, "peg_radius")
    peg_length = check_positive(peg_length, "peg_length")
    k = np.arange(0, len(result.t), every)
    tip = result.x[k, :3].copy()
    top = tip.copy()
    top[:, 2] += peg_length
    return {"t": result.t[k].copy(), "tip": tip, "top": top, "force": result.force[k].copy(),
            "inside": np.asarray(result.inside)[k].copy(), "centre": np.array(s.hole.centre),
            "hole_radius": peg_radius + s.hole.clearance, "peg_radius": peg_radius, "height": s.height,
            "bottom": s.height - s.hole.depth}
