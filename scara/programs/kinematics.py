"""Page programs of chapter 1: the direct-kinematics panel (the arm, its DH frames and their names in 3-D, ``x_e``
and ``det J_A``) and the inverse-kinematics panel (both elbow solutions of a typed target, or why it is out of
reach), each one compiled kernel ``program(inputs, data, out) -> status`` (see
:class:`scara.plots.panels.PageProgram`), with the kernels they are made of.

The geometry is the chapter's: the frames ``b, 0, 1, 2, 3, 4, e`` of the DH table (1.2) in the base frame
(:func:`frames_kernel`), the arm drawn through their origins with a triad of axes at each, the frames that share an
origin named once (:func:`frame_groups_kernel`), and the names placed in the 3-D view so that none overlaps another
(:func:`place_names_kernel`: a greedy choice among candidate pixel offsets, scored by how much of the drawing a
name would cover). The numbers of the view (the camera, the plot's height in pixels, the names' widths in pixels)
are made by :mod:`scara.plots.kinematics` and passed in ``data``: nothing here knows plotly.

A frame name cannot be computed as text in a kernel, so the names' trace holds one entry per possible name, the
frames of a subset of ``b, 0, ..., e`` (:data:`SLOT_LABELS`, 127 of them, listed by their first frame): a kernel
writes the point of each name it shows and NaN (nothing drawn) for the others.
"""
from __future__ import annotations

import math

import numpy as np

from .._compile import ArrayLayout, kernel
from .._manipulability import manipulability_kernel
from ..errors import MAX_ANGLE
from ..kinematics import IK_OK, ikine_kernel, planar_position, planar_trig

__all__ = [
    "FRAME_NAMES", "SLOT_MASKS", "SLOT_LABELS", "SLOT_OF_MASK", "N_SLOTS", "CANDIDATES", "N_CANDIDATES", "VIEW",
    "ARM_DATA", "ARM_OUTPUTS", "IK_DATA", "IK_OUTPUTS", "IK_ANGLE_TOO_LARGE", "SINGULAR_W", "COINCIDE_SIN",
    "frames_kernel", "arm_points_kernel", "frame_groups_kernel", "project_kernel", "place_names_kernel", "arm_kernel",
    "kinematics_program", "top_arm_kernel", "inverse_kinematics_kernel", "inverse_kinematics_program",
    "view_vector", "arm_data", "inverse_kinematics_data", "by_field", "run_arm", "run_inverse_kinematics",
]

# --------------------------------------------------------------------------------------------------
# the frames, their names and the candidate places of a name
# --------------------------------------------------------------------------------------------------
#: names of the frames drawn: the base frame, then the six of :func:`scara.kinematics.link_frames`
FRAME_NAMES = ("b", "0", "1", "2", "3", "4", "e")
N_FRAMES = 7
#: the frames whose origins the arm is drawn through: base, top of the column (0), elbow (1), end of link 2 (2),
#: tool point (e)
ARM_FRAMES = (0, 1, 2, 3, 6)
#: two frame origins closer than this (m) share one name
SAME_POINT = 1e-9
#: a gap in a drawn line, or a name not shown (NaN)
GAP = math.nan

#: every set of frames that may share a name, as a bit mask (frame k is bit k), listed by its first frame (then
#: by mask): the order the names are placed in, so that the names shown keep the order of their first frames
SLOT_MASKS = tuple(sorted(range(1, 2 ** N_FRAMES), key=lambda m: ((m & -m).bit_length(), m)))
N_SLOTS = len(SLOT_MASKS)
#: the text of each slot's name: its frames' names in order, e.g. ``"3, 4, e"``
SLOT_LABELS = tuple(", ".join(n for k, n in enumerate(FRAME_NAMES) if m >> k & 1) for m in SLOT_MASKS)
#: the slot of each mask (entry 0, the empty set, is -1)
SLOT_OF_MASK = tuple([-1] + [SLOT_MASKS.index(m) for m in range(1, 2 ** N_FRAMES)])

#: the drawing the names should not cover is sampled at this many points along each segment
SEGMENT_SAMPLES = 9
#: the arm's 4 segments and the 7 frames' 3 axes
N_SEGMENTS = 4 + 3 * N_FRAMES
#: the least gap (px) between two names' boxes
BOX_PAD = 3.0
#: the score of a candidate place: the points of the drawing its box covers, plus this per rank (farther places
#: score worse)
RANK_WEIGHT = 0.5


