"""scara.export without the tools it exports for: the files parse, hold the model's numbers exactly, chain the
DH frames (a small URDF reader written here from the URDF specification gives ``fkine``), state what they lose,
and the command writes both files and refuses bad values with a message.

The libraries' own reading of the files (Pinocchio, MuJoCo) is tests/agreement/test_exported_files.py (optional extras).
"""
from __future__ import annotations

import math
import subprocess
import sys
import xml.etree.ElementTree as ET

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from scara import ScaraError, ScaraParams, fkine, link_frames
from scara import export as ex
from scara.control import TAU_MAX
from scara.dynamics import inertia, inertia_split, inverse_dynamics

DRAKE = "{http://drake.mit.edu}"


def _floats(text: str) -> list[float]:
    return [float(v) for v in text.split()]


# ------------------------------------------------------------------------------------------------------
# a URDF reader from the specification: T_child = T_parent * origin * motion(q) about/along the axis
# ------------------------------------------------------------------------------------------------------
def _rpy(r, p, y):
    cr, sr, cp, sp, cy, sy = math.cos(r), math.sin(r), math.cos(p), math.sin(p), math.cos(y), math.sin(y)
    Rx = np.array([[1, 0, 0], [0, cr, -sr], [0, sr, cr]])
    Ry = np.array([[cp, 0, sp], [0, 1, 0], [-sp, 0, cp]])
    Rz = np.array([[cy, -sy, 0], [sy, cy, 0], [0, 0, 1]])
    return Rz @ Ry @ Rx


def _urdf_link_poses(text: str, q) -> dict:
    root = ET.fromstring(text)
    joints = {j.find("child").get("link"): j for j in root.findall("joint")}
    values = {f"joint{i + 1}": q[i] for i in range(4)}
    poses = {}

    def pose(link):
        if link in poses:
            return poses[link]
        if link not in joints:
            poses[link] = np.eye(4)
            return poses[link]
        j = joints[link]
        origin = j.find("origin")
        T = np.eye(4)
        T[:3, :3] = _rpy(*_floats(origin.get("rpy")))
        T[:3, 3] = _floats(origin.get("xyz"))
        M = np.eye(4)
        if j.get("type") != "fixed":
            axis = np.array(_floats(j.find("axis").get("xyz")))
            v = values[j.get("name")]
            if j.get("type") == "prismatic":
                M[:3, 3] = v * axis
            else:
                assert np.array_equal(axis, [0, 0, 1])
                M[:2, :2] = [[math.cos(v), -math.sin(v)], [math.sin(v), math.cos(v)]]
        poses[link] = pose(j.find("parent").get("link")) @ T @ M
        return poses[link]

    for link in root.findall("link"):
        pose(link.get("name"))
    return poses


@settings(max_examples=60, deadline=None)
@given(st.lists(st.floats(-math.pi, math.pi), min_size=4, max_size=4), st.floats(0.0, 1.0))
def test_urdf_chains_the_dh_frames(q, d3):
    """The URDF's links are chapter 1's DH frames: link i at T_i^b = A_0^b A_1^0 ... A_i^{i-1} (link4 = T_e^b)."""
    q = np.array([q[0], q[1], d3, q[3]])
    poses = _urdf_link_poses(ex.to_urdf(), q)
    frames = link_frames(q)
    for i, name in enumerate(("frame0", "link1", "link2", "link3", "link4")):
        assert np.max(np.abs(poses[name] - frames[i])) < 1e-14, name
    assert np.max(np.abs(poses["link4"] - fkine(q))) < 1e-14


