"""Chapter 7's interaction panel in Jupyter: built from its declaration, a move redraws the figure widget in place,
what it draws is what the page draws for the same settings (the page program translated to JavaScript, bound by
the same declarations), and a setting the package refuses shows the package's message in place of the figure."""
from __future__ import annotations

import html

import numpy as np
import pytest

pytest.importorskip("ipywidgets")

import plotly.graph_objects as go  # noqa: E402

from scara import UnstableError  # noqa: E402
from scara.interaction.environment import Surface  # noqa: E402
from scara.interaction.steady import approach_run  # noqa: E402
from scara.programs import interaction as pi  # noqa: E402
from scara.widgets import interaction_panel  # noqa: E402
from scara.widgets._common import REFUSED, STALE_TITLE, _same  # noqa: E402

from test_widgets import Spy, _widgets  # noqa: E402

POINTS = 300


@pytest.fixture(scope="module")
def panel():
    return interaction_panel(points=POINTS)


def _traces(fw) -> dict:
    """The figure widget's traces by name: x and y as float arrays, visibility."""
    return {t.name: (np.asarray(t.x, float), np.asarray(t.y, float)) for t in fw.data}


def test_the_panel_is_built_once_and_a_move_redraws_in_place(panel):
    assert len(panel.figures) == 1 and isinstance(panel.figures[0], go.FigureWidget)
    assert [w for w in _widgets(panel.widget) if isinstance(w, go.FigureWidget)] == panel.figures
    fw = panel.figures[0]
    spy = Spy(fw)
    before = _traces(fw)["−h_z (N)"][1].copy()
    panel.controls["force"].value = 20.0
    assert panel.last_error is None and panel.figures[0] is fw
    assert len(spy.messages) == 1   # one update, holding the new data and title
    restyle, relayout, _ = spy.messages[0]
    assert "y" in restyle and set(relayout) == {"title"}
    after = _traces(fw)["−h_z (N)"][1]
    assert not _same(before, after)
    # the panel draws the package's own run: the pressing force rests at 20 N on the compliance law's set point
    r = approach_run(pi.make_controller("compliance", 20.0, 5000.0, 650.0, 10.0, 2e-5, 2e-3), Surface(),
                     at=pi.AT, lift=pi.LIFT, force=20.0)
    np.testing.assert_allclose(after[-1], -r.force[-1, 2], rtol=1e-9)
    assert fw.layout.title.text.startswith("compliance: final −h_z ")
    panel.controls["force"].value = 10.0


def test_the_greyed_sliders_follow_the_law(panel):
    panel.controls["law"].value = "force"
    assert panel.controls["K_I"].disabled is False and panel.controls["K_z"].disabled is True
    panel.controls["law"].value = "impedance"
    assert panel.controls["M_z"].disabled is False and panel.controls["K_F"].disabled is True
    panel.controls["law"].value = "compliance"
    assert panel.controls["M_z"].disabled is True and panel.last_error is None


def test_an_unstable_gain_shows_the_packages_message_in_place_of_the_figure(panel):
    fw = panel.figures[0]
    panel.controls["D_z"].value = 5e4
    with pytest.raises(UnstableError) as err:
        approach_run(pi.make_controller("compliance", 10.0, 5000.0, 5e4, 10.0, 2e-5, 2e-3), Surface())
    assert panel.last_error.split(" with ")[0] == str(err.value).split(" with ")[0]
    assert "spectral radius 1.22202, which must be < 1" in panel.last_error
    assert panel.message.value.startswith(f"<b>{REFUSED}</b> {html.escape(panel.last_error.split(' with ')[0])}")
    assert fw.layout.title.text == STALE_TITLE and all(t.visible is False for t in fw.data)
    panel.controls["D_z"].value = 650.0
    assert panel.last_error is None and fw.layout.title.text != STALE_TITLE


def test_jupyter_and_the_page_draw_the_same_traces(panel):
    """The page's engine is the program translated to JavaScript; its outputs, bound by the program's declared
    bindings (what the page's script applies), equal what the figure widget shows for the same settings."""
    from scara.page.translate import translate

    from page._node import NODE, run_js

    if NODE is None:
        pytest.skip("node is not installed")
    script = translate([pi.interaction_program])
    prog = panel.declaration.page
    for law in ("admittance", "parallel"):
        panel.controls["law"].value = law
        panel.controls["k_e"].value = 5e4
        settings = panel.values()
        (ret, args, _), = run_js(script, [("interaction_program",
                                          [prog.pack(settings, {c.name: c for c in panel.declaration.controls}),
                                           prog._given, np.zeros(prog.outputs.size)], 1)])
        assert ret == 0
        page = prog.update("press", prog.values(args[2], settings))
        shown = panel.figures[0]
        for role, trace in zip(("force", "formula", "z", "z_d"), shown.data):
            for prop in ("x", "y"):
                np.testing.assert_allclose(np.asarray(getattr(trace, prop), float),
                                           np.asarray(page["traces"][role][prop], float), rtol=1e-9, atol=1e-12)
        assert shown.layout.title.text == page["title"]
    panel.controls["law"].value = "compliance"
    panel.controls["k_e"].value = 2e4


def _my_compliance(K_z, D_z):
    from scara.interaction import ComplianceController

    return ComplianceController(K_P=(5000.0, 5000.0, K_z, 200.0), K_D=(600.0, 600.0, D_z, 25.0))


def test_a_controller_of_ones_own_joins_the_dropdown_and_draws_as_the_panels_own():
    """The reader's compliance controller, built from the sliders it names and run by simulate_contact, draws what
    the panel's program draws for the package's compliance law at the same settings (to the rounding of the set
    point's quintic), and reads only the sliders it names."""
    from scara import ScaraError

    panel = interaction_panel(points=POINTS, controllers={"my compliance": _my_compliance})
    assert panel.declaration.page is None and panel.controls["law"].options[-1] == "my compliance"
    panel.controls["D_z"].value = 900.0
    ours = {k: v.copy() for k, v in ((t.name, np.asarray(t.y, float)) for t in panel.figures[0].data)}
    panel.controls["law"].value = "my compliance"
    assert panel.last_error is None, panel.last_error
    assert panel.controls["M_z"].disabled and not panel.controls["D_z"].disabled
    assert not panel.controls["k_e"].disabled
    theirs = {t.name: np.asarray(t.y, float) for t in panel.figures[0].data}
    for name in ("−h_z (N)", "p_z − height (mm)", "set point (mm)", "formula (N)"):
        w = ours[name]
        np.testing.assert_allclose(theirs[name], w, rtol=1e-9, atol=1e-9 * max(np.ptp(w), np.max(np.abs(w))),
                                   err_msg=name)
    assert panel.figures[0].layout.title.text.startswith("my compliance: final −h_z ")
    # an unstable setting of it: the package's check, with its label and the gains it was given
    panel.controls["D_z"].value = 5e4
    assert panel.last_error.startswith("my compliance with K_z = 5000, D_z = 50000: the sampled loop of compliance")
    assert panel.figures[0].layout.title.text == STALE_TITLE

    def broken(K_I):
        raise ValueError("no law here")

    bad = interaction_panel(points=POINTS, controllers={"broken": broken})
    bad.controls["law"].value = "broken"
    assert bad.last_error == "broken with K_I = 0.002: building it failed: ValueError: no law here"
    with pytest.raises(ScaraError, match="the label 'force' is one of the panel's own controllers"):
        interaction_panel(controllers={"force": _my_compliance})
