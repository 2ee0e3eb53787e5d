"""The computations answering chapter 7's exercises (see :mod:`scara.course.answers`)."""
import numpy as np

from scara.course.answers import solves
from scara.errors import ScaraError
from scara.interaction import (ForceController, ForceSensor, Hole, Surface, approach_run, elastic_equilibrium,
                               force_equilibrium, force_loop_bounds, force_loop_poly, insertion_summary, peg_in_hole,
                               stiffness_sweep)


@solves("ex-int-series")
def int_series(K_P: float, depth_mm: float) -> dict:
    """Compliance control with ``K_P,z = K_P`` held ``depth_mm`` below the book's surface: the force and the
    penetration at rest by (eq-int-equilibrium), and the force at the end of a simulated run."""
    s = Surface()
    if not 0.0 < depth_mm <= 10.0:
        raise ScaraError(f"exercise ex-int-series: a depth of {depth_mm} mm is outside 0 to 10 mm")
    x_d = np.array([0.4, 0.1, s.height - 1e-3 * depth_mm, 0.0])
    x, h = elastic_equilibrium([5000.0, 5000.0, K_P, 200.0], x_d, s)
    sim = stiffness_sweep([K_P], [s.stiffness], depth=1e-3 * depth_mm, points=2)["simulated"][0, 0]
    return {"force_N": float(-h[2]), "penetration_mm": float(1e3 * (s.height - x[2])), "sim_N": float(sim),
            "series": float(K_P * s.stiffness / (K_P + s.stiffness)), "k_e": s.stiffness}


@solves("ex-int-bias")
def int_bias(f_d: float, bias: float) -> dict:
    """Force control asked for ``f_d`` N down, its sensor biased by ``bias`` N on f_z (no noise): the true force
    and the penetration at rest (eq-int-force-rest), and a simulated approach's."""
    s = Surface()
    sensor = ForceSensor(noise=0.0, bias=(0.0, 0.0, bias))
    z, h = force_equilibrium(-f_d, s, sensor)
    run = approach_run(ForceController(f_d=-f_d), s, sensor, hold=2.0)
    return {"force_N": float(-h[2]), "penetration_mm": float(1e3 * (s.height - z)),
            "sim_N": float(run.normal_force[-1]), "sim_mm": float(1e3 * (s.height - run.x[-1, 2])),
            "measured_N": float(-run.measured_force[-1, 2])}


@solves("ex-int-force-loop")
def int_force_loop(K_I: float) -> dict:
    """Force control with the integral gain ``K_I`` on the book's surface: the force error's time constant
    (eq-int-force-tau), the continuous-time bound on ``K_I`` (eq-int-force-routh), the sampled loop's bound, and the
    slowest root of the cubic (eq-int-force-poly) for comparison with the time constant."""
    s = Surface()
    law = ForceController(K_I=K_I)
    b = force_loop_bounds(law, s)
    if not b["radius"] < 1.0:
        raise ScaraError(f"exercise ex-int-force-loop: K_I = {K_I} m/(N s) makes the sampled loop unstable")
    KF, k = law.K_F[2], s.stiffness
    slowest = float(-np.max(np.roots(force_loop_poly(law, s)).real))
    return {"tau_ms": float(1e3 * (1.0 + KF * k) / (K_I * k)), "routh": b["routh"], "sampled": b["sampled"],
            "slowest_ms": 1e3 / slowest, "radius": b["radius"]}


@solves("ex-int-peg")
def int_peg(clearance_mm: float) -> dict:
    """The peg of the book started 10 % within and 10 % beyond a clearance of ``clearance_mm``: the largest offset
    that drops straight in (the clearance), whether each run landed on the surface first, and when each entered."""
    if not 0.05 <= clearance_mm <= 2.0:
        raise ScaraError(f"exercise ex-int-peg: a clearance of {clearance_mm} mm is outside 0.05 to 2 mm")
    s = Surface(hole=Hole(clearance=1e-3 * clearance_mm))
    within = insertion_summary(peg_in_hole((0.9e-3 * clearance_mm, 0.0), s))
    beyond = insertion_summary(peg_in_hole((1.1e-3 * clearance_mm, 0.0), s))
    return {"offset_mm": float(clearance_mm), "within_landed": float(within["landed_on_surface"]),
            "beyond_landed": float(beyond["landed_on_surface"]), "within_entered": within["entered"],
            "beyond_entered": beyond["entered"], "within_depth_mm": 1e3 * within["depth_reached"],
            "beyond_depth_mm": 1e3 * beyond["depth_reached"]}