def _candidates(near=(6, 14, 24, 36, 50, 66)):
    """Pixel offsets ``(xshift, yshift, fx, fy)`` of a name from its point, nearest first, right and up first;
    ``fx`` (``fy``) is the fraction of the box's width (height) left of (below) the shifted point: 0 for a box
    anchored at its left (bottom), 0.5 centred, 1 at its right (top). The last row is the last resort, far above."""
    dirs = [(1, 1), (1, -1), (-1, 1), (-1, -1), (1, 0), (-1, 0), (0, 1), (0, -1)]
    rows = []
    for r in near:
        for dx, dy in dirs:
            k = r / math.hypot(dx, dy)
            rows.append((dx * k, dy * k, 0.0 if dx > 0 else 1.0 if dx < 0 else 0.5,
                         0.0 if dy > 0 else 1.0 if dy < 0 else 0.5))
    rows.append((0.0, 80.0, 0.5, 0.0))
    return np.array(rows, dtype=np.float64)


#: the candidate places of a name (see :func:`_candidates`), (N_CANDIDATES + 1, 4): the last is the fallback
CANDIDATES = _candidates()
N_CANDIDATES = len(CANDIDATES) - 1

#: the 3-D view, as the placement reads it: the centre and span of each axis range (m), the aspect ratio, the
#: camera's eye and its right, up and back directions (plotly's model coordinates), the focal length (px per unit
#: of the camera frame), the half width and half height (px) of the plot area a name must stay within, and the
#: height (px) of a name's box
VIEW = ArrayLayout(("mid", 3), ("span", 3), ("aspect", 3), ("eye", 3), ("right", 3), ("up", 3), ("back", 3),
                   ("focal", 1), ("half_width", 1), ("half_height", 1), ("label_height", 1))
_MID, _SPAN, _ASPECT, _EYE, _RIGHT, _UP, _BACK, _FOCAL, _HALF_W, _HALF_H, _LABEL_H = VIEW.offsets
VIEW_SIZE = VIEW.size

# --------------------------------------------------------------------------------------------------
# the direct-kinematics program's data and outputs
# --------------------------------------------------------------------------------------------------
#: the robot (m), the triads' length (m), the view, each slot's box width (px), the slot of each mask and the
#: candidate places
ARM_DATA = ArrayLayout(("a1", 1), ("a2", 1), ("d0", 1), ("triad", 1), ("view", VIEW_SIZE),
                       ("label_widths", N_SLOTS), ("slot_of_mask", 2 ** N_FRAMES),
                       ("candidates", 4 * (N_CANDIDATES + 1)))
_D_A1, _D_A2, _D_D0, _D_TRIAD, _D_VIEW, _D_WIDTHS, _D_SLOTS, _D_CANDS = ARM_DATA.offsets

_TRIAD_FIELDS = tuple(f"{a}_axes_{c}" for a in "xyz" for c in "xyz")
#: the configuration ``q`` (rad, rad, m, rad), the arm (5 points), the tool point ``p_e`` and ``phi`` (degrees),
#: the triads (x, y, z axes: 7 segments origin-tip-gap each), the 7 frame origins, the names' points (one per slot,
#: NaN where not shown) and the candidate each name took, the title's numbers (printed without a minus sign on
#: zero), ``det J_A``, ``w`` and the singular flag
ARM_OUTPUTS = ArrayLayout(
    ("q", 4), ("arm_x", 5), ("arm_y", 5), ("arm_z", 5), ("px", 1), ("py", 1), ("pz", 1), ("phi", 1),
    *((name, 3 * N_FRAMES) for name in _TRIAD_FIELDS), ("origins", 3 * N_FRAMES),
    ("names_x", N_SLOTS), ("names_y", N_SLOTS), ("names_z", N_SLOTS), ("names_choice", N_SLOTS),
    ("title_px", 1), ("title_py", 1), ("title_pz", 1), ("title_phi", 1), ("title_det", 1),
    ("det", 1), ("w", 1), ("singular", 1))
