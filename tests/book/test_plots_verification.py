"""The figures of scara.plots.verification (the appendix's speed and rotor-coupling figures): the rotor-coupling
figure refuses a sample count beyond its limit before any work. The reading rules of both figures are checked with
every figure's in test_plots_layout.py."""
from __future__ import annotations

import pytest

from _plots_shared import SAMPLE_COUNTS, check_sample_count_refused


@pytest.mark.parametrize("build, args, count", [
    ("rotor_coupling_figure", (None, None, None), "max_points"),
])
@pytest.mark.parametrize("value, names", SAMPLE_COUNTS)
def test_verification_figures_refuse_sample_counts_beyond_the_limit_before_any_work(build, args, count, value, names):
    check_sample_count_refused(build, args, count, value, names)
