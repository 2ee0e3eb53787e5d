"""``import scara`` is light and compiles nothing: the later chapters' modules load on first use and every kernel
compiles (or loads from the cache) on its first call. Not timed: each check runs in a fresh interpreter and
looks at what got imported or compiled (``benchmarks/startup.py`` measures the times)."""
import json
import subprocess
import sys

import pytest

import scara
import scara.control


def _run(code: str) -> dict:
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    return json.loads(out.stdout.strip().splitlines()[-1])


HEAVY = ["scara.trajectory", "scara._clik", "scara.dynamics", "scara._simulate", "scara.control", "scara.plots",
         "scara.widgets", "scipy.linalg", "scipy.optimize", "scipy.integrate"]


def test_import_scara_loads_only_the_first_chapters():
    loaded = _run(f"import json, sys; import scara; print(json.dumps([m for m in {HEAVY!r} if m in sys.modules]))")
    assert loaded == []


def test_importing_every_module_compiles_nothing():
    """No kernel is compiled, or loaded from the cache, at import: numba's typing of a first call (which
    brings in its cffi support) has not happened either."""
    code = """
import json, sys
import scara, scara.trajectory, scara._clik, scara.dynamics, scara._simulate, scara.control, scara._manipulability
import scara.control.robust, scara.control.adaptive, scara.control.operational
from scara import _compile
compiled = []
if _compile.COMPILED:
    from numba.core.dispatcher import Dispatcher
    for name, mod in list(sys.modules.items()):
        if name.startswith("scara"):
            for attr, obj in vars(mod).items():
                if isinstance(obj, Dispatcher) and obj.overloads:
                    compiled.append(f"{name}.{attr}")
                if isinstance(obj, _compile._SignatureKernel) and obj._dispatcher is not None:
                    compiled.append(f"{name}.{attr}")
print(json.dumps({"compiled": compiled, "scipy.linalg": "scipy.linalg" in sys.modules,
                  "typing": "numba.core.typing.cffi_utils" in sys.modules, "numba": _compile.COMPILED}))
"""
    res = _run(code)
    assert res["compiled"] == []
    if res["numba"]:
        assert not res["typing"], "numba typed a call at import"


@pytest.mark.parametrize("package", [scara, scara.control], ids=lambda m: m.__name__)
def test_every_public_name_resolves_and_is_listed(package):
    names = package.__all__
    assert len(set(names)) == len(names)
    assert set(names) <= set(dir(package))
    for name in names:
        assert getattr(package, name) is not None, name


def test_public_names_in_a_fresh_interpreter():
    """``from scara import X`` for every listed name, ``import *``, and the functions named like their modules
    (``scara.clik``, ``scara.simulate``, ``scara.manipulability``) stay functions after their module loads."""
    code = """
import json, inspect, types
import scara
names = list(scara.__all__)
missing = [n for n in names if n not in dir(scara)]
import scara._clik, scara._simulate, scara._manipulability
from scara._clik import clik2
from scara import clik, simulate, manipulability, RobustController, reference_trajectory, inertia
kinds = {n: type(getattr(scara, n)).__name__ for n in ("clik", "simulate", "manipulability")}
ns = {}
exec("from scara import *", ns)
star = [n for n in names if n not in ns]
from scara.control import law_cost, positive_gains, B_HAT
print(json.dumps({"missing": missing, "kinds": kinds, "star": star,
                  "same": [scara.clik is clik, scara.simulate is simulate, clik2 is scara.clik2],
                  "modules": [type(scara.dynamics).__name__, type(scara.control.robust).__name__]}))
"""
    res = _run(code)
    assert res["missing"] == [] and res["star"] == []
    assert res["kinds"] == {"clik": "function", "simulate": "function", "manipulability": "function"}
    assert all(res["same"])
    assert res["modules"] == ["module", "module"]


def test_unknown_names_raise_attribute_error():
    with pytest.raises(AttributeError, match="no attribute 'no_such_name'"):
        scara.no_such_name  # noqa: B018
    with pytest.raises(AttributeError):
        scara.control.no_such_name  # noqa: B018
    with pytest.raises(ImportError):
        exec("from scara import no_such_name", {})


def test_figures_and_panels_do_not_key_the_compile_cache():
    """Editing a figure or a panel keeps the numba cache warm: their sources are not part of its key (they hold
    no compiled code)."""
    import re
    from pathlib import Path

    from scara import _compile

    root = Path(_compile.__file__).resolve().parent
    compiled = re.compile(r"^\s*(from|import)\b[^\n]*\b(numba|_compile)\b|@\s*kernel\b", re.M)
    for sub in _compile.UNCOMPILED_PACKAGES:
        for f in (root / sub).rglob("*.py"):
            assert not compiled.search(f.read_text()), f"{f} holds compiled code: its source must key the cache"
