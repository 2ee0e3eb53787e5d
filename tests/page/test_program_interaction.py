"""The page program of chapter 7's interaction panel (scara.programs.interaction): one move is one compiled kernel
whose outputs equal the package's own run (the controllers, approach_run, contact_transition, the steady-state
formulas, the sampled loop's radius), whose refusals say what the package says, and which runs the same translated
to JavaScript."""
from __future__ import annotations

import math
import re

import numpy as np
import pytest

from scara import UnstableError
from scara.interaction.environment import ForceSensor, Surface
from scara.interaction.stability import sampled_radius, z_axis
from scara.interaction.steady import (approach_run, contact_transition, elastic_equilibrium, force_equilibrium,
                                      pressing_target)
from scara.plots._common import thin
from scara.programs import interaction as pi
from scara.widgets.interaction import interaction_declaration

POINTS = 300
RNG = np.random.default_rng(20261205)
#: the panel's defaults (the dropdown aside)
DEFAULTS = dict(force=10.0, K_z=5000.0, D_z=650.0, M_z=10.0, K_F=2e-5, K_I=2e-3, k_e=2e4)


@pytest.fixture(scope="module")
def setup():
    data = pi.interaction_data(points=POINTS)
    n = int(data[0])
    return data, np.concatenate([data, np.zeros(pi.interaction_scratch(n))]), pi.interaction_outputs(n, POINTS)


def _inputs(values: dict) -> np.ndarray:
    return np.array([float(pi.LAWS.index(values["law"]))] + [float(values[k]) for k in pi.INPUTS[1:]])


def _program(values: dict, data, outputs):
    """``(status, outputs by field)`` of one move of the program for the panel's settings ``values``."""
    out = np.zeros(outputs.size)
    status = int(pi.interaction_program(_inputs(values), data, out))
    return status, {n: (out[o] if outputs.sizes[n] == 1 else out[o:o + outputs.sizes[n]].copy())
                    for n, o in zip(outputs.names, outputs.offsets)}


def _controller(values: dict):
    return pi.make_controller(values["law"], *(values[k] for k in ("force", "K_z", "D_z", "M_z", "K_F", "K_I")))


def _random(law: str) -> dict:
    """Settings drawn log-uniformly inside the panel's sliders, where the runs stay stable most of the time."""
    def log(lo, hi):
        return float(10 ** RNG.uniform(math.log10(lo), math.log10(hi)))

    return dict(law=law, force=float(RNG.choice(np.arange(2.0, 40.0, 0.5))), K_z=log(1000.0, 3e4),
                D_z=log(300.0, 3000.0), M_z=log(5.0, 40.0), K_F=log(5e-6, 5e-5), K_I=log(5e-4, 5e-3),
                k_e=log(2e3, 2e5))


def _package_outputs(values: dict):
    """What the panel shows, by the package's own API: approach_run of the controller the settings make on the
    surface of stiffness k_e with the default sensor, contact_transition, the thinning of the figures, the
    steady-state formulas and the sampled loop's radius."""
    c = _controller(values)
    s = Surface(stiffness=values["k_e"])
    r = approach_run(c, s, ForceSensor(), at=pi.AT, lift=pi.LIFT, force=values["force"], move=pi.MOVE,
                     hold=pi.HOLD, substeps=pi.SUBSTEPS)
    tr = contact_transition(r)
    idx = thin(len(r.t), POINTS)
    if values["law"] in ("force", "parallel"):
        formula = -force_equilibrium(-values["force"], s, ForceSensor())[1][2]
    else:
        formula = -elastic_equilibrium(c.stiffness(), pressing_target(c, r.x_d[0], s, values["force"]), s)[1][2]
    m, cz = z_axis()
    loops = c.z_loops(m, cz, s.stiffness, s.damping, pi.DT)
    return dict(t=r.t[idx], force=-r.force[idx, 2], z=1e3 * (r.x[idx, 2] - s.height),
                z_d=1e3 * (r.x_d[idx, 2] - s.height), first_touch=tr["first_touch"], peak_force=tr["peak_force"],
                contact_losses=float(tr["contact_losses"]), bounced=float(tr["bounced"]),
                final_force=tr["final_force"], formula=formula, force_error=tr["final_force"] - formula,
                target_mm=1e3 * (r.x_d[-1, 2] - s.height), duration=r.t[-1],
                radius=sampled_radius(loops["contact"], m, cz, s.stiffness, s.damping, pi.DT),
                radius_free=sampled_radius(loops["free"], m, cz, 0.0, 0.0, pi.DT))


