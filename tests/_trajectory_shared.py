"""The chapter 3 scenario as the trajectory tests state it, independently of ``scara.trajectory.reference``:
shared by test_trajectory_*.py."""
from __future__ import annotations

import numpy as np


DT = 1e-3
SCENARIO_POINTS = np.array([
    [0.18, 0.20, 0.5], [0.14, 0.20, 0.5], [0.10, 0.20, 0.2], [0.05, 0.15, 0.5],
    [0.10, 0.10, 0.5], [0.225, 0.10, 0.5], [0.35, 0.10, 0.5], [0.70, 0.15, 0.3],
    [0.35, 0.20, 0.5], [0.30, 0.20, 0.5], [0.28, 0.20, 0.5], [0.18, 0.20, 0.5],
])
SCENARIO_VIA = {3: 1.5, 4: 2.0, 5: 1.5, 8: 1.6}
CENTRE = np.array([0.23, 0.20, 0.5])
