"""The book's robot (its data on book/intro.md) built in the libraries a student would reach for, plus a
plain-numpy twin.

Three builders, each from one :class:`scara.ScaraParams`:

* :func:`toolbox_robot` - Peter Corke's Robotics Toolbox for Python (``roboticstoolbox-python``): a
  ``DHRobot`` of standard-DH links (chapter 1, section The DH table) with the base transform ``A_0^b``, link
  masses, centres of mass, inertia tensors and the toolbox's motor model (``Jm`` rotor inertia, ``G`` gear ratio,
  ``B`` viscous friction at the motor, no Coulomb friction).
* :func:`pinocchio_model` - Pinocchio (``pin``): a model built in code, joint by joint, with the same
  frames and inertias; the reflected rotor inertia ``k_r^2 I_m`` goes in ``model.armature``.
* :class:`NumpyRobot` - the book's closed forms (chapters 1 and 5) written the ordinary way, with numpy arrays
  built per call: the baseline a student writes before thinking about speed.

Frames and conventions (shared by all three):

* Every DH frame has its z axis pointing down (``A_0^b`` turns z over, all ``alpha_i = 0``). Joint i
  turns about, or slides along, ``z_{i-1}``.
* Link 1 runs from the joint-1 axis (frame 0) to frame 1 along ``x_1``; its centre of mass is ``l1`` from
  the joint-1 axis, that is ``r_1 = [l1 - a1, 0, 0]`` in frame 1 (the toolbox measures the centre of mass
  in the link's own DH frame) and ``[l1, 0, 0]`` in Pinocchio's joint-1 frame (a joint frame sits on its
  axis). Link 2 likewise. The quill (link 3, mass ``m_l3`` plus any payload ``m_L``) has its centre of
  mass on the joint-3/4 axis; link 4 has no mass and the inertia ``I_l4`` about its axis.
* Only the vertical moment of inertia enters a SCARA's dynamics (every angular velocity is vertical).
  The horizontal moments are set to those of a thin horizontal disc, ``Ixx = Iyy = Izz / 2``, a physical
  tensor; the agreement tests show they change nothing.
* Rotors: the libraries model each rotor by its reflected inertia on the diagonal only,
  ``k_ri^2 I_mi``. Chapter 5, (eq-dyn-rotors) (as in Siciliano et al. 2009, ch. 7), also lets rotor i turn
  with link i-1, which adds constant off-diagonal and upper-diagonal terms (see ``agreement.rotor_coupling``).

Nothing in ``scara`` imports this module; it needs the optional extras of ``requirements-bench.txt``.
"""
from __future__ import annotations

import math

import numpy as np

from scara import ScaraParams

__all__ = [
    "BASE_TRANSFORM",
    "toolbox_robot",
    "pinocchio_model",
    "NumpyRobot",
    "reflected_rotor_inertia",
]


def _params(p):
    return ScaraParams() if p is None else p


def BASE_TRANSFORM(p: ScaraParams | None = None) -> np.ndarray:
    """``A_0^b`` of chapter 1, (eq-kin-base): frame 0 at height ``d0`` with its z axis pointing down."""
    p = _params(p)
    return np.array([[1.0, 0, 0, 0], [0, -1.0, 0, 0], [0, 0, -1.0, p.d0], [0, 0, 0, 1.0]])


def reflected_rotor_inertia(p: ScaraParams | None = None, rotors: bool = True) -> np.ndarray:
    """Diagonal ``k_ri^2 I_mi`` (kg m^2, kg for the prismatic joint): all that the libraries model of a rotor."""
    p = _params(p)
    if not rotors:
        return np.zeros(4)
    return np.asarray(p.k_r) ** 2 * np.asarray(p.I_m)


def _disc(Izz: float, horizontal: float = 0.5) -> np.ndarray:
    """Inertia tensor ``diag(h Izz, h Izz, Izz)``; ``h = 1/2`` is a thin horizontal disc (kg m^2)."""
    return np.diag([horizontal * Izz, horizontal * Izz, Izz])