#: the entries compared to round-off: the program builds the approach's z reference as start + (target - start) s
#: from the quintic's unit profile, the package by its quintic from start to target; the runs then agree to the
#: rounding of that product (1e-9 of each array's range, as the page's browser test asks of a run)
_RUN = ("t", "force", "z", "z_d", "peak_force", "final_force", "formula", "force_error", "target_mm")


@pytest.mark.parametrize("law", pi.LAWS)
def test_a_move_is_the_packages_run(setup, law):
    _, data, outputs = setup
    for values in (dict(DEFAULTS, law=law), _random(law)):
        status, got = _program(values, data, outputs)
        try:
            want = _package_outputs(values)
        except UnstableError:   # a random setting the package refuses: the program refuses it too
            assert status != 0, values
            continue
        assert status == 0, (values, pi.interaction_refusals()[status].format({**values, **got}))
        for name, w in want.items():
            if name in _RUN:   # the force error is the difference of two forces: rounded on their scale
                w = np.atleast_1d(w)
                scale = want["final_force"] if name == "force_error" else max(np.ptp(w), np.max(np.abs(w)))
                np.testing.assert_allclose(got[name], w, rtol=1e-9, atol=1e-9 * scale, err_msg=f"{law} {name}")
            else:
                assert got[name] == w or (math.isnan(w) and math.isnan(got[name])), (law, name, got[name], w)


def test_the_panels_gains_are_the_controllers(setup):
    """The program packs each law's gains as the controller the settings make packs them (gains_array)."""
    data, _, _ = setup
    for law in pi.LAWS:
        values = _random(law)
        gains = np.empty(pi._NG[pi.LAWS.index(law)])
        pi.make_gains(pi.LAWS.index(law), _inputs(values), data, gains)
        assert np.array_equal(gains, _controller(values).gains_array()), law


def _numbers(text: str) -> list:
    return [float(x) for x in re.findall(r"-?\d+(?:\.\d+)?(?:e[-+]?\d+)?", text)]


@pytest.mark.parametrize("law, change", [("compliance", dict(D_z=5e4)), ("compliance", dict(K_z=1e5, D_z=10.0)),
                                         ("impedance", dict(D_z=1e5)), ("admittance", dict(D_z=1e5, M_z=1.0)),
                                         ("force", dict(K_I=0.05)), ("parallel", dict(K_I=0.5))])
def test_an_unstable_gain_is_refused_in_the_packages_words(setup, law, change):
    """The refusal is check_contact's message: the same words, radius, limit and place; the gains the panel sets
    are written as its numbers are (``{:g}``), the others as the package writes them."""
    _, data, outputs = setup
    values = dict(DEFAULTS, law=law, **change)
    status, got = _program(values, data, outputs)
    with pytest.raises(UnstableError) as err:
        _package_outputs(values)
    want = str(err.value)
    assert status != 0
    shown = pi.interaction_refusals()[status].format({**values, **got})
    head, tail = want.split(" with ", 1)
    assert shown.startswith(head + " with ")
    assert shown.endswith("; lower the gains (or the sampling period)")
    np.testing.assert_allclose(_numbers(shown.split(" with ", 1)[1]), _numbers(tail), rtol=5e-6)