_O = ARM_OUTPUTS.offsets
_Q = _O.q
_ARM_X, _ARM_Y, _ARM_Z, _PX, _PY, _PZ, _PHI = _O.arm_x, _O.arm_y, _O.arm_z, _O.px, _O.py, _O.pz, _O.phi
_TRIADS, _ORIGINS = _O.x_axes_x, _O.origins  # the nine triad fields follow one another: x axes' x, y, z, ...
_NAMES_X, _NAMES_Y, _NAMES_Z, _NAMES_CHOICE = _O.names_x, _O.names_y, _O.names_z, _O.names_choice
_T_PX, _T_PY, _T_PZ, _T_PHI, _T_DET = _O.title_px, _O.title_py, _O.title_pz, _O.title_phi, _O.title_det
_DET, _W, _SINGULAR = _O.det, _O.w, _O.singular
assert [_O[ARM_OUTPUTS.names.index(n)] for n in _TRIAD_FIELDS] == [_TRIADS + 21 * i for i in range(9)]

#: ``w`` (m²) below which the summary calls the arm singular
SINGULAR_W = 1e-3


# --------------------------------------------------------------------------------------------------
# kernels: the frames and the drawing
# --------------------------------------------------------------------------------------------------
@kernel
def _hanging_frame(row, ox, oy, oz, c, s):
    """A frame of the arm (12,): origin ``(ox, oy, oz)``, then the columns of ``R = A_0^b R_z(angle)`` =
    ``[[c, -s, 0], [-s, -c, 0], [0, 0, -1]]`` (frame 0 hangs with its z axis down, (1.1)) with ``c, s`` the cosine and
    sine of the angle turned about that axis."""
    row[0], row[1], row[2] = ox, oy, oz
    row[3], row[4], row[5] = c, -s, 0.0
    row[6], row[7], row[8] = -s, -c, 0.0
    row[9], row[10], row[11] = 0.0, 0.0, -1.0


@kernel
def frames_kernel(q, a1, a2, d0, frames):
    """The frames ``b, 0, 1, 2, 3, 4, e`` of the arm at ``q = [theta1, theta2, d3, theta4]`` (rad, rad, m, rad) in
    the base frame, the product of the DH matrices of (1.2) written out: ``frames[k]`` = origin (m), x, y, z axes,
    ``frames`` (7, 12). The base frame is the identity; frame 0 hangs at ``d0`` (1.1); frame 1 turns by
    ``theta1`` about it, at the elbow ``(a1 c1, -a1 s1, d0)``; frames 2 and 3 by ``theta1 + theta2``, at the end
    of link 2 ``(p_x, p_y)`` of (1.5), frame 2 at ``d0`` and frame 3 at ``d0 - d3``; frames 4 and e by
    ``phi = theta1 + theta2 + theta4`` at the tool point (``R_e^b`` of (1.4))."""
    sc = planar_trig(q[0], q[1])
    s1, c1, s12, c12 = sc
    px, py = planar_position(sc, a1, a2)
    phi = q[0] + q[1] + q[3]
    s4, c4 = math.sin(phi), math.cos(phi)
    zt = d0 - q[2]
    row = frames[0]
    for j in range(12):
        row[j] = 0.0
    row[3], row[7], row[11] = 1.0, 1.0, 1.0
    _hanging_frame(frames[1], 0.0, 0.0, d0, 1.0, 0.0)
    _hanging_frame(frames[2], a1 * c1, -(a1 * s1), d0, c1, s1)
    _hanging_frame(frames[3], px, py, d0, c12, s12)
    _hanging_frame(frames[4], px, py, zt, c12, s12)
    _hanging_frame(frames[5], px, py, zt, c4, s4)
    _hanging_frame(frames[6], px, py, zt, c4, s4)


@kernel
def arm_points_kernel(q, a1, a2, d0, triad, frames, arm, triads):
    """The arm at ``q`` as drawn: its frames (:func:`frames_kernel`) into ``frames`` (7, 12); the polyline of the
    arm into ``arm`` (5, 3): base, top of the column (frame 0), elbow, end of link 2, tool point; the triads into
    ``triads`` (63, 3): for axis ``a`` (x, y, z), rows ``21 a + 3 k`` the origin of frame ``k``, ``+1`` the tip of its
    axis (``triad`` m long), ``+2`` a gap (NaN)."""
    frames_kernel(q, a1, a2, d0, frames)
    for i in range(5):
        k = ARM_FRAMES[i]
        for c in range(3):
            arm[i, c] = frames[k, c]
    for a in range(3):
        for k in range(N_FRAMES):
            r = 3 * (N_FRAMES * a + k)
            for c in range(3):
                triads[r, c] = frames[k, c]
                triads[r + 1, c] = frames[k, c] + triad * frames[k, 3 + 3 * a + c]
                triads[r + 2, c] = GAP


