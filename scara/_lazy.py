"""Public names of a package that load their sub-module on first use (PEP 562).

``from scara import simulate`` keeps working, but ``import scara`` no longer imports every chapter's module:
a name listed here is looked up in its sub-module the first time it is asked for, and then kept in the
package's namespace.
"""
from __future__ import annotations

import importlib
import sys
import types


def lazy_names(package: str, names: dict[str, str], submodules=(), shadowed=()):
    """``__getattr__`` and ``__dir__`` for the package ``package`` (PEP 562).

    ``names`` maps each public name to the sub-module that defines it (relative, ``"simulate"``);
    ``submodules`` lists sub-modules that are themselves public attributes (``scara.dynamics``); ``shadowed``
    lists sub-modules that define a public function of their own name (``scara.clik`` is the function
    ``clik``, as it has always been): once such a sub-module is imported, however that happens, the
    package's attribute stays the function (see :class:`_ShadowingPackage`).
    """
    module = sys.modules[package]
    namespace = vars(module)
    if shadowed:
        module.__class__ = _ShadowingPackage
        namespace["_SHADOWED"] = frozenset(shadowed)

    def __getattr__(name):
        sub = names.get(name)
        if sub is not None:
            value = getattr(importlib.import_module(f"{package}.{sub}"), name)
        elif name in submodules:
            value = importlib.import_module(f"{package}.{name}")
        else:
            raise AttributeError(f"module {package!r} has no attribute {name!r}")
        namespace[name] = value
        return value

    def __dir__():
        return sorted(set(namespace) | set(names) | set(submodules))

    return __getattr__, __dir__


class _ShadowingPackage(types.ModuleType):
    """A package whose public function ``f`` lives in its sub-module ``f`` (``scara.clik.clik``).

    Importing a sub-module binds it on its package (``setattr(scara, "clik", <module scara.clik>)``); for the
    names of ``_SHADOWED`` the package keeps the function instead, so ``scara.clik`` and ``from scara import
    clik`` give the function whether or not the sub-module was imported before.
    """

    def __setattr__(self, name, value):
        if (isinstance(value, types.ModuleType) and name in vars(self).get("_SHADOWED", ())
                and value.__name__ == f"{self.__name__}.{name}"):
            value = getattr(value, name)
        super().__setattr__(name, value)
