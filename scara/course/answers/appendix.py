"""The computations answering the appendix's exercises (see :mod:`scara.course.answers`)."""
from __future__ import annotations

import json
from functools import lru_cache
from pathlib import Path

import numpy as np

import scara
from scara import ScaraParams, inertia, jacobian
from scara.course.answers import solves
from scara.errors import ScaraError


@lru_cache(maxsize=1)
def _benchmarks() -> dict:
    """The recorded benchmark results the appendix's tables and figures show."""
    path = Path(scara.__file__).resolve().parents[1] / "benchmarks" / "results.json"
    return json.loads(path.read_text())


@solves("ex-ver-bound")
def pinocchio_bound(calls: int) -> dict:
    """A lower bound for the Pinocchio closed loop: ``calls`` aba calls per step at the per-call median."""
    results = _benchmarks()
    n_steps = int(results["closed_loop"]["_samples"]) - 1
    call_us = float(results["per_call"]["forward_dynamics"]["pinocchio"]["us"])
    measured = float(results["closed_loop"]["pinocchio"]["seconds"])
    bound = calls * call_us * 1e-6 * n_steps
    if not 0 < bound < measured:
        raise ScaraError(f"exercise ex-ver-bound: the bound {bound:.2f} s is not below the measured {measured:.2f} s")
    return {"bound_s": bound, "share_pct": 100 * bound / measured, "call_us": call_us, "n_steps": n_steps,
            "measured_s": measured}


def _rotor_coupling(p: ScaraParams, q) -> np.ndarray:
    """The package's rotor coupling Delta B at ``q``: B with rotors, less B without, less the diagonal kr^2 Im."""
    k_r, I_m = np.asarray(p.k_r), np.asarray(p.I_m)
    return inertia(q, p) - inertia(q, p.replace(I_m=(0.0, 0.0, 0.0, 0.0))) - np.diag(k_r ** 2 * I_m)


@solves("ex-ver-coupling")
def coupling_force(qdd1: float, qdd2: float) -> dict:
    """The force row 3 of the rotor coupling asks of the quill for joint accelerations ``qdd1``, ``qdd2``."""
    p = ScaraParams()
    dB = _rotor_coupling(p, np.array([0.2, 1.3, 0.4, -0.5]))
    force = float(dB[2] @ np.array([qdd1, qdd2, 0.0, 0.0]))
    return {"force_N": force, "k3Im3": float(p.k_r[2] * p.I_m[2])}


@solves("ex-ver-signs")
def signs(qd1: float) -> dict:
    """The yaw rate phi_dot of the book's J_A at q = 0 for qd = [qd1, 0, 0, 0], and the libraries' omega_z."""
    phidot = float((jacobian(np.zeros(4), ScaraParams()) @ np.array([qd1, 0.0, 0.0, 0.0]))[3])
    return {"phidot": phidot, "omega_z": -phidot}


@solves("ex-ver-com")
def misplaced_com(m_l1: float) -> dict:
    """The error of B11 when link 1's centre of mass is put at l1 from the wrong origin (a1 + l1 from the axis)."""
    if m_l1 <= 0:
        raise ScaraError(f"exercise ex-ver-com: link 1's mass must be positive, got {m_l1}")
    p = ScaraParams().replace(m_l1=m_l1)
    dB = m_l1 * ((p.a1 + p.l1) ** 2 - p.l1 ** 2)
    return {"dB": dB, "a1": p.a1, "l1": p.l1}
