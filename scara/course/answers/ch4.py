"""The computations answering chapter 4's exercises (see :mod:`scara.course.answers`)."""
from types import SimpleNamespace

import numpy as np

from scara import clik2, second_order_gains
from scara.course.answers import solves
from scara.errors import ScaraError


@solves("ex-clik-lag")
def clik_lag(A: float, K: float, duration: float) -> dict:
    """The steady lag of the second-order CLIK (eq-clik-lag2: T A K_D / (2 K_P)) for a reference accelerating at
    ``A`` along z, predicted and measured at the end of a run of ``duration`` from a fixed pose of the arm."""
    dt = 1e-3
    n = int(round(duration / dt)) + 1
    t = np.arange(n) * dt
    ramp = SimpleNamespace(t=t, x=np.tile([0.4, -0.3, 0.7, 0.2], (n, 1)), xd=np.zeros((n, 4)),
                           xdd=np.zeros((n, 4)), dt=dt)
    ramp.x[:, 2] -= 0.5 * A * t**2
    ramp.xd[:, 2] = -A * t
    ramp.xdd[:, 2] = -A
    run = clik2(ramp, *second_order_gains(np.array([400.0, 400.0, K, 100.0])))
    measured = abs(run.e[-1, 2])
    predicted = dt * A / K
    if not np.isclose(measured, predicted, rtol=1e-4):  # the lag has not settled in the run
        raise ScaraError(f"exercise ex-clik-lag: after {duration} s the error {measured:.3e} m is not yet the "
                         f"steady lag {predicted:.3e} m (K = {K} s^-1 too small for the run)")
    return {"lag_um": measured * 1e6, "pred_um": predicted * 1e6}
