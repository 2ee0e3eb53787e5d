"""Print pytest's time per test group and its slowest tests from a JUnit report (``--junitxml``).

    python .ci/test_groups.py _build/ci/junit.xml [--durations tests/durations.json]

With ``--durations`` it also writes the seconds of every test that took a second or more, by node id: the order in
which the test workers take up the test files (``tests/conftest.py``, longest first) is read from that file.

A group is the folder of the test's file (``tests/book``, ``tests/course``, ...), ``book`` for the notebooks run by
nbval and ``scara`` for the package's doctests. A group's seconds are its tests' own (set-up, call and tear-down)
added up: the two workers run side by side, so the groups add up to about twice the wall time of pytest.
"""
from __future__ import annotations

import sys
import xml.etree.ElementTree as ET
from collections import defaultdict

#: the slowest tests listed
SLOWEST = 25


def group(classname: str, name: str) -> str:
    """The group of a test from its JUnit ``classname`` (``tests.book.test_browser``, ``book.01_kinematics``,
    ``scara.kinematics``)."""
    parts = classname.split(".")
    if parts[0] == "tests":
        # tests/<folder>/test_x.py, or tests/test_x.py
        return "tests/" + parts[1] if len(parts) > 2 and not parts[1].startswith("test_") else "tests"
    return parts[0] or name


def nodeid(classname: str, name: str) -> str | None:
    """pytest's node id of a JUnit test case (``tests/book/test_browser.py::test_x[a]``,
    ``book/01_kinematics.ipynb::Cell 3``), or None for the package's doctests (their module's file cannot be told
    from the report)."""
    parts = classname.split(".")
    if parts[0] == "tests":
        return "/".join(parts) + ".py::" + name
    if parts[0] == "book" and classname.endswith(".ipynb"):
        return classname.replace(".", "/", 1) + "::" + name
    return None


def write_durations(path: str, out: str) -> None:
    import json  # noqa: PLC0415

    found = {}
    for case in ET.parse(path).getroot().iter("testcase"):
        t = float(case.get("time", 0) or 0)
        node = nodeid(case.get("classname", ""), case.get("name", ""))
        if node and t >= 1.0:
            found[node] = round(t, 1)
    with open(out, "w", encoding="utf-8") as fh:
        json.dump(dict(sorted(found.items())), fh, indent=0)
        fh.write("\n")


def main(path: str) -> int:
    cases = ET.parse(path).getroot().iter("testcase")
    seconds, counts, outcomes = defaultdict(float), defaultdict(int), defaultdict(lambda: defaultdict(int))
    timed = []
    for case in cases:
        key = group(case.get("classname", ""), case.get("name", ""))
        t = float(case.get("time", 0) or 0)
        seconds[key] += t
        counts[key] += 1
        outcome = "failed" if case.find("failure") is not None or case.find("error") is not None else (
            "skipped" if case.find("skipped") is not None else "passed")
        outcomes[key][outcome] += 1
        timed.append((t, f"{case.get('classname', '')}::{case.get('name', '')}"))
    print("\npytest by test group (seconds of its tests, summed over the workers)")
    for key in sorted(seconds, key=seconds.get, reverse=True):
        detail = ", ".join(f"{n} {o}" for o, n in sorted(outcomes[key].items()))
        print(f"  {key:<20} {seconds[key]:8.0f} s  {counts[key]:5d} tests ({detail})")
    print(f"  {'all':<20} {sum(seconds.values()):8.0f} s  {sum(counts.values()):5d} tests")
    print(f"\nthe {SLOWEST} slowest tests (seconds)")
    for t, name in sorted(timed, reverse=True)[:SLOWEST]:
        print(f"  {t:7.1f}  {name}")
    return 0


if __name__ == "__main__":
    if "--durations" in sys.argv:
        write_durations(sys.argv[1], sys.argv[sys.argv.index("--durations") + 1])
    sys.exit(main(sys.argv[1]))
