"""The environment the end effector meets (chapter 7): a compliant horizontal surface with Coulomb friction, an
optional hole for a peg along z, and the wrist force sensor; the contact force model as compiled kernels.

Sign convention (Siciliano et al., eq. 9.1): ``h_e`` is the force the end effector exerts on the environment, so
the plant is ``B qdd + C qd + F qd + g = tau - J^T h_e`` and the environment pushes the tool with ``-h_e``. Only
forces act (no moments: every contact is a point on the tool's axis), so ``J`` is the positional part of ``J_A``,
its first three rows.

The surface (a horizontal plane at ``p_z = z_s``)
    penetration ``delta = z_s - p_z``; normal force on the tool ``f_n = max(0, k_e delta + d_e delta_dot)`` for
    ``delta > 0`` and 0 otherwise (unilateral: it pushes, never pulls; the damper cannot pull either), upwards;
    tangential (friction) force ``-mu f_n tanh(|v_t| / v_s) v_t / |v_t|`` with ``v_t = (v_x, v_y)``: Coulomb's
    law, its jump at ``v_t = 0`` regularised by ``tanh`` over the speed ``v_s`` (default 1 mm/s). Below ``v_s`` it
    acts as a viscous damper of ``mu f_n / v_s`` (3000 N s/m at 10 N): the tool cannot stick as with true Coulomb
    friction (which holds it anywhere its tangential load stays below ``mu f_n``), it creeps to the frictionless
    equilibrium, with the time constant of that damper against the law's stiffness (0.6 s for compliance control's
    5000 N/m). The steady states of the laws are therefore those without friction; the transients are not.

The hole (centre ``(c_x, c_y)`` on the surface, radial clearance ``c``, depth ``D``)
    The peg is a rigid cylinder on the tool's axis with a flat end at the tool point; a SCARA's tool axis stays
    vertical, so the peg never tilts and the only geometry that matters is the offset ``rho`` of its axis from the
    hole's axis against the clearance ``c = r_hole - r_peg``. Above the hole (``rho <= c``) the surface does not
    push; elsewhere the peg's end rests on the surface. The peg is *inside* the hole once its end has crossed
    the surface's plane with ``rho <= c`` (a state kept by the engine, updated after every integration step,
    cleared when the end rises above the plane): inside, the walls push it back radially with
    ``f_w = max(0, k_w (rho - c) + d_e rho_dot)`` when ``rho > c``, with wall friction ``-mu f_w tanh(v_z / v_s)``
    along z, and the bottom at ``z_s - D`` acts as the surface does (same stiffness, damping and friction). A run
    starts with the peg out of the hole (its end above the plane, or off the hole's axis).

The sensor
    reads ``h_e + n + b`` at each sample, ``n`` white Gaussian noise (default std 0.2 N on each component,
    seeded), ``b`` a constant bias (default 0.5 N on ``f_z``).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .._compile import ArrayLayout, kernel
from .._simulate.interface import MAX_SAMPLES
from ..errors import ScaraError, as_array, check_count, check_number, check_positive
from ..kinematics import jacobian
from ..params import ScaraParams

__all__ = ["Surface", "Hole", "ForceSensor", "contact_force", "wrench_torque"]

#: The flat environment array a compiled loop reads (:meth:`Surface.array`): ``active`` (0: no environment),
#: the surface (``height`` m, ``stiffness`` N/m, ``damping`` N s/m, ``friction``, ``v_s`` m/s) and the hole
#: (``hole`` 0/1, centre ``c_x, c_y`` m, ``clearance`` m, ``depth`` m, wall stiffness ``k_w`` N/m).
ENVIRONMENT = ArrayLayout(("active", 1), ("height", 1), ("stiffness", 1), ("damping", 1), ("friction", 1),
                          ("v_s", 1), ("hole", 1), ("c_x", 1), ("c_y", 1), ("clearance", 1), ("depth", 1),
                          ("k_w", 1))
(_E_ON, _E_Z, _E_K, _E_D, _E_MU, _E_VS, _E_HOLE, _E_CX, _E_CY, _E_C, _E_DEPTH, _E_KW) = ENVIRONMENT.offsets

#: The largest friction coefficient accepted (no dry contact of machine parts comes near it).
MAX_FRICTION = 10.0


# --------------------------------------------------------------------------------------------------
# the contact force model (scalars in, tuples out)
# --------------------------------------------------------------------------------------------------
@kernel
def friction_factor(vx, vy, v_s):
    """``tanh(|v| / v_s) / |v|`` (s/m) of the planar velocity ``(vx, vy)``: the regularised Coulomb law's factor,
    ``1 / v_s`` at ``v = 0`` (its limit), so the friction force ``-mu f_n factor v`` is smooth everywhere."""
    s = math.sqrt(vx * vx + vy * vy)
    if s == 0.0:
        return 1.0 / v_s
    return math.tanh(s / v_s) / s


@kernel
def face_force(pen, pen_rate, vx, vy, k, d, mu, v_s):
    """The force ``(f_x, f_y, f_z)`` (N) on the tool from a horizontal face it penetrates by ``pen`` (m) at the
    rate ``pen_rate`` (m/s) while it slides at ``(vx, vy)`` (m/s): ``f_z = f_n = max(0, k pen + d pen_rate)``
    for ``pen > 0`` (else no force), friction ``-mu f_n tanh(|v| / v_s) v / |v|`` (see the module; the book's
    (eq-int-normal) and (eq-int-friction))."""
    if not pen > 0.0:
        return 0.0, 0.0, 0.0
    fn = k * pen + d * pen_rate
    if not fn > 0.0:
        return 0.0, 0.0, 0.0
    ft = mu * fn * friction_factor(vx, vy, v_s)
    return -ft * vx, -ft * vy, fn


@kernel
def contact_force_kernel(px, py, pz, vx, vy, vz, env, inside):
    """The force ``(f_x, f_y, f_z)`` (N) the environment ``env`` (:data:`ENVIRONMENT`) exerts on the tool at
    ``(px, py, pz)`` moving at ``(vx, vy, vz)``; ``inside`` (0/1) says whether the peg is in the hole (see the
    module). The force the end effector exerts on the environment is its opposite, ``h_e`` (the book's (eq-int-he))."""
    if not env[_E_ON] > 0.0:
        return 0.0, 0.0, 0.0
    z_s = env[_E_Z]
    k = env[_E_K]
    d = env[_E_D]
    mu = env[_E_MU]
    v_s = env[_E_VS]
    if env[_E_HOLE] > 0.0:
        dx = px - env[_E_CX]
        dy = py - env[_E_CY]
        rho = math.sqrt(dx * dx + dy * dy)
        c = env[_E_C]
        if inside > 0.0:
            fx, fy, fz = face_force(z_s - env[_E_DEPTH] - pz, -vz, vx, vy, k, d, mu, v_s)
            if rho > c:
                ux = dx / rho
                uy = dy / rho
                fw = env[_E_KW] * (rho - c) + d * (ux * vx + uy * vy)
                if fw > 0.0:
                    fx -= fw * ux
                    fy -= fw * uy
                    fz -= mu * fw * math.tanh(vz / v_s)
            return fx, fy, fz
        if rho <= c:
            return 0.0, 0.0, 0.0
    return face_force(z_s - pz, -vz, vx, vy, k, d, mu, v_s)


@kernel
def inside_after(px, py, pz, env, inside):
    """The peg's state after an integration step ending at ``(px, py, pz)``: 1.0 once its end is below the
    surface's plane with its axis within the clearance of the hole's, 0.0 once it is above the plane again,
    ``inside`` otherwise (0.0 without a hole)."""
    if not (env[_E_ON] > 0.0 and env[_E_HOLE] > 0.0):
        return 0.0
    if pz >= env[_E_Z]:
        return 0.0
    if inside > 0.0:
        return 1.0
    dx = px - env[_E_CX]
    dy = py - env[_E_CY]
    return 1.0 if math.sqrt(dx * dx + dy * dy) <= env[_E_C] else 0.0


# --------------------------------------------------------------------------------------------------
# the environment's data
# --------------------------------------------------------------------------------------------------
def _nonnegative(value, name, unit):
    v = check_number(value, name, unit=unit)
    if v < 0:
        raise ScaraError(f"{name} = {v:g} {unit} must be >= 0")
    return v


@dataclass(frozen=True)
class Hole:
    """A round hole for a peg along z, its centre ``centre = (c_x, c_y)`` (m) on the surface.

    ``clearance`` (m, > 0): the radial gap between peg and hole, ``r_hole - r_peg`` (default 0.5 mm); ``depth``
    (m, > 0, default 30 mm); ``wall_stiffness`` (N/m, > 0, default 1e6: stiff walls, 50 times the surface).

    >>> Hole((0.4, 0.1)).clearance
    0.0005
    """

    centre: tuple = (0.4, 0.1)
    clearance: float = 5e-4
    depth: float = 0.03
    wall_stiffness: float = 1e6

    def __post_init__(self):
        c = as_array(self.centre, "centre", (2,))
        object.__setattr__(self, "centre", (float(c[0]), float(c[1])))
        object.__setattr__(self, "clearance", check_positive(self.clearance, "clearance"))
        object.__setattr__(self, "depth", check_positive(self.depth, "depth"))
        object.__setattr__(self, "wall_stiffness", check_positive(self.wall_stiffness, "wall_stiffness"))


@dataclass(frozen=True)
class Surface:
    """A compliant horizontal surface at ``p_z = height`` (m), optionally with a :class:`Hole`.

    ``stiffness`` k_e (N/m, > 0, default 2e4), ``damping`` d_e (N s/m, >= 0, default 50), ``friction`` mu
    (Coulomb coefficient, ``0 <= mu <= 10``, default 0.3), ``v_s`` (m/s, > 0, default 1e-3): the speed over
    which ``tanh`` smooths the friction's jump (the module's docstring gives the model). The default surface at
    0.3 m is touched by the tool at ``d3 = d0 - 0.3 = 0.7`` m.

    >>> s = Surface()
    >>> s.stiffness, s.height
    (20000.0, 0.3)
    """

    height: float = 0.3
    stiffness: float = 2e4
    damping: float = 50.0
    friction: float = 0.3
    v_s: float = 1e-3
    hole: Hole | None = None

    def __post_init__(self):
        object.__setattr__(self, "height", check_number(self.height, "height", unit="m"))
        object.__setattr__(self, "stiffness", check_positive(self.stiffness, "stiffness"))
        object.__setattr__(self, "damping", _nonnegative(self.damping, "damping", "N s/m"))
        mu = _nonnegative(self.friction, "friction", "")
        if mu > MAX_FRICTION:
            raise ScaraError(f"friction = {mu:g} is above {MAX_FRICTION:g}, the largest Coulomb coefficient accepted")
        object.__setattr__(self, "friction", mu)
        object.__setattr__(self, "v_s", check_positive(self.v_s, "v_s"))
        if self.hole is not None and not isinstance(self.hole, Hole):
            raise ScaraError(f"hole must be a Hole or None, got {type(self.hole).__name__}")

    def check_reach(self, p: ScaraParams | None = None) -> None:
        """Refuse a surface (or a hole's bottom) the tool of the arm ``p`` cannot touch: the tool's height
        ``p_z = d0 - d3`` spans ``[d0 - d3_max, d0 - d3_min]`` over the quill's stroke."""
        p = ScaraParams.resolve(p)
        low, high = p.d0 - p.d3_max, p.d0 - p.d3_min
        bottom = self.height - (self.hole.depth if self.hole is not None else 0.0)
        what = "the hole's bottom" if self.hole is not None else "the surface"
        if bottom < low:
            raise ScaraError(f"{what} at p_z = {bottom:g} m is below the lowest point the tool reaches, d0 - d3_max = "
                             f"{low:g} m (the quill's stroke ends at d3_max = {p.d3_max:g} m)")
        if not self.height < high:
            raise ScaraError(f"the surface at p_z = {self.height:g} m is at or above the highest point the tool "
                             f"reaches, d0 - d3_min = {high:g} m: the tool would start inside it")

    def array(self) -> np.ndarray:
        """The flat :data:`ENVIRONMENT` array of this surface, for the compiled kernels."""
        h = self.hole
        return ENVIRONMENT.pack(active=1.0, height=self.height, stiffness=self.stiffness, damping=self.damping,
                                friction=self.friction, v_s=self.v_s, hole=0.0 if h is None else 1.0,
                                c_x=0.0 if h is None else h.centre[0], c_y=0.0 if h is None else h.centre[1],
                                clearance=0.0 if h is None else h.clearance, depth=0.0 if h is None else h.depth,
                                k_w=0.0 if h is None else h.wall_stiffness)


#: The array of "no environment": the run is the free arm's.
NO_ENVIRONMENT = ENVIRONMENT.zeros()


@dataclass(frozen=True)
class ForceSensor:
    """The wrist force sensor (the book's (eq-int-sensor)): it reads ``h_e + n + bias`` at each sample, ``n`` white
    Gaussian noise of standard deviation ``noise`` (N, >= 0) on each of ``f_x, f_y, f_z``, drawn from
    ``numpy.random.default_rng(seed)``; ``bias`` (3,) N, default 0.5 N on ``f_z``.

    >>> ForceSensor().readings(np.zeros((4, 3))).shape
    (4, 3)
    """

    noise: float = 0.2
    bias: tuple = (0.0, 0.0, 0.5)
    seed: int = 0

    def __post_init__(self):
        object.__setattr__(self, "noise", _nonnegative(self.noise, "noise", "N"))
        b = as_array(self.bias, "bias", (3,))
        object.__setattr__(self, "bias", tuple(float(v) for v in b))
        if isinstance(self.seed, bool) or not isinstance(self.seed, (int, np.integer)) or self.seed < 0:
            raise ScaraError(f"seed = {self.seed!r} must be a non-negative integer")

    def offsets(self, n: int) -> np.ndarray:
        """The sensor's error ``n_k + bias`` (n, 3) N for ``n`` samples (the same for the same seed)."""
        n = check_count(n, "n", 0, MAX_SAMPLES, "samples", "the longest run the engine accepts")
        rng = np.random.default_rng(int(self.seed))
        return rng.normal(0.0, self.noise, (n, 3)) + np.asarray(self.bias)

    def readings(self, h_e) -> np.ndarray:
        """The sensor's readings (N, 3) of a series of true forces ``h_e`` (N, 3)."""
        h = as_array(h_e, "h_e", (3,), allow_batch=True)
        h2 = np.atleast_2d(h)
        out = h2 + self.offsets(len(h2))
        return out if h.ndim == 2 else out[0]


# --------------------------------------------------------------------------------------------------
# public evaluations
# --------------------------------------------------------------------------------------------------
def contact_force(position, velocity, surface: Surface | None = None, inside: bool = False) -> np.ndarray:
    """The force ``h_e`` (3,) N the tool at ``position`` (3,) m moving at ``velocity`` (3,) m/s exerts on the
    surface (the environment pushes the tool with ``-h_e``; sign of Siciliano et al., eq. 9.1). ``inside``: the
    peg is in the surface's hole (see the module for the model).

    >>> contact_force([0.4, 0.1, 0.299], [0.0, 0.0, 0.0]).round(9).tolist()   # 1 mm into the default surface
    [0.0, 0.0, -20.0]
    """
    s = Surface() if surface is None else surface
    if not isinstance(s, Surface):
        raise ScaraError(f"surface must be a Surface or None, got {type(s).__name__}")
    p = as_array(position, "position", (3,))
    v = as_array(velocity, "velocity", (3,))
    if not isinstance(inside, (bool, np.bool_)):
        raise ScaraError(f"inside = {inside!r} must be True or False")
    f = contact_force_kernel(p[0], p[1], p[2], v[0], v[1], v[2], s.array(), 1.0 if inside else 0.0)
    return -np.array(f, dtype=float)


def wrench_torque(q, force, p: ScaraParams | None = None) -> np.ndarray:
    """``J(q)^T f`` (4,) (N m, N m, N, N m): the joint torques that balance the force ``f`` (3,) N applied at the
    tool, ``J`` the positional part (first three rows) of ``J_A`` (the statics of Siciliano et al., sec. 3.8). With ``f = h_e``
    it is the term the environment adds to the plant, ``B qdd + ... = tau - J^T h_e`` (eq. 9.1).

    >>> wrench_torque([0.0, -np.pi / 2, 0.7, 0.0], [0.0, 0.0, -10.0]).tolist()
    [0.0, 0.0, 10.0, 0.0]
    """
    f = as_array(force, "force", (3,))
    return jacobian(q, p)[:3].T @ f
