"""The page's assets: one engine holding every page program, and panel declarations small enough for a page."""
from __future__ import annotations

import json
import re

import pytest

from scara.page.assets import PANELS_JS, STATIC, engine_source, panel_spec, program_kernels

PANELS = ("kinematics_panel", "inverse_kinematics_panel", "manipulability_panel", "waypoint_editor", "clik_panel",
          "dynamics_panel", "control_panel", "interaction_panel")


@pytest.fixture(scope="module")
def engine():
    return engine_source()


def test_the_engine_holds_every_program_and_asks_for_nothing(engine):
    names = program_kernels()
    assert {"kinematics_program", "editor_program", "clik_program", "control_program", "clik_prepare",
            "interaction_program"} <= set(names)
    for name in names:
        assert re.search(rf"^\s+{name}: ", engine, re.M), name
    for text in (engine, (STATIC / PANELS_JS).read_text()):
        assert not re.search(r"https?://|importScripts|fetch\(", text), "a script would leave the page"
    assert len(engine) < 400_000


@pytest.mark.parametrize("name", PANELS)
def test_each_panel_declares_a_program_of_the_engine_and_stays_small(name):
    import scara.widgets as W

    made = getattr(W, name)()
    panel = getattr(made, "panel", made)
    spec = panel_spec(panel)
    assert spec["name"] == name
    assert spec["program"]["kernel"] in program_kernels()
    if spec["program"]["prepare"]:
        assert spec["program"]["prepare"] in program_kernels()
    assert [c["name"] for c in spec["controls"]] == list(panel.controls)
    size = len(json.dumps(spec))
    assert size < 600_000, f"{name}: {size} bytes of declaration"
