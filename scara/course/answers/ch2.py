"""The computations answering chapter 2's exercises (see :mod:`scara.course.answers`)."""
import math

import numpy as np

from scara import ScaraParams, force_ellipsoid, jacobian, manipulability, pose, velocity_ellipsoid, workspace_map
from scara.course.answers import solves
from scara.errors import ScaraError

ARM = ScaraParams()


def _axis_deg(e) -> float:
    """Direction of the major axis of a horizontal ellipse, in degrees from x_b, in [-90°, 90°) (no sign)."""
    return (math.degrees(math.atan2(e.axes[1, 0], e.axes[0, 0])) + 90) % 180 - 90


@solves("ex-manip-best")
def manip_best() -> dict:
    """Where w(r) of eq-manip-wr is largest on the course's arm, in closed form and on a fine grid of r."""
    r = np.linspace(ARM.r_min, ARM.r_max, 100001)
    c2 = (r**2 - ARM.a1**2 - ARM.a2**2) / (2 * ARM.a1 * ARM.a2)
    w = ARM.a1 * ARM.a2 * np.sqrt(np.clip(1 - c2**2, 0, None))
    return {"r_best": math.hypot(ARM.a1, ARM.a2), "w_max": ARM.a1 * ARM.a2,
            "r_grid": float(r[np.argmax(w)]), "w_grid": float(w.max())}


@solves("ex-manip-share")
def manip_share(pct: float) -> dict:
    """The share of the workspace's area where w >= pct % of a1 a2: in closed form (a ring between the radii of
    |θ2| = asin k and 180° - asin k) and counted on the 801 x 801 grid of workspace_map."""
    k = pct / 100.0
    if not 0.0 < k < 1.0:
        raise ScaraError(f"exercise ex-manip-share: the threshold {pct} % must lie strictly between 0 and 100 %")
    t_lo = math.asin(k)
    t_hi = math.pi - t_lo
    r2 = lambda t: ARM.a1**2 + ARM.a2**2 + 2 * ARM.a1 * ARM.a2 * math.cos(t)  # noqa: E731
    share = (r2(t_lo) - r2(t_hi)) / (ARM.r_max**2 - ARM.r_min**2)
    xs, ys, W = workspace_map(ARM, n=801)
    inside = ~np.isnan(W)
    share_grid = float(np.sum(W[inside] >= k * ARM.a1 * ARM.a2) / np.sum(inside))
    return {"share": share, "share_grid": share_grid, "t_lo": math.degrees(t_lo), "t_hi": math.degrees(t_hi)}


@solves("ex-manip-push")
def manip_push(t2: float) -> dict:
    """The strongest horizontal push at q = [0, t2°, 0.5, 0]: the major force axis, its length 1/σ2 and its
    direction in (-90°, 90°], with H Hᵀ and its eigenvalues for the worked solution."""
    q = np.array([0.0, math.radians(t2), 0.5, 0.0])
    if manipulability(q, ARM) < 0.05 * ARM.a1 * ARM.a2:
        raise ScaraError(f"exercise ex-manip-push: θ2 = {t2}° is too close to a singularity")
    f = force_ellipsoid(q, ARM, rows=(0, 1))
    k = int(np.argmax(f.lengths))
    u = f.axes[:, k] * np.sign(f.axes[0, k] or 1.0)
    angle = math.degrees(math.atan2(u[1], u[0]))
    if abs(angle) > 85.0:  # nearly along y_b: the angle would jump between +90° and -90°
        raise ScaraError(f"exercise ex-manip-push: at θ2 = {t2}° the direction is too close to ±90° to mark")
    H = jacobian(q, ARM)[:2, :2]
    HH = H @ H.T
    l_small, l_big = np.linalg.eigvalsh(HH)
    tip = pose(q, ARM)[:2]
    return {"push": float(f.lengths[k]), "angle": angle, "hh11": float(HH[0, 0]), "hh12": float(HH[0, 1]),
            "hh22": float(HH[1, 1]), "l1": float(l_big), "l2": float(l_small),
            "radial_angle": math.degrees(math.atan2(tip[1], tip[0]))}


@solves("ex-manip-turn")
def manip_turn(t2: float, t1: float) -> dict:
    """w, the velocity semi-axes and the major axis's direction at q = [0, t2°, 0.5, 0] and after the base turns
    to θ1 = t1°."""
    q_a = np.array([0.0, math.radians(t2), 0.5, 0.0])
    q_b = q_a + np.array([math.radians(t1), 0.0, 0.0, 0.0])
    e_a, e_b = velocity_ellipsoid(q_a, ARM, rows=(0, 1)), velocity_ellipsoid(q_b, ARM, rows=(0, 1))
    axis_a, axis_b = _axis_deg(e_a), _axis_deg(e_b)
    if abs(abs(axis_b) - 90.0) < 1.0:
        raise ScaraError(f"exercise ex-manip-turn: after a turn of {t1}° the major axis is too close to ±90° to mark")
    return {"w": float(manipulability(q_b, ARM)), "s1": float(e_b.lengths[0]), "s2": float(e_b.lengths[1]),
            "axis_b": axis_b, "axis_a": axis_a, "w_a": float(manipulability(q_a, ARM)),
            "turn": (axis_b - axis_a + 90) % 180 - 90}


@solves("ex-manip-unequal")
def manip_unequal(a1: float, a2: float) -> dict:
    """The largest w, where it is reached and the hole of the arm with links a1 and a2 (unequal)."""
    if abs(a1 - a2) < 0.05:
        raise ScaraError(f"exercise ex-manip-unequal: a1 = {a1} m and a2 = {a2} m are not unequal links")
    arm = ARM.replace(a1=a1, a2=a2)
    return {"r_best": math.hypot(arm.a1, arm.a2), "w_max": arm.a1 * arm.a2, "r_min": float(arm.r_min),
            "r_max": float(arm.r_max)}


@solves("ex-manip-stretched")
def manip_stretched(t2: float) -> dict:
    """The velocity semi-axes and the largest force semi-axis at q = [0, t2°, 0.5, 0], with w and the trace of
    H Hᵀ the worked solution uses, and the angle between the thin direction and the line to the gripper."""
    if not 0.0 < t2 < 180.0:
        raise ScaraError(f"exercise ex-manip-stretched: θ2 = {t2}° must lie strictly between 0° and 180°")
    q = np.array([0.0, math.radians(t2), 0.5, 0.0])
    v = velocity_ellipsoid(q, ARM, rows=(0, 1))
    tip = pose(q, ARM)[:2]
    thin = v.axes[:, int(np.argmin(v.lengths))]
    align = math.degrees(math.acos(min(1.0, abs(thin @ tip) / np.linalg.norm(tip))))
    trace = ARM.a1**2 + 2 * ARM.a2**2 + 2 * ARM.a1 * ARM.a2 * math.cos(math.radians(t2))
    return {"s1": float(v.lengths[0]), "s2": float(v.lengths[1]), "f2": float(1.0 / v.lengths[1]),
            "w": float(manipulability(q, ARM)), "trace": trace, "align": align}
