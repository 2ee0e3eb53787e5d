"""Shared by test_control_*.py: the payloads of chapter 6 and the error measures of a run."""

import numpy as np

from scara import ScaraParams


P0 = ScaraParams()
P5 = ScaraParams().with_payload(5.0)
G0 = P0.g0


def _pos_err(res):
    return np.linalg.norm(res.e[:, :3], axis=1)


def _after(res, t0=1.0):
    return res.t >= t0 - 1e-12


def _rest(res, window=2.0):
    return res.t >= res.t[-1] - window + 1e-12
