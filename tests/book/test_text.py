"""The book's text rules that need no browser (``text_checks.py`` holds the rules and the browser checks): no
output between an exercise and its solution in any notebook, and equal quantities printed equal."""
from __future__ import annotations

import pytest

from text_checks import HTML, NOTEBOOKS, _table_rows, exercise_output_problems


@pytest.mark.parametrize("nb", NOTEBOOKS, ids=lambda p: p.name)
def test_no_output_between_an_exercise_and_its_solution(nb):
    problems = exercise_output_problems(nb)
    assert not problems, "\n".join(problems)


def test_equal_quantities_print_equal():
    """Chapter 3's comparison of the three motions: values equal to 1e-12 (relative) print the same characters
    (the quill's peak speed, 0.05625 m/s in the operational and the cubic motion)."""
    page = HTML / "book" / "03_trajectory.html"
    if not page.exists():
        pytest.skip("the book is not built")
    from scara import reference_trajectory  # noqa: PLC0415
    from scara.trajectory import compare_joint_space  # noqa: PLC0415

    rows = compare_joint_space(reference_trajectory())
    table = _table_rows(page.read_text(), "peak ḋ3 (cm/s)")
    assert table, "chapter 3's comparison table is not in the built page"
    values = {"peak ḋ3 (cm/s)": [100 * r["max_joint_speed"][2] for r in rows],
              "motion ends (s)": [r["motion_end"] for r in rows]}
    for k in range(4):
        values[f"peak |τ{k + 1}| ({'N' if k == 2 else 'N m'})"] = [r["max_torque"][k] for r in rows]
    unequal = []
    for name, vals in values.items():
        shown = table.get(name)
        assert shown and len(shown) == len(vals), (name, shown)
        for i in range(len(vals)):
            for j in range(i + 1, len(vals)):
                if abs(vals[i] - vals[j]) <= 1e-12 * max(abs(vals[i]), abs(vals[j])) and shown[i] != shown[j]:
                    unequal.append(f"{name}: {vals[i]!r} and {vals[j]!r} print as {shown[i]} and {shown[j]}")
    assert not unequal, "equal values printed differently: " + "; ".join(unequal)
