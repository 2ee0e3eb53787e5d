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
import json
import os
from pathlib import Path

# Two workers share two cores: a BLAS of two threads in each would run four threads on two cores, and OpenBLAS's
# threads spin while they wait for work, so a loaded worker slows the other to a crawl. One thread each (and in
# every kernel and process the tests start, which inherit the setting).
for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import numpy  # noqa: E402, F401 - loaded here, so that the limit below reaches its BLAS
import pytest  # noqa: E402
import scipy.linalg  # noqa: E402, F401 - and scipy's own
from hypothesis import HealthCheck, settings  # noqa: E402
from threadpoolctl import threadpool_limits  # noqa: E402

import _largest  # noqa: E402

threadpool_limits(limits=1, user_api="blas")

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
# JupyterLab (tests/book/test_jupyterlab*.py): one server on the take-home copies of the chapters per worker
# --------------------------------------------------------------------------------------------------
@pytest.fixture(scope="session")
def jupyterlab_url():
    """The URL of one JupyterLab server per worker, shared by every JupyterLab test (each opens its own page and
    shuts its kernels down); the requesting module has checked that JupyterLab and the build are there
    (``jupyterlab_driver`` sits in tests/book, on ``sys.path`` once a module there is imported)."""
    import jupyterlab_driver

    with jupyterlab_driver.jupyterlab_server() as url:
        yield url


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


# --------------------------------------------------------------------------------------------------
# how the two workers share the tests out (pytest-xdist: units of work, in collection order)
# --------------------------------------------------------------------------------------------------
#: test files whose tests the workers share out one by one: each test is long beside its module's fixtures (a
#: server, a browser), so two workers may as well run them side by side. Every other file is one unit, run whole on
#: one worker (its tests share costly fixtures, or, for a notebook under nbval, its cells run in order in one kernel).
SPREAD = ("tests/book/test_browser.py", "tests/book/test_jupyterlab.py", "tests/book/test_page_panels.py",
          "tests/book/test_lab_copy.py", "tests/book/test_frames_browser.py", "tests/book/test_jupyterlab_reading.py",
          "tests/test_identification.py")
#: the seconds each test took in a recent run (``.ci/test_groups.py --durations``): the longest units go first, so
#: that no worker is left alone with a long one at the end. A test it does not know counts as a short one; a stale
#: number changes only the order, never what runs.
DURATIONS = Path(__file__).with_name("durations.json")
#: what a test the durations do not know is taken to last (s)
UNKNOWN = 0.05


def _unit(nodeid: str) -> str:
    """The unit of work of a test: its file, or the test itself in a file of :data:`SPREAD`."""
    path = nodeid.split("::", 1)[0]
    return nodeid if path in SPREAD else path


@pytest.hookimpl(tryfirst=True)
def pytest_collection_modifyitems(config, items):
    """The units of work (:func:`_unit`) sorted so that the files whose longest unit is longest come first (the
    long units start early, the short ones fill the end); a spread file's tests stay together, longest first (a
    worker keeps its module's fixtures between them). The sort is stable: equal weights keep the collection's
    order, and so does every file's own order of tests."""
    seconds = json.loads(DURATIONS.read_text()) if DURATIONS.is_file() else {}
    units: dict[str, list] = {}
    for item in items:
        units.setdefault(_unit(item.nodeid), []).append(item)
    weight = {u: sum(seconds.get(i.nodeid, UNKNOWN) for i in its) for u, its in units.items()}
    longest: dict[str, float] = {}
    for u in units:
        longest[u.split("::", 1)[0]] = max(longest.get(u.split("::", 1)[0], 0.0), weight[u])
    order = sorted(units, key=lambda u: (-longest[u.split("::", 1)[0]], u.split("::", 1)[0], -weight[u]))
    items[:] = [i for u in order for i in units[u]]


def pytest_xdist_make_scheduler(config, log):
    """pytest-xdist's scheduling by scope, with :func:`_unit` as the scope and the collection's order kept (the
    order :func:`pytest_collection_modifyitems` made): each worker is sent whole units."""
    from xdist.scheduler import LoadScopeScheduling

    class Units(LoadScopeScheduling):
        def _split_scope(self, nodeid: str) -> str:
            return _unit(nodeid)

    config.option.loadscopereorder = False
    return Units(config, log)
