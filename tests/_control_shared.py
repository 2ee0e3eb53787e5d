"""Shared by test_control_*.py: the payloads of chapter 6, the error measures of a run, and the first samples of
the reference run again without numba (to compare the plain-Python path with the compiled one)."""

import json
import os
import subprocess
import sys
from types import SimpleNamespace as NS

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


def first_samples(traj, jref, n):
    """The first ``n`` samples of the reference trajectory (a trajectory-like object) and of its joint reference."""
    sub = NS(t=traj.t[:n], x=traj.x[:n], xd=traj.xd[:n], xdd=traj.xdd[:n], dt=traj.dt, q0=traj.q0)
    return sub, (jref.q[:n], jref.qd[:n], jref.qdd[:n])


def plain_python(n, body):
    """Run ``body`` in a fresh interpreter without numba (``SCARA_NO_NUMBA=1``) after defining ``sub`` and ``jr``
    as :func:`first_samples` gives them for ``n`` samples, and ``p`` the arm with 5 kg; ``body`` prints one JSON
    value, which is returned."""
    code = (
        "import json, numpy as np\n"
        "from scara import *\n"
        "from types import SimpleNamespace as NS\n"
        "tr = reference_trajectory()\n"
        f"n = {n}\n"
        "sub = NS(t=tr.t[:n], x=tr.x[:n], xd=tr.xd[:n], xdd=tr.xdd[:n], dt=tr.dt, q0=tr.q0)\n"
        "c2 = clik2(tr)\n"
        "jr = (c2.q[:n], c2.qd[:n], c2.qdd[:n])\n"
        "p = ScaraParams().with_payload(5.0)\n"
        + body
    )
    env = dict(os.environ, SCARA_NO_NUMBA="1")
    out = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, check=True)
    return json.loads(out.stdout)
