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


def test_the_speed_figure_labels_each_bar_with_its_stored_time_and_ratio_and_marks_extrapolated_runs():
    import json
    from pathlib import Path

    from scara.plots.verification import RUN_TASKS, speed_figure

    results = json.loads((Path(__file__).resolve().parents[2] / "benchmarks" / "results.json").read_text())
    fig = speed_figure(results)
    runs = fig.data[-len(RUN_TASKS):]
    assert len(runs) == len(RUN_TASKS) == 2
    for trace, (key, _, _) in zip(runs, RUN_TASKS):
        for name, text, hover in zip(trace.x, trace.text, trace.hovertext):
            e = results[key][name]
            first, second = text.split("<br>")
            assert first.startswith("≈") == bool(e.get("extrapolated")) == hover.endswith("(extrapolated)"), text
            ratio = float(second.removesuffix("× ours"))   # a plain number: 1701, never 1.7e+03
            assert "e" not in second and abs(ratio - e["ratio_to_ours"]) <= 0.005 * e["ratio_to_ours"] + 0.5, (
                name, text, e["ratio_to_ours"])
    assert any(t.startswith("≈") for t in runs[-1].text), "the stored closed loop has extrapolated library runs"
