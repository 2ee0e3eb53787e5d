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
from scara import export as _export  # noqa: E402

import libraries as L  # noqa: E402

__all__ = ["TOLERANCE", "random_states", "kinematics_agreement", "dynamics_agreement", "rotor_coupling",
           "rotor_agreement", "reference_joint_motion", "rotor_effect", "all_agreement", "LIBRARIES"]

#: The bound every rotor-free comparison must meet (absolute, SI units; torques here reach ~10^2 N).
TOLERANCE = 1e-10

LIBRARIES = ("toolbox", "pinocchio")
NO_ROTORS = (0.0, 0.0, 0.0, 0.0)


def random_states(n: int = 500, seed: int = 7, p: ScaraParams | None = None):
    """``n`` random states ``(q, qd, qdd)``, each (n, 4): angles uniform in [-pi, pi], ``d3`` in the quill's stroke,
    joint rates uniform in [-3, 3] (m/s for d3: [-1, 1]), accelerations in [-10, 10] ([-3, 3])."""
    p = ScaraParams() if p is None else p
    rng = np.random.default_rng(seed)
    q = rng.uniform(-math.pi, math.pi, (n, 4))
    q[:, 2] = rng.uniform(p.d3_min, p.d3_max, n)
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

    def _cfg(self, q):
        """Pinocchio's configuration vector of ``q`` (the same four numbers for the model built in code)."""
        return q

    def fkine(self, q):
        pin = self.pin
        pin.forwardKinematics(self.model, self.data, self._cfg(q))
        return pin.updateFramePlacement(self.model, self.data, self.ee).homogeneous

    def jacob0(self, q):
        pin = self.pin
        return pin.computeFrameJacobian(self.model, self.data, self._cfg(q), self.ee, pin.LOCAL_WORLD_ALIGNED)

    def inertia(self, q):
        M = self.pin.crba(self.model, self.data, self._cfg(q))  # upper triangle filled
        return np.triu(M) + np.triu(M, 1).T

    def coriolis(self, q, qd):
        return self.pin.computeCoriolisMatrix(self.model, self.data, self._cfg(q), qd).copy()

    def gravload(self, q):
        return self.pin.computeGeneralizedGravity(self.model, self.data, self._cfg(q)).copy()

    def rne(self, q, qd, qdd):
        return self.pin.rnea(self.model, self.data, self._cfg(q), qd, qdd) + self.F * qd

    def accel(self, q, qd, tau):
        return self.pin.aba(self.model, self.data, self._cfg(q), qd, tau - self.F * qd).copy()


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
    """A wrapper with ``fkine, jacob0, inertia, coriolis, gravload, rne, accel`` for ``name``: one of
    :data:`LIBRARIES`, or of :data:`EXPORT_TOOLS` (the exported files as Pinocchio and MuJoCo load them; MuJoCo has
    no ``jacob0``)."""
    p = ScaraParams() if p is None else p
    if name not in _TOOLS:
        raise ValueError(f"unknown library {name!r}; known: {LIBRARIES + EXPORT_TOOLS}")
    return _TOOLS[name](p, rotors)


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
# ``Delta_B`` (eq-verif-rotor-coupling), the part of chapter 5's ``B`` that a diagonal ``k_r^2 I_m`` leaves out:
# the package states it once, beside the exported files that lose it.
rotor_coupling = _export.rotor_coupling


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
        export_tolerance=EXPORT_TOLERANCE,
        n_export=n_dyn,
        export=export_agreement(n_dyn, p=pL),
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
    if "export" in res:
        print(f"  the exported files (relative to our largest entry; tolerance {res['export_tolerance']:.0e}), "
              f"{res['n_export']} random states, 5 kg payload")
        for tool, e in res["export"].items():
            print(f"    {tool:15s} " + "  ".join(f"{k}={v:.1e}" for k, v in e.items()))
    for key, e in res.get("mujoco_runs", {}).items():
        print(f"  MuJoCo, {e['title']}: rotor-free {e['rotor_free']:.1e} (round-off bound {e['roundoff_bound']:.1e}); "
              f"rotors on {e['difference']:.2e} <= bound {e['bound']:.2e} (armature effect {e['armature_effect']:.2e}, "
              f"MuJoCo vs our model less the coupling {e['mujoco_vs_less']:.1e}); with MuJoCo's Euler in place of "
              f"RK4, rotor-free {e['euler_difference']:.1e}")



