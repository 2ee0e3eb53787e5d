"""Agreement of ``scara`` with Peter Corke's Robotics Toolbox for Python and with Pinocchio.

Every check draws many random states (joint positions over the whole range, velocities, accelerations) and
reports the largest absolute difference. Three groups:

1. Kinematics: ``T_e^b`` against the toolbox's ``fkine`` and Pinocchio's frame placement; the analytic
   Jacobian against the geometric one of each library (``jacob0``, and ``computeFrameJacobian`` in
   ``LOCAL_WORLD_ALIGNED``: linear velocity of the end-effector origin and angular velocity, both in the base
   frame). Sign conventions: the three position rows of ``J_A`` are the libraries' linear rows; the libraries'
   angular rate about the base z axis (up) is ``-phi_dot``, since ``phi`` turns about the downward ``z0``
   (chapter 1, (eq-kin-base) and (eq-fk)), so ``J_A[3] = -J_geo[5]``; the horizontal angular rows
   ``J_geo[3:5]`` are zero.
2. Rigid-body dynamics with the rotor inertias set to zero: ``B``, ``C`` (Christoffel; the toolbox's
   ``coriolis`` and Pinocchio's ``computeCoriolisMatrix``), ``g``, inverse dynamics ``tau`` (with the
   friction ``F qd``) and forward dynamics ``qdd``.
3. Rotors on: the libraries add only ``diag(k_r^2 I_m)``. The remainder ``B_ours - B_lib`` must equal
   :func:`rotor_coupling` (constant, since every rotor turns about the vertical with a link whose angular
   velocity is a sum of joint rates), so ``tau_ours - tau_lib = Delta_B qdd`` with no velocity or gravity
   part; and :func:`rotor_effect` measures that term along the reference motion of chapter 3 (section The
   reference path).

Run ``python benchmarks/agreement.py`` for the table. Needs the extras of ``requirements-bench.txt``.
"""
from __future__ import annotations

import math
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import scara  # noqa: E402
from scara import ScaraParams  # noqa: E402
from scara import dynamics as dyn  # noqa: E402

import libraries as L  # noqa: E402

__all__ = ["TOLERANCE", "random_states", "kinematics_agreement", "dynamics_agreement", "rotor_coupling",
           "rotor_agreement", "reference_joint_motion", "rotor_effect", "all_agreement", "LIBRARIES"]

#: The bound every rotor-free comparison must meet (absolute, SI units; torques here reach ~10^2 N).
TOLERANCE = 1e-10

LIBRARIES = ("toolbox", "pinocchio")
NO_ROTORS = (0.0, 0.0, 0.0, 0.0)


def random_states(n: int = 500, seed: int = 7, p: ScaraParams | None = None):
    """``n`` random states ``(q, qd, qdd)``, each (n, 4): angles uniform in [-pi, pi], ``d3`` in [0, d0],
    joint rates uniform in [-3, 3] (m/s for d3: [-1, 1]), accelerations in [-10, 10] ([-3, 3])."""
    p = ScaraParams() if p is None else p
    rng = np.random.default_rng(seed)
    q = rng.uniform(-math.pi, math.pi, (n, 4))
    q[:, 2] = rng.uniform(0.0, p.d0, n)
    scale_v = np.array([3.0, 3.0, 1.0, 3.0])
    scale_a = np.array([10.0, 10.0, 3.0, 10.0])
    qd = rng.uniform(-1.0, 1.0, (n, 4)) * scale_v
    qdd = rng.uniform(-1.0, 1.0, (n, 4)) * scale_a
    return q, qd, qdd