@kernel
def frame_groups_kernel(frames, first, masks):
    """The frames that share an origin (closer than :data:`SAME_POINT`), which share one name: group ``g`` starts at
    frame ``first[g]`` and holds the frames of the bit mask ``masks[g]`` (frame ``k`` is ``2**k``), frames taken in
    order and each joined to the first group whose first origin it meets. ``frames`` (n, >= 3) the origins first;
    ``first``, ``masks`` (>= n,). Returns the number of groups."""
    n = 0
    for k in range(frames.shape[0]):
        found = -1
        for g in range(n):
            f = int(first[g])
            dx = frames[k, 0] - frames[f, 0]
            dy = frames[k, 1] - frames[f, 1]
            dz = frames[k, 2] - frames[f, 2]
            if math.sqrt(dx * dx + dy * dy + dz * dz) < SAME_POINT:
                found = g
                break
        if found >= 0:
            masks[found] += 2.0 ** k
        else:
            first[n] = k
            masks[n] = 2.0 ** k
            n += 1
    return n


# --------------------------------------------------------------------------------------------------
# kernels: the 3-D view and the names' places
# --------------------------------------------------------------------------------------------------
@kernel
def _camera_point(view, x, y, z):
    """The point ``(x, y, z)`` (m) in the camera frame of ``view``: ``(right, up, depth)``, plotly's model
    coordinates (each axis range mapped onto its aspect ratio) seen from the eye."""
    r0 = (x - view[_MID]) / view[_SPAN] * view[_ASPECT] - view[_EYE]
    r1 = (y - view[_MID + 1]) / view[_SPAN + 1] * view[_ASPECT + 1] - view[_EYE + 1]
    r2 = (z - view[_MID + 2]) / view[_SPAN + 2] * view[_ASPECT + 2] - view[_EYE + 2]
    right = r0 * view[_RIGHT] + r1 * view[_RIGHT + 1] + r2 * view[_RIGHT + 2]
    up = r0 * view[_UP] + r1 * view[_UP + 1] + r2 * view[_UP + 2]
    depth = -(r0 * view[_BACK] + r1 * view[_BACK + 1] + r2 * view[_BACK + 2])
    return right, up, depth


@kernel
def project_kernel(view, x, y, z):
    """Where plotly draws the point ``(x, y, z)`` (m) of the base frame: ``(u, v)`` px from the centre of the plot
    area, u to the right and v up (a perspective of 45° vertical field of view, so the offsets depend on the plot
    area's height only)."""
    right, up, depth = _camera_point(view, x, y, z)
    return view[_FOCAL] * right / depth, view[_FOCAL] * up / depth