def test_urdf_holds_the_models_numbers_exactly():
    p = ScaraParams().with_payload(5.0)
    root = ET.fromstring(ex.to_urdf(p))
    links = {link.get("name"): link for link in root.findall("link")}
    for i, want in enumerate(ex.link_inertials(p)):
        el = links[f"link{i + 1}"].find("inertial")
        assert float(el.find("mass").get("value")) == want["mass"]
        assert _floats(el.find("origin").get("xyz")) == list(want["com"])
        I = el.find("inertia")
        assert [float(I.get(k)) for k in ("ixx", "iyy", "izz")] == list(want["inertia"])
        assert all(float(I.get(k)) == 0.0 for k in ("ixy", "ixz", "iyz"))
    assert float(links["link3"].find("inertial/mass").get("value")) == p.m_l3 + p.m_L == 15.0
    assert [float(links[f"link{i}"].find("inertial/origin").get("xyz").split()[0]) for i in (1, 2)] == [
        p.l1 - p.a1, p.l2 - p.a2]
    joints = {j.get("name"): j for j in root.findall("joint")}
    assert [joints[f"joint{i}"].get("type") for i in range(1, 5)] == ["continuous", "continuous", "prismatic",
                                                                      "continuous"]
    for i in range(4):
        assert float(joints[f"joint{i + 1}"].find("dynamics").get("damping")) == p.F[i]
    lim = joints["joint3"].find("limit")
    assert (float(lim.get("lower")), float(lim.get("upper"))) == (p.d3_min, p.d3_max)
    assert float(lim.get("effort")) == TAU_MAX[2] and float(lim.get("velocity")) == ex.QUILL_SPEED
    for i, tr in enumerate(root.findall("transmission")):
        act = tr.find("actuator")
        assert float(act.find("mechanicalReduction").text) == p.k_r[i]
        assert float(act.find(f"{DRAKE}rotor_inertia").get("value")) == p.I_m[i]
        assert float(act.find(f"{DRAKE}gear_ratio").get("value")) == p.k_r[i]
    # every link the drawing shows has a visual and a collision shape
    for name in ("base", "link1", "link2", "link3", "link4"):
        assert links[name].find("visual") is not None and links[name].find("collision") is not None, name


def test_mjcf_holds_the_models_numbers_exactly():
    p = ScaraParams().with_payload(7.5)
    root = ET.fromstring(ex.to_mjcf(p))
    opt = root.find("option")
    assert (opt.get("timestep"), opt.get("integrator")) == ("0.001", "RK4")
    assert _floats(opt.get("gravity")) == [0.0, 0.0, -p.g0]
    comp = root.find("compiler")
    assert float(comp.get("boundmass")) == float(comp.get("boundinertia")) == ex.MJCF_FLOOR
    bodies = {b.get("name"): b for b in root.iter("body")}
    assert bodies["frame0"].get("quat") == "0 1 0 0" and _floats(bodies["frame0"].get("pos")) == [0, 0, p.d0]
    armature = np.asarray(p.k_r) ** 2 * np.asarray(p.I_m)
    for i, want in enumerate(ex.link_inertials(p)):
        b = bodies[f"link{i + 1}"]
        el = b.find("inertial")
        assert float(el.get("mass")) == want["mass"]
        assert _floats(el.get("pos")) == list(want["com"])
        assert _floats(el.get("diaginertia")) == list(want["inertia"])
        j = b.find("joint")
        assert j.get("name") == f"joint{i + 1}"
        assert float(j.get("damping")) == p.F[i] and float(j.get("armature")) == armature[i]
        # the body is DH frame i; the joint sits on its axis, a_i back along x
        a = (p.a1, p.a2, 0.0, 0.0)[i]
        assert _floats(b.get("pos", "0 0 0")) == [a, 0.0, 0.0]
        assert _floats(j.get("pos", "0 0 0")) == [-a, 0.0, 0.0]
    assert _floats(bodies["link3"].find("joint").get("range")) == [p.d3_min, p.d3_max]
    motors = root.findall("actuator/motor")
    assert [_floats(m.get("ctrlrange")) for m in motors] == [[-t, t] for t in TAU_MAX]


