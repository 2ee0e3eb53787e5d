"""The checks of the CLIK's inputs and options, run before any loop: the parameters (the trajectory's own, or a
``p`` that agrees with them), the trajectory (shapes, sampling, a reachable reference), the start configuration,
the method and the options it uses (an option the chosen method has no use for is refused), the damping (4.15)
and the error bound. Every message names the offending value and the limit it breaks."""
from __future__ import annotations


import numpy as np

from ..errors import ScaraError, ShapeError, UnreachableError, as_array, check_angles, check_positive, is_bool
from ..kinematics import _elbow_sign, check_reachable, is_reachable
from ..params import ScaraParams
from .kernels import RES_ERROR, RES_SIZE, _damping_ceiling, _first_unclear_sample, _initial_error_check
from .records import _METHOD_CODE, _OBJECTIVE_CODE, COMPONENTS, MAX_DAMPING_REACH, METHODS, OBJECTIVES

#: the options of :func:`~scara.clik` that only some methods use: the methods that use each, and what it sets
_METHOD_OPTIONS = {
    "relaxed": (("pseudoinverse",), "the component the pseudo-inverse (4.13) leaves free"),
    "k0": (("pseudoinverse",), "the gain of the null-space term (4.14)"),
    "objective": (("pseudoinverse",), "the dexterity measure the null-space term (4.14) climbs"),
    "damping": (("inverse", "pseudoinverse"), "the damping of the least-squares inverse (4.15)"),
    "damping_threshold": (("inverse", "pseudoinverse"), "the manipulability below which (4.15) damps"),
}


def _params(traj, p) -> ScaraParams:
    """The parameters a run uses: ``traj.params`` when ``p`` is None, else ``p`` checked to have the trajectory's
    geometry (:meth:`ScaraParams.for_trajectory`)."""
    return ScaraParams.for_trajectory(traj, p)


def _trajectory(traj, need_acc: bool, p: ScaraParams):
    """Validate a trajectory-like object; return ``(t, x, xd, xdd or None, dt)``, with ``t`` and ``x`` copies
    (they go into the result, which owns its arrays) and the arrays C-contiguous."""
    missing = [a for a in ("t", "x", "xd") + (("xdd",) if need_acc else ()) if not hasattr(traj, a)]
    if missing:
        raise ScaraError(f"traj must have attributes t, x, xd{', xdd' if need_acc else ''} "
                         f"(and dt); {type(traj).__name__} lacks {', '.join(missing)}")
    if np.ndim(traj.t) != 1:
        raise ShapeError(f"traj.t must have shape (N,), got {np.shape(traj.t)}")
    n = len(traj.t)
    t = np.array(as_array(traj.t, "traj.t", (n,)))
    if n < 2:
        raise ShapeError(f"traj.t must hold at least 2 samples, got {n}")
    x = np.array(as_array(traj.x, "traj.x", (n, 4)), order="C")
    xd = np.ascontiguousarray(as_array(traj.xd, "traj.xd", (n, 4)))
    xdd = np.ascontiguousarray(as_array(traj.xdd, "traj.xdd", (n, 4))) if need_acc else None
    dt = getattr(traj, "dt", None)
    dt = check_positive(float(t[1] - t[0]) if dt is None else dt, "traj.dt")
    steps = np.diff(t)
    if np.max(np.abs(steps - dt)) > 1e-6 * dt + 1e-12:
        k = int(np.argmax(np.abs(steps - dt)))
        raise ScaraError(f"traj.t must be sampled every dt = {dt:g} s; t[{k + 1}] - t[{k}] = {steps[k]:g} s")
    if not _clearly_reachable(x, p):
        ok = is_reachable(x, p)
        if not ok.all():
            k = int(np.argmin(ok))
            check_reachable(x[k], p, label=f"reference sample {k} (t = {t[k]:.4g} s)")
            raise UnreachableError(f"reference sample {k} (t = {t[k]:.4g} s) is unreachable")  # pragma: no cover
    return t, x, xd, xdd, dt


def _clearly_reachable(x, p) -> bool:
    """One compiled pass over a finite reference ``x`` (N, 4): True if every sample is inside the workspace
    with a margin of 1e-9 m on the radius (squared radii, no square root). False means "look closer": the
    caller then runs :func:`~scara.kinematics.is_reachable`, which decides (and names the first bad sample).
    The stroke test is the same arithmetic as ``is_reachable``'s."""
    tol = 1e-12
    r2_lo = (p.r_min + 1e-9) ** 2 if p.r_min - tol > 0.0 else -1.0
    r2_hi = (p.r_max - 1e-9) ** 2
    return _first_unclear_sample(x, r2_lo, r2_hi, p.d0, p.d3_min - tol, p.d3_max + tol) < 0


def _elbow(traj) -> int:
    """The trajectory's elbow, ``traj.elbow`` (+1 or -1, checked: anything else is refused), when it carries one
    (a planned trajectory does), else -1, the elbow of the reference scenario (chapter 3)."""
    elbow = getattr(traj, "elbow", None)
    return -1 if elbow is None else _elbow_sign(elbow)


def _objective(objective) -> str:
    """``objective`` checked to be one of :data:`OBJECTIVES`."""
    if not isinstance(objective, str) or objective not in _OBJECTIVE_CODE:
        raise ScaraError(f"objective = {objective!r} is unknown; choose one of {', '.join(OBJECTIVES)}")
    return objective