@kernel
def place_names_kernel(points, widths, segments, view, candidates, chosen, boxes, spots):
    """Where the names of frames go in the 3-D ``view`` so that none overlaps another.

    ``points`` (n, 3): the point (m) each name belongs to, in the order the names are placed; ``widths`` (n,): the
    width (px) of each name's box; ``segments`` (m, 6): the drawing (segments from ``[0:3]`` to ``[3:6]``, m), which
    a name should not cover; ``candidates`` (c + 1, 4): the offsets ``(xshift, yshift, fx, fy)`` px a name may take
    from its point's pixel, nearest first, the last the fallback (see :data:`CANDIDATES`).

    Each name in turn takes, among the candidates whose box stays within the view's half width and half height and
    keeps :data:`BOX_PAD` px from the boxes placed before, the one of least score: the sampled points of the drawing
    its box covers plus :data:`RANK_WEIGHT` per rank (the first such on a tie); the fallback when none is free.
    Writes the candidate taken into ``chosen[g]``, the box (left, bottom, right, top; px from the centre of the plot
    area, y up) into ``boxes[g]`` and, into ``spots[g]``, the point of the scene drawn at the box's centre, at the
    depth of the name's point (on the camera ray through that pixel; m)."""
    n = points.shape[0]
    m = segments.shape[0]
    last = candidates.shape[0] - 1
    h = view[_LABEL_H]
    half_w = view[_HALF_W]
    half_h = view[_HALF_H]
    pix = np.empty((m * SEGMENT_SAMPLES, 2))
    for s in range(m):
        seg = segments[s]
        for i in range(SEGMENT_SAMPLES):
            t = i / (SEGMENT_SAMPLES - 1)
            u, v = project_kernel(view, seg[0] + t * (seg[3] - seg[0]), seg[1] + t * (seg[4] - seg[1]),
                                  seg[2] + t * (seg[5] - seg[2]))
            pix[s * SEGMENT_SAMPLES + i, 0] = u
            pix[s * SEGMENT_SAMPLES + i, 1] = v
    npix = m * SEGMENT_SAMPLES
    for g in range(n):
        px, py = project_kernel(view, points[g, 0], points[g, 1], points[g, 2])
        w = widths[g]
        best = -1
        best_score = 0.0
        for rank in range(last):
            cand = candidates[rank]
            left = px + cand[0] - cand[2] * w
            bottom = py + cand[1] - cand[3] * h
            right = left + w
            top = bottom + h
            if left < -half_w or right > half_w or bottom < -half_h or top > half_h:
                continue
            free = True
            for o in range(g):
                b = boxes[o]
                if left < b[2] + BOX_PAD and b[0] < right + BOX_PAD and bottom < b[3] + BOX_PAD and \
                        b[1] < top + BOX_PAD:
                    free = False
                    break
            if not free:
                continue
            count = 0
            for k in range(npix):
                if left < pix[k, 0] < right and bottom < pix[k, 1] < top:
                    count += 1
            score = count + RANK_WEIGHT * rank
            if best < 0 or score < best_score:
                best = rank
                best_score = score
        if best < 0:
            best = last
        cand = candidates[best]
        chosen[g] = best
        boxes[g, 0] = px + cand[0] - cand[2] * w
        boxes[g, 1] = py + cand[1] - cand[3] * h
        boxes[g, 2] = boxes[g, 0] + w
        boxes[g, 3] = boxes[g, 1] + h
        # the point at the name's depth drawn at the box's centre
        right, up, depth = _camera_point(view, points[g, 0], points[g, 1], points[g, 2])
        cx = (boxes[g, 0] + boxes[g, 2]) / 2
        cy = (boxes[g, 1] + boxes[g, 3]) / 2
        f = view[_FOCAL]
        for c in range(3):
            model = view[_EYE + c] + depth * (cx / f * view[_RIGHT + c] + cy / f * view[_UP + c] - view[_BACK + c])
            spots[g, c] = model / view[_ASPECT + c] * view[_SPAN + c] + view[_MID + c]


# --------------------------------------------------------------------------------------------------
# the direct-kinematics program
# --------------------------------------------------------------------------------------------------
@kernel
def _printed(x, half):
    """``x`` as it reads once printed to the decimal place of ``half`` (half a unit of it): 0 when it prints as
    zero, so that no "-0.000" is shown."""
    return 0.0 if abs(x) < half else x


