"""The package's public names, each read from the ``__all__`` of the module that defines it, and loaded on first
use for the later chapters' modules (PEP 562).

``import scara`` imports the first chapters' modules (``EAGER``) and binds their ``__all__``; a name of a module in
``LAZY`` is bound the first time it is asked for (``scara.simulate``, ``from scara import clik``), so that
``import scara`` does not import every chapter. Which module holds which lazy name is read from the module's
source (its literal ``__all__``) without importing it, so each public name is listed once, in its own module.
"""
from __future__ import annotations

import ast
import importlib
import os
import re
import sys

_ALL = re.compile(r"^__all__\s*=\s*(\[.*?\])\s*$", re.S | re.M)
_GROUP = re.compile(r"^_(EAGER|LAZY)\s*=\s*(\(.*?\))\s*$", re.S | re.M)


def _source(module: str) -> str:
    """The source file of ``module`` (``scara.control._common``), found from the top package's folder so that no
    package on the way (``scara.control``) is imported."""
    top, *parts = module.split(".")
    base = os.path.join(os.path.dirname(sys.modules[top].__file__), *parts)
    return os.path.join(base, "__init__.py") if os.path.isdir(base) else base + ".py"


def exported(module: str) -> tuple[str, ...]:
    """The public names of ``module`` (a dotted name), read from its source without importing it: its literal
    ``__all__ = [...]``, or, for a package whose names come from its sub-modules (it declares ``_EAGER`` and
    ``_LAZY`` tuples and calls :func:`public_names`), the names of those sub-modules. Raises ``ImportError`` when
    the module has neither."""
    with open(_source(module), encoding="utf-8") as fh:
        source = fh.read()
    match = _ALL.search(source)
    if match is not None:
        return tuple(ast.literal_eval(match.group(1)))
    groups = [ast.literal_eval(m.group(2)) for m in _GROUP.finditer(source)]
    if not groups:
        raise ImportError(f"{module} has no literal __all__ list: the package cannot list its public names")
    return tuple(dict.fromkeys(n for subs in groups for sub in subs for n in exported(f"{module}.{sub}")))


def public_names(package: str, eager=(), lazy=(), submodules=()):
    """Bind the public names of ``package``; return its ``__all__``, ``__getattr__`` and ``__dir__``.

    ``eager``: sub-modules imported now, whose ``__all__`` names are bound at once; ``lazy``: sub-modules whose
    names are bound when first asked for; ``submodules``: sub-modules that are public attributes themselves
    (``scara.dynamics``). A name defined by two sub-modules must be the same object in both (a re-export).
    """
    module = sys.modules[package]
    namespace = vars(module)
    owner: dict[str, str] = {}
    for sub in (*eager, *lazy):
        for name in exported(f"{package}.{sub}"):
            owner.setdefault(name, sub)
    for sub in eager:
        mod = importlib.import_module(f"{package}.{sub}")
        for name in mod.__all__:
            if owner[name] == sub:
                namespace[name] = getattr(mod, name)
    lazy_owner = {name: sub for name, sub in owner.items() if sub in lazy}

    def __getattr__(name):
        sub = lazy_owner.get(name)
        if sub is not None:
            value = getattr(importlib.import_module(f"{package}.{sub}"), name)
        elif name in submodules:
            value = importlib.import_module(f"{package}.{name}")
        else:
            raise AttributeError(f"module {package!r} has no attribute {name!r}")
        namespace[name] = value
        return value

    def __dir__():
        return sorted(set(namespace) | set(owner) | set(submodules))

    return [*owner, *submodules], __getattr__, __dir__
