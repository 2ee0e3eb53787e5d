"""The computations answering chapter 1's exercises (see :mod:`scara.course.answers`)."""
import math

import numpy as np

from scara import ScaraParams, UnreachableError, ikine, is_reachable, jacobian, pose
from scara.course.answers import solves
from scara.errors import ScaraError

ARM = ScaraParams()


def _clean(x: float) -> float:
    """``x`` as a float, with rounding noise below 1e-12 (and -0.0) shown as 0.0 in the worked solutions."""
    x = float(x)
    return 0.0 if abs(x) < 1e-12 else x


def _deg(x: float) -> float:
    """Radians to degrees, rounding noise cleaned."""
    return _clean(math.degrees(x))


@solves("ex-kin-direct")
def kin_direct(t1: float, t2: float, d3: float, t4: float) -> dict:
    """x_e = k(q) (eq-kin-xe) of q = [t1°, t2°, d3, t4°] on the course's arm."""
    q = np.array([math.radians(t1), math.radians(t2), d3, math.radians(t4)])
    if not ARM.d3_min <= d3 <= ARM.d3_max:
        raise ScaraError(f"exercise ex-kin-direct: d3 = {d3} m is outside the quill's stroke")
    x = pose(q, ARM)
    return {"px": _clean(x[0]), "py": _clean(x[1]), "pz": float(x[2]), "phi": _deg(x[3]),
            "t12": t1 + t2}


@solves("ex-kin-elbows")
def kin_elbows(px: float, py: float, pz: float, phi: float) -> dict:
    """Both inverse-kinematics solutions of x = (px, py, pz, phi°), with the numbers of eq-kin-ik-t2 and
    eq-kin-ik-t1. A target within 5 cm of the rim or the axis is refused: its two elbows nearly merge."""
    r = math.hypot(px, py)
    if not 0.05 <= r <= ARM.r_max - 0.05:
        raise ScaraError(f"exercise ex-kin-elbows: the target is {r:.3f} m from the joint-1 axis, too close to a "
                         f"singularity for two distinct elbows")
    x = np.array([px, py, pz, math.radians(phi)])
    up, down = ikine(x, ARM, elbow=+1), ikine(x, ARM, elbow=-1)  # UnreachableError for a target out of reach
    c2 = (r**2 - ARM.a1**2 - ARM.a2**2) / (2 * ARM.a1 * ARM.a2)
    gamma = math.atan2(-py, px)
    beta = math.atan2(ARM.a2 * math.sin(up[1]), ARM.a1 + ARM.a2 * math.cos(up[1]))
    return {"d3": float(up[2]), "t2_up": _deg(up[1]), "t1_up": _deg(up[0]), "t1_down": _deg(down[0]),
            "t2_down": _deg(down[1]), "t4_up": _deg(up[3]), "t4_down": _deg(down[3]),
            "r2": r**2, "c2": _clean(c2), "gamma": _deg(gamma), "beta": _deg(beta)}


@solves("ex-kin-straight")
def kin_straight(t2: float, v: float) -> dict:
    """The joint velocities solving J_A(q) qd = [v, 0, 0, 0] at q = [0, t2°, 0.5, 0]."""
    q = np.array([0.0, math.radians(t2), 0.5, 0.0])
    J = jacobian(q, ARM)
    if abs(np.linalg.det(J)) < 0.05 * ARM.a1 * ARM.a2:
        raise ScaraError(f"exercise ex-kin-straight: θ2 = {t2}° is too close to a singularity")
    qd = np.linalg.solve(J, [v, 0.0, 0.0, 0.0])
    return {"w1": _clean(qd[0]), "w2": _clean(qd[1]), "v3": _clean(qd[2]), "w4": _clean(qd[3]),
            "h11": _clean(J[0, 0]), "h12": _clean(J[0, 1]), "h21": _clean(J[1, 0]), "h22": _clean(J[1, 1])}


@solves("ex-kin-singular")
def kin_singular(a1: float, a2: float) -> dict:
    """The null motion of the stretched arm (θ2 = 0, here θ1 = 35°) with links a1, a2: θ̇2 for θ̇1 = 1 rad/s, from
    the SVD of the horizontal block of J_A, and the direction the gripper cannot move in."""
    arm = ARM.replace(a1=a1, a2=a2)
    q = np.array([math.radians(35), 0.0, 0.5, 0.0])
    U, sv, Vt = np.linalg.svd(jacobian(q, arm)[:2, :2])
    null = Vt[-1] / Vt[-1][0]
    tip = pose(q, arm)[:2]
    radial = tip / np.linalg.norm(tip)
    return {"null2": float(null[1]), "sigma_min": float(sv[-1]),
            "lost_radial": float(abs(U[:, -1] @ radial))}


@solves("ex-kin-unequal")
def kin_unequal(a1: float, a2: float, px: float) -> dict:
    """Whether (px, 0, 0.5) is reachable by the arm with links a1, a2, and the radius of its folded singularities.
    A point on the inner rim itself is refused (reachable or not would hang on the last digit)."""
    arm = ARM.replace(a1=a1, a2=a2)
    if abs(px - arm.r_min) < 1e-6 or abs(px - arm.r_max) < 1e-6:
        raise ScaraError(f"exercise ex-kin-unequal: the point at r = {px} m lies on the rim of the workspace")
    reachable = bool(is_reachable([px, 0.0, 0.5], arm))
    try:
        ikine([px, 0.0, 0.5, 0.0], arm)
        refused = False
    except UnreachableError:
        refused = True
    if refused == reachable:
        raise ScaraError("exercise ex-kin-unequal: is_reachable and ikine disagree")
    return {"reachable": float(reachable), "rmin": float(arm.r_min), "rmax": float(arm.r_max), "r": float(px)}


@solves("ex-kin-predict")
def kin_predict(t2: float) -> dict:
    """det J_A at q = [0, t2°, 0.5, 0], at the stretched arm, at -t2, and with θ1, d3 or θ4 moved (the table)."""
    start = np.array([0.0, math.radians(t2), 0.5, 0.0])

    def det(q):
        return float(np.linalg.det(jacobian(q, ARM))) + 0.0

    out = {"det_start": det(start), "det_zero": abs(det([0.0, 0.0, 0.5, 0.0])),
           "det_mirror": det([0.0, -math.radians(t2), 0.5, 0.0])}
    moves = [(0, start[0]), (0, math.radians(90)), (0, math.pi), (2, 0.0), (2, 1.0), (3, -math.pi / 2),
             (3, math.pi / 2)]
    for n, (k, value) in enumerate(moves):
        q = start.copy()
        q[k] = value
        out[f"moved_{n}"] = det(q)
    return out


@solves("ex-kin-edge")
def kin_edge(px: float) -> dict:
    """θ2 of both elbows at (px, 0, 0.5, 0) and at p_x = 1.0 m (the rim); 1.01 m must be refused."""
    up, down = ikine([px, 0.0, 0.5, 0.0], ARM, elbow=+1), ikine([px, 0.0, 0.5, 0.0], ARM, elbow=-1)
    rim = ikine([1.0, 0.0, 0.5, 0.0], ARM, elbow=+1)
    try:
        ikine([1.01, 0.0, 0.5, 0.0], ARM)
    except UnreachableError:
        pass
    else:
        raise ScaraError("exercise ex-kin-edge: 1.01 m should be out of reach")
    return {"t2": _deg(up[1]), "t2_down": _deg(down[1]), "t2_rim": abs(_deg(rim[1])),
            "c2": (px**2 - ARM.a1**2 - ARM.a2**2) / (2 * ARM.a1 * ARM.a2)}