@kernel
def arm_kernel(q, data, out):
    """Everything the direct-kinematics panel draws at ``q`` (rad, rad, m, rad), written into ``out``
    (:data:`ARM_OUTPUTS`) from ``data`` (:data:`ARM_DATA`): ``q`` itself, the arm and its triads
    (:func:`arm_points_kernel`), the frame names placed in the view (:func:`frame_groups_kernel`,
    :func:`place_names_kernel`; each shown name's point and candidate in its slot, NaN elsewhere), ``x_e`` (1.5) with
    ``phi`` in degrees, ``det J_A = a1 a2 sin theta2`` (1.7), ``w = |det J_A|`` (2.4) and whether ``w`` is below
    :data:`SINGULAR_W`."""
    a1 = data[_D_A1]
    a2 = data[_D_A2]
    d0 = data[_D_D0]
    for j in range(4):
        out[_Q + j] = q[j]
    frames = np.empty((N_FRAMES, 12))
    arm = np.empty((5, 3))
    triads = np.empty((9 * N_FRAMES, 3))
    arm_points_kernel(q, a1, a2, d0, data[_D_TRIAD], frames, arm, triads)
    for i in range(5):
        out[_ARM_X + i] = arm[i, 0]
        out[_ARM_Y + i] = arm[i, 1]
        out[_ARM_Z + i] = arm[i, 2]
    for a in range(3):
        for c in range(3):
            base = _TRIADS + 3 * N_FRAMES * (3 * a + c)
            for r in range(3 * N_FRAMES):
                out[base + r] = triads[3 * N_FRAMES * a + r, c]
    for k in range(N_FRAMES):
        for c in range(3):
            out[_ORIGINS + 3 * k + c] = frames[k, c]
    # the frame names: one per group of frames sharing an origin, placed in the order of their first frames
    first = np.empty(N_FRAMES)
    masks = np.empty(N_FRAMES)
    n = frame_groups_kernel(frames, first, masks)
    points = np.empty((n, 3))
    widths = np.empty(n)
    slots = np.empty(n)
    for g in range(n):
        f = int(first[g])
        for c in range(3):
            points[g, c] = frames[f, c]
        slot = int(data[_D_SLOTS + int(masks[g])])
        slots[g] = slot
        widths[g] = data[_D_WIDTHS + slot]
    segments = np.empty((N_SEGMENTS, 6))
    for s in range(4):
        for c in range(3):
            segments[s, c] = arm[s, c]
            segments[s, 3 + c] = arm[s + 1, c]
    for a in range(3 * N_FRAMES):
        for c in range(3):
            segments[4 + a, c] = triads[3 * a, c]
            segments[4 + a, 3 + c] = triads[3 * a + 1, c]
    cands = data[_D_CANDS:_D_CANDS + 4 * (N_CANDIDATES + 1)].reshape((N_CANDIDATES + 1, 4))
    chosen = np.empty(n)
    boxes = np.empty((n, 4))
    spots = np.empty((n, 3))
    place_names_kernel(points, widths, segments, data[_D_VIEW:_D_VIEW + VIEW_SIZE], cands, chosen, boxes, spots)
    for s in range(N_SLOTS):
        out[_NAMES_X + s] = GAP
        out[_NAMES_Y + s] = GAP
        out[_NAMES_Z + s] = GAP
        out[_NAMES_CHOICE + s] = GAP
    for g in range(n):
        slot = int(slots[g])
        out[_NAMES_X + slot] = spots[g, 0]
        out[_NAMES_Y + slot] = spots[g, 1]
        out[_NAMES_Z + slot] = spots[g, 2]
        out[_NAMES_CHOICE + slot] = chosen[g]
    # x_e, det J_A and w
    px = frames[N_FRAMES - 1, 0]
    py = frames[N_FRAMES - 1, 1]
    pz = frames[N_FRAMES - 1, 2]
    phi = math.degrees(q[0] + q[1] + q[3])
    det = a1 * a2 * math.sin(q[1])
    w = manipulability_kernel(q, a1, a2)
    out[_PX] = px
    out[_PY] = py
    out[_PZ] = pz
    out[_PHI] = phi
    out[_T_PX] = _printed(px, 0.0005)
    out[_T_PY] = _printed(py, 0.0005)
    out[_T_PZ] = _printed(pz, 0.0005)
    out[_T_PHI] = _printed(phi, 0.05)
    out[_T_DET] = _printed(det, 0.0005)
    out[_DET] = det
    out[_W] = w
    out[_SINGULAR] = 1.0 if w < SINGULAR_W else 0.0


@kernel
def kinematics_program(inputs, data, out):
    """The direct-kinematics panel's move: ``inputs = [theta1 (°), theta2 (°), d3 (m), theta4 (°)]``, ``data``
    :data:`ARM_DATA`, ``out`` :data:`ARM_OUTPUTS` (:func:`arm_kernel`). Every setting of the sliders is a
    configuration, so it never refuses: returns 0."""
    q = np.empty(4)
    q[0] = math.radians(inputs[0])
    q[1] = math.radians(inputs[1])
    q[2] = inputs[2]
    q[3] = math.radians(inputs[3])
    arm_kernel(q, data, out)
    return 0