class _Pin:
    """Pinocchio calls used by the checks and the timing loops (a thin, explicit wrapper)."""

    def __init__(self, p, rotors):
        import pinocchio as pin

        self.pin = pin
        self.model, self.data = L.pinocchio_model(p, rotors)
        self.ee = self.model.getFrameId("ee")
        self.F = np.asarray(p.F)

    def fkine(self, q):
        pin = self.pin
        pin.forwardKinematics(self.model, self.data, q)
        return pin.updateFramePlacement(self.model, self.data, self.ee).homogeneous

    def jacob0(self, q):
        pin = self.pin
        return pin.computeFrameJacobian(self.model, self.data, q, self.ee, pin.LOCAL_WORLD_ALIGNED)

    def inertia(self, q):
        M = self.pin.crba(self.model, self.data, q)  # upper triangle filled
        return np.triu(M) + np.triu(M, 1).T

    def coriolis(self, q, qd):
        return self.pin.computeCoriolisMatrix(self.model, self.data, q, qd).copy()

    def gravload(self, q):
        return self.pin.computeGeneralizedGravity(self.model, self.data, q).copy()

    def rne(self, q, qd, qdd):
        return self.pin.rnea(self.model, self.data, q, qd, qdd) + self.F * qd

    def accel(self, q, qd, tau):
        return self.pin.aba(self.model, self.data, q, qd, tau - self.F * qd).copy()


class _Toolbox:
    """Robotics Toolbox calls, same names as :class:`_Pin` (friction is inside the toolbox's ``rne``)."""

    def __init__(self, p, rotors):
        self.robot = L.toolbox_robot(p, rotors)

    def fkine(self, q):
        return self.robot.fkine(q).A

    def jacob0(self, q):
        return self.robot.jacob0(q)

    def inertia(self, q):
        return self.robot.inertia(q)

    def coriolis(self, q, qd):
        return self.robot.coriolis(q, qd)

    def gravload(self, q):
        return self.robot.gravload(q)

    def rne(self, q, qd, qdd):
        return self.robot.rne(q, qd, qdd)

    def accel(self, q, qd, tau):
        return self.robot.accel(q, qd, tau)


def library(name: str, p: ScaraParams | None = None, rotors: bool = True):
    """A wrapper with ``fkine, jacob0, inertia, coriolis, gravload, rne, accel`` for ``name``."""
    p = ScaraParams() if p is None else p
    if name == "toolbox":
        return _Toolbox(p, rotors)
    if name == "pinocchio":
        return _Pin(p, rotors)
    raise ValueError(f"unknown library {name!r}; known: {LIBRARIES}")


def _maxabs(a) -> float:
    return float(np.max(np.abs(a)))


# ------------------------------------------------------------------------------------------------------
# 1. kinematics
# ------------------------------------------------------------------------------------------------------
def kinematics_agreement(n: int = 500, seed: int = 7, p: ScaraParams | None = None) -> dict:
    """Largest differences over ``n`` random configurations, per library:

    ``fkine`` (all 16 entries of ``T_e^b``), ``jacobian_position`` (rows ``p_x, p_y, p_z`` of ``J_A`` against
    the linear rows), ``jacobian_phi`` (``J_A[3]`` against ``-omega_z`` row), ``jacobian_tilt`` (largest entry
    of the horizontal angular rows, which must vanish).
    """
    p = ScaraParams() if p is None else p
    q, _, _ = random_states(n, seed, p)
    out = {}
    for name in LIBRARIES:
        lib = library(name, p)
        e = dict(fkine=0.0, jacobian_position=0.0, jacobian_phi=0.0, jacobian_tilt=0.0)
        for qk in q:
            T = lib.fkine(qk)
            Jg = lib.jacob0(qk)
            JA = scara.jacobian(qk, p)
            e["fkine"] = max(e["fkine"], _maxabs(T - scara.fkine(qk, p)))
            e["jacobian_position"] = max(e["jacobian_position"], _maxabs(Jg[:3] - JA[:3]))
            e["jacobian_phi"] = max(e["jacobian_phi"], _maxabs(-Jg[5] - JA[3]))
            e["jacobian_tilt"] = max(e["jacobian_tilt"], _maxabs(Jg[3:5]))
        out[name] = e
    return out