# ------------------------------------------------------------------------------------------------------
# 4. the exported files: Pinocchio reads the URDF, MuJoCo the MJCF
# ------------------------------------------------------------------------------------------------------
EXPORT_TOOLS = ("pinocchio_urdf", "mujoco_mjcf")
#: The bound of every comparison with the exported files, relative to the largest entry of our quantity.
EXPORT_TOLERANCE = 1e-12


class _MuJoCo:
    """MuJoCo's terms of the exported MJCF: ``fkine`` (body ``link4``), ``inertia`` (``mj_fullM``), ``gravity``
    (the bias force at rest), ``coriolis`` (the Christoffel matrix, recovered from the bias forces, below),
    ``rne`` (``mj_inverse``, damping included) and ``accel`` (``mj_forward``'s ``qacc``)."""

    def __init__(self, p, rotors=True):
        import mujoco

        self.mj = mujoco
        self.model, self.data = L.mujoco_model(p, rotors)
        self.free, self.free_data = L.mujoco_model(p, rotors)
        self.free.opt.gravity[:] = 0.0  # the bias force without gravity is C(q, qd) qd alone
        self.link4 = mujoco.mj_name2id(self.model, mujoco.mjtObj.mjOBJ_BODY, "link4")

    def _forward(self, q, qd=None, tau=None, model=None, data=None):
        """``mj_forward`` at ``(q, qd)`` with ``tau`` applied as a generalised force (``qfrc_applied``: the motors'
        ``ctrlrange`` would clip the random torques of the checks)."""
        model = self.model if model is None else model
        data = self.data if data is None else data
        data.qpos[:] = q
        data.qvel[:] = 0.0 if qd is None else qd
        data.ctrl[:] = 0.0
        data.qfrc_applied[:] = 0.0 if tau is None else tau
        self.mj.mj_forward(model, data)
        return data

    def fkine(self, q):
        d = self._forward(q)
        T = np.eye(4)
        T[:3, :3] = d.xmat[self.link4].reshape(3, 3)
        T[:3, 3] = d.xpos[self.link4]
        return T

    def inertia(self, q):
        d = self._forward(q)
        M = np.zeros((4, 4))
        self.mj.mj_fullM(self.model, d, M)
        return M

    def gravload(self, q):
        return self._forward(q).qfrc_bias.copy()

    def _c(self, q, v):
        return self._forward(q, v, model=self.free, data=self.free_data).qfrc_bias.copy()

    def coriolis(self, q, qd):
        """``C(q, qd)`` of the Christoffel symbols: MuJoCo gives only ``c(v) = C(q, v) v = sum_jk Gamma_ijk v_j v_k``;
        since ``Gamma_ijk = Gamma_ikj``, ``Gamma_ijj = c_i(e_j)`` and ``2 Gamma_ijk = c_i(e_j + e_k) - c_i(e_j) -
        c_i(e_k)``, and ``C_ij = sum_k Gamma_ijk qd_k`` (chapter 5, (eq-dyn-christoffel))."""
        E = np.eye(4)
        G = np.zeros((4, 4, 4))
        single = [self._c(q, E[j]) for j in range(4)]
        for j in range(4):
            G[:, j, j] = single[j]
            for k in range(j + 1, 4):
                G[:, j, k] = G[:, k, j] = 0.5 * (self._c(q, E[j] + E[k]) - single[j] - single[k])
        return G @ np.asarray(qd, dtype=float)

    def rne(self, q, qd, qdd):
        d = self._forward(q, qd)
        d.qacc[:] = qdd
        self.mj.mj_inverse(self.model, d)
        return d.qfrc_inverse.copy()

    def accel(self, q, qd, tau):
        return self._forward(q, qd, tau).qacc.copy()


class _PinUrdf(_Pin):
    """:class:`_Pin` on the model Pinocchio builds from the exported URDF (its unbounded joints take ``cos, sin``)."""

    def __init__(self, p, rotors):
        import pinocchio as pin

        self.pin = pin
        self.model, self.data = L.pinocchio_from_urdf(p, rotors)
        self.ee = self.model.getFrameId("link4")
        self.F = self.model.damping.copy()  # the file's joint damping

    def _cfg(self, q):
        return L.pinocchio_configuration(self.model, q)