# --------------------------------------------------------------------------------------------------
# the inverse-kinematics program
# --------------------------------------------------------------------------------------------------
#: the robot (m) and the quill's stroke (m)
IK_DATA = ArrayLayout(("a1", 1), ("a2", 1), ("d0", 1), ("d3_min", 1), ("d3_max", 1))
_I_A1, _I_A2, _I_D0, _I_D3_MIN, _I_D3_MAX = IK_DATA.offsets
#: the target's distance ``r`` from the joint-1 axis (m), the ``d3 = d0 - p_z`` it needs (m), ``phi`` (rad), both
#: solutions ``q`` (elbow +1 "up", -1 "down") and their top views (base, elbow, end of link 2), the target's
#: marker, the joints in degrees (and minus theta2 of elbow -1, which is never positive) and whether the elbows
#: coincide
IK_OUTPUTS = ArrayLayout(
    ("r", 1), ("d3", 1), ("phi_rad", 1), ("q_up", 4), ("q_down", 4), ("up_x", 3), ("up_y", 3), ("down_x", 3),
    ("down_y", 3), ("target_x", 1), ("target_y", 1), ("theta1_up", 1), ("theta2_up", 1), ("theta4_up", 1),
    ("theta1_down", 1), ("theta2_down", 1), ("theta4_down", 1), ("theta2_down_size", 1), ("coincide", 1))
_P = IK_OUTPUTS.offsets
#: the refusal of a target whose ``phi`` is beyond :data:`scara.errors.MAX_ANGLE` (the other two are
#: :data:`scara.kinematics.IK_OUTSIDE_ANNULUS` and :data:`~scara.kinematics.IK_OUTSIDE_STROKE`)
IK_ANGLE_TOO_LARGE = 3
#: ``|sin theta2|`` below which the two elbows are said to coincide
COINCIDE_SIN = 1e-3


@kernel
def top_arm_kernel(q, a1, a2, xs, ys):
    """The arm at ``q`` seen from above (1.5): ``xs``, ``ys`` (3,) of the base axis, the elbow ``(a1 c1, -a1 s1)``
    and the end of link 2 ``(p_x, p_y)``."""
    sc = planar_trig(q[0], q[1])
    px, py = planar_position(sc, a1, a2)
    xs[0] = 0.0
    ys[0] = 0.0
    xs[1] = a1 * sc[1]
    ys[1] = -(a1 * sc[0])
    xs[2] = px
    ys[2] = py


@kernel
def inverse_kinematics_kernel(x, data, out):
    """Both closed-form solutions (1.8)-(1.10) of the target ``x = [p_x, p_y, p_z, phi]`` (m, rad), written into
    ``out`` (:data:`IK_OUTPUTS`) from ``data`` (:data:`IK_DATA`), with their top views (:func:`top_arm_kernel`).

    Returns 0, or why the target is refused: :data:`IK_ANGLE_TOO_LARGE` for ``|phi|`` beyond ``MAX_ANGLE`` (checked
    first), else the code of :func:`scara.kinematics.ikine_kernel` (outside the annulus, or ``d3`` outside the
    stroke); ``r``, ``d3`` and ``phi_rad`` are written in every case."""
    a1 = data[_I_A1]
    a2 = data[_I_A2]
    d0 = data[_I_D0]
    out[_P.r] = math.hypot(x[0], x[1])
    out[_P.d3] = d0 - x[2]
    out[_P.phi_rad] = x[3]
    if abs(x[3]) > MAX_ANGLE:
        return IK_ANGLE_TOO_LARGE
    up = out[_P.q_up:_P.q_up + 4]
    down = out[_P.q_down:_P.q_down + 4]
    code = ikine_kernel(x, a1, a2, d0, data[_I_D3_MIN], data[_I_D3_MAX], 1.0, up)
    if code != IK_OK:
        return code
    ikine_kernel(x, a1, a2, d0, data[_I_D3_MIN], data[_I_D3_MAX], -1.0, down)
    top_arm_kernel(up, a1, a2, out[_P.up_x:_P.up_x + 3], out[_P.up_y:_P.up_y + 3])
    top_arm_kernel(down, a1, a2, out[_P.down_x:_P.down_x + 3], out[_P.down_y:_P.down_y + 3])
    out[_P.target_x] = x[0]
    out[_P.target_y] = x[1]
    out[_P.theta1_up] = math.degrees(up[0])
    out[_P.theta2_up] = math.degrees(up[1])
    out[_P.theta4_up] = math.degrees(up[3])
    out[_P.theta1_down] = math.degrees(down[0])
    out[_P.theta2_down] = math.degrees(down[1])
    out[_P.theta4_down] = math.degrees(down[3])
    out[_P.theta2_down_size] = -math.degrees(down[1])
    out[_P.coincide] = 1.0 if abs(math.sin(up[1])) < COINCIDE_SIN else 0.0
    return IK_OK


