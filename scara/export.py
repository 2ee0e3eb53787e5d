"""The arm in the field's file formats: URDF (RViz, MoveIt, Pinocchio) and MJCF (MuJoCo).

:func:`to_urdf` and :func:`to_mjcf` write any :class:`~scara.ScaraParams` (payload included) as text;
``python -m scara.export`` writes both files. The model is the one of chapters 1 and 5, and what the formats
cannot say about it is stated here, with its size:

* **Frames.** Each link's frame is its DH frame (chapter 1, (eq-dh-table)): ``link1`` .. ``link4`` are DH frames
  1 .. 4, ``frame0`` is DH frame 0 at ``A_0^b`` (z down, (eq-kin-base)) and ``base`` is the base frame. The tool
  frame is ``link4`` (``A_e^4 = I``). A URDF joint's frame is its child's frame, so joints 1 and 2, whose DH
  frames sit a link length away from their axes, turn the massless links ``turn1`` and ``turn2`` (frame
  ``i-1`` turned by ``theta_i``), which carry ``link1`` and ``link2`` at ``x = a_i`` on fixed joints. MJCF places a
  joint anywhere in its body, so there each body is its DH frame.
* **Joints.** The revolute joints turn freely (URDF ``continuous``, MJCF hinges without range); the quill
  slides along ``z_2`` within its stroke ``[d3_min, d3_max]``. URDF demands an effort and a velocity bound on the
  quill: the effort is chapter 6's actuator bound ``TAU_MAX``, the velocity :data:`QUILL_SPEED` m/s, which is not a
  property of the book's arm (no run of the book comes near it). MJCF's motors carry ``TAU_MAX`` as their
  control range.
* **Masses and inertias** (chapter 5, (eq-dynamics)): link i has ``m_li`` at ``l_i`` from joint i's axis and
  ``I_li`` about the vertical; the quill carries ``m_l3 + m_L`` on its axis and no moment; link 4 carries
  ``I_l4`` and no mass. Only vertical moments enter a SCARA's dynamics, so the horizontal ones are those of a thin
  disc, ``I_xx = I_yy = I_zz / 2``, a physical tensor (they change nothing). MuJoCo refuses a moving body without
  mass or moment; the MJCF asks its compiler to raise those to :data:`MJCF_FLOOR` (``boundmass``,
  ``boundinertia``), which moves ``B`` by at most ``2e-14`` and ``g`` by ``1e-13`` N.
* **Friction**: the viscous ``F = diag(k_r^2 F_m)`` as joint damping.
* **Rotors.** Chapter 5, (eq-dyn-rotors), lets rotor ``i`` turn with link ``i-1`` at ``omega_{i-1} + k_ri qd_i``.
  Neither format can hold that: MJCF has ``armature``, URDF has nothing, so the URDF writes the rotor in its
  transmission (``mechanicalReduction = k_r``, and Drake's ``rotor_inertia = I_m``, ``gear_ratio = k_r``, which
  Drake turns into the same armature). Both keep the reflected inertia ``k_ri^2 I_mi`` on joint i's diagonal
  and lose the constant :func:`rotor_coupling` ``Delta_B``: with the book's motors its largest entry is
  ``B13 = B23 = k_r3 I_m3 = 0.25`` kg m (next ``B14 = B24 = k_r4 I_m4 = 0.02`` kg m^2, ``B11 = 0.016``,
  ``B12 = 0.016``, ``B22 = 0.006``). Along the reference path with the 5 kg payload the torque it carries,
  ``Delta_B qdd``, reaches at most (0.0053 N m, 0.0054 N m, 0.018 N, 0.0015 N m), at most 1.3 % of the torque
  a joint needs (joint 2).
* **Not in either file**: the controllers, the sampling, and the contact of chapter 7. Gravity and the 1 ms time
  step are MJCF options; URDF has no gravity (the tools assume ``9.81`` down the base's z; the file states
  ``g0`` in a comment).
"""
from __future__ import annotations

import argparse
import math
import os
import re
import sys
import xml.etree.ElementTree as ET

import numpy as np

from .errors import ScaraError
from .params import ScaraParams

__all__ = ["to_urdf", "to_mjcf", "rotor_coupling", "link_inertials", "QUILL_SPEED", "MJCF_FLOOR", "main"]

