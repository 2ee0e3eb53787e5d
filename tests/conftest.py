"""Shared test settings and fixtures of the package's tests (tests/*.py; tests/book and tests/agreement inherit the
settings).

- A hypothesis profile with no deadline (the first call of a compiled kernel compiles it) and a fixed seed of
  examples per test, so CI runs are repeatable in time.
- The chapter 3 reference trajectory and the chapter 6 runs (the comparison table's four and the
  independent-joint controller's), computed once per session (session-scoped fixtures)
  and shared by test_trajectory_*.py and test_control_*.py.
- ``L`` for tests/agreement (the benchmarks' ``libraries`` module).
- At the end of the run, the largest difference met by each independent check (``_largest.record``).

Helper modules (``_largest``, ``_trajectory_shared``, ``_control_shared`` here; ``_figure_rules``,
``jupyterlab_driver`` in tests/book) are imported by their plain names: the test folders have no ``__init__.py``,
so pytest (import mode ``prepend``) puts each test file's folder on ``sys.path`` before importing it.
"""
import os

import pytest
from hypothesis import HealthCheck, settings

import _largest

settings.register_profile(
    "scara",
    max_examples=int(os.environ.get("SCARA_HYPOTHESIS_EXAMPLES", "200")),
    deadline=None,
    suppress_health_check=[HealthCheck.too_slow],
    derandomize=True,
)
settings.load_profile("scara")


# --------------------------------------------------------------------------------------------------
# chapter 3: the reference trajectory (test_trajectory_*.py)
# --------------------------------------------------------------------------------------------------
@pytest.fixture(scope="session")
def ref():
    from scara import reference_trajectory  # here, not at the top: the book's tests need not import the chapters

    return reference_trajectory()


# --------------------------------------------------------------------------------------------------
# chapter 6: the reference, its joint reference and the four runs of the comparison table (test_control_*.py)
# --------------------------------------------------------------------------------------------------
@pytest.fixture(scope="session")
def traj(ref):
    """The same reference as chapter 3's (no test modifies it): computed once for both chapters."""
    return ref


@pytest.fixture(scope="session")
def jref(traj):
    from scara import clik2

    return clik2(traj)


@pytest.fixture(scope="session")
def runs(traj, jref):
    """The four runs of the chapter's comparison table, payload 5 kg."""
    from scara import AdaptiveController, OperationalSpaceController, RobustController, simulate

    from _control_shared import P5

    ctrls = {"robust": RobustController(), "adaptive": AdaptiveController(),
             "operational": OperationalSpaceController(), "operational_noint": OperationalSpaceController(integral=False)}
    out = {}
    for name, c in ctrls.items():
        out[name] = (c, simulate(c, traj, P5, joint_reference=jref if c.reference_kind == "joint" else None))
    return out


@pytest.fixture(scope="session")
def independent_runs(traj, jref):
    """The independent-joint runs of chapter 6, payload 5 kg: PID and PD with the stated bounds, and PID with the
    quill's force bounded at 155 N (5 % above the 147 N its weight and the payload's need), with and without
    anti-windup."""
    from scara import IndependentJointController, simulate

    from _control_shared import P5

    tight = (200.0, 200.0, 155.0, 50.0)
    ctrls = {"pid": IndependentJointController(), "pd": IndependentJointController(integral=False),
             "saturated": IndependentJointController(tau_max=tight),
             "windup": IndependentJointController(tau_max=tight, anti_windup=False)}
    return {name: (c, simulate(c, traj, P5, joint_reference=jref)) for name, c in ctrls.items()}


# --------------------------------------------------------------------------------------------------
# tests/agreement: the benchmarks' libraries module (one conftest only: a second conftest.py in a tree without
# packages clashes with this one when the doctests collect it)
# --------------------------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def L(A):
    """The benchmarks' ``libraries`` module, after the requesting module's own ``A`` fixture has checked that the
    extras it needs import (``_bench`` sits in tests/agreement, on ``sys.path`` once a module there is imported)."""
    from _bench import bench_module

    return bench_module("libraries")


# --------------------------------------------------------------------------------------------------
# the closing note: the largest difference met by each independent check
# --------------------------------------------------------------------------------------------------
def pytest_terminal_summary(terminalreporter):
    if not _largest.LARGEST:
        return
    terminalreporter.section("largest difference of each independent check")
    for module in sorted(_largest.LARGEST):
        for name, err in _largest.LARGEST[module].items():
            terminalreporter.write_line(f"{module}: {name}: {err:.2e}")