#: Every tool :func:`library` builds: the two libraries, then the exported files as the tools load them.
_TOOLS = {"toolbox": _Toolbox, "pinocchio": _Pin, "pinocchio_urdf": _PinUrdf, "mujoco_mjcf": _MuJoCo}


def _rel(a, b) -> float:
    """``max |a - b| / max |b|`` (0 when both vanish)."""
    scale = float(np.max(np.abs(b)))
    diff = float(np.max(np.abs(np.asarray(a) - b)))
    return diff / scale if scale > 0 else diff


def export_agreement(n: int = 200, seed: int = 17, p: ScaraParams | None = None) -> dict:
    """The exported files against ``scara`` at ``n`` random states, per tool, each relative to the largest entry of
    ours (:func:`_rel`): rotors off (``I_m = 0``): ``fkine``, ``inertia``, ``coriolis``, ``gravity``,
    ``inverse_dynamics`` (friction included), ``forward_dynamics``; rotors on:
    ``inertia_minus_coupling`` (``B_ours - B_tool - Delta_B``, relative to ``B_ours``), ``coriolis_rotors`` and
    ``gravity_rotors`` (unchanged by rotors) and ``inertia_difference`` (``max |B_ours - B_tool|``, absolute)."""
    p = ScaraParams() if p is None else p
    bare = p.replace(I_m=NO_ROTORS)
    D = rotor_coupling(p)
    q, qd, qdd = random_states(n, seed, p)
    out = {}
    for name in EXPORT_TOOLS:
        off, on = library(name, bare, rotors=False), library(name, p, rotors=True)
        e = dict(fkine=0.0, inertia=0.0, coriolis=0.0, gravity=0.0, inverse_dynamics=0.0, forward_dynamics=0.0,
                 inertia_minus_coupling=0.0, coriolis_rotors=0.0, gravity_rotors=0.0, inertia_difference=0.0)
        for qk, qdk, qddk in zip(q, qd, qdd):
            B, C, g = dyn.inertia(qk, bare), dyn.coriolis(qk, qdk, bare), dyn.gravity(qk, bare)
            tau = dyn.inverse_dynamics(qk, qdk, qddk, bare)
            Bp = dyn.inertia(qk, p)
            Bt = on.inertia(qk)
            got = dict(fkine=(off.fkine(qk), scara.fkine(qk, bare)), inertia=(off.inertia(qk), B),
                       coriolis=(off.coriolis(qk, qdk), C), gravity=(off.gravload(qk), g),
                       inverse_dynamics=(off.rne(qk, qdk, qddk), tau),
                       forward_dynamics=(off.accel(qk, qdk, tau), qddk),
                       inertia_minus_coupling=(Bt + D, Bp), coriolis_rotors=(on.coriolis(qk, qdk), C),
                       gravity_rotors=(on.gravload(qk), g))
            for what, (a, b) in got.items():
                e[what] = max(e[what], _rel(a, b))
            e["inertia_difference"] = max(e["inertia_difference"], _maxabs(Bp - Bt))
        out[name] = e
    return out


# ------------------------------------------------------------------------------------------------------
# 5. MuJoCo as a fourth peer of the engine: the same closed loops on the exported MJCF
# ------------------------------------------------------------------------------------------------------
def _law_loop(controller, ours, step) -> dict:
    """Drive ``step(q, qd, tau) -> (q, qd)`` (one sampling period with ``tau`` held) with ``controller``'s compiled
    law as :func:`scara.simulate` does in ``ours``: the same reference rows, start state and sampling. Returns
    ``q``, ``qd``, ``tau`` (N, 4) and ``seconds`` (CPU time of the loop)."""
    import time

    from scara._simulate.interface import law_arrays

    n = len(ours.t)
    dt = ours.dt
    ref = np.ascontiguousarray(ours.reference)
    (gains, model_array, state, work), sig, _ = law_arrays(controller, n)
    law = controller.law
    Q, QD, TAU = np.empty((n, 4)), np.empty((n, 4)), np.empty((n, 4))
    tau = np.zeros(4)
    q, qd = ours.q[0].copy(), ours.qd[0].copy()
    t0 = time.process_time()
    for k in range(n):
        code = law(k, k * dt, dt, q, qd, ref[k], gains, model_array, state, work, sig[k], tau)
        if code != 0:
            raise RuntimeError(f"{controller.name} failed at sample {k} (code {code})")
        Q[k], QD[k], TAU[k] = q, qd, tau
        if k < n - 1:
            q, qd = step(q, qd, tau)
    return dict(q=Q, qd=QD, tau=TAU, seconds=time.process_time() - t0)