#: The quill's velocity bound written in the URDF (m/s): URDF requires one, the book's arm has none.
QUILL_SPEED = 10.0
#: The smallest mass (kg) and moment (kg m^2) MuJoCo accepts here for a moving body (its own floor is 1e-15).
MJCF_FLOOR = 1e-14
#: Half the width of the links' boxes and the radii of the drawing's shapes (m).
_LINK_WIDTH = (0.10, 0.08)
_LINK_DEPTH = 0.06
_COLUMN_RADIUS = 0.07
_QUILL_RADIUS = 0.02
_FLANGE = (0.04, 0.02)
#: The colours of the book's drawing: the arm's grey ``scara.plots`` PALETTE["arm"], #4D4D4D, in the 0-1 RGBA the
#: formats take (written out here: the model's modules never import plotly; a test holds the two together), and a
#: lighter column.
_ARM_RGBA = (0.302, 0.302, 0.302, 1.0)
_BASE_RGBA = (0.6, 0.6, 0.6, 1.0)


def _num(x) -> str:
    """A float written so that it reads back exactly (the shortest repr)."""
    return repr(float(x))


def _vec(*xs) -> str:
    return " ".join(_num(x) for x in xs)


def _tau_max() -> tuple:
    from .control._common import TAU_MAX  # noqa: PLC0415 - the actuator bounds of chapter 6

    return tuple(float(t) for t in TAU_MAX)


def rotor_coupling(p: ScaraParams | None = None) -> np.ndarray:
    """``Delta_B`` (4, 4): the part of chapter 5's ``B`` ((eq-dyn-rotors)) that a rotor modelled as armature
    ``k_ri^2 I_mi`` on its own joint leaves out. Rotor i turns at ``omega_{i-1} + k_ri qd_i`` with ``omega_0 = 0``,
    ``omega_1 = qd1``, ``omega_2 = omega_3 = qd1 + qd2``, so its kinetic energy ``I_mi (omega_{i-1} + k_ri qd_i)^2 / 2``
    adds to ``B``, beyond that diagonal, ``I_mi`` on every ``B_jl`` with ``j, l`` among the joints that turn link
    ``i-1`` and ``k_ri I_mi`` on ``B_ji`` for those ``j``:

    ``Delta_B11 = I_m2 + I_m3 + I_m4``, ``Delta_B12 = k_r2 I_m2 + I_m3 + I_m4``, ``Delta_B22 = I_m3 + I_m4``,
    ``Delta_B13 = Delta_B23 = k_r3 I_m3``, ``Delta_B14 = Delta_B24 = k_r4 I_m4``, zero elsewhere.

    It does not depend on ``q``, so it adds nothing to ``C`` or ``g``; the tests check it against the rotors' part of
    :func:`~scara.dynamics.inertia_split`.

    >>> float(rotor_coupling()[0, 2])          # k_r3 I_m3 = 50 x 0.005
    0.25
    """
    p = ScaraParams.resolve(p)
    k, Im = p.k_r, p.I_m
    D = np.zeros((4, 4))
    D[0, 0] = Im[1] + Im[2] + Im[3]
    D[0, 1] = D[1, 0] = k[1] * Im[1] + Im[2] + Im[3]
    D[1, 1] = Im[2] + Im[3]
    D[0, 2] = D[2, 0] = D[1, 2] = D[2, 1] = k[2] * Im[2]
    D[0, 3] = D[3, 0] = D[1, 3] = D[3, 1] = k[3] * Im[3]
    return D


def link_inertials(p: ScaraParams | None = None) -> list[dict]:
    """The four links' inertial data as both files write them, each in its DH frame: ``mass`` (kg), ``com`` (3,)
    (m) and ``inertia`` (3,), the principal moments ``(I_xx, I_yy, I_zz)`` about the centre of mass (kg m^2).

    Link i's centre of mass is ``l_i`` from joint i's axis, so ``[l_i - a_i, 0, 0]`` in DH frame i; the quill
    carries ``m_l3 + m_L`` on its axis; link 4 has ``I_l4`` and no mass (chapter 5, (eq-dynamics))."""
    p = ScaraParams.resolve(p)

    def disc(izz):
        return (0.5 * izz, 0.5 * izz, float(izz))

    return [
        dict(mass=float(p.m_l1), com=(p.l1 - p.a1, 0.0, 0.0), inertia=disc(p.I_l1)),
        dict(mass=float(p.m_l2), com=(p.l2 - p.a2, 0.0, 0.0), inertia=disc(p.I_l2)),
        dict(mass=float(p.m3), com=(0.0, 0.0, 0.0), inertia=(0.0, 0.0, 0.0)),
        dict(mass=0.0, com=(0.0, 0.0, 0.0), inertia=disc(p.I_l4)),
    ]