@kernel
def inverse_kinematics_program(inputs, data, out):
    """The inverse-kinematics panel's move: ``inputs = [p_x, p_y, p_z (m), phi (°)]``, ``data`` :data:`IK_DATA`,
    ``out`` :data:`IK_OUTPUTS` (:func:`inverse_kinematics_kernel`, whose status it returns)."""
    x = np.empty(4)
    x[0] = inputs[0]
    x[1] = inputs[1]
    x[2] = inputs[2]
    x[3] = math.radians(inputs[3])
    return inverse_kinematics_kernel(x, data, out)


# --------------------------------------------------------------------------------------------------
# Python: the data, and one run read by field
# --------------------------------------------------------------------------------------------------
def view_vector(scene: dict, plot_height: float, half_width: float, label_height: float) -> np.ndarray:
    """The :data:`VIEW` of a 3-D ``scene`` (a plotly layout dict with axis ``range`` s, a manual ``aspectratio`` and a
    ``camera``) drawn ``plot_height`` px tall, names kept within ``half_width`` px of the centre and ``label_height``
    px tall: the camera looks from ``eye`` at ``center`` with +z up."""
    ranges = np.array([scene[k]["range"] for k in ("xaxis", "yaxis", "zaxis")], float)
    aspect = np.array([scene["aspectratio"][k] for k in "xyz"], float)
    cam = scene.get("camera", {})
    eye = np.array([cam.get("eye", {}).get(k, 1.25) for k in "xyz"], float)
    centre = np.array([cam.get("center", {}).get(k, 0.0) for k in "xyz"], float)
    back = (eye - centre) / np.linalg.norm(eye - centre)
    right = np.cross([0.0, 0.0, 1.0], back)
    right /= np.linalg.norm(right)
    up = np.cross(back, right)
    focal = 1.0 / math.tan(math.pi / 8) * plot_height / 2  # pixels per unit of the camera frame
    return VIEW.pack(mid=ranges.mean(axis=1), span=ranges[:, 1] - ranges[:, 0], aspect=aspect, eye=eye, right=right,
                     up=up, back=back, focal=focal, half_width=half_width, half_height=plot_height / 2,
                     label_height=label_height)


def arm_data(a1: float, a2: float, d0: float, triad: float, view, label_widths) -> np.ndarray:
    """The :data:`ARM_DATA` vector: the robot's lengths (m), the triads' length (m), the :data:`VIEW` and the width
    (px) of each slot's name box (:data:`SLOT_LABELS`)."""
    return ARM_DATA.pack(a1=a1, a2=a2, d0=d0, triad=triad, view=view, label_widths=label_widths,
                         slot_of_mask=SLOT_OF_MASK, candidates=CANDIDATES)


def inverse_kinematics_data(p) -> np.ndarray:
    """The :data:`IK_DATA` vector of the robot ``p`` (:class:`~scara.ScaraParams`)."""
    return IK_DATA.pack(a1=p.a1, a2=p.a2, d0=p.d0, d3_min=p.d3_min, d3_max=p.d3_max)


def by_field(out, layout) -> dict:
    """The outputs ``out`` of a program by field of ``layout``: one number as a float, more as an array (a copy)."""
    return {name: float(out[start]) if layout.sizes[name] == 1 else np.array(out[start:start + layout.sizes[name]])
            for name, start in zip(layout.names, layout.offsets)}


def run_arm(q, data) -> dict:
    """:func:`arm_kernel` at ``q`` (4,) rad, rad, m, rad: its outputs by field (:func:`by_field`)."""
    out = np.zeros(ARM_OUTPUTS.size)
    arm_kernel(np.ascontiguousarray(q, dtype=np.float64), data, out)
    return by_field(out, ARM_OUTPUTS)


def run_inverse_kinematics(x, data):
    """:func:`inverse_kinematics_kernel` for the target ``x`` (4,) m, m, m, rad: ``(status, outputs by field)``."""
    out = np.zeros(IK_OUTPUTS.size)
    status = int(inverse_kinematics_kernel(np.ascontiguousarray(x, dtype=np.float64), data, out))
    return status, by_field(out, IK_OUTPUTS)