def test_what_the_formats_lose_is_the_rotor_coupling():
    """The coupling equals the written-out entries of chapter 5's rotors, and the docstring's sizes are the model's."""
    p = ScaraParams(k_r=(3.0, 7.0, 40.0, 11.0), I_m=(0.02, 0.03, 0.004, 0.002))  # distinct numbers
    k, Im = p.k_r, p.I_m
    D = ex.rotor_coupling(p)
    # the rotors' part of B, from scara.dynamics.inertia_split, less the armature diagonal
    rotors = inertia_split(np.zeros(4), p)["rotors"]
    assert np.max(np.abs(D - (rotors - np.diag(np.asarray(k) ** 2 * np.asarray(Im))))) < 1e-13
    assert D[2, 3] == D[2, 2] == D[3, 3] == 0.0 and np.array_equal(D, D.T)
    # B with the rotors as armature only is B less the coupling, at any configuration
    q = np.array([0.2, 1.3, 0.4, -0.5])
    bare = inertia(q, p.replace(I_m=(0.0, 0.0, 0.0, 0.0)))
    assert np.max(np.abs(inertia(q, p) - D - bare - np.diag(np.asarray(k) ** 2 * np.asarray(Im)))) < 1e-13
    doc = ex.__doc__
    D = ex.rotor_coupling(ScaraParams())
    assert f"k_r3 I_m3 = {D[0, 2]:.2f}" in doc and f"k_r4 I_m4 = {D[0, 3]:.2f}" in doc
    assert f"B11 = {D[0, 0]:.3f}" in doc and f"B12 = {D[0, 1]:.3f}" in doc and f"B22 = {D[1, 1]:.3f}" in doc


def test_docstrings_sizes_along_the_reference_path():
    """The torque the coupling carries along the reference path with 5 kg, as the module docstring states it."""
    from scara import ikine_reference
    from scara.trajectory import reference_trajectory

    p = ScaraParams().with_payload(5.0)
    ref = ikine_reference(reference_trajectory(), p)
    q, qd, qdd = ref[:, :4], ref[:, 4:8], ref[:, 8:12]
    dtau = np.abs(qdd @ ex.rotor_coupling(p).T).max(axis=0)
    share = dtau / np.abs(inverse_dynamics(q, qd, qdd, p)).max(axis=0)
    text = " ".join(ex.__doc__.split())
    stated = f"({dtau[0]:.2g} N m, {dtau[1]:.2g} N m, {dtau[2]:.2g} N, {dtau[3]:.2g} N m)"
    assert stated in text, stated
    assert f"at most {100 * share.max():.1f} % of the torque a joint needs (joint {int(np.argmax(share)) + 1})" in text


def test_bad_arms_are_refused_with_the_value():
    with pytest.raises(ScaraError, match="ScaraParams"):
        ex.to_urdf("the book's arm")
    with pytest.raises(ScaraError, match="ScaraParams"):
        ex.to_mjcf(42)
    with pytest.raises(ScaraError, match="name"):
        ex.to_urdf(name="../escape")


def test_the_files_do_not_depend_on_the_caller_keeping_anything():
    """Same arm, same text (no memory, no clock), and the default is the book's arm without payload."""
    assert ex.to_urdf() == ex.to_urdf(ScaraParams())
    assert ex.to_mjcf(ScaraParams().with_payload(3.0)) == ex.to_mjcf(ScaraParams().with_payload(3.0))
    assert ex.to_mjcf() != ex.to_mjcf(ScaraParams().with_payload(3.0))


def test_command_writes_both_files(tmp_path):
    r = subprocess.run([sys.executable, "-m", "scara.export", "--out", str(tmp_path), "--payload", "5"],
                       capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr
    p = ScaraParams().with_payload(5.0)
    assert (tmp_path / "scara.urdf").read_text() == ex.to_urdf(p)
    assert (tmp_path / "scara.xml").read_text() == ex.to_mjcf(p)
    assert "scara.urdf" in r.stdout and "scara.xml" in r.stdout


@pytest.mark.parametrize("args, words", [(["--payload", "-1"], "m_L"), (["--payload", "nan"], "m_L"),
                                         (["--name", "a/b"], "name")])
def test_command_refuses_bad_values_without_a_traceback(tmp_path, args, words):
    r = subprocess.run([sys.executable, "-m", "scara.export", "--out", str(tmp_path), *args],
                       capture_output=True, text=True, timeout=120)
    assert r.returncode == 2
    assert words in r.stderr and "Traceback" not in r.stderr
    assert not list(tmp_path.iterdir())


def test_the_files_colour_the_arm_as_the_books_figures_do():
    from scara.plots._common import PALETTE

    grey = PALETTE["arm"].lstrip("#")
    rgb = [int(grey[i:i + 2], 16) / 255 for i in (0, 2, 4)]
    assert np.allclose(ex._ARM_RGBA[:3], rgb, atol=5e-4) and ex._ARM_RGBA[3] == 1.0
