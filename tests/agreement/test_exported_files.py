"""The exported files proven equal (the verification appendix, section on URDF and MJCF): Pinocchio loads the
URDF and MuJoCo the MJCF of ``scara.export``; their kinematics and rigid-body terms equal ``scara``'s, and MuJoCo
runs the engine's closed loops on the MJCF.

Needs the optional extras (``pip install -r requirements-bench.txt``: ``pin``, ``mujoco``); without them every
test here is skipped with the reason.

Tolerances:

* 1e-12 relative to the largest entry of our quantity for every term of the files (item "proven equal"): the
  files hold the model's numbers exactly (shortest repr, read back bit for bit), so only the libraries'
  summation order separates the results (measured 1e-16 to 3e-14; MuJoCo's floor of 1e-14 kg and kg m^2 on the
  massless link 4 and the quill's moment adds at most 2e-14 / 9 to ``B``).
* The closed loops: both integrate with the classical RK4, one step per 1 ms sample with the torque held, so
  their truncation errors are the same numbers; what separates two runs of the same model is round-off, at most
  one unit of the last place per step, ``samples x 2^-53 x max |q|`` (2.2e-11 rad for 70 s). With the rotors,
  MuJoCo's model is ours less the coupling ``Delta_B``, so the runs differ by the armature approximation, which the
  same loop on our model less ``Delta_B`` reproduces within that round-off bound.
"""
from __future__ import annotations

import math

import numpy as np
import pytest

from scara import ScaraParams
from scara.export import rotor_coupling

from _bench import bench_module, rotor_free_pd_gravity_run

REL = 1e-12


@pytest.fixture(scope="module")
def A():
    """The benchmarks' agreement module, after checking that Pinocchio and MuJoCo import."""
    return bench_module("agreement", "pinocchio", "mujoco")


@pytest.mark.parametrize("m_L", [0.0, 5.0, 10.0])
def test_files_hold_the_books_model(A, m_L):
    """Item 2: fkine, B, C, g (and tau, qdd with the friction the files state) equal scara's to 1e-12 relative with
    the rotors off; with the rotors on, B_ours - B_tool is the rotor coupling Delta_B, C and g are unchanged."""
    p = ScaraParams().with_payload(m_L)
    res = A.export_agreement(n=80, seed=23, p=p)
    assert set(res) == set(A.EXPORT_TOOLS)
    for tool, e in res.items():
        for what, err in e.items():
            if what == "inertia_difference":
                continue
            assert err < REL, f"{tool} {what} (m_L = {m_L}): {err:.3e}"
        assert e["inertia_difference"] == pytest.approx(float(np.max(np.abs(rotor_coupling(p)))), abs=1e-12)


def test_files_follow_other_arms(A):
    """Not only the book's numbers: another geometry, other masses and motors, and a stroke that does not start at
    zero, through both files."""
    p = ScaraParams(a1=0.4, a2=0.3, l1=0.15, l2=0.12, d0=0.8, m_l1=12.0, m_l2=7.0, m_l3=3.0, I_l1=0.9, I_l2=0.4,
                    I_l4=0.05, k_r=(80.0, 60.0, 300.0, 30.0), I_m=(2e-4, 1e-4, 5e-5, 2e-5),
                    F_m=(1e-4, 1e-4, 1e-3, 1e-3),
                    d3_min=0.1, d3_max=0.5).with_payload(2.0)
    res = A.export_agreement(n=40, seed=5, p=p)
    for tool, e in res.items():
        for what, err in e.items():
            if what != "inertia_difference":
                assert err < REL, f"{tool} {what}: {err:.3e}"


def test_pinocchio_reads_the_urdfs_limits_damping_and_armature(A, L):
    p = ScaraParams().with_payload(5.0)
    model, _ = L.pinocchio_from_urdf(p)
    assert [model.names[i] for i in range(1, 5)] == ["joint1", "joint2", "joint3", "joint4"]
    assert np.array_equal(model.damping, p.F)
    assert np.array_equal(model.armature, np.asarray(p.k_r) ** 2 * np.asarray(p.I_m))
    i3 = model.idx_qs[3]
    assert (model.lowerPositionLimit[i3], model.upperPositionLimit[i3]) == (p.d3_min, p.d3_max)
    # the DH frames are frames of the model: link i's placement is A_1^b ... A_i^b of chapter 1
    import pinocchio as pin

    from scara import link_frames

    data = model.createData()
    q = np.array([0.4, -1.3, 0.35, 2.2])
    pin.framesForwardKinematics(model, data, L.pinocchio_configuration(model, q))
    frames = link_frames(q, p)
    for i, name in enumerate(("frame0", "link1", "link2", "link3", "link4")):
        T = data.oMf[model.getFrameId(name)].homogeneous
        assert np.max(np.abs(T - frames[i])) < 1e-14, name