# ------------------------------------------------------------------------------------------------------
# 2. rigid-body dynamics, rotors off
# ------------------------------------------------------------------------------------------------------
def dynamics_agreement(n: int = 300, seed: int = 11, p: ScaraParams | None = None) -> dict:
    """Largest differences of ``B, C, g, tau, qdd`` over ``n`` random states with ``I_m = 0``, per library
    (and for the plain-numpy twin of ``libraries.NumpyRobot``, which keeps the closed forms of chapters 1 and 5)."""
    p = (ScaraParams() if p is None else p).replace(I_m=NO_ROTORS)
    q, qd, qdd = random_states(n, seed, p)
    libs = {name: library(name, p, rotors=False) for name in LIBRARIES}
    libs["numpy"] = L.NumpyRobot(p)
    out = {name: dict(inertia=0.0, coriolis=0.0, gravity=0.0, inverse_dynamics=0.0, forward_dynamics=0.0)
           for name in libs}
    for qk, qdk, qddk in zip(q, qd, qdd):
        B = dyn.inertia(qk, p)
        C = dyn.coriolis(qk, qdk, p)
        g = dyn.gravity(qk, p)
        tau = dyn.inverse_dynamics(qk, qdk, qddk, p)
        acc = dyn.forward_dynamics(qk, qdk, tau, p)
        for name, lib in libs.items():
            e = out[name]
            e["inertia"] = max(e["inertia"], _maxabs(lib.inertia(qk) - B))
            e["coriolis"] = max(e["coriolis"], _maxabs(lib.coriolis(qk, qdk) - C))
            e["gravity"] = max(e["gravity"], _maxabs((lib.gravload(qk) if name != "numpy" else lib.gravity(qk)) - g))
            e["inverse_dynamics"] = max(e["inverse_dynamics"], _maxabs(lib.rne(qk, qdk, qddk) - tau))
            e["forward_dynamics"] = max(e["forward_dynamics"], _maxabs(lib.accel(qk, qdk, tau) - acc))
    return out


# ------------------------------------------------------------------------------------------------------
# 3. rotors on
# ------------------------------------------------------------------------------------------------------
def rotor_coupling(p: ScaraParams | None = None) -> np.ndarray:
    """``Delta_B`` (eq-verif-rotor-coupling): the part of the ``B`` of chapter 5 ((eq-dynamics) with the rotors of
    (eq-dyn-rotors)) that a diagonal ``k_r^2 I_m`` leaves out, shape (4, 4).

    Rotor i turns at ``omega_{i-1} + k_ri qd_i`` with ``omega_0 = 0``, ``omega_1 = qd1``,
    ``omega_2 = omega_3 = qd1 + qd2``, so its kinetic energy ``I_mi (omega_{i-1} + k_ri qd_i)^2 / 2`` adds to B

    * the diagonal ``k_ri^2 I_mi`` (what the libraries have),
    * ``I_mi`` on every ``B_jl`` with ``j, l`` among the joints that turn link i-1 (rotor 2: joint 1;
      rotors 3, 4: joints 1 and 2),
    * ``k_ri I_mi`` on ``B_ji`` for those joints ``j``.

    Written out: ``Delta_B11 = I_m2 + I_m3 + I_m4``, ``Delta_B12 = k_r2 I_m2 + I_m3 + I_m4``,
    ``Delta_B22 = I_m3 + I_m4``, ``Delta_B13 = Delta_B23 = k_r3 I_m3``, ``Delta_B14 = Delta_B24 = k_r4 I_m4``,
    zero elsewhere. It does not depend on ``q``, so it adds nothing to ``C`` or ``g``.
    """
    p = ScaraParams() if p is None else p
    k, Im = p.k_r, p.I_m
    D = np.zeros((4, 4))
    D[0, 0] = Im[1] + Im[2] + Im[3]
    D[0, 1] = k[1] * Im[1] + Im[2] + Im[3]
    D[1, 1] = Im[2] + Im[3]
    D[0, 2] = D[1, 2] = k[2] * Im[2]
    D[0, 3] = D[1, 3] = k[3] * Im[3]
    return np.triu(D) + np.triu(D, 1).T