# ------------------------------------------------------------------------------------------------------
# Peter Corke's Robotics Toolbox for Python
# ------------------------------------------------------------------------------------------------------
def toolbox_robot(p: ScaraParams | None = None, rotors: bool = True, friction: bool = True,
                  horizontal: float = 0.5):
    """The book's robot as a ``roboticstoolbox.DHRobot`` (standard DH, base ``A_0^b``, gravity ``-z`` of base).

    Parameters
    ----------
    p : ScaraParams, optional
        The robot (None: the table of book/intro.md, no payload). The payload ``m_L`` rides on the quill (link 3).
    rotors : bool
        Set the toolbox's rotor inertia ``Jm = I_m`` and gear ratio ``G = k_r``; the toolbox then adds
        ``G^2 Jm qdd`` at each joint. With False, ``Jm = 0``.
    friction : bool
        Viscous friction at the motor ``B = F_m``; the toolbox refers it to the joint as ``G^2 B``, which is
        ``F`` of chapter 5, (eq-dynamics).
    horizontal : float
        Horizontal moments of inertia of links 1, 2, 4 as a multiple of the vertical one (they must not
        matter; the tests vary it).
    """
    import roboticstoolbox as rtb
    from spatialmath import SE3

    p = _params(p)
    k = p.k_r
    Jm = p.I_m if rotors else (0.0, 0.0, 0.0, 0.0)
    B = p.F_m if friction else (0.0, 0.0, 0.0, 0.0)
    common = [dict(Jm=Jm[i], G=k[i], B=B[i], Tc=[0.0, 0.0]) for i in range(4)]
    links = [
        rtb.RevoluteDH(a=p.a1, alpha=0.0, d=0.0, m=p.m_l1, r=[p.l1 - p.a1, 0.0, 0.0], I=_disc(p.I_l1, horizontal),
                       **common[0]),
        rtb.RevoluteDH(a=p.a2, alpha=0.0, d=0.0, m=p.m_l2, r=[p.l2 - p.a2, 0.0, 0.0], I=_disc(p.I_l2, horizontal),
                       **common[1]),
        rtb.PrismaticDH(a=0.0, alpha=0.0, theta=0.0, m=p.m3, r=[0.0, 0.0, 0.0], I=np.zeros((3, 3)),
                        qlim=[0.0, p.d0], **common[2]),
        rtb.RevoluteDH(a=0.0, alpha=0.0, d=0.0, m=0.0, r=[0.0, 0.0, 0.0], I=_disc(p.I_l4, horizontal), **common[3]),
    ]
    return rtb.DHRobot(links, name="SCARA (scara book)", base=SE3(BASE_TRANSFORM(p), check=False),
                       gravity=[0.0, 0.0, -p.g0])


# ------------------------------------------------------------------------------------------------------
# Pinocchio
# ------------------------------------------------------------------------------------------------------
def pinocchio_model(p: ScaraParams | None = None, rotors: bool = True, horizontal: float = 0.5):
    """The book's robot as a ``pinocchio.Model`` built in code: joints RZ, RZ, PZ, RZ.

    Joint 1 is placed at ``A_0^b``; joint i+1 at ``x = a_i`` of joint i's frame (the DH translation), so
    that joint i's frame after its motion is DH frame i-1 turned by ``theta_i`` (or moved by ``d_i``), and
    DH frame i is that frame shifted by ``a_i`` along x. The end-effector frame ``"ee"`` sits on joint 4
    (``A_e^4 = I``). Gravity is ``[0, 0, -g0]`` in the world (= base) frame. With ``rotors``,
    ``model.armature = k_r^2 I_m`` (what ``rnea``, ``crba`` and ``aba`` add on the diagonal). Friction is
    not part of a Pinocchio model here; loops subtract ``F qd`` themselves. ``horizontal`` as in
    :func:`toolbox_robot`.

    Returns ``(model, data)``.
    """
    import pinocchio as pin

    p = _params(p)
    model = pin.Model()
    model.name = "scara_book"
    A0 = BASE_TRANSFORM(p)
    placements = [
        pin.SE3(A0[:3, :3].copy(), A0[:3, 3].copy()),
        pin.SE3(np.eye(3), np.array([p.a1, 0.0, 0.0])),
        pin.SE3(np.eye(3), np.array([p.a2, 0.0, 0.0])),
        pin.SE3.Identity(),
    ]
    joints = [pin.JointModelRZ(), pin.JointModelRZ(), pin.JointModelPZ(), pin.JointModelRZ()]
    inertias = [
        pin.Inertia(p.m_l1, np.array([p.l1, 0.0, 0.0]), _disc(p.I_l1, horizontal)),
        pin.Inertia(p.m_l2, np.array([p.l2, 0.0, 0.0]), _disc(p.I_l2, horizontal)),
        pin.Inertia(p.m3, np.zeros(3), np.zeros((3, 3))),
        pin.Inertia(0.0, np.zeros(3), _disc(p.I_l4, horizontal)),
    ]
    parent = 0
    for i in range(4):
        parent = model.addJoint(parent, joints[i], placements[i], f"joint{i + 1}")
        jframe = model.addJointFrame(parent, -1)
        model.appendBodyToJoint(parent, inertias[i], pin.SE3.Identity())
        model.addBodyFrame(f"link{i + 1}", parent, pin.SE3.Identity(), jframe)
    model.addFrame(pin.Frame("ee", parent, model.getFrameId("link4"), pin.SE3.Identity(), pin.FrameType.OP_FRAME))
    model.gravity = pin.Motion(np.array([0.0, 0.0, -p.g0]), np.zeros(3))
    model.armature = reflected_rotor_inertia(p, rotors)
    model.lowerPositionLimit = np.array([-math.pi, -math.pi, 0.0, -math.pi]) * 4
    model.upperPositionLimit = np.array([math.pi, math.pi, p.d0, math.pi]) * 4
    return model, model.createData()