def _method(method) -> str:
    """``method`` checked to be one of :data:`METHODS`."""
    if not isinstance(method, str) or method not in _METHOD_CODE:
        raise ScaraError(f"method = {method!r} is unknown; choose one of {', '.join(METHODS)}")
    return method


def _refuse_unused(method: str, **given):
    """Refuse an option set (``given``: name -> value, only those set away from their default) that ``method``
    has no use for (see :data:`_METHOD_OPTIONS`), naming the option, its value and the method."""
    for name, value in given.items():
        users, does = _METHOD_OPTIONS[name]
        if method not in users:
            names = " and ".join(repr(m) for m in users)
            raise ScaraError(f"{name} = {value!r} only applies to method {names} ({does}), not to method={method!r}, "
                             f"which has no use for it; leave {name} at its default")


def _relaxed_index(relaxed) -> int:
    """The index of the component the pseudo-inverse leaves free: a name of :data:`COMPONENTS` or 0..3
    (default ``"x"``)."""
    r = "x" if relaxed is None else relaxed
    if isinstance(r, str) and r in COMPONENTS:
        return COMPONENTS.index(r)
    if isinstance(r, (int, np.integer)) and not is_bool(r) and 0 <= r < 4:
        return int(r)
    raise ScaraError(f"relaxed = {relaxed!r} is not an operational component; use one of "
                     f"{', '.join(COMPONENTS)} (or 0..3)")


def _first_order_options(method, relaxed, k0, objective, damping, damping_threshold, p):
    """Check the method of :func:`~scara.clik` and its options, refusing one the method does not use; return the
    kept-component mask (4,), the null-space gain ``k0`` as a float and the damping ``(lambda^2, w_thr)`` of
    :func:`_damping`."""
    method, objective = _method(method), _objective(objective)
    lam2, w_thr = _damping(damping, damping_threshold, p)
    k0v = 0.0 if k0 is None else check_positive(k0, "k0", strict=False)
    optional = {"relaxed": relaxed, "k0": k0, "damping_threshold": damping_threshold}
    given = {name: value for name, value in optional.items() if value is not None}
    if objective != "sin2":
        given["objective"] = objective
    if lam2 > 0.0:
        given["damping"] = damping
    _refuse_unused(method, **given)
    kept = np.ones(4)
    if method == "pseudoinverse":
        kept[_relaxed_index(relaxed)] = 0.0
        k0v = 1.0 if k0 is None else k0v
    return kept, k0v, lam2, w_thr


def _damping_text() -> str:
    """The refusal of a damping above :func:`~.kernels._damping_ceiling`, as a template with the fields
    ``damping`` and ``damping_limit`` (m)."""
    return (f"damping = {{damping:g}} m is above the largest damping accepted, {MAX_DAMPING_REACH:g} times the "
            "reach a1 + a2: {damping_limit:g} m (a larger lambda only freezes the arm)")


def _damping(damping, damping_threshold, p):
    """``(lambda^2, w_thr)`` of the damped least squares (4.15): ``0 <= damping <= MAX_DAMPING_REACH (a1 + a2)``
    (m, :func:`~.kernels._damping_ceiling`), and the threshold (m^2) > 0 or None (returned as 0: the damping
    applies everywhere)."""
    lam = check_positive(damping, "damping", strict=False)
    lam_max = _damping_ceiling(float(p.r_max))
    if lam > lam_max:
        raise ScaraError(_damping_text().format(damping=lam, damping_limit=lam_max))
    if damping_threshold is None:
        return lam * lam, 0.0
    return lam * lam, check_positive(damping_threshold, "damping_threshold")


def _max_error(max_error) -> float:
    """The error bound (m or rad) past which a run is stopped as divergent, checked finite and > 0."""
    return check_positive(max_error, "max_error")


def _check_q0(q0, p) -> np.ndarray:
    """A copy of the start configuration ``q0``, checked: shape (4,), finite, angles within ``MAX_ANGLE`` rad and
    ``d3`` inside the quill's stroke ``p.d3_min <= d3 <= p.d3_max``."""
    q = check_angles(as_array(q0, "q0", (4,)).copy(), "q0")
    if not p.d3_min <= q[2] <= p.d3_max:
        raise UnreachableError(f"q0[2] = d3 = {q[2]:.10g} m is outside the quill's stroke d3_min = {p.d3_min:g} m <= "
                               f"d3 <= d3_max = {p.d3_max:g} m: a motion cannot start there")
    return q


def _initial_error_text(component: str) -> str:
    """The refusal of a start whose initial error on ``component`` is above the error bound, as a template with
    the fields ``e0`` and ``max_error``."""
    return (f"the start configuration q0 leaves an initial {component} error of {{e0:.4g}}, above max_error = "
            "{max_error:g}; pass a larger max_error to allow it")


def _check_initial_error(x0_ref, q0, p, kept, max_err):
    """Refuse a start whose pose (1.5) leaves an error on a kept component above ``max_err``
    (:func:`~.kernels._initial_error_check`)."""
    res = np.zeros(RES_SIZE)
    i = _initial_error_check(np.ascontiguousarray(x0_ref, float), np.ascontiguousarray(q0, float), float(p.a1),
                             float(p.a2), float(p.d0), np.ascontiguousarray(kept, float), float(max_err), res)
    if i >= 0:
        raise ScaraError(_initial_error_text(COMPONENTS[i]).format(e0=res[RES_ERROR], max_error=max_err))
