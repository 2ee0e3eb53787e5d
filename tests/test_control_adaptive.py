"""Tests of scara.control.adaptive (chapter 6): the tracking target, the payload estimate, the adaptation gains
and an adaptation that is too fast."""

import numpy as np
import pytest

from scara import AdaptiveController, ScaraError, UnstableError, simulate
from scara.control import adaptation_gains
from scara.dynamics import PI_NAMES

from _control_shared import P0, P5, _after, _pos_err


# --------------------------------------------------------------------------------------------------
# the tracking targets of chapter 6
# --------------------------------------------------------------------------------------------------
def test_adaptive_error_and_payload_estimate(runs):
    c, r = runs["adaptive"]
    assert _pos_err(r)[_after(r)].max() <= 0.1e-3
    est = r.payload_estimate
    assert est[0] == 0.0  # the initial estimate has no payload
    assert np.abs(est[r.t >= 2.0] - 5.0).max() <= 0.25
    assert abs(c.final_estimate(r)[0] - (P0.m_l3 + 5.0)) <= 0.25


# --------------------------------------------------------------------------------------------------
# the adaptation gains: what adapts, and how much the adaptive law can carry
# --------------------------------------------------------------------------------------------------
def test_adaptation_gains_choose_what_adapts():
    g = adaptation_gains(0.5)
    assert g[0] == 2.0 and np.all(g[1:] == 0)
    g = adaptation_gains({"m3": 0.5, "F3": 4.0})
    assert g[PI_NAMES.index("F3")] == 0.25 and np.count_nonzero(g) == 2
    v = np.full(13, np.inf)
    v[[0, 11]] = 1.0
    assert np.count_nonzero(adaptation_gains(v)) == 2
    assert AdaptiveController(K_pi={"m3": 0.01, "F3": 1.0}).adapted == ("m3", "F3")
    assert AdaptiveController().adapted == ("m3",)


def test_adaptive_with_more_parameters_still_tracks(traj, jref):
    """Letting the quill's friction adapt too (its true value is known, so its estimate must stay put while
    the payload is learnt)."""
    c = AdaptiveController(K_pi={"m3": 0.01, "F3": 1.0})
    r = simulate(c, traj, P5, joint_reference=jref)
    assert _pos_err(r)[_after(r)].max() <= 0.1e-3
    pi_end = c.final_estimate(r)
    assert abs(pi_end[0] - 15.0) < 0.25
    assert abs(pi_end[PI_NAMES.index("F3")] - P0.F[2]) < 0.05 * P0.F[2]


# --------------------------------------------------------------------------------------------------
# failures
# --------------------------------------------------------------------------------------------------
def test_adaptation_too_fast_diverges(traj, jref):
    c = AdaptiveController(K_pi=1e-7)
    with pytest.raises(UnstableError, match=r"diverged at t = \d+\.\d+ s.*(max_error|tau_max)"):
        c.run(traj, P5, joint_reference=jref)


def test_adaptation_weights_must_be_numbers_with_a_finite_inverse():
    for bad in ("3", True, [1.0, 2.0]):
        with pytest.raises(ScaraError, match=r"K_pi must be a number"):
            adaptation_gains(bad)
    with pytest.raises(ScaraError, match=r"K_pi\[0\] = .* \(m3\) is too small: its inverse, the adaptation rate, is not "
                                         r"finite"):
        adaptation_gains(1e-320)