def mujoco_closed_loop(controller, ours, rotors: bool = True, integrator: str | None = None) -> dict:
    """Run ``controller`` on MuJoCo's model of the exported ``ours.plant`` as ``scara.simulate`` ran it in
    ``ours``: at each sample the compiled law computes ``tau`` from MuJoCo's state, which is held over one
    ``mj_step`` (the MJCF's RK4, one step per sample, as the engine). ``rotors=False`` exports the plant with
    ``I_m = 0`` (then ``ours`` must have been run on that plant). ``integrator`` replaces the MJCF's RK4 by another
    of MuJoCo's (``"Euler"``, its default, or ``"implicitfast"``).

    Returns :func:`_law_loop`'s dict and ``clipped``: whether a torque left the motors' ``ctrlrange`` (MuJoCo would
    have clipped it, and the runs could not be compared)."""
    import mujoco

    model, data = L.mujoco_model(ours.plant, rotors=rotors)
    model.opt.timestep = ours.dt
    if integrator is not None:
        model.opt.integrator = getattr(mujoco.mjtIntegrator, f"mjINT_{integrator.upper()}")
    lo, hi = model.actuator_ctrlrange[:, 0], model.actuator_ctrlrange[:, 1]
    clipped = [False]

    def step(q, qd, tau):
        data.qpos[:], data.qvel[:], data.ctrl[:] = q, qd, tau
        clipped[0] |= bool(np.any(tau < lo) or np.any(tau > hi))
        mujoco.mj_step(model, data)
        return data.qpos.copy(), data.qvel.copy()

    out = _law_loop(controller, ours, step)
    out["clipped"] = clipped[0]
    return out


def rk4_step(accel, q, qd, tau, h):
    """One classical RK4 step of ``h`` for ``qdd = accel(q, qd, tau)`` with ``tau`` held, as the engine steps
    (chapter 5): ``(q, qd, qdd)`` after the step, ``qdd`` the first stage's acceleration (at the start)."""
    a1 = accel(q, qd, tau)
    v2 = qd + 0.5 * h * a1
    a2 = accel(q + 0.5 * h * qd, v2, tau)
    v3 = qd + 0.5 * h * a2
    a3 = accel(q + 0.5 * h * v2, v3, tau)
    v4 = qd + h * a3
    a4 = accel(q + h * v3, v4, tau)
    return q + h / 6.0 * (qd + 2.0 * v2 + 2.0 * v3 + v4), qd + h / 6.0 * (a1 + 2.0 * a2 + 2.0 * a3 + a4), a1


def coupling_free_closed_loop(controller, ours) -> dict:
    """The loop of :func:`mujoco_closed_loop` integrated in Python with ``scara``'s own model *less* the rotor
    coupling: ``qdd = (B - Delta_B)^-1 (tau - C qd - F qd - g)`` (:func:`scara.export.rotor_coupling`), one classical
    RK4 step per sample with the torque held, as the engine and MuJoCo step. This is exactly the model the MJCF
    holds (rotors as armature), computed without MuJoCo."""
    p = ours.plant
    D = rotor_coupling(p)
    dp = dyn.dynamic_array(p)
    work = dyn.dynamics_workspace()
    zero = np.zeros(4)
    B, n = np.empty((4, 4)), np.empty(4)

    def accel(q, qd, tau):  # the compiled kernels behind scara.inertia and scara.inverse_dynamics
        dyn.inertia_kernel(q, dp, B)
        dyn.inverse_dynamics_kernel(q, qd, zero, dp, work, n)
        return np.linalg.solve(B - D, tau - n)

    def step(q, qd, tau):
        return rk4_step(accel, q, qd, tau, ours.dt)[:2]

    return _law_loop(controller, ours, step)


#: Unit round-off of double precision, 2^-53.
UNIT_ROUNDOFF = 2.0 ** -53


