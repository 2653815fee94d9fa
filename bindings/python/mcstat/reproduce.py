# Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
"""Deprecated: ``mcstat reproduce`` is ``mcstat_app.reproduce`` (kept for one release).

Its names and modules resolve to ``mcstat_app.reproduce``:
``import mcstat.reproduce.scene`` gives the module ``mcstat_app.reproduce.scene``
itself (not a copy), so classes and state are shared.
"""
import importlib
import importlib.abc
import importlib.util
import sys
import warnings
from typing import Any

from mcstat_app.reproduce import *  # noqa: F401,F403
from mcstat_app.reproduce import __all__  # noqa: F401

warnings.warn("mcstat.reproduce is deprecated: use mcstat_app.reproduce", DeprecationWarning, stacklevel=2)

__path__: list = []  # a package, so that its submodules can be imported (by the finder below)
_PREFIX = __name__ + "."


class _Alias(importlib.abc.MetaPathFinder, importlib.abc.Loader):
    """Imports mcstat.reproduce.X as the module mcstat_app.reproduce.X."""

    def find_spec(self, fullname: str, path: Any = None, target: Any = None):
        if fullname.startswith(_PREFIX):
            return importlib.util.spec_from_loader(fullname, self)
        return None

    def create_module(self, spec):
        return importlib.import_module("mcstat_app.reproduce." + spec.name[len(_PREFIX):])

    def exec_module(self, module) -> None:
        pass


if not any(isinstance(f, _Alias) for f in sys.meta_path):
    sys.meta_path.append(_Alias())


def __getattr__(name: str) -> Any:
    try:
        return importlib.import_module(f"mcstat_app.reproduce.{name}")
    except ModuleNotFoundError:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}") from None