@pytest.mark.parametrize("law", pi.LAWS)
def test_a_stopped_run_is_refused_in_the_engines_words(law):
    """Every way the contact loop stops (the law's codes, a divergence, a singular inertia, a NaN torque or signal,
    the quill's stroke): the program's message is simulate_contact's (its _raise_failure)."""
    import math

    from scara._simulate.engine import _raise_failure
    from scara._simulate.interface import DIVERGED, JOINT_LIMIT, LAW_FAILED, NOT_FINITE, SINGULAR_INERTIA
    from scara.params import ScaraParams
    from scara.programs.control import run_refusal

    P = ScaraParams()
    ctl = pi._CLASSES[pi.LAWS.index(law)]()
    names = ctl.signals_layout.entry_names
    n = 10
    q, qd, tau = RNG.normal(size=(n, 4)), RNG.normal(size=(n, 4)), RNG.normal(size=(n, 4))
    sig = RNG.normal(size=(n, 4))
    refusals = pi.interaction_refusals()
    cases = [(LAW_FAILED, 4, c) for c in (2, 3, 4, 7)] + [(DIVERGED, 5, 0), (SINGULAR_INERTIA, 6, 0)]
    cases += [(NOT_FINITE, 3, i) for i in range(4 + len(names))] + [(JOINT_LIMIT, 7, 0), (JOINT_LIMIT, 8, 0)]
    for status, k, extra in cases:
        info = np.array([status, k, extra], dtype=float)
        qq, tt, ss = q.copy(), tau.copy(), sig.copy()
        if status == JOINT_LIMIT:
            qq[k, 2] = 1.25 if k == 7 else -0.25
        if status == NOT_FINITE:
            (tt if extra < 4 else ss)[k, extra if extra < 4 else extra - 4] = (math.nan, math.inf, -math.inf)[k % 3]
        out = np.zeros(pi.SCALARS.size)
        code = run_refusal(pi._R_RUN + 100 * pi.LAWS.index(law), info, 1e-3, qq, qd, tt, ss, P.d3_min, P.d3_max,
                           out, pi._RUN_AT)
        values = {name: out[at] for name, at in zip(pi.SCALARS.names, pi.SCALARS.offsets)}
        with pytest.raises(UnstableError) as exc:
            _raise_failure(ctl, info, 1e-3, pi.LIMIT, (qq, qd, None, tt, None, None, ss), P, names)
        assert refusals[code].format(values) == str(exc.value), (status, extra)


def test_the_scratch_after_the_data_gives_the_same_moves(setup):
    data, full, outputs = setup
    stale = np.concatenate([data, np.full(full.size - data.size, np.nan)])
    for values in [dict(DEFAULTS, law=law) for law in pi.LAWS] + [dict(DEFAULTS, law="force", K_I=0.05)]:
        a, b = _program(values, stale, outputs), _program(values, data, outputs)
        assert a[0] == b[0] and all(np.array_equal(np.asarray(a[1][k]), np.asarray(b[1][k]), equal_nan=True)
                                    for k in a[1]), values
    assert np.array_equal(stale[:data.size], data)


def test_the_panel_declares_the_program():
    panel = interaction_declaration(points=POINTS)
    assert [c.name for c in panel.controls] == list(pi.INPUTS)
    assert panel.selector == "law" and panel.widget == "interaction_panel"
    assert panel.page.describe(panel)["kernel"] == "interaction_program"
    v = panel.compute(dict(DEFAULTS, law="force"))
    rows, notes = panel.summary(v)
    assert dict(rows)["formula (N)"] == f"{v['formula']:.5g}" and notes == []
    assert panel.figures[0].build(v).layout.title.text.startswith("force: final −h_z ")


def test_the_program_translates_and_runs_in_the_page(setup):
    from scara.page.translate import translate

    from ._node import NODE, run_js

    script = translate([pi.interaction_program])
    if NODE is None:
        pytest.skip("node is not installed")
    _, data, outputs = setup
    for values in [dict(DEFAULTS, law=law) for law in pi.LAWS] + [dict(DEFAULTS, law="force", K_I=0.05)]:
        status, ref = _program(values, data, outputs)
        (ret, args, _), = run_js(script, [("interaction_program", [_inputs(values), data, np.zeros(outputs.size)],
                                           1)])
        assert ret == status
        want = np.concatenate([np.atleast_1d(ref[n]) for n in outputs.names])
        # V8's sin, cos and tanh are not glibc's: the runs agree to the last digits, not bit for bit
        np.testing.assert_allclose(args[2], want, rtol=1e-6, atol=1e-9 * np.nanmax(np.abs(want)))