# ------------------------------------------------------------------------------------------------------
# plain numpy
# ------------------------------------------------------------------------------------------------------
class NumpyRobot:
    """The book's closed forms (chapter 1, (eq-fk) and (eq-jacobian); chapter 5, (eq-dynamics) with the rotor
    coupling of (eq-dyn-rotors)) in plain numpy.

    Each call builds its arrays with ``np.array``/``np.zeros`` and solves with ``np.linalg``: the code a
    student writes first. Written here from those equations, independently of ``scara``; the agreement tests compare
    it with ``scara`` too.
    """

    def __init__(self, p: ScaraParams | None = None):
        p = _params(p)
        self.p = p
        self.F = np.asarray(p.F)
        k, Im = np.asarray(p.k_r), np.asarray(p.I_m)
        self.k, self.Im = k, Im

    def pose(self, q):
        p = self.p
        t12 = q[0] + q[1]
        return np.array([p.a1 * np.cos(q[0]) + p.a2 * np.cos(t12), -(p.a1 * np.sin(q[0]) + p.a2 * np.sin(t12)),
                         p.d0 - q[2], t12 + q[3]])

    def fkine(self, q):
        x = self.pose(q)
        c, s = np.cos(x[3]), np.sin(x[3])
        return np.array([[c, -s, 0.0, x[0]], [-s, -c, 0.0, x[1]], [0.0, 0.0, -1.0, x[2]], [0.0, 0.0, 0.0, 1.0]])

    def jacobian(self, q):
        p = self.p
        s1, c1, s12, c12 = np.sin(q[0]), np.cos(q[0]), np.sin(q[0] + q[1]), np.cos(q[0] + q[1])
        return np.array([[-(p.a1 * s1 + p.a2 * s12), -p.a2 * s12, 0.0, 0.0],
                         [-(p.a1 * c1 + p.a2 * c12), -p.a2 * c12, 0.0, 0.0],
                         [0.0, 0.0, -1.0, 0.0],
                         [1.0, 1.0, 0.0, 1.0]])

    def inertia(self, q):
        p, k, Im = self.p, self.k, self.Im
        c2 = np.cos(q[1])
        m3 = p.m3
        B = np.zeros((4, 4))
        B[0, 0] = (p.I_l1 + p.m_l1 * p.l1 ** 2 + k[0] ** 2 * Im[0] + p.I_l2
                   + p.m_l2 * (p.a1 ** 2 + p.l2 ** 2 + 2 * p.a1 * p.l2 * c2)
                   + m3 * (p.a1 ** 2 + p.a2 ** 2 + 2 * p.a1 * p.a2 * c2) + p.I_l4 + Im[1] + Im[2] + Im[3])
        B[0, 1] = (p.I_l2 + p.m_l2 * (p.l2 ** 2 + p.a1 * p.l2 * c2) + m3 * (p.a2 ** 2 + p.a1 * p.a2 * c2)
                   + p.I_l4 + k[1] * Im[1] + Im[2] + Im[3])
        B[1, 1] = p.I_l2 + p.m_l2 * p.l2 ** 2 + m3 * p.a2 ** 2 + p.I_l4 + k[1] ** 2 * Im[1] + Im[2] + Im[3]
        B[0, 2] = B[1, 2] = k[2] * Im[2]
        B[2, 2] = m3 + k[2] ** 2 * Im[2]
        B[0, 3] = B[1, 3] = p.I_l4 + k[3] * Im[3]
        B[3, 3] = p.I_l4 + k[3] ** 2 * Im[3]
        return np.triu(B) + np.triu(B, 1).T

    def coriolis(self, q, qd):
        """Christoffel C: only ``B11``, ``B12`` depend on ``q`` (through ``theta2``), so
        ``h = -a1 (m_l2 l2 + m3 a2) s2`` and ``C = [[h qd2, h (qd1 + qd2), 0, 0], [-h qd1, 0, 0, 0], 0, 0]``."""
        p = self.p
        h = -p.a1 * (p.m_l2 * p.l2 + p.m3 * p.a2) * np.sin(q[1])
        C = np.zeros((4, 4))
        C[0, 0] = h * qd[1]
        C[0, 1] = h * (qd[0] + qd[1])
        C[1, 0] = -h * qd[0]
        return C

    def gravity(self, q):
        return np.array([0.0, 0.0, -self.p.m3 * self.p.g0, 0.0])

    def rne(self, q, qd, qdd):
        """Inverse dynamics ``tau = B qdd + C qd + F qd + g``."""
        return self.inertia(q) @ qdd + self.coriolis(q, qd) @ qd + self.F * qd + self.gravity(q)

    def accel(self, q, qd, tau):
        """Forward dynamics ``qdd = B^-1 (tau - C qd - F qd - g)``."""
        return np.linalg.solve(self.inertia(q), tau - self.coriolis(q, qd) @ qd - self.F * qd - self.gravity(q))