def test_mujoco_reads_the_mjcf_options(A, L):
    p = ScaraParams().with_payload(5.0)
    model, _ = L.mujoco_model(p)
    assert model.opt.timestep == 1e-3
    assert np.array_equal(model.opt.gravity, [0.0, 0.0, -p.g0])
    assert np.array_equal(model.dof_armature, np.asarray(p.k_r) ** 2 * np.asarray(p.I_m))
    assert np.array_equal(model.dof_damping, p.F)
    assert tuple(model.jnt_range[2]) == (p.d3_min, p.d3_max) and model.jnt_limited[2]
    assert not any(model.jnt_limited[[0, 1, 3]])
    import mujoco

    assert model.opt.integrator == mujoco.mjtIntegrator.mjINT_RK4


@pytest.fixture(scope="module")
def runs(A):
    return A.mujoco_agreement()


@pytest.mark.parametrize("key", ["pd_gravity", "free_fall", "computed_torque"])
def test_mujoco_runs_the_engines_closed_loops(runs, key):
    """Item 3: the same loop, the same RK4 at the same 1 ms step with the torque held."""
    e = runs[key]
    assert not e["clipped"]
    # nothing approximated: the runs part by round-off only (measured ~4e-16 rad over 70 s)
    assert e["rotor_free"] <= e["roundoff_bound"], key
    # with the rotors, MuJoCo integrates exactly our model less Delta_B ...
    assert e["mujoco_vs_less"] <= e["roundoff_bound"], key
    # ... so it stays within the armature approximation plus round-off of the engine
    assert e["difference"] <= e["bound"], key
    # the approximation must be visible, or the comparison proves nothing about it
    assert e["armature_effect"] > 100 * e["roundoff_bound"], key
    assert e["samples"] == (70001 if key != "free_fall" else 501)
    # MuJoCo's default integrator (semi-implicit Euler, first order) in place of RK4 parts the runs by O(h):
    # far above round-off, which is why the MJCF asks for RK4
    assert e["euler_difference"] > 1e4 * e["roundoff_bound"], key


def test_free_fall_matches_the_closed_form_to_rk4s_order(A, L):
    """MuJoCo's quill, falling from rest with no torque, against the exact solution: with armature only,
    ``B33 d3'' = m3 g0 - F3 d3'``, so ``d3(t) = v (t - T (1 - exp(-t/T)))``, ``T = B33 / F3``, ``v = m3 g0 / F3``.
    Classical RK4 on this linear system errs per step by ``h^5 / 120`` times the fifth derivative of the solution,
    ``|d3^(5)| <= v / T^4``; over ``t / h`` steps of a stable system the global error is at most
    ``t h^4 v / (120 T^4)`` (1e-14 m for 0.5 s), plus round-off ``steps x 2^-53 x d3``. Joints 1, 2 and 4 do not
    move at all: the armature cannot carry rotor 3's reaction."""
    import mujoco

    from scara._simulate import TorqueController, simulate

    p = ScaraParams().with_payload(5.0)
    q0 = np.array([0.3, -1.2, 0.0, 0.5])
    ours = simulate(TorqueController(), plant=p, duration=0.5, q0=q0)
    mj = A.mujoco_closed_loop(TorqueController(), ours)
    B33 = p.m3 + p.k_r[2] ** 2 * p.I_m[2]
    F3 = p.F[2]
    T, v = B33 / F3, p.m3 * p.g0 / F3
    t = ours.t
    exact = v * (t - T * (1.0 - np.exp(-t / T)))
    h = ours.dt
    bound = t[-1] * h ** 4 * v / (120 * T ** 4) + len(t) * 2.0 ** -53 * float(exact.max()) * 4
    assert np.max(np.abs(mj["q"][:, 2] - exact)) <= bound
    assert np.array_equal(mj["q"][:, [0, 1, 3]], np.tile(q0[[0, 1, 3]], (len(t), 1)))
    # the book's model: rotor 3 spinning up turns the links it rides on (its reaction, B13 = B23 = k_r3 I_m3)
    assert np.max(np.abs(ours.q[:, 1] - q0[1])) > 1e-3
    assert mujoco.mj_version() > 0


def test_closed_loop_timing_loop_on_mujoco_reproduces_simulate(A):
    """The timed MuJoCo loop of benchmarks/run.py does the same work: PD + gravity, rotors off, same motion."""
    import run

    traj, plant, model, ctrl, ref, ours = rotor_free_pd_gravity_run(A.NO_ROTORS)
    steps = 2000
    q = run.closed_loop(run.MuJoCoCalls(plant, rotors=False), run.MuJoCoCalls(model, rotors=False), ref, ref[0, :4],
                        ref[0, 4:8], traj.dt, ctrl.K_P, ctrl.K_D, steps)
    assert np.max(np.abs(q - ours.q[:steps])) < steps * 2.0 ** -53 * math.pi
