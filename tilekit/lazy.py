"""Lazy re-exports for packages (PEP 562): public names imported from their modules on first use.

A plugin package is imported whenever pluggy loads the plugins, i.e. by every ``tilekit``
command, ``--help`` included; re-exporting its library eagerly would make each of them pay for
NumPy, shapely and the rest (measured start-up cost: about a second on the 2-core dev box).
"""

from __future__ import annotations

import importlib
import sys
import types
from collections.abc import Callable, Iterable, Mapping
from typing import Any


def lazy_exports(
    package: str, names: Mapping[str, str], *, pinned: Iterable[str] = ()
) -> tuple[Callable[[str], Any], Callable[[], list[str]]]:
    """``__getattr__`` and ``__dir__`` for the package ``package``: attribute ``n`` of
    ``names`` is ``getattr(import_module(names[n]), n)``, imported once and then cached.

    ``pinned`` names a public object that shares its name with a submodule (a function
    ``solve`` next to the module ``solve.py``): importing that submodule makes the import
    system set the package's attribute to the module, which an eager ``from .solve import
    solve`` used to override. The package then keeps the object, as it did before.
    """
    module = sys.modules[package]
    keep = frozenset(pinned)

    def __getattr__(name: str) -> Any:
        target = names.get(name)
        if target is None:
            raise AttributeError(f"module {package!r} has no attribute {name!r}")
        value = getattr(importlib.import_module(target), name)
        module.__dict__[name] = value
        return value

    def __dir__() -> list[str]:
        return sorted(set(module.__dict__) | set(names))

    if keep:

        class _Package(types.ModuleType):
            def __setattr__(self, name: str, value: Any) -> None:
                if name in keep and isinstance(value, types.ModuleType) and value.__name__ == f"{package}.{name}":
                    return
                super().__setattr__(name, value)

        module.__class__ = _Package
    return __getattr__, __dir__