# ------------------------------------------------------------------------------------------------------
# the exported files (scara.export), loaded by the tools they are for
# ------------------------------------------------------------------------------------------------------
def _exported(p, rotors: bool) -> ScaraParams:
    """The arm an export writes: ``p`` (default the book's), with ``I_m = 0`` when ``rotors`` is False."""
    p = _params(p)
    return p if rotors else p.replace(I_m=(0.0, 0.0, 0.0, 0.0))


def urdf_armature(urdf: str) -> np.ndarray:
    """The reflected rotor inertia a URDF written by ``scara.export.to_urdf`` states in its transmissions,
    ``gear_ratio^2 rotor_inertia`` per joint (Drake's reading of them), read back from the text."""
    import xml.etree.ElementTree as ET

    ns = {"drake": "http://drake.mit.edu"}
    out = []
    for tr in ET.fromstring(urdf).findall("transmission"):
        act = tr.find("actuator")
        k = float(act.find("drake:gear_ratio", ns).get("value"))
        Im = float(act.find("drake:rotor_inertia", ns).get("value"))
        out.append(k * k * Im)
    return np.array(out)


def pinocchio_from_urdf(p: ScaraParams | None = None, rotors: bool = True):
    """Pinocchio's model of ``scara.export.to_urdf(p)`` (``buildModelFromXML``), gravity ``-g0`` along the base z
    (URDF holds none) and the armature its transmissions state. With ``rotors=False`` the exported arm has
    ``I_m = 0``. Continuous joints become Pinocchio's unbounded revolute joints (``nq = 2``: ``cos, sin``);
    :func:`pinocchio_configuration` maps ``q`` to them. Returns ``(model, data)``."""
    import pinocchio as pin

    from scara.export import to_urdf

    p = _exported(p, rotors)
    text = to_urdf(p)
    model = pin.buildModelFromXML(text)
    model.gravity = pin.Motion(np.array([0.0, 0.0, -p.g0]), np.zeros(3))
    model.armature = urdf_armature(text)
    return model, model.createData()


def pinocchio_configuration(model, q) -> np.ndarray:
    """``q`` (4,) of chapter 1 as the configuration vector of ``model`` (unbounded joints as ``cos, sin``)."""
    out = []
    for j, qj in zip(model.joints[1:], q):
        out.extend((math.cos(qj), math.sin(qj)) if j.nq == 2 else (qj,))
    return np.array(out)


def mujoco_model(p: ScaraParams | None = None, rotors: bool = True):
    """MuJoCo's model of ``scara.export.to_mjcf(p)`` (``MjModel.from_xml_string``); ``rotors=False`` exports the
    arm with ``I_m = 0``. Returns ``(model, data)``."""
    import mujoco

    from scara.export import to_mjcf

    p = _exported(p, rotors)
    model = mujoco.MjModel.from_xml_string(to_mjcf(p))
    return model, mujoco.MjData(model)
