"""The benchmarks' modules (``benchmarks/agreement.py``, ``libraries.py``, ``run.py``) for the agreement tests, each
imported only after the optional extras it needs (``requirements-bench.txt``) import; otherwise the test is
skipped with the reason."""
from __future__ import annotations

import importlib
import os
import sys

import pytest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
BENCH = os.path.join(ROOT, "benchmarks")


def bench_module(name: str, *extras: str):
    """``benchmarks/<name>.py`` as a module, after ``pytest.importorskip`` of every module in ``extras``."""
    for extra in extras:
        pytest.importorskip(extra, reason=f"needs the optional extras: pip install -r requirements-bench.txt ({extra})")
    if BENCH not in sys.path:
        sys.path.insert(0, BENCH)
    return importlib.import_module(name)


def rotor_free_pd_gravity_run(no_rotors):
    """The reference run of the closed-loop comparisons, rotors off (``I_m = no_rotors``): PD + gravity
    compensation on the nominal model, the plant carrying 5 kg, ``scara.simulate``'s run of the 70 s reference.
    Returns ``(traj, plant, model, ctrl, ref, ours)``, ``ref`` the joint reference (N, 12) and ``ours`` the run."""
    from scara import ScaraParams
    from scara._simulate import PDGravityController, ikine_reference, simulate
    from scara.trajectory import reference_trajectory

    traj = reference_trajectory()
    plant = ScaraParams().with_payload(5.0).replace(I_m=no_rotors)
    model = ScaraParams().replace(I_m=no_rotors)
    ctrl = PDGravityController(model=model)
    ref = ikine_reference(traj, plant)
    return traj, plant, model, ctrl, ref, simulate(ctrl, traj, plant, joint_reference=ref)
