"""The page's formatter (scara-panels.js) formats every template field as Python's str.format does, for the format
specs a panel's declaration may use (scara.plots.panels.Text)."""
from __future__ import annotations

import json
import subprocess

import numpy as np
import pytest

from scara.errors import ScaraError
from scara.page.assets import STATIC, PANELS_JS
from scara.plots.panels import Text

from ._node import NODE

SPECS = [".0f", ".1f", ".2f", ".3f", ".4f", "+.2f", "8.3f", ".3g", ".4g", "g", ".2g", ".6g", ".1e", ".3e", ".1%",
         ".0%", " .2f", "+.3g", ".12g"]

_STUB = """
global.window = {};
global.document = {currentScript: null, readyState: 'complete', querySelectorAll: () => []};
global.location = {hash: ''};
require(process.argv[1]);
const cases = JSON.parse(require('fs').readFileSync(0, 'utf8'));
process.stdout.write(JSON.stringify(cases.map(([t, v]) => window.scaraFormat(t, {x: v}))));
"""


def _numbers():
    rng = np.random.default_rng(7)
    special = [0.0, -0.0, 0.5, 1.5, 2.5, -2.5, 0.125, 0.375, 1e-5, 1.23456e-5, 9.9995, 99999.5, 1e16, 123456789.0,
               -0.0004, 0.00012345, 1e21 * 0 + 3.14159, 1e-300, 5e-324, 1.7976931348623157e308, 0.05, 0.15, 0.25]
    return special + list(rng.normal(0, 1, 40)) + list(10.0 ** rng.uniform(-7, 9, 60) * rng.choice([-1, 1], 60))


def test_page_formatter_equals_python():
    if NODE is None:
        pytest.skip("node is not installed")
    cases = [("{x:" + spec + "}", float(v)) for spec in SPECS for v in _numbers()]
    res = subprocess.run([NODE, "-e", _STUB, str(STATIC / PANELS_JS)], input=json.dumps(cases), capture_output=True,
                         text=True, timeout=60)
    assert res.returncode == 0, res.stderr
    got = json.loads(res.stdout)
    wrong = [(t, v, g, t.format(x=v)) for (t, v), g in zip(cases, got) if g != t.format(x=v)]
    assert not wrong, f"{len(wrong)} of {len(cases)} differ, e.g. {wrong[:8]}"


def test_templates_refuse_specs_the_page_does_not_format():
    for spec in ("d", ".2x", ">10.2f", ",.2f", "#.3g"):
        with pytest.raises(ScaraError, match="format spec"):
            Text("{x:" + spec + "}")
    with pytest.raises(ScaraError, match="needs a format spec"):
        Text("{x}").format({"x": 1.5})