def _agreement_runs(traj=None):
    """The three runs of the fourth peer, as ``{key: (title, controller, plant -> SimulationResult)}``: the PD +
    gravity loop of chapter 5's reference run (the model does not know the 5 kg payload), the quill's free fall of
    chapter 5 (no torque, from d3 = 0, 0.5 s: the rotor-free quill reaches the end of its stroke at 0.52 s) and
    chapter 6's computed torque with the unknown payload, each along the reference path of chapter 3 tracked
    through the second-order CLIK."""
    from scara import clik2
    from scara._simulate import PDGravityController, TorqueController, simulate
    from scara.control.classic import ComputedTorqueController
    from scara.trajectory import reference_trajectory

    traj = reference_trajectory() if traj is None else traj
    ref = clik2(traj)
    q_drop = np.array([ref.q[0][0], ref.q[0][1], 0.0, 0.0])
    return {
        "pd_gravity": ("PD + gravity, reference run (chapter 5)", PDGravityController(),
                       lambda plant, c: simulate(c, traj, plant, joint_reference=ref)),
        "free_fall": ("free fall of the quill (chapter 5)", TorqueController(),
                      lambda plant, c: simulate(c, plant=plant, duration=0.5, q0=q_drop)),
        "computed_torque": ("computed torque (chapter 6)", ComputedTorqueController(),
                            lambda plant, c: simulate(c, traj, plant, joint_reference=ref)),
    }


def mujoco_agreement(traj=None, keys=None) -> dict:
    """MuJoCo as a fourth peer of the engine, per run of :func:`_agreement_runs` (plant: the book's arm with the
    5 kg payload):

    * ``rotor_free``: ``max |q_ours - q_mujoco|`` with ``I_m = 0`` in both (nothing approximated), against
      ``roundoff_bound = samples x 2^-53 x max |q|``: both integrate by the same classical RK4, one step per
      1 ms sample with the torque held, so the integrators' errors (of order ``h^4`` per step) are the same
      numbers and only round-off, at most one unit per step in the last place, can separate the runs;
    * with the book's rotors, which MuJoCo holds as armature: ``difference = max |q_ours - q_mujoco|``, the
      ``armature_effect = max |q_ours - q_less|`` of the same loop on our model less the coupling
      (:func:`coupling_free_closed_loop`), ``mujoco_vs_less`` (round-off again) and
      ``bound = armature_effect + roundoff_bound``;
    * ``euler_difference``: the rotor-free run again with MuJoCo's default integrator, semi-implicit Euler, in
      place of RK4: a first-order method, whose error per unit time is of order ``h`` (the bound the same-RK4
      comparison does without);
    * ``mujoco_seconds``, ``ours_seconds`` (CPU time of the two loops of the rotors-on run).
    """
    plant = ScaraParams().with_payload(5.0)
    bare = plant.replace(I_m=NO_ROTORS)
    out = {}
    for key, (title, controller, run) in _agreement_runs(traj).items():
        if keys is not None and key not in keys:
            continue
        free = run(bare, controller)
        mj_free = mujoco_closed_loop(controller, free, rotors=False)
        mj_euler = mujoco_closed_loop(controller, free, rotors=False, integrator="Euler")
        ours = run(plant, controller)
        mj = mujoco_closed_loop(controller, ours)
        less = coupling_free_closed_loop(controller, ours)
        n = len(ours.t)
        roundoff = n * UNIT_ROUNDOFF * float(np.max(np.abs(ours.q)))
        diff = np.max(np.abs(ours.q - mj["q"]), axis=0)
        arm = float(np.max(np.abs(ours.q - less["q"])))
        out[key] = dict(title=title, duration_s=float(ours.t[-1]), samples=n,
                        rotor_free=float(np.max(np.abs(free.q - mj_free["q"]))), roundoff_bound=roundoff,
                        euler_difference=float(np.max(np.abs(free.q - mj_euler["q"]))),
                        difference=float(diff.max()), difference_per_joint=diff.tolist(), armature_effect=arm,
                        mujoco_vs_less=float(np.max(np.abs(mj["q"] - less["q"]))), bound=arm + roundoff,
                        clipped=bool(mj["clipped"] or mj_free["clipped"]), mujoco_seconds=mj["seconds"],
                        ours_seconds=float(ours.elapsed))
    return out


if __name__ == "__main__":
    _print(all_agreement())