def rotor_agreement(n: int = 300, seed: int = 13, p: ScaraParams | None = None) -> dict:
    """With the rotors on (the values of the introduction's table), per library, the largest of

    * ``inertia_minus_coupling``: ``|B_ours - B_lib - Delta_B|``,
    * ``coriolis``, ``gravity``: ``|C_ours - C_lib|``, ``|g_ours - g_lib|`` (the rotors add nothing there),
    * ``torque_minus_coupling``: ``|tau_ours - tau_lib - Delta_B qdd|``,
    * ``forward_dynamics_lib_model``: ``|qdd_lib - (B_ours - Delta_B)^-1 (tau - C qd - F qd - g)|``, i.e. the
      library integrates exactly our model less the coupling,
    * ``inertia_difference``: ``|B_ours - B_lib|`` itself, for scale.
    """
    p = ScaraParams() if p is None else p
    D = rotor_coupling(p)
    q, qd, qdd = random_states(n, seed, p)
    out = {}
    for name in LIBRARIES:
        lib = library(name, p, rotors=True)
        e = dict(inertia_minus_coupling=0.0, coriolis=0.0, gravity=0.0, torque_minus_coupling=0.0,
                 forward_dynamics_lib_model=0.0, inertia_difference=0.0)
        for qk, qdk, qddk in zip(q, qd, qdd):
            B = dyn.inertia(qk, p)
            Bl = lib.inertia(qk)
            tau = dyn.inverse_dynamics(qk, qdk, qddk, p)
            e["inertia_minus_coupling"] = max(e["inertia_minus_coupling"], _maxabs(B - Bl - D))
            e["inertia_difference"] = max(e["inertia_difference"], _maxabs(B - Bl))
            e["coriolis"] = max(e["coriolis"], _maxabs(dyn.coriolis(qk, qdk, p) - lib.coriolis(qk, qdk)))
            e["gravity"] = max(e["gravity"], _maxabs(dyn.gravity(qk, p) - lib.gravload(qk)))
            e["torque_minus_coupling"] = max(e["torque_minus_coupling"],
                                             _maxabs(tau - lib.rne(qk, qdk, qddk) - D @ qddk))
            n_ = dyn.inverse_dynamics(qk, qdk, np.zeros(4), p)  # C qd + F qd + g
            expected = np.linalg.solve(B - D, tau - n_)
            e["forward_dynamics_lib_model"] = max(e["forward_dynamics_lib_model"],
                                                  _maxabs(lib.accel(qk, qdk, tau) - expected))
        out[name] = e
    return out


def reference_joint_motion(traj=None, p: ScaraParams | None = None):
    """The joint motion that tracks the reference exactly: ``q = k^-1(x_d)`` (closed form, elbow
    ``theta2 < 0`` as at the start of chapter 3's reference path), ``qd = J_A^-1 xd_d``,
    ``qdd = J_A^-1 (xdd_d - Jdot_A qd)``.

    Returns ``(t, q, qd, qdd)``; ``traj`` defaults to ``scara.reference_trajectory()``.
    """
    p = ScaraParams() if p is None else p
    if traj is None:
        from scara.trajectory import reference_trajectory

        traj = reference_trajectory()
    q = scara.ikine(np.asarray(traj.x), p, elbow=-1)
    qd = np.empty_like(q)
    qdd = np.empty_like(q)
    for k in range(q.shape[0]):
        J = scara.jacobian(q[k], p)
        qd[k] = np.linalg.solve(J, traj.xd[k])
        qdd[k] = np.linalg.solve(J, traj.xdd[k] - scara.jacobian_dot(q[k], qd[k], p) @ qd[k])
    return np.asarray(traj.t), q, qd, qdd