def _shapes(p: ScaraParams) -> dict:
    """The drawing's shapes, per body, in its own frame: ``(kind, centre, size)`` with ``size`` the full lengths of a
    box, or ``(radius, length)`` of a cylinder along the frame's z. The column stands on the base up to frame 0;
    each link is a box from its joint's axis to the next; the quill is a cylinder as long as its stroke rising from
    the tool point; link 4 is a flange below it (every DH frame's z points down)."""
    stroke = p.d3_max - p.d3_min
    return {
        "base": [("cylinder", (0.0, 0.0, 0.5 * p.d0), (_COLUMN_RADIUS, p.d0))],
        "link1": [("box", (-0.5 * p.a1, 0.0, 0.0), (p.a1, _LINK_WIDTH[0], _LINK_DEPTH))],
        "link2": [("box", (-0.5 * p.a2, 0.0, 0.0), (p.a2, _LINK_WIDTH[1], _LINK_DEPTH))],
        "link3": [("cylinder", (0.0, 0.0, -0.5 * stroke), (_QUILL_RADIUS, stroke))],
        "link4": [("cylinder", (0.0, 0.0, 0.5 * _FLANGE[1]), _FLANGE)],
    }


_NAME = re.compile(r"[A-Za-z][A-Za-z0-9_-]{0,63}")


def _check(p, name: str) -> ScaraParams:
    """The arm (a :class:`~scara.ScaraParams` holds only valid arms) and a name fit for the files and the XML."""
    if not isinstance(name, str) or not _NAME.fullmatch(name):
        raise ScaraError(f"the model's name must be a letter followed by up to 63 letters, digits, '_' or '-' (it also "
                         f"names the files), got {name!r}")
    return ScaraParams.resolve(p)


def _xml(root: ET.Element, header: str) -> str:
    ET.indent(root, space="  ")
    return f'<?xml version="1.0"?>\n<!-- {header} -->\n' + ET.tostring(root, encoding="unicode") + "\n"


def _header(p: ScaraParams, fmt: str) -> str:
    return (f"The SCARA arm of the scara course book as {fmt}, written by scara.export: "
            f"payload m_L = {_num(p.m_L)} kg, "
            f"g0 = {_num(p.g0)} m/s^2 down the base's z. Rotors as armature k_r^2 I_m: the coupling "
            f"scara.export.rotor_coupling is left out.")


# ------------------------------------------------------------------------------------------------------
# URDF
# ------------------------------------------------------------------------------------------------------
def _urdf_shape(parent: ET.Element, tag: str, shape, material: str | None = None) -> None:
    kind, centre, size = shape
    el = ET.SubElement(parent, tag)
    ET.SubElement(el, "origin", xyz=_vec(*centre), rpy="0 0 0")
    geo = ET.SubElement(el, "geometry")
    if kind == "box":
        ET.SubElement(geo, "box", size=_vec(*size))
    else:
        ET.SubElement(geo, "cylinder", radius=_num(size[0]), length=_num(size[1]))
    if material is not None:
        ET.SubElement(el, "material", name=material)


def _urdf_link(robot, name, p, shapes, material, inertial=None):
    link = ET.SubElement(robot, "link", name=name)
    if inertial is not None:
        el = ET.SubElement(link, "inertial")
        ET.SubElement(el, "origin", xyz=_vec(*inertial["com"]), rpy="0 0 0")
        ET.SubElement(el, "mass", value=_num(inertial["mass"]))
        ixx, iyy, izz = inertial["inertia"]
        ET.SubElement(el, "inertia", ixx=_num(ixx), ixy="0", ixz="0", iyy=_num(iyy), iyz="0", izz=_num(izz))
    for shape in shapes.get(name, ()):
        _urdf_shape(link, "visual", shape, material)
        _urdf_shape(link, "collision", shape)
    return link


def _urdf_joint(robot, name, kind, parent, child, xyz=(0.0, 0.0, 0.0), rpy=(0.0, 0.0, 0.0), damping=None,
                limit=None):
    j = ET.SubElement(robot, "joint", name=name, type=kind)
    ET.SubElement(j, "parent", link=parent)
    ET.SubElement(j, "child", link=child)
    ET.SubElement(j, "origin", xyz=_vec(*xyz), rpy=_vec(*rpy))
    if kind != "fixed":
        ET.SubElement(j, "axis", xyz="0 0 1")
        ET.SubElement(j, "dynamics", damping=_num(damping), friction="0")
    if limit is not None:
        ET.SubElement(j, "limit", **{k: _num(v) for k, v in limit.items()})
    return j


