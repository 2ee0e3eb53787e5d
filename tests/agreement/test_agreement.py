"""Agreement of scara with Peter Corke's Robotics Toolbox for Python and Pinocchio (the verification appendix,
section The same robot in two other libraries); the exported files and MuJoCo are
tests/agreement/test_exported_files.py.

The comparisons need the optional extras (``pip install -r requirements-bench.txt``); without them those
tests are skipped with the reason, so the main CI stays lean. The check of the stored
``benchmarks/results.json`` (which the book's verification appendix reads) runs everywhere.

Tolerance: 1e-10 absolute in SI units for every rotor-free comparison. Entries are O(1) to O(10^2)
(torques up to ~150 N), so double-precision round-off is ~1e-13; 1e-10 leaves room for summation order and
nothing else: any modelling difference (a lever arm, a sign, a missing inertia term) is >= 1e-3.
"""
from __future__ import annotations

import json
import math
import os

import numpy as np
import pytest

import scara
from scara import ScaraParams
from scara import dynamics as dyn

from _bench import BENCH, bench_module, rotor_free_pd_gravity_run

TOL = 1e-10


@pytest.fixture(scope="module")
def A():
    """The benchmarks' agreement module, after checking that both libraries import."""
    return bench_module("agreement", "roboticstoolbox", "pinocchio")


PAYLOADS = [0.0, 5.0]


# ------------------------------------------------------------------------------------------------------
# kinematics
# ------------------------------------------------------------------------------------------------------
def test_kinematics_agree(A):
    res = A.kinematics_agreement(n=200, seed=3)
    for lib, e in res.items():
        for what, err in e.items():
            assert err < TOL, f"{lib} {what}: {err:.3e}"


def test_base_transform_is_the_books(A, L):
    """Both models hang frame 0 at d0 with z0 down (chapter 1, (eq-kin-base)), and gravity points down the base z."""
    p = ScaraParams()
    A0 = np.array([[1, 0, 0, 0], [0, -1, 0, 0], [0, 0, -1, p.d0], [0, 0, 0, 1.0]])
    robot = L.toolbox_robot(p)
    assert np.array_equal(robot.base.A, A0)
    assert np.allclose(robot.gravity, [0, 0, -p.g0])
    model, _ = L.pinocchio_model(p)
    assert np.array_equal(model.jointPlacements[1].homogeneous, A0)
    assert np.allclose(model.gravity.linear, [0, 0, -p.g0])
    # the toolbox's DH table is chapter 1's (a, alpha, d, theta), joint variables filled in
    q = np.array([0.3, -1.1, 0.2, 0.7])
    for link, row in zip(robot.links, scara.dh_table(q, p)):
        a, alpha, d, theta = row
        assert (link.a, link.alpha) == (a, alpha)
        assert (link.d if link.isrevolute else link.theta) == (d if link.isrevolute else theta)


def test_jacobian_sign_convention_by_motion(A):
    """phi turns about the downward z0: a positive qd1 turns the tool clockwise seen from above, so the
    libraries' angular rate about the (upward) base z is -phi_dot, and J_A[3] = -J_geo[5]."""
    lib = A.library("pinocchio")
    q = np.array([0.4, -0.9, 0.3, 0.2])
    Jg = lib.jacob0(q)
    assert Jg[5, 0] == pytest.approx(-1.0, abs=TOL)
    assert scara.jacobian(q)[3, 0] == 1.0


# ------------------------------------------------------------------------------------------------------
# rigid-body dynamics, rotors off
# ------------------------------------------------------------------------------------------------------
@pytest.mark.parametrize("m_L", PAYLOADS)
def test_rigid_body_dynamics_agree_without_rotors(A, m_L):
    res = A.dynamics_agreement(n=120, seed=5, p=ScaraParams().with_payload(m_L))
    assert set(res) == {"toolbox", "pinocchio", "numpy"}
    for lib, e in res.items():
        for what, err in e.items():
            assert err < TOL, f"{lib} {what} (m_L = {m_L}): {err:.3e}"


