"""The page program of chapter 2's ellipses panel: for the sliders' ``theta1``, ``theta2`` (degrees) and the
drawing scale, the arm seen from above with its horizontal velocity and force ellipses, their principal axes,
``w`` and the semi-axes, all in one compiled kernel (:func:`ellipse_program`).

The horizontal ellipses come from the 2x2 block ``H`` of ``J_A`` (rows x, y; columns theta1, theta2) in closed
form (:func:`planar_ellipse_axes`): the eigenvalues of the symmetric ``H H^T`` are ``sigma_i^2``, its
eigenvectors the principal axes. The smaller semi-axis is formed as ``w / sigma_1`` (``w = sigma_1 sigma_2 =
|det H|``, (2.4)), so it keeps its relative accuracy as the arm nears a singularity, where a subtraction would
lose it.

The fields of the kernel's vectors are declared here (:data:`ELLIPSE_INPUTS`, :data:`ELLIPSE_DATA`,
:data:`ELLIPSE_OUTPUTS`); how the outputs are drawn is declared beside the figure, in
:mod:`scara.plots.manipulability`.
"""
from __future__ import annotations

import math

import numpy as np

from .._compile import ArrayLayout, kernel
from .._manipulability import manipulability_kernel
from ..kinematics import planar_jacobian_at, planar_position, planar_trig

__all__ = ["ELLIPSE_POINTS", "ELLIPSE_CLIP", "SINGULAR_RATIO", "ELLIPSE_INPUTS", "ELLIPSE_DATA", "ELLIPSE_OUTPUTS",
           "REFUSED_SCALE", "planar_ellipse_axes", "ellipse_outline", "ellipse_axes_segments", "ellipse_program",
           "ellipse_data"]

#: points of each drawn ellipse outline (the first and the last coincide: a closed line)
ELLIPSE_POINTS = 181
#: m: a drawn semi-axis is capped here (the view is about 2.5 m wide), so an unbounded force ellipse draws as a
#: strip of parallel lines
ELLIPSE_CLIP = 50.0
#: below this ratio of the smaller to the larger velocity semi-axis the arm is treated as singular (its force
#: ellipse unbounded)
SINGULAR_RATIO = 1e-6

#: the controls the kernel reads, in order: degrees, degrees, metres drawn per m/s and per N
ELLIPSE_INPUTS = ("theta1", "theta2", "scale")
#: the panel's fixed numbers: the link lengths (m)
ELLIPSE_DATA = ArrayLayout(("a1", 1), ("a2", 1))
_A1, _A2 = ELLIPSE_DATA.offsets

#: the kernel's outputs: ``w`` (m²); the velocity semi-axes ``sigma1 >= sigma2`` (m/s for a unit joint-speed
#: norm) and the force semi-axes ``force1 = 1/sigma1``, ``force2 = 1/sigma2`` (N for a unit torque norm, ``inf``
#: at a singular arm); ``major``, the direction of the major velocity axis (degrees from x_b towards y_b, in
#: (-90°, 90°]); ``singular`` (1 or 0); the arm's base, elbow and tip seen from above (m); the two outlines and
#: their principal axes as two segments each (NaN between them), drawn ``scale`` metres per m/s and per N
ELLIPSE_OUTPUTS = ArrayLayout(
    ("w", 1), ("sigma1", 1), ("sigma2", 1), ("force1", 1), ("force2", 1), ("major", 1), ("singular", 1),
    ("arm_x", 3), ("arm_y", 3),
    ("vel_x", ELLIPSE_POINTS), ("vel_y", ELLIPSE_POINTS), ("vel_axes_x", 6), ("vel_axes_y", 6),
    ("force_x", ELLIPSE_POINTS), ("force_y", ELLIPSE_POINTS), ("force_axes_x", 6), ("force_axes_y", 6))
(_W, _S1, _S2, _F1, _F2, _MAJOR, _SINGULAR, _ARM_X, _ARM_Y, _VEL_X, _VEL_Y, _VEL_AX, _VEL_AY,
 _FRC_X, _FRC_Y, _FRC_AX, _FRC_AY) = ELLIPSE_OUTPUTS.offsets

#: the refusal: a scale of 0 draws nothing
REFUSED_SCALE = 1


@kernel
def planar_ellipse_axes(j11, j12, j21, j22, w):
    """Semi-axes and direction of the horizontal velocity ellipse from the block ``H = [[j11, j12], [j21, j22]]``
    of ``J_A`` (1.6) and ``w = |det H|`` (2.4), in closed form: with ``H H^T = [[m11, m12], [m12, m22]]``,
    ``sigma_1^2 = (m11 + m22) / 2 + hypot((m11 - m22) / 2, m12)`` (the larger eigenvalue), ``sigma_2 = w /
    sigma_1`` and the major axis at ``phi = atan2(2 m12, m11 - m22) / 2`` (rad, in (-pi/2, pi/2]; the minor axis
    is at ``phi + pi/2``). Returns ``(sigma_1, sigma_2, phi)``; ``phi = 0`` for a round ellipse."""
    m11 = j11 * j11 + j12 * j12
    m22 = j21 * j21 + j22 * j22
    m12 = j11 * j21 + j12 * j22 + 0.0  # + 0.0 turns -0.0 into 0.0: atan2 then stays in (-pi, pi]
    half = 0.5 * (m11 - m22)
    s1 = math.sqrt(0.5 * (m11 + m22) + math.hypot(half, m12))
    s2 = w / s1 if s1 > 0.0 else 0.0
    return s1, s2, 0.5 * math.atan2(m12, half)