def to_urdf(p: ScaraParams | None = None, name: str = "scara") -> str:
    """The arm ``p`` (default the book's, no payload) as URDF text: frames, joints, inertias, shapes, damping and
    the rotors in the transmissions, as the module's docstring states (with what URDF cannot say).

    Links ``base`` (the base frame), ``frame0``, ``turn1``, ``link1``, ``turn2``, ``link2``, ``link3``, ``link4``
    (DH frames; ``link4`` is the tool frame); joints ``joint1`` .. ``joint4`` (``continuous``, ``continuous``,
    ``prismatic`` along ``z_2`` with ``d3 = q3``, ``continuous``), each positive as in chapter 1.
    """
    p = _check(p, name)
    tau_max = _tau_max()
    inertials = link_inertials(p)
    shapes = _shapes(p)
    F = p.F
    robot = ET.Element("robot", {"name": name, "xmlns:drake": "http://drake.mit.edu"})
    for mat, rgba in (("arm", _ARM_RGBA), ("column", _BASE_RGBA)):
        ET.SubElement(ET.SubElement(robot, "material", name=mat), "color", rgba=_vec(*rgba))
    _urdf_link(robot, "base", p, shapes, "column")
    _urdf_joint(robot, "base_to_frame0", "fixed", "base", "frame0", xyz=(0.0, 0.0, p.d0), rpy=(math.pi, 0.0, 0.0))
    _urdf_link(robot, "frame0", p, shapes, "arm")
    parent = "frame0"
    for i, a in ((1, p.a1), (2, p.a2)):
        _urdf_joint(robot, f"joint{i}", "continuous", parent, f"turn{i}", damping=F[i - 1])
        _urdf_link(robot, f"turn{i}", p, shapes, "arm")
        _urdf_joint(robot, f"turn{i}_to_link{i}", "fixed", f"turn{i}", f"link{i}", xyz=(a, 0.0, 0.0))
        _urdf_link(robot, f"link{i}", p, shapes, "arm", inertials[i - 1])
        parent = f"link{i}"
    _urdf_joint(robot, "joint3", "prismatic", "link2", "link3", damping=F[2],
                limit=dict(lower=p.d3_min, upper=p.d3_max, effort=tau_max[2], velocity=QUILL_SPEED))
    _urdf_link(robot, "link3", p, shapes, "arm", inertials[2])
    _urdf_joint(robot, "joint4", "continuous", "link3", "link4", damping=F[3])
    _urdf_link(robot, "link4", p, shapes, "arm", inertials[3])
    for i in range(4):
        tr = ET.SubElement(robot, "transmission", name=f"transmission{i + 1}")
        ET.SubElement(tr, "type").text = "transmission_interface/SimpleTransmission"
        j = ET.SubElement(tr, "joint", name=f"joint{i + 1}")
        ET.SubElement(j, "hardwareInterface").text = "hardware_interface/EffortJointInterface"
        act = ET.SubElement(tr, "actuator", name=f"motor{i + 1}")
        ET.SubElement(act, "mechanicalReduction").text = _num(p.k_r[i])
        ET.SubElement(act, "drake:rotor_inertia", value=_num(p.I_m[i]))
        ET.SubElement(act, "drake:gear_ratio", value=_num(p.k_r[i]))
    return _xml(robot, _header(p, "URDF"))


# ------------------------------------------------------------------------------------------------------
# MJCF
# ------------------------------------------------------------------------------------------------------
def _mjcf_geoms(body: ET.Element, shapes, material: str) -> None:
    for kind, centre, size in shapes:
        half = [0.5 * s for s in size] if kind == "box" else [size[0], 0.5 * size[1]]
        # contype 1, conaffinity 0: the arm's parts never touch each other, and touch what a user adds
        ET.SubElement(body, "geom", type=kind, pos=_vec(*centre), size=_vec(*half), material=material,
                      contype="1", conaffinity="0")


def _mjcf_inertial(body: ET.Element, inertial: dict) -> None:
    ET.SubElement(body, "inertial", pos=_vec(*inertial["com"]), mass=_num(inertial["mass"]),
                  diaginertia=_vec(*inertial["inertia"]))