def rotor_effect(traj=None, p: ScaraParams | None = None, motion=None) -> dict:
    """How much the rotor coupling ``Delta_B qdd`` changes the torques along the reference motion.

    ``p`` defaults to the robot with the 5 kg payload (the dynamics chapter's case). Per joint: the largest
    ``|Delta_B qdd|`` (N m, N for the quill), the largest ``|tau|`` of the full model, and their ratio; also
    the largest difference between our torques and each library's along the motion, minus the coupling term
    (it must vanish to the tolerance).
    """
    p = ScaraParams().with_payload(5.0) if p is None else p
    t, q, qd, qdd = reference_joint_motion(traj, p) if motion is None else motion
    tau = dyn.inverse_dynamics(q, qd, qdd, p)
    dtau = qdd @ rotor_coupling(p).T
    res = dict(
        samples=int(q.shape[0]), payload=p.m_L,
        max_coupling_torque=np.max(np.abs(dtau), axis=0).tolist(),
        max_torque=np.max(np.abs(tau), axis=0).tolist(),
        rms_coupling_torque=np.sqrt(np.mean(dtau ** 2, axis=0)).tolist(),
    )
    res["ratio_max"] = [c / m if m > 0 else 0.0 for c, m in zip(res["max_coupling_torque"], res["max_torque"])]
    # spot check along the motion: every library's torque + Delta_B qdd = ours (subsampled, the toolbox is slow)
    idx = np.arange(0, q.shape[0], max(1, q.shape[0] // 400))
    for name in LIBRARIES:
        lib = library(name, p, rotors=True)
        err = max(_maxabs(tau[k] - lib.rne(q[k], qd[k], qdd[k]) - dtau[k]) for k in idx)
        res[f"{name}_torque_minus_coupling"] = err
    return res


def all_agreement(n_kin: int = 500, n_dyn: int = 300) -> dict:
    """Every agreement figure in one dict (stored in ``results.json`` by ``run.py``)."""
    p0 = ScaraParams()
    pL = ScaraParams().with_payload(5.0)
    return dict(
        tolerance=TOLERANCE,
        n_kinematics=n_kin,
        n_dynamics=n_dyn,
        kinematics=kinematics_agreement(n_kin, p=p0),
        dynamics_no_rotors=dynamics_agreement(n_dyn, p=p0),
        dynamics_no_rotors_payload=dynamics_agreement(n_dyn, seed=12, p=pL),
        rotors_on=rotor_agreement(n_dyn, p=pL),
        rotor_coupling=rotor_coupling(pL).tolist(),
        rotor_effect=rotor_effect(p=pL),
    )


def _print(res: dict) -> None:
    tol = res["tolerance"]
    print(f"Agreement (largest absolute difference; tolerance {tol:.0e})")
    print(f"  kinematics over {res['n_kinematics']} random configurations")
    for lib, e in res["kinematics"].items():
        print(f"    {lib:10s} " + "  ".join(f"{k}={v:.1e}" for k, v in e.items()))
    for key, title in (("dynamics_no_rotors", "rigid body, rotors off, no payload"),
                       ("dynamics_no_rotors_payload", "rigid body, rotors off, 5 kg payload")):
        print(f"  {title}, {res['n_dynamics']} random states")
        for lib, e in res[key].items():
            print(f"    {lib:10s} " + "  ".join(f"{k}={v:.1e}" for k, v in e.items()))
    print("  rotors on (5 kg payload): difference minus the rotor coupling (eq-verif-rotor-coupling)")
    for lib, e in res["rotors_on"].items():
        print(f"    {lib:10s} " + "  ".join(f"{k}={v:.1e}" for k, v in e.items()))
    r = res["rotor_effect"]
    print("  rotor coupling along the reference motion: max |Delta_B qdd| per joint "
          + ", ".join(f"{v:.3g}" for v in r["max_coupling_torque"])
          + "; as a share of max |tau| " + ", ".join(f"{100 * v:.2f}%" for v in r["ratio_max"]))


if __name__ == "__main__":
    _print(all_agreement())