def test_horizontal_moments_of_inertia_do_not_matter(A, L):
    """Only the vertical moment enters (all angular velocities are vertical): other tensors, same model."""
    import pinocchio as pin

    p = ScaraParams().with_payload(5.0)
    q, qd, qdd = A.random_states(30, seed=2, p=p)
    tb_a, tb_b = L.toolbox_robot(p, horizontal=0.5), L.toolbox_robot(p, horizontal=3.0)
    (ma, da), (mb, db) = L.pinocchio_model(p, horizontal=0.5), L.pinocchio_model(p, horizontal=3.0)
    for qk, qdk, qddk in zip(q, qd, qdd):
        assert np.max(np.abs(tb_a.rne(qk, qdk, qddk) - tb_b.rne(qk, qdk, qddk))) < TOL
        assert np.max(np.abs(pin.rnea(ma, da, qk, qdk, qddk) - pin.rnea(mb, db, qk, qdk, qddk))) < TOL


def test_skew_symmetry_holds_for_library_coriolis(A):
    """Bdot - 2C is skew-symmetric for the toolbox's C too (Bdot by central differences along qd)."""
    lib = A.library("toolbox", rotors=False)
    q, qd, _ = A.random_states(10, seed=9)
    h = 1e-6
    for qk, qdk in zip(q, qd):
        Bdot = (lib.inertia(qk + h * qdk) - lib.inertia(qk - h * qdk)) / (2 * h)
        N = Bdot - 2 * lib.coriolis(qk, qdk)
        assert np.max(np.abs(N + N.T)) < 1e-7  # central-difference error ~ h^2 * |B'''| ~ 1e-11, round-off ~ 1e-9


# ------------------------------------------------------------------------------------------------------
# rotors on
# ------------------------------------------------------------------------------------------------------
def test_libraries_model_rotors_as_diagonal_reflected_inertia(A, L):
    p = ScaraParams()
    q, _, _ = A.random_states(20, seed=4)
    k2Im = np.asarray(p.k_r) ** 2 * np.asarray(p.I_m)
    for name in A.LIBRARIES:
        on, off = A.library(name, p, rotors=True), A.library(name, p, rotors=False)
        for qk in q:
            assert np.max(np.abs(on.inertia(qk) - off.inertia(qk) - np.diag(k2Im))) < TOL, name


def test_rotor_coupling_from_rotor_kinetic_energy(A):
    """Independent derivation: rotor i spins at a_i . qd with a_1 = [k1,0,0,0], a_2 = [1,k2,0,0],
    a_3 = [1,1,k3,0], a_4 = [1,1,0,k4] (chapter 5, (eq-dyn-rotors)), so its share of B is I_mi a_i a_i^T."""
    p = ScaraParams(k_r=(3.0, 7.0, 40.0, 11.0), I_m=(0.02, 0.03, 0.004, 0.002))  # distinct numbers
    k, Im = p.k_r, p.I_m
    a = np.array([[k[0], 0, 0, 0], [1, k[1], 0, 0], [1, 1, k[2], 0], [1, 1, 0, k[3]]])
    B_rotor = sum(Im[i] * np.outer(a[i], a[i]) for i in range(4))
    expected = B_rotor - np.diag(np.asarray(k) ** 2 * np.asarray(Im))
    assert np.max(np.abs(A.rotor_coupling(p) - expected)) < 1e-15
    # and it is exactly what scara's B has beyond the rotor-free B and the reflected diagonal
    q = np.array([0.2, 1.3, 0.4, -0.5])
    Bfull = dyn.inertia(q, p)
    Bbare = dyn.inertia(q, p.replace(I_m=(0.0, 0.0, 0.0, 0.0)))
    assert np.max(np.abs(Bfull - Bbare - B_rotor)) < TOL


@pytest.mark.parametrize("m_L", PAYLOADS)
def test_rotor_difference_is_exactly_the_coupling(A, m_L):
    res = A.rotor_agreement(n=100, seed=8, p=ScaraParams().with_payload(m_L))
    for lib, e in res.items():
        for what in ("inertia_minus_coupling", "coriolis", "gravity", "torque_minus_coupling",
                     "forward_dynamics_lib_model"):
            assert e[what] < TOL, f"{lib} {what}: {e[what]:.3e}"
        # the coupling is real: its largest entry k_r3 I_m3 = 0.25 kg m
        assert e["inertia_difference"] == pytest.approx(0.25, abs=TOL)


def test_numpy_twin_is_the_full_model(A, L):
    p = ScaraParams().with_payload(5.0)
    r = L.NumpyRobot(p)
    q, qd, qdd = A.random_states(100, seed=21, p=p)
    for qk, qdk, qddk in zip(q, qd, qdd):
        tau = dyn.inverse_dynamics(qk, qdk, qddk, p)
        assert np.max(np.abs(r.rne(qk, qdk, qddk) - tau)) < TOL
        assert np.max(np.abs(r.accel(qk, qdk, tau) - qddk)) < 1e-9  # through a solve: cond(B) ~ 1e2