def to_mjcf(p: ScaraParams | None = None, name: str = "scara") -> str:
    """The arm ``p`` (default the book's, no payload) as MJCF text for MuJoCo: bodies in the DH frames, hinge and
    slide joints with damping ``F`` and armature ``k_r^2 I_m``, inertias, shapes, a motor per joint (gear 1,
    control range ``TAU_MAX``), gravity ``g0`` and the book's 1 ms step with MuJoCo's RK4 integrator, as the
    module's docstring states (with what MJCF cannot say).

    ``qpos`` is ``q`` of chapter 1 (``d3`` for the quill) and ``ctrl`` the joint torques ``tau``.
    """
    p = _check(p, name)
    tau_max = _tau_max()
    inertials = link_inertials(p)
    shapes = _shapes(p)
    F = p.F
    armature = np.asarray(p.k_r) ** 2 * np.asarray(p.I_m)
    root = ET.Element("mujoco", model=name)
    ET.SubElement(root, "compiler", angle="radian", autolimits="true", inertiafromgeom="false",
                  boundmass=_num(MJCF_FLOOR), boundinertia=_num(MJCF_FLOOR))
    ET.SubElement(root, "option", timestep="0.001", integrator="RK4", gravity=_vec(0.0, 0.0, -p.g0))
    asset = ET.SubElement(root, "asset")
    for mat, rgba in (("arm", _ARM_RGBA), ("column", _BASE_RGBA)):
        ET.SubElement(asset, "material", name=mat, rgba=_vec(*rgba))
    world = ET.SubElement(root, "worldbody")
    base = ET.SubElement(world, "body", name="base")
    _mjcf_geoms(base, shapes["base"], "column")
    body = ET.SubElement(base, "body", name="frame0", pos=_vec(0.0, 0.0, p.d0), quat="0 1 0 0")  # A_0^b: x turned by pi
    offsets = (p.a1, p.a2, 0.0, 0.0)
    kinds = ("hinge", "hinge", "slide", "hinge")
    for i in range(4):
        body = ET.SubElement(body, "body", name=f"link{i + 1}")
        joint = dict(name=f"joint{i + 1}", type=kinds[i], axis="0 0 1", damping=_num(F[i]), armature=_num(armature[i]))
        if offsets[i]:  # DH frame i sits a_i along x from joint i's axis
            body.set("pos", _vec(offsets[i], 0.0, 0.0))
            joint["pos"] = _vec(-offsets[i], 0.0, 0.0)
        if i == 2:
            joint["range"] = _vec(p.d3_min, p.d3_max)
        ET.SubElement(body, "joint", **joint)
        _mjcf_inertial(body, inertials[i])
        _mjcf_geoms(body, shapes[f"link{i + 1}"], "arm")
    ET.SubElement(body, "site", name="tool", pos="0 0 0", size="0.01")
    act = ET.SubElement(root, "actuator")
    for i in range(4):
        ET.SubElement(act, "motor", name=f"motor{i + 1}", joint=f"joint{i + 1}", gear="1",
                      ctrlrange=_vec(-tau_max[i], tau_max[i]))
    return _xml(root, _header(p, "MJCF"))


# ------------------------------------------------------------------------------------------------------
# the command
# ------------------------------------------------------------------------------------------------------
def main(argv=None) -> int:
    """``python -m scara.export [--out DIR] [--payload KG] [--name NAME]``: write ``NAME.urdf`` and ``NAME.xml``
    (MJCF) of the book's arm, with the payload given, into ``DIR``. Returns 0; a bad value prints its message and
    returns 2."""
    ap = argparse.ArgumentParser(prog="python -m scara.export", description="Write the SCARA arm of the course as "
                                 "URDF and MJCF (MuJoCo).")
    ap.add_argument("--out", default=".", help="folder to write into (default: here)")
    ap.add_argument("--payload", type=float, default=0.0, help="payload on the quill, kg (default 0)")
    ap.add_argument("--name", default="scara", help="model and file name (default scara)")
    args = ap.parse_args(argv)
    try:
        p = ScaraParams().with_payload(args.payload)
        texts = {f"{args.name}.urdf": to_urdf(p, args.name), f"{args.name}.xml": to_mjcf(p, args.name)}
        os.makedirs(args.out, exist_ok=True)
    except (ScaraError, OSError) as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 2
    for fname, text in texts.items():
        path = os.path.join(args.out, fname)
        with open(path, "w", encoding="utf-8") as fh:
            fh.write(text)
        print(f"wrote {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