@kernel
def ellipse_outline(cx, cy, l1, l2, phi, scale, clip, x, y):
    """The outline of an ellipse centred at ``(cx, cy)`` with semi-axes ``l1`` along ``(cos phi, sin phi)`` and
    ``l2`` along ``(-sin phi, cos phi)``, each drawn ``min(scale l_i, clip)`` long (``inf`` draws ``clip``):
    ``(x_k, y_k) = c + cos t_k L1 u1 + sin t_k L2 u2`` at ``t_k = 2 pi k / (n - 1)``, ``n = len(x)``, into ``x``
    and ``y`` (the first and last points coincide)."""
    n = len(x)
    a = min(scale * l1, clip)
    b = min(scale * l2, clip)
    c = math.cos(phi)
    s = math.sin(phi)
    step = 2.0 * math.pi / (n - 1)
    for k in range(n):
        t = k * step if k < n - 1 else 2.0 * math.pi
        ct = math.cos(t)
        st = math.sin(t)
        x[k] = cx + ct * a * c - st * b * s
        y[k] = cy + ct * a * s + st * b * c


@kernel
def ellipse_axes_segments(cx, cy, l1, l2, phi, scale, clip, x, y):
    """The two principal axes of the ellipse of :func:`ellipse_outline` as segments through its centre, each
    ``2 min(scale l_i, clip)`` long: ``x``, ``y`` (6,) hold the ends of the major-direction segment, a NaN (a gap
    in the line), the ends of the other segment and a NaN."""
    c = math.cos(phi)
    s = math.sin(phi)
    gap = math.nan
    for i in range(2):
        half = min(scale * (l1 if i == 0 else l2), clip)
        ux = c if i == 0 else -s
        uy = s if i == 0 else c
        x[3 * i] = cx - half * ux
        y[3 * i] = cy - half * uy
        x[3 * i + 1] = cx + half * ux
        y[3 * i + 1] = cy + half * uy
        x[3 * i + 2] = gap
        y[3 * i + 2] = gap


@kernel
def ellipse_program(inputs, data, out):
    """The ellipses panel's move: ``inputs = [theta1 (°), theta2 (°), scale]``, ``data`` of
    :data:`ELLIPSE_DATA`, ``out`` of :data:`ELLIPSE_OUTPUTS`. Returns 0, or :data:`REFUSED_SCALE` for a scale
    that is not above 0.

    The arm at ``q = [theta1, theta2, ., .]`` (1.5) seen from above: base, elbow ``(a1 c1, -a1 s1)`` and tip;
    ``w`` (2.4); the semi-axes and directions of :func:`planar_ellipse_axes`, the force ellipse being the dual
    one (same axes, reciprocal lengths; ``inf`` when ``sigma_2 < SINGULAR_RATIO sigma_1``); the outlines
    (:func:`ellipse_outline`, :data:`ELLIPSE_POINTS` points) and principal axes (:func:`ellipse_axes_segments`)
    centred at the tip."""
    scale = inputs[2]
    if not scale > 0.0:
        return REFUSED_SCALE
    a1 = data[_A1]
    a2 = data[_A2]
    t1 = math.radians(inputs[0])
    t2 = math.radians(inputs[1])
    sc = planar_trig(t1, t2)
    px, py = planar_position(sc, a1, a2)
    j11, j12, j21, j22 = planar_jacobian_at(px, py, sc[2], sc[3], a2)
    q = np.zeros(4)
    q[0] = t1
    q[1] = t2
    w = manipulability_kernel(q, a1, a2)
    s1, s2, phi = planar_ellipse_axes(j11, j12, j21, j22, w)
    singular = s2 < SINGULAR_RATIO * s1
    f1 = 1.0 / s1
    f2 = math.inf if singular else 1.0 / s2
    out[_W] = w
    out[_S1] = s1
    out[_S2] = s2
    out[_F1] = f1
    out[_F2] = f2
    out[_MAJOR] = math.degrees(phi)
    out[_SINGULAR] = 1.0 if singular else 0.0
    out[_ARM_X] = 0.0
    out[_ARM_Y] = 0.0
    out[_ARM_X + 1] = a1 * sc[1]
    out[_ARM_Y + 1] = -a1 * sc[0]
    out[_ARM_X + 2] = px
    out[_ARM_Y + 2] = py
    n = ELLIPSE_POINTS
    ellipse_outline(px, py, s1, s2, phi, scale, ELLIPSE_CLIP, out[_VEL_X:_VEL_X + n], out[_VEL_Y:_VEL_Y + n])
    ellipse_axes_segments(px, py, s1, s2, phi, scale, ELLIPSE_CLIP, out[_VEL_AX:_VEL_AX + 6],
                          out[_VEL_AY:_VEL_AY + 6])
    ellipse_outline(px, py, f1, f2, phi, scale, ELLIPSE_CLIP, out[_FRC_X:_FRC_X + n], out[_FRC_Y:_FRC_Y + n])
    ellipse_axes_segments(px, py, f1, f2, phi, scale, ELLIPSE_CLIP, out[_FRC_AX:_FRC_AX + 6],
                          out[_FRC_AY:_FRC_AY + 6])
    return 0


def ellipse_data(p) -> np.ndarray:
    """The ``data`` vector of :func:`ellipse_program` for the robot ``p`` (a :class:`~scara.ScaraParams`)."""
    return ELLIPSE_DATA.pack(a1=p.a1, a2=p.a2)