def test_rotor_effect_along_reference_motion(A):
    from scara.trajectory import reference_trajectory

    traj = reference_trajectory()
    res = A.rotor_effect(traj)
    assert res["samples"] == len(traj.t)
    for lib in A.LIBRARIES:
        assert res[f"{lib}_torque_minus_coupling"] < TOL
    # the coupling moves joint 3 by k_r3 I_m3 (qdd1 + qdd2): nonzero wherever the arm turns
    assert all(c > 0 for c in res["max_coupling_torque"])
    assert all(0 < r < 1 for r in res["ratio_max"])


# ------------------------------------------------------------------------------------------------------
# the benchmark loops do the same work as ours
# ------------------------------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def run(A):
    import run as run_module

    return run_module


def test_clik_loops_reproduce_scara_clik(run):
    from scara.trajectory import reference_trajectory

    traj = reference_trajectory()
    from scara._clik import clik

    ours = clik(traj, "inverse")
    steps = 400
    for cls in (run.NumpyCalls, run.PinocchioCalls, run.ToolboxCalls):
        q = run.clik_loop(cls(ScaraParams()), traj.x, traj.xd, ours.q[0], traj.dt, run.SEED_K, steps)
        assert np.max(np.abs(q - ours.q[:steps])) < TOL, cls.name


def test_closed_loops_reproduce_scara_simulate(run, A):
    traj, plant, model, ctrl, ref, ours = rotor_free_pd_gravity_run(A.NO_ROTORS)
    steps = 300
    for cls in (run.NumpyCalls, run.PinocchioCalls, run.ToolboxCalls):
        q = run.closed_loop(cls(plant, rotors=False), cls(model, rotors=False), ref, ref[0, :4], ref[0, 4:8],
                            traj.dt, ctrl.K_P, ctrl.K_D, steps)
        assert np.max(np.abs(q - ours.q[:steps])) < TOL, cls.name


# ------------------------------------------------------------------------------------------------------
# the stored results the book reads (no extras needed)
# ------------------------------------------------------------------------------------------------------
def test_stored_results_are_complete_and_consistent():
    path = os.path.join(BENCH, "results.json")
    if not os.path.exists(path):
        pytest.skip("benchmarks/results.json not written yet: run python benchmarks/run.py")
    with open(path) as fh:
        res = json.load(fh)
    for key in ("date", "machine", "versions", "agreement", "per_call", "clik", "closed_loop", "targets"):
        assert key in res, key
    assert res["machine"]["cpu"] and res["machine"]["cores"] >= 1
    for name in ("numpy", "roboticstoolbox-python", "spatialmath-python", "pin"):
        assert res["versions"][name], name
    ag = res["agreement"]
    for group in ("kinematics", "dynamics_no_rotors", "dynamics_no_rotors_payload"):
        for lib, e in ag[group].items():
            assert max(e.values()) < ag["tolerance"], (group, lib)
    for lib, e in ag["rotors_on"].items():
        assert e["torque_minus_coupling"] < ag["tolerance"], lib
    # the exported files (relative differences) and MuJoCo's runs of the engine's loops
    assert set(ag["export"]) == {"pinocchio_urdf", "mujoco_mjcf"}
    for tool, e in ag["export"].items():
        assert max(v for k, v in e.items() if k != "inertia_difference") < ag["export_tolerance"], tool
    assert set(ag["mujoco_runs"]) == {"pd_gravity", "free_fall", "computed_torque"}
    for key, e in ag["mujoco_runs"].items():
        assert e["rotor_free"] <= e["roundoff_bound"] < e["euler_difference"] and e["difference"] <= e["bound"], key
        assert not e["clipped"], key
    assert res["versions"]["mujoco"]
    for key in ("clik", "closed_loop"):
        for name in ("ours", "numpy", "pinocchio", "toolbox") + (("mujoco",) if key == "closed_loop" else ()):
            e = res[key][name]
            assert e["seconds"] > 0 and math.isfinite(e["ratio_to_ours"])
            assert e["max_q_difference"] < 1e-8, (key, name)
    for t in res["targets"].values():
        assert t["met"] == (t["measured"] >= t["target"])
